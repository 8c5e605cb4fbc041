"""Figures of meshes and point clouds and functions on them: interactive plotly 3D, a static
matplotlib fallback, and sliders that drive a figure.

Every function that takes a :class:`~lbo_notebooks.Mesh` also takes a
:class:`~lbo_notebooks.PointCloud`, drawn as points coloured by the function (its values are per
point, as a cloud's spectrum gives them). plotly, ipywidgets and open3d are imported inside the
functions, so importing this module is cheap. Meshes above ``max_faces`` triangles are decimated
for display only (quadric decimation), with each displayed vertex taking the value of its nearest
original vertex; clouds above ``max_faces`` points show an evenly spaced subset of their points.
"""

from __future__ import annotations

from typing import Any, Hashable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Relation, Satisfies, validated
from ..geometry._mesh import Mesh
from ..geometry._pointcloud import PointCloud
from ._display import (
    DEFAULT_MAX_FACES,
    MAX_FACES,
    SCALARS,
    Display,
    check_scalars,
    colour_range,
    default_colorscale,
    positions,
    tidy_label,
)
from ._scene import (
    AZIMUTH,
    ELEVATION,
    MARGIN,
    NOMINAL_WIDTH,
    UP,
    View,
    scene_layout,
    trace,
    wrap,
)

__all__ = ["plot_mesh", "plot_meshes", "plot_mesh_static"]


_TITLE_FONT = 13               # px; about 7 px per character
_COLORBAR_PX = 70              # room for a colour bar and its tick labels, in px
_ROW_GAP_PX = 10               # between rows of panels


def _is_shared(shared: Any, meshes: list[Any]) -> bool:
    """``shared_colour_range`` is True, False or one group label per mesh."""
    if isinstance(shared, (bool, np.bool_)):
        return True
    return not isinstance(shared, str) and isinstance(shared, Sequence) and len(shared) == len(meshes)


# plot_meshes: the meshes as a list (an iterator is read once), and one scalars, title and group label per mesh.
_MESHES = (Satisfies(lambda meshes: True, convert=list),
           Relation(lambda meshes, **_: len(meshes) > 0, "plot_meshes needs at least one mesh"))
_SCALARS_PER_MESH = Relation(
    lambda meshes, scalars, **_: scalars is None or len(scalars) == len(meshes),
    lambda meshes, scalars, **_: (f"got {len(scalars)} scalar arrays for {len(meshes)} meshes; "
                                  "pass one (or None) per mesh"))
_TITLES = Relation(lambda meshes, titles, **_: titles is None or len(titles) == len(meshes),
                   lambda meshes, titles, **_: f"got {len(titles)} titles for {len(meshes)} meshes")
_SHARED = Relation(
    lambda meshes, shared_colour_range, **_: _is_shared(shared_colour_range, meshes),
    lambda meshes, shared_colour_range, **_: ("shared_colour_range must be True, False or one group label per mesh "
                                              f"({len(meshes)}); got {shared_colour_range!r}"))
# Whole numbers, as int or float (``cols=2.0``, ``height=0.5 * 800``).
_COLS = Satisfies(lambda cols: int(cols) == cols and cols >= 1, "a positive integer", none=True)
_HEIGHT = Satisfies(lambda height: int(height) == height and height >= 50, "a number of pixels (at least 50) or None",
                    none=True)


