"""Shared pieces of the figures: a Figure that displays itself (with its alternative
text, and text large enough to read where it is shown), colours and line styles that
do not rely on colour alone, mean bands."""

import collections
import io
import re
import threading

import matplotlib.axes
import matplotlib.collections
import matplotlib.figure
import matplotlib.image
import matplotlib.layout_engine
import matplotlib.patches
import matplotlib.text
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg, RendererAgg

from icm import _validate, stats

TASK_COLOURS = {"red": "#d62728", "green": "#2ca02c"}
"""The paper's names for its tasks and their colours. Red and green are the hardest
pair for the most common colour blindness (deuteranomaly), so no figure tells them
apart by colour alone: see `SERIES_STYLES`."""

SERIES_STYLES = {"red": {"linestyle": "-", "marker": "o"},
                 "green": {"linestyle": "--", "marker": "s"},
                 "blue": {"linestyle": "-.", "marker": "^"}}
"""How each task or rod's line looks besides its colour: a line style and a marker, so
that a figure reads the same in grey or to a reader who does not see red and green
apart (checked with a simulation of colour blindness)."""

_LAYOUT_ENGINES = (matplotlib.layout_engine.ConstrainedLayoutEngine,
                   matplotlib.layout_engine.TightLayoutEngine)
"""The layouts that savefig runs a pass of before drawing (as `Figure.png` does)."""

DISPLAY_WIDTH_PX = 740
"""The widest a figure is shown: the book's text column at a 1366 px laptop screen
(about 741 px) and about a notebook's output area. A wider PNG is scaled down to it."""

MIN_TEXT_PX = 16
"""The smallest text a figure may show, in screen pixels where it is shown: the book's
caption text (16 px; tests/test_browser.py measures both in the built book)."""

_RENDERERS = collections.OrderedDict()
"""The Agg renderers of the last `_KEPT_RENDERERS` sizes `Figure.png` drew at, by
(width px, height px, dpi). Matplotlib keeps its text metrics per renderer, so a new
renderer for each figure measures every text again: a live panel, a new figure on
every slider move, draws its PNG about 15% faster with the renderer kept (the pixels
are the same; benchmarks/bench.py times it)."""
_KEPT_RENDERERS = 4
_RENDERER_LOCK = threading.Lock()
"""Held while a kept renderer draws and its pixels are written: one drawing at a
time on it."""


def series_style(name):
    """The line style and marker of a series named after a task or rod ("red",
    "green toppled", ...): `SERIES_STYLES` of its first word, with a dotted line for a
    second series of the same colour ("... toppled")."""
    style = dict(SERIES_STYLES.get(str(name).split()[0], {"linestyle": "-", "marker": None}))
    if str(name).endswith("toppled"):
        style["linestyle"] = ":"
        style["marker"] = {"o": "D", "^": "v", "s": "P"}.get(style["marker"], "x")
    return style


