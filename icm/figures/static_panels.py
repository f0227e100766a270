"""Static interactive panels: Vega-Lite figures whose sliders redraw them in the browser,
with no Python kernel, from a grid of settings computed beforehand
(`icm.experiments.panel_data.precompute`).

Each figure is a Vega-Lite specification, a declarative description written here as
a plain dict: each slider is a parameter bound to a range input, and the marks draw
the rows of the precomputed data whose setting equals the sliders' values. (Altair
builds the same specifications, and the tests check ours against its Vega-Lite
schema; the library does not import it, which would cost seconds per notebook.) The book's HTML loads Vega, Vega-Lite and vega-embed from its own
`_static/vendor` folder (no network); in the page, each panel's view is kept in
``window.icmPanels[id]`` and the time it was drawn in ``window.icmPanelTimes`` (the
browser test reads both).
"""

import hashlib
import html
import json
import math
import textwrap

import numpy as np

from icm import _validate
from icm.experiments import panel_data as _panel_data
from icm.figures._common import MIN_TEXT_PX, series_style
from icm.figures.panel_plots import SERIES_COLOURS

DIGITS = 4
"""Decimals kept in the page's data: far finer than a pixel of the figure."""


class StaticPanel:
    """A Vega-Lite figure with its own sliders, for the HTML book.

    Jupyter shows it through its HTML: a div, the Vega-Lite specification as JSON, and
    the call that draws the one into the other once the page's scripts are loaded. In
    a running notebook it shows only a short note (the page's scripts are the book's),
    so use the live `icm.widgets` panels there.

    Attributes:
      spec: the Vega-Lite specification (a dict, data included).
      title: what the panel shows.
      element_id: the id of its div in the page (a hash of the specification).
      print_note: what it says in print instead of its sliders (the settings shown).
    """

    def __init__(self, spec, title, print_note=None):
        if not isinstance(spec, dict) or "$schema" not in spec:
            raise _validate.ArgumentTypeError(f"spec must be a Vega-Lite specification "
                                              f"dict, got {_validate.show(spec)}")
        self.spec = spec
        self.title = _validate.text("title", title)
        self.print_note = _validate.text("print_note", print_note) if print_note is not None \
            else "In print, this figure shows its default settings."
        text = json.dumps(spec, sort_keys=True, separators=(",", ":"))
        self.element_id = "icm-panel-" + hashlib.sha256(text.encode()).hexdigest()[:12]
        self._json = text

    def html(self):
        """The panel as HTML: a div, its specification, and the script that draws it."""
        # No "<" or ">" inside the script element, as JSON escapes: text such as
        # "<!--<script>" in a title would otherwise change how the browser reads the
        # rest of the page (HTML's script-data states).
        spec = self._json.replace("&", "\\u0026").replace("<", "\\u003c").replace(
            ">", "\\u003e")
        note = html.escape(f"{self.title}: this figure is drawn by the book's HTML pages "
                           f"(Vega-Lite). In Jupyter, use the live panel of icm.widgets.")
        return (f'<div class="icm-static-panel" id="{self.element_id}">'
                f'<p class="icm-static-panel-note">{note}</p></div>\n'
                f'<p class="icm-print-note">{html.escape(self.print_note)}</p>\n'
                f'<script type="application/json" id="{self.element_id}-spec">{spec}'
                f'</script>\n<script>{_EMBED % {"id": self.element_id}}</script>')

    def _repr_html_(self):
        return self.html()

    def __repr__(self):
        return f"<StaticPanel {self.title!r}>"


_EMBED = """(function () {
  var id = "%(id)s", tries = 0;
  function draw() {
    if (typeof vegaEmbed === "undefined") {
      if (++tries < 200) { setTimeout(draw, 50); }
      return;
    }
    var spec = JSON.parse(document.getElementById(id + "-spec").textContent);
    var element = document.getElementById(id), wide = (spec.usermeta || {}).icmMinWidth;
    if (spec.hconcat && wide && element.clientWidth < wide) {  // a phone: one below the other
      spec.vconcat = spec.hconcat;
      delete spec.hconcat;
      var room = element.clientWidth - (spec.usermeta.icmMargin || 0), narrowest = room;
      spec.vconcat.forEach(function (view) {  // each as wide as the column allows
        if (view.width > room) {
          view.height = Math.round(view.height * room / view.width);
          view.width = room;
        }
        narrowest = Math.min(narrowest, view.width);
      });
      spec.config = Object.assign({}, spec.config);  // legends under the maps, as long
      spec.config.legend = Object.assign({}, spec.config.legend,  // as the maps are wide
                                         {orient: "bottom", gradientLength: narrowest});
    }
    vegaEmbed("#" + id, spec, {actions: false, renderer: "svg"}).then(function (result) {
      (window.icmPanels = window.icmPanels || {})[id] = result.view;
      (window.icmPanelTimes = window.icmPanelTimes || []).push(performance.now());
    }).catch(function (error) { console.error(error); });
  }
  draw();
})();"""


