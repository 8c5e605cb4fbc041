"""Mesh repair: :func:`clean_mesh` fixes what can be fixed in a triangle soup and reports it.

The rules for what is broken are the ones :class:`~lbo_notebooks.Mesh` checks
(:func:`~lbo_notebooks.geometry._mesh.degenerate_faces`, :func:`~lbo_notebooks.geometry._mesh.unique_rows`,
``Mesh.component_labels``); this module only applies them. What no repair can make manifold
(edges shared by more than two faces, non-orientable pieces) is kept and reported: such a mesh
still gets a spectrum, through the robust Laplacian (:mod:`lbo_notebooks.operators._robust`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Sequence, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Boolean, validated
from ._mesh import Mesh, MeshError, degenerate_faces, plural, real_coordinates, unique_rows

__all__ = ["clean_mesh", "clean_arrays", "CleanReport", "triangulate_polygons"]


def triangulate_polygons(polygons: Sequence[Sequence[int]] | NDArray[np.integer]) -> tuple[NDArray[np.int64], int]:
    """Triangles from polygons: a fan from each polygon's first corner; also the polygon count.

    Right for convex polygons, which is what exporters write.

    Examples
    --------
    >>> tris, n_polygons = triangulate_polygons([[0, 1, 2, 3], [3, 2, 4]])
    >>> tris.tolist(), n_polygons
    ([[0, 1, 2], [0, 2, 3], [3, 2, 4]], 1)
    """
    if isinstance(polygons, np.ndarray) and polygons.ndim == 2 and polygons.shape[1] >= 3:
        corners = polygons.shape[1]  # all polygons alike: one fan per row, vectorised
        fans = np.stack([polygons[:, [0, k, k + 1]] for k in range(1, corners - 1)], axis=1)
        return fans.reshape(-1, 3).astype(np.int64), len(polygons) if corners > 3 else 0
    tris: list[tuple[int, int, int]] = []
    n_poly = 0
    for poly in polygons:
        if len(poly) > 3:
            n_poly += 1
        a = poly[0]
        for k in range(1, len(poly) - 1):
            tris.append((a, poly[k], poly[k + 1]))
    try:
        return np.array(tris, dtype=np.int64).reshape(-1, 3), n_poly
    except OverflowError:
        big = next(i for t in tris for i in t if not -(2**63) <= int(i) < 2**63)
        raise MeshError(f"vertex index {big} is too large for any mesh (beyond 64-bit integers); the faces are corrupt.") from None


@dataclass(frozen=True)
class CleanReport:
    """What :func:`clean_mesh` changed. ``str(report)`` is a one-line summary.

    Attributes
    ----------
    n_vertices_in, n_faces_in, n_vertices_out, n_faces_out : int
        Sizes before (triangles, after splitting polygons) and after cleaning.
    polygons_split : int
        Faces with more than three corners split into triangles.
    vertices_welded : int
        Vertices merged into an earlier vertex with exactly the same coordinates.
    degenerate_faces : int
        Zero-area faces removed (repeated corners, or area below the :class:`Mesh` tolerance).
    duplicate_faces : int
        Faces removed because an earlier face has the same three vertices.
    unreferenced_vertices : int
        Vertices removed because no face uses them (also those orphaned by removed faces).
    faces_flipped : int
        Faces whose orientation was reversed to agree with their neighbours.
    components_removed : int
        Components dropped by ``keep_largest_component``.
    non_manifold_edges : int
        Edges shared by more than two faces, kept: no repair makes them manifold.
        ``eigenbasis`` then uses the robust Laplacian.
    non_orientable_components : int
        Components no choice of face orientations makes consistent (Moebius-like), kept as
        they are: the Laplacian does not depend on orientation.
    n_components : int
        Connected components of the result; its spectrum has this many (near-)zero eigenvalues.
    vertex_map : ndarray, shape (n_vertices_in,)
        New index of each input vertex, or -1 if it was removed.
    """

    n_vertices_in: int
    n_faces_in: int
    n_vertices_out: int
    n_faces_out: int
    polygons_split: int = 0
    vertices_welded: int = 0
    degenerate_faces: int = 0
    duplicate_faces: int = 0
    unreferenced_vertices: int = 0
    faces_flipped: int = 0
    components_removed: int = 0
    non_manifold_edges: int = 0
    non_orientable_components: int = 0
    n_components: int = 1
    vertex_map: NDArray[np.int64] = field(default_factory=lambda: np.zeros(0, np.int64), repr=False, compare=False)

    @property
    def changed(self) -> bool:
        """True when cleaning changed anything."""
        return bool(
            self.polygons_split or self.vertices_welded or self.degenerate_faces or self.duplicate_faces
            or self.unreferenced_vertices or self.faces_flipped or self.components_removed
        )

    def __str__(self) -> str:
        items = [  # (count, singular, plural)
            (self.polygons_split, "polygon split into triangles", "polygons split into triangles"),
            (self.vertices_welded, "duplicate vertex welded", "duplicate vertices welded"),
            (self.degenerate_faces, "degenerate face removed", "degenerate faces removed"),
            (self.duplicate_faces, "duplicate face removed", "duplicate faces removed"),
            (self.unreferenced_vertices, "unreferenced vertex removed", "unreferenced vertices removed"),
            (self.faces_flipped, "face flipped to a consistent orientation", "faces flipped to a consistent orientation"),
            (self.components_removed, "smaller component removed", "smaller components removed"),
        ]
        parts = [plural(n, one, many) for n, one, many in items if n]
        done = "; ".join(parts) if parts else "nothing to repair"
        kept = [
            (self.non_manifold_edges, "non-manifold edge", "non-manifold edges",
             " kept (eigenbasis will use the robust Laplacian)"),
            (self.non_orientable_components, "non-orientable component", "non-orientable components",
             " kept as they are" if self.non_orientable_components > 1 else " kept as it is"),
        ]
        notes = "".join(f"; {plural(n, one, many)}{what}" for n, one, many, what in kept if n)
        if self.n_components > 1:
            notes += (
                f"; {self.n_components} connected components, so the spectrum starts with "
                f"{self.n_components} zero eigenvalues (keep_largest_component=True keeps one)"
            )
        return (
            f"{done} ({self.n_vertices_in} -> {self.n_vertices_out} vertices, "
            f"{self.n_faces_in} -> {self.n_faces_out} faces){notes}"
        )

    @property
    def noteworthy(self) -> bool:
        """True when the mesh changed, kept a defect, or has several components (several zero eigenvalues)."""
        return self.changed or bool(self.non_manifold_edges or self.non_orientable_components) or self.n_components > 1


MeshLike = Union[Mesh, tuple[ArrayLike, Any]]


@validated(keep_largest_component=Boolean())
def clean_mesh(mesh: MeshLike, keep_largest_component: bool = False) -> tuple[Mesh, CleanReport]:
    """Repair a mesh or raw ``(vertices, faces)`` arrays; return the clean mesh and a report.

    Repairs, in this order: split polygons into fans of triangles; weld vertices with exactly
    equal coordinates (the first keeps its place); remove degenerate faces (repeated corners or
    zero area, same rule as :class:`Mesh`), then duplicate faces (same three vertices in
    any order; the first is kept); re-orient each orientable connected component consistently
    (breadth first over faces that share a manifold edge, flipping as few faces as possible);
    optionally keep the component with the most faces; finally drop unreferenced vertices,
    keeping the others' order. Boundaries and several components are legal and left alone.
    Non-manifold edges and non-orientable components cannot be repaired: they are kept and
    counted in the report, and the result is built with ``Mesh(..., check=False)``;
    :func:`~lbo_notebooks.eigenbasis` serves it with the robust Laplacian.

    Parameters
    ----------
    mesh : Mesh or (vertices, faces)
        A :class:`Mesh` (e.g. built with ``check=False``) or raw arrays: ``vertices`` (n, 3) and
        ``faces`` as an (m, 3) integer array or a sequence of polygons (index sequences with at
        least three corners). The caller's arrays are never modified.
    keep_largest_component : bool, default False
        Keep only the vertex-connected component with the most faces.

    Returns
    -------
    mesh : Mesh
        The repaired, validated mesh.
    report : CleanReport
        What changed (``str(report)`` summarises it; ``report.vertex_map`` maps old vertex
        indices to new ones).

    Raises
    ------
    MeshError
        For what is corrupt rather than broken: wrong shapes, indices out of range, non-finite
        coordinates on a used vertex, no face left.

    Examples
    --------
    >>> v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0], [5, 5, 5]]
    >>> f = [[0, 1, 2], [2, 3, 4], [0, 1, 2]]     # vertex 4 repeats vertex 1, 5 is unused
    >>> m, report = clean_mesh((v, f))
    >>> m.faces.tolist()
    [[0, 1, 2], [2, 1, 3]]
    >>> print(report)
    1 duplicate vertex welded; 1 duplicate face removed; 1 unreferenced vertex removed; 1 face flipped to a consistent orientation (6 -> 4 vertices, 3 -> 2 faces)
    """
    if isinstance(mesh, Mesh):
        vertices, faces = mesh.vertices, mesh.faces
    else:
        try:
            vertices, faces = mesh
        except (TypeError, ValueError):
            raise TypeError("clean_mesh needs a Mesh or a (vertices, faces) pair.") from None
    v = real_coordinates(vertices, "vertices")
    if v.ndim != 2 or v.shape[1] != 3:
        raise MeshError(f"vertices must have shape (n, 3), got {v.shape}.")
    n_poly = 0
    given = np.asarray(faces) if isinstance(faces, np.ndarray) else None
    if given is not None and given.size and given.dtype.kind in "uf":
        # An unsigned index beyond int64 would wrap, a fractional one would be truncated: refuse both.
        if given.dtype.kind == "f" and not np.all(np.isfinite(given) & (given == np.round(given))):
            raise MeshError(f"faces must hold integer vertex indices, got dtype {given.dtype} with non-integer values.")
        if given.max() > np.iinfo(np.int64).max:
            raise MeshError(f"vertex index {given.max()} is too large for any mesh (beyond 64-bit integers); "
                            "the faces are corrupt.")
    try:
        f = np.array(faces, dtype=np.int64, copy=True)
        if f.ndim == 2 and f.shape[1] == 3:
            pass
        elif f.ndim == 2 and f.shape[1] > 3 or f.ndim == 1 and f.size == 0:
            raise ValueError
        else:
            raise MeshError(f"faces must have shape (m, 3) or be a list of polygons, got shape {f.shape}.")
    except (ValueError, TypeError, OverflowError):
        polygons = [list(map(int, poly)) for poly in faces]
        short = [k for k, poly in enumerate(polygons) if len(poly) < 3]
        if short:
            raise MeshError(f"{plural(len(short), 'face has', 'faces have')} fewer than 3 corners (first: face "
                            f"{short[0]}, counted from 0).") from None
        f, n_poly = triangulate_polygons(polygons)
    return clean_arrays(v, f, keep_largest_component=keep_largest_component, polygons_split=n_poly)


def clean_arrays(
    v: NDArray[np.float64], f: NDArray[np.int64], *, keep_largest_component: bool = False, polygons_split: int = 0
) -> tuple[Mesh, CleanReport]:
    """:func:`clean_mesh` on raw triangle arrays (what a file reader returns).

    ``polygons_split`` is how many polygons the reader already split into triangles, for the
    report. The arrays are not modified.

    Examples
    --------
    >>> m, report = clean_arrays(np.eye(3), np.array([[0, 1, 2], [0, 1, 2]]))
    >>> m.n_faces, report.duplicate_faces
    (1, 1)
    """
    v = np.asarray(v, dtype=np.float64)
    f = np.asarray(f, dtype=np.int64)
    keep_largest, n_poly = keep_largest_component, polygons_split
    n_in, m_in = len(v), len(f)
    if m_in == 0:
        raise MeshError("the mesh has no faces; nothing to clean.")
    if f.min() < 0 or f.max() >= n_in:
        bad = np.flatnonzero(((f < 0) | (f >= n_in)).any(axis=1))
        raise MeshError(
            f"{bad.size} faces use vertex indices outside 0..{n_in - 1} (first: face {bad[0]} = {f[bad[0]].tolist()}, "
            "faces and vertices counted from 0); "
            "fix the file: indices must refer to existing vertices."
        )
    used = np.zeros(n_in, dtype=bool)
    used[f.ravel()] = True
    finite = np.isfinite(v).all(axis=1)
    if np.any(used & ~finite):
        bad = np.flatnonzero(used & ~finite)
        raise MeshError(
            f"{plural(bad.size, 'vertex used by faces has', 'vertices used by faces have')} non-finite (NaN or inf) "
            f"coordinates (first: vertex {bad[0]}, counted from 0); "
            "fix them in the source."
        )

    # Weld used vertices with exactly equal coordinates onto the first of them.
    rep = np.arange(n_in)
    idx = np.flatnonzero(used)
    first, inverse = unique_rows(v[idx])
    rep[idx] = idx[first[inverse]]
    welded = int(np.count_nonzero(rep[idx] != idx))
    f = rep[f]

    # Degenerate faces, by the Mesh rule (scale: the bounding box of the referenced vertices).
    repeated = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])
    if repeated.all():
        raise MeshError("every face is degenerate (zero area); there is no surface left.")
    v_r, f_r, _ = _compact(v, f)
    degenerate = degenerate_faces(Mesh(v_r, f_r, check=False))
    f = f[~degenerate]
    n_degenerate = int(degenerate.sum())
    if len(f) == 0:
        raise MeshError("every face is degenerate (zero area); there is no surface left.")

    # Duplicate faces: same vertex set; keep the first occurrence.
    first_face, _ = unique_rows(np.sort(f, axis=1))
    keep = np.zeros(len(f), dtype=bool)
    keep[first_face] = True
    n_duplicate = int(len(f) - keep.sum())
    f = f[keep]

    v_c, f_c, vmap = _compact(v, f)
    removed_components = 0
    if keep_largest:
        labels = Mesh(v_c, f_c, check=False).component_labels[f_c[:, 0]]
        sizes = np.bincount(labels)
        removed_components = int(np.count_nonzero(sizes)) - 1
        f_c = f_c[labels == int(np.argmax(sizes))]
    f_c, flipped, n_non_orientable = _orient(f_c)
    v_out, f_out, vmap2 = _compact(v_c, f_c)

    # Compose: input vertex -> its weld representative -> compacted index -> final index.
    mid = vmap[rep]
    vertex_map = np.where(mid >= 0, vmap2[np.maximum(mid, 0)], -1)
    unreferenced = n_in - welded - len(v_out)
    mesh = Mesh(v_out, f_out, check=False)
    n_non_manifold = int(np.count_nonzero(mesh.edge_face_counts > 2))
    if n_non_manifold == 0 and n_non_orientable == 0:
        mesh = Mesh(v_out, f_out)  # all checks must pass now; a failure here is a bug worth seeing
    report = CleanReport(
        n_vertices_in=n_in, n_faces_in=m_in, n_vertices_out=mesh.n_vertices, n_faces_out=mesh.n_faces,
        polygons_split=n_poly, vertices_welded=welded, degenerate_faces=n_degenerate,
        duplicate_faces=n_duplicate, unreferenced_vertices=unreferenced, faces_flipped=flipped,
        components_removed=removed_components, non_manifold_edges=n_non_manifold,
        non_orientable_components=n_non_orientable, n_components=mesh.n_components, vertex_map=vertex_map,
    )
    return mesh, report


def _compact(v: NDArray[np.float64], f: NDArray[np.int64]) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64]]:
    """Drop unreferenced vertices keeping order; also return old -> new index (-1 if dropped)."""
    used = np.zeros(len(v), dtype=bool)
    used[f.ravel()] = True
    new = np.full(len(v), -1, dtype=np.int64)
    new[used] = np.arange(int(used.sum()))
    return v[used], new[f], new


def _orient(f: NDArray[np.int64]) -> tuple[NDArray[np.int64], int, int]:
    """Flip faces so that every manifold interior edge is traversed in opposite directions.

    Breadth-first over the faces of each component joined by edges with exactly two faces (all
    components at once, level by level); per component the orientation needing fewer flips wins.
    A non-orientable component is left as it is. Returns the faces, the number flipped and the
    number of non-orientable components.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    m = len(f)
    half = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    face_of = np.tile(np.arange(m), 3)
    _, edge_id = unique_rows(np.sort(half, axis=1))
    manifold = np.bincount(edge_id)[edge_id] == 2  # orientation is meaningless across a fin
    order = np.argsort(edge_id, kind="stable")
    order = order[manifold[order]]
    e_sorted = edge_id[order]
    pair = np.flatnonzero(e_sorted[1:] == e_sorted[:-1])  # interior edges: two consecutive half-edges
    h1, h2 = order[pair], order[pair + 1]
    if h1.size == 0:
        return f.copy(), 0, 0
    a, b = face_of[h1], face_of[h2]
    # Same direction along the shared edge -> the two faces need opposite flip states.
    need = (half[h1, 0] == half[h2, 0]).astype(np.int8)

    graph = coo_matrix((np.ones(a.size), (a, b)), shape=(m, m)).tocsr()
    graph = graph + graph.T
    n_comp, labels = connected_components(graph, directed=False)
    # Adjacency with the 'need' bit, both directions, in CSR form.
    src = np.concatenate([a, b])
    dst = np.concatenate([b, a])
    bit = np.concatenate([need, need])
    srt = np.argsort(src, kind="stable")
    src, dst, bit = src[srt], dst[srt], bit[srt]
    indptr = np.searchsorted(src, np.arange(m + 1))

    state = np.full(m, -1, dtype=np.int8)
    _, roots = np.unique(labels, return_index=True)
    state[roots] = 0
    frontier = roots
    while frontier.size:
        starts, stops = indptr[frontier], indptr[frontier + 1]
        lengths = stops - starts
        if lengths.sum() == 0:
            break
        pos = np.repeat(starts - np.cumsum(lengths) + lengths, lengths) + np.arange(lengths.sum())
        owners = np.repeat(frontier, lengths)
        nb = dst[pos]
        fresh = state[nb] < 0
        nb, owners, pos = nb[fresh], owners[fresh], pos[fresh]
        nb_unique, first = np.unique(nb, return_index=True)
        state[nb_unique] = state[owners[first]] ^ bit[pos[first]]
        frontier = nb_unique

    conflict = (state[a] ^ state[b]) != need
    non_orientable = np.zeros(n_comp, dtype=bool)
    non_orientable[labels[a[conflict]]] = True
    state[non_orientable[labels]] = 0  # no consistent choice exists: keep the file's orientation
    flips_per_comp = np.bincount(labels, weights=state, minlength=n_comp)
    size_per_comp = np.bincount(labels, minlength=n_comp)
    invert = flips_per_comp > size_per_comp / 2
    flip = state.astype(bool) ^ invert[labels]
    out = f.copy()
    out[flip] = out[flip][:, [0, 2, 1]]
    return out, int(flip.sum()), int(non_orientable.sum())

