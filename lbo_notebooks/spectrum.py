"""Eigenbasis of the Laplace–Beltrami operator and the A-inner-product algebra around it.

The eigenvectors of ``W phi = lam A phi`` are orthonormal in the *A* inner product
``<f, g>_A = f @ A @ g``, not the Euclidean one. :class:`Spectrum` makes the right thing the easy
thing: ``project`` returns ``Phi.T @ (A @ f)``, ``reconstruct`` and ``error`` use the same inner
product.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Union

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from .mesh import Mesh
from .operators import MASS_KINDS, MassKind, mass_matrix, stiffness_matrix

__all__ = ["Spectrum", "eigenbasis", "fix_signs", "check_operators"]

Operators = tuple[sp.spmatrix, sp.spmatrix]

# Below this many vertices a dense generalized eigensolver is faster and exact.
DENSE_LIMIT = 600


@dataclass(frozen=True, eq=False)
class Spectrum:
    """The first ``k`` eigenpairs of ``W phi = lam A phi``.

    Attributes
    ----------
    values : ndarray, shape (k,)
        Eigenvalues, ascending; ``values[0]`` is 0 (up to round-off) on a connected surface.
    vectors : ndarray, shape (n, k)
        Eigenvectors, A-orthonormal (``vectors.T @ mass @ vectors == I``), signs fixed by
        :func:`fix_signs`.
    stiffness, mass : scipy.sparse.csr_matrix
        The operators the spectrum was computed from.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(3), 16)
    >>> s.values[1:4].round(1).tolist()
    [2.0, 2.0, 2.0]
    """

    values: NDArray[np.float64]
    vectors: NDArray[np.float64]
    stiffness: sp.csr_matrix
    mass: sp.csr_matrix

    def __post_init__(self) -> None:
        self.values.setflags(write=False)
        self.vectors.setflags(write=False)

    @property
    def k(self) -> int:
        """Number of eigenpairs."""
        return int(self.values.shape[0])

    @property
    def n_vertices(self) -> int:
        return int(self.vectors.shape[0])

    def __len__(self) -> int:
        return self.k

    def __repr__(self) -> str:
        return f"Spectrum(k={self.k}, n_vertices={self.n_vertices}, values=[{self.values[0]:.4g} .. {self.values[-1]:.4g}])"

    # --- the A-inner-product algebra -------------------------------------------------------
    def _check_f(self, f: ArrayLike) -> NDArray[np.float64]:
        arr = np.asarray(f, dtype=np.float64)
        if arr.ndim not in (1, 2) or arr.shape[0] != self.n_vertices:
            raise ValueError(
                f"f must have shape ({self.n_vertices},) or ({self.n_vertices}, c): one value per "
                f"vertex; got {arr.shape}."
            )
        if not np.all(np.isfinite(arr)):
            raise ValueError("f contains NaN or inf; the projection would be meaningless.")
        return arr

    def _check_n(self, n: int | None) -> int:
        if n is None:
            return self.k
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
            raise ValueError(f"n must be an integer number of eigenfunctions, got {n!r}.")
        if not 0 <= n <= self.k:
            raise ValueError(f"n must be between 0 and k={self.k} (the eigenpairs computed), got {n}.")
        return int(n)

    def project(self, f: ArrayLike, n: int | None = None) -> NDArray[np.float64]:
        """Coefficients ``Phi_n.T @ (A @ f)`` of ``f`` in the first ``n`` eigenfunctions.

        ``f`` is (n_vertices,) or (n_vertices, c); the result is (n,) or (n, c).
        """
        arr = self._check_f(f)
        n = self._check_n(n)
        return self.vectors[:, :n].T @ (self.mass @ arr)

    def reconstruct(self, f: ArrayLike, n: int | None = None) -> NDArray[np.float64]:
        """The A-orthogonal projection of ``f`` onto the span of the first ``n`` eigenfunctions."""
        n = self._check_n(n)
        return self.vectors[:, :n] @ self.project(f, n)

    def error(self, f: ArrayLike, n: int | None = None) -> NDArray[np.float64] | float:
        """A-norm of ``f - reconstruct(f, n)``: a float for 1-D ``f``, an array per column for 2-D."""
        arr = self._check_f(f)
        r = arr - self.reconstruct(arr, n)
        sq = np.einsum("i...,i...->...", r, self.mass @ r)
        out = np.sqrt(np.maximum(sq, 0.0))
        return float(out) if arr.ndim == 1 else out


def check_operators(stiffness: sp.spmatrix, mass: sp.spmatrix) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Validate a (stiffness, mass) pair and return both as CSR float64."""
    if not (sp.issparse(stiffness) and sp.issparse(mass)):
        raise ValueError("stiffness and mass must be scipy.sparse matrices (see operators.stiffness_matrix).")
    W, A = sp.csr_matrix(stiffness, dtype=np.float64), sp.csr_matrix(mass, dtype=np.float64)
    n = W.shape[0]
    if W.shape != (n, n) or A.shape != (n, n):
        raise ValueError(f"stiffness {W.shape} and mass {A.shape} must be square and of the same size.")
    if not (np.all(np.isfinite(W.data)) and np.all(np.isfinite(A.data))):
        raise ValueError("stiffness or mass contains NaN or inf; check the mesh for degenerate faces.")
    for name, M in (("stiffness", W), ("mass", A)):
        scale = abs(M).max() if M.nnz else 0.0
        if M.nnz and abs(M - M.T).max() > 1e-10 * scale:
            raise ValueError(f"{name} must be symmetric; symmetrise it with (M + M.T) / 2.")
    if np.any(A.diagonal() <= 0):
        raise ValueError("the mass matrix has a non-positive diagonal entry; it must be positive definite.")
    return W, A


