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

import re
from typing import Any, Callable, Hashable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..mesh import Mesh
from ..pointcloud import PointCloud

__all__ = ["plot_mesh", "plot_meshes", "plot_mesh_static", "mesh_slider", "MeshSlider", "display_mesh", "tidy_label"]

DEFAULT_MAX_FACES = 40_000
_POINT_SIZE = 3                # px, the markers of a point cloud


def _positions(shape: Mesh | PointCloud) -> NDArray[np.float64]:
    """The vertices of a mesh or the points of a cloud."""
    if isinstance(shape, Mesh):
        return shape.vertices
    if isinstance(shape, PointCloud):
        return shape.points
    raise TypeError(f"expected a Mesh or a PointCloud, got {type(shape).__name__}; build one with "
                    "lbo.Mesh(vertices, faces) or lbo.PointCloud(points).")


class _Display:
    """A mesh or cloud as shown on screen: possibly decimated, with a map back to the original
    vertices. ``faces`` is None for a point cloud."""

    faces: NDArray[np.int64] | None

    def __init__(self, mesh: Mesh | PointCloud, max_faces: int) -> None:
        _positions(mesh)  # a Mesh or a PointCloud, or a TypeError naming what it got
        if isinstance(mesh, PointCloud):
            n = mesh.n_points
            self.faces, self.index = None, None
            if n <= max_faces:
                self.vertices = mesh.points
            else:  # evenly spaced in the file's order, deterministic
                self.index = np.unique(np.linspace(0, n - 1, int(max_faces)).round().astype(np.int64))
                self.vertices = mesh.points[self.index]
            return
        if mesh.n_faces <= max_faces:
            self.vertices, self.faces, self.index = mesh.vertices, mesh.faces, None
            return
        from scipy.spatial import cKDTree

        from .._open3d import import_open3d

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


def display_mesh(mesh: Mesh | PointCloud, max_faces: int = DEFAULT_MAX_FACES
                 ) -> tuple[NDArray[np.float64], NDArray[np.int64] | None, NDArray[np.int64] | None]:
    """Vertices and faces to draw for ``mesh`` and, if decimated, the original vertex behind each.

    For a :class:`~lbo_notebooks.PointCloud` the faces are None and the vertices are its points
    (an evenly spaced subset of at most ``max_faces`` of them).
    """
    d = _Display(mesh, max_faces)
    return d.vertices, d.faces, d.index


def _check_scalars(mesh: Mesh | PointCloud, scalars: ArrayLike | None) -> NDArray[np.float64] | None:
    if scalars is None:
        return None
    s = np.asarray(scalars, dtype=np.float64)
    n, what = len(_positions(mesh)), "point" if isinstance(mesh, PointCloud) else "vertex"
    if s.shape != (n,):
        raise ValueError(f"scalars must have one value per {what}, shape ({n},); got {s.shape}.")
    if not np.all(np.isfinite(s)):
        raise ValueError("scalars contain NaN or inf; plotly would draw them as holes. Replace them first.")
    return s


def _colour_range(s: NDArray[np.float64] | None, cmin: float | None, cmax: float | None,
                  symmetric: bool) -> tuple[float | None, float | None]:
    """The colour range for ``s``; a (numerically) constant function gets the middle colour.

    A range that collapses to a point (or, with ``symmetric``, a constant function drawn at one
    end of ``[-|c|, |c|]``) would paint the whole surface in the extreme colour, which reads as
    "large" rather than "constant". Constant means a spread below ``sqrt(eps)`` times the size.
    """
    if s is None:
        return cmin, cmax
    lo, hi = float(s.min()), float(s.max())
    size = max(abs(lo), abs(hi))
    if cmin is None and cmax is None and hi - lo <= np.sqrt(np.finfo(float).eps) * size:
        centre = (lo + hi) / 2
        half = abs(centre) or 1.0
        return centre - half, centre + half
    if symmetric and cmin is None and cmax is None:
        r = size or 1.0
        return -r, r
    return (lo if cmin is None else cmin), (hi if cmax is None else cmax)


_NEGATIVE_ZERO = re.compile(r"(?<![\w.])-(0(?:\.0*)?)(?![\d.])")
_GREEK = {"alpha": "α", "beta": "β", "lam": "λ", "lambda": "λ", "mu": "μ", "phi": "φ", "psi": "ψ", "rho": "ρ",
          "sigma": "σ"}
