"""The built book in a real browser, offline: headless Chromium (Debian's `chromium`
package) driven by Playwright, with every network request refused.

Skipped, with the reason shown, where Chromium or Playwright is missing; `.ci/run`
installs Chromium before `make test`.
"""

import json
import re
import shutil

import pytest

from conftest import ROOT, toc_files

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
        context = browser.new_context(offline=True, viewport={"width": 1366, "height": 800})
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
                "overflowing": page.evaluate(OVERFLOWING),
                "errors": errors,
            }
            page.close()
        seen["__requests__"] = requests
        browser.close()
    return seen


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


def test_nothing_is_cut_off_at_laptop_width(browser_pages):
    for name in toc_files():
        assert browser_pages[name]["overflowing"] == [], (name, browser_pages[name]["overflowing"])


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


def test_no_page_has_a_dead_widget_slider(browser_pages):
    # The book's panels are static Vega-Lite figures in the HTML; an ipywidgets slider
    # there could be dragged but would never redraw anything.
    for name in toc_files():
        assert browser_pages[name]["expected_sliders"] == 0, name
        assert browser_pages[name]["sliders"] == 0, name


def test_formulas_are_typeset_offline(browser_pages):
    assert sum(browser_pages[name]["math"] for name in toc_files()) >= 1


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


@pytest.fixture(scope="module")
def static_panels(built_book):
    """Opens every page with static panels, offline, and moves each of their sliders
    with the keyboard (one step right) and the mouse (a click near each end), and
    each choice by a click; records what the panel showed after each move."""
    record = {"panels": [], "requests": [], "errors": {}}
    with playwright_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=CHROMIUM, args=["--no-sandbox", "--disable-gpu"])
        context = browser.new_context(offline=True, viewport={"width": 1366, "height": 900})

        def refuse_network(route):
            if route.request.url.startswith("file:"):
                route.continue_()
            else:
                record["requests"].append(route.request.url)
                route.abort()

        context.route("**/*", refuse_network)
        for name in toc_files():
            path = built_book / f"{name}.html"
            if "icm-static-panel" not in path.read_text():
                continue
            page = context.new_page()
            errors = record["errors"].setdefault(name, [])
            # Errors, and Vega's own warnings ("WARN ...": a spec it had to correct).
            page.on("console", lambda message: errors.append(message.text)
                    if message.type == "error" or message.text.startswith("WARN")
                    else None)
            page.on("pageerror", lambda error: errors.append(str(error)))
            page.goto(path.as_uri(), wait_until="load")
            page.wait_for_function(
                "() => document.querySelectorAll('.icm-static-panel').length > 0 && "
                "Object.keys(window.icmPanels || {}).length == "
                "document.querySelectorAll('.icm-static-panel').length", timeout=30000)
            for panel_id in page.evaluate("Object.keys(window.icmPanels)"):
                spec = json.loads(page.evaluate(
                    f"document.getElementById('{panel_id}-spec').textContent"))
                moves = [("start", None, page.evaluate(PANEL_STATE, panel_id))]
                for param in spec["params"]:
                    bind, param_name = param["bind"], param["name"]
                    if bind["input"] == "range":
                        slider = page.locator(f"#{panel_id} input[type=range][name={param_name}]")
                        slider.focus()
                        up = param["value"] + bind["step"] <= bind["max"] + 1e-9
                        page.keyboard.press("ArrowRight" if up else "ArrowLeft")
                        page.wait_for_timeout(150)
                        moves.append(("keyboard up" if up else "keyboard down", param_name,
                                      page.evaluate(PANEL_STATE, panel_id)))
                        box = slider.bounding_box()
                        for fraction in (0.95, 0.05):
                            page.mouse.click(box["x"] + fraction * box["width"],
                                             box["y"] + box["height"] / 2)
                            page.wait_for_timeout(150)
                            moves.append((f"mouse {fraction}", param_name,
                                          page.evaluate(PANEL_STATE, panel_id)))
                    else:
                        for option in bind["options"][1:]:
                            page.locator(f"#{panel_id} input[type=radio][name={param_name}]"
                                         f"[value={option}]").click()
                            page.wait_for_timeout(150)
                            moves.append((f"click {option}", param_name,
                                          page.evaluate(PANEL_STATE, panel_id)))
                record["panels"].append({"page": name, "id": panel_id, "spec": spec,
                                         "moves": moves})
            page.close()
        browser.close()
    return record


