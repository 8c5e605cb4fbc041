"""The one sparse factorisation of a symmetric matrix: a fill-reducing symmetric order, diagonal pivots.

Every solver in the package factorises a symmetric matrix built from ``W`` and ``A``: the
shift-invert eigensolver (``W - b A``, indefinite), the heat method (``A + t W``, the pinned
``W``), regularized PCA, the smoothing bases. :func:`symmetric_lu` is that factorisation, once.

The ordering decides the cost. On a surface mesh the graph is planar-like, and nested dissection
(METIS, via ``pymetis``) cuts it along small separators. On large meshes it leaves less fill than
SuperLU's own minimum-degree ordering of the same matrix, so the factorisation and every solve
are faster, the ordering's own run included. The ordering
depends only on the sparsity pattern, so matrices that share one can share it
(:func:`fill_reducing_order`), as the eigensolver's shifts do. Below
:data:`NESTED_DISSECTION_MIN` unknowns METIS's own run costs more than it saves, so a matrix given
without an order is ordered by SuperLU's minimum degree there
(:attr:`SymmetricFactor.permutation` hands that order on to matrices of the same pattern).

Pivots are taken on the diagonal, in the symmetric order: ``P M P^T = L U`` with ``U = D L^T``,
so for an indefinite ``M`` the signs of ``D`` are its inertia (Sylvester's law), which is how
the eigensolver counts eigenvalues (:attr:`SymmetricFactor.n_negative`): :class:`SliceFactor`
factorises ``W - b A`` and counts the eigenvalues below ``b`` (:func:`count_below`).
"""

from __future__ import annotations

from dataclasses import dataclass

import ctypes

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray


__all__ = [
    "NESTED_DISSECTION_MIN", "SymmetricFactor", "SliceFactor", "count_below", "fill_reducing_order",
    "return_freed_memory",
    "symmetric_lu",
]

# Below this many unknowns a matrix with no order given is ordered by SuperLU itself (minimum
# degree on A + A^T): on small meshes METIS's own run costs more than the fill it saves, on large
# ones it pays for itself. The eigensolver follows the same rule with its several shifts (the
# first factorisation's order serves the others), and below this size it is no slower for it.
NESTED_DISSECTION_MIN = 20_000


def fill_reducing_order(matrix: sp.spmatrix) -> NDArray[np.intp]:
    """Nested-dissection ordering (METIS) of the sparsity graph of a square sparse matrix.

    The graph has an edge ``i - j`` where ``matrix[i, j]`` or ``matrix[j, i]`` is stored; values
    do not matter, so one ordering serves every matrix with that pattern.

    Returns
    -------
    ndarray (n,)
        A permutation: ``matrix[order][:, order]`` is the matrix to factorise.

    Examples
    --------
    >>> from lbo_notebooks import shapes, stiffness_matrix
    >>> order = fill_reducing_order(stiffness_matrix(shapes.icosphere(2)))
    >>> sorted(order.tolist()) == list(range(162))
    True
    """
    import pymetis

    entries = sp.coo_matrix(matrix)
    if entries.ndim != 2 or entries.shape[0] != entries.shape[1]:
        raise ValueError(f"a fill-reducing order needs a square matrix, got shape {entries.shape}.")
    n = entries.shape[0]
    if n <= 2:
        return np.arange(n)
    off_diagonal = entries.row != entries.col
    rows, cols = entries.row[off_diagonal], entries.col[off_diagonal]
    graph = sp.csr_matrix((np.ones(rows.size), (rows, cols)), shape=(n, n))
    graph = (graph + graph.T).tocsr()  # METIS wants each edge in both directions
    graph.sort_indices()
    order, _ = pymetis.nested_dissection(pymetis.CSRAdjacency(graph.indptr, graph.indices))
    return np.asarray(order, dtype=np.intp)


