"""Shared pieces of the interactive panels."""

import ipywidgets


def slider(name, spec):
    """An int or float slider named `name` from a dict of min, max, step and value; it
    redraws only when released (continuous_update off), since a redraw reruns seeds."""
    cls = ipywidgets.IntSlider if isinstance(spec["value"], int) else ipywidgets.FloatSlider
    return cls(description=name, continuous_update=False,
               style={"description_width": "initial"}, **spec)


def panel(sliders, draw, per_row=2):
    """A VBox of `sliders` (a dict name -> slider) above an Output that shows
    `draw(**values)`, redrawn whenever a slider is released."""
    from IPython.display import display

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
