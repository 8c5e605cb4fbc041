"""Figures for meshes and functions on them: interactive plotly 3D, a static matplotlib fallback,
and sliders that drive a figure.

plotly, ipywidgets and open3d are imported inside the functions, so importing this module is
cheap. Meshes above ``max_faces`` triangles are decimated for display only (quadric decimation),
with each displayed vertex taking the value of its nearest original vertex.
"""

from __future__ import annotations

from typing import Any, Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .mesh import Mesh

__all__ = ["plot_mesh", "plot_meshes", "plot_mesh_static", "mesh_slider", "MeshSlider", "display_mesh"]

DEFAULT_MAX_FACES = 40_000


class _Display:
    """A mesh as shown on screen: possibly decimated, with a map back to the original vertices."""

    def __init__(self, mesh: Mesh, max_faces: int) -> None:
        if mesh.n_faces <= max_faces:
            self.vertices, self.faces, self.index = mesh.vertices, mesh.faces, None
            return
        from scipy.spatial import cKDTree

        from ._open3d import import_open3d

        o3d = import_open3d()
        m = o3d.geometry.TriangleMesh(
            o3d.utility.Vector3dVector(np.array(mesh.vertices)), o3d.utility.Vector3iVector(mesh.faces.astype(np.int32))
        )
        small = m.simplify_quadric_decimation(target_number_of_triangles=int(max_faces))
        self.vertices = np.asarray(small.vertices)
        self.faces = np.asarray(small.triangles, dtype=np.int64)
        self.index = cKDTree(mesh.vertices).query(self.vertices)[1]

    def values(self, per_vertex: NDArray[np.float64]) -> NDArray[np.float64]:
        return per_vertex if self.index is None else per_vertex[self.index]


def display_mesh(mesh: Mesh, max_faces: int = DEFAULT_MAX_FACES) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64] | None]:
    """Vertices and faces to draw for ``mesh`` and, if decimated, the original vertex behind each."""
    d = _Display(mesh, max_faces)
    return d.vertices, d.faces, d.index


def _check_scalars(mesh: Mesh, scalars: ArrayLike | None) -> NDArray[np.float64] | None:
    if scalars is None:
        return None
    s = np.asarray(scalars, dtype=np.float64)
    if s.shape != (mesh.n_vertices,):
        raise ValueError(f"scalars must have one value per vertex, shape ({mesh.n_vertices},); got {s.shape}.")
    if not np.all(np.isfinite(s)):
        raise ValueError("scalars contain NaN or inf; plotly would draw them as holes. Replace them first.")
    return s


def _colour_range(s: NDArray[np.float64] | None, cmin: float | None, cmax: float | None, symmetric: bool) -> tuple[float | None, float | None]:
    if s is None:
        return cmin, cmax
    if symmetric and cmin is None and cmax is None:
        r = float(np.abs(s).max()) or 1.0
        return -r, r
    return (float(s.min()) if cmin is None else cmin), (float(s.max()) if cmax is None else cmax)


def _trace(d: _Display, s: NDArray[np.float64] | None, *, colorscale: str, cmin: float | None, cmax: float | None,
           showscale: bool, name: str | None = None, colorbar_x: float | None = None) -> Any:
    import plotly.graph_objects as go

    v, f = d.vertices, d.faces
    kwargs: dict[str, Any] = dict(
        x=v[:, 0], y=v[:, 1], z=v[:, 2], i=f[:, 0], j=f[:, 1], k=f[:, 2], name=name,
        flatshading=False, lighting=dict(ambient=0.45, diffuse=0.8, specular=0.15, roughness=0.6),
        lightposition=dict(x=100, y=200, z=300), hoverinfo="skip",
    )
    if s is None:
        kwargs["color"] = "#b9c7d6"
    else:
        kwargs.update(intensity=d.values(s), intensitymode="vertex", colorscale=colorscale, cmin=cmin, cmax=cmax,
                      showscale=showscale)
        if colorbar_x is not None:
            kwargs["colorbar"] = dict(x=colorbar_x, len=0.8, thickness=12)
    return go.Mesh3d(**kwargs)