def test_the_static_panels_are_there(static_panels):
    titles = [panel["spec"]["title"] for panel in static_panels["panels"]]
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


def test_a_live_view_starts_in_the_book_and_presses_a_button(built_book):
    # The live iCub (icm.viewer) in a built page: its scripts found through the page's
    # content root, loaded only on the click, the press opening the red box. The viewer
    # itself is checked in depth on a page of its own by tests/test_live_viewer.py.
    with playwright_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=[
            "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync"])
        context = browser.new_context(offline=True, viewport={"width": 1366, "height": 800})
        requests, errors = [], []
        context.route("**/*", lambda route: route.continue_() if route.request.url.startswith(
            "file:") else (requests.append(route.request.url), route.abort()))
        page = context.new_page()
        page.on("console", lambda message: errors.append(message.text)
                if message.type == "error" else None)
        page.on("pageerror", lambda error: errors.append(str(error)))
        page.goto((built_book / "book" / "simulated_icub.html").as_uri(), wait_until="load")
        assert page.evaluate("typeof window.icmLive") == "undefined"
        view = page.locator(".icm-live").first
        view.get_by_role("button", name="Start the live view").click()
        page.wait_for_function("window.icmLive && window.icmLive.views.length === 1 && "
                               "window.icmLive.views[0].stats.frames > 0", timeout=60000)
        view.get_by_role("button", name="Press button 2").click()
        page.wait_for_function("!window.icmLive.views[0].sim.busy", timeout=60000)
        assert "opened the red box" in view.locator(".icm-live-status").inner_text()
        browser.close()
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


@pytest.fixture(scope="module")
def quizzes(built_book):
    """Opens every page with questions, offline; answers each question first with no
    option chosen, then every option in turn (by keyboard for even-numbered options,
    by mouse for odd ones), recording the feedback after each Check."""
    record = {"questions": [], "requests": [], "errors": {}}
    with playwright_api.sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=CHROMIUM, args=["--no-sandbox", "--disable-gpu"])
        context = browser.new_context(offline=True, viewport={"width": 1366, "height": 900})

        def refuse_network(route):
            if route.request.url.startswith("file:"):
                route.continue_()
            else:
                record["requests"].append(route.request.url)
                route.abort()

        context.route("**/*", refuse_network)
        for name in toc_files():
            path = built_book / f"{name}.html"
            if "icm-quiz-choices" not in path.read_text():
                continue
            page = context.new_page()
            errors = record["errors"].setdefault(name, [])
            page.on("console", lambda message: errors.append(message.text)
                    if message.type == "error" else None)
            page.on("pageerror", lambda error: errors.append(str(error)))
            page.goto(path.as_uri(), wait_until="load")
            page.wait_for_selector("fieldset.icm-quiz-ready", state="attached", timeout=30000)
            for quiz_id in page.eval_on_selector_all("fieldset.icm-quiz-choices",
                                                     "els => els.map(e => e.id)"):
                labels = page.evaluate(QUIZ_LABELS, quiz_id)
                before = page.evaluate(QUIZ_STATE, quiz_id)
                button = page.locator(f"#{quiz_id} button.icm-quiz-check")
                button.click()
                answers = [("none", None, page.evaluate(QUIZ_STATE, quiz_id))]
                for i, option in enumerate(labels["options"]):
                    radio = page.locator(f"#{option['id']}")
                    if i % 2 == 0:  # the keyboard: focus the option, Space, Tab, Enter
                        radio.focus()
                        page.keyboard.press("Space")
                        page.keyboard.press("Tab")
                        focused = page.evaluate("document.activeElement.className")
                        page.keyboard.press("Enter")
                        how = f"keyboard (Tab went to {focused})"
                    else:  # the mouse: a click on the option's label, then on Check
                        page.locator(f"label[for='{option['id']}']").click()
                        button.click()
                        how = "mouse"
                    page.wait_for_timeout(50)
                    answers.append((how, option, page.evaluate(QUIZ_STATE, quiz_id)))
                record["questions"].append({"page": name, "id": quiz_id, "labels": labels,
                                            "before": before, "answers": answers})
            page.close()
        browser.close()
    return record


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
