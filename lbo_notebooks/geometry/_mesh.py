"""The :class:`Mesh` value type and the checks that make a triangle mesh usable.

A :class:`Mesh` is immutable: it copies the arrays it is given, marks its copies read-only and
caches what is computed from them on first use (:class:`Mesh`, *Notes*). Every check that fails raises
:class:`MeshError`, whose message names the defect and how to fix it.
"""

from __future__ import annotations

import functools
import hashlib
from typing import Any, Callable, Hashable, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["Mesh", "MeshError", "validate_topology", "degenerate_faces", "unique_rows", "per_mesh", "USABLE_SIZE_RANGE",
           "box_diagonal", "check_coordinate_range", "real_coordinates", "plural"]

T = TypeVar("T")

# A face is degenerate when its area is below this fraction of the squared bounding-box diagonal.
DEGENERATE_AREA_TOL = 1e-14

#: The sizes (largest extent of the bounding box of the vertices the faces use) a mesh may have.
#: Areas and cotangents go through squared edge lengths and their products (fourth powers), which
#: overflow double precision above about 1e77 and underflow below about 1e-77; the margin keeps
#: every face that is not degenerate (area above ``DEGENERATE_AREA_TOL`` times the squared size)
#: and the eigenvalues (about 1/size**2) far inside the range.
USABLE_SIZE_RANGE = (1e-60, 1e60)


def plural(n: int, singular: str, plural_form: str | None = None) -> str:
    """``n`` and the noun in the right number, for messages: "1 face", "2 faces", "1 vertex", "3 vertices".

    ``plural_form`` defaults to ``singular`` + "s" (so a phrase must end in its noun).

    Examples
    --------
    >>> plural(1, "duplicate face"), plural(2, "duplicate face"), plural(1, "vertex", "vertices")
    ('1 duplicate face', '2 duplicate faces', '1 vertex')
    """
    if n == 1:
        return f"{n} {singular}"
    return f"{n} {plural_form if plural_form is not None else singular + 's'}"


class MeshError(ValueError):
    """A triangle mesh that cannot be used as given; the message says why and what to do."""


def real_coordinates(values: ArrayLike, what: str) -> NDArray[np.float64]:
    """``values`` as a new float64 array; complex or non-numeric input raises :class:`MeshError`.

    NumPy would cut complex numbers to their real part with only a warning; a coordinate with an
    imaginary part is a bug upstream (an eigenvector, an FFT), so it is refused, not guessed.

    Examples
    --------
    >>> real_coordinates([[1, 2, 3]], "vertices").dtype
    dtype('float64')
    >>> real_coordinates([[1j, 2, 3]], "vertices")
    Traceback (most recent call last):
    ...
    lbo_notebooks.geometry._mesh.MeshError: vertices are complex numbers; ...
    """
    try:
        a = np.asarray(values)
        if np.iscomplexobj(a) or (a.dtype == object and any(isinstance(x, complex) for x in a.ravel())):
            raise MeshError(
                f"{what} are complex numbers; coordinates must be real. Pass the real part explicitly "
                "(np.real(...)) if the imaginary part is round-off, or find where it came from."
            )
        return np.array(a, dtype=np.float64, copy=True)
    except MeshError:
        raise
    except (TypeError, ValueError) as exc:
        raise MeshError(f"{what} must be numbers convertible to float64: {exc}") from None


def box_diagonal(points: np.ndarray) -> float:
    """Bounding-box diagonal of ``(n, d)`` points, computed without overflow (the box is scaled by its largest side first).

    Examples
    --------
    >>> box_diagonal(np.array([[0.0, 0, 0], [3, 4, 0]]))
    5.0
    """
    with np.errstate(over="ignore"):  # coordinates near +-1.8e308: an infinite side, handled below
        sides = points.max(axis=0) - points.min(axis=0)
    largest = float(np.max(sides)) if sides.size else 0.0
    if np.isnan(largest):
        return largest
    if not np.isfinite(largest):  # the sides themselves overflow (coordinates near +-1.8e308)
        return float("inf")
    if largest == 0.0:
        return 0.0
    return largest * float(np.linalg.norm(sides / largest))


