/* The book's "predict, then check" questions, in the HTML page with no kernel.

   A question is an element of class "icm-quiz" (an exercise) that holds a fieldset of
   class "icm-quiz-choices" (radio buttons, each with data-correct and data-hint,
   written by icm.exercises.quiz.Choices at build time) and, after it, an element of
   class "icm-quiz-explanation" (the explanation, with the numbers the chapter
   computed). This script adds a Check button and a feedback line under the options,
   and hides the explanation until the right option is checked: a wrong option shows
   its hint, the right one "Right." and the explanation. Without this script the
   options and the explanation are simply shown. Native radio buttons and a button:
   usable with the keyboard (Tab, the arrow keys, Enter or Space); the feedback line
   is a live region, read out by screen readers. */
(function () {
  "use strict";

  function setUp(choices) {
    var quiz = choices.closest(".icm-quiz") || choices.parentElement;
    var explanation = quiz.querySelector(".icm-quiz-explanation");
    var button = document.createElement("button");
    button.type = "button";
    button.className = "icm-quiz-check";
    button.textContent = "Check";
    var feedback = document.createElement("p");
    feedback.className = "icm-quiz-feedback";
    feedback.setAttribute("role", "status");
    feedback.setAttribute("aria-live", "polite");
    feedback.id = choices.id + "-feedback";
    button.setAttribute("aria-describedby", feedback.id);
    choices.appendChild(button);
    choices.appendChild(feedback);
    if (explanation) {
      explanation.hidden = true;
      explanation.id = choices.id + "-explanation";
    }
    button.addEventListener("click", function () {
      var chosen = choices.querySelector("input[type=radio]:checked");
      feedback.classList.remove("icm-quiz-right", "icm-quiz-wrong");
      if (!chosen) {
        feedback.textContent = "Choose an answer first.";
        return;
      }
      if (chosen.getAttribute("data-correct") === "true") {
        feedback.textContent = "Right." + (explanation ? " The explanation follows." : "");
        feedback.classList.add("icm-quiz-right");
        if (explanation) { explanation.hidden = false; }
      } else {
        feedback.textContent = "Not quite. " + chosen.getAttribute("data-hint");
        feedback.classList.add("icm-quiz-wrong");
        if (explanation) { explanation.hidden = true; }
      }
    });
    choices.classList.add("icm-quiz-ready");
  }

  function setUpAll() {
    var all = document.querySelectorAll("fieldset.icm-quiz-choices");
    for (var i = 0; i < all.length; i++) {
      if (!all[i].classList.contains("icm-quiz-ready")) { setUp(all[i]); }
    }
  }

  if (document.readyState === "loading") {
    document.addEventListener("DOMContentLoaded", setUpAll);
  } else {
    setUpAll();
  }
})();
