"""The min–max (Courant–Fischer) principle for ``W phi = lam A phi``, made computable.

Discrete Courant–Fischer (docs/maths.md, "Min–max")::

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

from .._support.validation import Array, Integer, Options, Relation, Satisfies, validated
from ..spectral._inner_product import (
    a_orthonormalize,
    check_functions,
    check_operators,
    fix_signs,
)
from ..spectral._solvers import default_shift, start_vector, symmetric_lu, use_dense
from ..spectral._spectrum import Spectrum

__all__ = [
    "rayleigh_quotient",
    "min_rayleigh_quotient",
    "ConstrainedRayleigh",
    "random_subspace",
    "optimal_subspace",
    "complement_ratio",
]

Method = Literal["auto", "dense", "sparse"]

_METHOD = Options("auto", "dense", "sparse", message="method must be 'auto', 'dense' or 'sparse', got {value!r}.")

# Below this many free dimensions (n minus the codimension) Lanczos has no room: solve densely.
_LANCZOS_ROOM = 50


def _operators(stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Accept sparse or dense (e.g. a 3 x 3 example) operators; validate them."""
    return check_operators(stiffness, mass, allow_dense=True)


def rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix, f: ArrayLike
) -> NDArray[np.float64] | float:
    """Rayleigh quotient ``(f W f) / (f A f)`` per column of ``f``.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import eigenbasis, shapes
    >>> s = eigenbasis(shapes.icosphere(2), 4)
    >>> bool(np.allclose(rayleigh_quotient(s.stiffness, s.mass, s.vectors), s.values, rtol=1e-10, atol=1e-10 * s.values[-1]))
    True
    """
    W, A = _operators(stiffness, mass)
    arr = check_functions(f, W.shape[0])
    den = np.einsum("i...,i...->...", arr, A @ arr)
    if np.any(den <= 0):
        raise ValueError("f (or one of its columns) is zero: the Rayleigh quotient is undefined.")
    out = np.einsum("i...,i...->...", arr, W @ arr) / den
    return float(out) if arr.ndim == 1 else np.asarray(out)


def _constraint_basis(orthogonal_to: ArrayLike | None, A: sp.csr_matrix) -> NDArray[np.float64]:
    n = A.shape[0]
    if orthogonal_to is None:
        return np.zeros((n, 0))
    # The rule applied here, not in a table: n is that of the checked operators.
    C = Array(rows=n, cols_name="codim", column=True).check(orthogonal_to, "orthogonal_to", {})
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


def _result(
    value: float, f: NDArray[np.float64], A: sp.csr_matrix, return_vector: bool
) -> float | tuple[float, NDArray[np.float64]]:
    if not return_vector:
        return value
    return value, fix_signs(f / np.sqrt(float(f @ (A @ f))), A)


