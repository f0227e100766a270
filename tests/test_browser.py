"""The built book in a real browser, offline: headless Chromium (Debian's `chromium`
package) driven by Playwright, with every network request refused.

One Chromium serves the module's tests (`chromium`), through Playwright's async API so
that several pages are worked at once; each page of the book is opened once at laptop
width and once at phone width (`book_visits`), and every check that reads a page at
laptop width reads it from that one visit. (The page-load benchmark, run beside the
visits, drives a Chromium of its own, as `make bench` runs it.)

Skipped, with the reason shown, where Chromium or Playwright is missing; `.ci/run`
installs Chromium before `make test`.
"""

import asyncio
import importlib.util
import json
import pathlib
import re
import shutil
import urllib.parse

import pytest

from conftest import ROOT, toc_files

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
playwright_api = pytest.importorskip("playwright.async_api",
                                     reason="Playwright is not installed (pip)")
pytestmark = [
    pytest.mark.book,
    pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed "
                       "(Debian: apt-get install chromium); the offline browser check "
                       "of the book is skipped"),
]
SLIDER_VIEWS = {"IntSliderView", "FloatSliderView"}


def expected_sliders(html):
    """Sliders in the widget state saved in a page (the panels' controls)."""
    match = re.search(r'<script type="application/vnd.jupyter.widget-state\+json">(.*?)</script>',
                      html, re.DOTALL)
    if not match:
        return 0
    state = json.loads(match.group(1))["state"]
    return sum(1 for model in state.values() if model["state"].get("_view_name") in SLIDER_VIEWS)


LAUNCH_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
               "--disable-background-networking", "--disable-component-update",
               "--disable-sync"]
AXE = ROOT / "book" / "_static" / "vendor" / "axe" / "axe.min.js"
"""axe-core, vendored from npm (book/_static/vendor/README.md); injected by the test."""
WIDTHS = {"laptop": 1366, "phone": 390}
PAGES_AT_ONCE = 2
"""Pages the visits work at the same time, each in a browser context (and renderer
process) of its own; the page-load benchmark opens one more beside them. On this
2-core machine, under other work (load average 9), all the visits took 79 and 83 s
two at a time, 79 and 104 s three at a time: more only share the same cores."""


class Chromium:
    """The module's one headless Chromium, driven through Playwright's async API on an
    event loop of the module's own: `run(coroutine)` runs a test's coroutine on it,
    which may work several pages at once."""

    def __init__(self, loop, browser):
        self.loop, self.browser = loop, browser

    def run(self, coroutine):
        return self.loop.run_until_complete(coroutine)


@pytest.fixture(scope="module")
def chromium():
    loop = asyncio.new_event_loop()
    playwright = loop.run_until_complete(playwright_api.async_playwright().start())
    try:
        browser = loop.run_until_complete(
            playwright.chromium.launch(executable_path=CHROMIUM, args=LAUNCH_ARGS))
        yield Chromium(loop, browser)
        loop.run_until_complete(browser.close())
    finally:
        loop.run_until_complete(playwright.stop())
        loop.close()


async def _offline_context(browser, width, files):
    """A browser context of `width` px that refuses the network and records every file
    a page loads in `files`."""
    context = await browser.new_context(offline=True, viewport={"width": width, "height": 800})
    requests = []

    async def refuse_network(route):
        url = route.request.url
        if url.startswith("file:"):
            files.append(url)
            await route.continue_()
        elif url.startswith("data:"):
            await route.continue_()
        else:
            requests.append(url)
            await route.abort()

    await context.route("**/*", refuse_network)
    return context, requests


def _file_of(url):
    return pathlib.Path(urllib.parse.unquote(urllib.parse.urlparse(url).path))


class _Visit:
    """A page of the book opened offline in a context of its own, laid out (loaded,
    its panels drawn, its formulas typeset, its fonts in); records every console
    message and page error with the phase of the visit it came in (`phase`)."""

    def __init__(self):
        self.phase, self.messages, self.files = "open", [], []

    async def open(self, browser, path, width):
        self.context, self.requests = await _offline_context(browser, width, self.files)
        self.page = page = await self.context.new_page()
        page.on("console", lambda message: self.messages.append(
            (self.phase, message.type, message.text)))
        page.on("pageerror", lambda error: self.messages.append(
            (self.phase, "error", str(error))))
        await page.goto(path.as_uri(), wait_until="load")
        await page.wait_for_function(PANELS_DRAWN, timeout=30000)
        await page.evaluate(RENDERED)  # formulas typeset, fonts loaded: laid out
        return page

    def errors(self, phases=None, warnings=False):
        """The errors logged (in `phases`, or in any), and with `warnings` Vega's own
        warnings too ("WARN ...": a spec it had to correct)."""
        return [text for phase, kind, text in self.messages
                if (phases is None or phase in phases)
                and (kind == "error" or warnings and text.startswith("WARN"))]


