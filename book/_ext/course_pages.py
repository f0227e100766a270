"""Sphinx extension: the instructors' page shows each chapter's learning objectives and
exercises as the chapter's notebook states them, never typed a second time.

- ``chapter-objectives``: the chapter's objectives block, the admonition of class
  ``icm-objectives`` in the markdown cell that opens the chapter (after its title)::

      :::{chapter-objectives} button_experiment
      :::

  A chapter without one shows nothing there (the build says so in its log).
- ``chapter-exercises``: a table of the chapter's exercises, each as "Exercise N: its
  title" (linked), its kind, and the time the instructor estimates (the directive's
  content, one ``label: time`` line per exercise; every exercise of the chapter must
  have one, and no other)::

      :::{chapter-exercises} button_experiment
      ex-press-outcome: 10 min
      :::

- ``exref``: a link to an exercise as "Exercise N: its title", e.g.
  ``{exref}`ex-press-outcome```, the title read from the chapter that holds it.

They read ``book/<name>.ipynb`` (a chapter's notebook is in the same folder as the
page that names it), so that a page rebuilds when a chapter changes.
"""

import pathlib
import re

import nbformat
from docutils import nodes, utils
from docutils.parsers.rst import Directive, directives
from docutils.statemachine import StringList
from sphinx import addnodes
from sphinx.util import logging

LOGGER = logging.getLogger(__name__)
EXERCISE = re.compile(r"\{exercise(?:-start)?\} (Implement|Predict, then check|Extend): "
                      r"(.+)\n:label: (ex-[a-z0-9-]+)")
KINDS = {"Implement": "implement", "Predict, then check": "predict, then check",
         "Extend": "extend"}
OBJECTIVES = "icm-objectives"
"""The class of a chapter's objectives block."""
STATIC = pathlib.Path(__file__).resolve().parent / "course_static"


def _notebook(directive, name):
    env = directive.state.document.settings.env
    path = pathlib.Path(env.doc2path(env.docname)).parent / f"{name}.ipynb"
    if not path.exists():
        raise directive.error(f"{directive.name}: no chapter notebook {path}")
    env.note_dependency(str(path))
    return nbformat.read(path, as_version=4), path


def objectives_block(notebook):
    """The lines of a chapter's objectives block (the MyST admonition with its
    fences), or None: it is looked for in the first markdown cell that holds a
    title, and the cell after it.

    Args:
      notebook: the chapter's notebook.

    Returns:
      A list of lines, or None.
    """
    markdown = [cell for cell in notebook.cells if cell.cell_type == "markdown"]
    for cell in markdown[:2]:
        lines = cell.source.splitlines()
        for start, line in enumerate(lines):
            fence = re.match(r"(:{3,}|`{3,})\{admonition\}", line)
            if not fence:
                continue
            end = next((i for i in range(start + 1, len(lines))
                        if lines[i].strip() == fence.group(1)), None)
            block = lines[start:end + 1] if end is not None else None
            if block and any(re.match(rf":class:.*\b{OBJECTIVES}\b", b) for b in block):
                return block
    return None


def chapter_exercises(notebook):
    """[(label, kind, title)] of a chapter's exercises, in order.

    Args:
      notebook: the chapter's notebook.

    Returns:
      The list.
    """
    found = []
    for cell in notebook.cells:
        if cell.cell_type == "markdown" and "solution" not in cell.metadata.get("tags", []):
            for kind, title, label in EXERCISE.findall(cell.source):
                found.append((label, KINDS[kind], title.strip()))
    return found


def _literal(title):
    """A title as the text of a numbered reference, whose "%s" Sphinx fills with the
    number: its own "%" doubled ("how many seeds make 90%")."""
    return title.replace("%", "%%")


class ChapterObjectives(Directive):
    """The objectives block of a chapter, as its notebook states it."""

    required_arguments = 1
    has_content = False

    def run(self):
        notebook, path = _notebook(self, self.arguments[0])
        block = objectives_block(notebook)
        if block is None:
            LOGGER.info(f"chapter-objectives: {path.name} opens with no objectives block "
                        f"(:class: {OBJECTIVES})")
            return []
        container = nodes.container(classes=["icm-chapter-objectives"])
        self.state.nested_parse(StringList(block, source=str(path)), 0, container)
        return [container]


class ChapterExercises(Directive):
    """A table of a chapter's exercises (number and title, kind, time)."""

    required_arguments = 1
    has_content = True

    def run(self):
        notebook, path = _notebook(self, self.arguments[0])
        times = {}
        for line in self.content:
            if line.strip():
                match = re.match(r"\s*(ex-[a-z0-9-]+):\s*(.+?)\s*$", line)
                if not match:
                    raise self.error(f"chapter-exercises: '{line}' is not 'label: time'")
                times[match.group(1)] = match.group(2)
        exercises = chapter_exercises(notebook)
        labels = [label for label, _, _ in exercises]
        if sorted(times) != sorted(labels):
            raise self.error(f"chapter-exercises: the times must name the exercises of "
                             f"{path.name} and no other: missing {sorted(set(labels) - set(times))},"
                             f" unknown {sorted(set(times) - set(labels))}")
        lines = [":::{list-table}", ":header-rows: 1", ":widths: 70 18 12",
                 ":class: icm-exercise-table", "", "* - exercise", "  - kind", "  - time"]
        for label, kind, title in exercises:
            lines += [f"* - {{numref}}`Exercise %s: {_literal(title)} <{label}>`", f"  - {kind}",
                      f"  - {times[label]}"]
        lines.append(":::")
        container = nodes.container(classes=["icm-chapter-exercises"])
        self.state.nested_parse(StringList(lines, source=str(path)), 0, container)
        return [container]


def exref_role(name, rawtext, text, lineno, inliner, options=None, content=None):
    """``{exref}`label```: "Exercise N: title", linked to the exercise."""
    env = inliner.document.settings.env
    label = utils.unescape(text).strip()
    titles = {}
    for path in sorted(pathlib.Path(env.doc2path(env.docname)).parent.glob("*.ipynb")):
        env.note_dependency(str(path))
        for found, _, title in chapter_exercises(nbformat.read(path, as_version=4)):
            titles[found] = title
    if label not in titles:
        message = inliner.reporter.error(f"exref: no exercise labelled {label!r}",
                                         line=lineno)
        return [inliner.problematic(rawtext, rawtext, message)], [message]
    text = f"Exercise %s: {_literal(titles[label])}"
    reference = addnodes.pending_xref(rawtext, refdoc=env.docname, refdomain="std",
                                      reftype="numref", reftarget=label, refexplicit=True,
                                      refwarn=True)
    reference += nodes.inline(text, text, classes=["xref", "std", "std-numref"])
    return [reference], []


def _static_path(app, config):
    config.html_static_path = list(config.html_static_path) + [str(STATIC)]


def setup(app):
    directives.register_directive("chapter-objectives", ChapterObjectives)
    directives.register_directive("chapter-exercises", ChapterExercises)
    app.add_role("exref", exref_role)
    app.connect("config-inited", _static_path)
    app.add_css_file("icm-course.css")
    return {"parallel_read_safe": True, "parallel_write_safe": True}
