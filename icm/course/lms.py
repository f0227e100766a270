"""The book's "predict, then check" questions for a learning platform: one Moodle XML
file holding all of them, read from the built book's pages.

    python -m icm.course lms _build/html --out questions.xml [--force]

In the book a question is answered in the page, with no kernel (`icm.exercises.Choices`
and `book/_static/icm-quiz.js`); its right option was chosen when the book was built,
from the number the chapter computed, and its explanation quotes that number. The
export takes each question as the built page shows it: its text, its options with
the right one and a hint for each wrong one, and its explanation (Moodle's general
feedback), one category per chapter. Moodle imports the file as it is (Question bank,
Import, format "Moodle XML"); formulas stay as `\\(...\\)`, which Moodle's MathJax
filter typesets.

The file is then read back with moodle-xml-parser (PyPI), a parser of Moodle's
question format, and each question must come back as it was written (`validate`).

The file to write is checked before any work (`icm.files.check_file`): it must end in
.xml, may not lie in the built book, and an existing file is replaced only if it is an
export of this command (its comment `SIGNATURE` on its second line), unless `force`.
It is written under a temporary name and renamed.
"""

import contextlib
import html
import io
import pathlib
import xml.etree.ElementTree as ElementTree

from icm import _validate, files, records
from icm.course.assign import chapters

DECLARATION = '<?xml version="1.0" encoding="UTF-8"?>'
SIGNATURE = ("<!-- Moodle XML written by python -m icm.course lms: the book's \"predict, "
             "then check\" questions. -->")
"""The comment under the XML declaration that marks an export of this command (which
it may replace)."""


class ExportError(ValueError):
    """A built book with no questions, or an export that does not read back."""


def _soup(path):
    from bs4 import BeautifulSoup

    try:
        return BeautifulSoup(records.read_text(path), "html.parser")
    except records.RecordError as error:
        raise ExportError(f"a page of the built book: {error}") from None


def _html_of(nodes):
    """The HTML of page nodes, links and the glue's spans reduced to their text."""
    from bs4 import BeautifulSoup

    text = "".join(str(node) for node in nodes)
    copy = BeautifulSoup(text, "html.parser")
    for tag in copy.find_all(["a", "span"]):
        if tag.name == "a" or "pasted-text" in tag.get("class", []):
            tag.unwrap()
    return str(copy).strip()


def quiz_questions(html_dir, root=None):
    """Every "predict, then check" question of the built book, in the book's order.

    Args:
      html_dir: the built book's HTML folder.
      root: the project's folder (default: this package's), for the chapters' order.

    Returns:
      A list of dicts: "chapter" (its title, numbered), "label", "name" (the exercise's
      number and title), "text" (HTML), "options" (a list of (text, right, hint)) and
      "explanation" (HTML).

    Raises:
      ExportError: for a folder that is not a built book.
    """
    html_dir = records.input_folder(html_dir, "the built book's folder",
                                    "build it first (make book)")
    names = [name for name, _ in (chapters() if root is None else chapters(root))]
    questions = []
    for number, name in enumerate(names, 1):
        page_path = html_dir / "book" / f"{name}.html"
        if not page_path.exists():
            raise ExportError(f"{page_path} is missing: build the book first (make book)")
        page = _soup(page_path)
        heading = page.find("h1")
        chapter = f"{number}. {heading.get_text(' ', strip=True).rstrip('#').strip()}"
        for block in page.select("div.exercise.icm-quiz"):
            fieldset = block.select_one("fieldset.icm-quiz-choices")
            explanation = block.select_one("div.icm-quiz-explanation")
            content = block.select_one("section") or block
            if fieldset is None or explanation is None:
                raise ExportError(f"{page_path.name}: the question {block.get('id')} has no "
                                  f"options or no explanation")
            text = []
            for child in content.children:
                if getattr(child, "name", None) == "div":
                    break
                text.append(child)
            title = block.select_one("p.admonition-title")
            if title is None:
                raise ExportError(f"{page_path.name}: the question {block.get('id')} has no "
                                  f"title")
            title = title.get_text(" ", strip=True)
            options = []
            for option in fieldset.select("div.icm-quiz-option"):
                choice, label = option.find("input"), option.find("label")
                if choice is None or label is None:
                    raise ExportError(f"{page_path.name}: an option of {block.get('id')} has "
                                      f"no input or no label")
                options.append((label.get_text(" ", strip=True),
                                choice.get("data-correct") == "true",
                                choice.get("data-hint", "")))
            if sum(right for _, right, _ in options) != 1:
                raise ExportError(f"{page_path.name}: {block.get('id')} must have one right "
                                  f"option")
            questions.append({"chapter": chapter, "label": block.get("id"),
                              "name": " ".join(title.replace("(", "").replace(")", "")
                                               .split()),
                              "text": _html_of(text),
                              "options": options,
                              "explanation": _html_of(explanation.children)})
    if not questions:
        raise ExportError(f"no \"predict, then check\" question in {html_dir}")
    return questions


def _text(parent, tag, value, html_format=False):
    element = ElementTree.SubElement(parent, tag)
    if html_format:
        element.set("format", "html")
    ElementTree.SubElement(element, "text").text = value
    return element


