"""One reveal.js slide deck per chapter, made from the built book's pages: the
chapter's title, its learning objectives (the block of class `icm-objectives`), each
of its figures with its caption, its key takeaways (the block of class
`icm-takeaways`) and the list of its exercises. Nothing is typed a second time: a
deck changes when its chapter does.

    python -m icm.course slides _build/html --out _build/slides [--force]   (make slides)

The decks work offline: reveal.js (and MathJax, for the formulas) come from the
book's vendored copies (`book/_static/vendor`, copied into the built book's
`_static`), the figures are copied beside the decks. Open `index.html`.

Every slide fits its 960 x 700 frame, whatever the screen (reveal.js scales the frame
to the window): a figure is stretched to the height its caption leaves it (reveal.js's
`r-stretch`), and a list too long for one slide goes on over the next ones, split
between its items (`split_text`). tests/test_slides.py opens every deck in Chromium
and measures every slide.

The decks' folder is checked before any work (`icm.files.check_folder`): new, empty,
or a folder icm wrote (its marker, `icm.files.MARKER`), unless `force`; never the
built book, inside it, or holding it. The decks are written into a staging folder
inside it and replace the old ones only when all are written (`icm.files.staged`).
A figure is copied only from inside the built book.
"""

import html
import math
import os
import pathlib
import shutil

from icm import _validate, files, records
from icm.course.assign import chapters

OBJECTIVES = "icm-objectives"
"""The class of a chapter's learning-objectives block."""
TAKEAWAYS = "icm-takeaways"
"""The class of a chapter's key-takeaways block."""
SLIDE_WIDTH, SLIDE_HEIGHT = 960, 700
"""The frame every slide is laid out in, in CSS pixels (reveal.js's default size),
which reveal.js scales to the window."""
TEXT_ROOM = 594.0
"""The height a slide of text has for its text under its heading, in CSS pixels: 700
less the heading (65.5: 1.3 x 42 px at line height 1.2) and the margins under it and
under the text (20 each). Measured in Chromium: these decks' slides of text, heading
and all, are 105.5 px taller than their text."""
LINE_HEIGHT = 0.8 * 42 * 1.3
"""The height of a line of text, in CSS pixels: the text is 0.8 of the theme's 42 px,
at the theme's line height, 1.3."""
GAP = 20.0
"""The gap between two paragraphs or items, in CSS pixels (the theme's block margin)."""
CHARS_PER_LINE = 55
"""Characters of a line of text, to estimate where lines break: in Chromium, the
items of these decks' lists broke after 53 to 82 characters (900 px of 33.6 px text),
so an estimate of 55 never gave an item fewer lines than it took, and a line more
than it took to about a third of them (a formula's source, longer than what it
shows, counts whole)."""
_STYLE = """
.reveal h1 { font-size: 1.9em; }
.reveal h2 { font-size: 1.3em; }
.reveal section { text-align: left; }
.reveal .icm-title { text-align: center; }
.reveal .icm-text { font-size: 0.8em; }
.reveal .icm-text ul, .reveal .icm-text ol { display: block; }
.reveal .icm-figure img { display: block; margin: 0 auto; max-width: 100%; max-height: none; }
.reveal .icm-caption { font-size: 0.5em; line-height: 1.35; margin: 0.4em 0 0; }
.reveal .icm-source { font-size: 0.45em; color: #555; }
"""


COMMAND = "python -m icm.course slides"
"""The command, as the marker of its output folder names it (`icm.files.MARKER`)."""


class SlidesError(ValueError):
    """A built book the decks cannot be made from."""


def _soup(path):
    from bs4 import BeautifulSoup

    try:
        return BeautifulSoup(records.read_text(path), "html.parser")
    except records.RecordError as error:
        raise SlidesError(f"a page of the built book: {error}") from None


def _clean(node):
    """A copy of a page's node without the parts that mean nothing on a slide:
    header links, and the MathJax that the page typeset (the deck typesets again)."""
    from bs4 import BeautifulSoup

    copy = BeautifulSoup(str(node), "html.parser")
    for link in copy.select("a.headerlink"):
        link.decompose()
    for link in copy.find_all("a"):  # links into the book: their text only
        link.unwrap()
    return copy


