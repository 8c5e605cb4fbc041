"""The A-inner-product algebra: one home for the building blocks every module shares.

Functions on a mesh live in the inner product ``<f, g>_A = f @ A @ g`` of the mass matrix ``A``,
not the Euclidean one. This module holds, once, what the spectral modules need around it:

* checks: :func:`check_operators` (a ``(stiffness, mass)`` pair), :func:`check_functions`;
* norms and bases: :func:`a_norms`, :func:`a_orthonormalize` (the one orthonormaliser),
  :func:`principal_angles`, :func:`reconstruct` and :func:`reconstruction_error` for any
  A-orthonormal basis;
* the deterministic sign rule :func:`fix_signs`.

The products with a lumped mass and the Cholesky QR refinement, which the engine shares, are
:mod:`lbo_notebooks.spectral._mass_products`.

The solvers' conventions (shift, start vector, dense or sparse) are
:mod:`lbo_notebooks.spectral._engine.policy`; the one sparse factorisation of a symmetric matrix is
:func:`~lbo_notebooks.spectral._engine.factor.symmetric_lu`.

The formulas are in ``docs/maths.md``, section "The A inner product".
"""

from __future__ import annotations

from typing import Any, Sequence

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Array, Number, Satisfies, validated
from ._mass_products import ROW_BLOCK, DiagonalMass, cholesky_qr, mass_operator

__all__ = [
    "is_square_matrix",
    "check_operators",
    "check_functions",
    "a_norms",
    "a_orthonormalize",
    "fix_signs_in_place",
    "fix_signs",
    "principal_angles",
    "reconstruct",
    "reconstruction_error",
]

_BLOCK = 32


# --- checks ------------------------------------------------------------------------------------
def _is_square_sparse(mass: Any) -> bool:
    return (sp.issparse(mass) or isinstance(mass, DiagonalMass)) and len(mass.shape) == 2 and (
        mass.shape[0] == mass.shape[1])


def is_square_matrix(mass: Any) -> bool:
    """True for a square sparse matrix, a :class:`DiagonalMass` or a square 2-D array-like."""
    return _is_square_sparse(mass) or (np.ndim(mass) == 2 and len(set(np.shape(mass))) == 1)


#: The rules for ``mass``, first in every table whose other rules read its size: sparse (for the
#: orthonormaliser), or any square matrix (where the body converts it, as ``sp.csr_matrix(mass)``).
_MASS = Satisfies(_is_square_sparse, message="mass must be a square scipy.sparse matrix (see operators.mass_matrix).")
_SQUARE_MASS = Satisfies(is_square_matrix, message=(
    "mass must be a square matrix (usually scipy.sparse: see operators.mass_matrix), got {type}."))


def _rows(mass: Any, **_: Any) -> int:
    """The number of vertices, from the mass matrix: the row count every function argument must have."""
    return int(np.shape(mass)[0])


_FUNCTIONS = Array((1, 2), rows=lambda n_vertices, **_: n_vertices, meaning="one value per vertex",
                   hint="replace them first")
_BASIS = Array(2, rows=_rows, cols_name="k", meaning="one column per basis function")
_TARGET = Array((1, 2), rows=_rows, cols_name="d", nonempty=True, meaning="one row per vertex", hint="clean it first")
_SUBSPACE = Array(2, rows=_rows, cols_name="k")


def _check_symmetric(M: sp.csr_matrix, name: str) -> None:
    scale = abs(M).max() if M.nnz else 0.0
    if M.nnz and abs(M - M.T).max() > 1e-10 * scale:
        raise ValueError(f"{name} must be symmetric; symmetrise it with (M + M.T) / 2.")