_SCENE = dict(aspectmode="data", xaxis=dict(visible=False), yaxis=dict(visible=False), zaxis=dict(visible=False))


def plot_mesh(
    mesh: Mesh,
    scalars: ArrayLike | None = None,
    *,
    title: str | None = None,
    colorscale: str = "RdBu_r",
    cmin: float | None = None,
    cmax: float | None = None,
    symmetric: bool = False,
    max_faces: int = DEFAULT_MAX_FACES,
    height: int = 450,
) -> Any:
    """An interactive 3D plotly figure of ``mesh``, coloured by per-vertex ``scalars``.

    Parameters
    ----------
    mesh : Mesh
    scalars : array_like, shape (n_vertices,), optional
        A function on the vertices; drawn with smooth (per-vertex) colour interpolation.
    title : str, optional
    colorscale : str
        Any plotly colour scale name.
    cmin, cmax : float, optional
        Colour range; by default the range of ``scalars`` (or ``[-r, r]`` with ``symmetric``).
    symmetric : bool
        Centre the colour range on zero (good for eigenfunctions).
    max_faces : int
        Meshes with more triangles are decimated for display.
    height : int
        Figure height in pixels.

    Returns
    -------
    plotly.graph_objects.Figure

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> sphere = shapes.icosphere(2)
    >>> fig = plot_mesh(sphere, sphere.vertices[:, 2], title="z")
    >>> fig.data[0].type
    'mesh3d'
    """
    import plotly.graph_objects as go

    s = _check_scalars(mesh, scalars)
    lo, hi = _colour_range(s, cmin, cmax, symmetric)
    fig = go.Figure(_trace(_Display(mesh, max_faces), s, colorscale=colorscale, cmin=lo, cmax=hi, showscale=s is not None))
    fig.update_layout(title=title, scene=_SCENE, height=height, margin=dict(l=0, r=0, t=40 if title else 10, b=0))
    return fig


def plot_meshes(
    meshes: Sequence[Mesh],
    scalars: Sequence[ArrayLike | None] | None = None,
    titles: Sequence[str] | None = None,
    *,
    colorscale: str = "RdBu_r",
    cmin: float | None = None,
    cmax: float | None = None,
    symmetric: bool = False,
    shared_colour_range: bool = False,
    max_faces: int = DEFAULT_MAX_FACES // 2,
    height: int = 380,
) -> Any:
    """Several meshes side by side in one plotly figure, one 3D scene each.

    ``scalars`` is a list with one entry (or ``None``) per mesh. With ``shared_colour_range``
    all panels use one colour range, so colours compare across panels.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> a, b = shapes.icosphere(1), shapes.torus(n_major=16, n_minor=8)
    >>> fig = plot_meshes([a, b], titles=["sphere", "torus"])
    >>> len(fig.data)
    2
    """
    from plotly.subplots import make_subplots

    meshes = list(meshes)
    if not meshes:
        raise ValueError("plot_meshes needs at least one mesh.")
    if scalars is None:
        scalars = [None] * len(meshes)
    if len(scalars) != len(meshes):
        raise ValueError(f"got {len(scalars)} scalar arrays for {len(meshes)} meshes; pass one (or None) per mesh.")
    if titles is not None and len(titles) != len(meshes):
        raise ValueError(f"got {len(titles)} titles for {len(meshes)} meshes.")
    values = [_check_scalars(m, s) for m, s in zip(meshes, scalars)]
    if shared_colour_range and any(v is not None for v in values):
        allv = np.concatenate([v for v in values if v is not None])
        cmin, cmax = _colour_range(allv, cmin, cmax, symmetric)
    cols = len(meshes)
    fig = make_subplots(rows=1, cols=cols, specs=[[{"type": "scene"}] * cols],
                        subplot_titles=list(titles) if titles else None, horizontal_spacing=0.01)
    for c, (m, v) in enumerate(zip(meshes, values), start=1):
        lo, hi = (cmin, cmax) if shared_colour_range else _colour_range(v, cmin, cmax, symmetric)
        show = v is not None and (not shared_colour_range or c == cols)
        fig.add_trace(_trace(_Display(m, max_faces), v, colorscale=colorscale, cmin=lo, cmax=hi, showscale=show,
                             colorbar_x=(c / cols) - 0.02 if show else None), row=1, col=c)
    fig.update_scenes(**_SCENE)
    fig.update_layout(height=height, margin=dict(l=0, r=0, t=40 if titles else 10, b=0), showlegend=False)
    return fig


