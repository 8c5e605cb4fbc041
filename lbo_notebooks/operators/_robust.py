"""The robust Laplacian: a Laplace–Beltrami operator for any triangle soup and for point clouds.

The cotangent operator (:mod:`lbo_notebooks.operators._cotangent`) needs an edge-manifold mesh with
well-shaped triangles. Real scans break both rules: edges shared by three or more faces, pinched
("bowtie") vertices, needle triangles. The intrinsic *tufted* Laplacian of Sharp & Crane (2020,
"A Laplacian for Nonmanifold Triangle Meshes", package ``robust-laplacian``) serves all of them:
it builds the tufted cover of the mesh, flips it to an intrinsic Delaunay triangulation and returns
the cotangent pair of that cover. On a mesh that is already intrinsic Delaunay it *is* the
cotangent stiffness with the barycentric (lumped) mass.

Conventions are those of :mod:`lbo_notebooks.operators._cotangent`: ``stiffness`` is positive semidefinite
with constants in its kernel, ``mass`` is diagonal and positive, and the eigenproblem is
``stiffness phi = lam mass phi``. Hence one zero eigenvalue per connected component: a scan in
132 pieces has 132 (near-)zero eigenvalues before the first one that describes shape.

Examples
--------
>>> from lbo_notebooks import shapes
>>> from lbo_notebooks.operators._cotangent import stiffness_matrix
>>> sphere = shapes.icosphere(2)          # intrinsic Delaunay: the two operators agree
>>> W, A = robust_operators(sphere)
>>> bool(abs(W - stiffness_matrix(sphere)).max() < 1e-12 * abs(W).max())
True
>>> cotan_defects(sphere)
[]
"""

from __future__ import annotations

from typing import Any, Literal

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .._support.validation import Integer, Number, Satisfies, is_integer, validated
from ..geometry._mesh import Mesh, MeshError
from ..geometry._pointcloud import PointCloud
from ..geometry._rescaling import length_exponent
from ._cotangent import MESH

__all__ = [
    "LAPLACIANS",
    "Laplacian",
    "LaplacianWarning",
    "NEEDLE_ANGLE",
    "N_NEIGHBORS",
    "check_referenced",
    "cotan_defects",
    "non_manifold_vertices",
    "robust_operators",
    "point_cloud_operators",
]

Laplacian = Literal["auto", "cotan", "robust"]
LAPLACIANS: tuple[str, ...] = ("auto", "cotan", "robust")

#: A triangle with a corner angle below this (radians) is a needle: its cotangent weight exceeds
#: 1e4, so the stiffness matrix mixes entries of wildly different size (badly conditioned);
#: intrinsic Delaunay flips remove such weights.
NEEDLE_ANGLE = 1e-4

#: Neighbours of each point in its local triangulation, by default; on a cloud of at most this many
#: points the default means all the others (``n_points - 1``), so every cloud PointCloud accepts has one.
N_NEIGHBORS = 30

#: robust-laplacian's default: edge lengths are padded by this fraction of the mean edge length
#: wherever a triangle is (nearly) degenerate, so that every intrinsic triangle is valid.
MOLLIFY_FACTOR = 1e-5

_MOLLIFY = Number(0, what=f"a number >= 0 (default {MOLLIFY_FACTOR:g})")


class LaplacianWarning(UserWarning):
    """Issued by :func:`~lbo_notebooks.eigenbasis` when it chose the robust Laplacian; says why."""


@validated(mesh=MESH)
def non_manifold_vertices(mesh: Mesh) -> NDArray[np.int64]:
    """Sorted indices of vertices whose faces do not form one edge-connected fan (bowties).

    Two faces around a vertex are joined when they share an edge through that vertex; a manifold
    vertex (interior or on the boundary) has all its faces in one such group.

    Examples
    --------
    >>> bowtie = Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [-1, 0, 0], [-1, -1, 0]], [[0, 1, 2], [0, 3, 4]])
    >>> non_manifold_vertices(bowtie).tolist()
    [0]
    """

    def compute(m: Mesh) -> NDArray[np.int64]:
        from scipy.sparse.csgraph import connected_components

        f, n = m.faces, m.n_vertices
        n_corners = 3 * len(f)
        corner = np.arange(n_corners).reshape(-1, 3)  # corner id of (face, slot)
        # Half-edge (a -> b) of face t, slots (j, j+1): both its endpoints are corners of t.
        a_slot = np.concatenate([corner[:, 0], corner[:, 1], corner[:, 2]])
        b_slot = np.concatenate([corner[:, 1], corner[:, 2], corner[:, 0]])
        a, b = f.ravel()[a_slot], f.ravel()[b_slot]
        lo, hi = np.minimum(a, b), np.maximum(a, b)
        lo_corner = np.where(a == lo, a_slot, b_slot)
        hi_corner = np.where(a == lo, b_slot, a_slot)
        key = lo * np.int64(n) + hi
        order = np.argsort(key, kind="stable")
        same = key[order][1:] == key[order][:-1]  # consecutive half-edges on one edge
        h1, h2 = order[:-1][same], order[1:][same]
        rows = np.concatenate([lo_corner[h1], hi_corner[h1]])
        cols = np.concatenate([lo_corner[h2], hi_corner[h2]])
        graph = sp.coo_matrix((np.ones(rows.size), (rows, cols)), shape=(n_corners, n_corners))
        n_fans, label = connected_components(graph, directed=False)
        # Joined corners share their vertex, so each fan (component) belongs to one vertex.
        fan_vertex = np.empty(n_fans, dtype=np.int64)
        fan_vertex[label] = f.ravel()
        per_vertex = np.bincount(fan_vertex, minlength=n)
        out = np.flatnonzero(per_vertex > 1).astype(np.int64)
        out.setflags(write=False)
        return out

    return mesh.cached("non_manifold_vertices", compute)