def _rounded(values):
    return [None if not math.isfinite(v) else round(float(v), DIGITS)
            for v in np.asarray(values, dtype=float)]


def _plain(value):
    return value if isinstance(value, str) else float(value) if not float(value).is_integer() \
        else int(value)


VEGA_LITE_SCHEMA = "https://vega.github.io/schema/vega-lite/v6.json"
"""The Vega-Lite version of the specifications (the vendored vega-lite is 6.4)."""

DATASET = "grid"
"""Name of a static panel's dataset (the precomputed rows) in its specification."""

_CONFIG = {"view": {"stroke": None},
           "title": {"anchor": "start", "fontSize": MIN_TEXT_PX + 1,
                     "subtitleFontSize": MIN_TEXT_PX},
           "axis": {"labelFontSize": MIN_TEXT_PX, "titleFontSize": MIN_TEXT_PX},
           "legend": {"labelFontSize": MIN_TEXT_PX, "titleFontSize": MIN_TEXT_PX,
                      "symbolOpacity": 1, "symbolStrokeWidth": 3, "symbolSize": 300,
                      "labelLimit": 400},
           "text": {"fontSize": MIN_TEXT_PX}}
"""No text smaller than the book's caption text (`MIN_TEXT_PX`), and legend swatches
drawn at full strength."""

_DASHES = {"-": [1, 0], "--": [8, 4], "-.": [10, 4, 2, 4], ":": [2, 3]}
"""Vega's stroke dash of each matplotlib line style."""


def _controls(spec):
    """Vega-Lite parameters for the panel's sliders and choices, and the filter that
    keeps the rows of the setting they show."""
    params, tests = [], []
    for name, values in spec.sliders.items():
        params.append(_slider(name, values, spec.defaults[name], spec.setting(name).label))
        tests.append(f"abs(datum.{name} - {name}) < 1e-6")
    for name, options in spec.choices.items():
        params.append({"name": name, "value": spec.defaults[name],
                       "bind": {"input": "radio", "options": list(options),
                                "name": spec.setting(name).label + " "}})
        tests.append(f"datum.{name} == {name}")
    return params, " && ".join(tests)


def _print_note(spec, params):
    """What a printed panel says instead of its sliders: the settings it shows."""
    shown = "; ".join(f"{spec.setting(p['name']).label} {_plain(spec.defaults[p['name']])}"
                      for p in params)
    return (f"Printed at its default settings ({shown}). In the HTML book, its sliders "
            f"redraw it for the other settings, from numbers computed beforehand.")


def _slider(name, values, default, label):
    """A parameter bound to a range input over the evenly spaced `values`, labelled in
    words (`label`, the setting's)."""
    step = round(values[1] - values[0], 10) if len(values) > 1 else 1
    return {"name": name, "value": _plain(default),
            "bind": {"input": "range", "min": _plain(values[0]), "max": _plain(values[-1]),
                     "step": _plain(step), "name": label + " "}}


def _specification(rows, params, transform, body, description):
    return {"$schema": VEGA_LITE_SCHEMA, "description": description,
            "data": {"name": DATASET}, "datasets": {DATASET: rows}, "params": params,
            "transform": transform, "config": _CONFIG, **body}


def _lines(text, width=34):
    """`text` as lines of at most `width` characters (a Vega title does not wrap)."""
    return textwrap.wrap(text, width)


def curves_rows(grid):
    """The page's data of a curves panel: one row per setting and series, the series'
    points as arrays (x, mean, low, high)."""
    _validate.instance("grid", grid, _panel_data.PanelGrid,
                       "a PanelGrid (from icm.experiments.panel_data.precompute)")
    rows = []
    for setting, curves in zip(grid.settings, grid.curves):
        x = [int(v) for v in curves["x"]]
        for group in curves["groups"]:
            for series, (mean, low, high) in group["series"].items():
                rows.append({**{k: _plain(v) for k, v in setting.items()},
                             "series": series, "x": x, "mean": _rounded(mean),
                             "low": _rounded(low), "high": _rounded(high)})
    return rows