@validated(scalars=SCALARS, up=UP, max_faces=MAX_FACES)
def plot_mesh(
    mesh: Mesh | PointCloud,
    scalars: ArrayLike | None = None,
    *,
    title: str | None = None,
    colorscale: str | None = None,
    cmin: float | None = None,
    cmax: float | None = None,
    symmetric: bool = False,
    up: str | ArrayLike = "auto",
    max_faces: int = DEFAULT_MAX_FACES,
    height: int = 450,
) -> Any:
    """An interactive 3D plotly figure of ``mesh``, coloured by per-vertex ``scalars``.

    The axes have equal scale and the camera shows the whole mesh with a margin from any
    direction (its bounding sphere fits the view), so rotating never clips it.

    Parameters
    ----------
    mesh : Mesh or PointCloud
        A cloud is drawn as points (plotly ``Scatter3d`` markers) coloured by ``scalars``.
    scalars : array_like, shape (n_vertices,) or (n_points,), optional
        A function on the vertices; drawn with smooth (per-vertex) colour interpolation.
    title : str, optional
    colorscale : str, optional
        Any plotly colour scale name. Default: diverging ``"RdBu_r"`` for a function of both signs
        (or with ``symmetric``), sequential ``"Viridis"`` for one of one sign (a distance).
    cmin, cmax : float, optional
        Colour range; by default the range of ``scalars`` (or ``[-r, r]`` with ``symmetric``).
        A constant function is drawn in the middle colour.
    symmetric : bool
        Centre the colour range on zero (good for eigenfunctions).
    up : {"auto", "x", "y", "z", "-x", "-y", "-z"} or array_like, shape (3,)
        The direction drawn upwards: an axis (``"y"`` for a file in the y-up convention of OBJ
        and glTF, ``"z"`` for z-up), an axis with a sign (``"-y"`` for a shape stored upside
        down) or any 3-vector. ``"auto"`` (the default) chooses between +z and +y, the two
        conventions of mesh files: the axis whose coordinate plane the shape stands on (the
        built-in creatures stand on z = 0 in every pose), else the taller of the two extents
        (so an animal, sitting or standing, is upright either way). The camera looks along the
        thinnest horizontal direction (a side view of an animal), slightly from above. Pass
        ``up`` when "auto" guesses wrong, e.g. for a wide, low object in a y-up file.
    max_faces : int
        Meshes with more triangles are decimated for display (clouds with more points thinned).
    height : int
        Figure height in pixels.

    Returns
    -------
    plotly.graph_objects.Figure

    Examples
    --------
    >>> from lbo_notebooks import shapes, PointCloud
    >>> sphere = shapes.icosphere(2)
    >>> fig = plot_mesh(sphere, sphere.vertices[:, 2], title="z", up="y")
    >>> fig.data[0].type, fig.layout.scene.camera.up.y
    ('mesh3d', 1.0)
    >>> cloud = PointCloud(sphere.vertices)
    >>> plot_mesh(cloud, cloud.points[:, 2]).data[0].type
    'scatter3d'
    """
    import plotly.graph_objects as go

    s = scalars  # checked by SCALARS: None or one finite float64 per vertex
    lo, hi = colour_range(s, cmin, cmax, symmetric)
    view = View(positions(mesh), up)
    radius = view.radius * (1 + MARGIN)
    top = 40 if title else 10
    colorscale = colorscale or default_colorscale(lo, hi, symmetric)
    fig = go.Figure(trace(Display(mesh, max_faces), s, colorscale=colorscale, cmin=lo, cmax=hi, view=view,
                           showscale=s is not None, colorbar=dict(len=0.8, thickness=12)))
    scene_width = NOMINAL_WIDTH - (_COLORBAR_PX if s is not None else 0)
    fig.update_layout(title=tidy_label(title), height=height, margin=dict(l=0, r=0, t=top, b=0),
                      scene=scene_layout(view, radius, None, scene_width, height - top))
    return fig


@validated(meshes=_MESHES, scalars=_SCALARS_PER_MESH, titles=_TITLES, cols=_COLS, height=_HEIGHT,
           shared_colour_range=_SHARED, up=UP, max_faces=MAX_FACES)
