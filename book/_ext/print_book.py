"""Prints the built HTML book to one PDF, offline, with headless Chromium.

    python book/_ext/print_book.py [--html _build/html] [--out _build/pdf/book.pdf]

`make pdf` runs it after `make book`. Jupyter Book's own `pdfhtml` builder downloads a
browser of its own (pyppeteer), which fails offline; its `pdflatex` builder needs a
TeX installation of several hundred MB. This uses what the browser test already
needs: Debian's `chromium` and Playwright (requirements.txt), and pypdf to join the
pages:

1. each page of the table of contents but the API reference (its hundreds of
   signatures are for the screen; the PDF says where to find them) is opened offline,
   with the network refused, and waited for until its formulas are typeset and its
   static panels drawn;
2. it is printed with the book's print styles (`book/_static/icm.css`,
   `@media print`): no navigation or buttons, every figure whole. Interactive
   elements become their static figures with a note: a static panel prints at its
   default settings, the sliders replaced by a line saying so; a live iCub view
   prints its still; an animation its first frame;
3. the pages are joined in table-of-contents order, each chapter a bookmark of the
   PDF, its pages footed with the chapter's title and page numbers.

Exit status: 0 when the PDF was written; 2 when --out is refused (a file this command
did not print, a folder, a link, inside the built book); 1 (with the reason) when the built book or
Chromium is missing, or a page failed to load or reached for the network.
"""

import argparse
import io
import pathlib
import shutil
import sys

import yaml

from icm import files

ROOT = pathlib.Path(__file__).resolve().parents[2]
LEFT_OUT = ("book/api",)
"""Pages the PDF leaves out (the API reference: see the docstring)."""
FOOTER = """<div style="font-size: 8px; width: 100%; margin: 0 12mm; color: #444;
  display: flex; justify-content: space-between; font-family: sans-serif;">
  <span>{title}</span><span><span class="pageNumber"></span> / <span class="totalPages"></span></span>
</div>"""
READY = """() => {
  const panels = document.querySelectorAll('.icm-static-panel').length;
  const drawn = Object.keys(window.icmPanels || {}).length;
  const math = !window.MathJax || !window.MathJax.startup ||
               !window.MathJax.startup.promise ? true : window.icmMathDone === true;
  return panels === drawn && math;
}"""


def pages(html):
    """(name, path) of the pages to print, in table-of-contents order."""
    from icm._book import toc_pages  # here: the build's own scripts import no more of icm

    names = toc_pages(ROOT)
    return [(name, html / f"{name}.html") for name in names if name not in LEFT_OUT]


def find_chromium():
    return shutil.which("chromium") or shutil.which("chromium-browser")


def print_book(html, out, chromium=None):
    """Prints the book built in `html` to the PDF `out`; returns its page count.

    Raises:
      FileNotFoundError: the built book or Chromium is missing.
      RuntimeError: a page logged an error or reached for the network.
    """
    from playwright.sync_api import sync_playwright
    from pypdf import PdfReader, PdfWriter

    html = pathlib.Path(html).resolve()
    listed = pages(html)
    missing = [str(path) for _, path in listed if not path.exists()]
    if missing:
        raise FileNotFoundError(f"no built book at {html} (missing {missing[0]}): run "
                                f"`make book` first")
    chromium = chromium or find_chromium()
    if chromium is None:
        raise FileNotFoundError("Chromium is missing (Debian: apt-get install chromium)")
    writer = PdfWriter()
    requests, errors = [], []
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium, args=[
            "--no-sandbox", "--disable-gpu", "--no-first-run",
            "--disable-background-networking", "--disable-component-update"])
        context = browser.new_context(offline=True)
        context.route("**/*", lambda route: route.continue_()
                      if route.request.url.startswith(("file:", "data:"))
                      else (requests.append(route.request.url), route.abort()))
        for name, path in listed:
            page = context.new_page()
            page.on("pageerror", lambda error, name=name: errors.append(f"{name}: {error}"))
            page.goto(path.as_uri(), wait_until="load")
            page.evaluate("""() => { if (window.MathJax && MathJax.startup && MathJax.startup.promise)
                MathJax.startup.promise.then(() => { window.icmMathDone = true; }); }""")
            page.wait_for_function(READY, timeout=60000)
            title = page.evaluate("document.querySelector('.bd-article h1') ? "
                                  "document.querySelector('.bd-article h1').textContent"
                                  ".replace(/[#¶]/g, '').trim() : document.title")
            pdf = page.pdf(format="A4", print_background=True, display_header_footer=True,
                           header_template="<span></span>",
                           footer_template=FOOTER.format(title=_escape(title)),
                           margin={"top": "14mm", "bottom": "16mm", "left": "12mm",
                                   "right": "12mm"})
            start = len(writer.pages)
            writer.append(PdfReader(io.BytesIO(pdf)))
            writer.add_outline_item(title=title, page_number=start)
            page.close()
        browser.close()
    if requests or errors:
        raise RuntimeError(f"printing the book: network requests {requests[:3]}, "
                           f"errors {errors[:3]}")
    writer.add_metadata({"/Title": _book_title(), "/Author": _book_author(),
                         PRINTED_BY: PRINTED_BY_VALUE})
    data = io.BytesIO()
    writer.write(data)
    files.write_bytes(out, data.getvalue())  # whole or not at all
    return len(writer.pages)


PRINTED_BY, PRINTED_BY_VALUE = "/ICMPrintedBy", "book/_ext/print_book.py"
"""The PDF's own mark (in its metadata): a file that has it is one this command wrote,
which it may replace; any other file at --out is refused unless --force."""


def printed_here(path):
    """Whether the file at `path` is a PDF this command printed (`PRINTED_BY`)."""
    from pypdf import PdfReader
    from pypdf.errors import PyPdfError

    with open(path, "rb") as handle:
        if handle.read(5) != b"%PDF-":
            return False
    try:
        metadata = PdfReader(path).metadata or {}
    except PyPdfError:  # a damaged PDF, or one that only starts like a PDF
        return False
    return metadata.get(PRINTED_BY) == PRINTED_BY_VALUE


def check_out(out, html, force=False):
    """Refuses, before any page is printed, an --out this command must not write: not
    ending in .pdf, a symbolic link or a folder, inside the built book (an input), or
    an existing file it did not print (unless `force`). Raises files.DestinationError."""
    out = pathlib.Path(out)
    if out.suffix.lower() != ".pdf":
        raise files.DestinationError(f"--out must end in .pdf, got {out}")
    return files.check_file(out, own=printed_here, force=force, inputs=[html],
                            what="--out")


def _escape(text):
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _config():
    return yaml.safe_load((ROOT / "_config.yml").read_text())


def _book_title():
    return _config()["title"]


def _book_author():
    return _config()["author"]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--html", type=pathlib.Path, default=ROOT / "_build" / "html",
                        help="the built HTML book (default: _build/html)")
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "_build" / "pdf" / "book.pdf",
                        help="where the PDF goes (default: _build/pdf/book.pdf); a file "
                             "there that this command did not print is refused")
    parser.add_argument("--force", action="store_true",
                        help="replace a file at --out that this command did not print")
    args = parser.parse_args(argv)
    try:
        check_out(args.out, args.html, args.force)
    except files.DestinationError as error:
        print(f"print_book: {error}", file=sys.stderr)
        return 2
    try:
        count = print_book(args.html, args.out)
    except (FileNotFoundError, RuntimeError) as error:
        print(f"print_book: {error}", file=sys.stderr)
        return 1
    print(f"The PDF: {args.out.resolve()} ({count} pages)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
