"""The slide decks (`python -m icm.course slides`, icm/course/slides.py): what a deck
holds, a block of text too long for one slide split between its items, and every
slide of every deck, opened offline in headless Chromium at several window sizes,
within the frame reveal.js scales to the window (issue 43: 10 of the 73 slides were
taller than it and cut off)."""

import math
import re
import shutil

import pytest

from conftest import ROOT, chromium, first_objective

from icm.course import assign, slides

WINDOWS = ((1280, 720), (1024, 768), (1920, 1080), (768, 1024))
"""The windows every deck is measured in: a 16:9 laptop or projector, a 4:3
projector, a full-HD screen (the figures' old height, 62% of the window, ran out of
their slides there) and a tablet held upright."""
SMALLEST_FIGURE = 0.5
"""The least share of the slide's height a figure takes under its caption, unless it
is as wide as the slide (a wide figure is as tall as its width allows)."""


def _fake_book(folder, with_blocks=True, takeaways=1, caption="The caption of {name}"):
    """A built book's pages as the decks read them: a title, an objectives block, a
    figure, a takeaways block of `takeaways` items (each about three lines long) and an
    exercise per chapter, with the vendored scripts."""
    static = folder / "_static" / "vendor"
    for name in ("reveal", "mathjax"):
        shutil.copytree(ROOT / "book" / "_static" / "vendor" / name, static / name)
    (folder / "_images").mkdir(parents=True)
    (folder / "book").mkdir()
    for number, (name, _) in enumerate(assign.chapters(), 1):
        shutil.copy(ROOT / "assets" / "images" / "figure5.png",
                    folder / "_images" / f"{name}.png")
        items = "".join(f"<li><p>Takeaway {i} of {name}: " + "a point worth making " * 8
                        + f"\\(x_{i}\\).</p></li>" for i in range(1, takeaways + 1))
        blocks = (f'<div class="admonition icm-objectives"><p class="admonition-title">'
                  f'Learning objectives</p><p>After this chapter you can:</p><ul><li>'
                  f'Objective of {name}</li></ul></div><div class="admonition '
                  f'icm-takeaways"><p class="admonition-title">Key takeaways</p>'
                  f'<ul class="simple">{items}</ul></div>') if with_blocks else ""
        (folder / "book" / f"{name}.html").write_text(
            f'<html><body><main><section><h1>Chapter {name}<a class="headerlink" '
            f'href="#">#</a></h1>{blocks}<figure id="fig-{number}"><img src="../_images/'
            f'{name}.png" alt="a plot"><figcaption><p><span class="caption-number">Fig. '
            f'{number}.1 </span><span class="caption-text">{caption.format(name=name)}, '
            f'\\(x^2\\).</span></p></figcaption></figure><div class="exercise admonition" '
            f'id="ex-{number}"><p class="admonition-title">Exercise {number}.1 (Implement: '
            f'a thing)</p></div><div class="solution"><figure><img src="../_images/'
            f'{name}.png" alt="hidden"></figure></div></section></main></body></html>')
    return folder


def test_a_deck_holds_the_chapters_objectives_figures_and_takeaways(tmp_path):
    book = _fake_book(tmp_path / "html")
    decks = slides.build_slides(book, tmp_path / "slides")
    assert [d.stem for d in decks] == [name for name, _ in assign.chapters()]
    for deck in decks:
        text = deck.read_text()
        assert f"Objective of {deck.stem}" in text and f"Takeaway 1 of {deck.stem}" in text
        assert f"The caption of {deck.stem}" in text and "headerlink" not in text
        assert text.count("<section") == 5  # title, objectives, figure, takeaways, exercises
        assert 'alt="hidden"' not in text  # a solution's figure stays in the book
        # The figure takes the height its caption leaves (reveal.js's r-stretch).
        assert f'<img class="r-stretch" src="images/{deck.stem}.png"' in text
        assert "Exercise" in text and "http" not in text.split("<body>")[1]
    assert (tmp_path / "slides" / "index.html").exists()
    bare = _fake_book(tmp_path / "bare", with_blocks=False)
    text = slides.build_slides(bare, tmp_path / "bare-slides")[0].read_text()
    assert "Learning objectives" not in text and text.count("<section") == 3
    with pytest.raises(ValueError, match="nothing does not exist"):
        slides.build_slides(tmp_path / "nothing", tmp_path / "x")
    (tmp_path / "nothing").mkdir()
    with pytest.raises(slides.SlidesError, match="not a built book"):
        slides.build_slides(tmp_path / "nothing", tmp_path / "x")
    assert not (tmp_path / "x").exists()  # refused before anything was written


