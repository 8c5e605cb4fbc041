"""The optimality theorem of the spectral domain, checked numerically.

Aflalo, Brezis and Kimmel prove that no n-dimensional basis represents functions of bounded
Dirichlet energy better than the first n eigenfunctions of the Laplace–Beltrami operator:

* **Bound.** For every ``f``, ``||f - Phi_n Phi_n.T A f||_A^2 <= (f @ W @ f) / lam[n]``
  (:func:`representation_error`, :func:`error_bound`).
* **Optimality.** For every subspace ``V`` of dimension ``n`` the *worst-case constant*
  ``C(V) = sup_f ||f - P_V f||_A^2 / (f @ W @ f)`` is at least ``1 / lam[n]``, with equality for
  the eigenbasis (:func:`worst_case_ratio`; ``worst_case_ratio * lam[n]`` is the normalised figure).

The exact ``C(V)`` minimises the energy over the part of ``f`` that lies *in* ``V`` (a Schur
complement). Using ``W`` itself on the A-orthogonal complement of ``V`` instead is a classic trap:
it gives only a lower bound (:func:`~lbo_notebooks.analyses.complement_ratio`, kept to show the difference). See docs/maths.md,
section "Optimality".
"""

from __future__ import annotations

from typing import Any, Literal, overload

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.csgraph as csgraph
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from .._support.validation import (
    Array,
    Constraint,
    Integer,
    Options,
    Relation,
    Satisfies,
    validated,
)
from ..spectral._inner_product import a_orthonormalize, check_operators, fix_signs
from ..spectral._solvers import start_vector, symmetric_lu, use_dense
from ..spectral._spectrum import Spectrum

__all__ = [
    "representation_error",
    "error_bound",
    "dirichlet_energy",
    "kernel_basis",
    "worst_case_ratio",
    "witness_function",
]

Method = Literal["auto", "dense", "sparse"]


# --- input checks ----------------------------------------------------------------------------
_SPECTRUM = Satisfies(lambda s: isinstance(s, Spectrum),
                      message="spectrum must be a Spectrum (from lbo_notebooks.eigenbasis), got {type}.")
_METHOD = Options("auto", "dense", "sparse", message="method must be 'auto', 'dense' or 'sparse', got {value!r}.")


_SQUARE_SPARSE = Satisfies(lambda W: sp.issparse(W) and W.shape[0] == W.shape[1],
                           message="stiffness must be a square scipy.sparse matrix (see operators.stiffness_matrix).")


def _basis(n_vertices: Any) -> tuple[Constraint, ...]:
    """The table entry of ``basis``: a finite 2-D array of ``n_vertices`` rows and 1..n_vertices - 1 columns.

    ``n_vertices`` is a count or a callable of the arguments (``lambda spectrum, **_: spectrum.n_vertices``).
    """
    return (
        Array(2, rows=n_vertices, message=(
            "{name} must be a 2-D array of shape ({rows}, n): one column per basis function; got {shape}. "
            "Use basis[:, None] for a single function.")),
        Satisfies(lambda basis: 1 <= basis.shape[1] < basis.shape[0], message=lambda name, value: (
            f"{name} must have between 1 and n_vertices - 1 = {value.shape[0] - 1} columns, got {value.shape[1]}.")),
    )


# --- the bound ---------------------------------------------------------------------------------
@validated(stiffness=_SQUARE_SPARSE, f=Array(rows=lambda stiffness, **_: stiffness.shape[0],
                                              meaning="one value per vertex", hint="replace them first"))
def dirichlet_energy(stiffness: sp.spmatrix, f: ArrayLike) -> NDArray[np.float64] | float:
    """Dirichlet energy ``f @ W @ f`` (the squared L2 norm of the gradient), per column.

    Parameters
    ----------
    stiffness : sparse (n, n)
        Cotangent stiffness matrix ``W``.
    f : array (n,) or (n, c)
        Function(s) with one value per vertex.

    Returns
    -------
    float for 1-D ``f``, array (c,) for 2-D ``f``.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, stiffness_matrix
    >>> m = shapes.rectangle(2.0, 1.0, 8, 4)
    >>> round(dirichlet_energy(stiffness_matrix(m), m.vertices[:, 0]), 12)  # |grad x|^2 * area
    2.0
    """
    out = np.einsum("i...,i...->...", f, stiffness @ f)
    return float(out) if f.ndim == 1 else np.asarray(out)