_SUBSCRIPT = dict(zip("0123456789+-aehijklmnoprstuvx", "₀₁₂₃₄₅₆₇₈₉₊₋ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ"))
# A Greek letter (by name, or the letter itself) with an underscore subscript: phi_6, lam_n+1, λ_{i}.
_GREEK_SUBSCRIPT = re.compile(r"(?<![A-Za-z])(" + "|".join(sorted(_GREEK, key=len, reverse=True))
                              + r"|[" + "".join(sorted(set(_GREEK.values()))) + r"])"
                              r"_(\{[0-9a-z+\-]+\}|[0-9]+|[a-z](?:[+\-][0-9]+)?)(?![A-Za-z0-9_])")


def _subscript(match: re.Match[str]) -> str:
    letter, index = match.group(1), match.group(2).strip("{}")
    if not all(ch in _SUBSCRIPT for ch in index):
        return match.group(0)
    return _GREEK.get(letter, letter) + "".join(_SUBSCRIPT[ch] for ch in index)


def tidy_label(text: str | None) -> str | None:
    """``text`` as a figure shows it: Greek letters with subscripts in Unicode, and every number
    that was rounded to a negative zero ("-0.00") written as zero.

    ``phi_6``, ``φ_8``, ``lam_n+1`` and ``λ_{i}`` become φ₆, φ₈, λₙ₊₁ and λᵢ (the names alpha,
    beta, lam, lambda, mu, phi, psi, rho, sigma, or the letters themselves, followed by ``_`` and
    digits or one letter; other words with an underscore, such as ``head_turned``, stay as they
    are). A value like ``-3e-16`` formatted with ``:.2f`` prints "-0.00"; the sign is round-off,
    not information. Every title drawn by :func:`plot_mesh`, :func:`plot_meshes`,
    :func:`plot_mesh_static` and :func:`mesh_slider` goes through this function.

    Examples
    --------
    >>> tidy_label("λ = -0.00, μ = -0.01, t = -0")
    'λ = 0.00, μ = -0.01, t = 0'
    >>> tidy_label("dog: phi_6, λ_i, lam_n+1; head_turned")
    'dog: φ₆, λᵢ, λₙ₊₁; head_turned'
    """
    if text is None:
        return None
    return _NEGATIVE_ZERO.sub(r"\1", _GREEK_SUBSCRIPT.sub(_subscript, text))


# --- the camera ------------------------------------------------------------------------------

_AXES = {"x": 0, "y": 1, "z": 2}
_FOV_Y = np.pi / 4             # plotly's perspective camera: 45 degree vertical field of view
_NOMINAL_WIDTH = 800           # px; the figure is at least this wide in JupyterLab and on the site
_MARGIN = 0.06                 # empty border around the bounding sphere, as a fraction of its radius
_ELEVATION, _AZIMUTH = np.radians(18.0), np.radians(28.0)


_RESTING = 0.02                # a shape whose lowest point is this close to a coordinate plane stands on it
_SAME_EXTENT = 1e-6            # relative difference below which two extents count as equal


def _auto_up(vertices: NDArray[np.float64]) -> NDArray[np.float64]:
    """The axis drawn upwards when ``up="auto"``: +z or +y, the two conventions of mesh files.

    Files are authored axis-aligned and upright, either z-up (CAD, scanners, our creatures) or
    y-up (OBJ, glTF, most graphics tools); x is not used for up by either. Which of the two:

    1. a shape that stands on the coordinate plane z = 0 but not on y = 0 is z-up, and
       conversely (the built-in creatures stand on z = 0 in every pose; many scans stand on
       their floor);
    2. otherwise the taller of the two extents is up (an animal, a person, a bust or a bunny is
       taller than it is deep or wide, whatever its pose; a flat shape is then seen face on);
       equal extents (a sphere) give z.

    Principal axes or the axis of middle extent are not robust: a sitting dog is taller than it is
    long, and the mass of a head or of legs tilts principal axes.
    """
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    extent = hi - lo
    size = float(extent.max()) or 1.0
    stands = [bool(abs(lo[a]) <= _RESTING * size < extent[a]) for a in (1, 2)]
    if stands[0] != stands[1]:
        return np.eye(3)[1 if stands[0] else 2]
    y, z = extent[1], extent[2]
    return np.eye(3)[1 if y > z * (1 + _SAME_EXTENT) else 2]


