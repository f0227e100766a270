"""How soon each page of the built book is interactive in headless Chromium (`make
bench` prints it; also `python benchmarks/page_load.py [HTML_DIR]`).

Each page of `_build/html` is opened from disk, offline, at laptop width (1366 px),
each time in a new browser context (nothing cached), `repeats` times. A page counts as
interactive once its load event has run and its static panels are drawn (the live
views load on request and do not count). The figure is the best of the repeats, as
the machine may be busy with other work; a blank page opened the same way in the same
run is the reference, so that the ratio says how much of the time is the page's own.
The budget is the course issue's: every page interactive within `BUDGET_MS`.

This is a benchmark, not a test: the time depends on the machine's load. The tests
check only that every page becomes interactive (tests/test_browser.py).
"""

import pathlib
import shutil
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[1]
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
BUDGET_MS = 2000
"""Every chapter interactive within 2 s of being opened, on this machine."""

PANELS_DRAWN = """() => document.querySelectorAll('.icm-static-panel').length ==
    Object.keys(window.icmPanels || {}).length"""
"""True once every static panel of the page is drawn (icm.figures.static_panels); the
browser tests wait on it too."""
READY = """() => {
  const navigation = performance.getEntriesByType("navigation")[0];
  return Math.max(navigation.loadEventEnd, ...(window.icmPanelTimes || [0]));
}"""


def _toc_pages(html_dir):
    import yaml

    toc = yaml.safe_load((ROOT / "_toc.yml").read_text())
    chapters = list(toc.get("chapters", []))
    for part in toc.get("parts", []):
        chapters += part["chapters"]
    names = [toc["root"]] + [chapter["file"] for chapter in chapters]
    return {name.split("/")[-1]: pathlib.Path(html_dir) / f"{name}.html" for name in names}


def measure(html_dir=ROOT / "_build" / "html", repeats=3, pages=None):
    """{page: best milliseconds to interactive} for the pages of the book in
    `html_dir` (`pages`: some of their names, such as "preface"; every page by
    default), with the blank reference page under "(blank page)"; None where Chromium
    or Playwright is missing or the book is not built."""
    if repeats < 1:
        raise ValueError(f"repeats must be at least 1, got {repeats!r}")
    every = _toc_pages(html_dir)
    if pages is None:
        paths = every
    elif pages and all(name in every for name in pages):
        paths = {name: every[name] for name in pages}
    else:
        raise ValueError(f"pages must be names of the book's pages ({', '.join(every)}), "
                         f"got {pages!r}")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    if chromium is None or not all(path.exists() for path in paths.values()):
        return None
    times = {}
    with tempfile.TemporaryDirectory() as folder, sync_playwright() as playwright:
        blank = pathlib.Path(folder) / "blank.html"
        blank.write_text("<!DOCTYPE html><html><head><title>blank</title></head>"
                         "<body><p>blank</p></body></html>")
        browser = playwright.chromium.launch(executable_path=chromium, args=FLAGS)
        for name, path in {"(blank page)": blank, **paths}.items():
            best = float("inf")
            for _ in range(repeats):
                context = browser.new_context(offline=True,
                                              viewport={"width": 1366, "height": 800})
                page = context.new_page()
                page.goto(path.as_uri(), wait_until="load")
                page.wait_for_function(PANELS_DRAWN, timeout=60000)
                best = min(best, page.evaluate(READY))
                context.close()
            times[name] = best
        browser.close()
    return times


def report(times):
    """The figures as lines of text."""
    if times is None:
        return ["  skipped: Chromium (apt-get install chromium) or Playwright is missing, "
                "or the book is not built (make book)"]
    reference = max(times["(blank page)"], 1.0)
    lines = [f"  blank page (the reference): {times['(blank page)']:.0f} ms"]
    for name, ms in times.items():
        if name != "(blank page)":
            verdict = "ok" if ms <= BUDGET_MS else "MISSED"
            lines.append(f"  {name}: {ms:.0f} ms, {ms / reference:.1f} x the blank page, "
                         f"budget {BUDGET_MS} ms {verdict}")
    return lines


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    html = sys.argv[1] if len(sys.argv) > 1 else ROOT / "_build" / "html"
    print("Pages interactive in headless Chromium, offline, best of 3 (ms):")
    print("\n".join(report(measure(html))))
