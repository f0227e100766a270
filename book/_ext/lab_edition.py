"""Writes the notebooks `make lab` opens, and opens them in JupyterLab: each chapter
as its page reads, with the book's numbers in its prose.

    python book/_ext/lab_edition.py [--instructor] [--path-output DIR] [--folder DIR]
                                    [--write-only] [JUPYTER_OPTION ...]

`make lab` runs it for a student, `make lab-instructor` with `--instructor`. Why it
is needed: a chapter's prose quotes its numbers through myst-nb's glue roles
(`` {glue:text}`key:.1f` ``), which only the book's build fills in, from the
notebook's executed outputs. JupyterLab shows Markdown cells as they are written;
jupyterlab-myst (pinned in requirements.txt) renders MyST there (admonitions,
dropdowns, exercises, figures), but it knows nothing of myst-nb's glue, nor of
Sphinx's `{doc}` and sphinxcontrib-bibtex's `{cite:p}`, nor of the page's script that
checks a quiz. So this writes a copy of each chapter for Jupyter:

1. **Executed as the book is**: the notebooks run through `execute_book.py` into the
   book's execution cache (`<path-output>/_build/.jupyter_cache`, the one `make book`
   uses and fills: after a `make book`, nothing runs again; on a fresh clone, every
   chapter runs once, a few minutes). Each copy is the source notebook with the
   cached outputs merged in, as myst-nb merges them to build the page
   (jupyter-cache's `merge_match_into_notebook`): the page and the copy are made from
   the same executed notebook.
2. **The glue resolved** (`resolve_markdown`), with myst-nb's own functions, so that
   each number reads as on the page: `{glue:text}` by myst-nb's `format_plain_text`,
   `{glue:md}` (role and directive) by the glued Markdown, `{glue:figure}` by a MyST
   `figure` whose image is the glued PNG, attached to the cell (`attachment:`). The
   hidden glue outputs, which Jupyter would show as "no renderer", are dropped, as
   myst-nb drops them.
3. **What only the book's build or page knows, written for Jupyter**: `{doc}` becomes a
   link to the chapter's notebook, titled as the book titles it; `{cite:p}` and
   `{cite:t}` read as the page's author-year citations (`bibliography.author_year`,
   the labels of the References page); a quiz's explanation
   (`{div} icm-quiz-explanation`, which the page's script shows once the reader has
   answered) is folded in a dropdown, so that the answer is not shown before the
   question is answered. A cell the page hides (`remove-input`, `remove-cell`,
   `hide-input`, ...) has its code collapsed (`jupyter.source_hidden`, which
   JupyterLab and Notebook 7 honour), and its outputs too where the page shows none
   (`remove-cell`, `remove-output`, ...).
4. **The students' copy has no solutions**: `student_edition.strip_solutions` (the
   students' edition of the book does the same) takes out every cell tagged
   `solution`, so Run All runs no solution. `--instructor` keeps them.
5. **Written where this command may write**: `<path-output>/_build/lab/students` (or
   `instructor`), never into `book/`. The folder carries a marker
   (`MARKER`, with what was written); a folder without it is refused. A notebook
   whose cells a student has changed since it was written (its cells' sources
   differ from the record) is kept, with a note, never overwritten; the others are
   replaced (through a temporary file and a rename).
6. **JupyterLab, started in that folder** (unless `--write-only`), with the other
   options passed on (`--port 8890 --no-browser`, ...). As root (a container, a
   Binder-like set-up), Jupyter refuses to start without `--allow-root`: it is
   added, with a line that says so.

A construct this cannot write for Jupyter (a glue role of another kind, glue from
another notebook) stops it, naming the notebook and the cell.

Exit status: 0 (or JupyterLab's own), 1 when the notebooks could not be executed or
written.
"""

import argparse
import base64
import copy
import hashlib
import json
import os
import pathlib
import re
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

import student_edition  # noqa: E402  (book/_ext: strip_solutions, the one stripper)

