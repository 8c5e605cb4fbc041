"""Regularized PCA: principal components married to the Dirichlet energy (paper, section 6).

Given training functions ``X`` (n x c, e.g. the x, y, z coordinates of two poses that share a
triangulation), regularized PCA looks for an A-orthonormal basis ``P`` (n x k) that represents the
data well *and* is smooth:

    minimise  sum_i ||P P.T A x_i - x_i||_A^2 + mu * sum_j P_j.T W P_j   subject to  P.T A P = I.

The objective equals ``const - trace(P.T (A X X.T A - mu W) P)``, so the minimiser is the set of
``k`` *top* generalized eigenvectors of ``(A X X.T A - mu W) p = sigma A p`` (docs/maths.md, "Regularized PCA").
``mu -> infinity`` gives the first ``k`` Laplace–Beltrami eigenfunctions; ``mu -> 0`` gives the
PCA directions first, and then (the data have rank at most c) the smoothest functions A-orthogonal
to the data.

The closed form is computed exactly without ever forming an n x n matrix. The difficulty is a badly
spread spectrum: the few data eigenvalues can be 1e6 times larger than the smoothness ones, so a
single shift-invert Lanczos run cannot resolve both ends. :class:`RegularizedPCA` therefore

1. factorises ``W + t0 A`` once (``t0`` a small area-scaled shift) and, with the Woodbury identity,
   counts the eigenvalues above the split point ``tau = mu t0`` exactly from a c x c matrix;
2. finds those few "data" eigenpairs by a rational Krylov / inverse-iteration Rayleigh–Ritz,
   with one shift (one sparse factorisation) per data eigenvalue;
3. finds the remaining ``k - n_data`` eigenpairs by shift-invert Lanczos at ``tau`` on the
   A-orthogonal complement of the data eigenvectors (Woodbury solves with the step-1 factor);
4. finishes with one Rayleigh–Ritz over both sets.

Cost: one sparse factorisation of ``W + t0 A``, one per data eigenvalue above the split (at most
c, the number of data columns), and a Lanczos run as long as :func:`~lbo_notebooks.eigenbasis`'s;
memory O(n (k + c)). In CPU time a solve costs a little more than the eigenbasis alone.

Threads: the sparse path's time goes to sparse solves and Lanczos' level-2 products. On an idle
machine BLAS threads make the latter somewhat faster, but OpenBLAS threads spin while they wait
for a core: beside one busy program the same call is slower than on one thread, and on a loaded
machine several times slower. So on meshes of
10,000 vertices or more the solver looks whether the machine's other cores are idle
(:func:`~lbo_notebooks.spectral._solvers.blas_threads_for`, 50 ms) and otherwise, as always on smaller
meshes, runs BLAS on one thread (a count the user set is kept).

The step-1 factor does not depend on ``mu`` (``mu W + tau A = mu (W + t0 A)``), so a sweep over
``mu`` reuses it: build one :class:`RegularizedPCA` and call :meth:`RegularizedPCA.solve` per weight.

A raw ``mu`` depends on the units of the data and of the mesh. The dimensionless weight
``beta in [0, 1]`` balances the two terms, each normalised by its top eigenvalue::

    maximise  (1 - beta) trace(P.T B P) / s_B  -  beta trace(P.T W P) / lam_ref,

with ``s_B`` the largest data eigenvalue (top eigenvalue of ``X.T A X``) and ``lam_ref = 4 pi k /
area`` Weyl's estimate of the k-th Laplace–Beltrami eigenvalue, i.e.
``mu = beta / (1 - beta) * s_B / lam_ref`` (:func:`mu_from_beta`). ``beta = 0`` is the ``mu -> 0``
limit (the PCA directions, then the smoothest functions A-orthogonal to the data), ``beta = 1`` the
eigenbasis, and a given ``beta`` gives the same basis whatever the shape's size and units (the best
``beta`` for a task still depends on the shape and the data).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal, Sequence

import numpy as np
import scipy.linalg
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from .._support.progress import LARGE_MESH, PROGRESS, progress_bar
from .._support.validation import Array, Integer, Number, Options, Relation, Satisfies, validated
from ..spectral._inner_product import (
    a_orthonormalize,
    check_operators,
    fix_signs,
)
from ._rpca_sparse import complement_lanczos, data_eigenpairs, rayleigh_ritz
from ..spectral._solvers import SymmetricFactor, blas_threads_for, default_shift, symmetric_lu, use_dense
from ..spectral._spectrum import eigenbasis

__all__ = [
    "RegularizedPCA",
    "RPCAResult",
    "regularized_pca",
    "mu_from_beta",
    "beta_from_mu",
]

Method = Literal["auto", "dense", "sparse"]

# --- input checks ------------------------------------------------------------------------------
def _rows(matrix: Any) -> int | None:
    """The number of rows of an operator, for the table of ``data``; ``None`` (any) when it has no shape.

    The operators themselves are checked in the body (:func:`~lbo_notebooks.spectral.check_operators`).
    """
    try:
        shape = np.shape(matrix)
    except ValueError:  # a ragged sequence
        return None
    return shape[0] if len(shape) else None


def _data(operator: str) -> Array:
    """``data``: one row per vertex of ``operator`` (``"stiffness"`` or ``"mass"``), one column per function."""
    return Array(
        rows=lambda **arguments: _rows(arguments[operator]), column=True, nonempty=True,
        message="{name} must have shape ({rows}, c): one row per vertex of the operators and one column per "
                "training function (e.g. np.hstack of (n, 3) vertex arrays); got {shape}.",
        hint="regularized PCA of such data is meaningless. Clean it first",
    )


def _basis_size(n: Any) -> tuple[Integer, Integer]:
    """``k``: an integer in 1..``n(**arguments)`` (the number of vertices)."""
    return (
        Integer(what="an integer number of basis functions"),
        Integer(1, n, message="k must be between 1 and the number of vertices ({high}), got {value}."),
    )


def _mu(none: bool = False) -> tuple[Satisfies, Satisfies]:
    """``mu``: a number >= 0, ``inf`` included (the eigenbasis end), which :class:`Number` does not allow."""
    return (
        Satisfies(lambda mu: not isinstance(mu, bool) and np.isscalar(mu) and not np.isnan(mu), "a number >= 0",
                  none=none),
        Satisfies(lambda mu: mu >= 0, convert=float, none=none,
                  message="mu must be >= 0, got {value!r}: a negative weight would reward rough functions. "
                          "Use mu = 0 for the PCA end or a beta in [0, 1] (see mu_from_beta)."),
    )


def _beta(none: bool = False) -> Number:
    return Number(0, 1, none=none, what="a number in [0, 1] (0: the PCA end, 1: the Laplace–Beltrami eigenbasis)")


_K = _basis_size(lambda self, **_: self.n_vertices)
_ONE_WEIGHT = Relation(lambda mu, beta, **_: (mu is None) != (beta is None),
                       "give exactly one of mu (raw weight) or beta (dimensionless weight in [0, 1]).")
_ONE_SERIES = Relation(lambda betas, mus, **_: (betas is None) != (mus is None), "give exactly one of betas or mus.")
_METHOD = Options("auto", "dense", "sparse", message="method must be 'auto', 'dense' or 'sparse', got {value!r}.")


def _mu_from_beta(beta: float, s_B: float, lam_ref: float) -> float:
    if beta == 1.0:
        return float("inf")
    if s_B <= 0.0:
        raise ValueError("the data are identically zero (after centring), so beta has no meaning; pass mu instead.")
    return beta / (1.0 - beta) * s_B / lam_ref


def _area_weights(A: sp.csr_matrix) -> NDArray[np.float64]:
    return np.asarray(A.sum(axis=1)).ravel()


def _centred(X: NDArray[np.float64], A: sp.csr_matrix) -> NDArray[np.float64]:
    a = _area_weights(A)
    return X - (a @ X) / a.sum()


# --- results -----------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class RPCAResult:
    """A regularized PCA basis and its generalized eigenvalues.

    Attributes
    ----------
    basis : ndarray, shape (n, k)
        A-orthonormal columns, ordered by decreasing ``values``; signs fixed by
        :func:`~lbo_notebooks.spectral.fix_signs`.
    values : ndarray, shape (k,)
        Generalized eigenvalues ``sigma`` of ``(A X X.T A - mu W) p = sigma A p``, descending.
        At ``mu = 0`` the directions beyond the rank of the data all have ``sigma = 0`` and are
        ordered by smoothness (the ``mu -> 0`` limit). At ``mu = inf`` every direction with
        positive Dirichlet energy has ``sigma = -inf``.
    mu : float
        The raw weight used (``inf`` for ``beta = 1``).
    n_data : int
        Number of eigenvalues above the split point: the "data" directions (at most c).
    """

    basis: NDArray[np.float64]
    values: NDArray[np.float64]
    mu: float
    n_data: int

    def __post_init__(self) -> None:
        for name in ("basis", "values"):  # read-only views: a caller's own arrays stay writable
            view = np.asarray(getattr(self, name)).view()
            view.setflags(write=False)
            object.__setattr__(self, name, view)

    @property
    def k(self) -> int:
        """Number of basis functions."""
        return int(self.basis.shape[1])

    def __repr__(self) -> str:
        return f"RPCAResult(k={self.k}, mu={self.mu:.4g}, n_data={self.n_data})"


# --- the solver ----------------------------------------------------------------------------------
class RegularizedPCA:
    """Regularized PCA of fixed training data on a fixed mesh, solved for any weight ``mu``.

    The expensive, weight-independent work (operator checks, the factorisation of ``W + t0 A``,
    the data products) is done once, so sweeping ``mu`` or ``beta`` is cheap.

    Parameters
    ----------
    data : array_like, shape (n, c) or (n,)
        Training functions, one column each (e.g. ``np.hstack([pose1, pose2])``). Copied.
    stiffness, mass : scipy.sparse matrix, shape (n, n)
        Cotangent stiffness ``W`` and mass ``A`` (:mod:`lbo_notebooks.operators._cotangent`).
    center : bool
        Subtract the A-weighted mean of every column first. With centred data the constant
        function is always in the basis (for ``mu > 0``), which is what shape reconstruction wants.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> mesh = shapes.bumpy_sphere(3)
    >>> W, A = stiffness_matrix(mesh), mass_matrix(mesh)
    >>> X = np.hstack([mesh.vertices, mesh.vertices ** 2])
    >>> solver = RegularizedPCA(X, W, A, center=True)
    >>> result = solver.solve(20, beta=0.5)
    >>> bool(np.allclose(result.basis.T @ A @ result.basis, np.eye(20), atol=1e-10))
    True
    """

    @validated(data=_data("stiffness"))
    def __init__(self, data: ArrayLike, stiffness: sp.spmatrix, mass: sp.spmatrix, *, center: bool = False) -> None:
        W, A = check_operators(stiffness, mass)
        n = W.shape[0]
        X = np.array(data, copy=True)  # frozen below: never the caller's array
        if center:
            X = _centred(X, A)
        X.setflags(write=False)
        self.stiffness, self.mass, self.data, self.center = W, A, X, bool(center)
        self.n_vertices = n
        self.area = float(_area_weights(A).sum())
        U = np.asarray(A @ X)
        U.setflags(write=False)
        self._U = U
        gram = X.T @ U
        self.data_values = np.sort(np.linalg.eigvalsh((gram + gram.T) / 2))[::-1]
        self.data_values.setflags(write=False)
        # The split-point shift: small against the smoothness eigenvalues at every scale.
        self._t0 = default_shift(A)
        self._base_factor: SymmetricFactor | None = None
        self._base_solved: NDArray[np.float64] | None = None

    def __repr__(self) -> str:
        return f"RegularizedPCA(n_vertices={self.n_vertices}, n_data={self.data.shape[1]}, center={self.center})"

    # ---- weights ----
    @property
    def top_data_value(self) -> float:
        """``s_B``: the largest eigenvalue of ``(A X X.T A, A)``, i.e. of ``X.T A X``."""
        return float(max(self.data_values[0], 0.0))

    @validated(k=_K)
    def reference_eigenvalue(self, k: int) -> float:
        """Weyl's estimate ``4 pi k / area`` of the k-th Laplace–Beltrami eigenvalue."""
        return 4.0 * np.pi * k / self.area

    @validated(k=_K, beta=_beta())
    def mu_from_beta(self, beta: float, k: int) -> float:
        """Raw weight ``mu = beta / (1 - beta) * s_B / lam_ref`` for a dimensionless ``beta``."""
        return _mu_from_beta(beta, self.top_data_value, self.reference_eigenvalue(k))

    @validated(mu=_mu())
    def beta_from_mu(self, mu: float, k: int) -> float:
        """Inverse of :meth:`mu_from_beta`."""
        if np.isinf(mu):
            return 1.0
        if self.top_data_value <= 0.0:
            raise ValueError("the data are identically zero (after centring), so beta has no meaning.")
        r = mu * self.reference_eigenvalue(k) / self.top_data_value
        return r / (1.0 + r)

    # ---- solving ----
    @validated(k=_K, mu=_mu(none=True), beta=(_beta(none=True), _ONE_WEIGHT), method=_METHOD)
    def solve(self, k: int, mu: float | None = None, *, beta: float | None = None, method: Method = "auto") -> RPCAResult:
        """The regularized PCA basis of size ``k`` for weight ``mu`` (or dimensionless ``beta``).

        Parameters
        ----------
        k : int
            Number of basis functions, ``1 <= k <= n``.
        mu : float, optional
            Raw weight ``>= 0`` (``inf`` allowed: the eigenbasis). Give exactly one of mu, beta.
        beta : float in [0, 1], optional
            Dimensionless weight (:meth:`mu_from_beta`).
        method : {"auto", "dense", "sparse"}
            ``"dense"`` uses ``scipy.linalg.eigh`` on n x n matrices (small meshes only);
            ``"sparse"`` the exact factor-and-Lanczos scheme of the module docstring;
            ``"auto"`` follows :func:`~lbo_notebooks.spectral._engine.policy.use_dense`.

        Returns
        -------
        RPCAResult
        """
        mu = self.mu_from_beta(beta, k) if beta is not None else mu
        n, c = self.data.shape
        method = "dense" if use_dense(n, method) else "sparse"
        if method == "sparse" and 2 * k + c + 2 > n:
            method = "dense"  # Lanczos needs room: k close to n is a small-mesh problem anyway
        if np.isinf(mu):
            return self._solve_infinite(k)  # the eigensolver limits its BLAS threads itself
        if method == "dense":  # small meshes: LAPACK on an n x n matrix, where BLAS threads pay
            return self._solve_pca_limit(k, method) if mu == 0.0 else self._solve_dense(k, mu)
        # The sparse paths: BLAS threads only on a large mesh and an otherwise idle machine
        # (module docstring, "Threads").
        with blas_threads_for(large=self.n_vertices >= LARGE_MESH):
            return self._solve_pca_limit(k, method) if mu == 0.0 else self._solve_sparse(k, mu)

    # mu = inf: the Laplace–Beltrami eigenbasis
    def _solve_infinite(self, k: int) -> RPCAResult:
        spectrum = eigenbasis((self.stiffness, self.mass), k, progress=False)
        P = np.array(spectrum.vectors)
        kernel = spectrum.values <= 1e-9 * max(float(spectrum.values[-1]), 1e-300)
        PU = P.T @ self._U
        data_term = np.einsum("ij,ij->i", PU, PU)
        values = np.where(kernel, data_term, -np.inf)
        return RPCAResult(basis=P, values=values, mu=float("inf"), n_data=0)

    # mu = 0: PCA first, then the smoothest functions A-orthogonal to the data (the mu -> 0 limit)
    def _solve_pca_limit(self, k: int, method: str) -> RPCAResult:
        W, A, U = self.stiffness, self.mass, self._U
        Q = a_orthonormalize(self.data, A, drop_dependent=True)  # basis of span X (rank r)
        QU = Q.T @ U
        w, E = np.linalg.eigh(QU @ QU.T)
        order = np.argsort(w)[::-1]
        w, E = w[order], E[:, order]
        positive = w > 1e-12 * max(float(w[0]) if w.size else 0.0, 1e-300)
        r = int(positive.sum())
        pca = Q @ E[:, :r]
        if k <= r:
            basis, values = pca[:, :k], w[:k]
        else:
            Q_all = Q  # deflate the whole span of the data, not only its top directions
            if method == "dense":
                Z = scipy.linalg.null_space((A @ Q_all).T)
                Zw = Z.T @ (W @ Z)
                Za = Z.T @ (A @ Z)
                _, Y = scipy.linalg.eigh((Zw + Zw.T) / 2, (Za + Za.T) / 2, subset_by_index=[0, k - r - 1])
                rest = Z @ Y  # already A-orthonormal: Y.T (Z.T A Z) Y = I
            else:
                rest = complement_lanczos(W, A, U, self._base()[0], self._t0, k - r, Q_all, mu=None)
            basis = np.hstack([pca, rest])
            values = np.concatenate([w[:r], np.zeros(k - r)])
        return RPCAResult(basis=fix_signs(basis, A), values=np.asarray(values, dtype=np.float64), mu=0.0, n_data=min(r, k))

    def _solve_dense(self, k: int, mu: float) -> RPCAResult:
        n = self.n_vertices
        U = self._U
        L = U @ U.T - mu * self.stiffness.toarray()
        Ad = self.mass.toarray()
        values, vectors = scipy.linalg.eigh((L + L.T) / 2, (Ad + Ad.T) / 2, subset_by_index=[n - k, n - 1])
        values, vectors = values[::-1], vectors[:, ::-1]
        tau = mu * self._t0
        return RPCAResult(
            basis=fix_signs(vectors, self.mass), values=np.ascontiguousarray(values), mu=mu, n_data=int((values > tau).sum())
        )

    # ---- the sparse exact path ----
    def _base(self) -> tuple[SymmetricFactor, NDArray[np.float64]]:
        """Factor of ``W + t0 A`` and ``(W + t0 A)^-1 A X``: independent of mu, computed once."""
        if self._base_factor is None:
            self._base_factor = symmetric_lu(self.stiffness + self._t0 * self.mass)
            self._base_solved = self._base_factor.solve(np.array(self._U))
        assert self._base_solved is not None
        return self._base_factor, self._base_solved

    def _solve_sparse(self, k: int, mu: float) -> RPCAResult:
        W, A, U = self.stiffness, self.mass, self._U
        tau = mu * self._t0
        F0, Z0 = self._base()
        Y0 = Z0 / mu  # (mu W + tau A)^-1 U
        H = U.T @ Y0
        # Sylvester's law of inertia on [[-M, U], [U.T, -I]]: the number of eigenvalues of the
        # pencil above tau equals the number of eigenvalues of U.T M^-1 U above 1.
        n_above = int((np.linalg.eigvalsh((H + H.T) / 2) > 1.0).sum())
        n_data = min(n_above, k)
        data_vectors = np.zeros((self.n_vertices, 0))
        rest = np.zeros((self.n_vertices, 0))
        if n_data:
            data_vectors = data_eigenpairs(W, A, U, self.data, n_data, mu, tau, Y0)
        if k > n_data:
            rest = complement_lanczos(W, A, U, F0, self._t0, k - n_data, data_vectors, mu=mu, Y0=Y0)
        subspace = a_orthonormalize(np.hstack([data_vectors, rest]), A, drop_dependent=True)
        values, ritz = rayleigh_ritz(subspace, U, W, mu, k)
        if ritz.shape[1] < k:  # pragma: no cover - would mean a lost direction
            raise RuntimeError("regularized PCA lost a direction; try method='dense' and report this.")
        return RPCAResult(basis=fix_signs(ritz, A), values=values, mu=mu, n_data=n_data)

    @validated(mus=_ONE_SERIES, progress=PROGRESS)
    def sweep(
        self,
        k: int,
        *,
        betas: Sequence[float] | None = None,
        mus: Sequence[float] | None = None,
        progress: bool | None = None,
    ) -> list[RPCAResult]:
        """Solve for every weight in ``betas`` (or ``mus``), reusing the factorisation.

        ``progress`` shows a bar over the weights (:mod:`lbo_notebooks._support.progress`): ``True``
        always, ``False`` never, ``None`` (default) only for meshes of 10,000 vertices or more and
        only in a notebook or a terminal (never in a log file or under pytest).
        """
        weights = [("beta", b) for b in betas] if betas is not None else [("mu", m) for m in mus]  # type: ignore[union-attr]
        results = []
        with progress_bar(len(weights), "regularized PCA", progress, long=self.n_vertices >= LARGE_MESH) as bar:
            for name, value in weights:
                results.append(self.solve(k, beta=value) if name == "beta" else self.solve(k, value))
                bar.update()
        return results