def _up_vector(up: str | ArrayLike, vertices: NDArray[np.float64]) -> NDArray[np.float64]:
    if isinstance(up, str):
        key = up.strip().lower()
        if key == "auto":
            return _auto_up(vertices)
        sign = -1.0 if key.startswith("-") else 1.0
        if key.lstrip("+-") not in _AXES:
            raise ValueError(f'up={up!r}: use "auto", "x", "y", "z" (optionally with a sign, e.g. "-y") '
                             "or a 3-vector.")
        return sign * np.eye(3)[_AXES[key.lstrip("+-")]]
    u = np.asarray(up, dtype=np.float64)
    if u.shape != (3,) or not np.all(np.isfinite(u)) or np.linalg.norm(u) == 0:
        raise ValueError(f"up must be a finite non-zero 3-vector or one of 'auto', 'x', 'y', 'z'; got {up!r}.")
    return u / np.linalg.norm(u)


class _View:
    """Where the camera looks from: a unit ``up``, a unit ``toward`` (centre to eye), and the
    bounding sphere (``centre``, ``radius``) of the vertices."""

    def __init__(self, vertices: NDArray[np.float64], up: str | ArrayLike) -> None:
        v = np.asarray(vertices, dtype=np.float64)
        self.up = _up_vector(up, v)
        lo, hi = v.min(axis=0), v.max(axis=0)
        self.centre = (lo + hi) / 2
        self.radius = float(np.linalg.norm(v - self.centre, axis=1).max()) or 1.0
        # Look along the thinnest horizontal direction (a side view of an animal), from slightly
        # above and to one side so that depth reads.
        plane = np.eye(3) - np.outer(self.up, self.up)
        d = (v - self.centre) @ plane
        if np.count_nonzero(np.abs(self.up) > 1e-12) == 1:   # an axis: compare the other two axes
            others = [a for a in range(3) if abs(self.up[a]) <= 1e-12]
            extent = np.ptp(d[:, others], axis=0)
            thin = np.eye(3)[others[int(np.argmin(extent))]]
        else:                                                  # a general vector: principal axes in the plane
            w, vecs = np.linalg.eigh(d.T @ d)                  # one eigenvector is up itself (w = 0)
            in_plane = [i for i in range(3) if i != int(np.argmax(np.abs(vecs.T @ self.up)))]
            thin = vecs[:, in_plane[0]]                        # eigh sorts ascending
        # The eye is on the side of -thin (thin's largest component made positive): for a z-up
        # animal that is x to the right, as in a textbook front view.
        self.front = -thin * np.sign(thin[np.argmax(np.abs(thin))])       # horizontal, centre to eye
        self.right = np.cross(self.up, self.front)                           # screen right
        horizontal = np.cos(_AZIMUTH) * self.front + np.sin(_AZIMUTH) * self.right
        self.toward = np.cos(_ELEVATION) * horizontal + np.sin(_ELEVATION) * self.up
        # The light: from above, a little to the right and behind the shape, in the view's frame,
        # so that a y-up and a z-up file are shaded alike.
        self.light = 100 * self.right - 200 * self.front + 300 * self.up

    def ranges(self, radius: float) -> list[list[float]]:
        """Axis ranges: a cube of half-side ``radius`` around the centre (equal aspect ratio)."""
        return [[float(c - radius), float(c + radius)] for c in self.centre]

    def camera(self, radius: float, width_px: float, height_px: float) -> dict[str, Any]:
        """A plotly camera that shows the whole bounding sphere in a ``width_px`` x ``height_px`` scene.

        plotly maps the axis ranges to the cube [-0.5, 0.5]^3 and draws with a perspective
        camera of vertical field of view 45 degrees; the sphere of normalised radius
        ``rho`` is inside the view when ``rho / distance <= sin(half field of view)`` in both
        directions.
        """
        rho = 0.5 * self.radius / radius
        half_v = _FOV_Y / 2
        half_h = np.arctan(np.tan(half_v) * width_px / height_px)
        distance = rho * (1 + _MARGIN) / np.sin(min(half_v, half_h))
        eye = distance * self.toward
        return dict(up=dict(zip("xyz", map(float, self.up))), eye=dict(zip("xyz", map(float, eye))),
                    center=dict(x=0.0, y=0.0, z=0.0), projection=dict(type="perspective"))


