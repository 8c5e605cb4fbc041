"""Gaussian curvature and the metrics ``|K|^alpha g`` (scale-invariant for ``alpha = 1``).

The metric ``g_alpha = |K|^alpha g`` (Aflalo, Kimmel, Raviv 2013) interpolates between the regular
metric (``alpha = 0``) and a scale-invariant one (``alpha = 1``). In two dimensions the Dirichlet
energy is conformally invariant, so the cotangent stiffness ``W`` does not change: **only the mass
changes** (docs/maths.md, "Scale-invariant metrics"). This module computes that mass; :func:`lbo_notebooks.eigenbasis`
uses it when called with ``alpha != 0``.

Regularisation (why ``|K|`` needs one, and which one)
-----------------------------------------------------
``|K|`` vanishes on flat regions, which would give them zero mass. The conformal factor used here is

``rho_i = max(kappa_i, floor * 4 pi / area)``, where
``kappa_i = sum_j |delta_j| / sum_j a_j`` over the *interior* vertices ``j`` of the closed one-ring
of ``i`` (``i`` and its neighbours), ``delta`` the angle defects and ``a`` the mixed Voronoi areas.

* ``kappa`` averages ``|K|`` over a one-ring, which tames the vertex-to-vertex noise of angle
  defects on irregular meshes.
* ``4 pi / area`` is the curvature of the round sphere with the same area, so the floor is a
  dimensionless fraction of a curvature scale that is never zero (unlike the mean ``|K|``, which is
  zero on a flat surface) and that scales as ``1 / s^2`` like ``kappa``. Hence ``rho * a`` is
  unchanged by a uniform scaling: ``alpha = 1`` is exactly scale-invariant, and the result does
  not depend on the mesh's units.
* The turning angle ``pi - sum of angles`` at a boundary vertex is the geodesic curvature of the
  boundary curve, not Gaussian curvature of the surface, so it is left out of ``kappa`` (boundary
  vertices take the curvature of their interior neighbours). On a flat rectangle or disk every
  interior defect is zero, ``rho`` is the floor everywhere, the metric is a constant multiple
  ``c = (floor * 4 pi / area)^alpha`` of ``g``: the eigenfunctions are the regular ones (divided
  by ``sqrt(c)`` to stay A-orthonormal) and the eigenvalues are the regular ones divided by ``c``.

Mass matrices (``kind``)
------------------------
* ``"voronoi"`` / ``"barycentric"`` (lumped): per vertex, ``A_alpha[i, i] = rho_i^alpha A[i, i]``.
* ``"consistent"``: per triangle, the local P1 matrix ``|t|/12 [[2,1,1],[1,2,1],[1,1,2]]`` times
  ``rho_t^alpha`` with ``rho_t`` the mean of ``rho`` over the triangle's corners. It stays
  symmetric positive definite, and ``alpha = 1`` stays scale-invariant.

Everything that does not depend on ``alpha`` (angle defects, vertex areas, ``rho``) is computed once
per mesh with :meth:`Mesh.cached` and reused across alphas.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .._support.validation import Number, Options, validated
from ..geometry._mesh import Mesh, per_mesh
from ._cotangent import MASS_KIND, MESH, MassKind, corner_angles, mass_matrix

__all__ = [
    "DEFAULT_FLOOR",
    "angle_defects",
    "gaussian_curvature",
    "metric_curvature",
    "conformal_factor",
    "metric_mass_matrix",
]

#: Default floor of the conformal factor, as a fraction of ``4 pi / area``.
DEFAULT_FLOOR = 1e-3


_ALPHA = Number(0, 1, what="a number in [0, 1] (0: regular metric, 1: scale-invariant)")
_FLOOR = Number(
    0, open_low=True, what="a positive finite number (a fraction of 4 pi / area, e.g. 1e-3)",
    hint="a zero floor would give flat regions zero mass and a singular mass matrix",
)


@per_mesh
def _topology(m: Mesh) -> tuple[NDArray[np.bool_], sp.csr_matrix]:
    """Interior-vertex mask and the closed one-ring (vertex + neighbours) as a 0/1 CSR matrix.

    Built from the faces' directed edges with one sparse sum (faster than the mesh's sorted edge
    table): an undirected edge used by one face is a boundary edge.
    """
    f, n = m.faces, m.n_vertices
    i = f.ravel()
    j = f[:, [1, 2, 0]].ravel()
    directed = sp.csr_matrix((np.ones(i.size), (i, j)), shape=(n, n))
    undirected = (directed + directed.T).tocoo()
    interior = np.ones(n, dtype=bool)
    on_boundary = undirected.data == 1.0
    interior[undirected.row[on_boundary]] = False
    ring = sp.csr_matrix((np.ones(undirected.nnz), (undirected.row, undirected.col)), shape=(n, n))
    closed = (ring + sp.identity(n, format="csr")).tocsr()
    interior.setflags(write=False)
    return interior, closed


def _interior_mask(mesh: Mesh) -> NDArray[np.bool_]:
    return _topology(mesh)[0]


@per_mesh
def _angle_defects(m: Mesh) -> NDArray[np.float64]:
    # angle = arccot(cot) in (0, pi); the three angles of each face sum to pi to round-off.
    angles = corner_angles(m)
    total = np.bincount(m.faces.ravel(), weights=angles.ravel(), minlength=m.n_vertices)
    full = np.where(_interior_mask(m), 2.0 * np.pi, np.pi)
    out = full - total
    out.setflags(write=False)
    return out


@validated(mesh=MESH)
def angle_defects(mesh: Mesh) -> NDArray[np.float64]:
    """Angle defect at each vertex: ``2 pi - sum of angles`` (``pi - sum`` on the boundary).

    The defects sum to ``2 pi chi`` (discrete Gauss–Bonnet, exact up to round-off) and do not
    change under a uniform scaling. Returns a read-only array of shape (n,), cached per mesh.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> d = angle_defects(shapes.icosphere(2))
    >>> bool(abs(d.sum() - 4 * np.pi) < d.size * np.finfo(float).eps * 4 * np.pi)  # Gauss-Bonnet
    True
    """
    return _angle_defects(mesh)


@per_mesh
def _gaussian_curvature(m: Mesh) -> NDArray[np.float64]:
    out = angle_defects(m) / _voronoi_areas(m)
    out.setflags(write=False)
    return out


@validated(mesh=MESH)
def gaussian_curvature(mesh: Mesh) -> NDArray[np.float64]:
    """Gaussian curvature per vertex: angle defect divided by the mixed Voronoi vertex area.

    ``K * a`` with ``a = mass_matrix(mesh, "voronoi").diagonal()`` gives back the angle defects, so
    ``(K * a).sum() == 2 pi chi`` to round-off (Gauss–Bonnet). On a boundary vertex the defect is
    ``pi - sum of angles``: it holds the geodesic curvature of the boundary there, which is what
    Gauss–Bonnet with boundary needs. Converges to ``1 / R^2`` on a sphere of radius ``R``.

    Parameters
    ----------
    mesh : Mesh

    Returns
    -------
    ndarray, shape (n,)
        Read-only, cached per mesh.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> K = gaussian_curvature(shapes.icosphere(3, radius=2.0))
    >>> bool(abs(np.median(K) - 0.25) < 0.01)
    True
    """
    return _gaussian_curvature(mesh)


@per_mesh
def _voronoi_areas(mesh: Mesh) -> NDArray[np.float64]:
    return mass_matrix(mesh, "voronoi").diagonal()


@per_mesh
def _kappa(m: Mesh) -> NDArray[np.float64]:
    """One-ring summed |angle defect| over interior vertices / their summed Voronoi area."""
    interior_mask, closed = _topology(m)
    interior = interior_mask.astype(np.float64)
    n = m.n_vertices
    num = closed @ (np.abs(angle_defects(m)) * interior)
    den = closed @ (_voronoi_areas(m) * interior)
    out = np.divide(num, den, out=np.zeros(n), where=den > 0)
    out.setflags(write=False)
    return out


@per_mesh
def _rho(m: Mesh, floor: float) -> NDArray[np.float64]:
    out = np.maximum(_kappa(m), floor * 4.0 * np.pi / m.area)
    out.setflags(write=False)
    return out


@validated(mesh=MESH, floor=_FLOOR)
def metric_curvature(mesh: Mesh, *, floor: float = DEFAULT_FLOOR) -> NDArray[np.float64]:
    """The regularised ``|K|`` per vertex that defines the metric, ``rho`` (see the module notes).

    ``rho_i = max(kappa_i, floor * 4 pi / area)`` with ``kappa_i`` the summed ``|angle defect|``
    over the interior vertices of the closed one-ring of ``i`` divided by their summed Voronoi
    area. ``rho`` scales as ``1 / s^2`` under a uniform scaling by ``s``.

    Parameters
    ----------
    mesh : Mesh
    floor : float > 0, default 1e-3
        Lower bound as a fraction of ``4 pi / area`` (the curvature of the round sphere with the
        same area). Dimensionless, so the same value works in any units.

    Returns
    -------
    ndarray, shape (n,), positive
        Read-only, cached per mesh and floor.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> rho = metric_curvature(shapes.rectangle(2.0, 1.0, 8, 4))  # flat: the floor everywhere
    >>> bool(np.allclose(rho, 1e-3 * 4 * np.pi / 2.0))
    True
    """
    return _rho(mesh, floor)


@validated(
    alpha=_ALPHA, mesh=MESH, floor=_FLOOR,
    where=Options("vertex", "face", message="where must be 'vertex' or 'face', got {value!r}."),
)
def conformal_factor(
    mesh: Mesh,
    alpha: float,
    *,
    floor: float = DEFAULT_FLOOR,
    where: Literal["vertex", "face"] = "vertex",
) -> NDArray[np.float64]:
    """The conformal factor ``rho^alpha`` of the metric ``|K|^alpha g``, for plotting or weighting.

    Parameters
    ----------
    mesh : Mesh
    alpha : float in [0, 1]
    floor : float > 0, default 1e-3
        See :func:`metric_curvature`.
    where : {"vertex", "face"}
        ``"vertex"``: ``rho_i^alpha`` (used by the lumped masses); ``"face"``: ``rho_t^alpha`` with
        ``rho_t`` the mean of ``rho`` over the face's corners (used by the consistent mass).

    Returns
    -------
    ndarray, shape (n,) or (m,)

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> m = shapes.bumpy_sphere(2)
    >>> float(conformal_factor(m, 0.0).max()), conformal_factor(m, 0.5, where="face").shape
    (1.0, (320,))
    """
    rho = metric_curvature(mesh, floor=floor)
    if where == "vertex":
        return rho**alpha
    return rho[mesh.faces].mean(axis=1) ** alpha


@validated(mesh=MESH, alpha=_ALPHA, floor=_FLOOR, mass_kind=MASS_KIND)
def metric_mass_matrix(
    mesh: Mesh,
    alpha: float,
    *,
    mass_kind: MassKind = "voronoi",
    floor: float = DEFAULT_FLOOR,
) -> sp.csr_matrix:
    """Mass matrix of the metric ``|K|^alpha g``; the stiffness ``W`` is unchanged.

    Parameters
    ----------
    mesh : Mesh
    alpha : float in [0, 1]
        ``0`` returns exactly ``mass_matrix(mesh, mass_kind)``; ``1`` is the scale-invariant metric,
        whose spectrum does not change when the shape is scaled. In general the eigenvalues
        scale as ``s^(-2 (1 - alpha))``.
    mass_kind : {"voronoi", "barycentric", "consistent"}
        Lumped kinds scale each vertex's area by ``rho_i^alpha``; ``"consistent"`` scales each
        triangle's local matrix by ``rho_t^alpha`` (see the module notes).
    floor : float > 0, default 1e-3
        Regularisation of ``|K|`` as a fraction of ``4 pi / area`` (see :func:`metric_curvature`).
        On a flat surface the metric becomes a constant multiple of ``g``.

    Returns
    -------
    scipy.sparse.csr_matrix, shape (n, n)
        Symmetric positive definite.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> m = shapes.bumpy_sphere(2)
    >>> big = m.with_vertices(3.0 * m.vertices)
    >>> a, b = metric_mass_matrix(m, 1.0), metric_mass_matrix(big, 1.0)
    >>> bool(abs(a.diagonal() - b.diagonal()).max() < 1e-12 * a.diagonal().max())
    True
    """
    base = mass_matrix(mesh, mass_kind)
    if alpha == 0.0:
        return base
    if mass_kind == "consistent":
        f, n = mesh.faces, mesh.n_vertices
        weight = mesh.face_areas * conformal_factor(mesh, alpha, floor=floor, where="face")
        local = np.array([[2, 1, 1], [1, 2, 1], [1, 1, 2]], dtype=np.float64).ravel() / 12.0
        rows = np.repeat(f, 3, axis=1).ravel()
        cols = np.tile(f, (1, 3)).ravel()
        A = sp.coo_matrix(((weight[:, None] * local[None, :]).ravel(), (rows, cols)), shape=(n, n)).tocsr()
        A.sum_duplicates()
        A.sort_indices()
        return A
    scale = conformal_factor(mesh, alpha, floor=floor, where="vertex")
    return sp.diags(base.diagonal() * scale).tocsr()