class Figure(matplotlib.figure.Figure):
    """A matplotlib Figure that Jupyter displays as a PNG without pyplot's help, with
    its alternative text and its text large enough to read.

    `png_dpi` sets its resolution; `quick_png` trades file size for speed (light
    compression), for figures that are redrawn on every slider move.

    **Alternative text.** The PNG output carries, in its metadata, what the figure shows
    in words (`alt_text()`): the figure function's own sentence about its data
    (`summary`, set with `describe`), then the panels, their axes and their labelled
    series, read from the figure itself. The book's build puts it in the page's `alt`
    (book/_ext/accessible_html.py), so no notebook can forget it.

    **Readable text.** Before it is drawn, every text smaller than `min_text_points()`
    is raised to it: `MIN_TEXT_PX` screen pixels once the PNG is shown at most
    `DISPLAY_WIDTH_PX` wide. The PNG records the smallest text it holds, in its own
    pixels (`icm:smallest-text-px`), and how many data points its legends cover
    (`icm:legend-overlaps`) and how many of its texts overlap (`icm:text-overlaps`),
    which the book's browser test reads, and how many texts written on a box (a patch
    such as a box, a cell or a button) run out of it (`icm:text-outside-box`).

    **One drawing.** `png()` draws the figure once (after a layout pass without
    rendering, as savefig makes, for a figure with a layout engine): the text is
    fitted before (tick labels need no drawing to be known), the measures are read
    from that drawing's renderer, at the PNG's resolution, and the PNG is written
    from its pixels.
    """

    png_dpi = 110
    quick_png = False
    summary = None

    def describe(self, summary):
        """Sets what the figure shows, in words (a sentence or two from its data), the
        start of its alternative text; returns the figure."""
        self.summary = _validate.text("summary", summary)
        return self

    def alt_text(self):
        """What the figure shows, in words: `summary`, then its panels (title, axes,
        labelled series with their line styles)."""
        parts = [self.summary] if self.summary else []
        panels = [ax for ax in self.axes if ax.get_visible() and ax.get_label() != "<colorbar>"]
        described = [_describe_axes(ax) for ax in panels]
        described = [text for text in described if text]
        if len(described) > 1:
            parts.append(f"{len(described)} panels. " + " ".join(
                f"Panel {i + 1}: {text}" for i, text in enumerate(described)))
        elif described:
            parts.append(described[0])
        suptitle = self._suptitle.get_text() if self._suptitle is not None else ""
        if suptitle:
            parts.insert(0, suptitle.rstrip(".") + ".")
        text = " ".join(parts) or "A figure."
        return re.sub(r"\s+", " ", text.replace("$", "")).strip()

    def min_text_points(self):
        """The smallest font size (points) this figure may use: `MIN_TEXT_PX` on screen
        when its PNG is shown at most `DISPLAY_WIDTH_PX` wide."""
        width_px = self.get_figwidth() * self.png_dpi
        scale = min(1.0, DISPLAY_WIDTH_PX / width_px)
        return MIN_TEXT_PX * 72.0 / (self.png_dpi * scale)

    def fit_text(self):
        """Raises every visible text smaller than `min_text_points()` to it (tick
        labels included: asking an axis for them makes them, without a drawing)."""
        floor = self.min_text_points()
        for ax in self.axes:
            for axis, name in ((ax.xaxis, "x"), (ax.yaxis, "y")):
                for which, labels in (("major", axis.get_majorticklabels()),
                                      ("minor", axis.get_minorticklabels())):
                    sizes = [label.get_fontsize() for label in labels]
                    if sizes and min(sizes) < floor - 1e-9:
                        ax.tick_params(axis=name, which=which, labelsize=floor)
        for text in _texts(self):
            if text.get_fontsize() < floor - 1e-9:
                text.set_fontsize(floor)

    def measures(self, renderer=None):
        """What the browser test reads from the PNG: the smallest text in the PNG's
        pixels, the data points (line vertices, marker and scatter positions) that
        a legend covers, the pairs of texts that overlap, and the texts that run out of
        the box they are written on (`texts_outside_boxes`). `renderer`: that of the
        drawing the PNG is made of (without one, nothing is placed: 0 overlaps)."""
        sizes = [text.get_fontsize() for text in _texts(self)]
        smallest = min(sizes) * self.png_dpi / 72.0 if sizes else 0.0
        return {"icm:smallest-text-px": f"{smallest:.4f}",
                "icm:legend-overlaps": str(_legend_overlaps(self, renderer)),
                "icm:text-overlaps": str(_text_overlaps(self, renderer)),
                "icm:text-outside-box": str(len(texts_outside_boxes(self, renderer)))}

    def png(self):
        """The figure as PNG bytes, drawn once at `png_dpi`, with its text fitted
        (`fit_text`) and, in the PNG's text chunks, its alternative text
        (`Description`) and `measures()` of that very drawing. A `quick_png` figure
        (redrawn on every slider move) skips the fitting and the measures and is
        compressed lightly."""
        if not self.quick_png:
            self.fit_text()
        dpi = self.dpi
        self.dpi = self.png_dpi  # as savefig(dpi=png_dpi) does, for this drawing
        try:
            canvas = FigureCanvasAgg(self)
            if isinstance(self.get_layout_engine(), _LAYOUT_ENGINES):
                # As savefig does: a layout pass without rendering first, so that the
                # constrained layout places what it learned from the first (a figure
                # legend, wrapped titles); without it a figure's top titles were cut.
                self.draw_without_rendering()
            with _RENDERER_LOCK:
                _keep_renderer(canvas)
                canvas.draw()
                metadata = None if self.quick_png else {
                    "Description": self.alt_text(), **self.measures(canvas.get_renderer())}
                buffer = io.BytesIO()
                # What savefig's PNG writer does after its own drawing (backend_agg's
                # _print_pil): the pixels just drawn, written with their metadata.
                matplotlib.image.imsave(
                    buffer, canvas.buffer_rgba(), format="png", origin="upper",
                    dpi=self.png_dpi, metadata=metadata,
                    pil_kwargs={"compress_level": 1} if self.quick_png else None)
        finally:
            self.dpi = dpi
        return buffer.getvalue()

    def _repr_png_(self):
        """The PNG and, as its metadata, its alternative text (``{"alt": ...}``), which
        the book's build puts in the page."""
        return self.png(), {"alt": self.alt_text()}


