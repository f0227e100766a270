// The ipywidgets HTML manager typesets widget text with MathJax 2's
// MathJax.Hub.Queue(["Typeset", MathJax.Hub, element]); the book uses MathJax 3, which
// has no Hub. Give every MathJax object that appears a Hub whose Queue typesets with
// MathJax 3 (or does nothing while MathJax is still loading).
(function () {
  function addHub(mathjax) {
    if (mathjax && typeof mathjax === "object" && !mathjax.Hub) {
      mathjax.Hub = {
        Queue: function (job) {
          var element = job && job[2];
          var current = window.MathJax;
          if (current && typeof current.typesetPromise === "function") {
            current.typesetPromise(element ? [element] : undefined).catch(function () {});
          }
        }
      };
    }
    return mathjax;
  }
  var current = addHub(window.MathJax);
  Object.defineProperty(window, "MathJax", {
    configurable: true,
    get: function () { return current; },
    set: function (value) { current = addHub(value); }
  });
})();