def _block(page, css_class):
    """The items of an admonition block of the page (its list, or its paragraphs),
    as HTML, or None when the page has none."""
    block = page.select_one(f"div.{css_class}")
    if block is None:
        return None
    block = _clean(block)
    title = block.select_one(".admonition-title")
    if title is not None:
        title.decompose()
    inner = block.select_one(f"div.{css_class}") or block
    return "".join(str(child) for child in inner.children).strip()


def chapter_slides(page_path):
    """What a chapter's deck shows, read from its built page.

    Args:
      page_path: the chapter's HTML page.

    Returns:
      A dict: "title", "objectives" and "takeaways" (HTML, or None), "figures" (a
      list of {"src": the image's path, "alt", "caption" (HTML), "number"}) and
      "exercises" (a list of titles).
    """
    page = _soup(page_path)
    main = page.select_one("main") or page
    heading = main.find("h1")
    if heading is None:
        raise SlidesError(f"{page_path}: no title (h1)")
    title = _clean(heading).get_text(" ", strip=True)
    figures = []
    for figure in main.find_all("figure"):
        if figure.find_parent(class_=["solution", "exercise"]) is not None:
            continue
        image = figure.find("img")
        if image is None or not image.get("src"):
            continue
        caption = figure.find("figcaption")
        text = caption.select_one(".caption-text") if caption else None
        number = caption.select_one(".caption-number") if caption else None
        figures.append({"src": image["src"], "alt": image.get("alt", ""),
                        "caption": "".join(str(c) for c in _clean(text).children).strip()
                        if text else "",
                        "number": number.get_text(strip=True) if number else ""})
    exercises = [_clean(title).get_text(" ", strip=True)
                 for title in main.select("div.exercise > p.admonition-title")]
    return {"title": title, "objectives": _block(main, OBJECTIVES),
            "takeaways": _block(main, TAKEAWAYS), "figures": figures,
            "exercises": exercises}


def _pieces(block):
    """The pieces of a block of HTML that a slide may end between: each paragraph (or
    other element) on its own, and each item of a list, with the list it belongs to.

    Returns:
      [(html, its list (its number in the block and its opening tag) or None, the
      characters of its text)].
    """
    from bs4 import BeautifulSoup, Comment, NavigableString

    pieces = []
    for number, child in enumerate(BeautifulSoup(block, "html.parser").contents):
        if isinstance(child, Comment):
            continue
        if isinstance(child, NavigableString):
            if child.strip():
                pieces.append((html.escape(child.strip()), None, len(child.strip())))
        elif child.name in ("ul", "ol"):
            opening = str(child)[:str(child).index(">") + 1]
            for item in child.find_all("li", recursive=False):
                pieces.append((str(item), (number, opening),
                               len(item.get_text(" ", strip=True))))
        else:
            pieces.append((str(child), None, len(child.get_text(" ", strip=True))))
    return pieces


def _height(characters):
    """The height a piece of text of `characters` takes (CSS pixels, estimated), with
    the gap after it."""
    return max(1, math.ceil(characters / CHARS_PER_LINE)) * LINE_HEIGHT + GAP


def _balanced(costs, parts):
    """Where to cut `costs` into `parts` runs of consecutive pieces, the largest run as
    small as it can be: the runs' [start, end) bounds (the linear partition problem)."""
    n = len(costs)
    total = [0.0]
    for cost in costs:
        total.append(total[-1] + cost)
    best = [[math.inf] * (parts + 1) for _ in range(n + 1)]
    cut = [[0] * (parts + 1) for _ in range(n + 1)]
    best[0][0] = 0.0
    for end in range(1, n + 1):
        for used in range(1, min(parts, end) + 1):
            for start in range(used - 1, end):
                worst = max(best[start][used - 1], total[end] - total[start])
                if worst < best[end][used]:
                    best[end][used], cut[end][used] = worst, start
    bounds, end = [], n
    for used in range(parts, 0, -1):
        bounds.insert(0, (cut[end][used], end))
        end = cut[end][used]
    return bounds