def plot_mesh_static(
    mesh: Mesh,
    scalars: ArrayLike | None = None,
    *,
    ax: Any = None,
    cmap: str = "RdBu_r",
    elev: float = 20.0,
    azim: float = -60.0,
    title: str | None = None,
    max_faces: int = 20_000,
) -> Any:
    """A static matplotlib rendering of ``mesh`` (for print, PDFs and environments without plotly).

    Returns the matplotlib 3D axes.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from lbo_notebooks import shapes
    >>> ax = plot_mesh_static(shapes.icosphere(1))
    """
    import matplotlib.pyplot as plt
    from matplotlib import colormaps
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    s = _check_scalars(mesh, scalars)
    d = _Display(mesh, max_faces)
    if ax is None:
        ax = plt.figure(figsize=(5, 5)).add_subplot(projection="3d")
    tris = d.vertices[d.faces]
    normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    shade = 0.55 + 0.45 * np.clip(normals @ np.array([0.3, -0.4, 0.85]), 0, 1)
    if s is None:
        colours = np.column_stack([np.outer(shade, [0.72, 0.78, 0.85]), np.ones(len(shade))])
    else:
        face_values = d.values(s)[d.faces].mean(axis=1)
        lo, hi = float(s.min()), float(s.max())
        colours = colormaps[cmap]((face_values - lo) / (hi - lo if hi > lo else 1.0))
        colours[:, :3] *= shade[:, None]
    ax.add_collection3d(Poly3DCollection(tris, facecolors=colours, edgecolors="none"))
    lo, hi = d.vertices.min(axis=0), d.vertices.max(axis=0)
    centre, r = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set(xlim=(centre[0] - r, centre[0] + r), ylim=(centre[1] - r, centre[1] + r), zlim=(centre[2] - r, centre[2] + r))
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()
    if title:
        ax.set_title(title)
    return ax


