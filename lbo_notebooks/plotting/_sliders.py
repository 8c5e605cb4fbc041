"""Sliders that drive a figure: one plotly ``FigureWidget`` of a shape whose function (or vertex
positions) follows an ipywidgets slider.
"""

from __future__ import annotations

from typing import Any, Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Relation, Satisfies, validated
from ..geometry._mesh import Mesh
from ..geometry._pointcloud import PointCloud
from ._display import (
    DEFAULT_MAX_FACES,
    Display,
    check_scalars,
    colour_range,
    default_colorscale,
    positions,
    tidy_label,
)
from ._meshes import plot_mesh
from ._scene import MARGIN, UP, View

__all__ = ["MeshSlider", "mesh_slider"]


_LOOK_AHEAD = 3                # slider values tried for a first frame that is not blank

# The slider's values as a list (an iterator is read once), at least one; ``start`` one of them.
_SLIDER = dict(
    values=(Satisfies(lambda values: True, convert=list),
            Relation(lambda values, **_: len(values) > 0, "mesh_slider needs at least one slider value")),
    start=Relation(lambda values, start, **_: start is None or start in values,
                   lambda values, start, **_: f"start={start!r} is not one of the slider values {values[:3]}...; "
                                              "pick one of them"),
    up=UP,
)


def _first_informative(frame: Callable[[Any], Any], values: list[Any]) -> Any:
    """The first of the first few ``values`` whose frame is not a constant function.

    A constant function is drawn in one colour, a blank surface (e.g. the eigenfunction phi_0,
    or a reconstruction from phi_0 alone); a frame that moves the vertices always counts.
    """
    for value in values[:_LOOK_AHEAD]:
        out = frame(value)
        vertices, scalars = (out if isinstance(out, tuple) else (None, out))
        if vertices is not None or scalars is None:
            return value
        s = np.asarray(scalars, dtype=np.float64)
        if s.ndim != 1 or not np.all(np.isfinite(s)):
            return value          # positions, or bad values that update() reports
        if np.ptp(s) > np.sqrt(np.finfo(float).eps) * np.abs(s).max():
            return value
    return values[0]


