"""The exact sparse path of regularized PCA: eigenpairs of the pencil ``(U U.T - mu W, A)``.

``U = A X`` holds the c data columns, so the pencil is a sparse matrix plus a rank-c term. Its
spectrum is badly spread (docstring of :mod:`lbo_notebooks.analyses._rpca`): the few "data" eigenvalues above
the split point ``tau = mu t0`` are found by :func:`data_eigenpairs` (rational Krylov and inverse
iteration, one sparse factorisation per data eigenvalue, Woodbury for the rank-c term), the others
by :func:`complement_lanczos` (shift-invert Lanczos at ``tau`` on the A-orthogonal complement of
the data eigenvectors, with the one factor of ``W + t0 A``), and :func:`rayleigh_ritz` combines
subspaces. :class:`~lbo_notebooks.analyses.RegularizedPCA` drives them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..spectral._inner_product import a_orthonormalize
from ..spectral._solvers import SymmetricFactor, start_vector, symmetric_lu

__all__ = ["DATA_TOL", "MAX_ROUNDS", "complement_lanczos", "data_eigenpairs", "rayleigh_ritz"]

#: Residual (relative backward error) at which a data eigenpair counts as converged.
DATA_TOL = 1e-12
#: Rounds of inverse iteration at most for the data eigenpairs.
MAX_ROUNDS = 8


def rayleigh_ritz(
    basis: NDArray[np.float64], U: NDArray[np.float64], W: sp.csr_matrix, mu: float, k: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Top ``k`` Ritz pairs of ``(U U.T - mu W, A)`` on the A-orthonormal columns of ``basis``."""
    projected_data = basis.T @ U
    projected = projected_data @ projected_data.T - mu * (basis.T @ (W @ basis))
    values, vectors = np.linalg.eigh((projected + projected.T) / 2)
    order = np.argsort(values)[::-1][:k]
    return values[order], basis @ vectors[:, order]


@dataclass(frozen=True)
class _ShiftedFactor:
    """A sparse LU of ``mu W + shift A`` with the Woodbury pieces for ``- U U.T``."""

    shift: float
    factor: SymmetricFactor
    solved: NDArray[np.float64]  # factor^-1 U
    capacitance: NDArray[np.float64]  # I - U.T factor^-1 U


def data_eigenpairs(
    W: sp.csr_matrix, A: sp.csr_matrix, U: NDArray[np.float64], X: NDArray[np.float64], k: int, mu: float, tau: float, Y0: NDArray[np.float64]
) -> NDArray[np.float64]:
    """The top ``k`` eigenvectors (all with eigenvalue > tau) by rational Krylov + inverse iteration."""
    c = U.shape[1]
    subspace = a_orthonormalize(np.hstack([X, Y0]), A, drop_dependent=True)
    theta, ritz = rayleigh_ritz(subspace, U, W, mu, k)
    # One factorisation per data eigenvalue, at its current Ritz estimate (Ritz values are lower
    # bounds; below tau we keep the tau factor, whose block Y0 is already in the subspace).
    factors: list[_ShiftedFactor] = []
    for shift in theta:
        if shift <= tau * (1 + 1e-8):
            continue
        factor = symmetric_lu(mu * W + shift * A)
        solved = factor.solve(np.array(U))
        factors.append(_ShiftedFactor(float(shift), factor, solved, np.eye(c) - U.T @ solved))
    if factors:
        subspace = a_orthonormalize(np.hstack([f.solved for f in factors]), A, prepend=subspace, drop_dependent=True)
        theta, ritz = rayleigh_ritz(subspace, U, W, mu, k)

    def shifted_solve(j: int, b: NDArray[np.float64]) -> NDArray[np.float64]:
        # (mu W + s A - U U.T)^-1 b by Woodbury, with the factor whose shift is nearest theta[j].
        near = min(factors, key=lambda f: abs(np.log(f.shift / max(theta[j], tau))))
        z = near.factor.solve(b)
        try:
            return z + near.solved @ np.linalg.solve(near.capacitance, U.T @ z)
        except np.linalg.LinAlgError:  # shift is an exact eigenvalue: solved already holds the vector
            return z

    scale = abs(theta[0]) + mu * abs(W).sum(axis=1).max() + 1.0
    for _ in range(MAX_ROUNDS):
        residual = U @ (U.T @ ritz) - mu * (W @ ritz) - (A @ ritz) * theta
        backward_error = np.linalg.norm(residual, axis=0) / (scale * np.sqrt(np.einsum("ij,ij->j", ritz, A @ ritz)) * max(1.0, np.abs(A).max()))
        if np.all(backward_error < DATA_TOL) or not factors:
            break
        corrections = np.column_stack([shifted_solve(j, A @ ritz[:, j]) for j in range(k)])
        subspace = a_orthonormalize(corrections, A, prepend=subspace, drop_dependent=True)
        theta, ritz = rayleigh_ritz(subspace, U, W, mu, k)
    return ritz