def plot_meshes(
    meshes: Sequence[Mesh | PointCloud],
    scalars: Sequence[ArrayLike | None] | None = None,
    titles: Sequence[str] | None = None,
    *,
    colorscale: str | None = None,
    cmin: float | None = None,
    cmax: float | None = None,
    symmetric: bool = False,
    shared_colour_range: bool | Sequence[Hashable] = False,
    up: str | ArrayLike = "auto",
    same_scale: bool = True,
    cols: int | None = None,
    max_faces: int = DEFAULT_MAX_FACES // 2,
    height: int | None = None,
) -> Any:
    """Several meshes in one plotly figure, one 3D scene per panel, on a grid.

    All scenes have the same size, and by default they are square, so that every shape fills its
    panel (its bounding sphere spans the scene's width). Panels drawn with the same colour range
    share one colour bar, right of the last of them; its column of the grid gets the room for it,
    so no scene is narrowed by a colour bar. Titles are wrapped to the panel's width above the
    scene. With ``same_scale`` every panel uses the same length scale (the largest bounding
    sphere), so sizes compare across panels; each mesh is centred in its panel and never clipped.

    Parameters
    ----------
    meshes : sequence of Mesh or PointCloud
        Clouds are drawn as points.
    scalars : sequence of (array_like or None), optional
        One function per mesh (or ``None`` for a plain surface).
    titles : sequence of str, optional
    colorscale, cmin, cmax, symmetric :
        As in :func:`plot_mesh`.
    shared_colour_range : bool or sequence
        ``True``: one colour range (and one colour bar) for all panels, so colours compare
        across panels. A sequence of labels, one per mesh: one range per label, e.g.
        ``["HKS", "HKS", "φ₈", "φ₈"]`` compares the first two panels with each other and the
        last two with each other. (Panels given the same ``cmin`` and ``cmax`` share a colour
        bar anyway.)
    up : str or array_like
        As in :func:`plot_mesh`; ``"auto"`` is decided per mesh.
    same_scale : bool
        One length scale for all panels.
    cols : int, optional
        Panels per row; by default all in one row up to 4 meshes, else two rows.
    max_faces : int
        Meshes with more triangles are decimated for display.
    height : int, optional
        Height of one row of panels, in pixels. By default the scenes are square (for a figure
        800 pixels wide; wider figures only add room beside each shape), at least 180 and at
        most 450 pixels high, plus room for the titles.

    Returns
    -------
    plotly.graph_objects.Figure

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> a, b = shapes.icosphere(1), shapes.torus(n_major=16, n_minor=8)
    >>> fig = plot_meshes([a, b], [a.vertices[:, 0], b.vertices[:, 0]], titles=["sphere", "torus"],
    ...                   shared_colour_range=True)
    >>> len(fig.data), fig.layout.scene2.domain.x[0] >= fig.layout.scene.domain.x[1]
    (2, True)
    >>> [trace.showscale for trace in fig.data]      # one colour bar for the shared range
    [False, True]
    """
    import plotly.graph_objects as go

    if scalars is None:
        scalars = [None] * len(meshes)
    values = [check_scalars(m, s) for m, s in zip(meshes, scalars)]  # per mesh: no table sees them
    n = len(meshes)
    ranges = _panel_ranges(values, shared_colour_range, cmin, cmax, symmetric)
    # One colour bar per distinct range, beside the last panel drawn with it.
    last_of = {r: p for p, r in enumerate(ranges) if r is not None}
    shows = [r is not None and last_of[r] == p for p, r in enumerate(ranges)]
    cols = int(cols) if cols is not None else (n if n <= 4 else -(-n // 2))
    cols = min(cols, n)
    rows = -(-n // cols)
    views = [View(positions(m), up) for m in meshes]
    shared_radius = max(v.radius for v in views) * (1 + MARGIN)

    # Columns: equal scenes; a column whose panels show a colour bar gets the bar's width more.
    gap = 0.01
    bar = _COLORBAR_PX / NOMINAL_WIDTH
    has_bar = [any(shows[p] for p in range(c, n, cols)) for c in range(cols)]
    scene_w = (1 - cols * gap - bar * sum(has_bar)) / cols
    left = np.concatenate([[0.0], np.cumsum([gap + scene_w + (bar if b else 0) for b in has_bar])])[:-1] + gap / 2
    scene_px = scene_w * NOMINAL_WIDTH

    chars = max(10, int((scene_w + gap) * NOMINAL_WIDTH / (0.58 * _TITLE_FONT)))
    wrapped = [wrap(tidy_label(t) or "", chars) for t in titles] if titles else None
    lines = max((w.count("<br>") + 1 for w in wrapped), default=0) if wrapped else 0
    title_px = (_TITLE_FONT + 5) * lines + (6 if lines else 0)
    scene_h = float(height) - title_px if height is not None else float(np.clip(scene_px, 180, 450))
    row_h = scene_h + title_px + (_ROW_GAP_PX if rows > 1 else 0)
    total_h = row_h * rows

    fig = go.Figure()
    annotations = []
    for p, (mesh, v, view, show, r) in enumerate(zip(meshes, values, views, shows, ranges)):
        row, c = divmod(p, cols)
        x0, x1 = float(left[c]), float(left[c] + scene_w)
        y1 = 1 - row / rows
        y0 = y1 - (scene_h + title_px) / total_h
        scene_top = y1 - title_px / total_h
        name = "scene" if p == 0 else f"scene{p + 1}"
        radius = shared_radius if same_scale else view.radius * (1 + MARGIN)
        fig.update_layout({name: scene_layout(view, radius, dict(x=[x0, x1], y=[y0, scene_top]), scene_px,
                                        (scene_top - y0) * total_h)})
        lo, hi = r if r is not None else (None, None)
        colorbar = dict(x=x1, xanchor="left", xref="paper", y=(y0 + scene_top) / 2, yanchor="middle",
                        len=0.8 * (scene_top - y0), lenmode="fraction", thickness=10,
                        tickfont=dict(size=10)) if show else None
        fig.add_trace(trace(Display(mesh, max_faces), v, colorscale=colorscale or default_colorscale(lo, hi, symmetric),
                             cmin=lo, cmax=hi, showscale=show,
                             view=view, scene=name, colorbar=colorbar))
        if wrapped:
            annotations.append(dict(text=wrapped[p], x=(x0 + x1) / 2, y=y1, xref="paper", yref="paper",
                                    xanchor="center", yanchor="top", showarrow=False,
                                    font=dict(size=_TITLE_FONT)))
    fig.update_layout(height=round(total_h), margin=dict(l=0, r=0, t=4, b=0), showlegend=False,
                      annotations=annotations)
    return fig


def _panel_ranges(values: list[NDArray[np.float64] | None], shared: bool | Sequence[Hashable], cmin: float | None,
                  cmax: float | None, symmetric: bool) -> list[tuple[float, float] | None]:
    """The colour range of each panel (None for a panel without a function).

    ``shared`` is False (a range per panel), True (one for all) or one group label per panel
    (one range per group), as :func:`plot_meshes` checked it.
    """
    n = len(values)
    if isinstance(shared, (bool, np.bool_)):
        groups: list[Hashable] = [0] * n if shared else list(range(n))
    else:
        groups = list(shared)
    out: list[tuple[float, float] | None] = [None] * n
    for g in dict.fromkeys(groups):
        members = [p for p in range(n) if groups[p] == g and values[p] is not None]
        if not members:
            continue
        lo, hi = colour_range(np.concatenate([values[p] for p in members]), cmin, cmax, symmetric)
        for p in members:
            out[p] = (float(lo), float(hi))
    return out


def _view_rotation(view: View) -> NDArray[np.float64]:
    """Rows: screen right, into the screen, up -- a rotation (right = into x up)."""
    return np.array([view.right, -view.front, view.up])


# The default colour scales by their matplotlib names.
_MATPLOTLIB = {"RdBu_r": "RdBu_r", "Viridis": "viridis"}


@validated(scalars=SCALARS, up=UP, max_faces=MAX_FACES)
def plot_mesh_static(
    mesh: Mesh | PointCloud,
    scalars: ArrayLike | None = None,
    *,
    ax: Any = None,
    cmap: str | None = None,
    up: str | ArrayLike = "auto",
    elev: float | None = None,
    azim: float | None = None,
    symmetric: bool = False,
    title: str | None = None,
    max_faces: int = 20_000,
) -> Any:
    """A static matplotlib rendering of ``mesh`` (for print, PDFs and environments without plotly).

    A :class:`~lbo_notebooks.PointCloud` is drawn as points coloured by ``scalars``. The mesh is turned so that ``up`` (as in :func:`plot_mesh`) points up and seen from the same
    direction as the interactive figure, with equal scale on all axes and its whole bounding
    sphere inside the axes. ``elev`` and ``azim`` (degrees) override the viewing angles.

    Returns the matplotlib 3D axes.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from lbo_notebooks import shapes
    >>> ax = plot_mesh_static(shapes.icosphere(1), up="y")
    """
    import matplotlib.pyplot as plt
    from matplotlib import colormaps
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    s = scalars  # checked by SCALARS: None or one finite float64 per vertex
    d = Display(mesh, max_faces)
    view = View(positions(mesh), up)
    # Rotate into the view frame: x to the right, y away from the viewer, z up; matplotlib then
    # looks from -y (azimuth -90) at the given elevation.
    rotation = _view_rotation(view)
    shown = (d.vertices - view.centre) @ rotation.T
    if ax is None:
        ax = plt.figure(figsize=(5, 5)).add_subplot(projection="3d")
    if d.faces is None:  # a point cloud
        if s is None:
            colours: Any = "#5b7a99"
        else:
            lo, hi = colour_range(s, None, None, symmetric)
            colours = colormaps[cmap or _MATPLOTLIB[default_colorscale(lo, hi, symmetric)]]((d.values(s) - lo) / (hi - lo))
        ax.scatter(shown[:, 0], shown[:, 1], shown[:, 2], c=colours, s=6, depthshade=True, linewidths=0)
        return _finish_static(ax, view, elev, azim, title)
    tris = shown[d.faces]
    normals = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.divide(normals, lengths, out=np.zeros_like(normals), where=lengths > 0)
    shade = 0.55 + 0.45 * np.clip(normals @ np.array([0.3, -0.85, 0.45]), 0, 1)
    if s is None:
        colours = np.column_stack([np.outer(shade, [0.72, 0.78, 0.85]), np.ones(len(shade))])
    else:
        face_values = d.values(s)[d.faces].mean(axis=1)
        lo, hi = colour_range(s, None, None, symmetric)
        colours = colormaps[cmap or _MATPLOTLIB[default_colorscale(lo, hi, symmetric)]]((face_values - lo) / (hi - lo))
        colours[:, :3] *= shade[:, None]
    ax.add_collection3d(Poly3DCollection(tris, facecolors=colours, edgecolors="none"))
    return _finish_static(ax, view, elev, azim, title)


def _finish_static(ax: Any, view: View, elev: float | None, azim: float | None, title: str | None) -> Any:
    """Equal axes holding the bounding sphere, the viewing angles and the title of a static figure."""
    r = view.radius * (1 + MARGIN)
    ax.set(xlim=(-r, r), ylim=(-r, r), zlim=(-r, r))
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=np.degrees(ELEVATION) if elev is None else elev,
                 azim=-90 + np.degrees(AZIMUTH) if azim is None else azim)
    ax.set_axis_off()
    if title:
        ax.set_title(tidy_label(title))
    return ax