def _keep_renderer(canvas):
    """Gives `canvas` the kept renderer of its size and resolution (`_RENDERERS`),
    made the first time; the canvas clears it before it draws."""
    width, height = canvas.get_width_height(physical=True)
    key = (width, height, canvas.figure.dpi)
    renderer = _RENDERERS.pop(key, None)
    if renderer is None:
        renderer = RendererAgg(width, height, canvas.figure.dpi)
    _RENDERERS[key] = renderer
    while len(_RENDERERS) > _KEPT_RENDERERS:
        _RENDERERS.popitem(last=False)
    # FigureCanvasAgg.get_renderer reuses the renderer it holds for the same key.
    canvas.renderer, canvas._lastKey = renderer, key


def _texts(fig):
    """The texts `fig` shows: its own and its suptitle, and per visible axes its
    titles, axis labels and tick labels (where the axis is drawn), texts and
    annotations, legend entries and title; only visible, non-empty ones."""
    found = list(fig.texts) + ([fig._suptitle] if fig._suptitle is not None else [])
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        found += [ax.title, ax._left_title, ax._right_title] + list(ax.texts)
        if ax.axison:
            for axis in (ax.xaxis, ax.yaxis):
                if axis.get_visible():
                    found += [axis.label, axis.get_offset_text()] + _tick_labels(axis)
        legend = ax.get_legend()
        if legend is not None and legend.get_visible():
            found += list(legend.get_texts()) + [legend.get_title()]
    for legend in fig.legends:
        found += list(legend.get_texts()) + [legend.get_title()]
    seen, texts = set(), []
    for text in found:
        if id(text) not in seen and text.get_visible() and text.get_text().strip():
            seen.add(id(text))
            texts.append(text)
    return texts


def _tick_labels(axis):
    """The tick labels `axis` draws: those of ticks inside its view."""
    low, high = sorted(axis.get_view_interval())
    margin = (high - low) * 1e-6
    labels = []
    for tick in axis.get_major_ticks() + axis.get_minor_ticks():
        if low - margin <= tick.get_loc() <= high + margin:
            labels += [label for label, on in ((tick.label1, tick.label1.get_visible()),
                                               (tick.label2, tick.label2.get_visible())) if on]
    return labels


def _text_box(text, renderer):
    """Where `text` is written: its box if it has one, else its letters; an
    annotation's arrow left out (matplotlib counts it in the annotation's extent, so
    two labels whose arrows point at neighbouring things would count as overlapping)."""
    patch = text.get_bbox_patch()
    if patch is not None:
        text.update_bbox_position_size(renderer)
        return patch.get_window_extent(renderer)
    return matplotlib.text.Text.get_window_extent(text, renderer)


def _text_overlaps(fig, renderer):
    """How many pairs of texts overlap (by more than 2 px each way), or reach out of
    the figure."""
    if renderer is None:
        return 0
    boxes = [_text_box(text, renderer) for text in _texts(fig)]
    count = 0
    for i, a in enumerate(boxes):
        if a.x0 < -1 or a.y0 < -1 or a.x1 > fig.bbox.width + 1 or a.y1 > fig.bbox.height + 1:
            count += 1
        for b in boxes[i + 1:]:
            if min(a.x1, b.x1) - max(a.x0, b.x0) > 2 and min(a.y1, b.y1) - max(a.y0, b.y0) > 2:
                count += 1
    return count


