"""Products with the mass matrix that the eigensolver and the A-inner-product algebra share.

A lumped (diagonal) mass applied as a row scaling (:class:`DiagonalMass`, :func:`mass_operator`),
and the one-pass Cholesky QR refinement of a nearly A-orthonormal block (:func:`cholesky_qr`).
Kernels on arrays the library built: no argument checks here (the callers' tables check what a
user passes), so the engine can use them without standing on the checks.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

__all__ = ["DiagonalMass", "mass_operator", "cholesky_qr", "ROW_BLOCK"]

# Columns whose A-Gram matrix is this close to I are finished by one Cholesky QR pass.
_NEARLY_ORTHONORMAL = 1e-8


class DiagonalMass:
    """A diagonal (lumped) mass matrix applied as a row scaling: ``mass @ X`` keeps X's memory order.

    SciPy's sparse-times-dense product walks the rows in C order (copying a Fortran-ordered
    block first) and is several times slower than the scaling on tall blocks.

    Examples
    --------
    >>> import numpy as np
    >>> (DiagonalMass(np.array([2.0, 3.0])) @ np.ones(2)).tolist()
    [2.0, 3.0]
    """

    def __init__(self, diagonal: NDArray[np.float64]) -> None:
        self.diagonal = np.asarray(diagonal, dtype=np.float64)
        self.shape = (self.diagonal.size, self.diagonal.size)

    def __matmul__(self, X: ArrayLike) -> NDArray[np.float64]:
        X = np.asarray(X)
        return self.diagonal[:, None] * X if X.ndim == 2 else self.diagonal * X


def mass_operator(mass: sp.spmatrix) -> sp.spmatrix | DiagonalMass:
    """``mass`` ready for many products ``mass @ X``: a :class:`DiagonalMass` when it is diagonal, else itself.

    Examples
    --------
    >>> import numpy as np, scipy.sparse as sp
    >>> A = mass_operator(sp.diags([1.0, 2.0, 3.0]))
    >>> type(A).__name__, (A @ np.ones((3, 2))).tolist()
    ('DiagonalMass', [[1.0, 1.0], [2.0, 2.0], [3.0, 3.0]])
    """
    if isinstance(mass, DiagonalMass):
        return mass
    coo = sp.coo_matrix(mass)
    stored = coo.data != 0
    if np.array_equal(coo.row[stored], coo.col[stored]):
        return DiagonalMass(np.asarray(mass.diagonal(), dtype=np.float64))
    return mass


ROW_BLOCK = 4096  # row blocks of tall products: small temporaries, still BLAS-3


def cholesky_qr(
    vectors: NDArray[np.float64], mass: sp.spmatrix | DiagonalMass, *, out: NDArray[np.float64]
) -> NDArray[np.float64] | None:
    """``out = V L^-T`` with ``L L^T = V^T A V`` when ``V`` is A-orthonormal to ``1e-8``; else ``None``.

    The refinement of :func:`a_orthonormalize` (``refine=True``): one Cholesky QR pass, exact to
    round-off for nearly orthonormal input, all BLAS-3, column ``j`` mixing only columns
    ``0..j``. Row block by row block, so ``out`` may be ``vectors`` itself (an eigensolver's own
    output, refined without a second n x k array) and a lumped mass needs no n x k temporary.

    Examples
    --------
    >>> import numpy as np, scipy.sparse as sp
    >>> V = np.eye(4)[:, :2] * 0.5 * (1 + 1e-10)
    >>> Q = cholesky_qr(V, sp.identity(4) * 4.0, out=V)
    >>> bool(np.allclose(Q.T @ (4.0 * Q), np.eye(2), rtol=0, atol=1e-15)), Q is V
    (True, True)
    """
    n, k = vectors.shape
    mass = mass_operator(mass)
    if isinstance(mass, DiagonalMass):
        gram = np.zeros((k, k))
        for start in range(0, n, ROW_BLOCK):
            block = vectors[start : start + ROW_BLOCK]
            gram += block.T @ (mass.diagonal[start : start + ROW_BLOCK, None] * block)
    else:
        gram = vectors.T @ (mass @ vectors)
    gram = 0.5 * (gram + gram.T)
    if not np.abs(gram - np.eye(k)).max() < _NEARLY_ORTHONORMAL:
        return None
    # V @ L^-T as matrix products: much faster than solve(L, V.T) on tall blocks.
    inverse_t = np.linalg.inv(np.linalg.cholesky(gram)).T
    for start in range(0, n, ROW_BLOCK):
        out[start : start + ROW_BLOCK] = vectors[start : start + ROW_BLOCK] @ inverse_t
    return out
