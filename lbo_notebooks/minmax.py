"""The min–max (Courant–Fischer) principle for ``W phi = lam A phi``, made computable.

Discrete Courant–Fischer (MATH.md section 2)::

    lam[n] = max over subspaces L of codimension n of  min over f in L of (f W f) / (f A f)

and the maximum is attained by the A-orthogonal complement of the first n eigenvectors. A
codimension-n subspace is represented here by n *constraint* vectors ``C`` (columns):
``L = {f : C.T @ A @ f = 0}``, the A-orthogonal complement of ``span(C)``. Then

* :func:`min_rayleigh_quotient` computes ``min over f in L`` of the Rayleigh quotient,
* :func:`random_subspace` draws random constraints, and
* :func:`optimal_subspace` returns the constraints that attain the maximum.

This is the engine of the optimality theorem: for any n-dimensional V, the complement of V has
codimension n, so its minimum quotient is at most ``lam[n]``.
"""

from __future__ import annotations

from typing import Literal, overload

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from .optimality import _check_functions, _check_symmetric, a_orthonormalize
from .spectrum import Spectrum, check_operators

__all__ = ["rayleigh_quotient", "min_rayleigh_quotient", "random_subspace", "optimal_subspace"]

# Below this many vertices min_rayleigh_quotient(method="auto") uses dense linear algebra.
DENSE_LIMIT = 400

Method = Literal["auto", "dense", "sparse"]


