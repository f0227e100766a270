"""Sphinx extension for the book's offline HTML.

1. Drops repeated <script> entries from each page: sphinx-thebe registers its inline
   configuration once per reading pass, and a second pass (sphinxcontrib-bibtex asks
   for one) makes `const THEBE_JS_URL` appear twice, a JavaScript error.
2. Loads `mathjax-v2-shim.js` first: the ipywidgets HTML manager typesets through
   MathJax 2's `MathJax.Hub.Queue`, which MathJax 3 no longer has.
"""


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


def setup(app):
    app.add_js_file("mathjax-v2-shim.js", priority=100)
    app.connect("html-page-context", dedupe_scripts, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
