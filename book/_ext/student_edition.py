"""Builds the students' edition of the book: every page, with the exercises, their
placeholder cells and their checks, and no solution.

    python book/_ext/student_edition.py [--path-output DIR] [--strict] [--keep-going]

`make book-students` runs it. What it does:

1. **Copies the book's sources** into `<path-output>/_build/students/source`
   (`_config.yml`, `_toc.yml`, `book/`; `icm/`, `assets/`, `requirements.txt` and
   `pyproject.toml` linked, so that the execution cache knows the library), and
   marks the copy's configuration as the students' edition (its title, and
   sphinx-exercise's `hide_solutions`, a second guard). The library holds the
   exercises' answers (its own implementation of each piece, and the references of
   `icm.exercises`), so the copy has no source pages (Sphinx's `viewcode` is left
   out: no "[source]" link), its API page leaves out the references and the
   hidden cases' generators of `icm.exercises` (`students_api`), and its
   instructors' page only points to the full edition (the marking guides describe
   the answers).
2. **Strips the solutions** from every notebook (`strip_solutions`): the cells tagged
   `solution` go, which are a solution's `solution-start` and `solution-end` cells and
   everything between them. It refuses a notebook where a solution is left untagged,
   or where a cell that stays uses a name defined, or a number glued, only in a
   solution (the students' notebook would then fail, or differ from the book).
3. **Reuses the book's execution** when it can: a notebook whose full version is in
   the book's execution cache (`<path-output>/_build/.jupyter_cache`, written by
   `make book`) is not executed again; its executed copy, without the solution cells
   and their outputs, goes into the students' cache. That is the students' notebook
   executed, since (step 2) no cell that stays depends on a solution. The others are
   executed afresh.
4. **Builds** the copy with its own `book/_ext/build_book.py` (the same steps as the
   book: execution, then Jupyter Book); the HTML is in
   `<path-output>/_build/students/_build/html`, and the notebooks students download
   from it (`_sources/`) hold the placeholders.

Exit status: that of the build, 1 when a notebook's solutions cannot be stripped.
"""

import argparse
import ast
import os
import pathlib
import re
import shutil
import sys

import nbformat
import yaml

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
SOLUTION_TAG = "solution"
LINKED = ("icm", "assets", "requirements.txt", "pyproject.toml")
COPIED = ("_config.yml", "_toc.yml", "book")
GLUED = re.compile(r"\{glue(?::\w+)?\}`([A-Za-z0-9_]+)")
GLUE_CALL = re.compile(r"""glue\(\s*f?["']([A-Za-z0-9_]*)(\{)?""")
NO_STUDENTS_EXTENSIONS = ("sphinx.ext.viewcode",)
"""Extensions the students' edition goes without (viewcode shows the library's code)."""
STUDENTS_INSTRUCTORS_PAGE = """# For instructors

This is the students' edition of the book. The instructors' page (grading, course plans,
marking guides) is in the book's full edition.
"""
"""The instructors' page of the students' edition: its marking guides say what the
extend exercises' answers hold."""
ANSWERS = ("reference_", "hidden_")
"""Prefixes of the functions of `icm.exercises` that the students' API page leaves out:
the references (the answers) and the generators of the hidden cases."""


class StripError(ValueError):
    """A notebook whose solutions cannot be taken out safely."""


def _tags(cell):
    return cell.get("metadata", {}).get("tags", [])


def _is_solution(cell):
    return SOLUTION_TAG in _tags(cell)


def _names_defined(source):
    """Names a code cell binds (assignments, defs, classes, imports, for targets)."""
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return set()
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            names.update((a.asname or a.name).split(".")[0] for a in node.names)
    return names


def _names_used(source):
    """Names a code cell reads."""
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return set()
    return {node.id for node in ast.walk(tree)
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)}


def _glue_keys(source):
    """The glue keys a code cell writes: exact keys, and prefixes of f-string keys
    (as "prefix*")."""
    return {key + ("*" if brace else "") for key, brace in GLUE_CALL.findall(source)}


def _glued_by(keys, key):
    return key in keys or any(k.endswith("*") and key.startswith(k[:-1]) for k in keys)