def curves_panel(grid, width="container", height=280):
    """The static version of a curves panel (Figures 5, 6 and 7): a line and a 95% band
    per series, for the setting its sliders show.

    Args:
      grid: a `PanelGrid` of "figure5", "figure6" or "figure7".
      width, height: size of the plot in pixels; the width may be "container", as
        wide as the page's column (so that a phone shows the panel whole).

    Returns:
      A `StaticPanel`.
    """
    _validate.instance("grid", grid, _panel_data.PanelGrid,
                       "a PanelGrid (from icm.experiments.panel_data.precompute)")
    if width != "container":
        width = _validate.integer("width", width, 200, 2000)
    height = _validate.integer("height", height, 100, 2000)
    spec = grid.spec
    rows = curves_rows(grid)
    first = grid.curves[0]
    group = first["groups"][0]
    names = list(group["series"])
    colour = {"field": "series", "type": "nominal",
              "scale": {"domain": names,
                        "range": [SERIES_COLOURS[n.split()[0]] for n in names]}}
    # Each series also has its own dash, shown in the legend with its colour: no two
    # series differ by colour alone ("red" and "red toppled" included).
    dash = {"field": "series", "type": "nominal",
            "scale": {"domain": names,
                      "range": [_DASHES[series_style(n)["linestyle"]] for n in names]}}
    top = max(max(v for v in row["high"] if v is not None) for row in rows)
    x = {"field": "x", "type": "quantitative", "title": first["xlabel"],
         "scale": {"domain": [int(first["x"][0]), int(first["x"][-1])]}}
    params, keep = _controls(spec)
    # One legend for the layers (the same definition in each, or Vega-Lite warns),
    # its swatches at full strength (_CONFIG) with each series' colour and dash.
    legend = {"title": None, "orient": "top", "symbolType": "stroke", "columns": 2}
    band = {"mark": {"type": "area", "opacity": 0.2},
            "encoding": {"x": x, "y": {"field": "low", "type": "quantitative",
                                       "scale": {"domain": [0, top * 1.02], "nice": False},
                                       "title": group["ylabel"]},
                         "y2": {"field": "high"}, "color": {**colour, "legend": legend}}}
    tooltip = [{"field": "series", "type": "nominal"},
               {"field": "x", "type": "quantitative", "title": first["xlabel"]}] + \
        [{"field": f, "type": "quantitative", "format": ".3f"} for f in ("mean", "low", "high")]
    line = {"mark": {"type": "line", "strokeWidth": 2},
            "encoding": {"x": x, "y": {"field": "mean", "type": "quantitative"},
                         "color": {**colour, "legend": legend},
                         "strokeDash": {**dash, "legend": legend},
                         "tooltip": tooltip}}
    title = f"{spec.title}, {spec.fixed['n_seeds']} seeds per setting, 95% bands"
    body = {"title": _lines(title), "width": width, "height": height,
            "autosize": {"type": "fit-x", "contains": "padding"}, "layer": [band, line]}
    transform = [{"filter": keep}, {"flatten": ["x", "mean", "low", "high"]}]
    description = (
        f"{title}. A line chart of {group['ylabel']} against {first['xlabel']}, one line "
        f"and 95% band per series: " + "; ".join(
            f"{n} ({'solid' if series_style(n)['linestyle'] == '-' else 'dashed'} line)"
            for n in names) + ". The sliders under it choose the setting: "
        + ", ".join(spec.setting(name).label for name in [p["name"] for p in params]) + ".")
    return StaticPanel(_specification(rows, params, transform, body, description), title,
                       _print_note(spec, params))


def sweep_rows(grid):
    """The page's data of the sweep panel: one row per setting of the Figure 5 grid with
    its `sweep_cell` numbers."""
    _validate.instance("grid", grid, _panel_data.PanelGrid,
                       "a PanelGrid (from icm.experiments.panel_data.precompute)")
    if grid.cells is None:
        raise ValueError(f"grid must be the figure5 grid (its runs give the sweep), got "
                         f"the {grid.name} grid")
    rows = []
    for setting, cell in zip(grid.settings, grid.cells):
        row = {k: _plain(v) for k, v in setting.items()}
        row.update({k: (None if not math.isfinite(v) else round(float(v), DIGITS))
                    for k, v in cell.items()})
        rows.append(row)
    return rows