async def _visit_at_laptop_width(browser, built_book, name, with_controls):
    """Everything the checks read of a page at laptop width, from one visit, in this
    order: the page as it opens (layout, images, files, formulas) and axe-core's
    findings on it; then, on the pages with controls, the walk with Tab
    (`_walk_with_tab`); then the questions answered (`_answer_quizzes`); then the
    static panels' sliders moved (`_move_panels`)."""
    path = built_book / f"{name}.html"
    html = path.read_text()
    visit = _Visit()
    page = await visit.open(browser, path, WIDTHS["laptop"])
    record = {
        # When it became interactive, by the page-load benchmark's measure (its load
        # event run, its static panels drawn: `visit.open` waited for both).
        "interactive_ms": await page.evaluate(page_load.READY),
        "overflowing": await page.evaluate(OVERFLOWING),
        "page_width": await page.evaluate(
            "document.documentElement.scrollWidth - window.innerWidth"),
        "images": await page.eval_on_selector_all(
            "img", "els => els.map(e => [e.naturalWidth, "
                   "e.getAttribute('src').slice(0, 80)])"),
        "figures": await page.evaluate(FIGURES),
        "panel_text": await page.evaluate(PANEL_TEXT),
        # Vega names the panel's container after its description.
        "panel_labels": await page.eval_on_selector_all(
            ".icm-static-panel", "els => els.map(e => "
            "[e.getAttribute('role'), e.getAttribute('aria-label') || ''])"),
        "caption_px": await page.evaluate(CAPTION_PX),
        "sliders": await page.locator(".widget-slider").count(),
        "expected_sliders": expected_sliders(html),
        "math": await page.locator("mjx-container").count(),
        "files": sorted({str(_file_of(url)) for url in visit.files}),
        "code_scrolling": await page.evaluate(CODE_SCROLLING),
    }
    # axe-core after the book's own checks: it is not the book's, and it reads the page
    # as it is, before any control is worked.
    visit.phase = "axe"
    await page.add_script_tag(path=str(AXE))
    record["axe"] = await page.evaluate(AXE_RUN)
    questions = panels = None
    if with_controls:
        visit.phase = "keys"
        record["keys"] = await _walk_with_tab(page)
    if "icm-quiz-choices" in html:
        visit.phase = "quizzes"
        questions = await _answer_quizzes(page, name)
    if "icm-static-panel" in html:
        visit.phase = "panels"
        panels = await _move_panels(page, name)
    record["errors"] = visit.errors(phases=("open",))
    await visit.context.close()
    return {"record": record, "requests": visit.requests, "questions": questions,
            "panels": panels, "errors": visit.errors(),
            "errors_and_warnings": visit.errors(warnings=True)}


async def _visit_at_phone_width(browser, built_book, name):
    """What the checks read of a page at phone width: its layout as it opens."""
    visit = _Visit()
    page = await visit.open(browser, built_book / f"{name}.html", WIDTHS["phone"])
    record = {"overflowing": await page.evaluate(OVERFLOWING),
              "page_width": await page.evaluate(
                  "document.documentElement.scrollWidth - window.innerWidth"),
              "errors": visit.errors(phases=("open",))}
    await visit.context.close()
    return {"record": record, "requests": visit.requests}


async def _visit_book(browser, built_book):
    with_controls = set(_pages_with_controls(built_book))
    visits = [(name, device) for device in WIDTHS for name in toc_files()]
    # The visits at laptop width first (they do the most), the largest pages first
    # (axe-core's time grows with a page's elements: on the API page it takes half a
    # minute), so that no long visit is left to run alone at the end.
    visits.sort(key=lambda visit: (visit[1] != "laptop",
                                   -(built_book / f"{visit[0]}.html").stat().st_size))
    at_once = asyncio.Semaphore(PAGES_AT_ONCE)

    async def visit(name, device):
        async with at_once:
            if device == "laptop":
                return await _visit_at_laptop_width(browser, built_book, name,
                                                    name in with_controls)
            return await _visit_at_phone_width(browser, built_book, name)

    async def run_the_benchmark():
        # The benchmark drives its own Chromium with Playwright's sync API, which must
        # not run on this event loop: it runs in a thread, beside the visits.
        try:
            return await asyncio.to_thread(page_load.measure, built_book, repeats=1,
                                           pages=BENCHMARKED_PAGES)
        except Exception as error:  # for its test to raise
            return error

    benchmark, *found = await asyncio.gather(
        run_the_benchmark(), *(visit(name, device) for name, device in visits))
    return dict(zip(visits, found)), benchmark


@pytest.fixture(scope="module")
def book_visits(built_book, chromium):
    """Opens every page of the book offline, at laptop and phone width, several at a
    time; returns what the browser saw per page and device ("pages"; at laptop width
    also what axe-core found and the walk with Tab), the questions answered
    ("quizzes") and the static panels moved ("panels"), each with the requests the
    visits made (all refused) and the errors logged; and what `make bench`'s page-load
    benchmark measured meanwhile in its own browser ("benchmark": its times on
    `BENCHMARKED_PAGES`, or the error it raised)."""
    found, benchmark = chromium.run(_visit_book(chromium.browser, built_book))
    seen, requests = {}, []
    quizzes = {"questions": [], "requests": [], "errors": {}}
    panels = {"panels": [], "requests": [], "errors": {}}
    for name in toc_files():
        for device in WIDTHS:
            visit = found[name, device]
            seen.setdefault(name, {})[device] = visit["record"]
            requests += visit["requests"]
        laptop = found[name, "laptop"]
        if laptop["questions"] is not None:
            quizzes["questions"] += laptop["questions"]
            quizzes["requests"] += laptop["requests"]
            quizzes["errors"][name] = laptop["errors"]
        if laptop["panels"] is not None:
            panels["panels"] += laptop["panels"]
            panels["requests"] += laptop["requests"]
            panels["errors"][name] = laptop["errors_and_warnings"]
    seen["__requests__"] = requests
    return {"pages": seen, "quizzes": quizzes, "panels": panels, "benchmark": benchmark}


@pytest.fixture(scope="module")
def browser_pages(book_visits):
    """What the browser saw of every page, per device (and, at laptop width, what
    axe-core found and the walk with Tab), with every request refused under
    "__requests__"."""
    return book_visits["pages"]