def texts_outside_boxes(fig, renderer):
    """The texts written on a box that run out of it: for each text of an axes (its
    `ax.text` and annotations) whose anchor lies on one of the axes' patches (a box, a
    table cell, a button), the smallest such patch, which must hold the whole text
    (the four corners of its extent, 1 px in from each side). A label wider than its
    box reads cut short where it leaves it ("ope" for "open", white on white).
    Returns [(text, patch)] of those that do not fit; [] without a `renderer`."""
    if renderer is None:
        return []
    found = []
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        patches = []
        for patch in ax.patches:
            if not (patch.get_visible() and isinstance(patch, matplotlib.patches.Patch)):
                continue
            path = patch.get_transform().transform_path(patch.get_path())
            patches.append((path, abs(np.prod(np.ptp(path.vertices, axis=0))), patch))
        if not patches:
            continue
        for text in ax.texts:
            if not (text.get_visible() and text.get_text().strip()):
                continue
            anchor = text.get_transform().transform(text.get_unitless_position())
            holding = [(area, path, patch) for path, area, patch in patches
                       if path.contains_point(anchor)]
            if not holding:
                continue
            _, path, patch = min(holding, key=lambda entry: entry[0])
            box = text.get_window_extent(renderer)
            x0, x1 = sorted((box.x0 + 1, box.x1 - 1))
            y0, y1 = sorted((box.y0 + 1, box.y1 - 1))
            corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
            if not path.contains_points(corners).all():
                found.append((text, patch))
    return found


def _legend_overlaps(fig, renderer):
    """How many data points of its axes each legend covers, summed: line vertices,
    markers and scatter offsets (bands and images are not counted)."""
    if renderer is None:
        return 0
    count = 0
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None or not legend.get_visible():
            continue
        box = legend.get_window_extent(renderer)
        for line in ax.get_lines():  # the labelled ones (not faint per-seed curves)
            xy = line.get_xydata()
            if line.get_visible() and len(xy) and not line.get_label().startswith("_"):
                count += box.count_contains(line.get_transform().transform(xy))
        for collection in ax.collections:  # scatter plots' points (not bands, not images)
            offsets = collection.get_offsets()
            if isinstance(collection, matplotlib.collections.PathCollection) \
                    and collection.get_visible() and len(offsets):
                count += box.count_contains(
                    collection.get_offset_transform().transform(offsets))
    return count


def _describe_axes(ax):
    """One panel in words: its title, its axes' labels and ranges, and its labelled
    series (with their line style and marker)."""
    words = []
    title = ax.get_title() or ax.get_title("left")
    if title:
        words.append(f"\"{title}\".")
    for axis, name in ((ax.xaxis, "x"), (ax.yaxis, "y")):
        label = axis.get_label_text()
        if not label or not axis.get_visible():
            continue
        low, high = (ax.get_xlim() if name == "x" else ax.get_ylim())
        words.append(f"{'Horizontal' if name == 'x' else 'Vertical'} axis: {label}, "
                     f"{_number(min(low, high))} to {_number(max(low, high))}.")
    series = []
    for line in ax.get_lines():
        label = line.get_label()
        if label.startswith("_") or not line.get_visible():
            continue
        style = {"-": "solid", "--": "dashed", ":": "dotted", "-.": "dash-dotted"}.get(
            line.get_linestyle(), "")
        marker = line.get_marker()
        marker = {"o": "circles", "s": "squares", "^": "triangles", "D": "diamonds",
                  "v": "down triangles", "P": "pluses", "x": "crosses"}.get(marker, "")
        look = ", ".join(w for w in (f"{style} line" if style else "", marker) if w)
        series.append(f"{label} ({look})" if look else label)
    legend = ax.get_legend()
    if not series and legend is not None:
        series = [t.get_text() for t in legend.get_texts() if t.get_text()]
    if series:
        words.append("Series: " + "; ".join(series) + ".")
    if ax.images and not series:
        words.append("An image.")
    return " ".join(words)


