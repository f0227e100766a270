"""Shared pieces of the interactive panels."""

import inspect

import ipywidgets

from icm import _validate


def check_fixed(run_fn, fixed, controlled):
    """Raises ValueError unless every key of `fixed` is an argument of `run_fn` that the
    panel does not control itself (`controlled`: its sliders and choices)."""
    parameters = inspect.signature(run_fn).parameters
    allowed = [p for p in parameters if p not in controlled and p != "progress"]
    for name in fixed:
        if name not in allowed:
            raise ValueError(f"{name!r} cannot be held fixed in this panel; allowed: "
                             f"{', '.join(allowed)} (the panel sets {', '.join(controlled)})")


def slider(name, spec):
    """An int or float slider named `name` from a dict of min, max, step and value; it
    redraws only when released (continuous_update off), since a redraw reruns seeds."""
    _validate.text("name", name)
    if not isinstance(spec, dict) or not {"min", "max", "step", "value"} <= set(spec):
        raise _validate.ArgumentTypeError(f"spec must be a dict of min, max, step and value, "
                                          f"got {_validate.show(spec)}")
    cls = ipywidgets.IntSlider if isinstance(spec["value"], int) else ipywidgets.FloatSlider
    return cls(description=name, continuous_update=False,
               style={"description_width": "initial"}, **spec)


def panel(sliders, draw, per_row=2):
    """A VBox of `sliders` (a dict name -> slider) above an Output that shows
    `draw(**values)`, redrawn whenever a slider is released."""
    from IPython.display import display

    if not isinstance(sliders, dict) or not sliders:
        raise _validate.ArgumentTypeError(f"sliders must be a non-empty dict of name to "
                                          f"widget, got {_validate.show(sliders)}")
    _validate.function("draw", draw, allow_none=False)
    per_row = _validate.integer("per_row", per_row, 1, 10)
    output = ipywidgets.Output()

    def redraw(_change=None):
        with output:
            output.clear_output(wait=True)
            display(draw(**{name: s.value for name, s in sliders.items()}))

    for s in sliders.values():
        s.observe(redraw, names="value")
    redraw()
    controls = list(sliders.values())
    rows = [ipywidgets.HBox(controls[i:i + per_row]) for i in range(0, len(controls), per_row)]
    return ipywidgets.VBox(rows + [output])