EDITIONS = ("students", "instructor")
MARKER = ".icm-lab-edition.json"
"""The file that marks a folder as written by this command, with a record of the
notebooks written (name: hash of their cells' sources)."""
HIDDEN_INPUT_TAGS = ("remove-input", "remove-cell", "hide-input", "hide-cell")
"""Tags with which the book hides a cell's code (Jupyter Book's); Jupyter collapses it."""
HIDDEN_OUTPUT_TAGS = ("remove-output", "hide-output", "remove-cell", "hide-cell")
QUIZ_EXPLANATION = "icm-quiz-explanation"
"""The class of a quiz's explanation (`{div} icm-quiz-explanation`), which the page's
script shows once the reader has answered (book/_static/icm-quiz.js)."""
QUIZ_DROPDOWN_TITLE = "Check your answer"
ROLE = re.compile(r"\{(?P<name>[a-z][a-z0-9:_-]*)\}`(?P<content>[^`]*)`")
RENDERED_AS_WRITTEN = ("math", "sub", "sup", "abbr", "kbd", "u", "del", "strike",
                       "smallcaps")
"""Roles jupyterlab-myst renders as the page does, left as they are (the others that
this does not write for Jupyter stop it)."""
DIRECTIVE = re.compile(
    r"^(?P<indent>[ \t]*)(?P<fence>`{3,}|:{3,})\{(?P<name>glue(?::[a-z]+)?|div)\}"
    r"[ \t]*(?P<argument>.*?)[ \t]*$")
OPTION = re.compile(r"^[ \t]*:(?P<key>[a-z_-]+):[ \t]*(?P<value>.*?)[ \t]*$")


class LabEditionError(ValueError):
    """A chapter that cannot be written for Jupyter, or a folder that may not be written."""


# --- what a chapter's prose quotes -----------------------------------------------------

def glue_data(notebook):
    """The glued outputs of an executed notebook ({key: output}), and the notebook with
    the hidden glue outputs dropped, as myst-nb reads and drops them (a new notebook)."""
    from myst_nb.ext.glue import extract_glue_data_cell

    notebook = copy.deepcopy(notebook)
    data = {}
    for cell in notebook.cells:
        if cell.cell_type == "code":
            data.update(extract_glue_data_cell(cell))
    return data, notebook


def _glued(data, key, mime, where):
    if key not in data:
        raise LabEditionError(f"{where}: no glued value {key!r} in the executed notebook")
    bundle = data[key].get("data", {})
    if mime not in bundle:
        raise LabEditionError(f"{where}: the glued value {key!r} has no {mime}")
    return bundle[mime]


def _text(data, content, where):
    """`{glue:text}`key:format``, as the page shows it (myst-nb's PasteTextRole)."""
    from myst_nb.core.variables import format_plain_text

    if "::" in content:
        raise LabEditionError(f"{where}: glue from another notebook ({content!r}) is not "
                              f"written for Jupyter (the book uses none)")
    key, _, spec = content.rpartition(":") if ":" in content else (content, "", "s")
    return format_plain_text(_glued(data, key, "text/plain", where), spec)


def _markdown(data, content, where):
    """`{glue:md}`key``: the glued Markdown (a format after the key is the page's)."""
    key = content.rsplit(":", 1)[0]
    return _glued(data, key, "text/markdown", where).strip()


def chapter_titles(root=ROOT):
    """{page: title} of the book's pages (their first `# ` heading), for `{doc}`."""
    titles = {}
    for path in sorted((root / "book").glob("*.ipynb")) + sorted((root / "book").glob("*.md")):
        if path.suffix == ".ipynb":
            cells = json.loads(path.read_text())["cells"]
            text = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "markdown")
        else:
            text = path.read_text()
        heading = re.search(r"^# (.+)$", text, re.MULTILINE)
        titles[path.stem] = (heading.group(1).strip() if heading else path.stem, path.suffix)
    return titles


def citation_labels(root=ROOT):
    """{key: "Author, year"} of the book's bibliography, as the page cites it."""
    from pybtex.database import parse_file

    import bibliography

    entries = parse_file(str(root / "book" / "references.bib")).entries
    return {key: bibliography.author_year(entry) for key, entry in entries.items()}