class SymmetricFactor:
    """``M = P^T L D L^T P`` for a symmetric sparse ``M``, as an unpivoted SuperLU of ``P M P^T``.

    Parameters
    ----------
    matrix : scipy.sparse matrix (n, n)
        Symmetric; not modified.
    order : ndarray (n,), optional
        The symmetric permutation ``P`` (a :func:`fill_reducing_order` of this matrix or of any
        with the same pattern, worth sharing when several matrices have it). When omitted: METIS's
        from :data:`NESTED_DISSECTION_MIN` unknowns on, SuperLU's minimum degree below.

    Raises
    ------
    RuntimeError
        SuperLU's, on an exactly zero pivot (the matrix is singular, or is one step from it).
    """

    def __init__(self, matrix: sp.spmatrix, order: ArrayLike | None = None) -> None:
        M = sp.csr_matrix(matrix)
        n = M.shape[0]
        self.shape = (n, n)
        if order is None and n >= NESTED_DISSECTION_MIN:
            order = fill_reducing_order(M)
        self.order = None if order is None else np.asarray(order, dtype=np.intp)
        if self.order is not None:
            if self.order.shape != (n,) or not np.array_equal(np.sort(self.order), np.arange(n)):
                raise ValueError(f"order must be a permutation of the {n} indices 0..{n - 1} (see fill_reducing_order).")
            self._inverse = np.argsort(self.order)  # x[order] = y  <=>  x = y[inverse]
        # Threshold 0 pivots on the diagonal, and SymmetricMode orders rows as columns: U = D L^T.
        options = {"diag_pivot_thresh": 0.0, "options": {"SymmetricMode": True}}
        if self.order is None:
            self._lu = spla.splu(M.tocsc(), permc_spec="MMD_AT_PLUS_A", **options)
        else:
            self._lu = spla.splu(M[self.order][:, self.order].tocsc(), permc_spec="NATURAL", **options)
        self._summary: tuple[int, NDArray[np.float64]] | None = None

    def _read_factors(self) -> tuple[int, NDArray[np.float64]]:
        """The fill and the pivots, read from SuperLU's ``L`` and ``U``, whose copies then go.

        SciPy builds ``L`` and ``U`` as CSC matrices on first access and keeps them on the
        factorisation: a second copy of the factor that no solve uses (at 51k vertices 54 MB, at
        10k 9 MB). Only their size and diagonal are kept; the kept matrices are emptied, since
        SciPy hands out the same objects again.
        """
        if self._summary is None:
            L, U = self._lu.L, self._lu.U
            self._summary = (int(L.nnz + U.nnz), U.diagonal())
            for copy in (L, U):
                copy.data, copy.indices = copy.data[:0].copy(), copy.indices[:0].copy()
        return self._summary

    @property
    def permutation(self) -> NDArray[np.intp]:
        """The symmetric order this factorisation used: the one given, or SuperLU's minimum degree.

        Matrices with the same pattern can be given it (``order=``) and skip the ordering step.
        """
        if self.order is not None:
            return self.order
        # SuperLU moves column j to position perm_c[j]: the order is its inverse.
        return np.argsort(self._lu.perm_c)

    @property
    def nnz(self) -> int:
        """Stored entries of ``L`` and ``U`` (the fill)."""
        return self._read_factors()[0]

    @property
    def n_negative(self) -> int:
        """Number of negative eigenvalues of the matrix (negative pivots: Sylvester's law of inertia).

        Raises ``ValueError`` if SuperLU pivoted off the diagonal (then the pivots are not the
        inertia) or a pivot is not finite.
        """
        if not np.array_equal(self._lu.perm_r, self._lu.perm_c):
            raise ValueError("the factorisation pivoted off the diagonal, so its pivots do not give the inertia.")
        pivots = self._read_factors()[1]
        if not np.all(np.isfinite(pivots)):
            raise ValueError("the matrix has a non-finite pivot; check it for NaN or inf.")
        return int(np.count_nonzero(pivots < 0))

    def solve(self, rhs: ArrayLike) -> NDArray[np.float64]:
        """``M^{-1} rhs`` for a vector (n,) or a block (n, c) of right-hand sides; a new array."""
        b = np.asarray(rhs, dtype=np.float64)
        if b.shape[:1] != (self.shape[0],) or b.ndim > 2:
            raise ValueError(f"rhs must have shape ({self.shape[0]},) or ({self.shape[0]}, c), got {b.shape}.")
        if self.order is None:
            return self._lu.solve(b)
        if b.ndim == 1:
            return self._lu.solve(b[self.order])[self._inverse]
        # Permute the rows through the transposes: one gather each way, and the Fortran order
        # SuperLU reads and writes is kept (no extra copy of the block).
        y = self._lu.solve(b.T[:, self.order].T)
        return y.T[:, self._inverse].T


