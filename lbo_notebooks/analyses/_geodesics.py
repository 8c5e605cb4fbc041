"""Geodesic distances on triangle meshes and farthest-point sampling in geodesic distance.

Distances come from well-kept libraries, not a hand-written solver:

* ``"heat"`` — the heat method (Crane, Weischedel, Wardetzky 2013) of :mod:`.heat_method`: two
  sparse factorisations once per mesh, then two back-substitutions per source, done for a whole
  block of sources at a time. Approximate, with an error that shrinks with the mesh size h. The
  fast default.
* ``"exact"`` — exact polyhedral geodesics (Mitchell, Mount, Papadimitriou; Surazhsky et al. 2005)
  through libigl's ``exact_geodesic``. Exact on the piecewise-flat surface, but each source costs
  roughly O(n^1.5 log n): use it as a reference on small meshes.
* ``"fmm"`` — fast marching (Kimmel & Sethian 1998) of potpourri3d. First-order accurate;
  no factorisation, so it is cheap for a handful of sources.

:class:`GeodesicSolver` holds the per-mesh set-up so that it is paid once for many sources; it is
cached on the mesh, so :func:`geodesic_distances` and :func:`farthest_point_sampling` on the same
mesh share one factorisation.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from typing import Any, Callable, Literal, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.progress import PROGRESS, progress_bar
from .._support.validation import Indices, Integer, Number, Options, validated
from ._heat_method import HeatMethod
from ..geometry._mesh import Mesh, MeshError, per_mesh
from ..operators._cotangent import MESH

__all__ = [
    "GeodesicSolver",
    "geodesic_distances",
    "farthest_point_sampling",
    "METHODS",
    "check_connected",
    "distance_matrix_bytes",
    "check_memory",
    "MEMORY_BUDGET",
    "geodesic_solver",
]

GeodesicMethod = Literal["heat", "exact", "fmm"]
METHODS: tuple[str, ...] = ("heat", "exact", "fmm")

# Show a progress bar by default once a request has at least this many sources.
PROGRESS_THRESHOLD = 500

#: Table entry (:func:`~lbo_notebooks._support.validation.validated`) of a geodesic method; a mesh's
#: is the operators' ``MESH``, and whether the mesh is connected is :func:`check_connected`'s.
METHOD = Options(*METHODS)
#: The rule for ``memory_budget``: None (half of the memory available) or a positive number of bytes.
MEMORY_BUDGET = Number(0, open_low=True, infinite=True, none=True,
                       message="memory_budget must be a positive number of bytes, got {value!r}.")


def check_connected(mesh: Mesh, what: str = "geodesic distances") -> None:
    """Raise :class:`MeshError` if ``mesh`` has more than one connected component.

    Geodesic distances between components are infinite, so neither distances nor any embedding
    built from them exist. The message says how to keep the largest component.
    """
    if not isinstance(mesh, Mesh):
        MESH.check(mesh, "mesh", {})
    k = mesh.n_components
    if k > 1:
        sizes = np.bincount(mesh.component_labels)
        raise MeshError(
            f"{what} need a connected mesh, but this one has {k} connected components (vertex counts "
            f"{sorted(sizes.tolist(), reverse=True)[:5]}{' ...' if k > 5 else ''}); distances between "
            "components are infinite. Keep the largest component: "
            "mesh, _ = lbo_notebooks.clean_mesh(mesh, keep_largest_component=True) (or load it with "
            "load_mesh(path, clean=True, keep_largest_component=True))."
        )


def distance_matrix_bytes(rows: int, cols: int) -> int:
    """Bytes of a float64 ``rows x cols`` distance matrix."""
    return 8 * int(rows) * int(cols)


def _vertex_indices(role: str, n_vertices: Callable[..., int], none: bool = False) -> Indices:
    """Table entry of one vertex index or a non-empty 1-D sequence of them (``role`` names them in messages)."""
    return Indices(lambda **arguments: n_vertices(**arguments) - 1, scalar=True, integral=True, nonempty=True, none=none,
                   what="a vertex index or a non-empty 1-D sequence of integer vertex indices",
                   out_of_range=role + " vertex {index} is out of range: the mesh has {count} vertices, so "
                   "indices must lie in 0..{high}.")


_OF_SOLVER = lambda self, **_: self.n_vertices  # noqa: E731 - the solver's vertex count, for its methods' tables


def _progress(iterable: Sequence[Any], total: int, show: bool | None, desc: str) -> Any:
    """``iterable`` under a bar, by the package's rule (:mod:`lbo_notebooks._support.progress`): ``None``
    shows one only for at least ``PROGRESS_THRESHOLD`` steps and where someone watches (a notebook,
    or stderr on a terminal), so logs and tests stay clean."""
    if show is False or (show is None and total < PROGRESS_THRESHOLD):
        return iterable
    bar = progress_bar(total, desc, show)

    def steps() -> Any:
        with bar:
            for item in iterable:
                yield item
                bar.update()

    return steps()


class GeodesicSolver:
    """Geodesic distances from many sources on one mesh, set up once.

    Parameters
    ----------
    mesh : Mesh
        A connected triangle mesh (boundaries are allowed).
    method : {"heat", "exact", "fmm"}
        See the module docstring. ``"heat"`` factorises two sparse matrices here, once.
    heat_time : float, default 1.0
        For ``"heat"``: the diffusion time as a multiple of h^2 (h the mean edge length).
        Smaller is sharper but less smooth.

    Raises
    ------
    MeshError
        If the mesh has several connected components (distances between them are infinite).

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> solver = GeodesicSolver(shapes.icosphere(3), "heat")
    >>> d = solver.distances([0, 5])
    >>> d.shape, bool(abs(d[0].max() / 3.1416 - 1) < 0.05)   # half a great circle
    ((2, 642), True)
    """

    @validated(method=METHOD, heat_time=Number(0, open_low=True, what="a positive number (a multiple of h^2)"))
    def __init__(self, mesh: Mesh, method: GeodesicMethod = "heat", *, heat_time: float = 1.0) -> None:
        check_connected(mesh)
        self.method = method
        self.mesh = mesh
        self.heat_time = heat_time
        self._V = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
        self._F = np.ascontiguousarray(mesh.faces, dtype=np.int64)
        self._one: Callable[[int], NDArray[np.float64]]
        self._heat: HeatMethod | None = None
        if self.method == "heat":
            self._heat = HeatMethod(mesh, t_coef=self.heat_time)
            self._one = lambda s: self._heat.distances(np.array([s]))[0]  # type: ignore[union-attr]
        elif self.method == "fmm":
            import potpourri3d as pp3d

            fmm = pp3d.MeshFastMarchingDistanceSolver(self._V, self._F)
            # A source is a curve made of one point: (vertex index, no barycentric coordinates).
            self._one = lambda s: np.asarray(fmm.compute_distance([[(int(s), [])]]), dtype=np.float64)
        else:
            import igl

            targets = np.arange(mesh.n_vertices, dtype=np.int64)
            V, F = self._V, self._F
            self._one = lambda s: np.asarray(
                igl.exact_geodesic(V, F, VS=np.array([int(s)], dtype=np.int64), VT=targets), dtype=np.float64
            )

    @property
    def n_vertices(self) -> int:
        return self.mesh.n_vertices

    def __repr__(self) -> str:
        return f"GeodesicSolver(method={self.method!r}, n_vertices={self.n_vertices})"

    @validated(source=_vertex_indices("source", _OF_SOLVER))
    def distance(self, source: int) -> NDArray[np.float64]:
        """Distances from one vertex to every vertex, shape (n,); zero at the source."""
        s = int(source[0])
        d = self._one(s)
        if d.shape != (self.n_vertices,) or not np.all(np.isfinite(d)):
            raise RuntimeError(
                f"the {self.method!r} geodesic solver returned invalid distances from vertex {s}; "
                "check the mesh for degenerate or flipped triangles."
            )
        d = np.maximum(d, 0.0)
        d[s] = 0.0
        return d

    @validated(sources=_vertex_indices("source", _OF_SOLVER),
               targets=_vertex_indices("target", _OF_SOLVER, none=True),
               progress=PROGRESS,
               memory_budget=MEMORY_BUDGET)
    def distances(
        self,
        sources: ArrayLike,
        *,
        targets: ArrayLike | None = None,
        progress: bool | None = None,
        memory_budget: float | None = None,
    ) -> NDArray[np.float64]:
        """Distances from each source to every vertex (or to ``targets``), shape (len(sources), n).

        Parameters
        ----------
        sources : int or sequence of int
            Source vertex indices.
        targets : sequence of int, optional
            Keep only the distances to these vertices: shape (len(sources), len(targets)). Each
            field is still solved on the whole mesh, but only these columns are stored.
        progress : bool, optional
            Show a tqdm progress bar. Default: only for at least 500 sources.
        memory_budget : float, optional
            Refuse (``MemoryError`` with the size it would need) if the result would exceed this
            many bytes. Default: half of the memory currently available.
        """
        src, cols = sources, targets
        width = self.n_vertices if cols is None else cols.size
        need = distance_matrix_bytes(src.size, width)
        check_memory(need, memory_budget, f"a {src.size} x {width} distance matrix")
        out = np.empty((src.size, width), dtype=np.float64)
        if self._heat is not None:
            # Blocks of sources share each pass through the factorisations; the progress bar moves
            # once per group of blocks.
            group = 8 * self._heat.block_size
            starts = range(0, src.size, group)
            show = src.size >= PROGRESS_THRESHOLD if progress is None else progress
            for start in _progress(starts, len(starts), show, f"geodesics (heat, {group} sources at a time)"):
                self._heat.distances(src[start : start + group], out=out[start : start + group], targets=cols)
            if not np.all(np.isfinite(out)):
                raise RuntimeError(
                    "the heat-method geodesic solver returned invalid distances; check the mesh for "
                    "degenerate or flipped triangles."
                )
            return out
        for i, s in enumerate(_progress(src, src.size, progress, f"geodesics ({self.method})")):
            d = self.distance(int(s))
            out[i] = d if cols is None else d[cols]
        return out


def available_memory() -> int:
    """Bytes of memory currently available to this process (psutil's estimate)."""
    import psutil

    return int(psutil.virtual_memory().available)


def check_memory(need: int, budget: float | None, what: str, hint: str = "use fewer sources") -> None:
    """Raise ``MemoryError`` naming ``what`` and ``hint`` when ``need`` bytes exceed ``budget``.

    ``budget=None`` means half of the memory available now; a budget a user gives is checked by
    :data:`MEMORY_BUDGET` in the caller's table.
    """
    if budget is None:
        budget = 0.5 * available_memory()
        where = "half of the memory available now"
    else:
        where = "memory_budget"
    if need > budget:
        raise MemoryError(
            f"{what} needs {need / 2**30:.2f} GiB, more than {where} ({budget / 2**30:.2f} GiB). "
            f"{hint[0].upper() + hint[1:]}, or use spectral_mds / landmark_mds, which never form an n x n matrix."
        )


@validated(method=METHOD,
           mesh=MESH)
def geodesic_solver(mesh: Mesh, method: str) -> GeodesicSolver:
    """The solver of ``mesh`` for ``method``, built once and cached on the mesh."""
    return _solver(mesh, method)


@per_mesh
def _solver(mesh: Mesh, method: str) -> GeodesicSolver:
    return GeodesicSolver(mesh, method)


def geodesic_distances(
    mesh: Mesh,
    sources: ArrayLike,
    method: GeodesicMethod = "heat",
    *,
    targets: ArrayLike | None = None,
    progress: bool | None = None,
    memory_budget: float | None = None,
) -> NDArray[np.float64]:
    """Geodesic distances from ``sources`` to every vertex, shape (len(sources), n).

    The solver (and its factorisation) is built once per mesh and method and cached on the mesh,
    so repeated calls only pay for the new sources.

    Parameters
    ----------
    mesh : Mesh
        A connected mesh.
    sources : int or sequence of int
        Source vertex indices (0-based).
    method : {"heat", "exact", "fmm"}
        Heat method (fast, approximate), exact polyhedral geodesics (slow, exact) or fast marching.
    targets : sequence of int, optional
        Return only the distances to these vertices, shape (len(sources), len(targets)).
    progress : bool, optional
        tqdm progress bar; by default shown only for at least 500 sources.
    memory_budget : float, optional
        Refuse results larger than this many bytes (default: half the available memory).

    Returns
    -------
    ndarray, shape (len(sources), n)
        A scalar source still gives a 2-D result with one row.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> sphere = shapes.icosphere(3)
    >>> d = geodesic_distances(sphere, [0], method="exact")
    >>> bool(abs(d.max() - np.pi) < 0.02)   # the antipode is half a great circle away
    True
    """
    return geodesic_solver(mesh, method).distances(
        sources, targets=targets, progress=progress, memory_budget=memory_budget
    )


def _edge_graph(mesh: Mesh) -> Any:
    import scipy.sparse as sp

    e = mesh.edges
    length = np.linalg.norm(mesh.vertices[e[:, 0]] - mesh.vertices[e[:, 1]], axis=1)
    n = mesh.n_vertices
    return sp.csr_matrix((np.r_[length, length], (np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]])), shape=(n, n))