def check_coordinate_range(points: ArrayLike, what: str = "mesh") -> None:
    """Raise :class:`MeshError` when the bounding-box diagonal of ``points`` is outside :data:`USABLE_SIZE_RANGE`.

    Parameters
    ----------
    points : array (n, 3)
        Finite coordinates.
    what : str
        ``"mesh"`` or ``"point cloud"``: how the message names the input.

    Examples
    --------
    >>> import numpy as np
    >>> check_coordinate_range(np.eye(3))
    >>> try:
    ...     check_coordinate_range(np.eye(3) * 1e100)
    ... except MeshError as error:
    ...     print(str(error)[:69])
    the mesh's coordinates are out of the usable range: its bounding box
    """
    p = np.asarray(points, dtype=np.float64)
    if p.ndim != 2 or p.shape[0] == 0:
        return
    diagonal = box_diagonal(p)
    low, high = USABLE_SIZE_RANGE
    if low <= diagonal <= high:
        return
    if diagonal == 0.0 or np.isnan(diagonal):
        return  # all points coincide, or NaN coordinates: the callers' own checks name those problems
    size = "too large" if diagonal > high else "too small"
    direction = "overflow" if diagonal > high else "underflow"
    fix = ("mesh.with_vertices(mesh.vertices / mesh.diagonal)" if what == "mesh"
           else "PointCloud(points / scale), with scale the bounding-box diagonal")
    raise MeshError(
        f"the {what}'s coordinates are out of the usable range: its bounding box has a diagonal of {diagonal:.3g}, "
        f"{size} for double precision (areas and squared lengths computed from it {direction}; usable diagonals lie "
        f"between {low:g} and {high:g}). Rescale it to ordinary units first, e.g. {fix}; eigenvalues then scale "
        "by the square of the factor."
    )


def _as_vertices(vertices: ArrayLike) -> NDArray[np.float64]:
    v = real_coordinates(vertices, "vertices")
    if v.ndim != 2 or v.shape[1] != 3:
        raise MeshError(f"vertices must have shape (n, 3), got {v.shape}; pass one xyz row per vertex.")
    if v.shape[0] < 3:
        raise MeshError(f"a mesh needs at least 3 vertices, got {v.shape[0]}.")
    bad = ~np.isfinite(v).all(axis=1)
    if bad.any():
        rows = np.flatnonzero(bad)
        raise MeshError(
            f"{plural(rows.size, 'vertex has', 'vertices have')} non-finite (NaN or inf) coordinates (first: vertex "
            f"{rows[0]}, counted from 0); fix or remove them before building the mesh."
        )
    return v


def _as_faces(faces: ArrayLike, n_vertices: int) -> NDArray[np.int64]:
    try:
        f = np.array(faces, copy=True)
    except (ValueError, TypeError):  # NumPy refuses rows of different lengths ("inhomogeneous shape")
        f = np.empty(0, dtype=object)
    # Python integers beyond int64 make an object array; they are checked against the range below.
    big_ints = f.dtype == object and f.ndim == 2 and all(isinstance(x, (int, np.integer)) for x in f.ravel())
    if (f.dtype == object and not big_ints) or f.ndim != 2 or f.shape[1] != 3:
        shape = f.shape if f.dtype != object else "ragged (rows of different lengths or not numbers)"
        raise MeshError(
            f"faces must have shape (m, 3) (triangles only), got {shape}; "
            "triangulate polygons first (e.g. load with load_mesh, which splits quads)."
        )
    if f.shape[0] == 0:
        raise MeshError("the mesh has no faces; an LBO needs at least one triangle.")
    if not (big_ints or np.issubdtype(f.dtype, np.integer)):
        if not np.issubdtype(f.dtype, np.floating) or not np.all(np.isfinite(f)) or np.any(f != np.round(f)):
            raise MeshError(f"faces must hold integer vertex indices, got dtype {f.dtype} with non-integer values.")
    # The range check comes before the cast to int64, so that an index is shown as given, not wrapped.
    outside = ((f < 0) | (f >= n_vertices)).any(axis=1)
    if outside.any():
        bad = np.flatnonzero(outside)
        raise MeshError(
            f"{bad.size} faces use vertex indices outside 0..{n_vertices - 1} (first: face {bad[0]} = "
            f"{[int(x) for x in f[bad[0]]]}, faces and vertices counted from 0); indices are 0-based and must refer "
            "to existing vertices."
        )
    return f.astype(np.int64)