def _doc(content, titles, where):
    match = re.fullmatch(r"\s*(?:(?P<text>.*?)\s*<(?P<target>[^>]+)>|(?P<bare>[^<>]+?))\s*",
                         content)
    target = (match.group("target") or match.group("bare")).strip()
    name = target.lstrip("/").removeprefix("book/").removesuffix(".ipynb").removesuffix(".md")
    if name not in titles:
        raise LabEditionError(f"{where}: {{doc}} to {target!r}, not a page of the book")
    title, suffix = titles[name]
    text = match.group("text") or title
    # Jupyter opens a chapter's notebook beside this one; the book's other pages are
    # Markdown files it does not have.
    return f"[{text}]({name}.ipynb)" if suffix == ".ipynb" else f"*{text}* (in the book)"


def _cite(name, content, labels, where):
    keys = [key.strip() for key in content.split(",") if key.strip()]
    unknown = [key for key in keys if key not in labels]
    if unknown:
        raise LabEditionError(f"{where}: cited {', '.join(unknown)}, not in references.bib")
    cited = sorted(labels[key] for key in keys)  # in the page's order, by author and year
    if name == "cite:t":  # "Sutton and Barto [1998]", as sphinxcontrib-bibtex's author_year
        return ", ".join("{} [{}]".format(*label.rsplit(", ", 1)) for label in cited)
    return "[" + ", ".join(cited) + "]"


def _reference(name, content, targets, where):
    """A cross-reference as the page writes it: {ref} as the target's title (or the
    text given), {numref} as its number ("Fig. 3.2", "Exercise 3.1", or the text given
    with its %s filled)."""
    given = re.match(r"(?s)(.*?)\s*<([^>]*)>$", content)
    text, label = (given.group(1), given.group(2)) if given else (None, content.strip())
    target = (targets or {}).get(label)
    if target is None:
        raise LabEditionError(f"{where}: {{{name}}}`{content}` names no figure, exercise, "
                              f"section or fold of the book")
    if name == "ref":
        return text or target["title"]
    if target.get("number") is None:
        raise LabEditionError(f"{where}: {{numref}}`{content}`: {label} has no number")
    if text:
        return text.replace("%s", target["number"])
    return f"{target['kind']} {target['number']}"


def targets_of(cells, chapter):
    """The chapter's cross-reference targets, numbered as the page numbers them: its
    figures (captioned code cells and glued figures, in order: "Fig." N.k), its
    exercises ("Exercise" N.k), its labelled sections and folds (their titles).

    Args:
      cells: the chapter's cells (nbformat), in order.
      chapter: the chapter's number (None: nothing numbered).

    Returns:
      {label: {"kind", "number" (None if not numbered), "title"}}.
    """
    found, figures, exercises = {}, 0, 0
    number = lambda k: f"{chapter}.{k}" if chapter is not None else None
    for cell in cells:
        source = cell.source if isinstance(cell.source, str) else "".join(cell.source)
        if cell.cell_type == "code":
            figure = cell.get("metadata", {}).get("mystnb", {}).get("figure", {})
            if figure.get("caption"):
                figures += 1
                if figure.get("name"):
                    found[figure["name"]] = {"kind": "Fig.", "number": number(figures),
                                             "title": f"Fig. {number(figures)}"}
            continue
        if cell.cell_type != "markdown":
            continue
        for match in re.finditer(r"(?m)^[ \t]*(`{3,}|:{3,})\{(glue:figure|exercise(?:-start)?|"
                                 r"dropdown)\}[ \t]*(.*)$", source):
            kind, argument = match.group(2), match.group(3).strip()
            rest = source[match.end():]
            option = re.match(r"(?:\n[ \t]*:[a-z_-]+:.*)*?\n[ \t]*:(?:name|label):[ \t]*(\S+)",
                              rest)
            label = option.group(1) if option else None
            if kind == "glue:figure":
                figures += 1
                if label:
                    found[label] = {"kind": "Fig.", "number": number(figures),
                                    "title": f"Fig. {number(figures)}"}
            elif kind.startswith("exercise"):
                exercises += 1
                if label:
                    title = re.sub(r"^(Implement|Predict, then check|Extend):\s*", "", argument)
                    found[label] = {"kind": "Exercise", "number": number(exercises),
                                    "title": title}
            elif label:
                found[label] = {"kind": "", "number": None, "title": argument}
        for match in re.finditer(r"(?m)^\(([\w-]+)\)=[ \t]*\n#+[ \t]+(.+)$", source):
            found[match.group(1)] = {"kind": "", "number": None,
                                     "title": match.group(2).strip()}
    return found