# --- functional interface ----------------------------------------------------------------------
def regularized_pca(
    data: ArrayLike,
    stiffness: sp.spmatrix,
    mass: sp.spmatrix,
    k: int,
    mu: float | None = None,
    *,
    beta: float | None = None,
    center: bool = False,
    return_values: bool = False,
    method: Method = "auto",
) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A-orthonormal basis of the ``k`` top generalized eigenvectors of ``(A X X.T A - mu W, A)``.

    This is the exact minimiser of ``sum_i ||P P.T A x_i - x_i||_A^2 + mu sum_j P_j.T W P_j``
    over ``P.T A P = I``. No n x n matrix is formed unless ``method="dense"``.

    Parameters
    ----------
    data : array_like, shape (n, c)
        Training functions ``X``, one per column.
    stiffness, mass : scipy.sparse matrix
        ``W`` and ``A``.
    k : int
        Number of basis functions, ``1 <= k <= n``.
    mu : float, optional
        Raw weight, ``>= 0``; ``0`` is PCA (then the smoothest functions A-orthogonal to the data),
        ``inf`` the Laplace–Beltrami eigenbasis.
    beta : float in [0, 1], optional
        Dimensionless weight instead of ``mu`` (see :func:`mu_from_beta`).
    center : bool
        Remove the A-weighted mean of each data column first.
    return_values : bool
        Also return the eigenvalues ``sigma`` (descending).
    method : {"auto", "dense", "sparse"}

    Returns
    -------
    basis : ndarray, shape (n, k)
    values : ndarray, shape (k,), only if ``return_values``

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> mesh = shapes.bumpy_sphere(3)
    >>> W, A = stiffness_matrix(mesh), mass_matrix(mesh)
    >>> P = regularized_pca(mesh.vertices, W, A, 10, mu=1e-3, center=True)
    >>> P.shape
    (642, 10)
    """
    result = RegularizedPCA(data, stiffness, mass, center=center).solve(k, mu, beta=beta, method=method)
    basis = np.array(result.basis)
    return (basis, np.array(result.values)) if return_values else basis


@validated(k=_basis_size(lambda mass, **_: np.shape(mass)[0]), beta=_beta(), data=_data("mass"))
def mu_from_beta(beta: float, data: ArrayLike, mass: sp.spmatrix, k: int, *, center: bool = False) -> float:
    """Raw weight ``mu`` for a dimensionless ``beta`` in [0, 1].

    ``mu = beta / (1 - beta) * s_B / lam_ref``: ``s_B`` is the largest eigenvalue of ``X.T A X``
    (the top data eigenvalue) and ``lam_ref = 4 pi k / area`` is Weyl's estimate of the k-th
    Laplace–Beltrami eigenvalue. Both scale with the shape, so ``beta`` does not. ``beta = 1``
    gives ``inf``.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, mass_matrix
    >>> mesh = shapes.icosphere(2)
    >>> A = mass_matrix(mesh)
    >>> mu1 = mu_from_beta(0.5, mesh.vertices, A, 10)
    >>> mu2 = mu_from_beta(0.5, 2 * mesh.vertices, 4 * A, 10)  # the same sphere, twice the size
    >>> round(mu2 / mu1, 6)  # s_B grows 16x, lam_ref shrinks 4x
    64.0
    """
    A = sp.csr_matrix(mass, dtype=np.float64)
    X = data
    if center:
        X = _centred(X, A)
    gram = X.T @ (A @ X)
    s_B = float(np.linalg.eigvalsh((gram + gram.T) / 2)[-1])
    return _mu_from_beta(beta, s_B, 4.0 * np.pi * k / float(A.sum()))


@validated(mu=_mu())
def beta_from_mu(mu: float, data: ArrayLike, mass: sp.spmatrix, k: int, *, center: bool = False) -> float:
    """Inverse of :func:`mu_from_beta`."""
    if np.isinf(mu):
        return 1.0
    unit = mu_from_beta(0.5, data, mass, k, center=center)  # = s_B / lam_ref
    return (mu / unit) / (1.0 + mu / unit)


# --- evaluation protocol ----------------------------------------------------------------------
# reconstruct, reconstruction_error and principal_angles work for any A-orthonormal basis: they
# live in lbo_notebooks.spectral._inner_product and are re-exported here.