def fix_signs(vectors: NDArray[np.float64], mass: sp.spmatrix) -> NDArray[np.float64]:
    """Flip columns so that their signs are deterministic.

    A column gets the sign that makes its A-weighted third moment ``sum_i a_i v_i^3`` positive;
    when that moment vanishes (odd functions on symmetric shapes), the entry of largest magnitude
    is made positive instead. Both rules commute with vertex permutations.
    """
    v = np.array(vectors, dtype=np.float64, copy=True)
    a = np.asarray(mass.sum(axis=1)).ravel()
    moment = a @ v**3
    scale = a @ np.abs(v) ** 3
    # Mirror-image peaks on symmetric shapes agree to round-off: take the first vertex whose
    # magnitude is within a relative 1e-6 of the largest, so round-off cannot pick the sign.
    mag = np.abs(v)
    first_peak = np.argmax(mag >= (1.0 - 1e-6) * mag.max(axis=0), axis=0)
    peak = v[first_peak, np.arange(v.shape[1])]
    sign = np.where(np.abs(moment) > 1e-6 * scale, np.sign(moment), np.sign(peak))
    sign[sign == 0] = 1.0
    return v * sign


def _default_shift(A: sp.csr_matrix) -> float:
    # The first nonzero eigenvalue of a surface of area S is of order 4 pi / S (2 on the unit
    # sphere), so this shift is small against the spectrum at every scale yet keeps W + s A
    # positive definite (W alone is singular: constants are in its kernel).
    return 1e-2 * 4.0 * np.pi / float(A.sum())