def _scene(view: _View, radius: float, domain: dict[str, list[float]] | None, width_px: float,
           height_px: float) -> dict[str, Any]:
    axes = [dict(visible=False, range=r, autorange=False) for r in view.ranges(radius)]
    scene: dict[str, Any] = dict(xaxis=axes[0], yaxis=axes[1], zaxis=axes[2], aspectmode="manual",
                                 aspectratio=dict(x=1, y=1, z=1), camera=view.camera(radius, width_px, height_px))
    if domain is not None:
        scene["domain"] = domain
    return scene


def _wrap(text: str, width_chars: int) -> str:
    """Break ``text`` at spaces into lines of at most ``width_chars`` characters (plotly ``<br>``)."""
    lines: list[str] = []
    for word in text.split():
        if lines and len(lines[-1]) + 1 + len(word) <= width_chars:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return "<br>".join(lines)


def _trace(d: _Display, s: NDArray[np.float64] | None, *, colorscale: str, cmin: float | None, cmax: float | None,
           showscale: bool, view: _View, name: str | None = None, scene: str = "scene",
           colorbar: dict[str, Any] | None = None) -> Any:
    import plotly.graph_objects as go

    v, f = d.vertices, d.faces
    if f is None:  # a point cloud: markers coloured by the function
        marker: dict[str, Any] = dict(size=_POINT_SIZE, color="#5b7a99")
        if s is not None:
            marker.update(color=d.values(s), colorscale=colorscale, cmin=cmin, cmax=cmax, showscale=showscale)
            if colorbar is not None:
                marker["colorbar"] = colorbar
        return go.Scatter3d(x=v[:, 0], y=v[:, 1], z=v[:, 2], mode="markers", marker=marker, name=name, scene=scene,
                            hoverinfo="skip")
    kwargs: dict[str, Any] = dict(
        x=v[:, 0], y=v[:, 1], z=v[:, 2], i=f[:, 0], j=f[:, 1], k=f[:, 2], name=name, scene=scene,
        flatshading=False, lighting=dict(ambient=0.45, diffuse=0.8, specular=0.15, roughness=0.6),
        lightposition=dict(zip("xyz", map(float, view.light))), hoverinfo="skip",
    )
    if s is None:
        kwargs["color"] = "#b9c7d6"
    else:
        kwargs.update(intensity=d.values(s), intensitymode="vertex", colorscale=colorscale, cmin=cmin, cmax=cmax,
                      showscale=showscale)
        if colorbar is not None:
            kwargs["colorbar"] = colorbar
    return go.Mesh3d(**kwargs)


_TITLE_FONT = 13               # px; about 7 px per character
_COLORBAR_PX = 70              # room for a colour bar and its tick labels, in px
_ROW_GAP_PX = 10               # between rows of panels