class ConstrainedRayleigh:
    """Reusable solver for :func:`min_rayleigh_quotient` on one ``(W, A)`` pair, many subspaces.

    Factorises ``K = W + s A`` (positive definite for a small ``s > 0``) once by sparse LU; each
    query then costs ``codim`` extra solves and a short shift-invert Lanczos run. For constraints
    ``Q`` (A-orthonormal), the operator ``R b = x`` solving ``K x + A Q z = b, Q.T A x = 0`` is
    ``R b = K^{-1} b - Y (Q.T A Y)^{-1} Y.T b`` with ``Y = K^{-1} A Q``: it is symmetric, vanishes on
    ``A V`` and maps each eigenvector of the constrained problem to itself times ``1 / (mu + s)``.

    Examples
    --------
    >>> from lbo_notebooks import eigenbasis, shapes
    >>> s = eigenbasis(shapes.bumpy_sphere(3), 12)
    >>> solver = ConstrainedRayleigh(s.stiffness, s.mass)
    >>> bool(abs(solver.minimum(s.vectors[:, :5]) - s.values[5]) < 1e-9 * s.values[5])
    True
    """

    def __init__(self, stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix) -> None:
        self.stiffness, self.mass = _operators(stiffness, mass)
        self.shift = default_shift(self.mass)
        self._lu = symmetric_lu(self.stiffness + self.shift * self.mass)

    def minimum(
        self, orthogonal_to: ArrayLike | None = None, *, return_vector: bool = False
    ) -> float | tuple[float, NDArray[np.float64]]:
        """Minimum Rayleigh quotient on ``{f : C.T A f = 0}`` (see :func:`min_rayleigh_quotient`)."""
        W, A = self.stiffness, self.mass
        Q = _constraint_basis(orthogonal_to, A)
        n = W.shape[0]
        if n - Q.shape[1] < _LANCZOS_ROOM:
            value, f = _min_dense(W, A, Q)
        else:
            value, f = self._min_sparse(Q)
        return _result(value, f, A, return_vector)

    def _min_sparse(self, Q: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
        W, A, lu = self.stiffness, self.mass, self._lu
        n = W.shape[0]
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
        v0 = start_vector(n)
        v0 -= Q @ (AQ.T @ v0)  # the start vector must lie in the subspace
        values, vectors = spla.eigsh(
            W, k=1, M=A, sigma=-self.shift, OPinv=op, which="LM", v0=v0, tol=0.0, ncv=min(n - 1, 20)
        )
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
@validated(method=_METHOD)
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
        extra solves (no dense n x n matrix; see :class:`ConstrainedRayleigh`, which reuses the
        factorisation across many subspaces). ``"auto"`` follows :func:`~lbo_notebooks.spectral._engine.policy.use_dense`.
    return_vector : bool
        Also return the minimiser, A-normalised, sign fixed by :func:`~lbo_notebooks.spectral.fix_signs`.

    Returns
    -------
    float, or (float, ndarray (n,)).

    Examples
    --------
    >>> import numpy as np
    >>> M = np.diag([1.0, 2.0, 4.0])
    >>> min_rayleigh_quotient(M, np.eye(3), orthogonal_to=[1.0, 0.0, 0.0])  # lam_1 (from 0) for this plane
    2.0
    >>> round(min_rayleigh_quotient(M, np.eye(3), orthogonal_to=[1.0, 1.0, 0.0]), 6)  # any other: less
    1.5
    """
    W, A = _operators(stiffness, mass)
    if use_dense(W.shape[0], method):
        value, f = _min_dense(W, A, _constraint_basis(orthogonal_to, A))
        return _result(value, f, A, return_vector)
    return ConstrainedRayleigh(W, A).minimum(orthogonal_to, return_vector=return_vector)


def _pool_spans(k: int, pool: NDArray[np.float64] | None, **_: object) -> bool:
    return pool is None or pool.shape[1] >= k


@validated(n_vertices=Integer(1), k=Integer(0, lambda n_vertices, **_: n_vertices - 1), pool=(
    Array(2, rows=lambda n_vertices, **_: n_vertices, none=True,
          message="{name} must be a finite array of shape ({rows}, m), got {shape}."),
    Relation(_pool_spans, lambda k, pool, **_: (
        f"pool has {pool.shape[1]} columns; it needs at least k = {k} to span a codimension-{k} constraint set.")),
))
def random_subspace(
    n_vertices: int, k: int, *, seed: int = 0, pool: ArrayLike | None = None
) -> NDArray[np.float64]:
    """Constraints of a random codimension-``k`` subspace (for :func:`min_rayleigh_quotient`).

    Parameters
    ----------
    n_vertices : int
    k : int
        Codimension (number of constraint vectors), ``0 <= k < n_vertices``.
    seed : int
        Seed for ``numpy.random.default_rng``.
    pool : array (n_vertices, m), optional
        Draw the constraints as random Gaussian combinations of the pool's columns (for example
        the first 2n eigenvectors, which gives subspaces close to the optimal one). Default:
        i.i.d. Gaussian vectors in all of R^n_vertices.

    Returns
    -------
    ndarray (n_vertices, k): the subspace is ``{f : C.T @ A @ f = 0}``.

    Examples
    --------
    >>> random_subspace(100, 5, seed=1).shape
    (100, 5)
    """
    rng = np.random.default_rng(seed)
    if pool is None:
        return rng.normal(size=(n_vertices, k))
    return pool @ rng.normal(size=(pool.shape[1], k))


@validated(
    spectrum=Satisfies(lambda s: isinstance(s, Spectrum), message="spectrum must be a Spectrum, got {type}."),
    k=Integer(0, lambda spectrum, **_: spectrum.k - 1,
              what=lambda spectrum, **_: f"an integer with 0 <= k < spectrum.k = {spectrum.k} (lam[k] must be known)"),
)
def optimal_subspace(spectrum: Spectrum, k: int) -> NDArray[np.float64]:
    """Constraints of the optimal codimension-k subspace: the first k eigenvectors.

    Its minimum Rayleigh quotient is ``lam[k]``, attained at ``phi_k`` (Courant–Fischer).

    Examples
    --------
    >>> from lbo_notebooks import eigenbasis, shapes
    >>> s = eigenbasis(shapes.icosphere(2), 12)
    >>> C = optimal_subspace(s, 4)
    >>> bool(abs(min_rayleigh_quotient(s.stiffness, s.mass, C) - s.values[4]) < 1e-9 * s.values[4])
    True
    """
    return np.array(spectrum.vectors[:, :k])


def complement_ratio(basis: ArrayLike, stiffness: sp.spmatrix, mass: sp.spmatrix) -> float:
    """The **trap**: ``sup over r A-orthogonal to V of ||r||_A^2 / (r @ W @ r)``.

    This uses ``W`` itself on the complement of V instead of the Schur complement, i.e. it only
    looks at functions with no component in V. It is ``1 / min_rayleigh_quotient(W, A,
    orthogonal_to=basis)`` (Courant–Fischer's quantity), a *lower* bound on
    :func:`~lbo_notebooks.analyses.worst_case_ratio`. It is equal to it when ``W`` maps V into
    ``A V`` (e.g. V spanned by eigenvectors) -- a sufficient condition, not a necessary one: the
    tilted span of ``phi_0..phi_8, phi_9 + 0.5 phi_15`` on a dog is exact too (docs/maths.md,
    "Optimality"). Kept to show the difference; do not use it as the worst-case constant.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, eigenbasis, worst_case_ratio
    >>> s = eigenbasis(shapes.bumpy_sphere(2), 12)
    >>> B = s.vectors[:, :10] + 0.05 * np.random.default_rng(0).normal(size=(162, 10))
    >>> bool(complement_ratio(B, s.stiffness, s.mass) < worst_case_ratio(B, s.stiffness, s.mass))
    True
    """
    return 1.0 / min_rayleigh_quotient(stiffness, mass, orthogonal_to=basis)