def _roles(line, data, titles, labels, where, targets=None):
    def replace(match):
        name, content = match.group("name"), match.group("content")
        if name in ("ref", "numref"):
            return _reference(name, content, targets, where)
        if name == "glue:text":
            return _text(data, content, where)
        if name == "glue:md":
            return _markdown(data, content, where)
        if name == "doc":
            return _doc(content, titles, where)
        if name in ("cite:p", "cite:t"):
            return _cite(name, content, labels, where)
        if name in RENDERED_AS_WRITTEN:
            return match.group(0)
        raise LabEditionError(f"{where}: the role {{{name}}} is not written for Jupyter "
                              f"(lab_edition.py writes glue:text, glue:md, doc, ref, "
                              f"numref, cite:p and cite:t, and leaves "
                              f"{', '.join(RENDERED_AS_WRITTEN)})")

    return ROLE.sub(replace, line)


def _block(lines, start, indent, fence, where):
    """(options, content lines, index after the closing fence) of the directive whose
    opening fence is lines[start]."""
    options, index = {}, start + 1
    while index < len(lines) and OPTION.match(lines[index]):
        option = OPTION.match(lines[index])
        options[option.group("key")] = option.group("value")
        index += 1
    content = []
    closing = re.compile(rf"^{re.escape(indent)}{re.escape(fence[0])}{{{len(fence)},}}[ \t]*$")
    while index < len(lines) and not closing.match(lines[index]):
        content.append(lines[index])
        index += 1
    if index == len(lines):
        raise LabEditionError(f"{where}: the directive of line {start + 1} is not closed")
    while content and not content[0].strip():
        content.pop(0)
    return options, content, index + 1


def caption_markdown(label, caption):
    """A figure's caption as the page shows it under the figure: "**Fig. 2.1** ...",
    numbered as the page numbers it (numfig: chapter, then the figure's place in it)."""
    return f"**Fig. {label}** {caption.strip()}"


def _plain_words(markdown):
    """Markdown as one line of plain words (a figure's alternative text)."""
    return " ".join(re.sub(r"[*_`\\[\]]", "", markdown).split())


def resolve_markdown(source, data, titles, labels, next_figure=None, where="cell",
                     targets=None):
    """A Markdown cell's source with the book's own constructs written for Jupyter.

    Args:
      source: the cell's MyST Markdown.
      data: the glued outputs of the executed notebook (`glue_data`).
      titles: the book's pages' titles (`chapter_titles`).
      labels: the bibliography's citation labels (`citation_labels`).
      next_figure: called once per glued figure, returns its number ("2.4"); None
        numbers none.
      where: the notebook and cell, for errors.
      targets: the chapter's cross-reference targets (`targets_of`), for {ref} and
        {numref}.

    Returns:
      (source, attachments): the MyST Markdown jupyterlab-myst renders, and the cell's
      attachments (the glued figures' PNGs), {} when none.

    Raises:
      LabEditionError: naming `where`, for a construct not written for Jupyter.
    """
    lines = source.split("\n")
    out, attachments, index = [], {}, 0
    while index < len(lines):
        match = DIRECTIVE.match(lines[index])
        if not match:
            out.append(_roles(lines[index], data, titles, labels, where, targets))
            index += 1
            continue
        indent, fence, name = match.group("indent", "fence", "name")
        argument = match.group("argument")
        if name == "div":
            if argument.split() == [QUIZ_EXPLANATION]:
                out.append(f"{indent}{fence}{{dropdown}} {QUIZ_DROPDOWN_TITLE}")
            else:
                out.append(_roles(lines[index], data, titles, labels, where, targets))
            index += 1
            continue
        options, content, index = _block(lines, index, indent, fence, where)
        if name == "glue:md":
            out.extend(indent + line if line else line
                       for line in _markdown(data, argument, where).split("\n"))
        elif name == "glue:figure":
            # The image, then its caption as a paragraph, as under a code cell's figure
            # (`lab_notebook`): the page numbers both kinds in one sequence.
            png = _glued(data, argument, "image/png", where)
            attachment = f"{argument}.png"
            attachments[attachment] = {"image/png": png if isinstance(png, str)
                                       else base64.b64encode(png).decode()}
            caption = "\n".join(_roles(line[len(indent):] if line.startswith(indent) else line,
                                       data, titles, labels, where, targets)
                                for line in content)
            alt = options.get("alt") or _plain_words(caption)
            out.append(f"{indent}![{alt}](attachment:{attachment})")
            if caption.strip():
                label = next_figure() if next_figure else None
                text = caption_markdown(label, caption) if label else caption.strip()
                out.append("")
                out.extend(indent + line if line else line for line in text.split("\n"))
        else:
            raise LabEditionError(f"{where}: the directive {{{name}}} is not written for "
                                  f"Jupyter (lab_edition.py writes glue:md and glue:figure)")
    return "\n".join(out), attachments


