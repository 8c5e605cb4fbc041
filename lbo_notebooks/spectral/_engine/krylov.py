"""Block shift-invert Lanczos: the eigenpairs of ``W phi = lam A phi`` nearest a shift.

ARPACK's ``eigsh`` grows one vector at a time and orthogonalises it with matrix-vector products
(BLAS-2); for a Krylov space of a few hundred vectors on tens of thousands of vertices that
orthogonalisation, not the sparse solves, dominates. Here the space grows by blocks of ``b``
vectors: ``b`` right-hand sides share one pass through the factorisation, and full
reorthogonalisation is a pair of matrix-matrix products (BLAS-3).

With ``sigma`` the shift, the operator ``T = (W - sigma A)^{-1} A`` is self-adjoint in the
A-inner product and ``T phi = theta phi`` with ``theta = 1 / (lam - sigma)``: the eigenvalues
nearest ``sigma`` are the largest ``|theta|``. The basis ``Q`` is A-orthonormal and
``T Q_m = Q_m H_m + Q_next R E^T`` (block Arnoldi, ``H_m`` symmetric up to round-off), so a Ritz
pair ``(theta, Q_m s)`` has residual ``||T x - theta x||_A = ||R E^T s||``. When the basis is
full, the wanted Ritz vectors are kept and the space grows again from ``Q_next`` (thick restart).
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import scipy.linalg
import scipy.sparse as sp
from numpy.typing import NDArray

from .._mass_products import DiagonalMass, mass_operator

__all__ = ["nearest_eigenpairs"]

# Krylov blocks of this many vectors (rounded so that a slice needs a few of them).
BLOCK_SIZE = 4
# A direction of a new block is dependent when less than this fraction of its A-norm survives.
DEPENDENT = 1e-10
# Krylov basis size per wanted eigenpair before a thick restart (memory against restarts). At
# 2.5 an interior window could restart just before converging and need many more blocks; at 3.0
# it is done about one block after its first restart, as fast or faster for a little more memory
# (the basis is touched only as far as it grows).
BASIS_PER_PAIR = 3.0
# Thick restarts before giving up (each one refills the basis from the wanted Ritz vectors).
MAX_RESTARTS = 50
# A window may hold more pairs than expected (a cluster), and the basis grows to keep them, but to
# at most this many times its first size and never to the whole space: a window that held most of
# a 642-vertex spectrum once grew the basis past n at every restart and never returned.
MAX_GROWTH = 8


def _project_out(Q: NDArray[np.float64], Y: NDArray[np.float64], mass: sp.spmatrix | DiagonalMass) -> NDArray[np.float64]:
    """Remove from ``Y`` (in place) its A-projection on the A-orthonormal ``Q``; return the coefficients."""
    coefficients = Q.T @ (mass @ Y)
    Y -= Q @ coefficients
    return coefficients


def _rotate_in_place(Q: NDArray[np.float64], m: int, S: NDArray[np.float64], rows: int = 4096) -> None:
    """``Q[:, :p] = Q[:, :m] @ S`` without an (n, p) temporary: row blocks are independent."""
    p = S.shape[1]
    for start in range(0, Q.shape[0], rows):
        block = Q[start : start + rows]
        block[:, :p] = block[:, :m] @ S


def _orthonormal_block(
    Y: NDArray[np.float64],
    mass: sp.spmatrix | DiagonalMass,
    rng: np.random.Generator,
    Q: NDArray[np.float64],
    deflate: NDArray[np.float64] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """``Y = Q C + X R`` with ``X`` A-orthonormal and A-orthogonal to ``Q``; dependent directions replaced.

    ``Y`` is already A-orthogonal to ``Q`` up to round-off. Its A-Gram matrix
    ``G = U diag(d) U^T`` gives ``X = Y U d^{-1/2}``, ``R = d^{1/2} U^T``. When ``G`` is
    ill-conditioned that division amplifies round-off along ``Q``, so ``X`` is projected once more
    (the coefficients ``C``, usually zero, keep ``Y = Q C + X R`` exact). Directions with ``d``
    below ``DEPENDENT^2 max(d)`` (an invariant subspace was found) become random vectors orthogonal
    to everything (``deflate`` included), with zero rows in ``R``, so the block keeps its size.
    """
    n, b = Y.shape
    C = np.zeros((Q.shape[1], b))
    d, U = np.linalg.eigh(Y.T @ (mass @ Y))
    scale = max(float(d[-1]), np.finfo(float).tiny)
    keep = d > DEPENDENT**2 * scale
    r = int(np.count_nonzero(keep))
    X = np.empty((n, b), order="F")
    R = np.zeros((b, b))
    X[:, :r] = Y @ (U[:, keep] / np.sqrt(d[keep]))
    R[:r] = np.sqrt(d[keep])[:, None] * U[:, keep].T
    if r < b:
        X[:, r:] = rng.standard_normal((n, b - r))
        if deflate is not None:
            _project_out(deflate, X[:, r:], mass)
    if r < b or d[keep][0] < 1e-8 * scale:
        C += _project_out(Q, X, mass) @ R
        if r < b:  # the fresh columns: orthogonal to the kept ones too
            _project_out(Q, X[:, r:], mass)
            X[:, r:] -= X[:, :r] @ (X[:, :r].T @ (mass @ X[:, r:]))
    # Cholesky QR (twice in effect, after the eigen-step): X^T A X = I to round-off.
    L = np.linalg.cholesky(X.T @ (mass @ X))
    L_inv = np.linalg.inv(L)  # b x b, triangular
    X = (L_inv @ X.T).T  # Fortran-ordered like X, without a copy
    return X, L.T @ R, C


def nearest_eigenpairs(
    solve: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    stiffness: sp.spmatrix,
    mass: sp.spmatrix,
    shift: float,
    nev: int,
    *,
    start: NDArray[np.float64],
    window: tuple[float, float] | None = None,
    tol: float = 1e-10,
    block_size: int = BLOCK_SIZE,
    max_basis: int | None = None,
    seed: int = 0,
    deflate: NDArray[np.float64] | None = None,
    min_found: int = 0,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ``nev`` eigenpairs of ``stiffness phi = lam mass phi`` nearest ``shift``, ascending.

    Parameters
    ----------
    solve : callable
        ``solve(B)`` returns ``(stiffness - shift * mass)^{-1} B`` for a block ``B`` (n, b), e.g.
        the ``solve`` of a sparse LU factorisation.
    stiffness, mass : sparse (n, n)
        Symmetric, ``mass`` positive definite.
    shift : float
        Not an eigenvalue.
    nev : int
        Number of eigenpairs, ``1 <= nev < n``; with ``window``, the number expected in it (it
        sizes the basis, and the basis holds at least ``nev`` vectors before stopping).
    start : ndarray (n,)
        First start vector; the rest of the first block is seeded noise (deterministic).
    window : (low, high), optional
        Return every eigenpair with ``low < lam < high`` that the Krylov space has found instead
        of the ``nev`` nearest. Completeness is the caller's to prove (e.g. by inertia counts).
    tol : float
        Convergence: ``||T x - theta x||_A <= tol |theta|`` for each wanted Ritz pair.
    block_size : int
        Vectors per Krylov block. A block of ``b`` vectors finds at most ``b`` copies of an
        exactly repeated eigenvalue (in exact arithmetic; round-off may or may not bring the
        rest), so callers that can count eigenvalues retry with a larger block.
    max_basis : int, optional
        Largest basis before a thick restart; default ``max(BASIS_PER_PAIR nev, nev + 4 block_size)``.
    seed : int
        Seed of the start block's noise.
    deflate : ndarray (n, d), optional
        A-orthonormal eigenvectors already found: the space is kept A-orthogonal to them, so the
        run returns only eigenpairs outside their span (e.g. the copies of a multiple eigenvalue
        that an earlier run with a smaller block missed).
    min_found : int
        With ``window``: do not stop before at least this many pairs lie in it (e.g. the number an
        inertia count puts there); a ``RuntimeError`` after ``MAX_RESTARTS`` restarts otherwise.

    Returns
    -------
    values : ndarray (nev,) or (number in the window,)
        Rayleigh quotients of the eigenvectors, ascending.
    vectors : ndarray (n, len(values))
        A-orthonormal.

    Examples
    --------
    >>> import numpy as np, scipy.sparse.linalg as spla
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> m = shapes.icosphere(4)
    >>> W, A = stiffness_matrix(m), mass_matrix(m)
    >>> lu = spla.splu((W - 5.5 * A).tocsc())
    >>> values, vectors = nearest_eigenpairs(lu.solve, W, A, 5.5, 5, start=np.ones(m.n_vertices))
    >>> np.round(values, 1).tolist()  # l = 2: lam = 6 (l (l + 1) on the unit sphere), 5-fold
    [6.0, 6.0, 6.0, 6.0, 6.0]
    """
    n = stiffness.shape[0]
    if not 1 <= nev < n:
        raise ValueError(f"nev must be between 1 and n - 1 = {n - 1}, got {nev}.")
    if deflate is not None and (deflate.ndim != 2 or deflate.shape[0] != n or deflate.shape[1] + nev >= n):
        raise ValueError(f"deflate must be an (n, d) array with n = {n} and d + nev < n, got shape {deflate.shape}.")
    b = int(block_size)
    m_max = int(max_basis or max(int(BASIS_PER_PAIR * nev), nev + 4 * b))
    m_max = max(m_max - m_max % b, nev + 4 * b)  # room for three blocks after a thick restart
    largest = min(MAX_GROWTH * m_max, n - 2 * b)  # the basis grows (for a full window) at most to this
    if m_max + b >= n:  # the Krylov space would be most of the space: solve densely
        values, vectors = scipy.linalg.eigh(stiffness.toarray(), mass.toarray())
        if deflate is not None:  # the eigenvectors outside span(deflate) (D^T A x ~ 0 for them)
            rest = np.linalg.norm(deflate.T @ (mass @ vectors), axis=0) < 0.5
            values, vectors = values[rest], vectors[:, rest]
        if window is not None:
            chosen = (values > window[0]) & (values < window[1])
        else:
            chosen = np.sort(np.argsort(np.abs(values - shift), kind="stable")[:nev])
        return values[chosen], vectors[:, chosen]
    rng = np.random.default_rng(seed)
    mass = mass_operator(mass)  # a lumped mass: row scalings, not sparse products
    # The basis lives in the rows of a C-ordered buffer (Q is its transposed view, F-ordered, so
    # each block of columns is contiguous): at the end the buffer is shrunk in place to the
    # eigenvectors instead of copying them out of it.
    buffer = np.zeros((m_max + b, n))
    Q = buffer.T
    H = np.zeros((m_max + b, m_max + b))
    first = rng.standard_normal((n, b))
    first[:, 0] = start
    if deflate is not None:
        _project_out(deflate, first, mass)
    Q[:, :b], _, _ = _orthonormal_block(first, mass, rng, Q[:, :0], deflate)
    m = b  # columns in the basis
    cur = 0  # first column of the block T is applied to next
    local = 0  # T Q_cur lies in span(Q[:, local:m]) in exact arithmetic (Lanczos)
    restarts = 0
    # A set needs more than 2 basis vectors per pair before all its pairs converge: a look before
    # that only costs its O(m^3).
    next_check = max(nev + 2 * b, 2 * nev)
    while True:
        Y = np.asfortranarray(solve(mass @ Q[:, cur : cur + b]))
        if deflate is not None:  # span(deflate) is invariant: only round-off and residuals land there
            _project_out(deflate, Y, mass)
        # The recurrence's own coefficients, then one pass against the whole basis for the
        # round-off that the recurrence lets through (together: Gram-Schmidt twice where it matters).
        C = np.zeros((m, b))
        C[local:] = _project_out(Q[:, local:m], Y, mass)
        C += _project_out(Q[:, :m], Y, mass)
        X, R, extra = _orthonormal_block(Y, mass, rng, Q[:, :m], deflate)
        C += extra
        H[:m, cur : cur + b] = C
        H[cur : cur + b, :m] = C.T
        if m >= next_check or m + b > m_max:
            theta, S = np.linalg.eigh(H[:m, :m])  # LAPACK's divide and conquer: 20-30% sooner than evr here
            nearest = np.argsort(-np.abs(theta), kind="stable")
            if window is None:
                wanted = nearest[:nev]
            else:
                with np.errstate(divide="ignore"):
                    ritz = shift + 1.0 / theta[nearest]
                wanted = nearest[(ritz > window[0]) & (ritz < window[1])]
                if wanted.size + 2 * b > m_max:  # more in the window than expected: make room
                    m_max = int(BASIS_PER_PAIR * wanted.size) + 2 * b
                    m_max -= m_max % b
                    if m_max > largest:
                        raise RuntimeError(
                            f"block Lanczos at shift {shift:.6g}: the window ({window[0]:.6g}, {window[1]:.6g}) holds at "
                            f"least {wanted.size} Ritz values, far more than the {nev} expected; use a narrower window."
                        )
                    buffer = np.pad(buffer[:m], ((0, m_max + b - m), (0, 0)))
                    Q = buffer.T
                    H = np.pad(H[:m, :m], (0, m_max + b - m))
            residual = np.linalg.norm(R @ S[m - b : m, wanted], axis=0)
            converged = residual <= tol * np.abs(theta[wanted])
            if np.all(converged) and (window is None or (m >= nev + 2 * b and wanted.size >= min_found)):
                _rotate_in_place(Q, m, S[:, wanted])
                del Q
                buffer.resize((wanted.size, n), refcheck=False)  # no view of it is left
                vectors = buffer.T
                # Rayleigh quotients x^T W x (x is A-normalised), not shift + 1 / theta: the latter
                # loses digits by cancellation far from the shift (a zero eigenvalue came out as
                # -3e-12 instead of 4e-14). Column blocks keep the temporary small.
                values = np.concatenate(
                    [np.einsum("ij,ij->j", block, stiffness @ block) for block in np.array_split(vectors, max(1, -(-vectors.shape[1] // 32)), axis=1)]
                )
                order = np.argsort(values, kind="stable")
                return values[order], vectors[:, order]
            # An eigen-decomposition of H costs O(m^3): check again after about a tenth more.
            next_check = m + b * max(1, (m // 10) // b)
            if m + b > m_max:
                restarts += 1
                if restarts > MAX_RESTARTS:
                    raise RuntimeError(
                        f"block Lanczos at shift {shift:.6g} did not converge {nev} eigenpairs in {MAX_RESTARTS} restarts."
                    )
                # Thick restart: keep the wanted Ritz vectors plus a block of the next best and
                # continue from X, since T Q S_keep = Q S_keep Theta + X R E^T S_keep.
                others = nearest[~np.isin(nearest, wanted)]
                keep = np.concatenate((wanted, others[: max(nev + b - wanted.size, b)]))[: m - b]
                p = keep.size
                _rotate_in_place(Q, m, S[:, keep])
                H[:] = 0.0
                H[np.arange(p), np.arange(p)] = theta[keep]
                coupling = R @ S[m - b : m, keep]
                H[p : p + b, :p] = coupling
                H[:p, p : p + b] = coupling.T
                Q[:, p : p + b] = X
                m, cur, local = p + b, p, 0
                next_check = m + b
                continue
        Q[:, m : m + b] = X
        H[m : m + b, cur : cur + b] = R
        H[cur : cur + b, m : m + b] = R.T
        local, cur, m = cur, m, m + b
