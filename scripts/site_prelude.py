"""Kernel start-up file for ``scripts/build_site.py`` (run before the notebook, never by readers).

It changes only how results are *displayed*, so that the static HTML works offline:

- plotly figures render as HTML that calls ``Plotly.newPlot`` without embedding plotly.js (the
  site ships one ``plotly.min.js`` that every page loads);
- ``lbo_notebooks.plotting.mesh_slider`` viewers (a live ipywidgets slider + FigureWidget, which
  need a kernel) display as a plain plotly figure with a plotly slider whose steps hold up to
  ``LBO_SITE_SLIDER_STEPS`` (default 16) precomputed frames, so the figure stays interactive
  without a kernel; an ipywidgets box that contains such a viewer (e.g. with an extra control)
  shows the viewer's static figure at the other controls' current values. The viewer objects
  themselves are untouched: later cells can still drive them;
- ``tqdm.auto`` progress bars are switched off: in a kernel they are notebook widgets, which a
  static page can only show as a dead placeholder, and a finished bar says nothing to a reader.
"""



def _lbo_site_setup() -> None:
    # Everything lives in this function so that the notebook's namespace stays clean.
    import os

    import numpy as np
    import plotly.graph_objects as go
    import plotly.io as pio
    from plotly.io.base_renderers import MimetypeRenderer

    _MAX_STEPS = int(os.environ.get("LBO_SITE_SLIDER_STEPS", "16"))

    class _SiteRenderer(MimetypeRenderer):
        """text/html for a page that already loads plotly.js (no CDN, no MathJax)."""

        def to_mimebundle(self, fig_dict):
            html = pio.to_html(fig_dict, include_plotlyjs=False, include_mathjax=False, full_html=False,
                               default_width="100%", default_height=525, validate=False)
            return {"text/html": html}

    pio.renderers["lbo_site"] = _SiteRenderer()
    pio.renderers.default = "lbo_site"

    import tqdm.auto
    import tqdm.std

    class _SilentTqdm(tqdm.std.tqdm):
        def __init__(self, *args, **kwargs):
            kwargs["disable"] = True
            super().__init__(*args, **kwargs)

    tqdm.auto.tqdm = _SilentTqdm
    tqdm.auto.trange = lambda *args, **kwargs: _SilentTqdm(range(*args), **kwargs)

    def _slider_values(viewer) -> list:
        values = getattr(viewer, "_values", None)
        if values is None:
            slider = viewer.slider
            values = list(range(slider.min, slider.max + 1)) if hasattr(slider, "min") else list(slider.options)
        return list(values)

    def _trace_state(figure) -> dict:
        trace = figure.data[0]
        state = {key: np.asarray(getattr(trace, key), dtype=np.float32)
                 for key in ("x", "y", "z", "intensity") if getattr(trace, key, None) is not None}
        for key in ("cmin", "cmax"):
            if getattr(trace, key, None) is not None:
                state[key] = float(getattr(trace, key))
        title = figure.layout.title.text if figure.layout.title is not None else None
        return {"trace": state, "title": title}

    def static_slider_figure(viewer) -> go.Figure:
        """A plotly figure with a native slider reproducing ``viewer`` at up to ``_MAX_STEPS`` values."""
        values = _slider_values(viewer)
        current = viewer.slider.value
        picks = np.unique(np.linspace(0, len(values) - 1, min(_MAX_STEPS, len(values))).round().astype(int))
        chosen = [values[i] for i in picks]
        if current in values and current not in chosen:
            chosen = sorted(chosen + [current], key=values.index)
        states = []
        try:
            for value in chosen:
                viewer.update(value)
                states.append(_trace_state(viewer.figure))
        finally:
            viewer.update(current)
        varying = [k for k in states[0]["trace"]
                   if any(not np.array_equal(np.asarray(s["trace"][k]), np.asarray(states[0]["trace"][k])) for s in states)]
        figure = go.Figure(viewer.figure.to_dict())
        steps = []
        for value, state in zip(chosen, states):
            restyle = {k: [state["trace"][k]] for k in varying}
            relayout = {"title.text": state["title"]} if state["title"] is not None else {}
            steps.append(dict(method="update", label=str(value), args=[restyle, relayout]))
        description = getattr(viewer.slider, "description", "") or ""
        active = chosen.index(current) if current in chosen else 0
        figure.update_layout(sliders=[dict(active=active, steps=steps, pad=dict(t=10, b=10),
                                           currentvalue=dict(prefix=f"{description} = " if description else ""))],
                             margin=dict(t=50 if states[0]["title"] else 10, b=90))
        return figure

    try:
        from lbo_notebooks import plotting as _plotting
    except ImportError:  # the site can still be built for notebooks that do not use the package
        _plotting = None

    if _plotting is None or not hasattr(_plotting, "MeshSlider"):
        return
    import weakref

    import ipywidgets

    viewers: weakref.WeakValueDictionary = weakref.WeakValueDictionary()  # id(viewer.widget) -> viewer
    original_init = _plotting.MeshSlider.__init__

    def _init(self, *args, **kwargs):
        original_init(self, *args, **kwargs)
        viewers[id(self.widget)] = self

    def _display_static(self):
        from IPython.display import display

        display(static_slider_figure(self))

    def _descendant_viewers(widget) -> list:
        found = [viewers[id(widget)]] if id(widget) in viewers else []
        for child in getattr(widget, "children", ()):
            found += _descendant_viewers(child)
        return found

    original_box_repr = ipywidgets.Box._repr_mimebundle_

    def _box_repr(self, **kwargs):
        """A box holding mesh_slider viewers (e.g. with extra controls) shows their static figures."""
        inner = _descendant_viewers(self)
        if not inner:
            return original_box_repr(self, **kwargs)
        parts = [pio.renderers["lbo_site"].to_mimebundle(static_slider_figure(v).to_dict())["text/html"] for v in inner]
        note = ("<p><em>The other controls of this widget are live only when the notebook runs in "
                "JupyterLab; the figure shows their current setting.</em></p>")
        return {"text/html": note + "\n".join(parts)}

    _plotting.MeshSlider.__init__ = _init
    _plotting.MeshSlider._ipython_display_ = _display_static
    ipywidgets.Box._repr_mimebundle_ = _box_repr

_lbo_site_setup()
del _lbo_site_setup