@validated(spectrum=_SPECTRUM)
def representation_error(spectrum: Spectrum, f: ArrayLike, k: int) -> NDArray[np.float64] | float:
    """Squared A-norm error ``||f - Phi_k Phi_k.T A f||_A^2`` of the k-term eigen-expansion.

    Parameters
    ----------
    spectrum : Spectrum
        Eigenbasis with at least ``k`` eigenpairs.
    f : array (n_vertices,) or (n_vertices, c)
    k : int
        Number of eigenfunctions kept, ``0 <= k <= spectrum.k``.

    Returns
    -------
    float for 1-D ``f``, array (c,) for 2-D ``f``.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(3), 10)
    >>> x = s.vectors[:, 3] + s.vectors[:, 7]
    >>> bool(representation_error(s, x, 8) < 1e-20 * representation_error(s, x, 0))  # ||x||_A^2 = 2
    True
    >>> round(representation_error(s, x, 4), 10)
    1.0
    """
    err = spectrum.error(f, k)
    return err**2 if isinstance(err, float) else np.asarray(err) ** 2


@validated(spectrum=_SPECTRUM, k=(
    Integer(what="an integer number of eigenfunctions"),
    Integer(1, lambda spectrum, **_: spectrum.k - 1,
            what=lambda spectrum, **_: f"an integer with 1 <= k < spectrum.k = {spectrum.k} (error_bound needs lam[k])",
            hint="compute the spectrum with more than k eigenpairs"),
))
def error_bound(spectrum: Spectrum, f: ArrayLike, k: int) -> NDArray[np.float64] | float:
    """The theorem's bound ``(f @ W @ f) / lam[k]`` on :func:`representation_error`.

    ``lam[k]`` is the first eigenvalue *not* in the expansion (the paper's lambda_{k+1}), so the
    spectrum must hold more than ``k`` eigenpairs (``spectrum.k > k``). ``k = 0`` is excluded: ``lam[0] = 0``, and without the
    constant function no finite bound exists.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(3), 20)
    >>> z = shapes.icosphere(3).vertices[:, 2]
    >>> bool(representation_error(s, z ** 3, 9) <= error_bound(s, z ** 3, 9))
    True
    """
    lam = float(spectrum.values[k])
    if not lam > 0:
        raise ValueError(f"lam[{k}] = {lam:.3g} is not positive: the surface has more than {k} components.")
    return dirichlet_energy(spectrum.stiffness, f) / lam


# --- A-orthonormal bases -------------------------------------------------------------------------
def kernel_basis(stiffness: sp.spmatrix) -> NDArray[np.float64]:
    """The kernel of ``W``: one indicator column per connected component (shape (n, p)).

    Components are those of the graph of nonzero off-diagonal entries of ``W``; on a connected
    mesh this is the single constant function ``ones(n)[:, None]``.

    Examples
    --------
    >>> from lbo_notebooks import shapes, stiffness_matrix
    >>> kernel_basis(stiffness_matrix(shapes.icosphere(1))).shape
    (42, 1)
    """
    W = sp.coo_matrix(stiffness)
    keep = (W.row != W.col) & (W.data != 0)
    pattern = sp.csr_matrix((np.ones(int(keep.sum()), dtype=np.int8), (W.row[keep], W.col[keep])), shape=W.shape)
    p, labels = csgraph.connected_components(pattern, directed=False)
    return np.eye(p)[labels]