@validated(mesh=MESH)
def cotan_defects(mesh: Mesh) -> list[str]:
    """Why the cotangent Laplacian cannot serve ``mesh``: one phrase per defect, [] if it can.

    Checked: edges shared by more than two faces, non-manifold (bowtie) vertices, zero-area
    faces and needle triangles (a corner angle below :data:`NEEDLE_ANGLE`). Meshes built with
    ``Mesh(..., check=True)`` or returned by ``load_mesh(path, clean=True)`` have no zero-area faces.

    Examples
    --------
    >>> v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]]
    >>> fin = Mesh(v, [[0, 1, 2], [1, 0, 3], [0, 1, 4]], check=False)   # three fins on edge 0-1
    >>> cotan_defects(fin)
    ['1 non-manifold edge (shared by more than two faces)']
    """
    from ._cotangent import corner_angles

    def plural(n: int, one: str, many: str) -> str:
        return f"{n} {one if n == 1 else many}"

    reasons = []
    n_edges = int(np.count_nonzero(mesh.edge_face_counts > 2))
    if n_edges:
        reasons.append(f"{plural(n_edges, 'non-manifold edge', 'non-manifold edges')} (shared by more than two faces)")
    n_vertices = len(non_manifold_vertices(mesh))
    if n_vertices:
        reasons.append(f"{plural(n_vertices, 'non-manifold vertex', 'non-manifold vertices')} (faces meeting only at a point)")
    scale = max(mesh.diagonal, np.finfo(float).tiny) ** 2
    flat = mesh.face_areas <= 1e-14 * scale
    n_flat = int(np.count_nonzero(flat))
    if n_flat:
        reasons.append(plural(n_flat, "zero-area face", "zero-area faces"))
    if n_flat < mesh.n_faces:
        with np.errstate(invalid="ignore", divide="ignore"):
            angles = corner_angles(mesh)
        n_needle = int(np.count_nonzero((angles.min(axis=1) < NEEDLE_ANGLE) & ~flat))
        if n_needle:
            reasons.append(f"{plural(n_needle, 'needle triangle', 'needle triangles')} (a corner angle below {NEEDLE_ANGLE:g} rad)")
    return reasons


def check_referenced(mesh: Mesh) -> None:
    used = np.zeros(mesh.n_vertices, dtype=bool)
    used[mesh.faces.ravel()] = True
    if not used.all():
        first = int(np.flatnonzero(~used)[0])
        raise MeshError(
            f"{int((~used).sum())} vertices belong to no face (first: vertex {first}); they get no mass and "
            "no Laplacian is defined there. Drop them: lbo.clean_mesh(mesh) or load_mesh(path, clean=True)."
        )


@validated(
    mesh=Satisfies(lambda mesh: isinstance(mesh, Mesh), message=lambda name, value: (
        f"robust_operators needs a Mesh, got {type(value).__name__}; for points use point_cloud_operators.")),
    mollify_factor=_MOLLIFY,
)
def robust_operators(mesh: Mesh, *, mollify_factor: float = MOLLIFY_FACTOR) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """The tufted intrinsic Laplacian of ``mesh``: ``(stiffness, mass)``, CSR float64.

    ``stiffness`` is the cotangent matrix of the intrinsic Delaunay tufted cover (positive
    semidefinite), ``mass`` its lumped (barycentric, diagonal) mass. Works on any triangle soup
    without unreferenced vertices: non-manifold edges and vertices, needles, zero-area faces
    (after mollification), non-orientable pieces, many components.

    Parameters
    ----------
    mesh : Mesh
        Any mesh, also one built with ``check=False``.
    mollify_factor : float >= 0
        Edge-length padding, as a fraction of the mean edge length, for (nearly) degenerate
        triangles (robust-laplacian's ``mollify_factor``). ``0`` turns it off.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> W, A = robust_operators(shapes.icosphere(1))
    >>> bool(abs(W @ np.ones(42)).max() < 1e-12 * abs(W).max()), round(float(A.sum() / (4 * np.pi)), 2)
    (True, 0.93)
    """
    check_referenced(mesh)

    def compute(m: Mesh) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        import robust_laplacian

        return _in_unit_size(
            lambda unit: robust_laplacian.mesh_laplacian(unit, np.ascontiguousarray(m.faces), mollify_factor=float(mollify_factor)),
            m.vertices,
            "tufted Laplacian",
        )

    W, A = mesh.cached(f"robust_operators:{float(mollify_factor)!r}", compute)
    return W.copy(), A.copy()


