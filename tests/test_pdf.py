"""The book as a PDF (`make pdf`, book/_ext/print_book.py): printed offline by headless
Chromium from the book the tests build, with every chapter, every figure and text
that can be extracted."""

import html as html_module
import importlib.util
import re
import shutil

import pytest

from conftest import ROOT, toc_files

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
PRINT_BOOK = ROOT / "book" / "_ext" / "print_book.py"


def _module():
    spec = importlib.util.spec_from_file_location("print_book", PRINT_BOOK)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


print_book = _module()


def test_without_a_built_book_it_says_what_to_do(tmp_path, capsys):
    assert print_book.main(["--html", str(tmp_path / "nothing"), "--out",
                            str(tmp_path / "book.pdf")]) == 1
    assert "run `make book` first" in capsys.readouterr().err
    assert not (tmp_path / "book.pdf").exists()


@pytest.mark.parametrize("make_out, words", [
    (lambda d: d / "notes.ipynb", "must end in .pdf"),
    (lambda d: d / "html" / "book.pdf", "inside the input"),
    (lambda d: (d / "theirs.pdf").write_bytes(b"%PDF-1.4 a student's") and d / "theirs.pdf",
     "exists and was not written by this command"),
    (lambda d: (d / "folder.pdf").mkdir() or d / "folder.pdf", "is a folder"),
    (lambda d: (d / "link.pdf").symlink_to(d / "html" / "index.html") or d / "link.pdf",
     "symbolic link"),
])
def test_an_out_it_must_not_write_is_refused_before_printing(tmp_path, capsys, make_out,
                                                              words):
    (tmp_path / "html").mkdir()
    (tmp_path / "html" / "index.html").write_text("the built book")
    out = make_out(tmp_path)
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    assert print_book.main(["--html", str(tmp_path / "html"), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err, err
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before


def test_a_pdf_it_printed_is_replaced_and_another_only_with_force(tmp_path):
    from pypdf import PdfWriter

    ours, theirs = tmp_path / "ours.pdf", tmp_path / "theirs.pdf"
    for path, mark in [(ours, {print_book.PRINTED_BY: print_book.PRINTED_BY_VALUE}),
                       (theirs, {"/Title": "Lecture notes"})]:
        writer = PdfWriter()
        writer.add_blank_page(100, 100)
        writer.add_metadata(mark)
        with open(path, "wb") as handle:
            writer.write(handle)
    assert print_book.check_out(ours, tmp_path / "html") == ours
    with pytest.raises(print_book.files.DestinationError, match="--force"):
        print_book.check_out(theirs, tmp_path / "html")
    assert print_book.check_out(theirs, tmp_path / "html", force=True) == theirs


def test_make_pdf_prints_the_built_book():
    makefile = (ROOT / "Makefile").read_text()
    assert re.search(r"^pdf: book\b", makefile, re.MULTILINE)
    assert "book/_ext/print_book.py --html _build/html --out _build/pdf/book.pdf" in makefile


@pytest.fixture(scope="module")
def book_pdf(built_book, tmp_path_factory):
    if CHROMIUM is None:
        pytest.skip("Chromium is not installed (Debian: apt-get install chromium)")
    out = tmp_path_factory.mktemp("pdf") / "book.pdf"
    pages = print_book.print_book(built_book, out, CHROMIUM)
    assert print_book.printed_here(out)  # marked as this command's, so it may replace it
    return out, pages


def _titles(built_book):
    """Each printed page's title (its first heading), in order."""
    titles = {}
    for name in toc_files():
        if name in print_book.LEFT_OUT:
            continue
        page = (built_book / f"{name}.html").read_text()
        heading = next(h for h in re.findall(r"<h1>(.*?)</h1>", page, re.DOTALL)
                       if 'class="headerlink"' in h)
        heading = re.sub(r'<a class="headerlink".*', "", heading, flags=re.DOTALL)
        titles[name] = _normal(html_module.unescape(re.sub(r"<[^>]+>", "", heading)))
    return titles


def _images(obj, path=()):
    """The images a PDF page (or a form in it) draws, counted in its resources, forms
    included. Our own count, not pypdf's `page.images`: that parses every page's
    content stream to find inline images too, 7 of the test's 17 s on the book's 218
    pages. Chromium places every image of a page as an image object (on the book's
    PDF, page for page the count of `page.images`, 52 in all); inline images would go
    uncounted here, which can only fail the check."""
    from pypdf.generic import DictionaryObject, StreamObject

    resources = obj.get("/Resources")
    resources = resources.get_object() if resources is not None else None
    if not isinstance(resources, DictionaryObject) or "/XObject" not in resources:
        return 0
    xobjects = resources["/XObject"].get_object()
    count = 0
    for name in xobjects:
        entry = xobjects[name].get_object()
        if not isinstance(entry, StreamObject) or name in path:  # (a form in itself)
            continue
        count += 1 if entry.get("/Subtype") == "/Image" else _images(entry, path + (name,))
    return count


def _normal(text):
    return re.sub(r"\s+", " ", text).strip()


@pytest.mark.book
def test_the_pdf_holds_every_chapter_figure_and_its_text(book_pdf, built_book, capsys):
    from pypdf import PdfReader

    path, pages = book_pdf
    reader = PdfReader(path)
    assert len(reader.pages) == pages
    text = _normal(" ".join(page.extract_text() for page in reader.pages))
    titles = _titles(built_book)
    # Every chapter, in order, a bookmark each; its title in the text.
    assert [item.title for item in reader.outline] == list(titles.values())
    for title in titles.values():
        assert _normal(title) in text, title
    # Every figure: the PNGs and JPEGs of the pages as images of the PDF, and the
    # static panels (drawn as vectors) by their printed notes.
    figures = sum(len(re.findall(r'<img [^>]*src="\.\./_images/', (built_book / f"{n}.html")
                                 .read_text())) for n in titles)
    images = sum(_images(page) for page in reader.pages)
    assert figures >= 30 and images >= figures, (images, figures)
    notes = sum((built_book / f"{n}.html").read_text().count('class="icm-print-note"')
                for n in titles)
    assert notes >= 4 and text.count("Printed at its default settings") == notes
    # Text a reader can search and copy: the chapters' words.
    assert len(text.split()) > 8000
    assert "interest" in text and "Q-learning" in text
    # A book, not a poster: about as many pages as the chapters need.
    assert 8 * len(titles) <= len(reader.pages) <= 40 * len(titles), len(reader.pages)
    with capsys.disabled():
        print(f"\nthe PDF: {len(reader.pages)} pages, {images} images, "
              f"{path.stat().st_size / 1e6:.1f} MB")