def plot_mesh(
    mesh: Mesh | PointCloud,
    scalars: ArrayLike | None = None,
    *,
    title: str | None = None,
    colorscale: str = "RdBu_r",
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
    colorscale : str
        Any plotly colour scale name.
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

    s = _check_scalars(mesh, scalars)
    lo, hi = _colour_range(s, cmin, cmax, symmetric)
    view = _View(_positions(mesh), up)
    radius = view.radius * (1 + _MARGIN)
    top = 40 if title else 10
    fig = go.Figure(_trace(_Display(mesh, max_faces), s, colorscale=colorscale, cmin=lo, cmax=hi, view=view,
                           showscale=s is not None, colorbar=dict(len=0.8, thickness=12)))
    scene_width = _NOMINAL_WIDTH - (_COLORBAR_PX if s is not None else 0)
    fig.update_layout(title=tidy_label(title), height=height, margin=dict(l=0, r=0, t=top, b=0),
                      scene=_scene(view, radius, None, scene_width, height - top))
    return fig


def plot_meshes(
    meshes: Sequence[Mesh | PointCloud],
    scalars: Sequence[ArrayLike | None] | None = None,
    titles: Sequence[str] | None = None,
    *,
    colorscale: str = "RdBu_r",
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

    meshes = list(meshes)
    if not meshes:
        raise ValueError("plot_meshes needs at least one mesh.")
    if scalars is None:
        scalars = [None] * len(meshes)
    if len(scalars) != len(meshes):
        raise ValueError(f"got {len(scalars)} scalar arrays for {len(meshes)} meshes; pass one (or None) per mesh.")
    if titles is not None and len(titles) != len(meshes):
        raise ValueError(f"got {len(titles)} titles for {len(meshes)} meshes.")
    if cols is not None and (int(cols) != cols or cols < 1):
        raise ValueError(f"cols must be a positive integer; got {cols!r}.")
    if height is not None and (int(height) != height or height < 50):
        raise ValueError(f"height must be a number of pixels (at least 50) or None; got {height!r}.")
    values = [_check_scalars(m, s) for m, s in zip(meshes, scalars)]
    n = len(meshes)
    ranges = _panel_ranges(values, shared_colour_range, cmin, cmax, symmetric)
    # One colour bar per distinct range, beside the last panel drawn with it.
    last_of = {r: p for p, r in enumerate(ranges) if r is not None}
    shows = [r is not None and last_of[r] == p for p, r in enumerate(ranges)]
    cols = int(cols) if cols is not None else (n if n <= 4 else -(-n // 2))
    cols = min(cols, n)
    rows = -(-n // cols)
    views = [_View(_positions(m), up) for m in meshes]
    shared_radius = max(v.radius for v in views) * (1 + _MARGIN)

    # Columns: equal scenes; a column whose panels show a colour bar gets the bar's width more.
    gap = 0.01
    bar = _COLORBAR_PX / _NOMINAL_WIDTH
    has_bar = [any(shows[p] for p in range(c, n, cols)) for c in range(cols)]
    scene_w = (1 - cols * gap - bar * sum(has_bar)) / cols
    left = np.concatenate([[0.0], np.cumsum([gap + scene_w + (bar if b else 0) for b in has_bar])])[:-1] + gap / 2
    scene_px = scene_w * _NOMINAL_WIDTH

    chars = max(10, int((scene_w + gap) * _NOMINAL_WIDTH / (0.58 * _TITLE_FONT)))
    wrapped = [_wrap(tidy_label(t) or "", chars) for t in titles] if titles else None
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
        radius = shared_radius if same_scale else view.radius * (1 + _MARGIN)
        fig.update_layout({name: _scene(view, radius, dict(x=[x0, x1], y=[y0, scene_top]), scene_px,
                                        (scene_top - y0) * total_h)})
        lo, hi = r if r is not None else (None, None)
        colorbar = dict(x=x1, xanchor="left", xref="paper", y=(y0 + scene_top) / 2, yanchor="middle",
                        len=0.8 * (scene_top - y0), lenmode="fraction", thickness=10,
                        tickfont=dict(size=10)) if show else None
        fig.add_trace(_trace(_Display(mesh, max_faces), v, colorscale=colorscale, cmin=lo, cmax=hi, showscale=show,
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
    (one range per group).
    """
    n = len(values)
    if isinstance(shared, (bool, np.bool_)):
        groups: list[Hashable] = [0] * n if shared else list(range(n))
    elif isinstance(shared, str) or not isinstance(shared, Sequence) or len(shared) != n:
        raise ValueError(f"shared_colour_range must be True, False or one group label per mesh ({n}); "
                         f"got {shared!r}.")
    else:
        groups = list(shared)
    out: list[tuple[float, float] | None] = [None] * n
    for g in dict.fromkeys(groups):
        members = [p for p in range(n) if groups[p] == g and values[p] is not None]
        if not members:
            continue
        lo, hi = _colour_range(np.concatenate([values[p] for p in members]), cmin, cmax, symmetric)
        for p in members:
            out[p] = (float(lo), float(hi))
    return out


def _view_rotation(view: _View) -> NDArray[np.float64]:
    """Rows: screen right, into the screen, up -- a rotation (right = into x up)."""
    return np.array([view.right, -view.front, view.up])


def plot_mesh_static(
    mesh: Mesh | PointCloud,
    scalars: ArrayLike | None = None,
    *,
    ax: Any = None,
    cmap: str = "RdBu_r",
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

    s = _check_scalars(mesh, scalars)
    d = _Display(mesh, max_faces)
    view = _View(_positions(mesh), up)
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
            lo, hi = _colour_range(s, None, None, symmetric)
            colours = colormaps[cmap]((d.values(s) - lo) / (hi - lo))
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
        lo, hi = _colour_range(s, None, None, symmetric)
        colours = colormaps[cmap]((face_values - lo) / (hi - lo))
        colours[:, :3] *= shade[:, None]
    ax.add_collection3d(Poly3DCollection(tris, facecolors=colours, edgecolors="none"))
    return _finish_static(ax, view, elev, azim, title)


def _finish_static(ax: Any, view: _View, elev: float | None, azim: float | None, title: str | None) -> Any:
    """Equal axes holding the bounding sphere, the viewing angles and the title of a static figure."""
    r = view.radius * (1 + _MARGIN)
    ax.set(xlim=(-r, r), ylim=(-r, r), zlim=(-r, r))
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=np.degrees(_ELEVATION) if elev is None else elev,
                 azim=-90 + np.degrees(_AZIMUTH) if azim is None else azim)
    ax.set_axis_off()
    if title:
        ax.set_title(tidy_label(title))
    return ax


_LOOK_AHEAD = 3                # slider values tried for a first frame that is not blank


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

    def __init__(self, mesh: Mesh | PointCloud, frame: Callable[[Any], Any], values: Sequence[Any], description: str,
                 *, colorscale: str, symmetric: bool, max_faces: int, height: int, title: Callable[[Any], str] | None,
                 up: str | ArrayLike = "auto", start: Any = None) -> None:
        import ipywidgets as widgets
        import plotly.graph_objects as go

        values = list(values)
        if not values:
            raise ValueError("mesh_slider needs at least one slider value.")
        if start is None:
            start = _first_informative(frame, values)
        elif start not in values:
            raise ValueError(f"start={start!r} is not one of the slider values {values[:3]}...; pick one of them.")
        self.mesh, self._frame, self._values, self._title = mesh, frame, values, title
        self._symmetric, self._colorscale = symmetric, colorscale
        self._display = _Display(mesh, max_faces)
        self.figure = go.FigureWidget(plot_mesh(mesh, None, max_faces=max_faces, height=height, up=up))
        self._view = _View(_positions(mesh), up)
        self._radius = self._view.radius * (1 + _MARGIN)
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
            expected = _positions(self.mesh).shape
            if v.shape != expected:
                raise ValueError(f"frame returned positions of shape {v.shape}, expected {expected}.")
            v = self._display.values(v) if self._display.index is not None else v
        with self.figure.batch_update():
            trace = self.figure.data[0]
            if vertices is not None:
                trace.x, trace.y, trace.z = v[:, 0], v[:, 1], v[:, 2]
                self._fit(v)
            if arr is not None:
                s = _check_scalars(self.mesh, arr)
                lo, hi = _colour_range(s, None, None, self._symmetric)
                if self._display.faces is None:  # a point cloud: the markers carry the colours
                    trace.marker.update(color=self._display.values(s), colorscale=self._colorscale, cmin=lo, cmax=hi,
                                        showscale=True)
                else:
                    trace.intensity, trace.intensitymode = self._display.values(s), "vertex"
                    trace.colorscale, trace.cmin, trace.cmax, trace.showscale = self._colorscale, lo, hi, True
            if self._title is not None:
                self.figure.layout.title = tidy_label(self._title(value))

    def _fit(self, v: NDArray[np.float64]) -> None:
        """Grow the (cubic) axis ranges if moved vertices leave them; never shrink, so the view stays still."""
        reach = float(np.abs(v - self._view.centre).max()) * (1 + _MARGIN)
        if reach <= self._radius:
            return
        self._radius = reach
        scene = self.figure.layout.scene
        for axis, r in zip((scene.xaxis, scene.yaxis, scene.zaxis), self._view.ranges(reach)):
            axis.range = r

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)


def mesh_slider(
    mesh: Mesh | PointCloud,
    frame: Callable[[Any], Any],
    values: Sequence[Any],
    description: str = "n",
    *,
    colorscale: str = "RdBu_r",
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
