"""Figures and sliders made for one lesson each: the Rayleigh quotient on the sphere with a
rotating plane (notebook 07), the recorded MDS benchmark (notebook 10) and the alpha / n
reconstruction sliders (notebook 08). Built on :mod:`lbo_notebooks.plotting._meshes`.
"""

from __future__ import annotations

from typing import Any, Callable, Sequence, Sized

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Array, Relation, Satisfies, validated
from ..geometry._mesh import Mesh
from ._rayleigh_plane import MATRIX, OPTIONAL_NORMAL, plane_circle, plane_normal
from ._sliders import mesh_slider

__all__ = ["rayleigh_sphere_figure", "PlaneSlider", "plane_slider", "plot_mds_scaling", "reconstruction_sliders"]


# --- min-max (notebook 07): the Rayleigh quotient on the unit sphere of R^3 ------------------------
@validated(matrix=MATRIX, normal=OPTIONAL_NORMAL)
def rayleigh_sphere_figure(matrix: ArrayLike, normal: ArrayLike | None = None, *, resolution: int = 60) -> Any:
    """Plotly figure: the unit sphere coloured by ``x.T M x``, with a plane's great circle.

    The circle is the plane ``{x : normal . x = 0}`` on the sphere, and the marker its minimiser.

    Examples
    --------
    >>> fig = rayleigh_sphere_figure(np.diag([1.0, 2.0, 4.0]), [1.0, 0.0, 0.0])
    >>> [trace.type for trace in fig.data]
    ['surface', 'scatter3d', 'scatter3d']
    """
    import plotly.graph_objects as go

    M = matrix
    u, v = np.meshgrid(np.linspace(0, np.pi, resolution), np.linspace(0, 2 * np.pi, 2 * resolution))
    X = np.stack([np.sin(u) * np.cos(v), np.sin(u) * np.sin(v), np.cos(u)], axis=-1)
    R = np.einsum("...i,ij,...j->...", X, M, X)
    fig = go.Figure(
        go.Surface(x=X[..., 0], y=X[..., 1], z=X[..., 2], surfacecolor=R, colorscale="Viridis", opacity=0.9,
                   colorbar=dict(title="xᵀMx"))
    )
    if normal is not None:
        circle, point, value = plane_circle(M, normal)
        fig.add_trace(go.Scatter3d(x=circle[:, 0], y=circle[:, 1], z=circle[:, 2], mode="lines",
                                   line=dict(color="white", width=6), name="plane"))
        fig.add_trace(go.Scatter3d(x=[point[0]], y=[point[1]], z=[point[2]], mode="markers",
                                   marker=dict(color="red", size=6), name=f"min on plane = {value:.3f}"))
    # The legend sits top left, away from the colour bar and its title on the right.
    fig.update_layout(height=450, margin=dict(l=0, r=0, t=30, b=0), scene=dict(aspectmode="data"),
                      legend=dict(x=0.0, y=1.0, xanchor="left", yanchor="top", bgcolor="rgba(70,70,70,0.75)",
                                  font=dict(color="white")))  # a dark box: the white circle shows in it
    return fig


class PlaneSlider:
    """A :func:`rayleigh_sphere_figure` whose plane is rotated by an ipywidgets slider (degrees).

    ``widget`` is what to display (the notebook displays the object itself); ``figure`` and
    ``slider`` are exposed so that code and tests can drive it, and ``minimum`` is the smallest
    Rayleigh quotient on the plane shown. Build it with :func:`plane_slider`.
    """

    @validated(matrix=MATRIX)
    def __init__(self, matrix: ArrayLike, angles: Sequence[float]) -> None:
        import ipywidgets as widgets
        import plotly.graph_objects as go

        self.matrix = matrix
        self.lam = np.linalg.eigvalsh(self.matrix)
        self._values = list(angles)
        self.figure = go.FigureWidget(rayleigh_sphere_figure(self.matrix, plane_normal(self.matrix, angles[0])))
        self.slider = widgets.SelectionSlider(options=list(angles), value=angles[0], description="angle",
                                              continuous_update=False)
        self.slider.observe(lambda change: self.update(change["new"]), names="value")
        self.widget = widgets.VBox([self.slider, self.figure])
        self.update(angles[0])

    def update(self, angle: float) -> None:
        circle, point, value = plane_circle(self.matrix, plane_normal(self.matrix, angle))
        with self.figure.batch_update():
            line, marker = self.figure.data[1], self.figure.data[2]
            line.x, line.y, line.z = circle[:, 0], circle[:, 1], circle[:, 2]
            marker.x, marker.y, marker.z = [point[0]], [point[1]], [point[2]]
            marker.name = f"min on plane = {value:.3f}"
            self.figure.layout.title = f"angle {angle:.0f}°: min on the plane {value:.3f} ≤ λ₁ = {self.lam[1]:.3f}"
        self.minimum = float(value)

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)


@validated(matrix=MATRIX)
def plane_slider(matrix: ArrayLike, angles: Sequence[float] = tuple(range(0, 181, 5))) -> PlaneSlider:
    """Courant–Fischer in 3-D: rotate a plane and watch its minimum Rayleigh quotient.

    Examples
    --------
    >>> w = plane_slider(np.diag([1.0, 2.0, 4.0]))
    >>> w.slider.value = 45
    >>> round(w.minimum, 6) <= 2.0           # never above the middle eigenvalue
    True
    """
    return PlaneSlider(matrix, angles)


# --- recorded MDS benchmark (notebook 10) -------------------------------------------------------
@validated(rows=Satisfies(lambda rows: not isinstance(rows, Sized) or len(rows) > 0,
                          message="rows is empty; pass lbo_notebooks.analyses.recorded_benchmark('mds')['scaling']."))
