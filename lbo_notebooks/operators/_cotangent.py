"""Discrete Laplace–Beltrami operator: cotangent stiffness ``W`` and mass ``A`` (P1 elements).

Conventions (see docs/maths.md, "Operators"): ``W`` is positive semidefinite, ``W @ 1 = 0`` and
``f @ W @ f`` is the Dirichlet energy of the piecewise-linear function with vertex values ``f``.
The eigenproblem is ``W phi = lam A phi``.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .._support.validation import Options, Satisfies, validated
from ..geometry._mesh import Mesh, per_mesh

__all__ = [
    "stiffness_matrix", "mass_matrix", "face_cotangents", "corner_angles", "MassKind", "MASS_KINDS", "MASS_KIND", "MESH",
]

MassKind = Literal["voronoi", "barycentric", "consistent"]
MASS_KINDS: tuple[str, ...] = ("voronoi", "barycentric", "consistent")
#: The ``mass_kind`` constraint of every table that takes one (:func:`~lbo_notebooks._support.validation.validated`).
MASS_KIND = Options(*MASS_KINDS)
#: The rule for a mesh argument (every operator's, and the analyses' that take a mesh).
MESH = Satisfies(lambda mesh: isinstance(mesh, Mesh), message=(
    "{name} must be an lbo_notebooks.Mesh, got {type}; build one with lbo_notebooks.Mesh(vertices, faces)."))


@per_mesh
def _face_cotangents(m: Mesh) -> NDArray[np.float64]:
    v, f = m.vertices, m.faces
    p = v[f]  # (m, 3, 3): corners
    cot = np.empty(f.shape, dtype=np.float64)
    double_area = 2.0 * m.face_areas
    for k in range(3):
        a = p[:, (k + 1) % 3] - p[:, k]
        b = p[:, (k + 2) % 3] - p[:, k]
        # cot = cos / sin = (a . b) / |a x b|
        cot[:, k] = np.einsum("ij,ij->i", a, b) / double_area
    cot.setflags(write=False)
    return cot


@validated(mesh=MESH)
def face_cotangents(mesh: Mesh) -> NDArray[np.float64]:
    """Cotangent of each corner angle, shape (m, 3): column k is the angle at ``faces[:, k]``.

    Examples
    --------
    >>> from lbo_notebooks import Mesh
    >>> m = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> face_cotangents(m).round(12).tolist()
    [[0.0, 1.0, 1.0]]
    """
    return _face_cotangents(mesh)


@validated(mesh=MESH)
def corner_angles(mesh: Mesh) -> NDArray[np.float64]:
    """Interior angle (radians) at each corner, shape (m, 3): column k is the angle at ``faces[:, k]``.

    Examples
    --------
    >>> from lbo_notebooks import Mesh
    >>> m = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> np.degrees(corner_angles(m)).round(6).tolist()
    [[90.0, 45.0, 45.0]]
    """
    # cot = cos/sin with sin > 0, so arctan2(1, cot) is the angle in (0, pi), accurate near 0 and pi.
    return np.arctan2(1.0, face_cotangents(mesh))


@per_mesh
def _stiffness(m: Mesh) -> sp.csr_matrix:
    f, n = m.faces, m.n_vertices
    cot = face_cotangents(m)
    # The edge opposite corner k joins corners k+1 and k+2.
    i = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])
    j = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
    w = -0.5 * np.concatenate([cot[:, 0], cot[:, 1], cot[:, 2]])
    off = sp.coo_matrix((w, (i, j)), shape=(n, n))
    off = (off + off.T).tocsr()
    W = (off - sp.diags(np.asarray(off.sum(axis=1)).ravel())).tocsr()
    W.sum_duplicates()
    W.sort_indices()
    return W


@validated(mesh=MESH)
def stiffness_matrix(mesh: Mesh) -> sp.csr_matrix:
    """Cotangent stiffness matrix ``W`` (n x n, CSR), positive semidefinite.

    ``W[i, j] = -(cot a_ij + cot b_ij) / 2`` for an interior edge (one cotangent on a boundary
    edge) and ``W[i, i] = -sum_j W[i, j]``, so constants lie in its kernel (Neumann boundary).

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> W = stiffness_matrix(shapes.icosphere(2))
    >>> bool(abs(W @ np.ones(W.shape[0])).max() < 1e-12 * abs(W).max())
    True
    """
    return _stiffness(mesh).copy()


def _voronoi_corner_areas(mesh: Mesh) -> NDArray[np.float64]:
    """Mixed Voronoi area that each triangle gives to each of its corners, shape (m, 3)."""
    v, f = mesh.vertices, mesh.faces
    cot = face_cotangents(mesh)
    area = mesh.face_areas
    # Squared length of the edge opposite each corner k.
    sq = np.stack(
        [np.sum((v[f[:, (k + 1) % 3]] - v[f[:, (k + 2) % 3]]) ** 2, axis=1) for k in range(3)], axis=1
    )
    corner = np.empty_like(cot)
    for k in range(3):
        k1, k2 = (k + 1) % 3, (k + 2) % 3
        # Edge k->k1 is opposite k2, edge k->k2 is opposite k1.
        corner[:, k] = (sq[:, k2] * cot[:, k2] + sq[:, k1] * cot[:, k1]) / 8.0
    obtuse = cot < 0  # obtuse angle at that corner
    any_obtuse = obtuse.any(axis=1)
    corner[any_obtuse] = np.where(obtuse[any_obtuse], 0.5, 0.25) * area[any_obtuse, None]
    return corner


@per_mesh
def _mass(m: Mesh, mass_kind: str) -> sp.csr_matrix:
    f, n = m.faces, m.n_vertices
    if mass_kind == "consistent":
        area = m.face_areas
        rows = np.repeat(f, 3, axis=1).ravel()
        cols = np.tile(f, (1, 3)).ravel()
        local = np.array([[2, 1, 1], [1, 2, 1], [1, 1, 2]], dtype=np.float64).ravel() / 12.0
        vals = (area[:, None] * local[None, :]).ravel()
        A = sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()
        A.sum_duplicates()
        A.sort_indices()
        return A
    if mass_kind == "barycentric":
        corner = np.repeat(m.face_areas[:, None] / 3.0, 3, axis=1)
    else:
        corner = _voronoi_corner_areas(m)
    diag = np.bincount(f.ravel(), weights=corner.ravel(), minlength=n)
    return sp.diags(diag).tocsr()


@validated(mesh=MESH, mass_kind=MASS_KIND)
def mass_matrix(mesh: Mesh, mass_kind: MassKind = "voronoi") -> sp.csr_matrix:
    """Mass matrix ``A`` (n x n, CSR) of the given kind (``mass_kind``).

    Parameters
    ----------
    mesh : Mesh
    mass_kind : {"voronoi", "barycentric", "consistent"}
        ``"voronoi"``: lumped mixed Voronoi areas (Meyer et al. 2003); ``"barycentric"``: lumped,
        a third of each incident triangle; ``"consistent"``: the full P1 Gram matrix
        ``|t|/12 [[2,1,1],[1,2,1],[1,1,2]]``. All three sum to the surface area.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> m = shapes.rectangle(2.0, 1.0, 4, 2)
    >>> float(mass_matrix(m).sum())
    2.0
    """
    return _mass(mesh, mass_kind).copy()