def _items(html):
    return re.findall(r"<li><p>(Item \d+)", html)


def test_a_long_list_goes_on_over_slides_cut_between_its_items():
    long_item = "<li><p>Item {}: " + "words that take a line " * 6 + "</p></li>"
    block = ("<p>After this chapter you can:</p><ol class=\"simple\">"
             + "".join(long_item.format(i) for i in range(1, 10)) + "</ol>")
    parts = slides.split_text(block)
    assert len(parts) == 3 and all(size == 1.0 for _, size in parts)
    assert [_items(html) for html, _ in parts] == [
        [f"Item {i}" for i in range(1, 10)][start:start + 3] for start in (0, 3, 6)]
    # The lead-in opens the first slide only; the list's numbers go on.
    assert parts[0][0].startswith("<p>After this chapter you can:</p><ol class=\"simple\">")
    assert [re.match(r'<ol class="simple"( start="\d+")?>', html).group(1)
            for html, _ in parts[1:]] == [' start="4"', ' start="7"']
    assert all(html.count("<ol") == html.count("</ol>") == 1 for html, _ in parts)
    # Three slides, not two: two would put five items on one, which do not fit (and
    # three each, not 4, 4 and 1).
    item = math.ceil(len("Item 1: " + "words that take a line " * 6)
                     / slides.CHARS_PER_LINE) * slides.LINE_HEIGHT
    assert 3 * item + 3 * slides.GAP + slides.LINE_HEIGHT <= slides.TEXT_ROOM
    assert 5 * item + 4 * slides.GAP > slides.TEXT_ROOM
    # A list that fits stays whole, under its heading alone.
    (whole, size), = slides.split_text("<ul><li>one</li><li>two</li></ul>")
    assert whole == "<ul><li>one</li><li>two</li></ul>" and size == 1.0
    sections = slides.deck_slides({"title": "A", "objectives": block, "figures": [],
                                   "takeaways": None, "exercises": ["Exercise 1.1"]}, 1)
    assert [re.search(r"<h2>(.*?)</h2>", s).group(1) for s in sections[1:]] == [
        "Learning objectives (1 of 3)", "Learning objectives (2 of 3)",
        "Learning objectives (3 of 3)", "Exercises"]


def test_an_item_too_long_for_a_slide_has_one_of_its_own_in_smaller_text():
    block = ("<ul><li>short</li><li>" + "a very long item " * 300 + "</li><li>short</li></ul>")
    parts = slides.split_text(block)
    assert [size < 1.0 for _, size in parts] == [False, True, False]
    (section,) = [s for s in slides.deck_slides(
        {"title": "A", "objectives": None, "figures": [], "takeaways": block,
         "exercises": []}, 1) if "a very long item" in s]
    size = float(re.search(r'style="font-size: ([\d.]+)em"', section).group(1))
    assert size == pytest.approx(0.8 * parts[1][1], abs=1e-3)
    for bad in (0, -5.0, float("nan")):
        with pytest.raises(ValueError, match="room"):
            slides.split_text(block, room=bad)
    with pytest.raises(TypeError, match="block"):
        slides.split_text(None)


# --- in Chromium -------------------------------------------------------------------------

@pytest.fixture(scope="module")
def browser():
    with chromium() as launched:
        yield launched


MEASURE = """() => {
  Reveal.configure({transition: 'none', backgroundTransition: 'none'});
  Reveal.layout();
  const frame = Reveal.getConfig(), scale = Reveal.getScale();
  return Reveal.getSlides().map((slide, index) => {
    Reveal.slide(index);
    const heading = slide.querySelector('h1, h2, .icm-caption strong');
    const image = slide.querySelector('img');
    return {index, heading: heading ? heading.textContent : '',
            height: slide.scrollHeight, width: slide.scrollWidth,
            frame: [frame.width, frame.height],
            image: image ? [image.naturalWidth, image.getBoundingClientRect().width / scale,
                            image.getBoundingClientRect().height / scale] : null};
  });
}"""
"""Every slide of the open deck, each shown in turn: its heading, the height and width
of its content in the frame's CSS pixels (a slide's `scrollHeight`: reveal.js centres a
slide by it, and cuts off what passes the frame), the frame's size, and its image's
natural width and its width and height on the slide."""