def eigenbasis(
    mesh: Union[Mesh, Operators],
    k: int,
    *,
    mass: MassKind = "voronoi",
    alpha: float = 0.0,
    shift: float | None = None,
    curvature_floor: float | None = None,
    solver: str = "auto",
) -> Spectrum:
    """The ``k`` smallest eigenpairs of ``W phi = lam A phi``.

    Parameters
    ----------
    mesh : Mesh or (stiffness, mass) tuple
        A mesh, or precomputed sparse operators (so that other metrics can reuse the solver).
    k : int
        Number of eigenpairs, ``1 <= k <= n_vertices``.
    mass : {"voronoi", "barycentric", "consistent"}
        Mass matrix kind when ``mesh`` is a :class:`Mesh`.
    alpha : float in [0, 1]
        Exponent of the metric ``|K|^alpha g`` (notebook 06). ``0`` is exactly the regular metric;
        otherwise ``W`` is unchanged and the mass is
        :func:`~lbo_notebooks.curvature.metric_mass_matrix` (``1``: scale-invariant spectrum).
    shift : float, optional
        Positive number ``s``; shift-invert Lanczos runs at ``sigma = -s``. The shift is
        *negative* because ``W`` is singular (constants are in its kernel), so ``sigma = 0`` would
        factorise a singular matrix, while ``W + s A`` is positive definite. The default scales
        with the surface area, so results do not depend on the mesh's units.
    curvature_floor : float > 0, optional
        Only used when ``alpha != 0``: the regularisation of ``|K|`` as a fraction of
        ``4 pi / area`` (``rho = max(one-ring mean |K|, curvature_floor * 4 pi / area)``, see
        :mod:`lbo_notebooks.curvature`). Default ``curvature.DEFAULT_FLOOR`` (1e-3).
    solver : {"auto", "slicing", "arpack"}
        Above ``DENSE_LIMIT`` vertices: ``"slicing"`` runs several small shift-invert Lanczos
        solves whose inertia counts prove no eigenvalue is missed
        (:func:`~lbo_notebooks.eigensolver.slice_eigsh`); ``"arpack"`` is the single
        ``eigsh(W, k, M=A, sigma=-shift)`` call peer libraries make. ``"auto"`` slices when ``k``
        exceeds one slice (``eigensolver.SLICE_SIZE``), where one large Krylov space is slow.

    Returns
    -------
    Spectrum

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> s = eigenbasis(shapes.icosphere(3), 9)
    >>> bool(abs(s.values[4:9] / 6 - 1).max() < 0.02)  # l = 2: lam = l (l + 1) = 6
    True
    """
    if isinstance(mesh, Mesh):
        if mass not in MASS_KINDS:
            raise ValueError(f"mass kind must be one of {MASS_KINDS}, got {mass!r}.")
        if isinstance(alpha, bool) or not (np.isscalar(alpha) and np.isfinite(alpha) and 0.0 <= float(alpha) <= 1.0):
            raise ValueError(f"alpha must be a number in [0, 1], got {alpha!r}.")
        W = stiffness_matrix(mesh)
        if float(alpha) == 0.0:
            A = mass_matrix(mesh, mass)
        else:
            from .curvature import DEFAULT_FLOOR, metric_mass_matrix

            floor = DEFAULT_FLOOR if curvature_floor is None else curvature_floor
            A = metric_mass_matrix(mesh, float(alpha), kind=mass, floor=floor)
    elif isinstance(mesh, tuple) and len(mesh) == 2:
        if alpha != 0.0:
            raise ValueError("alpha applies to a Mesh; with explicit operators pass the scaled mass yourself.")
        W, A = check_operators(*mesh)
    else:
        raise ValueError(f"eigenbasis takes a Mesh or a (stiffness, mass) tuple, got {type(mesh).__name__}.")

    n = W.shape[0]
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not 1 <= k <= n:
        raise ValueError(f"k must be an integer between 1 and the number of vertices ({n}), got {k!r}.")
    k = int(k)
    if shift is None:
        shift = _default_shift(A)
    elif not (np.isfinite(shift) and shift > 0):
        raise ValueError(f"shift must be a positive number (sigma = -shift), got {shift!r}.")

    if solver not in ("auto", "slicing", "arpack"):
        raise ValueError(f"solver must be 'auto', 'slicing' or 'arpack', got {solver!r}.")

    if n <= DENSE_LIMIT or 2 * k + 1 > n:
        values, vectors = scipy.linalg.eigh(W.toarray(), A.toarray(), subset_by_index=[0, k - 1])
    else:
        # A fixed start vector makes ARPACK deterministic.
        v0 = 1.0 + 0.5 * np.cos(np.arange(n, dtype=np.float64))
        from .eigensolver import SLICE_SIZE, slice_eigsh

        if solver == "slicing" or (solver == "auto" and k > SLICE_SIZE):
            values, vectors, _ = slice_eigsh(W, A, k, v0=v0, shift=shift)
        else:
            values, vectors = spla.eigsh(W, k=k, M=A, sigma=-shift, which="LM", v0=v0)
            order = np.argsort(values)
            values, vectors = values[order], vectors[:, order]
        # ARPACK returns M-orthonormal vectors up to round-off; one Rayleigh-Ritz-free
        # re-orthonormalisation keeps Phi.T A Phi = I to machine precision.
        gram = vectors.T @ (A @ vectors)
        chol = np.linalg.cholesky(gram)
        vectors = np.linalg.solve(chol, vectors.T).T
    vectors = fix_signs(vectors, A)
    return Spectrum(values=np.ascontiguousarray(values), vectors=np.ascontiguousarray(vectors), stiffness=W, mass=A)