# --- one chapter for Jupyter ---------------------------------------------------------------

def chapter_numbers(root=ROOT):
    """{notebook stem: its number in the book} (the chapters of the numbered parts of
    _toc.yml, counted from 1, as the page numbers them)."""
    import yaml

    toc = yaml.safe_load((root / "_toc.yml").read_text())
    files = [chapter["file"] for part in toc.get("parts", []) if part.get("numbered")
             for chapter in part["chapters"]]
    return {pathlib.PurePosixPath(file).name: number
            for number, file in enumerate(files, start=1)}


def numbering_frontmatter(chapter):
    """MyST front matter that numbers the chapter's exercises as the page does
    ("Exercise 2.1"), for the notebook's first Markdown cell (jupyterlab-myst reads
    it there and does not show it)."""
    return f'---\nnumbering:\n  enumerator: "{chapter}.%s"\n---\n'


def lab_notebook(executed, edition, titles, labels, chapter=None, name="notebook",
                 book_targets=None):
    """The chapter as `make lab` opens it (a new notebook; the argument is unchanged).

    Args:
      executed: the chapter executed, its outputs merged into its source
        (`executed_chapters`).
      edition: "students" (without the solutions) or "instructor".
      titles, labels: as `resolve_markdown` takes them.
      chapter: the chapter's number in the book, which numbers its exercises and
        figures as the page does (None: not numbered).
      name: the notebook's name, for errors.
      book_targets: the other chapters' cross-reference targets (`book_targets`), for
        a {ref} or {numref} to another chapter, as the page resolves it (default: none).

    Raises:
      LabEditionError: for a construct not written for Jupyter.
      student_edition.StripError: for a chapter whose solutions cannot be taken out.
    """
    import nbformat

    if edition not in EDITIONS:
        raise ValueError(f"edition must be one of {', '.join(EDITIONS)}, got {edition!r}")
    data, notebook = glue_data(executed)
    if edition == "students":
        notebook = student_edition.strip_solutions(notebook, name)
    figures = []
    targets = {**(book_targets or {}), **targets_of(notebook.cells, chapter)}

    def next_figure():
        figures.append(f"{chapter}.{len(figures) + 1}")
        return figures[-1]

    cells, numbered = [], chapter is None
    for index, cell in enumerate(notebook.cells):
        where = f"{name}, cell {index}"
        tags = cell.get("metadata", {}).get("tags", [])
        cells.append(cell)
        if cell.cell_type == "markdown":
            cell.source, attachments = resolve_markdown(
                cell.source, data, titles, labels, next_figure if chapter else None, where,
                targets)
            if attachments:
                cell["attachments"] = {**cell.get("attachments", {}), **attachments}
            if not numbered:
                cell.source = numbering_frontmatter(chapter) + cell.source
                numbered = True
        elif cell.cell_type == "code":
            jupyter = cell.metadata.setdefault("jupyter", {})
            if any(tag in tags for tag in HIDDEN_INPUT_TAGS):
                jupyter["source_hidden"] = True
            if any(tag in tags for tag in HIDDEN_OUTPUT_TAGS):
                jupyter["outputs_hidden"] = True
            if not jupyter:
                del cell.metadata["jupyter"]
            figure = cell.metadata.get("mystnb", {}).get("figure", {})
            if figure.get("caption"):
                # The page shows the caption under the cell's output; Jupyter shows
                # none, so it follows the cell, as a Markdown cell of its own.
                caption, _ = resolve_markdown(figure["caption"], data, titles, labels,
                                              where=where, targets=targets)
                text = caption_markdown(next_figure(), caption) if chapter else caption
                cells.append(nbformat.v4.new_markdown_cell(
                    text, metadata={"icm": {"caption_of": figure.get("name", "")}}))
    notebook.cells = cells
    return notebook


