"""Spectrum slicing: the lowest eigenpairs of ``W phi = lam A phi`` with a proof that none is missed.

One shift-invert Lanczos run for ``k`` eigenpairs carries a Krylov space of ``2k + 1`` vectors, and
orthogonalising it costs ``O(n k^2)`` per restart: at 50k vertices and ``k = 300`` that, not the
sparse solves, is most of the time. Slicing (Vallet & Lévy 2008) cuts the spectrum into intervals
``(b_{j-1}, b_j]`` of a few dozen eigenvalues and runs one small Lanczos per interval.

Each shift ``b`` is factorised once, ``P (W - b A) P^T = L U`` with a symmetric ordering and no
row pivoting, so that ``U = D L^T`` and, by Sylvester's law of inertia, the number of negative
pivots in ``D`` *is* the number of eigenvalues below ``b``. The same factorisation runs a
shift-invert Lanczos for the eigenvalues nearest ``b``. Between two consecutive shifts the
difference of their counts says exactly how many eigenpairs the interval holds, and a slice that
comes back with a different number raises instead of silently dropping one.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

__all__ = ["SliceFactor", "count_below", "slice_eigsh"]

# Eigenvalues per slice: the orthogonalisation cost n * ncv^2 per slice against one
# factorisation per slice (about as costly as 30-40 solves at 50k vertices).
SLICE_SIZE = 100
# Lanczos convergence tolerance (ARPACK's, relative to the shifted-inverted eigenvalue).
TOL = 1e-10


@dataclass(frozen=True)
class SliceFactor:
    """``W - shift A`` factorised as ``L D L^T`` (via an unpivoted symmetric-ordering LU).

    Attributes
    ----------
    shift : float
        The point ``b`` of the spectrum.
    n_below : int
        Number of eigenvalues of ``W phi = lam A phi`` strictly below ``shift`` (Sylvester inertia).
    lu : scipy.sparse.linalg.SuperLU
        The factorisation; ``lu.solve`` applies ``(W - shift A)^{-1}``.
    """

    shift: float
    n_below: int
    lu: spla.SuperLU

    @classmethod
    def of(cls, stiffness: sp.spmatrix, mass: sp.spmatrix, shift: float) -> "SliceFactor":
        """Factorise ``stiffness - shift * mass``; raise ``ValueError`` when ``shift`` is an eigenvalue."""
        matrix = sp.csc_matrix(stiffness - shift * mass)
        try:
            # Diagonal pivots only (threshold 0) and one symmetric ordering of rows and columns:
            # then U = D L^T and the signs of diag(U) are the inertia of the matrix.
            lu = spla.splu(matrix, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        except RuntimeError as err:  # an exactly zero pivot: shift is (numerically) an eigenvalue
            raise ValueError(f"W - {shift:.17g} A is singular; move the shift off the eigenvalue.") from err
        if not np.array_equal(lu.perm_r, lu.perm_c):
            raise ValueError("the factorisation pivoted off the diagonal, so its pivots do not give the inertia.")
        pivots = lu.U.diagonal()
        if not np.all(np.isfinite(pivots)):
            raise ValueError(f"W - {shift:.17g} A has a non-finite pivot; check the operators for NaN or inf.")
        return cls(shift=float(shift), n_below=int(np.count_nonzero(pivots < 0)), lu=lu)


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


def _nearest(
    W: sp.csr_matrix, A: sp.csr_matrix, factor: SliceFactor, nev: int, v0: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ``nev`` eigenpairs nearest ``factor.shift`` (shift-invert Lanczos), ascending."""
    n = W.shape[0]
    op = spla.LinearOperator((n, n), matvec=factor.lu.solve, dtype=np.float64)
    ncv = min(n, max(2 * nev + 1, 20))
    # tol bounds the residual relative to 1 / (lam - shift); eigenvalues then err by its square.
    values, vectors = spla.eigsh(W, k=nev, M=A, sigma=factor.shift, which="LM", OPinv=op, v0=v0, ncv=ncv, tol=TOL)
    order = np.argsort(values)
    return values[order], vectors[:, order]