def strip_solutions(notebook, name="notebook"):
    """The notebook without its solutions (a new notebook; the argument is unchanged).

    Removes every cell tagged `solution`, and checks what remains:

    - no `{solution` directive is left in a cell that is not tagged;
    - a tagged run of cells starts with a `solution-start` and ends with a
      `solution-end` (no half solution is left);
    - no cell that stays reads a name that only a solution defined before it (the
      placeholder of an implement exercise defines its function too), nor quotes a
      number that only a solution glued.

    Raises:
      StripError: naming the notebook and the cell, when one of these fails.
    """
    cells = notebook.cells
    kept = []
    defined_by_solution, defined_elsewhere = set(), set()
    glued_by_solution, glued_elsewhere = set(), set()
    inside = False
    for index, cell in enumerate(cells):
        where = f"{name}, cell {index}"
        if _is_solution(cell):
            source = cell.source
            if cell.cell_type == "markdown" and "{solution-start}" in source:
                if inside:
                    raise StripError(f"{where}: a solution starts inside another")
                inside = True
            elif not inside:
                raise StripError(f"{where}: a cell tagged {SOLUTION_TAG!r} outside a "
                                 f"solution-start ... solution-end block")
            if cell.cell_type == "code":
                defined = _names_defined(source)
                defined_by_solution |= defined
                defined_elsewhere -= defined
                glued_by_solution |= _glue_keys(source)
            if cell.cell_type == "markdown" and "{solution-end}" in source:
                inside = False
            continue
        if inside:
            raise StripError(f"{where}: an untagged cell inside a solution (tag every "
                             f"cell from solution-start to solution-end {SOLUTION_TAG!r})")
        if "{solution" in cell.source:
            raise StripError(f"{where}: a solution directive in a cell not tagged "
                             f"{SOLUTION_TAG!r}")
        if cell.cell_type == "code":
            defined = _names_defined(cell.source)
            # (A name the cell binds itself counts as bound before it is read.)
            used = _names_used(cell.source) - defined_elsewhere - defined
            leaked = sorted(used & defined_by_solution)
            if leaked:
                raise StripError(f"{where} uses {', '.join(leaked)}, defined only in a "
                                 f"solution before it")
            defined_elsewhere |= defined
            defined_by_solution -= defined
            glued_elsewhere |= _glue_keys(cell.source)
        else:
            for key in GLUED.findall(cell.source):
                if _glued_by(glued_by_solution, key) and not _glued_by(glued_elsewhere, key):
                    raise StripError(f"{where} quotes the glued number {key!r}, glued "
                                     f"only in a solution")
        kept.append(cell)
    if inside:
        raise StripError(f"{name}: a solution-start without its solution-end")
    stripped = nbformat.from_dict(notebook)
    stripped.cells = [nbformat.from_dict(c) for c in kept]
    return stripped


def students_api(text):
    """The API page of the students' edition: every `icm.exercises` module documented
    with its members but the references and the hidden cases' generators (`ANSWERS`).

    Args:
      text: the book's API page (book/api.md).

    Returns:
      The students' page.
    """
    import importlib

    lines = text.splitlines()
    out = []
    for i, line in enumerate(lines):
        out.append(line)
        module = re.match(r"\.\. automodule:: (icm\.exercises\.\w+)\s*$", line)
        if module and i + 1 < len(lines) and lines[i + 1].strip() == ":members:":
            imported = importlib.import_module(module.group(1))
            names = sorted(name for name, value in vars(imported).items()
                           if name.startswith(ANSWERS) and callable(value)
                           and getattr(value, "__module__", None) == imported.__name__)
            if names:
                out.append(f"   :exclude-members: {', '.join(names)}")
    return "\n".join(out) + "\n"


def solutions_of(notebook):
    """The cells of a notebook's solutions (tagged `solution`), as a list of sources."""
    return [cell.source for cell in notebook.cells if _is_solution(cell)]


def _notebooks(book):
    return sorted(book.glob("*.ipynb"))


COMMAND = "book/_ext/student_edition.py"
"""The name in the marker of the folder this command fills (`icm.files`): it empties
only a folder that has it."""