def _measure_deck(browser, deck):
    """Opens `deck` offline (a context that refuses the network) and measures it in
    each of `WINDOWS`: ({window: `MEASURE`'s list}, its console and page errors, the
    requests it tried to make off the machine)."""
    context = browser.new_context(offline=True)
    requests, errors = [], []

    def refuse_network(route):
        url = route.request.url
        if url.startswith(("file:", "data:")):
            route.continue_()
        else:
            requests.append(url)
            route.abort()

    context.route("**/*", refuse_network)
    page = context.new_page()
    page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.set_viewport_size(dict(zip(("width", "height"), WINDOWS[0])))
        page.goto(deck.as_uri(), wait_until="load")
        page.wait_for_function("window.Reveal && Reveal.isReady()", timeout=60000)
        # The formulas typeset (the math plugin lays the deck out again after them).
        page.wait_for_function("window.MathJax && MathJax.startup && MathJax.startup.promise",
                               timeout=60000)
        page.evaluate("MathJax.startup.promise.then(() => true)")
        page.wait_for_function("[...document.images].every(image => image.complete)")
        measured = {}
        for width, height in WINDOWS:
            page.set_viewport_size({"width": width, "height": height})
            measured[(width, height)] = page.evaluate(MEASURE)
        return measured, errors, requests
    finally:
        context.close()


def _cut_off(measured):
    """The slides whose content passes their frame: [(window, slide, heading, height,
    width)]."""
    return [(window, s["index"], s["heading"], s["height"], s["width"])
            for window, sizes in measured.items() for s in sizes
            if s["height"] > s["frame"][1] or s["width"] > s["frame"][0]]


def _small_figures(measured):
    """The figures not loaded, or shown less than `SMALLEST_FIGURE` of their slide's
    height and narrower than the slide: [(window, slide, heading, width, height)]."""
    return [(window, s["index"], s["heading"], *s["image"][1:])
            for window, sizes in measured.items() for s in sizes if s["image"]
            if s["image"][0] == 0 or (s["image"][2] < SMALLEST_FIGURE * s["frame"][1]
                                      and s["image"][1] < s["frame"][0] - 1)]


def test_every_slide_fits_its_frame_and_a_long_list_would_not(browser, tmp_path):
    """Decks whose takeaways (six items of three lines) and captions are long: every
    slide fits, in every window; the same takeaways on one slide (no split) are
    measured cut off, so the measure can fail."""
    book = _fake_book(tmp_path / "html", takeaways=6,
                      caption="The caption of {name}, " + "which goes on " * 40)
    decks = slides.build_slides(book, tmp_path / "slides")
    first = decks[0]
    measured, errors, requests = _measure_deck(browser, first)
    assert errors == [] and requests == []
    headings = [s["heading"] for s in measured[WINDOWS[0]]]
    assert headings[3:5] == ["Key takeaways (1 of 2)", "Key takeaways (2 of 2)"]
    assert _cut_off(measured) == [] and _small_figures(measured) == []
    content = slides.chapter_slides(book / "book" / f"{first.stem}.html")
    content["figures"][0]["src"] = f"images/{first.stem}.png"
    unsplit = first.with_name("unsplit.html")
    unsplit.write_text(slides.deck_html(content, 1, room=10000.0))
    measured, _, _ = _measure_deck(browser, unsplit)
    cut = {(index, heading) for _, index, heading, height, _ in _cut_off(measured)}
    assert cut == {(3, "Key takeaways")}


def test_make_slides_gives_one_deck_per_chapter_that_opens_offline_and_fits(
        built_book, browser, tmp_path, note):
    decks = slides.build_slides(built_book, tmp_path / "slides")
    assert len(decks) == len(assign.chapters()) == 8
    total, cut, small = 0, [], []
    for deck in decks:
        content = slides.chapter_slides(built_book / "book" / deck.name)
        assert content["figures"] and content["objectives"] and content["takeaways"]
        measured, errors, requests = _measure_deck(browser, deck)
        assert errors == [] and requests == [], (deck.name, errors, requests)
        for sizes in measured.values():
            assert len(sizes) == len(slides.deck_slides(content, 1)), deck.name
        total += len(measured[WINDOWS[0]])
        cut += [(deck.stem, *entry) for entry in _cut_off(measured)]
        small += [(deck.stem, *entry) for entry in _small_figures(measured)]
    assert cut == [], cut
    assert small == [], small
    note(f"slides: {total} slides in {len(decks)} decks, each within its frame in "
         f"{len(WINDOWS)} windows")
    first = slides.chapter_slides(built_book / "book" / "button_experiment.html")
    assert first_objective("button_experiment") in " ".join(first["objectives"].split())
