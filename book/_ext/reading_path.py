"""What a student meets on each chapter page: the words of prose outside folds, the
visible code cells and those that only glue numbers, and whether the chapter opens
with its objectives and ends with its takeaways.

    python book/_ext/reading_path.py [HTML_DIR=_build/html]

It reads the notebooks (their cells and tags) and the built HTML (what a reader sees
with every fold closed). The tests call the same functions (tests/test_reading_path.py).

Folds are what the reader must open to see: sphinx-design dropdowns (`<details>`),
admonitions with the class `dropdown` (the exercises' solutions), and cell inputs or
outputs tagged `hide-input`/`hide-output`. Code is left out of the words (inputs and
`<pre>` blocks), as are the figures' images; their captions, tables and the exercises'
text count, since a student reads them.
"""

import json
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
BOOK = ROOT / "book"

OBJECTIVES_CLASS = "icm-objectives"
"""The class of a chapter's "Learning objectives" admonition (its first block)."""
TAKEAWAYS_CLASS = "icm-takeaways"
"""The class of a chapter's "Key takeaways" admonition (its last block before the
exercises)."""
MAX_WORDS = 3000
"""The most words of prose a chapter shows outside its folds (about 20 minutes)."""
HIDDEN_TAGS = {"remove-cell", "remove-input", "hide-input", "hide-cell"}
"""Tags that keep a code cell's input off the student's path."""
BOOKKEEPING = re.compile(r"\b(glue|require)\s*\(|\.claims\s*\(")
"""Calls that a visible cell must not make: gluing numbers for the prose, checking
the chapter's claims."""


def chapters():
    """The chapter notebooks in the order of `_toc.yml` (part "Chapters")."""
    from icm._book import toc_pages

    return [ROOT / (page + ".ipynb") for page in toc_pages(ROOT, "Chapters")]


def _source(cell):
    source = cell.get("source", "")
    return "".join(source) if isinstance(source, list) else source


def _tags(cell):
    return set(cell.get("metadata", {}).get("tags", []))


def notebook_path(notebook):
    """The student's path through a notebook's cells: a dict with "visible_code"
    (code cells whose input is shown), "visible_bookkeeping" (the indices of those
    that glue or check claims), "objectives_first" (the first block after the title
    is the objectives admonition) and "takeaways_last" (the last markdown before the
    exercises holds the takeaways admonition)."""
    cells = json.loads(pathlib.Path(notebook).read_text())["cells"]
    shown = [(i, c) for i, c in enumerate(cells) if not (_tags(c) & {"remove-cell"})]
    code = [(i, c) for i, c in shown if c["cell_type"] == "code"
            and not (_tags(c) & (HIDDEN_TAGS | {"solution"}))]  # solutions are folded
    bookkeeping = [i for i, c in code if BOOKKEEPING.search(_source(c))]
    markdown = [_source(c) for _, c in shown if c["cell_type"] == "markdown"]
    text = "\n".join(markdown)
    title = re.search(r"^# .*$", text, re.M)
    after_title = text[title.end():] if title else text
    first_block = re.search(r"^(:::+|```+)\s*\{[\w-]+\}.*$", after_title, re.M)
    objectives_first = bool(first_block) and OBJECTIVES_CLASS in \
        after_title[first_block.start():first_block.start() + 300] and \
        not re.search(r"^#+ ", after_title[:first_block.start()], re.M)
    before_exercises = text.split("\n## Exercises")[0]
    last = before_exercises.rfind(TAKEAWAYS_CLASS)
    takeaways_last = last >= 0 and not re.search(r"^#+ ", before_exercises[last:], re.M)
    return {"visible_code": len(code), "visible_bookkeeping": bookkeeping,
            "objectives_first": objectives_first, "takeaways_last": takeaways_last}


def _closed_page(html):
    """The page's article as a reader sees it with every fold closed (a BeautifulSoup
    element): folded blocks, code and images removed."""
    from bs4 import BeautifulSoup

    article = BeautifulSoup(html, "lxml").select_one("article.bd-article")
    folded = ["details", "div.dropdown", "div.toggle-hidden", ".tag_hide-input .cell_input",
              ".tag_hide-output .cell_output", ".tag_hide-cell", "div.cell_input", "pre",
              "script", "style", "img", "svg", "a.headerlink", ".icm-quiz-explanation"]
    for selector in folded:
        for element in article.select(selector):
            element.decompose()
    return article


def visible_words(html_file):
    """The words of prose a reader sees on a built page with every fold closed."""
    text = _closed_page(pathlib.Path(html_file).read_text()).get_text(" ")
    return len(re.findall(r"[^\W\d_]+(?:['’-][^\W\d_]+)*|\d[\d.,%]*", text))


def report(html_dir):
    """One dict per chapter: "chapter", "words" (`visible_words`) and the fields of
    `notebook_path`."""
    html_dir = pathlib.Path(html_dir)
    rows = []
    for notebook in chapters():
        page = html_dir / notebook.relative_to(ROOT).with_suffix(".html")
        rows.append({"chapter": notebook.stem, "words": visible_words(page),
                     **notebook_path(notebook)})
    return rows


def main(argv):
    html_dir = pathlib.Path(argv[0] if argv else ROOT / "_build" / "html")
    rows = report(html_dir)
    print(f"{'chapter':<24} {'words':>6} {'code':>5} {'glue':>5}  objectives  takeaways")
    for r in rows:
        print(f"{r['chapter']:<24} {r['words']:>6} {r['visible_code']:>5} "
              f"{len(r['visible_bookkeeping']):>5}  {str(r['objectives_first']):<10}  "
              f"{r['takeaways_last']}")
    print(f"{'total':<24} {sum(r['words'] for r in rows):>6} "
          f"{sum(r['visible_code'] for r in rows):>5} "
          f"{sum(len(r['visible_bookkeeping']) for r in rows):>5}")


if __name__ == "__main__":
    main(sys.argv[1:])