def split_text(block, room=TEXT_ROOM):
    """A block of HTML (a list, paragraphs) cut into slides whose text is at most
    `room` CSS pixels tall (estimated: lines of `CHARS_PER_LINE` characters), between
    its pieces (`_pieces`: paragraphs and list items, never inside one), in as few
    slides as that allows and as even as can be. A list cut in two goes on in the
    next slide (an ordered list from the number it had reached). A piece taller than
    `room` on its own has a slide to itself, its text made smaller to fit.

    Args:
      block: the HTML.
      room: the height a slide has for its text (see `TEXT_ROOM`).

    Returns:
      [(the slide's HTML, its text's size relative to the usual one: 1 or less)].
    """
    _validate.text("block", block)
    room = _validate.real("room", room, 0.0, low_open=True)
    pieces = _pieces(block)
    if not pieces:
        return []
    costs = [_height(characters) for _, _, characters in pieces]
    parts, filled = 1, 0.0  # the fewest slides: fill each in turn
    for i, cost in enumerate(costs):
        if i and filled + cost - GAP > room:
            parts, filled = parts + 1, 0.0
        filled += cost
    slides, counts = [], {}
    for start, end in _balanced(costs, parts):
        out, current = [], None
        for text, in_list, _ in pieces[start:end]:
            if in_list != current:
                if current is not None:
                    out.append(f"</{_tag(current[1])}>")
                if in_list is not None:
                    opening, before = in_list[1], counts.get(in_list, 0)
                    if before and _tag(opening) == "ol":  # its numbers go on
                        opening = opening[:-1] + f' start="{before + 1}">'
                    out.append(opening)
                current = in_list
            if in_list is not None:
                counts[in_list] = counts.get(in_list, 0) + 1
            out.append(text)
        if current is not None:
            out.append(f"</{_tag(current[1])}>")
        used = sum(costs[start:end]) - GAP
        slides.append(("".join(out), min(1.0, room / used)))
    return slides


def _tag(opening):
    """The tag name of an opening tag such as '<ul class="simple">'."""
    return opening[1:].split(None, 1)[0].rstrip(">")


def _text_slides(heading, block, room):
    """The slides of a block of text under `heading`, numbered when there are several
    ("Key takeaways (2 of 3)")."""
    parts = split_text(block, room)
    out = []
    for i, (body, size) in enumerate(parts, 1):
        title = heading if len(parts) == 1 else f"{heading} ({i} of {len(parts)})"
        style = "" if size >= 1.0 else f' style="font-size: {0.8 * size:.3f}em"'
        out.append(f'<section><h2>{html.escape(title)}</h2>'
                   f'<div class="icm-text"{style}>{body}</div></section>')
    return out


def deck_slides(content, chapter_number, room=TEXT_ROOM):
    """A deck's slides, as HTML sections, in order: the title, the objectives, one per
    figure, the takeaways and the exercises (a block of text over as many slides as it
    needs, `split_text`).

    Args:
      content: what `chapter_slides` read.
      chapter_number: the chapter's number in the book.
      room: the height a slide has for its text (see `TEXT_ROOM`).

    Returns:
      The sections' HTML.
    """
    room = _validate.real("room", room, 0.0, low_open=True)
    title = html.escape(content["title"])
    slides = [f'<section class="icm-title"><h1>{chapter_number}. {title}</h1>'
              f'<p class="icm-source">Intrinsic motivation on the iCub: the chapter\'s '
              f'figures and its summary, from the book</p></section>']
    if content["objectives"]:
        slides += _text_slides("Learning objectives", content["objectives"], room)
    for figure in content["figures"]:
        number = html.escape(figure["number"])
        # reveal.js's r-stretch: the image takes the height the caption leaves, on
        # any screen (reveal.js sets it at every layout, once the image has loaded).
        slides.append(
            f'<section class="icm-figure"><img class="r-stretch" '
            f'src="{html.escape(figure["src"])}" '
            f'alt="{html.escape(figure["alt"], quote=True)}">'
            f'<p class="icm-caption"><strong>{number}</strong> {figure["caption"]}</p>'
            f'</section>')
    if content["takeaways"]:
        slides += _text_slides("Key takeaways", content["takeaways"], room)
    if content["exercises"]:
        items = "".join(f"<li>{html.escape(e)}</li>" for e in content["exercises"])
        slides += _text_slides("Exercises", f"<ul>{items}</ul>", room)
    return slides


