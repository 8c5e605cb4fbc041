"""Geodesic distance fields from many sources at once: the heat method in batches.

The heat method (Crane, Weischedel & Wardetzky 2013) finds the distance from a source vertex s in
three linear steps:

1. diffuse heat for a short time ``t``: ``(A + t W) u = e_s``;
2. take the unit field pointing away from the source on every face, ``X = -grad u / |grad u|``;
3. find the function whose gradient fits ``X`` best in the least-squares sense: ``W phi = G.T a X``
   (``G`` the face-gradient operator, ``a`` the face areas, so that ``W = G.T a G``), and shift
   it so that ``phi(s) = 0``.

Both matrices are factorised once per mesh. Each source is a separate right-hand side of the same
two solves, and step 2 (not linear: it normalises) acts on each source's field alone, so a block
of b sources is b right-hand sides of the same two factorisations, and the triangular solves work
on b columns at once, so a source costs less in a block than alone. The two factorisations run
in two threads (SuperLU releases the GIL while it factorises; its solves release it too but gain
little from a second thread).

Step 1 uses the intrinsic Delaunay Laplacian of robust-laplacian (Sharp & Crane 2020): its
weights are non-negative, so the diffused heat has no spurious extrema on meshes with obtuse or
needle triangles, and its gradient points the right way. Steps 2-3 use the mesh's own
triangles, on which ``W = G.T a G`` holds exactly, so a linear function is recovered exactly from
its gradient.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from typing import Any, Callable

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .._support.validation import Number, Satisfies, validated
from ..geometry._mesh import Mesh, MeshError, per_mesh
from ..spectral._solvers import default_workers, mesh_order_where_it_pays, one_blas_thread, symmetric_lu

__all__ = ["HeatMethod", "face_gradient_operator", "solve_poisson"]

#: Largest block of sources. A source costs less in a block than alone; past blocks of 8 the cost
#: per source stops falling, and very large blocks cost more again.
MAX_BLOCK = 8
#: Cap on block size x vertices, so that the (3 m x block) gradient array stays under about 100 MB
#: on meshes of a million vertices.
BLOCK_ENTRIES = 2_000_000


def face_gradient_operator(mesh: Mesh) -> tuple[sp.csr_matrix, NDArray[np.float64]]:
    """The gradient of piecewise-linear functions, ``(G, areas)``.

    ``G`` has shape (3 m, n): rows ``c * m + f`` hold coordinate ``c`` of the (constant) gradient on
    face ``f`` of the hat functions, ``grad phi_i = (N x e_i) / (2 a_f)`` with ``e_i`` the edge
    opposite vertex ``i`` and ``N`` the unit normal. Faces of zero area get a zero gradient.
    ``G.T diag(a, a, a) G`` is the cotangent stiffness matrix.

    Examples
    --------
    >>> from lbo_notebooks import Mesh
    >>> m = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> G, a = face_gradient_operator(m)
    >>> (G @ np.array([0.0, 2.0, 3.0])).tolist(), a.tolist()   # f = 2x + 3y
    ([2.0, 3.0, 0.0], [0.5])
    """
    V, F = mesh.vertices, mesh.faces
    m, n = len(F), mesh.n_vertices
    edges = [V[F[:, (i + 2) % 3]] - V[F[:, (i + 1) % 3]] for i in range(3)]  # edge opposite corner i
    normal = np.cross(edges[0], edges[1])
    double_area = np.linalg.norm(normal, axis=1)
    # N / (2 a) with |N| = 2a; zero for a degenerate face.
    scale = np.divide(1.0, double_area**2, out=np.zeros(m), where=double_area > 0)
    faces = np.arange(m)
    rows, cols, vals = [], [], []
    for i in range(3):
        grad = np.cross(normal, edges[i]) * scale[:, None]
        for c in range(3):
            rows.append(c * m + faces)
            cols.append(F[:, i])
            vals.append(grad[:, c])
    G = sp.csr_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(3 * m, n)
    )
    return G, 0.5 * double_area


def _block_size(n: int) -> int:
    return int(np.clip(BLOCK_ENTRIES // max(n, 1), 1, MAX_BLOCK))


def _in_blocks(work: Callable[[slice], None], total: int, block: int) -> None:
    """``work(columns)`` for consecutive blocks of ``total`` columns, in two threads if there are two cores.

    Each thread gets one BLAS thread: SuperLU's solves call BLAS on blocks of ``block`` columns,
    and two threads each running a two-thread BLAS were no faster than one thread alone. With one
    BLAS thread each, two threads solve blocks of sources clearly faster than one,
    and every block comes out the same, bit for bit, for any
    number of threads.
    """
    blocks = [slice(start, min(start + block, total)) for start in range(0, total, block)]
    workers = min(default_workers(), len(blocks))
    with one_blas_thread():
        if workers == 1:
            for columns in blocks:
                work(columns)
        else:
            with ThreadPoolExecutor(workers) as pool:
                list(pool.map(work, blocks))


def _factor(matrix: sp.spmatrix, order: NDArray[np.intp] | None = None) -> Any:
    try:
        return symmetric_lu(matrix, order)
    except RuntimeError as err:  # SuperLU: "Factor is exactly singular"
        raise MeshError(
            f"could not factorise this mesh's Laplacian ({err}): some vertices touch only degenerate "
            "(zero-area) faces. Repair it: lbo_notebooks.clean_mesh(mesh) or load_mesh(path, clean=True)."
        ) from err


@per_mesh
def _gradient(mesh: Mesh) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """``(G, G.T diag(a))``: the face gradient and the (integrated) divergence of face fields."""
    G, areas = face_gradient_operator(mesh)
    return G, (G.T @ sp.diags(np.tile(areas, 3))).tocsr()


@per_mesh
def _poisson_factor(mesh: Mesh) -> Any:
    # W = G.T a G rather than operators.stiffness_matrix: equal on a good mesh, but it stays
    # finite on zero-area faces. It is singular (constants); pinning vertex 0 makes it definite
    # on a connected mesh.
    G, divergence = _gradient(mesh)
    order = mesh_order_where_it_pays(mesh)
    if order is not None:  # the same order without vertex 0
        order = order[order != 0] - 1
    return _factor((divergence @ G).tocsc()[1:, 1:], order)


def solve_poisson(mesh: Mesh, rhs: NDArray[np.float64]) -> NDArray[np.float64]:
    """Solve ``W phi = rhs`` column by column, with ``phi = 0`` at vertex 0.

    ``W`` is the cotangent stiffness matrix of the connected ``mesh`` (as ``G.T a G``). The
    equation has a solution only when a column of ``rhs`` sums to zero; for other columns the
    result is still linear in ``rhs``, so combinations of columns that sum to zero are solved
    exactly. The factorisation is made once per mesh and shared with :class:`HeatMethod`.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> from lbo_notebooks.operators._cotangent import stiffness_matrix
    >>> m = shapes.icosphere(2)
    >>> b = np.zeros((m.n_vertices, 1)); b[3], b[40] = 1.0, -1.0
    >>> phi = solve_poisson(m, b)
    >>> bool(np.allclose(stiffness_matrix(m) @ phi, b)), float(phi[0, 0])
    (True, 0.0)
    """
    rhs = np.asarray(rhs, dtype=np.float64)
    lu = _poisson_factor(mesh)
    out = np.zeros(rhs.shape)
    if rhs.ndim == 1:
        out[1:] = lu.solve(np.ascontiguousarray(rhs[1:]))
        return out

    def work(columns: slice) -> None:
        out[1:, columns] = lu.solve(np.ascontiguousarray(rhs[1:, columns]))

    _in_blocks(work, rhs.shape[1], _block_size(mesh.n_vertices))
    return out


class HeatMethod:
    """Heat-method distance fields on one connected mesh, factorised once.

    Parameters
    ----------
    mesh : Mesh
        A connected triangle mesh (boundaries are allowed; the heat flow is insulated there).
    t_coef : float, default 1.0
        Diffusion time ``t = t_coef * h**2``, ``h`` the mean edge length (Crane et al.'s choice).

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> heat = HeatMethod(shapes.icosphere(3))
    >>> d = heat.distances([0, 5])
    >>> d.shape, bool(abs(d[0].max() / np.pi - 1) < 0.02)   # the antipode: half a great circle
    ((2, 642), True)
    """

    @validated(
        mesh=Satisfies(lambda mesh: isinstance(mesh, Mesh), message="HeatMethod needs a Mesh, got {type}."),
        t_coef=Number(0, open_low=True, what="a positive number (the diffusion time in units of h^2; try 1.0)"),
    )
    def __init__(self, mesh: Mesh, t_coef: float = 1.0) -> None:
        from ..operators._robust import robust_operators

        self.n = mesh.n_vertices
        self._mesh = mesh
        self._G, self._divergence = _gradient(mesh)
        t = t_coef * mesh.mean_edge_length**2
        W_delaunay, A_delaunay = robust_operators(mesh)
        # Both factorisations at once (SuperLU releases the GIL while it factorises). The intrinsic
        # Delaunay operators have a pattern of their own (flipped edges: on a stretched torus a
        # mesh-edge order gave them much more fill), so the heat step is ordered on its own matrix.
        with ThreadPoolExecutor(2) as pool:
            poisson = pool.submit(_poisson_factor, mesh)
            self._heat = _factor(A_delaunay + t * W_delaunay)
            self._poisson = poisson.result()

    @property
    def block_size(self) -> int:
        """Sources solved together: :data:`MAX_BLOCK`, fewer on meshes above 250k vertices."""
        return _block_size(self.n)

    def _block(self, sources: NDArray[np.int64]) -> NDArray[np.float64]:
        b, m = sources.size, self._G.shape[0] // 3
        columns = np.arange(b)
        rhs = np.zeros((self.n, b))
        rhs[sources, columns] = 1.0
        u = np.ascontiguousarray(self._heat.solve(rhs))
        grad = self._G @ u  # (3m, b): x, y, z blocks of rows
        gx, gy, gz = grad[:m], grad[m : 2 * m], grad[2 * m :]
        norm = gx * gx
        norm += gy * gy
        norm += gz * gz
        np.sqrt(norm, out=norm)
        # -grad u / |grad u|; a face where u is flat (far from every source, or degenerate) gets 0.
        np.divide(-1.0, norm, out=norm, where=norm > 0)
        grad.reshape(3, m, b)[...] *= norm
        rhs = np.asarray(self._divergence @ grad)
        phi = np.zeros((self.n, b))
        phi[1:] = self._poisson.solve(np.ascontiguousarray(rhs[1:]))
        phi -= phi[sources, columns]
        np.maximum(phi, 0.0, out=phi)
        return phi.T

    def distances(
        self,
        sources: NDArray[np.int64],
        out: NDArray[np.float64] | None = None,
        targets: NDArray[np.int64] | None = None,
    ) -> NDArray[np.float64]:
        """Distance fields of ``sources`` (vertex indices), shape (len(sources), n).

        With ``targets``, only those columns are kept: shape (len(sources), len(targets)). Rows
        are written into ``out`` when it is given.
        """
        sources = self._indices(sources, "sources")
        columns = None if targets is None else self._indices(targets, "targets")
        shape = (sources.size, self.n if columns is None else columns.size)
        if out is None:
            out = np.empty(shape)
        elif out.shape != shape:
            raise ValueError(f"out must have shape {shape}, got {out.shape}.")

        def work(rows: slice) -> None:
            fields = self._block(sources[rows])
            out[rows] = fields if columns is None else fields[:, columns]

        if sources.size:  # no sources: the empty (0, n) answer, not a pool of no workers
            _in_blocks(work, sources.size, self.block_size)
        return out

    def _indices(self, indices: Any, name: str) -> NDArray[np.int64]:
        arr = np.asarray(indices).reshape(-1)
        if arr.size and (not np.issubdtype(arr.dtype, np.integer) or arr.min() < 0 or arr.max() >= self.n):
            raise ValueError(f"{name} must be vertex indices in 0..{self.n - 1}, got {arr[:5].tolist()}...")
        return arr.astype(np.int64)
