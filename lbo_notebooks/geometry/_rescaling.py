"""Units: results must not depend on them, and coordinates must fit in double precision.

Scaling a shape by ``s`` multiplies its mass matrix by ``s^2`` and divides its eigenvalues by
``s^2``, exactly (docs/maths.md, "Units"). A solver whose convergence test has any absolute floor
breaks that: ARPACK's shift-invert run on a 642-vertex icosphere scaled by 1e-8 lost two copies
of a 5-fold eigenvalue, silently. This module is the one place where units are taken out and put
back:

* :func:`unit_area_exponent`: :func:`~lbo_notebooks.eigenbasis` solves every problem on a copy
  whose mass is divided by ``4**q``, the power of four nearest its total mass (so the copy has
  about unit area), and multiplies the eigenvalues by ``4**-q`` and the eigenvectors by ``2**-q``.
  Powers of two make both steps exact in floating point: the copy of a shape and of the shape
  scaled by a power of two are the same bits.
* :func:`length_exponent`: the point-cloud and tufted Laplacians (robust-laplacian) get their
  points divided by the power of two nearest the bounding-box diagonal, and their mass back
  multiplied by its square, so the library always sees a shape of about unit size.
* :func:`~lbo_notebooks.geometry._mesh.check_coordinate_range` (in :mod:`~lbo_notebooks.geometry._mesh`, beside
  the range it enforces): coordinates whose bounding-box diagonal lies outside
  :data:`USABLE_DIAGONAL` are refused with an error that says so and how to rescale, instead of
  being blamed on degenerate faces or coincident points (or crashing a library).

Examples
--------
>>> import numpy as np
>>> unit_area_exponent(np.array([1.0, 2.0]) * 4.0**10)  # total 3 * 4^10: nearest to 4^11 in the logarithm
11
>>> length_exponent(np.array([[0.0, 0, 0], [1e-3, 0, 0]]))  # 2^-10 = 0.00098 is nearest to 1e-3
-10
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ._mesh import USABLE_SIZE_RANGE, box_diagonal

__all__ = ["USABLE_DIAGONAL", "length_exponent", "unit_area_exponent"]

#: Bounding-box diagonals (in the data's own units) the package computes with: the one range that
#: :data:`lbo_notebooks.geometry._mesh.USABLE_SIZE_RANGE` sets for meshes, applied here to point clouds and
#: to the operators (a diagonal is at most sqrt(3) times the largest side, far inside the margin).
#: The cotangent operators square cross products of edge vectors, fourth powers of lengths, which
#: overflow or underflow double precision (about 1.8e308 and 2.2e-308) beyond about 1e+-77.
USABLE_DIAGONAL = USABLE_SIZE_RANGE


def length_exponent(points: ArrayLike) -> int:
    """The exponent ``e`` of the power of two ``2**e`` nearest the bounding-box diagonal of ``points`` (0 if it is 0).

    Dividing coordinates by ``2**e`` is exact in floating point and gives a shape of about unit size.
    """
    diagonal = box_diagonal(np.asarray(points, dtype=np.float64))
    if not (np.isfinite(diagonal) and diagonal > 0):
        return 0
    return int(np.round(np.log2(diagonal)))


def unit_area_exponent(mass_entries: ArrayLike) -> int:
    """The exponent ``q`` of the power of four ``4**q`` nearest (in the logarithm) the total of ``mass_entries`` (the area).

    ``mass_entries`` are the stored entries of a mass matrix (``mass.data``); their total is
    ``ones @ mass @ ones``, the area of the surface. It is computed without overflow or underflow.

    Raises
    ------
    ValueError
        When the entries are not finite or do not sum to a positive number.
    """
    entries = np.asarray(mass_entries, dtype=np.float64).ravel()
    peak = float(np.max(np.abs(entries))) if entries.size else 0.0
    if not np.isfinite(peak):
        raise ValueError("the mass matrix has NaN or inf entries; check the mesh (or rescale it to ordinary units).")
    total = float(np.sum(entries / peak)) if peak > 0 else 0.0
    if not total > 0:
        raise ValueError(
            "the mass matrix sums to zero or less, so the shape has no area; a mass matrix must be positive "
            "definite (check the mesh for degenerate faces, or rescale coordinates that underflow)."
        )
    return int(np.round((np.log2(peak) + np.log2(total)) / 2.0))