class MeshSlider:
    """A plotly ``FigureWidget`` of a mesh (or point cloud) driven by an ipywidgets slider.

    Build it with :func:`mesh_slider`. ``widget`` is what to display (the notebook displays the
    object itself); ``figure`` and ``slider`` are exposed so that code and tests can drive it.
    """

    @validated(**_SLIDER)
    def __init__(self, mesh: Mesh | PointCloud, frame: Callable[[Any], Any], values: Sequence[Any], description: str,
                 *, colorscale: str | None, symmetric: bool, max_faces: int, height: int, title: Callable[[Any], str] | None,
                 up: str | ArrayLike = "auto", start: Any = None) -> None:
        import ipywidgets as widgets
        import plotly.graph_objects as go

        if start is None:
            start = _first_informative(frame, values)
        self.mesh, self._frame, self._values, self._title = mesh, frame, values, title
        self._symmetric, self._colorscale = symmetric, colorscale
        self._display = Display(mesh, max_faces)
        self.figure = go.FigureWidget(plot_mesh(mesh, None, max_faces=max_faces, height=height, up=up))
        self._view = View(positions(mesh), up)
        self._radius = self._view.radius * (1 + MARGIN)
        if title is not None:  # leave room for the title that update() sets
            self.figure.layout.margin.t = 40
        if all(isinstance(v, (int, np.integer)) for v in values) and values == list(range(values[0], values[-1] + 1)):
            self.slider = widgets.IntSlider(value=start, min=values[0], max=values[-1], description=description,
                                            continuous_update=False)
        else:
            self.slider = widgets.SelectionSlider(options=values, value=start, description=description,
                                                  continuous_update=False)
        self.slider.layout.width = "60%"
        self.slider.observe(lambda change: self.update(change["new"]), names="value")
        self.widget = widgets.VBox([self.slider, self.figure])
        self.update(start)

    def update(self, value: Any) -> None:
        """Redraw the figure for slider value ``value`` (called when the slider moves)."""
        out = self._frame(value)
        vertices, scalars = (out if isinstance(out, tuple) else (None, out))
        arr = None if scalars is None else np.asarray(scalars, dtype=np.float64)
        if arr is not None and arr.ndim == 2:  # the frame returned positions, not scalars
            vertices, arr = arr, None
        if vertices is not None:
            v = np.asarray(vertices, dtype=np.float64)
            expected = positions(self.mesh).shape
            if v.shape != expected:
                raise ValueError(f"frame returned positions of shape {v.shape}, expected {expected}.")
            v = self._display.values(v) if self._display.index is not None else v
        with self.figure.batch_update():
            trace = self.figure.data[0]
            if vertices is not None:
                trace.x, trace.y, trace.z = v[:, 0], v[:, 1], v[:, 2]
                self._fit(v)
            if arr is not None:
                s = check_scalars(self.mesh, arr)
                lo, hi = colour_range(s, None, None, self._symmetric)
                scale = self._colorscale or default_colorscale(lo, hi, self._symmetric)
                if self._display.faces is None:  # a point cloud: the markers carry the colours
                    trace.marker.update(color=self._display.values(s), colorscale=scale, cmin=lo, cmax=hi,
                                        showscale=True)
                else:
                    trace.intensity, trace.intensitymode = self._display.values(s), "vertex"
                    trace.colorscale, trace.cmin, trace.cmax, trace.showscale = scale, lo, hi, True
            if self._title is not None:
                self.figure.layout.title = tidy_label(self._title(value))

    def _fit(self, v: NDArray[np.float64]) -> None:
        """Grow the (cubic) axis ranges if moved vertices leave them; never shrink, so the view stays still."""
        reach = float(np.abs(v - self._view.centre).max()) * (1 + MARGIN)
        if reach <= self._radius:
            return
        self._radius = reach
        scene = self.figure.layout.scene
        for axis, r in zip((scene.xaxis, scene.yaxis, scene.zaxis), self._view.ranges(reach)):
            axis.range = r

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)


@validated(**_SLIDER)
def mesh_slider(
    mesh: Mesh | PointCloud,
    frame: Callable[[Any], Any],
    values: Sequence[Any],
    description: str = "n",
    *,
    colorscale: str | None = None,
    symmetric: bool = False,
    max_faces: int = DEFAULT_MAX_FACES,
    height: int = 450,
    title: Callable[[Any], str] | None = None,
    up: str | ArrayLike = "auto",
    start: Any = None,
) -> MeshSlider:
    """A 3D figure of ``mesh`` with a slider; moving the slider calls ``frame(value)`` and redraws.

    Parameters
    ----------
    mesh : Mesh or PointCloud
        A cloud is drawn as points coloured by the scalars.
    frame : callable
        ``frame(value)`` returns per-vertex scalars (n,), new vertex positions (n, 3), or a tuple
        ``(positions, scalars)`` (either may be None).
    values : sequence
        The slider's values (a contiguous integer range gives an ``IntSlider``).
    description : str
        Slider label.
    title : callable, optional
        ``title(value)`` gives the figure title for each value (a rounded "-0.00" shows as "0.00").
    up : str or array_like
        The direction drawn upwards, as in :func:`plot_mesh`.
    start : optional
        The value shown first. By default the first value whose frame is not a constant
        function (of the first three): an eigenfunction slider over ``range(k)`` starts on
        index 1, because index 0 is the constant function, a blank surface.

    Returns
    -------
    MeshSlider
        Display it in a notebook; ``.slider.value = x`` moves it programmatically.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> sphere = shapes.icosphere(2)
    >>> basis = eigenbasis(sphere, 10)
    >>> w = mesh_slider(sphere, lambda i: basis.vectors[:, i], range(10), "index", symmetric=True, start=1)
    >>> w.slider.value = 3
    """
    return MeshSlider(mesh, frame, values, description, colorscale=colorscale, symmetric=symmetric,
                      max_faces=max_faces, height=height, title=title, up=up, start=start)