def sweep_panel(grid, cell=52):
    """The static epsilon x window sweep: for the new-task factor its slider shows, two
    heatmaps over epsilon and window, the mean mastery gap (green - red, trials) and
    the share of seeds that master red first, each cell labelled with its number.
    A heatmap whose every cell, at every setting of the slider, holds the same number
    says nothing: the share of red first is then said in the panel's title instead of
    drawn (in the book's grid, every seed of every setting masters red first).

    Args:
      grid: the "figure5" `PanelGrid` (the sweep reuses its runs).
      cell: size of a heatmap cell in pixels.

    Returns:
      A `StaticPanel`.
    """
    rows = sweep_rows(grid)
    cell = _validate.integer("cell", cell, 20, 200)
    spec = grid.spec
    params = [_slider("new_task_factor", spec.sliders["new_task_factor"],
                      spec.defaults["new_task_factor"], spec.setting("new_task_factor").label)]
    axes = {"x": {"field": "epsilon", "type": "ordinal", "title": "epsilon",
                  "axis": {"labelAngle": 0}},
            "y": {"field": "window", "type": "ordinal", "title": "window k",
                  "sort": "descending"}}
    gaps = [r["gap"] for r in rows if r["gap"] is not None]
    maps = [("gap", "Mean mastery gap (green - red, trials)", [min(gaps), max(gaps)], ".1f")]
    red_first = {r["red_first"] for r in rows}
    if len(red_first) > 1:
        maps.append(("red_first_percent", "Seeds mastering red first (%)", [0, 100], ".0f"))
    heatmaps = []
    for field, title, domain, fmt in maps:
        tooltip = [{"field": "epsilon", "type": "ordinal"},
                   {"field": "window", "type": "ordinal"},
                   {"field": field, "type": "quantitative", "format": fmt}]
        if field == "gap":
            tooltip += [{"field": "gap_low", "type": "quantitative", "format": ".1f",
                         "title": "95% band from"},
                        {"field": "gap_high", "type": "quantitative", "format": ".1f",
                         "title": "to"},
                        {"field": "gap_seeds", "type": "quantitative",
                         "title": "seeds mastering both"}]
        rect = {"mark": "rect", "encoding": {**axes, "tooltip": tooltip, "color": {
            "field": field, "type": "quantitative",
            "scale": {"scheme": "viridis", "domain": domain},
            "legend": {"title": None, "format": fmt}}}}
        middle = (domain[0] + domain[1]) / 2
        text = {"mark": {"type": "text", "fontSize": MIN_TEXT_PX}, "encoding": {
            **axes, "text": {"field": field, "type": "quantitative", "format": fmt},
            "color": {"condition": {"test": f"datum.{field} < {middle}", "value": "white"},
                      "value": "black"}}}
        heatmaps.append({"title": _lines(title, 30), "width": cell * len(spec.sliders["epsilon"]),
                         "height": cell * len(spec.sliders["window"]),
                         "layer": [rect, text]})
    title = (f"The epsilon x window sweep, {spec.fixed['n_seeds']} seeds per cell, "
             f"{spec.fixed['n_trials']} trials")
    transform = [{"filter": "abs(datum.new_task_factor - new_task_factor) < 1e-6"},
                 {"calculate": "100 * datum.red_first", "as": "red_first_percent"}]
    cells = (f"over epsilon (columns: {', '.join(f'{v:g}' for v in spec.sliders['epsilon'])})"
             f" and the window k (rows: "
             f"{', '.join(f'{v:g}' for v in spec.sliders['window'])}), each cell labelled "
             f"with its number")
    slider = f"The slider under it chooses the {spec.setting('new_task_factor').label}."
    # Side by side where the page is wide enough (about cells + axis + legend each),
    # else one below the other, each as wide as the column allows (the page's script
    # reads usermeta.icmMinWidth).
    wide = len(heatmaps) * (cell * len(spec.sliders["epsilon"]) + 170) + 20
    body = {"title": _lines(title), "hconcat": heatmaps,
            "resolve": {"scale": {"color": "independent"}},
            "usermeta": {"icmMinWidth": wide, "icmMargin": 90}}
    if len(heatmaps) == 1:  # red first is the same everywhere: said, not drawn
        share = f"{100 * red_first.pop():.0f}%"
        said = (f"Red mastered first: {share} of the seeds in every cell, at every "
                f"{spec.setting('new_task_factor').label}")
        body["title"] = _lines(title) + _lines(said + ".")
        description = (f"{title}. A heatmap {cells}: the mean mastery gap, green minus "
                       f"red, in trials. {said}, so that share is not drawn. {slider}")
    else:
        description = (f"{title}. Two heatmaps {cells}: the mean mastery gap, green minus "
                       f"red, in trials, and the share of seeds that master red first. "
                       f"{slider}")
    return StaticPanel(_specification(rows, params, transform, body, description), title,
                       _print_note(spec, params))
