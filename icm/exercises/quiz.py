"""The "predict, then check" questions of the book: options a reader chooses from in
the HTML page, with no kernel, checked by `book/_static/icm-quiz.js`.

A question's right option is chosen at build time from a number the chapter computes
(`option_for`), so the page never claims what the library no longer gives; the
explanation that follows the options quotes that number with `myst_nb.glue`."""

import html
import re

from icm import _validate


def option_for(value, edges):
    """The index of the option a value falls in, for options split at `edges`
    (increasing): option 0 below edges[0], option i in [edges[i-1], edges[i]), the last
    from edges[-1] up.

    Args:
      value: the number computed.
      edges: the options' boundaries, increasing.

    Returns:
      The index of the option.

    Raises:
      ValueError: for a value that is not a finite number or edges that do not
        increase.
    """
    value = _validate.real("value", value)
    edges = [_validate.real("edges[i]", e) for e in edges]
    if any(b <= a for a, b in zip(edges, edges[1:])):
        raise ValueError(f"edges must increase, got {edges!r}")
    return sum(value >= e for e in edges)


class Choices:
    """The options of one question, shown as radio buttons with a Check button; the
    page's script says, for a wrong option, its hint, and for the right one "Right" and
    shows the explanation that follows in the page.

    Args:
      name: a name unique in the page (letters, digits, dashes), e.g. "epsilon-zero".
      options: the options' texts.
      correct: the index of the right option.
      hints: one hint per option, shown when that option is chosen and wrong (the
        right option's entry is not used).
      legend: the label of the group of options.

    Raises:
      ValueError: for a bad name, fewer than 2 options, hints not one per option, or a
        correct index outside the options.
    """

    def __init__(self, name, options, correct, hints, legend="Your prediction"):
        self.name = _validate.text("name", name)
        if not re.fullmatch(r"[a-z][a-z0-9-]*", name):
            raise ValueError(f"name must be lower-case letters, digits and dashes, got "
                             f"{name!r}")
        self.options = [_validate.text("options[i]", o) for o in options]
        if len(self.options) < 2:
            raise ValueError(f"options must hold at least 2 texts, got {len(self.options)}")
        self.hints = [_validate.text("hints[i]", h) for h in hints]
        if len(self.hints) != len(self.options):
            raise ValueError(f"hints must hold one text per option ({len(self.options)}), "
                             f"got {len(self.hints)}")
        self.correct = _validate.integer("correct", correct, 0, len(self.options) - 1)
        self.legend = _validate.text("legend", legend)

    def __repr__(self):
        lines = [f"{self.legend}:"]
        lines += [f"  ({chr(97 + i)}) {option}" for i, option in enumerate(self.options)]
        return "\n".join(lines)

    def _repr_html_(self):
        quiz = f"icm-quiz-{self.name}"
        parts = [f'<fieldset class="icm-quiz-choices" id="{quiz}">',
                 f"<legend>{html.escape(self.legend)}</legend>"]
        for i, (option, hint) in enumerate(zip(self.options, self.hints)):
            right = "true" if i == self.correct else "false"
            parts.append(
                f'<div class="icm-quiz-option"><input type="radio" name="{quiz}" '
                f'id="{quiz}-{i}" value="{i}" data-correct="{right}" '
                f'data-hint="{html.escape(hint, quote=True)}">'
                f'<label for="{quiz}-{i}">{html.escape(option)}</label></div>')
        parts.append("</fieldset>")
        return "".join(parts)
