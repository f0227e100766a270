"""Sphinx extension: the book's pages for every reader (WCAG 2.1 AA, checked by
axe-core in tests/test_browser.py).

1. **Alternative text from the figures themselves.** The library's figures
   (`icm.figures`) say what they show, in words, in their PNG output's metadata
   (``{"image/png": {"alt": ...}}``, IPython's `_repr_png_` metadata). MyST-NB 1.4
   takes an image's ``alt`` only from the cell's metadata (``mystnb: image: alt:``),
   and Sphinx then falls back to the file name; here the output's ``alt`` is used
   where the cell gives none, so a notebook cannot forget it. A cell's own
   ``mystnb.image.alt`` still wins.
2. **Bibliography entries as list items.** Docutils writes the references as
   ``<div role="list">`` holding ``<div role="doc-biblioentry">``, a role that is
   deprecated and not a list item (axe: aria-required-children, critical); the
   entries become ``role="listitem"``.
"""

from myst_nb.core.render import NbElementRenderer

_render_image = NbElementRenderer.render_image


def render_image(self, data):
    """MyST-NB's image rendering, with the output metadata's ``alt`` as the image's
    alternative text where the cell's metadata gives none."""
    nodes = _render_image(self, data)
    alt = data.output_metadata.get(data.mime_type, {}).get("alt")
    if alt and nodes and "alt" not in nodes[0].attributes:
        nodes[0]["alt"] = str(alt)
    return nodes


def bibliography_items(app, pagename, templatename, context, doctree):
    body = context.get("body")
    if body and 'role="doc-biblioentry"' in body:
        context["body"] = body.replace('role="doc-biblioentry"', 'role="listitem"')


def setup(app):
    NbElementRenderer.render_image = render_image
    app.connect("html-page-context", bibliography_items)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