def prepare(source, root=ROOT, force=False):
    """Copies the book into `source` and strips its notebooks; returns the stripped
    notebooks' paths. Raises StripError for a notebook that cannot be stripped, and
    files.DestinationError for a `source` this command did not write (not empty and
    without its marker; with `force`, its files are kept and ours written over them)."""
    from icm import files

    files.check_folder(source, force=force, inputs=[root / "book"], command=COMMAND,
                       what="the students' edition's sources")
    files.fresh_folder(source, command=COMMAND)
    for name in COPIED:
        path = root / name
        if path.is_dir():
            shutil.copytree(path, source / name, ignore=shutil.ignore_patterns(
                ".ipynb_checkpoints", "__pycache__"))
        else:
            shutil.copy2(path, source / name)
    for name in LINKED:
        os.symlink(root / name, source / name)
    config_path = source / "_config.yml"
    config = yaml.safe_load(config_path.read_text())
    config["title"] = config["title"] + " (students' edition)"
    config.setdefault("sphinx", {}).setdefault("config", {})["hide_solutions"] = True
    config["sphinx"]["extra_extensions"] = [
        extension for extension in config["sphinx"].get("extra_extensions", [])
        if extension not in NO_STUDENTS_EXTENSIONS]
    config_path.write_text("# The students' edition: written by book/_ext/student_edition.py\n"
                           + yaml.safe_dump(config, sort_keys=False))
    api = source / "book" / "api.md"
    if api.exists():
        api.write_text(students_api(api.read_text()))
    instructors = source / "book" / "instructors.md"
    if instructors.exists():  # its marking guides describe the extend exercises' answers
        instructors.write_text(STUDENTS_INSTRUCTORS_PAGE)
    stripped = []
    for path in _notebooks(source / "book"):
        notebook = nbformat.read(path, as_version=4)
        nbformat.write(strip_solutions(notebook, path.name), path)
        stripped.append(path)
    for path in (source / "book").glob("*.md"):
        if "{solution" in path.read_text():
            raise StripError(f"{path.name}: a solution in a page that is not a notebook")
    return stripped


def reuse_execution(stripped, book_cache, student_output):
    """Puts into the students' execution cache, for every stripped notebook whose full
    version the book's cache holds, that executed notebook without its solution
    cells. Returns the names of the notebooks reused."""
    if not book_cache.is_dir():
        return []
    from jupyter_cache import get_cache

    sys.path.insert(0, str(HERE))
    import execute_book

    cache = get_cache(str(book_cache))
    fingerprint_path = book_cache / execute_book.FINGERPRINT_FILE
    fingerprint = execute_book.library_fingerprint()
    if not fingerprint_path.exists() or fingerprint_path.read_text().strip() != fingerprint:
        return []  # the book's outputs are from another version of the library
    students = execute_book.ExecutionCache(
        student_output / "_build" / ".jupyter_cache", fingerprint, force=False)
    reused = []
    for path in stripped:
        full = nbformat.read(ROOT / "book" / path.name, as_version=4)
        try:
            record = cache.match_cache_notebook(full)
            executed = cache.get_cache_bundle(record.pk).nb
        except Exception:  # not cached, or unreadable: execute it afresh
            continue
        # (The cache keeps the code cells only: the structure was checked on the
        # source, in `prepare`; here the solutions' cells and outputs just go.)
        executed = nbformat.from_dict(executed)
        executed.cells = [c for c in executed.cells if not _is_solution(c)]
        students.store(path, executed, 0.0)
        reused.append(path.name)
    return reused


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--path-output", type=pathlib.Path, default=ROOT,
                        help="the book's output folder (default: the project); the "
                             "students' edition goes into its _build/students")
    parser.add_argument("--strict", action="store_true",
                        help="every Sphinx warning is an error, as in the tests")
    parser.add_argument("--keep-going", action="store_true",
                        help="after a notebook fails, execute the others anyway")
    parser.add_argument("--force", action="store_true",
                        help="write the sources into a _build/students/source that this "
                             "command did not write (its files are kept)")
    args = parser.parse_args(argv)
    output = args.path_output.resolve()
    students = output / "_build" / "students"
    source = students / "source"
    from icm import files

    try:
        stripped = prepare(source, force=args.force)
    except (StripError, files.DestinationError) as error:
        print(f"student_edition: {error}", file=sys.stderr)
        return 1
    print(f"students' edition: {len(stripped)} notebooks without their solutions in {source}")
    reused = reuse_execution(stripped, output / "_build" / ".jupyter_cache", students)
    if reused:
        print(f"students' edition: the book's execution reused for {len(reused)} notebooks")
    command = [sys.executable, str(source / "book" / "_ext" / "build_book.py"),
               "--path-output", str(students)]
    command += ["--strict"] * args.strict + ["--keep-going"] * args.keep_going
    import subprocess

    status = subprocess.call(command, cwd=source)
    if status == 0:
        print(f"Open the students' edition: {students / '_build' / 'html' / 'index.html'}")
    return status


if __name__ == "__main__":
    sys.exit(main())