def _max_neighbors(cloud: PointCloud, n_neighbors: Any, **_: Any) -> int:
    """``n_points - 1``; the default :data:`N_NEIGHBORS` is always allowed (it means ``n_points - 1`` on small clouds)."""
    if is_integer(n_neighbors) and n_neighbors == N_NEIGHBORS:
        return max(N_NEIGHBORS, cloud.n_points - 1)
    return cloud.n_points - 1


@validated(
    cloud=Satisfies(lambda cloud: isinstance(cloud, PointCloud), message=lambda name, value: (
        f"point_cloud_operators needs a PointCloud, got {type(value).__name__}.")),
    n_neighbors=Integer(
        3, _max_neighbors,
        what=lambda cloud, **_: f"an integer between 3 and the number of points - 1 ({cloud.n_points - 1})",
        hint="the default 30 (n_points - 1 on small clouds) suits most clouds",
    ),
    mollify_factor=_MOLLIFY,
)
def point_cloud_operators(
    cloud: PointCloud, *, n_neighbors: int = N_NEIGHBORS, mollify_factor: float = MOLLIFY_FACTOR
) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """The point-cloud Laplacian of Sharp & Crane (2020): ``(stiffness, mass)``, CSR float64.

    Each point's ``n_neighbors`` nearest neighbours are triangulated locally; the union of these
    small triangulations is a non-manifold mesh whose tufted Laplacian is returned. Neighbourhoods
    are *Euclidean*: where two sheets of the surface are closer than a neighbourhood's radius
    (thin parts, touching legs), they short-cut the surface.

    ``n_neighbors``: the default :data:`N_NEIGHBORS` (30) means ``n_points - 1`` on a cloud of at
    most 30 points (every cloud :class:`~lbo_notebooks.PointCloud` accepts has a default); any
    other value must lie between 3 and ``n_points - 1``.

    Examples
    --------
    >>> from lbo_notebooks import PointCloud, shapes
    >>> W, A = point_cloud_operators(PointCloud(shapes.icosphere(3).vertices))
    >>> W.shape, bool(abs(A.sum() / (4 * np.pi) - 1) < 0.05)
    ((642, 642), True)
    """
    if n_neighbors == N_NEIGHBORS:
        n_neighbors = min(N_NEIGHBORS, cloud.n_points - 1)

    def compute(c: Any) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        import robust_laplacian

        return _in_unit_size(
            lambda unit: robust_laplacian.point_cloud_laplacian(unit, mollify_factor=float(mollify_factor), n_neighbors=int(n_neighbors)),
            c.points,
            "point-cloud Laplacian",
        )

    W, A = cloud.cached(f"point_cloud_operators:{int(n_neighbors)}:{float(mollify_factor)!r}", compute)
    return W.copy(), A.copy()


def _in_unit_size(build: Any, points: NDArray[np.float64], name: str) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """``build(points / 2**e)``, ``2**e`` the power of two nearest their size, as ``(stiffness, mass * 4**e)``.

    robust-laplacian then always sees a shape of about unit size, whatever the units: the stiffness
    does not depend on them (cotangents are ratios), the mass goes back exactly (a power of two). A
    crash of the library on points it cannot triangulate becomes a :class:`MeshError`.
    """
    e = length_exponent(points)
    try:
        L, M = build(np.ascontiguousarray(np.ldexp(points, -e)))
    except RuntimeError as error:  # geometry-central's GC_SAFETY_ASSERT ("unreferenced vertex ...")
        raise MeshError(
            f"the {name} (robust-laplacian) could not triangulate these points ({error}). Some point's neighbours "
            "lie on a line or coincide with it; a Laplace-Beltrami operator needs points that sample a surface. "
            "Remove such points, or pass a larger n_neighbors for a point cloud."
        ) from None
    W, A = _as_pair(L, M)
    return W, A * np.ldexp(1.0, 2 * e)


def _as_pair(L: sp.spmatrix, M: sp.spmatrix) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    W = sp.csr_matrix(L, dtype=np.float64)
    W = ((W + W.T) * 0.5).tocsr()  # symmetric to the last bit, as check_operators demands
    A = sp.csr_matrix(M, dtype=np.float64)
    if not (np.all(np.isfinite(W.data)) and np.all(np.isfinite(A.data))) or np.any(A.diagonal() <= 0):
        raise MeshError(
            "the robust Laplacian came out with NaN/inf or a non-positive mass; the input has vertices that "
            "coincide or belong to no face. Weld or drop them (lbo.clean_mesh, or PointCloud without duplicates)."
        )
    return W, A