def _graph_farthest_points(mesh: Mesh, k: int, start: int) -> NDArray[np.int64]:
    """Farthest-point samples in shortest-path distance along the edges.

    A new sample can only bring vertices closer than the current covering radius R (the largest
    distance to the nearest sample), so its Dijkstra search stops at R: the searched balls shrink
    as samples are added and the whole run costs a few passes over the mesh.
    """
    from scipy.sparse.csgraph import dijkstra

    graph = _edge_graph(mesh)
    samples = np.empty(k, dtype=np.int64)
    nearest = np.full(mesh.n_vertices, np.inf)
    current = start
    for i in range(k):
        samples[i] = current
        radius = float(nearest.max())
        reach = dijkstra(graph, directed=True, indices=current, limit=radius)
        np.minimum(nearest, reach, out=nearest)
        nearest[samples[: i + 1]] = -1.0  # never twice, also where edges have zero length
        current = int(np.argmax(nearest))
    return samples


SampleSelection = Literal["geodesic", "graph"]


@validated(
    method=METHOD,
    mesh=MESH,
    k=Integer(1, lambda mesh, **_: mesh.n_vertices, what="an integer between 1 and the number of vertices ({high})",
              hint="you cannot pick more samples than the mesh has vertices"),
    select=Options("geodesic", "graph", message="select must be 'geodesic' or 'graph' (the distance samples are "
                   "chosen in), got {value!r}."),
    start=_vertex_indices("start", lambda mesh, **_: mesh.n_vertices),
    progress=PROGRESS,
)
def farthest_point_sampling(
    mesh: Mesh,
    k: int,
    *,
    start: int = 0,
    method: GeodesicMethod = "heat",
    return_distances: bool = False,
    progress: bool | None = None,
    select: SampleSelection = "geodesic",
) -> NDArray[np.int64] | tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Greedy farthest-point sampling in geodesic distance.

    Starting from ``start``, each new sample is the vertex farthest (in geodesic distance) from
    all samples chosen so far. The samples cover the surface evenly (a 2-approximation of the
    best covering radius). The result is *nested*: the first ``c`` samples of a run with
    ``k > c`` are exactly the samples of a run with ``k = c``.

    With ``select="graph"`` the samples are chosen by the same rule in shortest-path distance
    along the edges (which overestimates geodesic distance by a few percent, so the covering is
    as even), and only then are their geodesic fields computed, all together. For the heat method
    that is several times faster, because blocks of sources share each pass through the
    factorisations; with ``select="geodesic"`` every sample must wait for the previous one's
    field.

    Parameters
    ----------
    mesh : Mesh
        A connected mesh.
    k : int
        Number of samples, ``1 <= k <= n_vertices``.
    start : int, default 0
        The first sample.
    method : {"heat", "exact", "fmm"}
        Geodesic method (see :func:`geodesic_distances`).
    return_distances : bool, default False
        Also return the distance fields of the samples, shape (k, n), which sampling computes
        anyway (spectral and landmark MDS reuse them).
    progress : bool, optional
        tqdm progress bar; by default shown only for at least 500 samples.
    select : {"geodesic", "graph"}, default "geodesic"
        The distance in which samples are chosen (see above); the returned distances are
        geodesic either way.

    Returns
    -------
    samples : ndarray of int, shape (k,)
    distances : ndarray, shape (k, n)
        Only with ``return_distances=True``: ``distances[i]`` is the field of ``samples[i]``.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> sphere = shapes.icosphere(3)
    >>> s = farthest_point_sampling(sphere, 2, method="exact")
    >>> int(s[0]), bool(np.linalg.norm(sphere.vertices[s].sum(axis=0)) < 1e-9)  # antipodes
    (0, True)
    """
    check_connected(mesh)
    n, start = mesh.n_vertices, int(start[0])
    if select == "graph":
        # The solver factorises while the graph search runs (SuperLU releases the GIL), so
        # the two overlap instead of running one after the other.
        with ThreadPoolExecutor(1) as pool:
            building = pool.submit(geodesic_solver, mesh, method)
            samples = _graph_farthest_points(mesh, k, start)
            solver = building.result()
        if not return_distances:
            return samples
        return samples, solver.distances(samples, progress=progress)
    solver = geodesic_solver(mesh, method)
    check_memory(distance_matrix_bytes(k, n), None, f"{k} distance fields on {n} vertices")
    samples = np.empty(k, dtype=np.int64)
    fields = np.empty((k, n), dtype=np.float64)
    nearest = np.full(n, np.inf)
    current = start
    for i in _progress(range(k), k, progress, f"farthest-point sampling ({method})"):
        samples[i] = current
        fields[i] = solver.distance(current)
        np.minimum(nearest, fields[i], out=nearest)
        nearest[samples[: i + 1]] = -1.0  # never pick a sample twice (heat distances can be > 0 there)
        current = int(np.argmax(nearest))
    return (samples, fields) if return_distances else samples
