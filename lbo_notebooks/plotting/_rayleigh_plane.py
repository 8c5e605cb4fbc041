"""Teaching helpers: small pictures made for one lesson, kept out of the library's algorithms.

The min–max principle in three dimensions (notebook 05): for a symmetric 3 x 3 matrix ``M`` the
Rayleigh quotient ``x.T M x`` on the unit sphere, a plane through the origin (a subspace of
codimension 1) and its minimum on that plane. :func:`plane_normal` turns the plane away from the
optimal one, :func:`plane_circle` gives what the figure draws
(:func:`~lbo_notebooks.plotting.rayleigh_sphere_figure`, :func:`~lbo_notebooks.plotting.plane_slider`).
On a plane the minimum is a 2 x 2 eigenproblem, solved here by hand;
:func:`~lbo_notebooks.analyses.min_rayleigh_quotient` is the general computation (tests check that
both agree).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Array, Satisfies, validated
from ..spectral._inner_product import fix_signs

__all__ = ["MATRIX", "NORMAL", "OPTIONAL_NORMAL", "plane_normal", "symmetric_3x3", "plane_circle"]

#: The rule for ``matrix``: a finite symmetric 3 x 3 array (given to the body as float64).
MATRIX = (
    Array(2, rows=3, cols=3, meaning="a finite symmetric 3 x 3 array"),
    Satisfies(lambda M: np.allclose(M, M.T),
              message="{name} must be a finite symmetric 3 x 3 array; it is not symmetric (M != M.T)."),
)


def _is_normal(normal: ArrayLike) -> bool:
    n = np.asarray(normal, dtype=np.float64)
    return bool(n.shape == (3,) and np.all(np.isfinite(n)) and np.any(n))


#: The rule for a plane's ``normal``: a finite nonzero 3-vector (``OPTIONAL_NORMAL``: or None).
NORMAL = Satisfies(_is_normal, message="{name} must be a finite nonzero 3-vector, got {value!r}.")
OPTIONAL_NORMAL = Satisfies(_is_normal, message="{name} must be a finite nonzero 3-vector or None, got {value!r}.",
                            none=True)


@validated(matrix=MATRIX)
def plane_normal(matrix: ArrayLike, angle: float) -> NDArray[np.float64]:
    """Unit normal of a plane through the origin of R^3, rotated by ``angle`` degrees.

    At 0 the plane is orthogonal to the first eigenvector ``v0`` of the symmetric 3 x 3 ``matrix``
    (eigenvalues ``lam_0 <= lam_1 <= lam_2``, indices from 0; an optimal plane of Courant–Fischer,
    minimum quotient ``lam_1``); the normal then turns towards ``(v1 + v2) / sqrt(2)``, reaching it
    at 90 degrees.

    Examples
    --------
    >>> import numpy as np
    >>> plane_normal(np.diag([1.0, 2.0, 4.0]), 0.0).round(12).tolist()
    [1.0, 0.0, 0.0]
    """
    _, vec = np.linalg.eigh(matrix)
    vec = fix_signs(vec)
    t = np.deg2rad(float(angle))
    return np.cos(t) * vec[:, 0] + np.sin(t) * (vec[:, 1] + vec[:, 2]) / np.sqrt(2.0)


@validated(matrix=MATRIX)
def symmetric_3x3(matrix: ArrayLike) -> NDArray[np.float64]:
    """``matrix`` as a float array, checked to be a finite symmetric 3 x 3 matrix.

    Examples
    --------
    >>> symmetric_3x3(np.eye(3)).shape
    (3, 3)
    """
    return matrix


@validated(matrix=MATRIX, normal=NORMAL)
def plane_circle(matrix: ArrayLike, normal: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """The plane ``{x : normal . x = 0}`` on the unit sphere and its Rayleigh-quotient minimum.

    Returns the great circle (200 points), the minimiser (just off the sphere, for drawing) and
    the minimum value of ``x.T M x`` on the circle.

    Examples
    --------
    >>> circle, point, value = plane_circle(np.diag([1.0, 2.0, 4.0]), [1.0, 0.0, 0.0])
    >>> circle.shape, round(value, 12)
    ((200, 3), 2.0)
    """
    M = matrix
    nrm = np.asarray(normal, dtype=np.float64)
    nrm = nrm / np.linalg.norm(nrm)
    # The Rayleigh quotient restricted to the plane: a 2 x 2 eigenproblem in an orthonormal basis Z
    # of the plane (what minmax.min_rayleigh_quotient does for any codimension, here by hand).
    Z = scipy.linalg.null_space(nrm[None, :])
    values, vectors = scipy.linalg.eigh(Z.T @ M @ Z, Z.T @ Z, subset_by_index=[0, 0])
    value, point = float(values[0]), fix_signs(Z @ vectors[:, 0] / np.linalg.norm(Z @ vectors[:, 0]))
    e1 = point / np.linalg.norm(point)
    e2 = np.cross(nrm, e1)
    t = np.linspace(0, 2 * np.pi, 200)
    return np.outer(np.cos(t), e1) + np.outer(np.sin(t), e2), 1.01 * e1, value
