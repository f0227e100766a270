"""Shared pieces of the interactive panel_data."""

import ipywidgets

from icm import _book, _validate
from icm.figures import DISPLAY_WIDTH_PX, Figure

STATIC_ENV = _book.STATIC_ENV
"""When this environment variable is "1" (the book build sets it, see
`book/_ext/execute_book.py`), the panels are drawn as their static, precomputed
versions, which move in the HTML book without a kernel."""


PANEL_WIDTH_PX = DISPLAY_WIDTH_PX
"""The width, in CSS pixels, at which a live panel shows its figure (less in a
narrower output area: the image never overflows it): the width the book's figures are
shown at most (`icm.figures.DISPLAY_WIDTH_PX`). Without a width of its own the
image was stretched to the output area (about 1,360 px in JupyterLab on a 1920 px
screen, its PNG drawn 441 px wide: blurry, and taller than the screen)."""

PIXEL_RATIO = 2
"""Device pixels per CSS pixel that a live panel's PNG is drawn for: the 2 of
high-density screens (most laptops' and phones'). Python cannot ask the browser for
its own ratio; a screen of ratio 1 shows the PNG scaled down by half, still sharp."""


def wants_static(static):
    """Whether a panel should be its static version: `static` if True or False; if
    None, whether the book is being built (`STATIC_ENV` is "1")."""
    if static is None:
        return _book.static_panels()
    return _validate.boolean("static", static)


def check_fixed(fixed, controls, allowed):
    """Raises ValueError unless every key of `fixed` is one of `allowed` (the run's other
    arguments); `controls` are the panel's own sliders and choices, which cannot be held
    fixed."""
    for name in fixed:
        if name in controls:
            raise ValueError(f"{name!r} cannot be held fixed in this panel: it is one of "
                             f"its controls ({', '.join(controls)})")
        if name not in allowed:
            raise ValueError(f"{name!r} cannot be held fixed in this panel; allowed: "
                             f"{', '.join(allowed)}")


def run_arguments(run_fn, controls):
    """The arguments of `run_fn` a panel may hold fixed: all but its controls and the
    progress bar."""
    import inspect

    return tuple(p for p in inspect.signature(run_fn).parameters
                 if p not in controls and p != "progress")


def slider(name, spec, label=None):
    """An int or float slider named `name` from a dict of min, max, step and value; it
    redraws only when released (continuous_update off), since a redraw reruns seeds.
    `label` (words) is its tooltip and accessible name; `name` its description."""
    _validate.text("name", name)
    if label is not None:
        _validate.text("label", label)
    if not isinstance(spec, dict) or not {"min", "max", "step", "value"} <= set(spec):
        raise _validate.ArgumentTypeError(f"spec must be a dict of min, max, step and value, "
                                          f"got {_validate.show(spec)}")
    cls = ipywidgets.IntSlider if isinstance(spec["value"], int) else ipywidgets.FloatSlider
    return cls(description=name, description_allow_html=False, tooltip=label or name,
               continuous_update=False, style={"description_width": "initial"}, **spec)


def choice(name, options, label=None):
    """A toggle of `options` named `name`, first option selected; `label` (words) is
    its tooltip."""
    _validate.text("name", name)
    if label is not None:
        _validate.text("label", label)
    return ipywidgets.ToggleButtons(description=name, options=list(options),
                                    tooltip=label or name, value=options[0],
                                    style={"description_width": "initial"})