def complement_lanczos(
    W: sp.csr_matrix,
    A: sp.csr_matrix,
    U: NDArray[np.float64],
    base: SymmetricFactor,
    t0: float,
    count: int,
    deflate: NDArray[np.float64],
    *,
    mu: float | None,
    Y0: NDArray[np.float64] | None = None,
) -> NDArray[np.float64]:
    """Top ``count`` eigenvectors of the pencil on the A-orthogonal complement of ``deflate``.

    ``mu=None`` means the mu -> 0 limit: the smoothest functions (smallest ``W`` eigenvalues)
    A-orthogonal to ``deflate``. Otherwise the pencil is ``(U U.T - mu W, A)`` and shift-invert
    Lanczos runs at ``tau = mu t0``, using ``base``, the mu-independent factor of ``W + t0 A``.
    """
    n = W.shape[0]
    F0 = base
    D = deflate
    AD = np.asarray(A @ D)

    def project(x: NDArray[np.float64]) -> NDArray[np.float64]:  # A-orthogonal projector
        return x - D @ (D.T @ (A @ x)) if D.shape[1] else x

    def project_t(y: NDArray[np.float64]) -> NDArray[np.float64]:  # its transpose
        return y - AD @ (D.T @ y) if D.shape[1] else y

    if mu is None:
        # Constrained problem: smallest W eigenpairs on {p : D.T A p = 0}. Span D is not
        # W-invariant, so the shift-inverse of the *compressed* pencil is needed: the saddle
        # point solve [[W + t0 A, A D], [D.T A, 0]] (Schur complement on the few columns of D).
        sigma = -t0
        KD = F0.solve(np.array(AD)) if D.shape[1] else np.zeros((n, 0))
        schur = AD.T @ KD

        def inner(y: NDArray[np.float64]) -> NDArray[np.float64]:
            z = F0.solve(y)
            return z - KD @ np.linalg.solve(schur, AD.T @ z) if D.shape[1] else z

        L = spla.aslinearoperator(W)
    else:
        assert Y0 is not None
        sigma = mu * t0
        C = np.eye(U.shape[1]) - U.T @ Y0

        def inner(y: NDArray[np.float64]) -> NDArray[np.float64]:
            # (U U.T - mu W - tau A)^-1 y = -(M - U U.T)^-1 y, M = mu (W + t0 A); Woodbury.
            z = F0.solve(y) / mu
            return -(z + Y0 @ np.linalg.solve(C, U.T @ z))

        L = spla.LinearOperator((n, n), matvec=lambda x: U @ (U.T @ x) - mu * (W @ x), dtype=np.float64)

    def opinv(y: NDArray[np.float64]) -> NDArray[np.float64]:
        y = np.asarray(y, dtype=np.float64).reshape(n)
        return project(inner(project_t(y)))

    op = spla.LinearOperator((n, n), matvec=opinv, dtype=np.float64)
    v0 = project(start_vector(n))
    values, vectors = spla.eigsh(L, k=count, M=A, sigma=sigma, which="LM", OPinv=op, v0=v0)
    order = np.argsort(values)[::-1] if mu is not None else np.argsort(values)
    return a_orthonormalize(project(vectors[:, order]), A, refine=True)
