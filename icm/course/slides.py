"""One reveal.js slide deck per chapter, made from the built book's pages: the
chapter's title, its learning objectives (the block of class `icm-objectives`), each
of its figures with its caption, its key takeaways (the block of class
`icm-takeaways`) and the list of its exercises. Nothing is typed a second time: a
deck changes when its chapter does.

    python -m icm.course slides _build/html --out _build/slides     (make slides)

The decks work offline: reveal.js (and MathJax, for the formulas) come from the
book's vendored copies (`book/_static/vendor`, copied into the built book's
`_static`), the figures are copied beside the decks. Open `index.html`.
"""

import html
import pathlib
import shutil

from icm.course.assign import chapters

OBJECTIVES = "icm-objectives"
"""The class of a chapter's learning-objectives block."""
TAKEAWAYS = "icm-takeaways"
"""The class of a chapter's key-takeaways block."""
_STYLE = """
.reveal h1 { font-size: 1.9em; }
.reveal h2 { font-size: 1.3em; }
.reveal section { text-align: left; }
.reveal .icm-title { text-align: center; }
.reveal figure { margin: 0; text-align: center; }
.reveal figure img { max-height: 62vh; max-width: 100%; margin: 0 auto; }
.reveal figcaption { font-size: 0.42em; line-height: 1.35; text-align: left; margin-top: 0.4em; }
.reveal ul { font-size: 0.8em; }
.reveal .icm-source { font-size: 0.45em; color: #555; }
"""


class SlidesError(ValueError):
    """A built book the decks cannot be made from."""


def _soup(path):
    from bs4 import BeautifulSoup

    return BeautifulSoup(path.read_text(encoding="utf-8"), "html.parser")


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


def deck_html(content, chapter_number):
    """A deck's HTML page.

    Args:
      content: what `chapter_slides` read.
      chapter_number: the chapter's number in the book.

    Returns:
      The page's text.
    """
    title = html.escape(content["title"])
    slides = [f'<section class="icm-title"><h1>{chapter_number}. {title}</h1>'
              f'<p class="icm-source">Intrinsic motivation on the iCub: the chapter\'s '
              f'figures and its summary, from the book</p></section>']
    if content["objectives"]:
        slides.append(f"<section><h2>Learning objectives</h2>{content['objectives']}</section>")
    for figure in content["figures"]:
        number = html.escape(figure["number"])
        slides.append(
            f'<section><figure><img src="{html.escape(figure["src"])}" '
            f'alt="{html.escape(figure["alt"], quote=True)}">'
            f'<figcaption><strong>{number}</strong> {figure["caption"]}</figcaption>'
            f'</figure></section>')
    if content["takeaways"]:
        slides.append(f"<section><h2>Key takeaways</h2>{content['takeaways']}</section>")
    if content["exercises"]:
        items = "".join(f"<li>{html.escape(e)}</li>" for e in content["exercises"])
        slides.append(f"<section><h2>Exercises</h2><ul>{items}</ul></section>")
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
  plugins: [RevealMath.MathJax3],
  mathjax3: {{mathjax: "mathjax/tex-mml-chtml.js",
             tex: {{inlineMath: [["\\\\(", "\\\\)"]], displayMath: [["\\\\[", "\\\\]"]]}}}}
}});
</script>
</body>
</html>
"""


def build_slides(html_dir, out, root=None):
    """Writes one deck per chapter into `out`, with what they need to work offline.

    Args:
      html_dir: the built book's HTML folder (with `book/<chapter>.html` and
        `_static/vendor`).
      out: the decks' folder (emptied first).
      root: the project's folder (default: this package's), for the chapters' order.

    Returns:
      The decks' paths, in the book's order.

    Raises:
      SlidesError: for a folder that is not a built book.
    """
    html_dir = pathlib.Path(html_dir)
    vendor = html_dir / "_static" / "vendor"
    if not (vendor / "reveal" / "dist" / "reveal.js").exists():
        raise SlidesError(f"{html_dir} is not a built book with the vendored reveal.js "
                          f"(_static/vendor/reveal): build it with `make book`")
    out = pathlib.Path(out)
    if out.exists():
        shutil.rmtree(out)
    (out / "images").mkdir(parents=True)
    shutil.copytree(vendor / "reveal", out / "reveal")
    shutil.copytree(vendor / "mathjax", out / "mathjax")
    names = [name for name, _ in (chapters() if root is None else chapters(root))]
    decks, titles = [], []
    for number, name in enumerate(names, 1):
        page = html_dir / "book" / f"{name}.html"
        if not page.exists():
            raise SlidesError(f"{page} is missing: build the book first")
        content = chapter_slides(page)
        for figure in content["figures"]:
            if figure["src"].startswith("data:"):
                continue
            source = (page.parent / figure["src"]).resolve()
            target = out / "images" / source.name
            shutil.copyfile(source, target)
            figure["src"] = f"images/{source.name}"
        deck = out / f"{name}.html"
        deck.write_text(deck_html(content, number), encoding="utf-8")
        decks.append(deck)
        titles.append(content["title"])  # for the index: each page is read once
    items = "".join(f'<li><a href="{deck.name}">{i}. {html.escape(title)}</a></li>'
                    for i, (deck, title) in enumerate(zip(decks, titles), 1))
    (out / "index.html").write_text(
        f'<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8"><title>Slides</title>'
        f'</head><body><h1>Intrinsic motivation on the iCub: the slides</h1><ol>{items}'
        f'</ol></body></html>\n', encoding="utf-8")
    return decks