def _number(value):
    return f"{value:.3g}"


def check_result(name, result, cls, made_by):
    """Returns `result` if it is a `cls`, else raises an ArgumentTypeError that says
    which function makes one (`made_by`)."""
    return _validate.instance(name, result, cls, f"a {cls.__name__} (from {made_by})")


def check_axes(ax):
    """Returns `ax` if it is None or a matplotlib Axes, else raises."""
    if ax is not None:
        _validate.instance("ax", ax, matplotlib.axes.Axes, "None or a matplotlib Axes")
    return ax


def figure_and_axes(ax, **figure_kwargs):
    """(figure, axes) to draw into: `ax` and its figure, or a new figure's axes when
    `ax` is None (`new_figure(**figure_kwargs)`); raises for anything else."""
    check_axes(ax)
    if ax is None:
        return new_figure(**figure_kwargs)
    return ax.figure, ax


def check_title(title):
    """Returns `title` if it is None or a string, else raises."""
    if title is not None:
        _validate.text("title", title)
    return title


def new_figure(width=6.4, height=3.8, ncols=1, nrows=1, **kwargs):
    """A new `Figure` (constrained layout) and its axes, as `Figure.subplots` returns them."""
    width = _validate.real("width", width, 0.5, 60.0)
    height = _validate.real("height", height, 0.5, 60.0)
    ncols = _validate.integer("ncols", ncols, 1, 50)
    nrows = _validate.integer("nrows", nrows, 1, 50)
    fig = Figure(figsize=(width, height), layout="constrained")
    axes = fig.subplots(nrows, ncols, **kwargs)
    return fig, axes


def legend_below(ax, ncols=2, **kwargs):
    """A legend under `ax` (below its horizontal axis), where it covers no data; the
    figure's constrained layout makes room for it."""
    _validate.instance("ax", ax, matplotlib.axes.Axes, "a matplotlib Axes")
    return ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncols=ncols,
                     frameon=False, borderaxespad=0.0, **kwargs)


LINESTYLES = ("-", "--", ":", "-.")
"""The line styles `plot_mean_band` draws a mean with."""


MARKERS = (None, "o", "s", "^", "D", "v", "P", "x")
"""The markers `plot_mean_band` may put on a mean (None: no marker)."""


def markevery(n_points, marker):
    """Where a marker goes on a line of `n_points`: about eight along it, offset by
    marker so that two series' markers do not sit on each other."""
    step = max(1, n_points // 8)
    return (MARKERS.index(marker) * step // len(MARKERS)) % step, step


def plot_mean_band(ax, values, colour, label, x=None, per_seed=False, linestyle="-",
                   marker=None):
    """Draws the mean over seeds of `values` [seed, time] with its 95% band on `ax`: a
    percentile bootstrap (`icm.stats.bootstrap_band`), which stays within the range the
    values can take (an error's band never dips below zero). `x` defaults to 1, 2, ...;
    `per_seed` also draws every seed's curve faintly; `linestyle` and `marker` (one of
    `MARKERS`, about eight along the line) are the mean's: use `series_style(task)`
    so that no two series differ by colour alone."""
    _validate.instance("ax", ax, matplotlib.axes.Axes, "a matplotlib Axes")
    values = _validate.finite_array("values", values, ndim=2)
    linestyle = _validate.one_of("linestyle", linestyle, LINESTYLES)
    marker = _validate.one_of("marker", marker, MARKERS)
    x = np.arange(1, values.shape[1] + 1) if x is None else \
        _validate.finite_array("x", x, shape=(values.shape[1],))
    if per_seed:
        for row in values:
            ax.plot(x, row, color=colour, alpha=0.08, linewidth=0.6)
    mean, low, high = stats.bootstrap_band(values, resamples=stats.PANEL_RESAMPLES)
    ax.fill_between(x, low, high, color=colour, alpha=0.25, linewidth=0)
    ax.plot(x, mean, color=colour, linewidth=2, linestyle=linestyle, label=label,
            marker=marker, markersize=5, markevery=markevery(len(x), marker) if marker else None)