def _check_size(v: NDArray[np.float64], f: NDArray[np.int64]) -> None:
    """Refuse a mesh whose size is outside :data:`USABLE_SIZE_RANGE`, saying so (not "degenerate faces")."""
    used = np.zeros(len(v), dtype=bool)
    used[f.ravel()] = True
    pts = v[used]
    with np.errstate(over="ignore", invalid="ignore"):
        extent = pts.max(axis=0) - pts.min(axis=0)  # inf if the coordinates span more than 1.8e308
    size = float(extent.max())
    lo, hi = USABLE_SIZE_RANGE
    if size == 0 or lo <= size <= hi:
        return  # (size 0: every face is degenerate, which the topology check says)
    far = int(np.flatnonzero(used)[np.argmax(np.abs(pts - np.median(pts, axis=0)).max(axis=1))])
    outlier = f" The vertex farthest from the median is {far}, at {v[far].tolist()}." if size > hi else ""
    raise MeshError(
        f"coordinates out of a usable range: the mesh is {size:.3g} across (the largest side of its bounding box), "
        f"outside {lo:g} .. {hi:g}, where squared edge lengths and areas overflow or underflow double precision "
        f"(faces would come out with zero or infinite area).{outlier} Rescale the mesh, e.g. to unit size: "
        "Mesh(vertices / s, faces) with s its size, and scale the results back (lengths by s, areas by s**2, "
        "eigenvalues by 1/s**2)."
    )


def _readonly(a: np.ndarray) -> np.ndarray:
    a.setflags(write=False)
    return a