def executed_chapters(path_output, root=ROOT):
    """{notebook path: the notebook with its executed outputs merged in}, from the
    book's execution cache in `path_output`, after running every chapter the cache
    does not hold (`execute_book.py`, in a process of its own: its kernels' settings
    are the book's, not a student's).

    Raises:
      LabEditionError: when the execution failed.
    """
    import nbformat

    command = [sys.executable, str(HERE / "execute_book.py"), "--path-output", str(path_output)]
    if subprocess.call(command, cwd=root) != 0:
        raise LabEditionError("the chapters could not be executed (see above); the "
                              "notebooks need their outputs for the numbers of their prose")
    from jupyter_cache import get_cache

    import execute_book

    cache = get_cache(str(path_output / "_build" / ".jupyter_cache"))
    executed = {}
    for path in execute_book.notebooks():
        source = nbformat.read(path, as_version=4)
        try:
            # The source's cell metadata (its tags) wins over the cached copy's.
            _, merged = cache.merge_match_into_notebook(source, cell_meta=())
        except KeyError as error:
            raise LabEditionError(f"{path.name} is not in the execution cache after its "
                                  f"execution") from error
        executed[path] = merged
    return executed


# --- the folder ----------------------------------------------------------------------------

def cells_digest(notebook):
    """A hash of a notebook's cells' types and sources (what a student edits; running
    cells or JupyterLab's saving of metadata does not change it)."""
    digest = hashlib.sha256()
    for cell in notebook["cells"]:
        source = cell["source"]
        digest.update(json.dumps([cell["cell_type"], "".join(source) if isinstance(
            source, list) else source]).encode())
    return digest.hexdigest()


def _read_marker(folder):
    path = folder / MARKER
    try:
        record = json.loads(path.read_text())
        if record.get("written_by") != "book/_ext/lab_edition.py":
            raise ValueError
        return record
    except (OSError, ValueError, AttributeError) as error:
        raise LabEditionError(
            f"{folder} exists and was not written by make lab (no readable {MARKER}): "
            f"move it away, it is left as it is") from error


def write_edition(folder, notebooks, edition):
    """Writes `notebooks` ({file name: notebook}) into `folder`, the folder of this
    command (created with its marker, or carrying it).

    A notebook already there is replaced only if its cells are those this command
    wrote (`cells_digest`); one a student changed, or that this command did not write,
    is kept.

    Returns:
      (written, kept): the file names written and those kept.

    Raises:
      LabEditionError: for a folder that exists without the marker.
    """
    import nbformat

    folder = pathlib.Path(folder)
    if folder.exists():
        record = _read_marker(folder)
    else:
        folder.mkdir(parents=True)
        record = {"written_by": "book/_ext/lab_edition.py", "edition": edition, "notebooks": {}}
    written, kept = [], []
    for name, notebook in notebooks.items():
        path = folder / name
        if path.exists():
            try:
                current = cells_digest(json.loads(path.read_text()))
            except (OSError, ValueError, KeyError, TypeError):
                current = None
            if current is None or current != record["notebooks"].get(name):
                kept.append(name)
                continue
        temporary = folder / f".{name}.tmp"
        nbformat.write(notebook, temporary)
        os.replace(temporary, path)
        record["notebooks"][name] = cells_digest(json.loads(path.read_text()))
        written.append(name)
        temporary_marker = folder / f"{MARKER}.tmp"
        temporary_marker.write_text(json.dumps(record, indent=1, sort_keys=True))
        os.replace(temporary_marker, folder / MARKER)
    if not written:  # the marker of a new folder, even when nothing was written
        (folder / MARKER).write_text(json.dumps(record, indent=1, sort_keys=True))
    return written, kept


