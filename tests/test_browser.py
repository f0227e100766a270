"""The built book in a real browser, offline: headless Chromium (Debian's `chromium`
package) driven by Playwright, with every network request refused.

Skipped, with the reason shown, where Chromium or Playwright is missing; `.ci/run`
installs Chromium before `make test`.
"""

import json
import pathlib
import re
import shutil

import pytest

from conftest import toc_files

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
playwright_api = pytest.importorskip("playwright.sync_api",
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


@pytest.fixture(scope="module")
def browser_pages(built_book):
    """Opens every page of the book offline; returns what the browser saw per page."""
    seen = {}
    with playwright_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=CHROMIUM,
            args=["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                  "--disable-background-networking", "--disable-component-update",
                  "--disable-sync"])
        context = browser.new_context(offline=True)
        requests = []

        def refuse_network(route):
            if route.request.url.startswith("file:"):
                route.continue_()
            else:
                requests.append(route.request.url)
                route.abort()

        context.route("**/*", refuse_network)
        for name in toc_files():
            path = built_book / f"{name}.html"
            page = context.new_page()
            errors = []
            page.on("console", lambda message: errors.append(message.text)
                    if message.type == "error" else None)
            page.on("pageerror", lambda error: errors.append(str(error)))
            page.goto(path.as_uri(), wait_until="load")
            page.wait_for_timeout(1500)  # widgets and formulas render after load
            seen[name] = {
                "images": page.eval_on_selector_all(
                    "img", "els => els.map(e => [e.naturalWidth, e.getAttribute('src').slice(0, 80)])"),
                "sliders": page.locator(".widget-slider").count(),
                "expected_sliders": expected_sliders(path.read_text()),
                "math": page.locator("mjx-container").count(),
                "errors": errors,
            }
            page.close()
        seen["__requests__"] = requests
        browser.close()
    return seen


def test_every_page_loads_without_console_errors(browser_pages):
    for name in toc_files():
        assert browser_pages[name]["errors"] == [], f"{name}: {browser_pages[name]['errors']}"


def test_no_page_needs_the_network(browser_pages):
    assert browser_pages["__requests__"] == []


def test_every_figure_image_loads(browser_pages):
    total = 0
    for name in toc_files():
        broken = [src for width, src in browser_pages[name]["images"] if width == 0]
        assert broken == [], f"{name}: images that did not load: {broken}"
        total += len(browser_pages[name]["images"])
    assert total >= 10


def test_widget_panels_render_their_controls_from_the_saved_state(browser_pages):
    panels = 0
    for name in toc_files():
        page = browser_pages[name]
        assert page["sliders"] == page["expected_sliders"], name
        panels += page["expected_sliders"] > 0
    assert panels >= 1


def test_formulas_are_typeset_offline(browser_pages):
    assert sum(browser_pages[name]["math"] for name in toc_files()) >= 1