class MeshSlider:
    """A plotly ``FigureWidget`` of a mesh driven by an ipywidgets slider.

    Build it with :func:`mesh_slider`. ``widget`` is what to display (the notebook displays the
    object itself); ``figure`` and ``slider`` are exposed so that code and tests can drive it.
    """

    def __init__(self, mesh: Mesh, frame: Callable[[Any], Any], values: Sequence[Any], description: str,
                 *, colorscale: str, symmetric: bool, max_faces: int, height: int, title: Callable[[Any], str] | None) -> None:
        import ipywidgets as widgets
        import plotly.graph_objects as go

        values = list(values)
        if not values:
            raise ValueError("mesh_slider needs at least one slider value.")
        self.mesh, self._frame, self._values, self._title = mesh, frame, values, title
        self._symmetric, self._colorscale = symmetric, colorscale
        self._display = _Display(mesh, max_faces)
        self.figure = go.FigureWidget(plot_mesh(mesh, None, max_faces=max_faces, height=height))
        if title is not None:  # leave room for the title that update() sets
            self.figure.layout.margin.t = 40
        if all(isinstance(v, (int, np.integer)) for v in values) and values == list(range(values[0], values[-1] + 1)):
            self.slider = widgets.IntSlider(value=values[0], min=values[0], max=values[-1], description=description,
                                            continuous_update=False)
        else:
            self.slider = widgets.SelectionSlider(options=values, value=values[0], description=description,
                                                  continuous_update=False)
        self.slider.layout.width = "60%"
        self.slider.observe(lambda change: self.update(change["new"]), names="value")
        self.widget = widgets.VBox([self.slider, self.figure])
        self.update(values[0])

    def update(self, value: Any) -> None:
        """Redraw the figure for slider value ``value`` (called when the slider moves)."""
        out = self._frame(value)
        vertices, scalars = (out if isinstance(out, tuple) else (None, out))
        arr = None if scalars is None else np.asarray(scalars, dtype=np.float64)
        if arr is not None and arr.ndim == 2:  # the frame returned positions, not scalars
            vertices, arr = arr, None
        if vertices is not None:
            v = np.asarray(vertices, dtype=np.float64)
            if v.shape != self.mesh.vertices.shape:
                raise ValueError(f"frame returned vertices of shape {v.shape}, expected {self.mesh.vertices.shape}.")
            v = self._display.values(v) if self._display.index is not None else v
        with self.figure.batch_update():
            trace = self.figure.data[0]
            if vertices is not None:
                trace.x, trace.y, trace.z = v[:, 0], v[:, 1], v[:, 2]
            if arr is not None:
                s = _check_scalars(self.mesh, arr)
                lo, hi = _colour_range(s, None, None, self._symmetric)
                trace.intensity, trace.intensitymode = self._display.values(s), "vertex"
                trace.colorscale, trace.cmin, trace.cmax, trace.showscale = self._colorscale, lo, hi, True
            if self._title is not None:
                self.figure.layout.title = self._title(value)

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)


def mesh_slider(
    mesh: Mesh,
    frame: Callable[[Any], Any],
    values: Sequence[Any],
    description: str = "n",
    *,
    colorscale: str = "RdBu_r",
    symmetric: bool = False,
    max_faces: int = DEFAULT_MAX_FACES,
    height: int = 450,
    title: Callable[[Any], str] | None = None,
) -> MeshSlider:
    """A 3D figure of ``mesh`` with a slider; moving the slider calls ``frame(value)`` and redraws.

    Parameters
    ----------
    mesh : Mesh
    frame : callable
        ``frame(value)`` returns per-vertex scalars (n,), new vertex positions (n, 3), or a tuple
        ``(positions, scalars)`` (either may be None).
    values : sequence
        The slider's values (a contiguous integer range gives an ``IntSlider``).
    description : str
        Slider label.
    title : callable, optional
        ``title(value)`` gives the figure title for each value.

    Returns
    -------
    MeshSlider
        Display it in a notebook; ``.slider.value = x`` moves it programmatically.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> sphere = shapes.icosphere(2)
    >>> basis = eigenbasis(sphere, 10)
    >>> w = mesh_slider(sphere, lambda i: basis.vectors[:, i], range(10), "index", symmetric=True)
    >>> w.slider.value = 3
    """
    return MeshSlider(mesh, frame, values, description, colorscale=colorscale, symmetric=symmetric,
                      max_faces=max_faces, height=height, title=title)


# --- min-max (notebook 05): the Rayleigh quotient on the unit sphere of R^3 ------------------------
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

    from . import minmax

    M = minmax.symmetric_3x3(matrix)
    u, v = np.meshgrid(np.linspace(0, np.pi, resolution), np.linspace(0, 2 * np.pi, 2 * resolution))
    X = np.stack([np.sin(u) * np.cos(v), np.sin(u) * np.sin(v), np.cos(u)], axis=-1)
    R = np.einsum("...i,ij,...j->...", X, M, X)
    fig = go.Figure(
        go.Surface(x=X[..., 0], y=X[..., 1], z=X[..., 2], surfacecolor=R, colorscale="Viridis", opacity=0.9,
                   colorbar=dict(title="x'Mx"))
    )
    if normal is not None:
        circle, point, value = minmax.plane_circle(M, normal)
        fig.add_trace(go.Scatter3d(x=circle[:, 0], y=circle[:, 1], z=circle[:, 2], mode="lines",
                                   line=dict(color="white", width=6), name="plane"))
        fig.add_trace(go.Scatter3d(x=[point[0]], y=[point[1]], z=[point[2]], mode="markers",
                                   marker=dict(color="red", size=6), name=f"min on plane = {value:.3f}"))
    fig.update_layout(height=450, margin=dict(l=0, r=0, t=30, b=0), scene=dict(aspectmode="data"))
    return fig