def check_operators(
    stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix, *, allow_dense: bool = False
) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Validate a ``(stiffness, mass)`` pair and return both as CSR float64 (fresh copies).

    Both must be square, of the same size, finite and symmetric; the mass diagonal positive.

    Parameters
    ----------
    stiffness, mass : scipy.sparse (n, n)
        ``W`` and ``A`` (see :mod:`lbo_notebooks.operators._cotangent`).
    allow_dense : bool
        Also accept dense arrays (small examples such as a 3 x 3 matrix with ``numpy.eye(3)``).

    Examples
    --------
    >>> import numpy as np
    >>> W, A = check_operators(np.diag([1.0, 2.0]), np.eye(2), allow_dense=True)
    >>> W.format, A.shape
    ('csr', (2, 2))
    """
    if allow_dense:
        stiffness = stiffness if sp.issparse(stiffness) else sp.csr_matrix(np.asarray(stiffness, dtype=np.float64))
        mass = mass if sp.issparse(mass) else sp.csr_matrix(np.asarray(mass, dtype=np.float64))
    if not (sp.issparse(stiffness) and sp.issparse(mass)):
        raise ValueError("stiffness and mass must be scipy.sparse matrices (see operators.stiffness_matrix).")
    W, A = sp.csr_matrix(stiffness, dtype=np.float64), sp.csr_matrix(mass, dtype=np.float64)
    n = W.shape[0]
    if W.shape != (n, n) or A.shape != (n, n):
        raise ValueError(f"stiffness {W.shape} and mass {A.shape} must be square and of the same size.")
    if not (np.all(np.isfinite(W.data)) and np.all(np.isfinite(A.data))):
        raise ValueError("stiffness or mass contains NaN or inf; check the mesh for degenerate faces.")
    _check_symmetric(W, "stiffness")
    _check_symmetric(A, "mass")
    if np.any(A.diagonal() <= 0):
        raise ValueError("the mass matrix has a non-positive diagonal entry; it must be positive definite.")
    return W, A


def check_functions(f: ArrayLike, n_vertices: int, name: str = "f") -> NDArray[np.float64]:
    """``f`` as a float array of shape (n_vertices,) or (n_vertices, c), finite.

    Examples
    --------
    >>> check_functions([[1.0], [2.0]], 2).shape
    (2, 1)
    """
    return _FUNCTIONS.check(f, name, {"n_vertices": n_vertices})


# --- norms and orthonormal bases ---------------------------------------------------------------
@validated(mass=_SQUARE_MASS, X=Array(2, rows=_rows, meaning="one column per function"))
def a_norms(X: ArrayLike, mass: sp.spmatrix) -> NDArray[np.float64]:
    """A-norm ``sqrt(x @ A @ x)`` of each column of ``X`` (shape (c,)).

    Examples
    --------
    >>> import numpy as np, scipy.sparse as sp
    >>> a_norms(np.ones((4, 2)), sp.identity(4)).tolist()
    [2.0, 2.0]
    """
    return _a_norms(X, mass)


def _a_norms(X: NDArray[np.float64], mass: sp.spmatrix) -> NDArray[np.float64]:
    return np.sqrt(np.maximum(np.einsum("ij,ij->j", X, mass @ X), 0.0))


def _project_out(
    Q: NDArray[np.float64], X: NDArray[np.float64], mass: sp.spmatrix, norms: NDArray[np.float64]
) -> NDArray[np.float64]:
    """In place ``X -= Q Q.T A X``, repeated while a pass removes more than half of a column's
    norm ("twice is enough", with a guard for nearly dependent columns). Returns the new norms."""
    for _ in range(4):
        X -= Q @ (Q.T @ (mass @ X))
        new = _a_norms(X, mass)
        if np.all((new > 0.5 * norms) | (new == 0.0)):
            return new
        norms = new
    return norms


@validated(
    mass=_MASS,
    prepend=Array((1, 2), rows=_rows, cols_name="p", column=True, none=True, meaning="the columns placed first"),
    vectors=Array((1, 2), rows=_rows, cols_name="m", column=True, meaning="one column per function"),
    rtol=Number(0, 1, open_low=True, open_high=True),
)
def a_orthonormalize(
    vectors: ArrayLike,
    mass: sp.spmatrix,
    *,
    prepend: ArrayLike | None = None,
    drop_dependent: bool = False,
    rtol: float = 1e-8,
    refine: bool = False,
) -> NDArray[np.float64]:
    """A-orthonormal basis of the span of the columns, in column order (Gram–Schmidt in ``<.,.>_A``).

    Column ``j`` of the result combines only columns ``0..j`` of the input, so columns that are
    already A-orthonormal (e.g. eigenvectors up to round-off) keep their order and meaning. Each
    column is orthogonalised by classical Gram–Schmidt, repeated while a pass removes more than
    half of its norm ("twice is enough", with a guard), so ``Q.T @ A @ Q = I`` to round-off even
    for ill-conditioned input.

    Parameters
    ----------
    vectors : array (n_vertices, m) or (n_vertices,)
    mass : sparse (n_vertices, n_vertices)
        The mass matrix ``A`` defining the inner product.
    prepend : array (n_vertices,) or (n_vertices, p), optional
        Columns placed first (e.g. ``numpy.ones(n)`` for "the constant function first", or an
        A-orthonormal basis to extend).
    drop_dependent : bool
        Skip columns that are numerically in the span of the previous ones instead of raising.
    rtol : float
        A column is dependent when less than ``rtol`` of its A-norm survives orthogonalisation.
    refine : bool
        The columns are already A-orthonormal up to round-off (e.g. eigenvectors from ARPACK):
        when their A-Gram matrix is within ``1e-8`` of ``I``, finish them with one Cholesky QR
        pass ``Q = V L^-T``, ``L L^T = V^T A V`` (exact to round-off, all BLAS-3, column ``j`` still
        only mixes columns ``0..j``); otherwise Gram–Schmidt as usual.

    Returns
    -------
    ndarray (n_vertices, r), a fresh array (the input is not modified).

    Raises
    ------
    ValueError
        If a column is (numerically) dependent and ``drop_dependent`` is False: the basis is
        rank-deficient.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, mass_matrix
    >>> m = shapes.icosphere(2)
    >>> A = mass_matrix(m)
    >>> Q = a_orthonormalize(m.vertices, A, prepend=np.ones(m.n_vertices))
    >>> Q.shape, bool(np.allclose(Q.T @ A @ Q, np.eye(4)))
    ((162, 4), True)
    """
    nv = mass.shape[0]
    cols = vectors if prepend is None else np.hstack([prepend, vectors])  # both (nv, .) float64, checked
    mass = mass_operator(mass)
    if refine and cols.shape[1]:
        refined = cholesky_qr(cols, mass, out=np.empty(cols.shape))
        if refined is not None:
            return refined
    Q = np.empty((nv, cols.shape[1]))
    r = 0
    for lo in range(0, cols.shape[1], _BLOCK):
        # Block Gram-Schmidt against the columns accepted so far (BLAS-3), then column by column
        # inside the block.
        X = cols[:, lo : lo + _BLOCK].copy()
        norm0 = _a_norms(X, mass)
        if r:
            _project_out(Q[:, :r], X, mass, norm0)
        r_block = r
        for j in range(X.shape[1]):
            v = X[:, j : j + 1]
            before = float(_a_norms(v, mass)[0])
            norm = float(_project_out(Q[:, r_block:r], v, mass, np.array([before]))[0]) if r > r_block else before
            if r and 0.0 < norm < 1e-3 * before:
                # Heavy cancellation: refresh orthogonality against everything accepted so far.
                norm = float(_project_out(Q[:, :r], v, mass, np.array([norm]))[0])
            if norm0[j] == 0.0 or norm <= rtol * norm0[j]:
                if drop_dependent:
                    continue
                raise ValueError(
                    f"the basis is rank-deficient: column {lo + j} is (numerically) a combination of "
                    "the previous columns; remove it or pass drop_dependent=True."
                )
            Q[:, r] = v[:, 0] / norm
            r += 1
    return Q[:, :r]


# --- the sign rule -----------------------------------------------------------------------------
@validated(
    mass=Satisfies(is_square_matrix, none=True, message=(
        "mass must be None or a square matrix (usually scipy.sparse: see operators.mass_matrix), got {type}.")),
    # Shapes only: NaN columns keep their NaN, as they always did.
    vectors=Array((1, 2), rows=lambda mass, **_: None if mass is None else _rows(mass), cols_name="k",
                  finite=False, meaning="one row per vertex of the mass matrix"),
)
def fix_signs(vectors: ArrayLike, mass: sp.spmatrix | None = None) -> NDArray[np.float64]:
    """Flip columns so that their signs are deterministic (a fresh array; 1-D input allowed).

    A column gets the sign that makes its A-weighted third moment ``sum_i a_i v_i^3`` positive
    (``a`` = row sums of ``mass``; unit weights when ``mass`` is None, e.g. for point
    embeddings); when that moment vanishes (odd functions on symmetric shapes), the first entry
    within a relative 1e-6 of the largest magnitude is made positive instead. The third moment
    does not depend on the vertex order, and the sign of an eigenvector is arbitrary, so this is
    the one rule every module uses.

    Examples
    --------
    >>> import numpy as np
    >>> fix_signs(np.array([[-1.0], [-2.0], [0.5]]))[:, 0].tolist()
    [1.0, 2.0, -0.5]
    """
    v = np.array(vectors, dtype=np.float64, copy=True)
    if v.ndim == 1:
        return fix_signs(v[:, None], mass)[:, 0]
    return fix_signs_in_place(v, mass)


@validated(v=Satisfies(
    lambda v: getattr(v, "ndim", None) == 2 and getattr(v, "dtype", None) == np.float64,
    message=lambda name, value: (f"fix_signs_in_place needs a 2-D float64 array, got {np.ndim(value)}-D "
                                 f"{getattr(value, 'dtype', type(value).__name__)}."),
))
def fix_signs_in_place(v: NDArray[np.float64], mass: sp.spmatrix | None = None) -> NDArray[np.float64]:
    """:func:`fix_signs` on a 2-D float64 array of one's own, flipping its columns in place; returns it.

    For eigensolvers finishing their own output (no second n x k array).

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[-1.0], [-2.0], [0.5]])
    >>> fix_signs_in_place(v) is v, v[:, 0].tolist()
    (True, [1.0, 2.0, -0.5])
    """
    if v.size == 0:
        return v
    a = np.ones(v.shape[0]) if mass is None else np.asarray(mass.sum(axis=1)).ravel()
    # Row blocks: contiguous in a C-ordered basis, and the temporaries stay small for (n, 300) bases.
    moment, size = np.zeros(v.shape[1]), np.zeros(v.shape[1])
    for start in range(0, v.shape[0], ROW_BLOCK):
        block = v[start : start + ROW_BLOCK]
        cube = block * block * block  # not block**3: the generic power is several times slower
        moment += a[start : start + ROW_BLOCK] @ cube
        np.abs(cube, out=cube)
        size += a[start : start + ROW_BLOCK] @ cube
    sign = np.sign(moment)
    vanishing = np.flatnonzero(np.abs(moment) <= 1e-6 * size)
    # Mirror-image peaks on symmetric shapes agree to round-off: take the first vertex whose
    # magnitude is within a relative 1e-6 of the largest, so round-off cannot pick the sign. (A
    # few columns at a time: a symmetric shape has many such columns.)
    for start in range(0, vanishing.size, 32):
        columns = vanishing[start : start + 32]
        mag = np.abs(v[:, columns])
        first_peak = np.argmax(mag >= (1.0 - 1e-6) * mag.max(axis=0), axis=0)
        sign[columns] = np.sign(v[first_peak, columns])
    sign[sign == 0] = 1.0
    v *= sign
    return v


# --- any A-orthonormal basis -------------------------------------------------------------------
def _check_a_orthonormal(P: NDArray[np.float64], mass: sp.csr_matrix) -> None:
    gram = P.T @ (mass @ P)
    if not np.allclose(gram, np.eye(P.shape[1]), atol=1e-8):
        raise ValueError(
            "basis is not A-orthonormal (basis.T @ mass @ basis != I); the projection P P.T A would "
            "be wrong. A-orthonormalise it first (a_orthonormalize, or spectrum vectors)."
        )


def _as_columns(Y: NDArray[np.float64]) -> NDArray[np.float64]:
    return Y[:, None] if Y.ndim == 1 else Y


def _centred(Y: NDArray[np.float64], A: sp.csr_matrix) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    a = np.asarray(A.sum(axis=1)).ravel()
    centroid = (a @ Y) / a.sum()
    return Y - centroid, centroid


@validated(mass=_SQUARE_MASS, basis=_BASIS, target=_TARGET)
def reconstruct(basis: ArrayLike, mass: sp.spmatrix, target: ArrayLike) -> NDArray[np.float64]:
    """Best A-norm reconstruction of ``target`` (n, d) from an A-orthonormal basis, centroid kept.

    The A-weighted centroid of each column is removed, the rest projected with ``P P.T A``, and
    the centroid added back (so a basis without the constant is not charged for translation).

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> mesh = shapes.bumpy_sphere(3)
    >>> s = eigenbasis(mesh, 642)
    >>> bool(abs(reconstruct(s.vectors, s.mass, mesh.vertices) - mesh.vertices).max() < 1e-8 * abs(mesh.vertices).max())
    True
    """
    A = sp.csr_matrix(mass, dtype=np.float64)
    P = basis
    _check_a_orthonormal(P, A)
    Yc, centroid = _centred(_as_columns(target), A)
    out = P @ (P.T @ (A @ Yc)) + centroid
    return out[:, 0] if target.ndim == 1 else out


@validated(mass=_SQUARE_MASS, basis=_BASIS)
def reconstruction_error(
    basis: ArrayLike, mass: sp.spmatrix, targets: ArrayLike | Sequence[ArrayLike]
) -> float | NDArray[np.float64]:
    """Relative A-norm reconstruction error ``sqrt(sum_c ||x_c - x̂_c||_A^2 / sum_c ||x_c||_A^2)``.

    A-weighted centroids are removed from each column first, as in :func:`reconstruct`.

    Parameters
    ----------
    basis : array_like, shape (n, k)
        A-orthonormal basis.
    mass : scipy.sparse matrix
    targets : (n, d) array, or a list/tuple of them
        One shape (e.g. vertex coordinates of a pose) or several.

    Returns
    -------
    float for one target, ndarray of floats for a sequence.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> mesh = shapes.bumpy_sphere(3)
    >>> s = eigenbasis(mesh, 50)
    >>> e = reconstruction_error(s.vectors, s.mass, mesh.vertices)
    >>> bool(0 < e < 0.1)
    True
    """
    A = sp.csr_matrix(mass, dtype=np.float64)
    P = basis
    _check_a_orthonormal(P, A)
    many = isinstance(targets, (list, tuple))  # a sequence of shapes; an array is one shape
    errors = []
    for target in list(targets) if many else [targets]:
        Yc, _ = _centred(_as_columns(_TARGET.check(target, "target", {"mass": A})), A)
        residual = Yc - P @ (P.T @ (A @ Yc))
        num = float(np.einsum("ij,ij->", residual, A @ residual))
        den = float(np.einsum("ij,ij->", Yc, A @ Yc))
        if den <= 0:
            raise ValueError("a target is constant (zero after removing its centroid); its relative error is undefined.")
        errors.append(np.sqrt(max(num, 0.0) / den))
    return np.array(errors) if many else errors[0]


@validated(mass=_SQUARE_MASS, P=_SUBSPACE, Q=_SUBSPACE)
def principal_angles(P: ArrayLike, Q: ArrayLike, mass: sp.spmatrix) -> NDArray[np.float64]:
    """Principal angles (radians, ascending) between ``span P`` and ``span Q`` in the A inner product.

    Both are A-orthonormalised first. Equal spans give all angles ~0; the largest angle measures
    how far two bases are from spanning the same space.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(2), 4)
    >>> rotated = s.vectors @ np.linalg.qr(np.arange(16.0).reshape(4, 4) + np.eye(4))[0]
    >>> bool(principal_angles(s.vectors, rotated, s.mass).max() < 1e-6)
    True
    """
    A = sp.csr_matrix(mass, dtype=np.float64)
    Pa = a_orthonormalize(P, A, drop_dependent=True)
    Qa = a_orthonormalize(Q, A, drop_dependent=True)
    if Qa.shape[1] > Pa.shape[1]:
        Pa, Qa = Qa, Pa  # angles are symmetric; let Q be the smaller space
    k = Qa.shape[1]
    cos = np.clip(np.linalg.svd(Pa.T @ (A @ Qa), compute_uv=False), 0.0, 1.0)  # descending
    # arccos is inaccurate for small angles: take their sines from the residual of Q off span P.
    residual = Qa - Pa @ (Pa.T @ (A @ Qa))
    diag = A.diagonal()
    if abs(A - sp.diags(diag)).max() == 0:  # lumped mass: an exact square root
        sin = np.linalg.svd(np.sqrt(diag)[:, None] * residual, compute_uv=False)[::-1]
    else:
        g = residual.T @ (A @ residual)
        sin = np.sqrt(np.clip(np.linalg.eigvalsh((g + g.T) / 2), 0.0, None))
    sin = np.clip(np.sort(sin)[:k], 0.0, 1.0)  # ascending
    angles = np.where(cos > np.sqrt(0.5), np.arcsin(sin), np.arccos(cos))
    return np.sort(angles)