def _next_shift(W: sp.csr_matrix, A: sp.csr_matrix, current: SliceFactor, want: int, slope: float, k: int) -> SliceFactor:
    """Factorise a shift about ``want`` eigenvalues above ``current`` (``slope``: eigenvalues per unit).

    Too few or too many new eigenvalues move the shift (by the counts' slope, then by bisection
    between the last shifts that gave too few and too many). A cluster larger than a slice cannot
    be split: once the bracket is that narrow, the shift above the whole cluster is taken.
    """
    low, high = current.shift, None
    best_high: SliceFactor | None = None
    shift = current.shift + want / slope
    for _ in range(60):
        nxt = SliceFactor.of(W, A, shift)
        gained = nxt.n_below - current.n_below
        if gained > 2 * want + 8:
            high, best_high = shift, nxt
        elif gained < max(1, want // 3) and nxt.n_below < k:
            low = shift
        else:
            return nxt
        if high is None:
            shift = low + 2.0 * (low - current.shift) if gained == 0 else low + (low - current.shift) * min(2.0, want / gained)
        elif high - low <= 1e-9 * abs(high):
            return best_high
        else:
            shift = 0.5 * (low + high)
    if best_high is not None:
        return best_high
    raise RuntimeError("spectrum slicing could not place a shift; use solver='arpack'.")


def slice_eigsh(
    stiffness: sp.spmatrix,
    mass: sp.spmatrix,
    k: int,
    *,
    v0: NDArray[np.float64],
    shift: float,
    slice_size: int = SLICE_SIZE,
) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """The ``k`` smallest eigenpairs of ``stiffness phi = lam mass phi`` by spectrum slicing.

    Shifts ``sigma_0 = -shift < sigma_1 < ... < sigma_m`` are placed about ``slice_size``
    eigenvalues apart, each factorised once (which counts the eigenvalues below it). At each shift
    Lanczos finds the eigenvalues nearest to it (at the last shift only those below it are kept).
    Consecutive shifts' sets overlap; the interval between two shifts takes the lower set's
    eigenvalues below a split point and the upper set's above it, the split sitting in the widest
    gap of the overlap so that no cluster of (near-)equal eigenvalues is cut (or, failing that, one
    set alone). The number taken must equal the difference of the two inertia counts, or the shift
    is rerun with a larger set and finally a ``RuntimeError`` is raised: an eigenvalue is never
    silently missed.

    Parameters
    ----------
    stiffness, mass : scipy.sparse matrix
        Symmetric; ``stiffness`` positive semidefinite, ``mass`` positive definite.
    k : int
        Number of eigenpairs, ``1 <= k < n``.
    v0 : ndarray, shape (n,)
        Lanczos start vector (the same for every shift, so results are deterministic).
    shift : float > 0
        ``stiffness + shift * mass`` is positive definite; the first shift is ``-shift``.
    slice_size : int
        Target number of eigenvalues between consecutive shifts.

    Returns
    -------
    values : ndarray, shape (k,)
        Ascending.
    vectors : ndarray, shape (n, k)
        Eigenvectors, A-orthonormal within each shift's set (across sets up to residual / gap).
    n_below : int
        Inertia count at the last shift: exactly ``n_below >= k`` eigenvalues lie below it and all
        of them were found, so none below ``values[-1]`` is missing.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> m = shapes.icosphere(4)
    >>> W, A = stiffness_matrix(m), mass_matrix(m)
    >>> values, vectors, n_below = slice_eigsh(W, A, 25, v0=np.ones(m.n_vertices), shift=0.01, slice_size=8)
    >>> np.round(values[[1, 4, 9, 16]]).tolist()  # l (l + 1), l = 1..4, with multiplicities 2l + 1
    [2.0, 6.0, 12.0, 20.0]
    >>> n_below >= 25 and count_below(W, A, values[-1] * (1 + 1e-6)) == 25  # l <= 4: 25 eigenvalues
    True
    """
    W, A = sp.csr_matrix(stiffness, dtype=np.float64), sp.csr_matrix(mass, dtype=np.float64)
    n = W.shape[0]
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not 1 <= k < n:
        raise ValueError(f"k must be an integer between 1 and n - 1 = {n - 1}, got {k!r}.")
    if isinstance(slice_size, bool) or not isinstance(slice_size, (int, np.integer)) or slice_size < 1:
        raise ValueError(f"slice_size must be a positive integer, got {slice_size!r}.")
    if isinstance(shift, bool) or not (np.isscalar(shift) and np.isfinite(shift) and shift > 0):
        raise ValueError(f"shift must be a positive number, got {shift!r}.")
    v0 = np.asarray(v0, dtype=np.float64)
    if v0.shape != (n,) or not np.all(np.isfinite(v0)):
        raise ValueError(f"v0 must be a finite vector of shape ({n},), got shape {v0.shape}.")
    current = SliceFactor.of(W, A, -float(shift))
    if current.n_below:
        raise ValueError(f"stiffness + {shift:g} mass is not positive definite: stiffness must be positive semidefinite.")
    # Weyl's law N(lam) ~ area lam / (4 pi) sets the first spacing; later ones extrapolate the
    # measured counts (N grows about linearly in lam on a surface).
    slope = float(A.sum()) / (4.0 * np.pi)
    target = k + max(2, k // 50)  # the last shift only needs to clear lam_k
    margin = max(3, slice_size // 10)
    # Intervals come in increasing order and each is ascending, so results fill in order; only
    # the first k are kept (preallocated: no list of blocks plus a concatenated copy).
    out_values = np.empty(k)
    out_vectors = np.empty((n, k))
    filled = 0
    carry_values = np.empty(0)  # the previous set's eigenpairs above the previous shift
    carry_vectors = np.empty((n, 0))
    carry_top = -np.inf  # ... complete (all eigenvalues present) below this value
    previous: SliceFactor | None = None
    while True:
        last = previous is not None and current.n_below >= k
        interval = 0 if previous is None else current.n_below - previous.n_below
        covered = np.count_nonzero(carry_values < carry_top)
        below_need = max(interval - covered, 0) + margin
        if last:
            # Lanczos for the eigenvalues just below the shift (which="SA") keeps converging to
            # the unwanted ones just above it; asking for the nearest on both sides is faster
            # even though the upper half is discarded.
            nxt = None
            nev = 2 * below_need + margin
        else:
            nxt = _next_shift(W, A, current, min(slice_size, target - current.n_below), slope, k)
            slope = nxt.n_below / max(nxt.shift, np.finfo(float).tiny)
            nev = below_need + (nxt.n_below - current.n_below) // 2 + 1
        taken = -1
        for _ in range(3):
            nev = min(nev, n - 1)
            values, vectors = _nearest(W, A, current, nev, v0)
            radius = float(np.max(np.abs(values - current.shift)))
            if previous is None:
                break
            # Both sets should hold every eigenvalue strictly inside (current.shift - radius,
            # carry_top); either may reach past the interval (previous.shift, current.shift).
            low, top = max(current.shift - radius, previous.shift), min(carry_top, current.shift)
            inside = np.sort(np.concatenate(([low, top], carry_values[(carry_values > low) & (carry_values < top)])))
            # Split candidates: the widest gap of the overlap (no cluster cut), else one set alone.
            # Lanczos can return only part of an exactly multiple eigenvalue and farther ones
            # instead, so "complete inside its radius" is a hope, not a fact: the count decides.
            splits = [float(previous.shift)]
            if low < top:  # the overlap is not empty
                gaps = np.diff(inside)
                splits.insert(0, float(inside[np.argmax(gaps)] + gaps.max() / 2))
            if carry_top > current.shift:
                splits.append(float(current.shift))
            for split in splits:
                from_carry = carry_values < split
                mine = (values > split) & (values < current.shift)
                taken = np.count_nonzero(from_carry) + np.count_nonzero(mine)
                if taken == interval:
                    break
            if taken == interval:
                for vals, vecs in ((carry_values[from_carry], carry_vectors[:, from_carry]), (values[mine], vectors[:, mine])):
                    take = min(vals.size, k - filled)
                    out_values[filled : filled + take] = vals[:take]
                    out_vectors[:, filled : filled + take] = vecs[:, :take]
                    filled += take
                break
            if nev >= n - 1:
                break
            nev += max(interval - max(taken, 0), 0) + 2 * margin
        if previous is not None and taken != interval:
            raise RuntimeError(
                f"spectrum slicing found {max(taken, 0)} eigenvalues between the shifts {previous.shift:.6g} and "
                f"{current.shift:.6g} where the inertia counts say {interval}; use solver='arpack'."
            )
        if last:
            break
        above = values > current.shift
        carry_values, carry_vectors = values[above], vectors[:, above]
        carry_top = current.shift + radius
        previous, current = current, nxt
    return out_values, out_vectors, current.n_below