def _benchmark(name):
    """The module benchmarks/`name`.py (the benchmarks are scripts, not a package)."""
    spec = importlib.util.spec_from_file_location(name, ROOT / "benchmarks" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


page_load = _benchmark("page_load")
PANELS_DRAWN = page_load.PANELS_DRAWN  # the benchmark waits for the same moment
BENCHMARKED_PAGES = ("preface", "goal_oriented_interest")
"""The pages the page-load benchmark opens in the tests: one without static panels, and
the one with the most (two)."""

RENDERED = """async () => {
  // After the load event, MathJax typesets the formulas (MathJax 3 resolves
  // startup.promise once it has) and the web fonts may still arrive: both change the
  // layout the checks read. (No page saves widgets: a test checks it.)
  await document.fonts.ready;
  if (window.MathJax && window.MathJax.startup && window.MathJax.startup.promise) {
    await window.MathJax.startup.promise;
  }
}"""

AXE_RUN = """async () => {
  // Every rule of axe-core's WCAG 2.0, 2.1 and 2.2 A and AA sets and its best practices;
  // `preload: false`: axe does not fetch the style sheets again (file:// refuses it).
  const result = await axe.run(document, {preload: false, resultTypes: ["violations"]});
  return result.violations.map(v => ({id: v.id, impact: v.impact, help: v.help,
    nodes: v.nodes.map(n => n.target.join(" ") + " :: " + n.html.slice(0, 160))}));
}"""

FIGURES = """() => Array.from(document.querySelectorAll(".bd-article img")).map(img => ({
  src: img.getAttribute("src"), alt: img.getAttribute("alt") || "",
  natural: img.naturalWidth, shown: img.getBoundingClientRect().width,
  visible: img.getBoundingClientRect().width > 0}))"""

PANEL_TEXT = """() => Array.from(document.querySelectorAll(".icm-static-panel svg text"))
  .filter(t => t.textContent.trim() && t.getBoundingClientRect().width > 0)
  .map(t => [t.textContent.slice(0, 40), parseFloat(getComputedStyle(t).fontSize)])"""

CAPTION_PX = """() => {
  const caption = document.querySelector(".bd-article figcaption p, .bd-article figcaption");
  return caption ? parseFloat(getComputedStyle(caption).fontSize) : null;
}"""


OVERFLOWING = """() => {
  // Tables, figures and panels that reach past the page's text column. Output areas
  // and tables scroll sideways, so such an element is not lost, but a reader sees it
  // cut at the column's edge: nothing may be wider than the column.
  const article = document.querySelector(".bd-article");
  if (!article) { return []; }
  const style = getComputedStyle(article);
  const right = article.getBoundingClientRect().right - parseFloat(style.paddingRight) + 1;
  const out = [];
  for (const el of article.querySelectorAll("table, img, .icm-static-panel svg")) {
    const r = el.getBoundingClientRect();
    if (r.width > 0 && r.right > right)
      out.push(el.tagName + " " + Math.round(r.right - right) + " px too wide: " +
               (el.getAttribute("src") || el.textContent).slice(0, 60));
  }
  return out;
}"""


CODE_SCROLLING = """() => {
  // Code blocks (a cell's input or output, a code block of the text) that scroll
  // sideways: a reader sees their lines cut at the block's edge ("unless you chose
  // otherw"). Blocks in a closed fold are not shown, so not measured.
  const article = document.querySelector(".bd-article");
  if (!article) { return []; }
  const out = [];
  for (const pre of article.querySelectorAll("pre")) {
    const box = pre.getBoundingClientRect();
    if (box.width === 0 || box.height === 0) { continue; }
    // The block itself, or the box around it (a cell's output area), scrolls.
    const scrolling = [pre, pre.parentElement, pre.closest(".cell_output, .output")]
      .filter(e => e && e.scrollWidth > e.clientWidth + 1 &&
              ["auto", "scroll"].includes(getComputedStyle(e).overflowX));
    if (!scrolling.length) { continue; }
    const style = getComputedStyle(pre);
    const probe = document.createElement("span");  // the width of a character here
    probe.textContent = "0".repeat(100);
    pre.appendChild(probe);
    const character = probe.getBoundingClientRect().width / 100;
    probe.remove();
    const inner = pre.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight);
    const longest = pre.textContent.split("\\n").reduce((a, b) => (b.length > a.length ? b : a), "");
    out.push({kind: pre.closest(".cell_output, .output") ? "output"
                    : pre.closest(".cell_input, .cell") ? "input" : "code block",
              fits: Math.floor(inner / character), longest: longest.length,
              line: longest.slice(0, 100)});
  }
  return out;
}"""


def test_no_code_block_scrolls_sideways_at_laptop_width(browser_pages, note):
    # At 1366 px, every line of a code cell, of its output and of a code block in the
    # text fits its block (82 to 86 characters in the text column, fewer in a box).
    found = {name: browser_pages[name]["laptop"]["code_scrolling"] for name in toc_files()}
    found = {name: blocks for name, blocks in found.items() if blocks}
    if found:
        note(f"code blocks that scroll sideways at 1366 px: {sum(map(len, found.values()))}; "
             + "; ".join(f"{name.split('/')[-1]} {len(blocks)} (fit "
                         f"{'/'.join(map(str, sorted({b['fits'] for b in blocks})))} characters)"
                         for name, blocks in found.items()))
    assert found == {}, {name: [(b["kind"], b["longest"], b["fits"], b["line"][:60])
                                for b in blocks] for name, blocks in found.items()}


@pytest.mark.parametrize("device", WIDTHS)
def test_nothing_is_cut_off_at_laptop_or_phone_width(browser_pages, device):
    # At 390 px (a phone) as at 1366 px: no figure, panel or table reaches past the
    # column, and the page itself never scrolls sideways.
    for name in toc_files():
        seen = browser_pages[name][device]
        assert seen["overflowing"] == [], (name, device, seen["overflowing"])
        assert seen["page_width"] <= 0, (name, device, f"{seen['page_width']} px too wide")


@pytest.mark.parametrize("device", WIDTHS)
def test_every_page_loads_without_console_errors(browser_pages, device):
    for name in toc_files():
        errors = browser_pages[name][device]["errors"]
        assert errors == [], f"{name} ({device}): {errors}"


def test_no_page_needs_the_network(browser_pages):
    assert browser_pages["__requests__"] == []


def test_every_figure_image_loads(browser_pages):
    total = 0
    for name in toc_files():
        broken = [src for width, src in browser_pages[name]["laptop"]["images"] if width == 0]
        assert broken == [], f"{name}: images that did not load: {broken}"
        total += len(browser_pages[name]["laptop"]["images"])
    assert total >= 10


def test_no_page_has_a_dead_widget_slider(browser_pages):
    # The book's panels are static Vega-Lite figures in the HTML; an ipywidgets slider
    # there could be dragged but would never redraw anything.
    for name in toc_files():
        assert browser_pages[name]["laptop"]["expected_sliders"] == 0, name
        assert browser_pages[name]["laptop"]["sliders"] == 0, name


def test_formulas_are_typeset_offline(browser_pages):
    assert sum(browser_pages[name]["laptop"]["math"] for name in toc_files()) >= 1


# Every reader: axe-core's checks, alternative text, readable figures, light pages.

SERIOUS = ("serious", "critical")


def test_axe_finds_no_serious_or_critical_violation_on_any_page(browser_pages, note):
    serious, others = {}, {}
    for name in toc_files():
        for violation in browser_pages[name]["laptop"]["axe"]:
            bucket = serious if violation["impact"] in SERIOUS else others
            key = (violation["impact"], violation["id"])
            bucket.setdefault(key, []).append((name, len(violation["nodes"]),
                                               violation["nodes"][:2]))
    note("axe-core, the violations below serious, elements per page: " + "; ".join(
        f"{impact} {rule}: " + ", ".join(f"{page.split('/')[-1]} {n}" for page, n, _ in where)
        for (impact, rule), where in sorted(others.items())))  # the rest, for the record
    assert serious == {}, serious


def test_every_figure_has_alternative_text_in_words(browser_pages):
    figures = 0
    for name in toc_files():
        for image in browser_pages[name]["laptop"]["figures"]:
            alt = image["alt"]
            words = re.findall(r"[A-Za-z]{2,}", alt)
            assert len(words) >= 6, (name, image["src"][:60], alt)
            assert not re.search(r"\.(png|jpe?g|svg)\b|_images/|data:image", alt), (name, alt)
            figures += 1
        # A static panel says what it shows (its Vega-Lite description).
        for role, label in browser_pages[name]["laptop"]["panel_labels"]:
            assert role and len(re.findall(r"[A-Za-z]{2,}", label)) >= 12, (name, role, label)
            figures += 1
    assert figures >= 30


def _png_measures(built_book, page, src):
    """The measures an icm figure's PNG records (icm.figures._common.Figure.measures),
    or None for an image that is not a PNG of the book's figures."""
    from PIL import Image

    if not src.endswith(".png") or "_images/" not in src:
        return None
    path = (built_book / page).parent / src
    text = Image.open(path).text
    return {key: float(text[key]) for key in ("icm:smallest-text-px", "icm:legend-overlaps",
                                              "icm:text-overlaps", "icm:text-outside-box")
            } if text else {}


def test_no_text_in_a_figure_is_smaller_than_the_captions(browser_pages, built_book):
    # At 1366 px: a figure's PNG is shown scaled to the column; its smallest text, in
    # screen pixels there, must be at least the caption text's size; so must the text
    # of the static panels (SVG).
    captions = {browser_pages[n]["laptop"]["caption_px"] for n in toc_files()} - {None}
    assert len(captions) == 1, captions
    caption = captions.pop()
    smallest, measured = [], 0
    for name in toc_files():
        seen = browser_pages[name]["laptop"]
        for image in seen["figures"]:
            measures = _png_measures(built_book, f"{name}.html", image["src"])
            if measures is None:
                continue
            assert measures, (name, image["src"], "a PNG figure without its measures")
            shown = measures["icm:smallest-text-px"] * min(1.0, image["shown"] / image["natural"])
            smallest.append((round(shown, 2), name, image["src"][-20:]))
            measured += 1
        for text, size in seen["panel_text"]:
            smallest.append((size, name, f"panel text {text!r}"))
    assert measured >= 30
    too_small = [entry for entry in smallest if entry[0] < caption - 0.01]
    assert too_small == [], (caption, sorted(too_small)[:10])


def test_no_legend_covers_data_and_no_text_in_a_figure_overlaps_or_leaves_its_box(
        browser_pages, built_book):
    for name in toc_files():
        for image in browser_pages[name]["laptop"]["figures"]:
            measures = _png_measures(built_book, f"{name}.html", image["src"])
            if measures:
                assert measures["icm:legend-overlaps"] == 0, (name, image["alt"][:80])
                assert measures["icm:text-overlaps"] == 0, (name, image["alt"][:80])
                assert measures["icm:text-outside-box"] == 0, (name, image["alt"][:80])


PROGRESS = re.compile(r"\d+%\|[^|]*\|\s*\d+/\d+|\d+(\.\d+)?(it|[a-z]+)/s\]|"
                      r"(Float|Int)ProgressModel")
"""What a tqdm bar leaves in a page: "42%|████ | 21/50 [... 3.1seed/s]", or its widget."""


def test_no_progress_bar_is_baked_into_the_pages(built_book):
    for name in toc_files():
        html = (built_book / f"{name}.html").read_text()
        found = PROGRESS.search(html)
        assert found is None, (name, html[max(0, found.start() - 80):found.end() + 40])


PAGE_BUDGET_BYTES = 9_000_000
"""What a page may load when it opens (its HTML with the panels' data and the
animations' frames, scripts, styles, images and fonts); the live views' 4 MB load only
when the reader starts one."""
BASE_SCRIPT_BUDGET_BYTES = 1_750_000
"""The scripts every page loads (the theme's, Font Awesome's 1.5 MB among them), the
search index aside; MathJax (1.2 MB) comes on top only where there is a formula, Vega
(0.8 MB) only where there is a panel, the widget manager (3.2 MB) only where a page
saved widgets."""
SEARCH_INDEX_BUDGET_BYTES = 500_000
"""The search index, which the theme loads on every page for its search as you type; it
grows with the book's words (363 kB at 2026-12-05), so it has a budget of its own."""
OPTIONAL_SCRIPTS = {"mathjax": "tex-mml-chtml.js", "vega": "vega", "widgets": "html-manager"}


def test_the_pages_are_light_and_load_what_they_need_only(browser_pages, built_book, note):
    rows = []
    for name in toc_files():
        seen = browser_pages[name]["laptop"]
        files = [pathlib.Path(f) for f in seen["files"] if pathlib.Path(f).exists()]
        total = sum(f.stat().st_size for f in files)
        scripts = [f for f in files if f.suffix == ".js"]
        html = (built_book / f"{name}.html").read_text()
        needs = {"mathjax": seen["math"] > 0, "vega": "icm-static-panel" in html,
                 "widgets": "application/vnd.jupyter.widget-state+json" in html}
        optional = {}
        for what, mark in OPTIONAL_SCRIPTS.items():
            found = [f for f in scripts if mark in f.name or f.parent.name == mark]
            assert bool(found) == needs[what], (name, what, [f.name for f in found])
            optional[what] = sum(f.stat().st_size for f in found)
        assert not [f for f in files if f.parent.name in ("mujoco", "three", "axe")], name
        index = sum(f.stat().st_size for f in scripts if f.name == "searchindex.js")
        assert index <= SEARCH_INDEX_BUDGET_BYTES, (name, index)
        base = sum(f.stat().st_size for f in scripts) - sum(optional.values()) - index
        rows.append((name.split("/")[-1], total, base, optional))
    note("page weight on opening (MB: all; scripts every page loads, search index aside; "
         "MathJax, Vega): "
         + ", ".join(f"{page} {total / 1e6:.2f}; {base / 1e6:.2f}; "
                     f"{extra['mathjax'] / 1e6:.2f}, {extra['vega'] / 1e6:.2f}"
                     for page, total, base, extra in rows))
    assert all(extra["widgets"] == 0 for *_, extra in rows)  # no page saved widgets
    for page, total, base, _ in rows:
        assert total <= PAGE_BUDGET_BYTES, (page, total)
        assert base <= BASE_SCRIPT_BUDGET_BYTES, (page, base)


def test_every_page_becomes_interactive(browser_pages):
    # How soon is measured in `make bench` (benchmarks/page_load.py, against the budget
    # of 2 s), not here: a time depends on the machine's load (here, the other visits'
    # too). Here, every page of the book must get there (its load event run, its static
    # panels drawn), as the benchmark measures it (its READY, read by each visit).
    times = {name: browser_pages[name]["laptop"]["interactive_ms"] for name in toc_files()}
    assert all(0 < ms < float("inf") for ms in times.values()), times


def test_the_page_load_benchmark_measures_the_books_pages(book_visits):
    # `make bench`'s own run of Chromium, on a page without static panels and on one with
    # two (run beside the visits; every page would open each one a third time).
    times = book_visits["benchmark"]
    if isinstance(times, Exception):
        raise times
    assert times is not None
    assert set(times) == {"(blank page)", *BENCHMARKED_PAGES}
    assert all(0 < ms < float("inf") for ms in times.values()), times
    assert len(page_load.report(times)) == len(times)
    with pytest.raises(ValueError, match="names of the book's pages"):
        page_load.measure(pages=["no_such_page"])


# The keyboard: every control of a page reached with Tab, with a visible focus, and
# worked with keys alone.

MARK_CONTROLS = """() => {
  const article = document.querySelector(".bd-article");
  // Folds open, as a reader opens them: a link inside a fold must be reached too.
  article.querySelectorAll("details").forEach(d => { d.open = true; });
  // Every control a reader could work: the natively interactive elements (even one
  // taken out of the Tab order with tabindex="-1", which must then fail the test) and
  // any other element put into the Tab order, that the reader can see
  // (checkVisibility: not inside a fold still closed, such as a solution's).
  const native = "a[href], button, input, select, textarea, summary";
  const controls = Array.from(article.querySelectorAll(native + ", [tabindex]"))
    .filter(e => (e.matches(native) || e.getAttribute("tabindex") !== "-1") && !e.disabled &&
                 e.getClientRects().length > 0 && getComputedStyle(e).visibility !== "hidden" &&
                 e.checkVisibility());
  controls.forEach((e, i) => e.dataset.icmKey = i);
  article.setAttribute("tabindex", "-1");  // Tab goes on from the article's start
  article.focus();
  return controls.map(e => e.tagName.toLowerCase() + (e.type ? "[" + e.type + "]" : "") +
                           " " + (e.getAttribute("aria-label") || e.textContent || e.name || "")
                           .trim().slice(0, 40));
}"""

FOCUSED = """() => {
  const e = document.activeElement;
  if (!e || e.dataset.icmKey === undefined) { return null; }
  const style = getComputedStyle(e);
  const ring = (style.outlineStyle !== "none" && parseFloat(style.outlineWidth) > 0) ||
               style.boxShadow !== "none";
  return [parseInt(e.dataset.icmKey), ring];
}"""


def _pages_with_controls(built_book):
    marks = ("<input", "<button", "<select", "<summary")
    pages = []
    for name in toc_files():
        html = (built_book / f"{name}.html").read_text()
        article = html.split('class="bd-article"', 1)[-1]
        if any(mark in article for mark in marks) or "icm-static-panel" in html:
            pages.append(name)
    return pages


async def _walk_with_tab(page):
    """The page's controls (folds opened) and, after each press of Tab from the
    article's start, which of them had the focus and whether it showed it."""
    controls = await page.evaluate(MARK_CONTROLS)
    focused = []
    for _ in range(len(controls) + 5):
        await page.keyboard.press("Tab")
        focused.append(await page.evaluate(FOCUSED))
    return {"controls": controls, "focused": focused}


def test_every_control_is_reached_with_tab_and_shows_its_focus(browser_pages, built_book):
    pages = _pages_with_controls(built_book)
    assert {"book/simulated_icub", "book/goal_oriented_interest", "book/rod_toppling"} <= \
        set(pages)
    for name in pages:
        walk = browser_pages[name]["laptop"]["keys"]
        controls = walk["controls"]
        reached, no_ring = set(), []
        # Radio buttons of one group are one stop for Tab (the arrows move within).
        for focused in walk["focused"]:
            if focused is None:
                continue
            reached.add(focused[0])
            if not focused[1]:
                no_ring.append(controls[focused[0]])
        radios_of_a_group = {i for i, c in enumerate(controls) if c.startswith("input[radio]")}
        missed = [c for i, c in enumerate(controls)
                  if i not in reached and i not in radios_of_a_group]
        assert missed == [], (name, missed)
        assert no_ring == [], (name, "focus not shown", no_ring)


async def _work_the_animations_and_a_panels_choice(browser, built_book):
    context, _requests = await _offline_context(browser, WIDTHS["laptop"], [])
    page = await context.new_page()
    await page.goto((built_book / "book" / "simulated_icub.html").as_uri(), wait_until="load")
    player = page.locator(".animation").first
    slider = player.locator("input[type=range]")
    await player.get_by_role("button", name="Pause").focus()
    await page.keyboard.press("Enter")
    before = int(await slider.input_value())
    await player.get_by_role("button", name="Next frame").focus()
    await page.keyboard.press("Enter")
    assert int(await slider.input_value()) == \
        (before + 1) % (int(await slider.get_attribute("max")) + 1)
    await slider.focus()
    await page.keyboard.press("End")
    assert await slider.input_value() == await slider.get_attribute("max")
    words = page.locator(".icm-anim-text").first
    await words.locator("summary").focus()
    await page.keyboard.press("Enter")
    assert await words.evaluate("d => d.open") and await words.locator("li").count() > 5
    # A panel's choice (radio buttons): the arrow keys move it.
    page = await context.new_page()
    await page.goto((built_book / "book" / "actor_critic.html").as_uri(), wait_until="load")
    await page.wait_for_function("Object.keys(window.icmPanels || {}).length > 0",
                                 timeout=30000)
    radio = page.locator(".icm-static-panel input[type=radio]").first
    name = await radio.get_attribute("name")
    await radio.focus()
    await page.keyboard.press("ArrowRight")
    panel_id = await page.evaluate("Object.keys(window.icmPanels)[0]")
    await _settle(page, panel_id)
    checked = page.locator(f".icm-static-panel input[type=radio][name={name}]:checked")
    assert await checked.get_attribute("value") != await radio.get_attribute("value")
    assert await page.evaluate(f"window.icmPanels['{panel_id}'].signal('{name}')") == \
        await checked.get_attribute("value")
    await context.close()


def test_the_animations_and_the_panels_choices_work_with_the_keyboard(chromium, built_book):
    chromium.run(_work_the_animations_and_a_panels_choice(chromium.browser, built_book))


# The static panels: every slider moved with the keyboard and with the mouse, and the
# figure checked against the data precomputed for the setting the sliders then show.

PANEL_STATE = """id => {
  const view = window.icmPanels[id];
  const spec = JSON.parse(document.getElementById(id + "-spec").textContent);
  const signals = {};
  for (const p of spec.params) { signals[p.name] = view.signal(p.name); }
  return {signals: signals, shown: view.data("data_0"),
          svg: document.querySelector("#" + id + " svg").innerHTML};
}"""


def expected_rows(spec, signals):
    """The rows a panel must show for `signals`: its dataset's rows of that setting,
    flattened as its transform says."""
    rows = [row for row in spec["datasets"]["grid"]
            if all(row[name] == value if isinstance(value, str)
                   else abs(row[name] - value) < 1e-6 for name, value in signals.items())]
    flatten = [t["flatten"] for t in spec.get("transform", []) if "flatten" in t]
    if flatten:
        fields = flatten[0]
        rows = [{**row, **{f: row[f][i] for f in fields}} for row in rows
                for i in range(len(row[fields[0]]))]
    return rows


def shown_key(rows):
    """What a panel draws, comparable between the page and the dataset."""
    if rows and "series" in rows[0]:
        return sorted((r["series"], r["x"], r["mean"], r["low"], r["high"]) for r in rows)
    return sorted((r["epsilon"], r["window"], r["gap"], r["red_first"]) for r in rows)


TAKEN = """id => {
  // Vega takes an input's new value into its signal on its next run (later still
  // where the binding has a debounce): true once every input of the panel (or of
  // every panel, id null) shows its signal's value.
  const ids = id === null ? Object.keys(window.icmPanels || {}) : [id];
  return ids.every(each => {
    const view = window.icmPanels[each];
    return Array.from(document.querySelectorAll("#" + each + " input")).every(input =>
      input.type === "range" ? Math.abs(Number(input.value) - view.signal(input.name)) < 1e-9
      : input.type === "radio" && input.checked ? input.value === String(view.signal(input.name))
      : true);
  });
}"""

DRAWN = """async id => {
  // The view's run has ended and drawn its figure (runAsync waits for a run under way).
  const ids = id === null ? Object.keys(window.icmPanels || {}) : [id];
  for (const each of ids) { await window.icmPanels[each].runAsync(); }
}"""


async def _settle(page, panel_id=None):
    """Waits until a panel (or every panel) has taken the values of its inputs (`TAKEN`;
    after 10 s it goes on, and the checks read what is shown) and drawn them
    (`DRAWN`)."""
    try:
        await page.wait_for_function(TAKEN, arg=panel_id, timeout=10000)
    except playwright_api.TimeoutError:
        pass
    await page.evaluate(DRAWN, panel_id)


async def _move_panels(page, name):
    """Moves each slider of the page's static panels with the keyboard (one step right)
    and the mouse (a click near each end), and each choice by a click; returns, per
    panel, what it showed after each move."""
    await page.wait_for_function(
        "() => document.querySelectorAll('.icm-static-panel').length > 0 && "
        "Object.keys(window.icmPanels || {}).length == "
        "document.querySelectorAll('.icm-static-panel').length", timeout=30000)
    panels = []
    for panel_id in await page.evaluate("Object.keys(window.icmPanels)"):
        spec = json.loads(await page.evaluate(
            f"document.getElementById('{panel_id}-spec').textContent"))
        moves = [("start", None, await page.evaluate(PANEL_STATE, panel_id))]
        for param in spec["params"]:
            bind, param_name = param["bind"], param["name"]
            if bind["input"] == "range":
                slider = page.locator(f"#{panel_id} input[type=range][name={param_name}]")
                await slider.focus()
                up = param["value"] + bind["step"] <= bind["max"] + 1e-9
                await page.keyboard.press("ArrowRight" if up else "ArrowLeft")
                await _settle(page, panel_id)
                moves.append(("keyboard up" if up else "keyboard down", param_name,
                              await page.evaluate(PANEL_STATE, panel_id)))
                box = await slider.bounding_box()
                for fraction in (0.95, 0.05):
                    await page.mouse.click(box["x"] + fraction * box["width"],
                                           box["y"] + box["height"] / 2)
                    await _settle(page, panel_id)
                    moves.append((f"mouse {fraction}", param_name,
                                  await page.evaluate(PANEL_STATE, panel_id)))
            else:
                for option in bind["options"][1:]:
                    await page.locator(f"#{panel_id} input[type=radio][name={param_name}]"
                                       f"[value={option}]").click()
                    await _settle(page, panel_id)
                    moves.append((f"click {option}", param_name,
                                  await page.evaluate(PANEL_STATE, panel_id)))
        panels.append({"page": name, "id": panel_id, "spec": spec, "moves": moves})
    return panels


@pytest.fixture(scope="module")
def static_panels(book_visits):
    """Every page with static panels, opened offline, each of their sliders moved with
    the keyboard (one step right) and the mouse (a click near each end), and each
    choice by a click (`_move_panels`): what each panel showed after each move, the
    requests the visits made (all refused), and per page the errors and Vega's
    warnings logged while it was open."""
    return book_visits["panels"]


def test_the_static_panels_are_there(static_panels):
    titles = [" ".join(panel["spec"]["title"]) if isinstance(panel["spec"]["title"], list)
              else panel["spec"]["title"] for panel in static_panels["panels"]]
    for figure in ("Figure 5", "Figure 6", "Figure 7", "epsilon x window sweep"):
        assert any(figure in title for title in titles), (figure, titles)


def test_every_static_slider_moves_its_figure_to_the_precomputed_data(static_panels):
    moved = 0
    for panel in static_panels["panels"]:
        spec, moves = panel["spec"], panel["moves"]
        grids = {p["name"]: p["bind"] for p in spec["params"]}
        previous = None
        for how, name, state in moves:
            expected = expected_rows(spec, state["signals"])
            assert expected, (panel["page"], how, name, state["signals"])
            assert shown_key(state["shown"]) == shown_key(expected), (panel["page"], how, name)
            if name is not None:
                bind = grids[name]
                value = state["signals"][name]
                before = previous["signals"][name]
                if how.startswith("keyboard"):
                    sign = 1 if how == "keyboard up" else -1
                    assert value == pytest.approx(before + sign * bind["step"]), (how, name)
                elif how == "mouse 0.95":
                    assert value == pytest.approx(bind["max"]), (how, name)
                elif how == "mouse 0.05":
                    assert value == pytest.approx(bind["min"]), (how, name)
                else:
                    assert value == how.split(" ", 1)[1], (how, name)
                assert value != before, (how, name)
                assert state["svg"] != previous["svg"], ("the figure did not change", how, name)
                moved += 1
            previous = state
    # Figure 5: 3 sliders, sweep: 1, Figure 6: 3 sliders and 3 more variants, Figure 7: 4
    # sliders; 3 moves per slider.
    assert moved >= 3 * (3 + 1 + 3 + 4) + 3


def test_static_panels_need_no_network_and_log_no_errors(static_panels):
    assert static_panels["requests"] == []
    assert static_panels["errors"] and all(e == [] for e in static_panels["errors"].values()), \
        static_panels["errors"]


async def _start_a_live_view_and_press_a_button(browser, built_book):
    context = await browser.new_context(offline=True, viewport={"width": 1366, "height": 800})
    requests, errors = [], []

    async def refuse_network(route):
        if route.request.url.startswith("file:"):
            await route.continue_()
        else:
            requests.append(route.request.url)
            await route.abort()

    await context.route("**/*", refuse_network)
    page = await context.new_page()
    page.on("console", lambda message: errors.append(message.text)
            if message.type == "error" else None)
    page.on("pageerror", lambda error: errors.append(str(error)))
    await page.goto((built_book / "book" / "simulated_icub.html").as_uri(), wait_until="load")
    assert await page.evaluate("typeof window.icmLive") == "undefined"
    view = page.locator(".icm-live").first
    # With the keyboard alone: Enter on the focused button.
    await view.get_by_role("button", name="Start the live view").focus()
    await page.keyboard.press("Enter")
    await page.wait_for_function("window.icmLive && window.icmLive.views.length === 1 && "
                                 "window.icmLive.views[0].stats.frames > 0", timeout=60000)
    await view.get_by_role("button", name="Press button 2").focus()
    await page.keyboard.press("Enter")
    await page.wait_for_function("!window.icmLive.views[0].sim.busy", timeout=60000)
    assert "opened the red box" in await view.locator(".icm-live-status").inner_text()
    # The running view, its controls and its panel, for every reader too.
    await page.add_script_tag(path=str(AXE))
    found = await page.evaluate(AXE_RUN.replace("axe.run(document,", "axe.run('.icm-live',"))
    await context.close()
    return [v for v in found if v["impact"] in SERIOUS], errors, requests


def test_a_live_view_starts_in_the_book_and_presses_a_button(chromium, built_book):
    # The live iCub (icm.viewer) in a built page: its scripts found through the page's
    # content root, loaded only on the click, the press opening the red box. The viewer
    # itself is checked in depth on a page of its own by tests/test_live_viewer.py.
    serious, errors, requests = chromium.run(
        _start_a_live_view_and_press_a_button(chromium.browser, built_book))
    assert serious == [], serious
    assert errors == [] and requests == []


# The "predict, then check" questions: every option of every question answered, wrong
# and right, with the keyboard and with the mouse, and the feedback read.

QUIZ_STATE = """id => {
  const choices = document.getElementById(id);
  const quiz = choices.closest(".icm-quiz") || choices.parentElement;
  const explanation = quiz.querySelector(".icm-quiz-explanation");
  const feedback = choices.querySelector(".icm-quiz-feedback");
  return {feedback: feedback ? feedback.textContent : null,
          role: feedback ? feedback.getAttribute("role") : null,
          live: feedback ? feedback.getAttribute("aria-live") : null,
          explanation_shown: explanation ? !explanation.hidden && explanation.offsetHeight > 0 : null,
          explanation_text: explanation ? explanation.textContent : ""};
}"""

QUIZ_LABELS = """id => {
  const choices = document.getElementById(id);
  const legend = choices.querySelector("legend");
  return {legend: legend ? legend.textContent.trim() : "",
          button: (choices.querySelector("button.icm-quiz-check") || {}).textContent,
          options: Array.from(choices.querySelectorAll("input[type=radio]")).map(input => {
            const label = document.querySelector("label[for='" + input.id + "']");
            return {id: input.id, label: label ? label.textContent.trim() : "",
                    correct: input.dataset.correct, hint: input.dataset.hint};
          })};
}"""


async def _answer_quizzes(page, name):
    """Answers each question of the page first with no option chosen, then every
    option in turn (by keyboard for even-numbered options, by mouse for odd ones);
    returns, per question, its labels and the feedback after each Check."""
    await page.wait_for_selector("fieldset.icm-quiz-ready", state="attached", timeout=30000)
    questions = []
    for quiz_id in await page.eval_on_selector_all("fieldset.icm-quiz-choices",
                                                   "els => els.map(e => e.id)"):
        labels = await page.evaluate(QUIZ_LABELS, quiz_id)
        before = await page.evaluate(QUIZ_STATE, quiz_id)
        button = page.locator(f"#{quiz_id} button.icm-quiz-check")
        await button.click()
        answers = [("none", None, await page.evaluate(QUIZ_STATE, quiz_id))]
        for i, option in enumerate(labels["options"]):
            radio = page.locator(f"#{option['id']}")
            if i % 2 == 0:  # the keyboard: focus the option, Space, Tab, Enter
                await radio.focus()
                await page.keyboard.press("Space")
                await page.keyboard.press("Tab")
                focused = await page.evaluate("document.activeElement.className")
                await page.keyboard.press("Enter")
                how = f"keyboard (Tab went to {focused})"
            else:  # the mouse: a click on the option's label, then on Check
                await page.locator(f"label[for='{option['id']}']").click()
                await button.click()
                how = "mouse"
            # No wait: Check answers in its click handler (book/_static/icm-quiz.js),
            # which has run when Playwright's press or click returns.
            answers.append((how, option, await page.evaluate(QUIZ_STATE, quiz_id)))
        questions.append({"page": name, "id": quiz_id, "labels": labels,
                          "before": before, "answers": answers})
    return questions


@pytest.fixture(scope="module")
def quizzes(book_visits):
    """Every page with questions, opened offline, each question answered first with no
    option chosen, then with every option in turn (`_answer_quizzes`): the feedback
    after each Check, the requests the visits made (all refused), and per page the
    errors logged while it was open."""
    return book_visits["quizzes"]


def test_every_chapter_has_a_question_answered_in_the_page(quizzes):
    pages = {q["page"] for q in quizzes["questions"]}
    chapters = [n for n in toc_files() if (ROOT / f"{n}.ipynb").exists()]
    assert len(chapters) == 8
    assert set(chapters) <= pages, set(chapters) - pages


def test_questions_are_labelled_for_keyboard_and_screen_readers(quizzes):
    for question in quizzes["questions"]:
        labels = question["labels"]
        assert labels["legend"], question["id"]
        assert labels["button"] == "Check", question["id"]
        assert len(labels["options"]) >= 2
        assert all(option["label"] for option in labels["options"]), question["id"]
        assert [o["correct"] for o in labels["options"]].count("true") == 1, question["id"]
        assert question["before"]["role"] == "status" and question["before"]["live"] == "polite"
        assert question["before"]["explanation_shown"] is False, \
            f"{question['id']}: the explanation shows before an answer"


def test_every_answer_gets_its_feedback(quizzes):
    answered = 0
    for question in quizzes["questions"]:
        for how, option, state in question["answers"]:
            if option is None:
                assert state["feedback"] == "Choose an answer first.", question["id"]
                assert state["explanation_shown"] is False
                continue
            if how.startswith("keyboard"):
                assert "icm-quiz-check" in how, f"{question['id']}: Tab did not reach Check"
            if option["correct"] == "true":
                assert state["feedback"].startswith("Right."), (question["id"], how, state)
                assert state["explanation_shown"] is True, (question["id"], how)
                assert re.search(r"\d", state["explanation_text"]), \
                    f"{question['id']}: the explanation quotes no number"
            else:
                assert state["feedback"] == "Not quite. " + option["hint"], (question["id"], how)
                assert option["hint"], question["id"]
                assert state["explanation_shown"] is False, (question["id"], how)
            answered += 1
    assert answered >= 8 * 3


def test_questions_need_no_network_and_log_no_errors(quizzes):
    assert quizzes["requests"] == []
    assert quizzes["errors"] and all(e == [] for e in quizzes["errors"].values()), \
        quizzes["errors"]