def plot_mds_scaling(rows: Sequence[dict]) -> Any:
    """Time and peak memory of spectral vs classical MDS against n, from ``benchmarks/mds.py`` rows.

    ``rows`` is the ``"scaling"`` list of the recorded MDS benchmark
    (``lbo_notebooks.analyses.recorded_benchmark("mds")["scaling"]``): each row has ``n`` and,
    for ``"smds"`` and ``"classical"``, ``seconds``, ``cpu_seconds`` and ``peak_mib`` (classical
    rows may be missing above the size it was run to). Left: wall and CPU seconds on log-log axes
    with slope-1 and slope-2 guides; right: peak MiB with the size of two n x n float64 matrices.
    Returns the matplotlib figure.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> row = lambda n, s: {"seconds": s, "cpu_seconds": s, "peak_mib": n / 100}
    >>> fig = plot_mds_scaling([{"n": n, "smds": row(n, n / 1e3), "classical": row(n, (n / 1e3) ** 2)}
    ...                         for n in (1000, 2000, 4000)])
    >>> len(fig.axes)
    2
    """
    import matplotlib.pyplot as plt

    n = np.array([r["n"] for r in rows], dtype=np.float64)

    def get(kind: str, key: str) -> NDArray[np.float64]:
        return np.array([r.get(kind, {}).get(key, np.nan) for r in rows], dtype=np.float64)

    has_c = np.isfinite(get("classical", "seconds"))
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
    for key, style, what in (("seconds", "-", "wall"), ("cpu_seconds", "--", "CPU")):
        a1.loglog(n, get("smds", key), "o" + style, color="C0", label=f"spectral MDS ({what})")
        a1.loglog(n[has_c], get("classical", key)[has_c], "s" + style, color="C1", label=f"classical MDS ({what})")
    a1.loglog(n, get("smds", "cpu_seconds")[0] * n / n[0], "k:", label="slope 1")
    if has_c.any():
        first = np.flatnonzero(has_c)[0]
        a1.loglog(n[has_c], get("classical", "cpu_seconds")[first] * (n[has_c] / n[first]) ** 2, "k-.", label="slope 2")
    a1.set_xlabel("vertices"); a1.set_ylabel("seconds"); a1.legend(fontsize=8); a1.set_title("time (recorded)")
    a2.loglog(n, get("smds", "peak_mib"), "o-", label="spectral MDS")
    a2.loglog(n[has_c], get("classical", "peak_mib")[has_c], "s-", label="classical MDS")
    a2.loglog(n[has_c], 2 * 8 * n[has_c] ** 2 / 2**20, "k--", label="two n × n float64 matrices")
    a2.set_xlabel("vertices"); a2.set_ylabel("peak MiB above baseline"); a2.legend(fontsize=8); a2.set_title("memory (recorded)")
    fig.tight_layout()
    return fig


# --- reconstruction sliders (notebook 08) -------------------------------------------------------
@validated(
    target=Array(2, rows=lambda mesh, **_: mesh.n_vertices, cols=3, finite=False,
                 what=lambda mesh, **_: f"be an ({mesh.n_vertices}, 3) array of positions"),
    alphas=Satisfies(lambda alphas: True, convert=list),
    counts=(Satisfies(lambda counts: True, convert=lambda counts: [int(c) for c in counts]),
            Relation(lambda alphas, counts, **_: len(alphas) > 0 and len(counts) > 0,
                     "alphas and counts must not be empty")),
)
def reconstruction_sliders(
    mesh: Mesh,
    target: ArrayLike,
    spectrum_for: Callable[[float], Any],
    alphas: Sequence[float],
    counts: Sequence[int],
    *,
    alpha: float | None = None,
    count: int | None = None,
) -> Any:
    """Two sliders, the metric exponent alpha and the number n of functions, over one mesh figure.

    The figure shows ``target`` (n_vertices, 3) rebuilt from the first n eigenfunctions of the
    metric ``|K|^alpha g`` (``spectrum_for(alpha)`` returns a :class:`~lbo_notebooks.Spectrum`
    with at least ``max(counts)`` pairs; cache inside it, it is called at every redraw), coloured
    by the per-vertex error ``|x - x_hat| / diagonal``. Returns an ipywidgets ``VBox`` with
    attributes ``alpha_slider`` and ``viewer`` (the :class:`MeshSlider` of n).

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> m = shapes.icosphere(2)
    >>> cache = {}
    >>> spectrum_for = lambda a: cache.setdefault(a, eigenbasis(m, 20, alpha=a))
    >>> box = reconstruction_sliders(m, m.vertices, spectrum_for, [0.0, 1.0], [5, 10, 20])
    >>> box.alpha_slider.value = 1.0
    >>> sorted(cache)
    [0.0, 1.0]
    """
    import ipywidgets as widgets

    X = target
    alpha_slider = widgets.SelectionSlider(options=alphas, value=alphas[0] if alpha is None else alpha,
                                           description="alpha", continuous_update=False)

    def frame(n: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        rebuilt = spectrum_for(alpha_slider.value).reconstruct(X, n)
        return rebuilt, np.linalg.norm(X - rebuilt, axis=1) / mesh.diagonal

    viewer = mesh_slider(mesh, frame, counts, "n", colorscale="Viridis",
                         title=lambda n: f"α = {alpha_slider.value}, n = {n}: colour = |x − x̂| / diagonal")
    viewer.slider.value = counts[-1] if count is None else count
    alpha_slider.observe(lambda change: viewer.update(viewer.slider.value), names="value")
    box = widgets.VBox([alpha_slider, viewer.widget])
    box.alpha_slider, box.viewer = alpha_slider, viewer
    return box
