"""Sphinx extension for the book's offline HTML.

1. Drops repeated <script> entries from each page: sphinx-thebe registers its inline
   configuration once per reading pass, and a second pass (sphinxcontrib-bibtex asks
   for one) makes `const THEBE_JS_URL` appear twice, a JavaScript error.
2. Loads `mathjax-v2-shim.js` first: the ipywidgets HTML manager typesets through
   MathJax 2's `MathJax.Hub.Queue`, which MathJax 3 no longer has.
3. Loads Vega, Vega-Lite and vega-embed (about 0.8 MB) only on the pages that have a
   static panel (`icm.figures.static_panels`: an element of class `icm-static-panel`),
   deferred, so that they never delay the page's first paint; a panel waits for
   them (`static_panels._EMBED`).
4. Loads MathJax (1.2 MB) only on the pages that show a formula. Sphinx also loads it
   on a page whose table of contents includes a page with one (the preface, which
   lists every chapter), where it typesets nothing.
"""

VEGA_SCRIPTS = ("vendor/vega/vega.min.js", "vendor/vega/vega-lite.min.js",
                "vendor/vega/vega-embed.min.js")
"""The static panels' scripts, in the order they must run (under `html_static_path`)."""
PANEL_MARKER = 'class="icm-static-panel"'


def _key(script):
    # An inline script may be registered with filename None or "": the same script.
    filename = getattr(script, "filename", script) or ""
    attributes = getattr(script, "attributes", {}) or {}
    return str(filename), tuple(sorted((k, str(v)) for k, v in attributes.items()))


def dedupe_scripts(app, pagename, templatename, context, doctree):
    scripts = context.get("script_files")
    if not scripts:
        return
    seen, unique = set(), []
    for script in scripts:
        key = _key(script)
        if key not in seen:
            seen.add(key)
            unique.append(script)
    context["script_files"] = unique


def vega_where_needed(app, pagename, templatename, context, doctree):
    if PANEL_MARKER in (context.get("body") or ""):
        for script in VEGA_SCRIPTS:
            app.add_js_file(script, loading_method="defer")


def mathjax_where_needed(app, pagename, templatename, context, doctree):
    scripts = context.get("script_files")
    body = context.get("body") or ""
    if not scripts or 'class="math' in body:
        return
    mathjax = app.config.mathjax_path

    def is_mathjax(script):
        filename = str(getattr(script, "filename", script) or "")
        inline = str((getattr(script, "attributes", {}) or {}).get("body", ""))
        return (mathjax and filename.endswith(mathjax)) or inline.startswith("window.MathJax")

    context["script_files"] = [script for script in scripts if not is_mathjax(script)]


def setup(app):
    app.add_js_file("mathjax-v2-shim.js", priority=100)
    app.connect("html-page-context", vega_where_needed)
    app.connect("html-page-context", mathjax_where_needed, priority=900)
    app.connect("html-page-context", dedupe_scripts, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
