"""Solver policy shared by every eigen- and linear solver of the package: one convention each.

* :data:`DENSE_LIMIT` and :func:`use_dense` — up to 600 unknowns a dense ``scipy.linalg.eigh``
  is exact and fast; above it the sparse (factorise-and-Lanczos) paths win;
* :func:`default_shift` — the shift of shift-invert, ``1e-2 * 4 pi / area``, which scales like
  the eigenvalues (so results do not depend on units), and :func:`max_shift`, the largest shift a
  caller may give (:data:`SHIFT_LIMIT` times a bound on the top of the spectrum);
* :func:`start_vector` — the fixed Lanczos start vector that makes ARPACK deterministic.

The A-inner-product algebra these solvers share is :mod:`lbo_notebooks.spectral._inner_product`.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..._support.validation import Options, validated

__all__ = ["DENSE_LIMIT", "SHIFT_LIMIT", "Method", "default_shift", "max_shift", "start_vector", "use_dense"]

#: Up to this many unknowns a dense ``scipy.linalg.eigh`` is exact and fast enough on a laptop;
#: above it the sparse (factorise-and-Lanczos) paths win. One limit for every solver.
DENSE_LIMIT = 600

Method = Literal["auto", "dense", "sparse"]

#: A caller's shift ``s`` (shift-invert at ``sigma = -s``) may be at most this many times the
#: Gershgorin bound on the top of the spectrum (:func:`max_shift`). Past the top, ``(W + s A)^{-1} A``
#: squeezes the whole spectrum into ``1 / (lam + s)`` ~ ``1 / s``: the smallest eigenvalues are no
#: better separated than in ``W`` itself, and ``lam = 1 / theta - s`` loses ``log10(s / lam)``
#: digits. On a 642-vertex icosphere (top 308) ARPACK dropped a copy of a 5-fold eigenvalue at
#: ``s = 100`` and ``1e4`` and lost its start vector at ``1e300``. Ten times the bound (about 14
#: times the top there) refuses only shifts that are nonsense, never one near the wanted eigenvalues.
SHIFT_LIMIT = 10.0


def default_shift(mass: sp.spmatrix) -> float:
    """Default shift ``s = 1e-2 * 4 pi / area`` for shift-invert at ``sigma = -s``.

    ``4 pi / S`` is 1 on the unit sphere, whose first nonzero eigenvalue is 2 (``8 pi / S``).
    The shift scales like the eigenvalues, so ``s / lam[1]`` does not depend on the units; it
    depends on the shape (0.005 on a round sphere, about 0.02 on a procedural dog). It keeps
    ``W + s A`` positive definite (``W`` alone is singular: constants are in its kernel). A
    ``ValueError`` when the total mass is not a positive number (zero, or overflowed).

    Examples
    --------
    >>> import numpy as np, scipy.sparse as sp
    >>> bool(np.isclose(default_shift(sp.identity(4) * np.pi), 1e-2))
    True
    """
    area = float(mass.sum())
    shift = 1e-2 * 4.0 * np.pi / area if np.isfinite(area) and area > 0 else 0.0
    if not (np.isfinite(shift) and shift > 0):
        raise ValueError(
            f"the mass matrix sums to {area:g}, so no default shift (1e-2 * 4 pi / area) exists: a mass matrix must "
            "have a positive, finite total. If it comes from a mesh, its coordinates are out of double precision's "
            "usable range (see lbo_notebooks.geometry._rescaling): rescale it to ordinary units."
        )
    return shift


def max_shift(stiffness: sp.spmatrix, mass: sp.spmatrix) -> float:
    """The largest shift ``s`` (shift-invert at ``sigma = -s``) worth taking: ``SHIFT_LIMIT`` times the top of the spectrum.

    The top is bounded by Gershgorin's ``max_i sum_j |W_ij| / A_ii`` (exact for a lumped mass, about
    0.85 times the top for the consistent one: the limit's factor covers both). In the units of the
    eigenvalues, like the shift; ``inf`` when ``W`` is zero (no spectrum to be above).

    Examples
    --------
    >>> import scipy.sparse as sp
    >>> W = sp.csr_matrix([[1.0, -1.0], [-1.0, 1.0]])  # eigenvalues 0 and 2 with A = I
    >>> float(max_shift(W, sp.identity(2)))  # 10 x (|1| + |-1|) / 1
    20.0
    """
    W, A = sp.csr_matrix(stiffness), sp.csr_matrix(mass)
    rows = np.asarray(abs(W).sum(axis=1)).ravel()
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        top = float(np.max(rows / A.diagonal())) if rows.size else 0.0
    return SHIFT_LIMIT * top if np.isfinite(top) and top > 0 else float("inf")


def start_vector(n: int) -> NDArray[np.float64]:
    """The fixed Lanczos start vector ``1 + cos(i) / 2``: makes ARPACK deterministic.

    It is positive (so never orthogonal to the constant function) and not constant (so it has
    a component along every eigenvector in practice).

    Examples
    --------
    >>> start_vector(3).round(3).tolist()
    [1.5, 1.27, 0.792]
    """
    return 1.0 + 0.5 * np.cos(np.arange(int(n), dtype=np.float64))


@validated(method=Options("auto", "dense", "sparse",
                          message="method must be 'auto', 'dense' or 'sparse', got {value!r}."))
def use_dense(n: int, method: str = "auto") -> bool:
    """The dense-or-sparse policy: ``method`` checked, ``"auto"`` is dense up to :data:`DENSE_LIMIT`.

    Examples
    --------
    >>> use_dense(100), use_dense(100_000), use_dense(100_000, "dense")
    (True, False, True)
    """
    return method == "dense" or (method == "auto" and n <= DENSE_LIMIT)