def _operators(stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Accept sparse or dense (e.g. a 3 x 3 example) operators; validate them."""
    W = stiffness if sp.issparse(stiffness) else sp.csr_matrix(np.asarray(stiffness, dtype=np.float64))
    A = mass if sp.issparse(mass) else sp.csr_matrix(np.asarray(mass, dtype=np.float64))
    W, A = check_operators(W, A)
    _check_symmetric(W, "stiffness")
    _check_symmetric(A, "mass")
    return W, A


def rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix, f: ArrayLike
) -> NDArray[np.float64] | float:
    """Rayleigh quotient ``(f W f) / (f A f)`` per column of ``f``.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import eigenbasis, shapes
    >>> s = eigenbasis(shapes.icosphere(2), 4)
    >>> np.round(rayleigh_quotient(s.stiffness, s.mass, s.vectors), 10).tolist() == np.round(s.values, 10).tolist()
    True
    """
    W, A = _operators(stiffness, mass)
    arr = _check_functions(f, W.shape[0])
    den = np.einsum("i...,i...->...", arr, A @ arr)
    if np.any(den <= 0):
        raise ValueError("f (or one of its columns) is zero: the Rayleigh quotient is undefined.")
    out = np.einsum("i...,i...->...", arr, W @ arr) / den
    return float(out) if arr.ndim == 1 else np.asarray(out)


def _constraint_basis(orthogonal_to: ArrayLike | None, A: sp.csr_matrix) -> NDArray[np.float64]:
    n = A.shape[0]
    if orthogonal_to is None:
        return np.zeros((n, 0))
    C = np.asarray(orthogonal_to, dtype=np.float64)
    C = C[:, None] if C.ndim == 1 else C
    if C.ndim != 2 or C.shape[0] != n:
        raise ValueError(f"orthogonal_to must have shape ({n},) or ({n}, codim), got {np.shape(orthogonal_to)}.")
    if not np.all(np.isfinite(C)):
        raise ValueError("orthogonal_to contains NaN or inf.")
    if C.shape[1] >= n:
        raise ValueError(f"the codimension ({C.shape[1]}) must be smaller than the dimension ({n}).")
    return a_orthonormalize(C, A)


def _min_dense(W: sp.csr_matrix, A: sp.csr_matrix, Q: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
    Wd, Ad = W.toarray(), A.toarray()
    if Q.shape[1] == 0:
        values, vectors = scipy.linalg.eigh(Wd, Ad, subset_by_index=[0, 0])
        return float(values[0]), vectors[:, 0]
    Z = scipy.linalg.null_space((Ad @ Q).T)  # Euclidean basis of {f : Q.T A f = 0}
    values, vectors = scipy.linalg.eigh(Z.T @ Wd @ Z, Z.T @ Ad @ Z, subset_by_index=[0, 0])
    return float(values[0]), Z @ vectors[:, 0]


def _min_sparse(W: sp.csr_matrix, A: sp.csr_matrix, Q: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
    # Shift-invert Lanczos on the constrained pencil. With K = W + s A (positive definite), the
    # operator R b = x solving  K x + A Q z = b,  Q.T A x = 0  is symmetric, vanishes on A V and
    # maps the complement's eigenvectors to themselves with eigenvalue 1 / (mu + s). One sparse LU
    # of K plus the codim solves Y = K^{-1} A Q give R b = K^{-1} b - Y (Q.T A Y)^{-1} Y.T b.
    n = W.shape[0]
    shift = 1e-2 * 4.0 * np.pi / float(A.sum())
    lu = spla.splu((W + shift * A).tocsc(), permc_spec="MMD_AT_PLUS_A")
    AQ = np.asarray(A @ Q)
    if Q.shape[1]:
        Y = lu.solve(AQ)
        G = scipy.linalg.cho_factor(Q.T @ (A @ Y))

        def solve(b: NDArray[np.float64]) -> NDArray[np.float64]:
            b = np.ravel(b)
            return lu.solve(b) - Y @ scipy.linalg.cho_solve(G, Y.T @ b)
    else:

        def solve(b: NDArray[np.float64]) -> NDArray[np.float64]:
            return lu.solve(np.ravel(b))

    op = spla.LinearOperator((n, n), matvec=solve, dtype=np.float64)
    v0 = 1.0 + 0.5 * np.cos(np.arange(n, dtype=np.float64))
    v0 -= Q @ (AQ.T @ v0)
    values, vectors = spla.eigsh(W, k=1, M=A, sigma=-shift, OPinv=op, which="LM", v0=v0, tol=0.0, ncv=min(n - 1, 20))
    return float(values[0]), vectors[:, 0]


@overload
def min_rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix, orthogonal_to: ArrayLike | None = ..., *,
    method: Method = ..., return_vector: Literal[False] = ...,
) -> float: ...
@overload
def min_rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix, orthogonal_to: ArrayLike | None = ..., *,
    method: Method = ..., return_vector: Literal[True],
) -> tuple[float, NDArray[np.float64]]: ...
def min_rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix,
    mass: ArrayLike | sp.spmatrix,
    orthogonal_to: ArrayLike | None = None,
    *,
    method: Method = "auto",
    return_vector: bool = False,
) -> float | tuple[float, NDArray[np.float64]]:
    """Minimum of ``(f W f) / (f A f)`` over the subspace ``L = {f : C.T @ A @ f = 0}``.

    Parameters
    ----------
    stiffness, mass : sparse or dense (n, n)
        ``W`` (symmetric) and ``A`` (symmetric positive definite). Dense arrays are accepted for
        small examples such as a 3 x 3 matrix with ``mass = numpy.eye(3)``.
    orthogonal_to : array (n,) or (n, codim), optional
        Constraint vectors ``C``; ``L`` is the A-orthogonal complement of their span, of
        codimension ``rank(C)``. ``None`` means the whole space (the answer is ``lam[0]``).
    method : {"auto", "dense", "sparse"}
        ``"dense"``: a basis of L by SVD and ``scipy.linalg.eigh`` (small n); ``"sparse"``:
        shift-invert Lanczos on the constrained problem, one sparse LU of ``W + s A`` and ``codim``
        extra solves (no dense n x n matrix). ``"auto"`` picks dense below ``DENSE_LIMIT``.
    return_vector : bool
        Also return the minimiser, A-normalised with its largest entry positive.

    Returns
    -------
    float, or (float, ndarray (n,)).

    Examples
    --------
    >>> import numpy as np
    >>> M = np.diag([1.0, 2.0, 4.0])
    >>> min_rayleigh_quotient(M, np.eye(3), orthogonal_to=[1.0, 0.0, 0.0])  # lam_2 for this plane
    2.0
    >>> round(min_rayleigh_quotient(M, np.eye(3), orthogonal_to=[1.0, 1.0, 0.0]), 6)  # any other: less
    1.5
    """
    W, A = _operators(stiffness, mass)
    if method not in ("auto", "dense", "sparse"):
        raise ValueError(f"method must be 'auto', 'dense' or 'sparse', got {method!r}.")
    Q = _constraint_basis(orthogonal_to, A)
    n = W.shape[0]
    use_dense = method == "dense" or (method == "auto" and n <= DENSE_LIMIT) or n - Q.shape[1] < 50
    value, f = (_min_dense if use_dense else _min_sparse)(W, A, Q)
    if not return_vector:
        return value
    f = f / np.sqrt(float(f @ (A @ f)))
    return value, f if f[np.argmax(np.abs(f))] >= 0 else -f


def random_subspace(
    n_vertices: int, codim: int, *, seed: int = 0, pool: ArrayLike | None = None
) -> NDArray[np.float64]:
    """Constraints of a random codimension-``codim`` subspace (for :func:`min_rayleigh_quotient`).

    Parameters
    ----------
    n_vertices : int
    codim : int
        Codimension n (number of constraint vectors), ``0 <= codim < n_vertices``.
    seed : int
        Seed for ``numpy.random.default_rng``.
    pool : array (n_vertices, m), optional
        Draw the constraints as random Gaussian combinations of the pool's columns (for example
        the first 2n eigenvectors, which gives subspaces close to the optimal one). Default:
        i.i.d. Gaussian vectors in all of R^n_vertices.

    Returns
    -------
    ndarray (n_vertices, codim): the subspace is ``{f : C.T @ A @ f = 0}``.

    Examples
    --------
    >>> random_subspace(100, 5, seed=1).shape
    (100, 5)
    """
    if isinstance(n_vertices, bool) or not isinstance(n_vertices, (int, np.integer)) or n_vertices < 1:
        raise ValueError(f"n_vertices must be a positive integer, got {n_vertices!r}.")
    if isinstance(codim, bool) or not isinstance(codim, (int, np.integer)) or not 0 <= codim < n_vertices:
        raise ValueError(f"codim must be an integer in 0..{n_vertices - 1}, got {codim!r}.")
    rng = np.random.default_rng(seed)
    if pool is None:
        return rng.normal(size=(int(n_vertices), int(codim)))
    P = np.asarray(pool, dtype=np.float64)
    if P.ndim != 2 or P.shape[0] != n_vertices or not np.all(np.isfinite(P)):
        raise ValueError(f"pool must be a finite array of shape ({n_vertices}, m), got {P.shape}.")
    if P.shape[1] < codim:
        raise ValueError(f"pool has {P.shape[1]} columns; it needs at least codim = {codim} to span a codim-{codim} constraint set.")
    return P @ rng.normal(size=(P.shape[1], int(codim)))


def optimal_subspace(spectrum: Spectrum, n: int) -> NDArray[np.float64]:
    """Constraints of the optimal codimension-n subspace: the first n eigenvectors.

    Its minimum Rayleigh quotient is ``lam[n]``, attained at ``phi_n`` (Courant–Fischer).

    Examples
    --------
    >>> from lbo_notebooks import eigenbasis, shapes
    >>> s = eigenbasis(shapes.icosphere(2), 12)
    >>> C = optimal_subspace(s, 4)
    >>> bool(abs(min_rayleigh_quotient(s.stiffness, s.mass, C) - s.values[4]) < 1e-9)
    True
    """
    if not isinstance(spectrum, Spectrum):
        raise ValueError(f"spectrum must be a Spectrum, got {type(spectrum).__name__}.")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 0 <= n < spectrum.k:
        raise ValueError(f"n must be an integer with 0 <= n < k = {spectrum.k} (lam[n] must be known), got {n!r}.")
    return np.array(spectrum.vectors[:, : int(n)])