def edition_folder(path_output, edition):
    """Where the notebooks of `edition` are written."""
    return pathlib.Path(path_output) / "_build" / "lab" / edition


EDITION_WORDS = {"students": "the students' edition, without the solutions",
                 "instructor": "the instructor's edition, with the solutions"}


def book_targets(executed, numbers):
    """Every chapter's cross-reference targets in one map (`targets_of`, each chapter
    numbered by `numbers`), so that a chapter may name another's figure as the page
    does; a label used by two chapters is an error, as Sphinx warns of it."""
    found, owner = {}, {}
    for path, notebook in executed.items():
        for label, target in targets_of(notebook.cells, numbers.get(path.stem)).items():
            if label in found:
                raise LabEditionError(f"{path.name}: the label {label!r} is also "
                                      f"{owner[label]}'s")
            found[label], owner[label] = target, path.name
    return found


def prepare(path_output, edition, folder=None, root=ROOT):
    """Executes (what the cache lacks), writes the edition's notebooks into `folder`
    (default: `edition_folder`); returns the folder. Prints what it wrote and kept."""
    executed = executed_chapters(path_output, root)
    titles, labels, numbers = chapter_titles(root), citation_labels(root), chapter_numbers(root)
    targets = book_targets(executed, numbers)
    notebooks = {path.name: lab_notebook(nb, edition, titles, labels,
                                         numbers.get(path.stem), path.name, targets)
                 for path, nb in executed.items()}
    folder = pathlib.Path(folder) if folder else edition_folder(path_output, edition)
    written, kept = write_edition(folder, notebooks, edition)
    print(f"lab: {len(written)} chapters written for Jupyter into {folder} "
          f"({EDITION_WORDS[edition]})")
    for name in kept:
        print(f"lab: kept your copy of {name} (you changed its cells); delete it and run "
              f"this again for the book's current version")
    return folder


# --- JupyterLab ------------------------------------------------------------------------------

def jupyter_command(folder, options=(), euid=None):
    """The command that starts JupyterLab on `folder` with `options`; with
    `--allow-root` added when run as root (`euid` 0; default: this process's), since
    Jupyter refuses to start as root without it."""
    euid = os.geteuid() if euid is None else euid
    command = [sys.executable, "-m", "jupyter", "lab", f"--ServerApp.root_dir={folder}"]
    if euid == 0 and "--allow-root" not in options:
        command.append("--allow-root")
    return command + list(options)


def main(argv=None):
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0], allow_abbrev=False,
        epilog="Other options are passed to jupyter lab (e.g. --port 8890 --no-browser).")
    parser.add_argument("--instructor", action="store_true",
                        help="the notebooks with the exercises' solutions (default: a "
                             "student's, without them)")
    parser.add_argument("--path-output", type=pathlib.Path, default=ROOT,
                        help="the book's output folder, whose _build holds the execution "
                             "cache; the notebooks go into its _build/lab (default: the "
                             "project)")
    parser.add_argument("--folder", type=pathlib.Path,
                        help="where the notebooks go (default: <path-output>/_build/lab/"
                             "students, or instructor)")
    parser.add_argument("--write-only", action="store_true",
                        help="write the notebooks, do not start JupyterLab")
    args, options = parser.parse_known_args(argv)
    edition = "instructor" if args.instructor else "students"
    try:
        folder = prepare(args.path_output.resolve(), edition,
                         args.folder.resolve() if args.folder else None)
    except (LabEditionError, student_edition.StripError) as error:
        print(f"lab: {error}", file=sys.stderr)
        return 1
    if args.write_only:
        return 0
    command = jupyter_command(folder, options)
    if "--allow-root" in command and "--allow-root" not in options:
        print("lab: running as root, so JupyterLab is started with --allow-root")
    sys.stdout.flush()
    os.execv(command[0], command)  # JupyterLab takes this process (and its Ctrl-C)


if __name__ == "__main__":
    sys.exit(main())
