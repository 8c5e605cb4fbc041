"""What a figure shows: a mesh (decimated above ``max_faces``) or a point cloud (an evenly spaced subset),
the function's values on it, their colour range, and labels with Greek letters and subscripts.
"""

from __future__ import annotations

import re

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Array, Integer, Satisfies, validated
from ..geometry._mesh import Mesh
from ..geometry._pointcloud import PointCloud

__all__ = ["DEFAULT_MAX_FACES", "POINT_SIZE", "positions", "Display", "display_mesh", "SCALARS", "MAX_FACES", "check_scalars",
           "colour_range", "tidy_label", "default_colorscale", "DIVERGING", "SEQUENTIAL"]


DEFAULT_MAX_FACES = 40_000
#: The rule for ``max_faces``: at least one triangle (or point) to draw.
MAX_FACES = Integer(1, what="a positive integer (the most triangles, or points, drawn)")
POINT_SIZE = 3                # px, the markers of a point cloud


def positions(shape: Mesh | PointCloud) -> NDArray[np.float64]:
    """The vertices of a mesh or the points of a cloud."""
    if isinstance(shape, Mesh):
        return shape.vertices
    if isinstance(shape, PointCloud):
        return shape.points
    raise TypeError(f"expected a Mesh or a PointCloud, got {type(shape).__name__}; build one with "
                    "lbo.Mesh(vertices, faces) or lbo.PointCloud(points).")


class Display:
    """A mesh or cloud as shown on screen: possibly decimated, with a map back to the original
    vertices. ``faces`` is None for a point cloud."""

    faces: NDArray[np.int64] | None

    def __init__(self, mesh: Mesh | PointCloud, max_faces: int) -> None:
        positions(mesh)  # a Mesh or a PointCloud, or a TypeError naming what it got
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

        from .._support.optional_open3d import import_open3d

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


@validated(max_faces=MAX_FACES)
def display_mesh(mesh: Mesh | PointCloud, max_faces: int = DEFAULT_MAX_FACES
                 ) -> tuple[NDArray[np.float64], NDArray[np.int64] | None, NDArray[np.int64] | None]:
    """Vertices and faces to draw for ``mesh`` and, if decimated, the original vertex behind each.

    For a :class:`~lbo_notebooks.PointCloud` the faces are None and the vertices are its points
    (an evenly spaced subset of at most ``max_faces`` of them).
    """
    d = Display(mesh, max_faces)
    return d.vertices, d.faces, d.index


def _one_per_vertex(mesh: Mesh | PointCloud, **_: object) -> str:
    what = "point" if isinstance(mesh, PointCloud) else "vertex"
    return f"have one value per {what}, shape ({len(positions(mesh))},)"


#: The rule for ``scalars`` beside ``mesh`` (a Mesh or a PointCloud): None, or one finite value per
#: vertex (per point), as a float64 array.
SCALARS = Array(1, rows=lambda mesh, **_: len(positions(mesh)), none=True, what=_one_per_vertex,
                hint="plotly would draw them as holes. Replace them first")


def check_scalars(mesh: Mesh | PointCloud, scalars: ArrayLike | None) -> NDArray[np.float64] | None:
    """``scalars`` checked by :data:`SCALARS` for ``mesh``, where no table sees them (one of many meshes, a frame)."""
    return SCALARS.check(scalars, "scalars", {"mesh": mesh, "scalars": scalars})


def colour_range(s: NDArray[np.float64] | None, cmin: float | None, cmax: float | None,
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


#: The default colour scales: diverging (a neutral middle at zero) for a function of both signs or a
#: range centred on zero, sequential for one of one sign (a distance, a density, a curvature floor),
#: whose low end is not "zero" and whose middle means nothing.
DIVERGING, SEQUENTIAL = "RdBu_r", "Viridis"


def default_colorscale(lo: float | None, hi: float | None, symmetric: bool) -> str:
    """The colour scale (a plotly name) for a colour range ``[lo, hi]`` when the caller gives none.

    >>> default_colorscale(-1.0, 2.0, False), default_colorscale(0.0, 5.0, False), default_colorscale(0.0, 5.0, True)
    ('RdBu_r', 'Viridis', 'RdBu_r')
    """
    if symmetric or lo is None or hi is None or (lo < 0 < hi):
        return DIVERGING
    return SEQUENTIAL


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


@validated(text=Satisfies(lambda text: isinstance(text, str), none=True,
                          message="text must be a string (or None), got {value!r} of type {type}."))
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