def moodle_xml(questions, course="Intrinsic motivation on the iCub"):
    """The questions as a Moodle XML quiz: a category per chapter, a single-answer
    multiple-choice question per question, options in the book's order.

    Args:
      questions: what `quiz_questions` gives.
      course: the top category's name.

    Returns:
      The XML text.
    """
    quiz = ElementTree.Element("quiz")
    chapter = None
    for question in questions:
        if question["chapter"] != chapter:
            chapter = question["chapter"]
            category = ElementTree.SubElement(quiz, "question", type="category")
            _text(category, "category", f"$course$/top/{course}/{chapter}")
        item = ElementTree.SubElement(quiz, "question", type="multichoice")
        _text(item, "name", question["name"])
        _text(item, "questiontext", question["text"], html_format=True)
        _text(item, "generalfeedback", question["explanation"], html_format=True)
        for tag, value in (("defaultgrade", "1"), ("penalty", "0.3333333"), ("hidden", "0"),
                           ("idnumber", question["label"]), ("single", "true"),
                           ("shuffleanswers", "false"), ("answernumbering", "abc")):
            ElementTree.SubElement(item, tag).text = value
        _text(item, "correctfeedback", "Right.", html_format=True)
        _text(item, "partiallycorrectfeedback", "", html_format=True)
        _text(item, "incorrectfeedback", "Not this one: see the hint.", html_format=True)
        for text, right, hint in question["options"]:
            answer = ElementTree.SubElement(item, "answer", fraction="100" if right else "0",
                                            format="html")
            ElementTree.SubElement(answer, "text").text = html.escape(text, quote=False)
            _text(answer, "feedback", "Right." if right else html.escape(hint, quote=False),
                  html_format=True)
    ElementTree.indent(quiz)
    return f"{DECLARATION}\n{SIGNATURE}\n" + ElementTree.tostring(quiz, encoding="unicode") + \
        "\n"


def is_export(path):
    """Whether a file is an export of this command (its first two lines: the XML
    declaration and `SIGNATURE`).

    Args:
      path: the file.

    Returns:
      True or False.
    """
    with open(path, "rb") as file:
        start = file.read(len(DECLARATION) + len(SIGNATURE) + 2)
    return start.decode("utf-8", "replace").split("\n")[:2] == [DECLARATION, SIGNATURE]


def validate(xml_text, questions):
    """Reads an export back with moodle-xml-parser and compares it with the questions.

    Args:
      xml_text: the export.
      questions: what was exported.

    Returns:
      A list of problems, empty when every question reads back as written.
    """
    from moodle_xml_parser.parser import parse_string

    said = io.StringIO()
    try:
        with contextlib.redirect_stdout(said):  # (the parser prints what it cannot read)
            parsed = parse_string(xml_text)
    except ValueError as error:
        return [f"not XML: {error}"]
    problems = [f"the parser: {line}" for line in said.getvalue().splitlines() if line.strip()]
    read = parsed["multichoice"]
    if len(read) != len(questions):
        return problems + [f"{len(read)} multiple-choice questions read, "
                           f"{len(questions)} written"]
    for question, back in zip(questions, read):
        # (The parser returns a text's HTML with its entities decoded: "&lt;" as "<".)
        where = question["label"]
        if back.name != question["name"]:
            problems.append(f"{where}: name {back.name!r}")
        if back.text_pre_parse != html.unescape(question["text"]):
            problems.append(f"{where}: the question's text differs")
        if back.general_feedback != html.unescape(question["explanation"]):
            problems.append(f"{where}: the explanation differs")
        if not back.single or back.shuffle_answers:
            problems.append(f"{where}: not one answer in the book's order")
        options = [(option.answer, option.score_fraction == 100.0, option.feedback)
                   for option in back.options]
        written = [(text, right, "Right." if right else hint)
                   for text, right, hint in question["options"]]
        if options != written:
            problems.append(f"{where}: options {options} read back, {written} written")
        if not any(option.score_fraction == 100.0 for option in back.options):
            problems.append(f"{where}: no right option")
    return problems


def export_moodle(html_dir, out, root=None, force=False):
    """Writes every "predict, then check" question of the built book into one Moodle
    XML file, and checks that it reads back.

    Args:
      html_dir: the built book's HTML folder.
      out: the file to write (.xml): new, or an export of this command (`is_export`),
        never inside `html_dir`.
      root: the project's folder (default: this package's).
      force: replace an existing file that is not an export of this command.

    Returns:
      The number of questions written.

    Raises:
      ExportError: when the book has no questions or the file does not read back.
      icm.files.DestinationError: for an `out` refused, before any work.
    """
    force = _validate.boolean("force", force)
    out = pathlib.Path(out)
    if out.suffix.lower() != ".xml":
        raise files.DestinationError(f"--out {out}: a Moodle XML file's name ends in .xml")
    files.check_file(out, own=is_export, force=force, inputs=[html_dir], what="--out")
    questions = quiz_questions(html_dir, root)
    text = moodle_xml(questions)
    problems = validate(text, questions)
    if problems:
        raise ExportError("the Moodle XML does not read back as written: " +
                          "; ".join(problems))
    files.write_text(out, text)
    return len(questions)