def panel(sliders, draw, per_row=2, width=PANEL_WIDTH_PX):
    """A VBox of `sliders` (a dict name -> slider) above an image of `draw(**values)`
    (an `icm.figures.Figure`), redrawn whenever a slider is released.

    The image is shown `width` CSS pixels wide (at most the output area's width) and
    its PNG drawn `width * PIXEL_RATIO` pixels wide (`panel_png`), sharp on a
    high-density screen.

    The figure is an `ipywidgets.Image` holding its PNG, not a display into an
    `ipywidgets.Output`. Every program that runs a notebook through nbclient
    (nbconvert, papermill, nbval, Jupyter Book) answers each display into an Output
    widget with a comm message on the kernel's shell channel, and jupyter_client
    (7.4 and later) sends it through a synchronous shadow of the asyncio socket on
    which nbclient is waiting for the cell's reply: when the reply has just arrived,
    that send swallows its wakeup and the client waits forever (nbconvert's default
    timeout is none). A new value of an Image widget needs no answer.

    The first figure is drawn before any widget exists, so that a bad argument raises
    its error here; a redraw's error is shown above the figure, which keeps the last
    one drawn."""
    import html

    if not isinstance(sliders, dict) or not sliders:
        raise _validate.ArgumentTypeError(f"sliders must be a non-empty dict of name to "
                                          f"widget, got {_validate.show(sliders)}")
    _validate.function("draw", draw, allow_none=False)
    per_row = _validate.integer("per_row", per_row, 1, 10)
    width = _validate.integer("width", width, 100, 4000)

    def png(figure):
        _validate.instance("the figure draw returned", figure, Figure,
                           "an icm.figures.Figure")
        return panel_png(figure, width)

    # An explicit width: in a VBox (a flex column) an image without one is stretched
    # to the output area's width.
    image = ipywidgets.Image(value=png(draw(**{n: s.value for n, s in sliders.items()})),
                             format="png", layout=ipywidgets.Layout(
                                 width=f"{width}px", max_width="100%", height="auto"))
    message = ipywidgets.HTML()

    def redraw(_change=None):
        try:
            figure = draw(**{name: s.value for name, s in sliders.items()})
        except Exception as error:  # shown in the panel, as a cell would show it
            message.value = f"<b>{type(error).__name__}:</b> {html.escape(str(error))}"
            return
        message.value = ""
        image.value = png(figure)

    for s in sliders.values():
        s.observe(redraw, names="value")
    controls = list(sliders.values())
    rows = [ipywidgets.HBox(controls[i:i + per_row]) for i in range(0, len(controls), per_row)]
    return ipywidgets.VBox(rows + [message, image])


def panel_png(figure, width=PANEL_WIDTH_PX, pixel_ratio=PIXEL_RATIO):
    """The PNG of a live panel's figure, drawn for where the panel shows it: `width`
    CSS pixels wide on a screen of `pixel_ratio` device pixels per CSS pixel, so
    `width * pixel_ratio` pixels wide (rounded to a whole pixel), and as tall as the
    figure's proportions make it. Only the figure's resolution (`png_dpi`) changes:
    its layout and its text, in inches and points, stay as drawn.

    Args:
      figure: an `icm.figures.Figure`.
      width: the width it is shown at, in CSS pixels (100 to 4000).
      pixel_ratio: device pixels per CSS pixel (1 to 4).

    Returns:
      The PNG's bytes.
    """
    _validate.instance("figure", figure, Figure, "an icm.figures.Figure")
    width = _validate.integer("width", width, 100, 4000)
    pixel_ratio = _validate.real("pixel_ratio", pixel_ratio, 1.0, 4.0)
    # Agg's canvas is inches x dpi pixels, truncated (matplotlib forgives a product
    # 1e-8 short of a whole pixel, as 116 / 1.1 * 1.1 is).
    figure.png_dpi = round(width * pixel_ratio) / figure.get_figwidth()
    return figure.png()


def live_sliders(name):
    """The live sliders of panel `name` (one of `icm.experiments.panel_data.PANELS`): for
    each, {min, max, step, value} from its setting's `Slider.live` and default. Every
    value of the static panel's grid is on them (a test checks it)."""
    from icm.experiments import panel_data

    spec = panel_data.spec(name)
    out = {}
    for slider_name in spec.slider_names:
        setting = spec.setting(slider_name)
        low, high, step = setting.slider.live
        out[slider_name] = dict(min=low, max=high, step=step, value=setting.default)
    return out


def curves_panel(name, static, fixed, per_row=2):
    """Panel `name` of `icm.experiments.panel_data.PANELS`: live (ipywidgets sliders and the
    panel's choices, from its settings, that rerun `panel_curves_for`) or static (its
    precomputed grid as a Vega-Lite figure), as `wants_static(static)` says."""
    from icm import figures
    from icm.experiments import panel_data

    spec = panel_data.spec(name)
    sliders = live_sliders(name)
    check_fixed(fixed, spec.controls, run_arguments(spec.run, spec.controls))
    if wants_static(static):
        if fixed:
            raise ValueError(f"the static panel shows its precomputed grid and cannot hold "
                             f"{', '.join(fixed)} fixed; use static=False")
        from icm.figures import static_panels

        return static_panels.curves_panel(panel_data.precompute(name))
    controls = {n: slider(n, s, spec.setting(n).label) for n, s in sliders.items()}
    for n, options in spec.choices.items():
        controls[n] = choice(n, options, spec.setting(n).label)

    def draw(**values):
        return figures.panel_figure(name, panel_data.panel_curves_for(name, fixed, **values))

    return panel(controls, draw, per_row=per_row)