class Mesh:
    """An immutable triangle mesh: ``vertices`` (n, 3) float64 and ``faces`` (m, 3) int64.

    Parameters
    ----------
    vertices : array_like, shape (n, 3)
        Vertex positions. Copied; the caller's array is never modified.
    faces : array_like, shape (m, 3)
        Triangles as 0-based vertex indices. Copied.
    check : bool, default True
        Run the topology checks of :func:`validate_topology` (degenerate, duplicate faces,
        unreferenced vertices, non-manifold edges, inconsistent orientation). Shapes, finiteness
        and index ranges are always checked.

    Raises
    ------
    MeshError
        If the arrays do not describe a valid mesh; the message names the defect and the fix.

    Notes
    -----
    What is computed from the arrays (geometry, operators, curvature, factorisations, orderings) is cached on
    the mesh, keyed as :func:`per_mesh` says; :meth:`clear_cache` drops it (factorisations can outweigh the arrays).

    Examples
    --------
    >>> m = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> m.n_vertices, m.n_faces, m.area
    (3, 1, 0.5)
    """

    __slots__ = ("_vertices", "_faces", "_cache")

    def __init__(self, vertices: ArrayLike, faces: ArrayLike, *, check: bool = True) -> None:
        v = _as_vertices(vertices)
        f = _as_faces(faces, v.shape[0])
        _check_size(v, f)
        object.__setattr__(self, "_vertices", _readonly(v))
        object.__setattr__(self, "_faces", _readonly(f))
        object.__setattr__(self, "_cache", {})
        if check:
            validate_topology(self)

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("Mesh is immutable; build a new one (see Mesh.with_vertices).")

    def __reduce__(self) -> tuple[Any, ...]:
        # Pickled as its two arrays (a graded answer holding a mesh, a worker process): the cache of
        # operators stays behind, and the copy is checked again as it is rebuilt.
        return (Mesh, (np.array(self._vertices), np.array(self._faces)))

    # --- basic data -------------------------------------------------------------------------
    @property
    def vertices(self) -> NDArray[np.float64]:
        """Vertex positions, shape (n, 3), read-only."""
        return self._vertices

    @property
    def faces(self) -> NDArray[np.int64]:
        """Triangles as vertex indices, shape (m, 3), read-only."""
        return self._faces

    @property
    def n_vertices(self) -> int:
        return int(self._vertices.shape[0])

    @property
    def n_faces(self) -> int:
        return int(self._faces.shape[0])

    def with_vertices(self, vertices: ArrayLike) -> "Mesh":
        """A new mesh with the same faces and new vertex positions (e.g. a pose or a scaling)."""
        v = _as_vertices(vertices)
        if v.shape != self._vertices.shape:
            raise MeshError(f"new vertices have shape {v.shape}, expected {self._vertices.shape}.")
        new = Mesh.__new__(Mesh)
        object.__setattr__(new, "_vertices", _readonly(v))
        object.__setattr__(new, "_faces", self._faces)
        object.__setattr__(new, "_cache", {})
        _check_size(v, self._faces)
        _check_degenerate(new)
        return new

    def cached(self, key: Hashable, compute: Callable[["Mesh"], T]) -> T:
        """Return ``compute(self)`` computed once per mesh and stored under ``key``.

        Prefer the :func:`per_mesh` decorator, which builds the key from the function and its
        arguments. Callers must not modify what they get back.
        """
        cache = self._cache
        if key not in cache:
            cache[key] = compute(self)
        return cache[key]

    def clear_cache(self) -> None:
        """Drop what was computed from this mesh and kept on it; it is recomputed when asked for."""
        self._cache.clear()

    # --- derived geometry -------------------------------------------------------------------
    @property
    def edges(self) -> NDArray[np.int64]:
        """Unique undirected edges, shape (e, 2), each row sorted ascending."""
        return _edge_table(self)[0]

    @property
    def edge_face_counts(self) -> NDArray[np.int64]:
        """How many faces use each edge of :attr:`edges` (1 on the boundary, 2 inside)."""
        return _edge_table(self)[1]

    @property
    def boundary_edges(self) -> NDArray[np.int64]:
        """Edges used by exactly one face, shape (b, 2)."""
        return self.edges[self.edge_face_counts == 1]

    @property
    def boundary_vertices(self) -> NDArray[np.int64]:
        """Sorted indices of vertices on the boundary."""
        return np.unique(self.boundary_edges)

    @property
    def face_areas(self) -> NDArray[np.float64]:
        """Area of each triangle, shape (m,)."""
        return _face_areas(self)

    @property
    def face_normals(self) -> NDArray[np.float64]:
        """Unit normal of each triangle (right-hand rule), shape (m, 3)."""
        return _face_normals(self)

    @property
    def area(self) -> float:
        """Total surface area."""
        return float(self.face_areas.sum())

    @property
    def bounding_box(self) -> NDArray[np.float64]:
        """Axis-aligned bounding box as a (2, 3) array: row 0 the minimum, row 1 the maximum."""
        return np.stack([self._vertices.min(axis=0), self._vertices.max(axis=0)])

    @property
    def diagonal(self) -> float:
        """Length of the bounding-box diagonal (a scale for tolerances)."""
        return float(np.linalg.norm(np.subtract(*self.bounding_box[::-1])))

    @property
    def mean_edge_length(self) -> float:
        """Mean length of the unique edges (the mesh size h)."""
        e = self.edges
        return float(np.linalg.norm(self._vertices[e[:, 0]] - self._vertices[e[:, 1]], axis=1).mean())

    @property
    def euler_characteristic(self) -> int:
        """V - E + F (2 for a sphere, 0 for a torus, 1 for a disk)."""
        return self.n_vertices - len(self.edges) + self.n_faces

    @property
    def component_labels(self) -> NDArray[np.int64]:
        """Connected-component label of each vertex, 0-based, ordered by first vertex."""
        return _component_labels(self)

    @property
    def n_components(self) -> int:
        """Number of connected components."""
        return int(self.component_labels.max()) + 1

    @property
    def is_closed(self) -> bool:
        """True when the surface has no boundary edges."""
        return bool(np.all(self.edge_face_counts == 2))

    # --- value semantics --------------------------------------------------------------------
    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Mesh):
            return NotImplemented
        return np.array_equal(self._vertices, other._vertices) and np.array_equal(self._faces, other._faces)

    def __hash__(self) -> int:
        return _hash(self)

    def __repr__(self) -> str:
        return (f"Mesh(n_vertices={self.n_vertices}, n_faces={self.n_faces}, components={self.n_components}, "
                f"boundary_edges={len(self.boundary_edges)}, euler_characteristic={self.euler_characteristic})")

    def summary(self) -> str:
        """A one-paragraph human-readable description (size, topology, scale)."""
        lo, hi = self.bounding_box
        return (
            f"{self.n_vertices} vertices, {self.n_faces} faces, {len(self.edges)} edges; "
            f"{self.n_components} component(s), {len(self.boundary_edges)} boundary edge(s), "
            f"Euler characteristic {self.euler_characteristic}; area {self.area:.6g}; "
            f"bounding box {np.round(lo, 4).tolist()} .. {np.round(hi, 4).tolist()}"
        )