def symmetric_lu(matrix: sp.spmatrix, order: ArrayLike | None = None) -> SymmetricFactor:
    """Factorise a symmetric sparse matrix (:class:`SymmetricFactor`): a fill-reducing symmetric order, diagonal pivots.

    Examples
    --------
    >>> import numpy as np
    >>> lu = symmetric_lu(sp.diags([2.0, -1.0, 4.0]))
    >>> lu.solve(np.array([2.0, 1.0, 8.0])).tolist(), lu.n_negative
    ([1.0, -1.0, 2.0], 1)
    """
    return SymmetricFactor(matrix, order)


@dataclass(frozen=True)
class SliceFactor:
    """``W - shift A`` factorised as ``L D L^T`` (via an unpivoted symmetric-ordering LU).

    Attributes
    ----------
    shift : float
        The point ``b`` of the spectrum.
    n_below : int
        Number of eigenvalues of ``W phi = lam A phi`` strictly below ``shift`` (Sylvester inertia).
    lu : SymmetricFactor or None
        The factorisation; ``lu.solve`` applies ``(W - shift A)^{-1}``. ``None`` once dropped (at
        50k vertices a factorisation takes as much memory as 125 eigenvectors; the count remains).
    """

    shift: float
    n_below: int
    lu: SymmetricFactor | None

    @classmethod
    def of(cls, stiffness: sp.spmatrix, mass: sp.spmatrix, shift: float, order: NDArray[np.intp] | None = None) -> "SliceFactor":
        """Factorise ``stiffness - shift * mass``; raise ``ValueError`` when ``shift`` is an eigenvalue.

        ``order``: a :func:`~lbo_notebooks.spectral._engine.factor.fill_reducing_order` of the pattern of
        ``stiffness`` and ``mass``, shared by every shift (when omitted,
        :func:`~lbo_notebooks.spectral._engine.factor.symmetric_lu` chooses one by size).
        """
        try:
            lu = symmetric_lu(stiffness - shift * mass, order)
        except RuntimeError as err:  # an exactly zero pivot: shift is (numerically) an eigenvalue
            raise ValueError(f"W - {shift:.17g} A is singular; move the shift off the eigenvalue.") from err
        try:
            n_below = lu.n_negative
        except ValueError as err:
            raise ValueError(f"W - {shift:.17g} A: {err}") from err
        return cls(shift=float(shift), n_below=n_below, lu=lu)


def count_below(stiffness: sp.spmatrix, mass: sp.spmatrix, value: float) -> int:
    """Number of eigenvalues of ``stiffness phi = lam mass phi`` below ``value`` (Sylvester inertia).

    Examples
    --------
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> m = shapes.icosphere(3)
    >>> count_below(stiffness_matrix(m), mass_matrix(m), 4.0)  # l = 0, 1: 1 + 3 eigenvalues below 4
    4
    """
    return SliceFactor.of(stiffness, mass, value).n_below


def return_freed_memory() -> None:
    """Ask glibc to hand freed heap pages back to the system (a factorisation leaves many behind).

    Does nothing where the C library is not glibc.

    Examples
    --------
    >>> return_freed_memory()  # never fails, whatever the platform
    """
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):  # not glibc (macOS, Windows, musl): nothing to do
        pass