# --- the worst-case constant ---------------------------------------------------------------------
class _RegularisedStiffnessSolver:
    """Solves ``(W + sum_k a_k a_k.T / s_k) x = b`` without forming a dense matrix.

    ``a_k = A 1_k`` for the indicator ``1_k`` of component k and ``s_k = 1_k A 1_k``. One vertex per
    component is pinned, the rest of ``W`` (positive definite) is factorised once by sparse LU,
    and the pinned solution is corrected by the constants: the right-hand side's component sums
    fix the mean of x, the A-mean-zero part solves ``W y = b'``.
    """

    def __init__(self, W: sp.csr_matrix, A: sp.csr_matrix, kernel: NDArray[np.float64]) -> None:
        n = W.shape[0]
        # Everything per component via bincount on labels: no (n, 1) BLAS calls, which are slow
        # under thread oversubscription.
        self.labels = np.argmax(kernel, axis=1)
        self.p = kernel.shape[1]
        self.a = np.asarray(A @ np.ones(n)).ravel()  # A is block diagonal over components
        self.s = self._sum(self.a)
        pinned = np.argmax(kernel, axis=0)  # first vertex of each component
        keep = np.ones(n, dtype=bool)
        keep[pinned] = False
        self.keep = keep
        self.lu = symmetric_lu(W[keep][:, keep])
        self.W = W

    def _sum(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.bincount(self.labels, weights=x, minlength=self.p)

    def matvec(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        x = np.ravel(x)
        return self.W @ x + self.a * (self._sum(self.a * x) / self.s)[self.labels]

    def solve(self, b: NDArray[np.float64]) -> NDArray[np.float64]:
        b = np.asarray(b, dtype=np.float64).ravel()
        sums = self._sum(b)  # = a_k . x for the solution x
        rhs = b - self.a * (sums / self.s)[self.labels]  # consistent: orthogonal to every 1_k
        y = np.zeros_like(b)
        y[self.keep] = self.lu.solve(rhs[self.keep])
        return y + ((sums - self._sum(self.a * y)) / self.s)[self.labels]


def _worst_case_dense(
    Q: NDArray[np.float64], W: sp.csr_matrix, A: sp.csr_matrix, kernel: NDArray[np.float64]
) -> tuple[float, NDArray[np.float64]]:
    AQ = A @ Q
    a = np.asarray(A @ kernel)
    s = np.einsum("ik,ik->k", kernel, a)
    left = A.toarray() - AQ @ AQ.T
    right = W.toarray() + (a / s) @ a.T
    n = W.shape[0]
    values, vectors = scipy.linalg.eigh(left, right, subset_by_index=[n - 1, n - 1])
    return float(values[0]), vectors[:, 0]


def _worst_case_sparse(
    Q: NDArray[np.float64], W: sp.csr_matrix, A: sp.csr_matrix, kernel: NDArray[np.float64]
) -> tuple[float, NDArray[np.float64]]:
    n = W.shape[0]
    AQ = np.asarray(A @ Q)
    solver = _RegularisedStiffnessSolver(W, A, kernel)
    left = spla.LinearOperator((n, n), matvec=lambda x: A @ np.ravel(x) - AQ @ (AQ.T @ np.ravel(x)), dtype=np.float64)
    right = spla.LinearOperator((n, n), matvec=solver.matvec, dtype=np.float64)
    right_inv = spla.LinearOperator((n, n), matvec=solver.solve, dtype=np.float64)
    # tol=0 asks for machine precision.
    values, vectors = spla.eigsh(
        left, k=1, M=right, Minv=right_inv, which="LA", v0=start_vector(n), tol=0.0, ncv=min(n - 1, 24)
    )
    return float(values[0]), vectors[:, 0]


@overload
def worst_case_ratio(
    basis: ArrayLike, stiffness: sp.spmatrix, mass: sp.spmatrix, *, method: Method = ..., return_vector: Literal[False] = ...
) -> float: ...
@overload
def worst_case_ratio(
    basis: ArrayLike, stiffness: sp.spmatrix, mass: sp.spmatrix, *, method: Method = ..., return_vector: Literal[True]
) -> tuple[float, NDArray[np.float64]]: ...
@validated(method=_METHOD)
def worst_case_ratio(
    basis: ArrayLike,
    stiffness: sp.spmatrix,
    mass: sp.spmatrix,
    *,
    method: Method = "auto",
    return_vector: bool = False,
) -> float | tuple[float, NDArray[np.float64]]:
    """Exact worst-case constant ``C(V) = sup_f ||f - P_V f||_A^2 / (f @ W @ f)`` of a basis.

    ``V`` is the span of the columns of ``basis`` and ``P_V`` the A-orthogonal projection onto it.
    The theorem says ``C(V) >= 1 / lam[n]`` for every n-dimensional V, with equality for the first
    n eigenfunctions; ``worst_case_ratio(basis, W, A) * lam[n]`` is therefore exactly 1 for the
    eigenbasis and above 1 for every other basis.

    **C(V) is infinite when the constant function is not in V** (more generally, when the kernel
    of ``W``, the constants on each connected component, is not contained in V): a constant has
    zero energy but a nonzero representation error. This function then returns ``inf``. Put
    ``numpy.ones(n)`` among the columns (e.g. ``a_orthonormalize(..., prepend=ones)``) to get a
    finite constant.

    How it is computed (docs/maths.md, "Optimality"): with ``f = r + v``, ``v`` in V and ``r`` A-orthogonal to
    V, the error is ``||r||_A^2`` and the smallest energy over ``v`` is the Schur complement
    ``r @ S @ r``, ``S = W - W Q (Q.T W Q)^+ Q.T W``. Equivalently ``C(V)`` is the largest eigenvalue
    of the pencil ``(A - (A Q)(A Q).T,  W + sum_c a_c a_c.T / area_c)``, ``Q`` an A-orthonormal basis
    of V, with one rank-one term per connected component ``c``: ``a_c = A 1_c`` for the indicator
    ``1_c`` of the component and ``area_c = 1_c @ A @ 1_c`` (a single ``a a.T / area`` on a connected
    mesh). These terms make the right side positive definite (one term alone would not on a mesh with
    several components). They change the ratio of an individual ``f``, whose energy gains
    ``sum_c (a_c @ f)**2 / area_c``, but not the supremum: with the constants in V, adding a constant
    on each component changes neither the error nor the energy and makes every ``a_c @ f`` zero.
    (Using ``W`` instead of ``S`` on the complement is the trap:
    :func:`~lbo_notebooks.analyses.complement_ratio`.)

    Parameters
    ----------
    basis : array (n_vertices, n)
        Any full-rank basis of V (it is A-orthonormalised internally; the input is not modified).
    stiffness, mass : sparse (n_vertices, n_vertices)
        ``W`` and ``A``.
    method : {"auto", "dense", "sparse"}
        ``"dense"``: ``scipy.linalg.eigh`` of the pencil (O(n_vertices^3), small meshes);
        ``"sparse"``: Lanczos (``eigsh``, ``k=1``, ``which="LA"``) with
        ``(W + sum_c a_c a_c.T/area_c)^{-1}`` applied by a sparse LU of ``W`` with one vertex pinned
        per component, corrected by the constants; no dense
        n_vertices x n_vertices matrix is formed. ``"auto"`` picks dense below
        ``DENSE_LIMIT`` vertices.
    return_vector : bool
        Also return a worst-case function ``f`` (scaled so that ``||f - P_V f||_A = 1``).

    Returns
    -------
    float, or (float, ndarray (n_vertices,)) with ``return_vector``.

    Raises
    ------
    ValueError
        For a basis of the wrong shape, with NaN/inf, or rank-deficient; for invalid operators.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.bumpy_sphere(2), 12)
    >>> round(worst_case_ratio(s.vectors[:, :10], s.stiffness, s.mass) * float(s.values[10]), 8)
    1.0
    >>> worst_case_ratio(s.vectors[:, 1:10], s.stiffness, s.mass)  # no constant function
    inf
    """
    W, A = check_operators(stiffness, mass)
    n = W.shape[0]
    arr = basis
    for rule in _basis(n):  # inline: the number of rows is that of the checked operators
        arr = rule.check(arr, "basis", {})
    dense = use_dense(n, method)
    Q = a_orthonormalize(arr, A)
    kernel = kernel_basis(W)
    # Is the kernel of W (the constants) inside V? Relative A-norm of what V misses.
    residual = kernel - Q @ (Q.T @ (A @ kernel))
    missed = np.einsum("ik,ik->k", residual, A @ residual) / np.einsum("ik,ik->k", kernel, A @ kernel)
    if np.any(missed > 1e-16):  # a relative A-norm above 1e-8
        if return_vector:
            f = residual[:, int(np.argmax(missed))]
            return float("inf"), fix_signs(f / np.sqrt(float(f @ (A @ f))), A)
        return float("inf")
    value, f = (_worst_case_dense if dense else _worst_case_sparse)(Q, W, A, kernel)
    if not return_vector:
        return value
    r = f - Q @ (Q.T @ (A @ f))
    return value, fix_signs(f / np.sqrt(float(r @ (A @ r))), A)


def _too_few_eigenpairs(spectrum: Spectrum, basis: NDArray[np.float64], **_: Any) -> str:
    return f"the spectrum needs at least n + 1 = {basis.shape[1] + 1} eigenpairs, it has {spectrum.k}."


@validated(spectrum=_SPECTRUM, basis=(
    *_basis(lambda spectrum, **_: spectrum.n_vertices),
    Relation(lambda spectrum, basis, **_: basis.shape[1] + 1 <= spectrum.k, _too_few_eigenpairs),
))
def witness_function(spectrum: Spectrum, basis: ArrayLike) -> NDArray[np.float64]:
    """The witness argument (notebook 05, section 6): a nonzero ``f`` in span(phi_0..phi_n) A-orthogonal to V.

    V (spanned by the n columns of ``basis``) imposes n linear conditions on the n+1 coefficients
    of ``f = Phi_{n+1} c``, so such an ``f`` exists. Its error is all of it,
    ``||f - P_V f||_A^2 = ||f||_A^2 = |c|^2``, while its energy is ``sum lam_i c_i^2 <= lam[n] |c|^2``:
    hence ``C(V) >= 1 / lam[n]`` for every V.

    Returns
    -------
    ndarray (n_vertices,), A-normalised (``f @ A @ f = 1``), sign fixed by :func:`~lbo_notebooks.spectral.fix_signs`.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(2), 12)
    >>> B = np.random.default_rng(1).normal(size=(162, 8))
    >>> f = witness_function(s, B)
    >>> bool(np.abs(B.T @ s.mass @ f).max() < 1e-10 and f @ s.stiffness @ f <= s.values[8] * (1 + 1e-12))
    True
    """
    n = basis.shape[1]
    Q = a_orthonormalize(basis, spectrum.mass)
    coupling = Q.T @ (spectrum.mass @ spectrum.vectors[:, : n + 1])  # (n, n + 1)
    c = scipy.linalg.null_space(coupling)[:, 0]  # the last right-singular vector
    f = spectrum.vectors[:, : n + 1] @ c
    return fix_signs(f / np.sqrt(float(f @ (spectrum.mass @ f))), spectrum.mass)
