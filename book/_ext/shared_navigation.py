"""Sphinx extension: the left-hand navigation of the pages that are not chapters,
computed once per set of relative links rather than once per page.

`sphinx.ext.viewcode` writes a page of highlighted source for each of icm's modules
(about 90, under _modules/), and the book's theme gives each the whole book's
navigation: Sphinx resolves the global table of contents for every one of them, deep-
copying each chapter's tree of headings, about 0.25 s a page, a third of the HTML
build. None of these pages is in the table of contents, so no entry of their
navigation is marked current, and its links differ only by the way back to the
book's pages. This extension wraps the `toctree` function the theme calls and reuses
its result for every page whose links to the book's documents are the same strings:
the source pages of one folder share one. A document's link to itself is "#", so each
document keeps its own navigation, with itself current. The HTML written is byte for
byte what it was (tests/test_shared_navigation.py compares the builds of a small book
with and without it).

Our own code, because neither Sphinx nor the theme caches the navigation across
pages: each page's may differ in what is current, which is never the case here.
"""

PRIORITY = 400
"""Before the theme's own handlers (priority 500), which call `toctree` while they
prepare the page."""


def share_navigation(app, pagename, templatename, context, doctree):
    toctree = context.get("toctree")
    if toctree is None:
        return
    links = tuple(context["pathto"](doc) for doc in sorted(app.builder.env.all_docs))
    cache = app.builder.__dict__.setdefault("_icm_shared_navigation", {})

    def shared_toctree(**kwargs):
        key = (links, tuple(sorted((k, repr(v)) for k, v in kwargs.items())))
        if key not in cache:
            cache[key] = toctree(**kwargs)
        return cache[key]

    context["toctree"] = shared_toctree


def setup(app):
    app.connect("html-page-context", share_navigation, priority=PRIORITY)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