# --- the per-mesh cache ------------------------------------------------------------------------------
def per_mesh(function: Callable[..., T]) -> Callable[..., T]:
    """Decorator: compute ``function(mesh, *args)`` once per mesh and arguments, cached on the mesh.

    The cache key is the function itself plus the (hashable) positional arguments, so no module
    writes string keys and two functions can never collide. A :class:`Mesh` is immutable, so the
    cache can never go stale; what the function returns must be treated as read-only.

    Examples
    --------
    >>> calls = []
    >>> @per_mesh
    ... def n_edges(mesh):
    ...     calls.append(1)
    ...     return len(mesh.edges)
    >>> m = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> n_edges(m), n_edges(m), len(calls)
    (3, 3, 1)
    """

    @functools.wraps(function)
    def wrapper(mesh: Mesh, *args: Hashable) -> T:
        return mesh.cached((wrapper, args), lambda m: function(m, *args))

    return wrapper


# --- helpers ------------------------------------------------------------------------------------
def _face_cross(m: Mesh) -> NDArray[np.float64]:
    v, f = m.vertices, m.faces
    return np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])


def _directed_edges(f: NDArray[np.int64]) -> NDArray[np.int64]:
    return np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])


def _pair_keys(pairs: NDArray[np.int64], n: int) -> NDArray[np.int64]:
    # One int64 per index pair: 1-D np.unique is much faster than np.unique(..., axis=0).
    return pairs[:, 0] * np.int64(n) + pairs[:, 1]


@per_mesh
def _face_areas(m: Mesh) -> NDArray[np.float64]:
    return _readonly(0.5 * np.linalg.norm(_face_cross(m), axis=1))


@per_mesh
def _face_normals(m: Mesh) -> NDArray[np.float64]:
    c = _face_cross(m)
    return _readonly(c / np.linalg.norm(c, axis=1, keepdims=True))


@per_mesh
def _hash(m: Mesh) -> int:
    h = hashlib.sha1(m.vertices.tobytes())
    h.update(m.faces.tobytes())
    return int.from_bytes(h.digest()[:8], "little")


@per_mesh
def _edge_table(m: Mesh) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    n = m.n_vertices
    e = np.sort(_directed_edges(m.faces), axis=1)
    keys, counts = np.unique(_pair_keys(e, n), return_counts=True)
    edges = np.stack([keys // n, keys % n], axis=1)
    return _readonly(edges.astype(np.int64)), _readonly(counts.astype(np.int64))


@per_mesh
def _component_labels(m: Mesh) -> NDArray[np.int64]:
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    e = m.edges
    n = m.n_vertices
    graph = coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    # Relabel so that components are numbered in order of their first vertex.
    _, first = np.unique(labels, return_index=True)
    order = np.argsort(first)
    relabel = np.empty_like(order)
    relabel[order] = np.arange(order.size)
    return _readonly(relabel[labels].astype(np.int64))


def degenerate_faces(mesh: Mesh) -> NDArray[np.bool_]:
    """Mask of the faces with a repeated corner or an area below ``DEGENERATE_AREA_TOL * diagonal**2``.

    The one rule for "zero-area": :class:`Mesh` refuses such faces and
    :func:`~lbo_notebooks.clean_mesh` removes them.

    Examples
    --------
    >>> m = Mesh([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]], [[0, 1, 2], [0, 1, 3]], check=False)
    >>> degenerate_faces(m).tolist()
    [True, False]
    """
    f = mesh.faces
    repeated = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])
    return repeated | (mesh.face_areas <= DEGENERATE_AREA_TOL * max(mesh.diagonal, np.finfo(float).tiny) ** 2)