def deck_html(content, chapter_number, room=TEXT_ROOM):
    """A deck's HTML page.

    Args:
      content: what `chapter_slides` read.
      chapter_number: the chapter's number in the book.
      room: the height a slide has for its text (see `TEXT_ROOM`).

    Returns:
      The page's text.
    """
    title = html.escape(content["title"])
    slides = deck_slides(content, chapter_number, room)
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1.0">
<title>{chapter_number}. {title}: slides</title>
<link rel="stylesheet" href="reveal/dist/reset.css">
<link rel="stylesheet" href="reveal/dist/reveal.css">
<link rel="stylesheet" href="reveal/dist/theme/white.css">
<style>{_STYLE}</style>
</head>
<body>
<div class="reveal"><div class="slides">
{chr(10).join(slides)}
</div></div>
<script src="reveal/dist/reveal.js"></script>
<script src="reveal/dist/plugin/math.js"></script>
<script>
Reveal.initialize({{
  hash: true,
  width: {SLIDE_WIDTH},
  height: {SLIDE_HEIGHT},
  plugins: [RevealMath.MathJax3],
  mathjax3: {{mathjax: "mathjax/tex-mml-chtml.js",
             tex: {{inlineMath: [["\\\\(", "\\\\)"]], displayMath: [["\\\\[", "\\\\]"]]}}}}
}});
</script>
</body>
</html>
"""


def _figure_source(html_dir, page, src):
    """The file of a figure a page shows, which must be a file of the built book."""
    source = pathlib.Path(os.path.realpath(page.parent / src))
    book = pathlib.Path(os.path.realpath(html_dir))
    if book not in source.parents or not source.is_file():
        raise SlidesError(f"{page}: the figure {src[:200]!r} is not a file of the built "
                          f"book {html_dir}")
    return source


def build_slides(html_dir, out, root=None, force=False):
    """Writes one deck per chapter into `out`, with what they need to work offline.

    Args:
      html_dir: the built book's HTML folder (with `book/<chapter>.html` and
        `_static/vendor`).
      out: the decks' folder: new, empty, or one icm wrote (whose contents the decks
        replace); never `html_dir`, inside it or holding it.
      root: the project's folder (default: this package's), for the chapters' order.
      force: write into an existing folder that icm did not write (its other files
        stay).

    Returns:
      The decks' paths, in the book's order.

    Raises:
      SlidesError: for a folder that is not a built book.
      icm.files.DestinationError: for an `out` refused, before any work.
    """
    force = _validate.boolean("force", force)
    out = files.check_folder(out, force=force, inputs=[html_dir], what="--out",
                             command=COMMAND)
    html_dir = records.input_folder(html_dir, "the built book's folder",
                                    "build it first (make book)")
    vendor = html_dir / "_static" / "vendor"
    if not (vendor / "reveal" / "dist" / "reveal.js").is_file() or \
            not (vendor / "mathjax").is_dir():
        raise SlidesError(f"{html_dir} is not a built book with the vendored reveal.js "
                          f"and MathJax (_static/vendor): build it with `make book`")
    names = [name for name, _ in (chapters() if root is None else chapters(root))]
    pages = [html_dir / "book" / f"{name}.html" for name in names]
    for page in pages:
        if not page.is_file():
            raise SlidesError(f"{page} is missing: build the book first")
    with files.staged(out, replace=True, command=COMMAND) as staging:
        (staging / "images").mkdir()
        shutil.copytree(vendor / "reveal", staging / "reveal", symlinks=True)
        shutil.copytree(vendor / "mathjax", staging / "mathjax", symlinks=True)
        decks, titles = [], []
        for number, (name, page) in enumerate(zip(names, pages), 1):
            content = chapter_slides(page)
            for figure in content["figures"]:
                if figure["src"].startswith("data:"):
                    continue
                source = _figure_source(html_dir, page, figure["src"])
                shutil.copyfile(source, staging / "images" / source.name)
                figure["src"] = f"images/{source.name}"
            files.write_text(staging / f"{name}.html", deck_html(content, number))
            decks.append(out / f"{name}.html")
            titles.append(content["title"])  # for the index: each page is read once
        items = "".join(f'<li><a href="{deck.name}">{i}. {html.escape(title)}</a></li>'
                        for i, (deck, title) in enumerate(zip(decks, titles), 1))
        files.write_text(
            staging / "index.html",
            f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>Slides'
            f'</title></head><body><h1>Intrinsic motivation on the iCub: the slides</h1>'
            f'<ol>{items}</ol></body></html>\n')
    return decks