class PlaneSlider:
    """A :func:`rayleigh_sphere_figure` whose plane is rotated by an ipywidgets slider (degrees).

    ``widget`` is what to display (the notebook displays the object itself); ``figure`` and
    ``slider`` are exposed so that code and tests can drive it. Build it with :func:`plane_slider`.
    """

    def __init__(self, matrix: ArrayLike, angles: Sequence[float]) -> None:
        import ipywidgets as widgets
        import plotly.graph_objects as go

        from . import minmax

        self.matrix = minmax.symmetric_3x3(matrix)
        self.lam = np.linalg.eigvalsh(self.matrix)
        self._values = list(angles)
        self.figure = go.FigureWidget(rayleigh_sphere_figure(self.matrix, minmax.plane_normal(self.matrix, angles[0])))
        self.slider = widgets.SelectionSlider(options=list(angles), value=angles[0], description="angle",
                                              continuous_update=False)
        self.slider.observe(lambda change: self.update(change["new"]), names="value")
        self.widget = widgets.VBox([self.slider, self.figure])
        self.update(angles[0])

    def update(self, angle: float) -> None:
        from . import minmax

        circle, point, value = minmax.plane_circle(self.matrix, minmax.plane_normal(self.matrix, angle))
        with self.figure.batch_update():
            line, marker = self.figure.data[1], self.figure.data[2]
            line.x, line.y, line.z = circle[:, 0], circle[:, 1], circle[:, 2]
            marker.x, marker.y, marker.z = [point[0]], [point[1]], [point[2]]
            marker.name = f"min on plane = {value:.3f}"
            self.figure.layout.title = f"angle {angle:.0f} deg: min on the plane {value:.3f} <= lam_2 = {self.lam[1]:.3f}"

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)


def plane_slider(matrix: ArrayLike, angles: Sequence[float] = tuple(range(0, 181, 5))) -> PlaneSlider:
    """Courant–Fischer in 3-D: rotate a plane and watch its minimum Rayleigh quotient.

    Examples
    --------
    >>> w = plane_slider(np.diag([1.0, 2.0, 4.0]))
    >>> w.slider.value = 45
    """
    return PlaneSlider(matrix, angles)


# --- recorded MDS benchmark (notebook 07) -------------------------------------------------------
def plot_mds_scaling(rows: Sequence[dict]) -> Any:
    """Time and peak memory of spectral vs classical MDS against n, from ``benchmarks/mds.py`` rows.

    ``rows`` is the ``"scaling"`` list of ``benchmarks/results/mds.json``: each row has ``n`` and,
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

    if not rows:
        raise ValueError("rows is empty; pass the 'scaling' list of benchmarks/results/mds.json.")
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
    a2.loglog(n[has_c], 2 * 8 * n[has_c] ** 2 / 2**20, "k--", label="two n x n float64 matrices")
    a2.set_xlabel("vertices"); a2.set_ylabel("peak MiB above baseline"); a2.legend(fontsize=8); a2.set_title("memory (recorded)")
    fig.tight_layout()
    return fig


# --- reconstruction sliders (notebook 06) -------------------------------------------------------
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

    X = np.asarray(target, dtype=np.float64)
    if X.shape != (mesh.n_vertices, 3):
        raise ValueError(f"target must be an ({mesh.n_vertices}, 3) array of positions, got {np.shape(target)}.")
    alphas, counts = list(alphas), [int(c) for c in counts]
    if not alphas or not counts:
        raise ValueError("alphas and counts must not be empty.")
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