def unique_rows(a: NDArray[Any]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Group equal rows of a 2-D array: ``first`` row of each group (groups sorted) and ``inverse``.

    A stable lexicographic sort: much faster than ``np.unique(a, axis=0)``, which sorts opaque
    row records. Used to weld coincident vertices and to find duplicate faces.

    Examples
    --------
    >>> first, inverse = unique_rows(np.array([[1, 2], [0, 5], [1, 2]]))
    >>> first.tolist(), inverse.tolist()
    ([1, 0], [1, 0, 1])
    """
    if len(a) == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    order = np.lexsort(a.T[::-1])
    s = a[order]
    new = np.ones(len(a), dtype=bool)
    new[1:] = np.any(s[1:] != s[:-1], axis=1)
    inverse = np.empty(len(a), dtype=np.int64)
    inverse[order] = np.cumsum(new) - 1
    return order[new].astype(np.int64), inverse


def _check_degenerate(m: Mesh) -> None:
    f = m.faces
    bad = np.flatnonzero(degenerate_faces(m))
    if bad.size:
        raise MeshError(
            f"{plural(bad.size, 'degenerate (zero-area) face')} (first: face {bad[0]} = {f[bad[0]].tolist()}, "
            "faces and vertices counted from 0); "
            "their cotangent weights are undefined. Remove them, or load with "
            "load_mesh(path, clean=True), which drops them."
        )


def validate_topology(mesh: Mesh) -> None:
    """Raise :class:`MeshError` unless ``mesh`` is a clean, oriented, edge-manifold surface.

    Checked: degenerate faces, duplicate faces, unreferenced vertices, edges shared by more than
    two faces, and neighbouring faces with opposite orientation. Boundaries and several connected
    components are legal.
    """
    _check_degenerate(mesh)
    f, n = mesh.faces, mesh.n_vertices

    key = np.sort(f, axis=1)
    key = (key[:, 0] * np.int64(n) + key[:, 1]) * np.int64(n) + key[:, 2] if n < 2**21 else key
    _, first, inverse, counts = np.unique(key, axis=0 if key.ndim == 2 else None, return_index=True,
                                          return_inverse=True, return_counts=True)
    if np.any(counts > 1):
        repeats = np.flatnonzero(first[inverse.ravel()] != np.arange(len(f)))  # every copy after the first
        again, original = int(repeats[0]), int(first[inverse.ravel()[repeats[0]]])
        raise MeshError(
            f"{plural(int((counts - 1).sum()), 'duplicate face')} (first: face {again} = {f[again].tolist()} repeats "
            f"face {original} = {f[original].tolist()}, faces and vertices counted from 0); each triangle must "
            "appear once. Load with clean=True to drop them."
        )

    used = np.zeros(n, dtype=bool)
    used[f.ravel()] = True
    if not used.all():
        unused = np.flatnonzero(~used)
        raise MeshError(
            f"{plural(unused.size, 'unreferenced vertex', 'unreferenced vertices')} (first: vertex {unused[0]}, "
            f"counted from 0) {'belongs' if unused.size == 1 else 'belong'} to no face; "
            "they would get a zero row in the mass matrix. Load with clean=True to drop them."
        )

    counts = mesh.edge_face_counts
    if np.any(counts > 2):
        bad = mesh.edges[counts > 2]
        raise MeshError(
            f"{plural(len(bad), 'non-manifold edge is', 'non-manifold edges are')} shared by more than two faces "
            f"(first: edge {bad[0].tolist()}, vertices counted from 0); the cotangent LBO needs an edge-manifold surface. Load with "
            "load_mesh(path, clean=True) (or build Mesh(..., check=False)): eigenbasis then uses the robust "
            "Laplacian, which serves non-manifold meshes."
        )

    keys, dcounts = np.unique(_pair_keys(_directed_edges(f), n), return_counts=True)
    if np.any(dcounts > 1):
        twice = keys[dcounts > 1]
        bad = np.stack([twice // n, twice % n], axis=1)
        raise MeshError(
            f"inconsistent orientation: {plural(len(bad), 'edge is', 'edges are')} traversed in the same direction "
            f"by both of their faces (first: edge {bad[0].tolist()}, vertices counted from 0). Flip faces so that neighbours agree, "
            "or load with clean=True, which re-orients each orientable component."
        )
