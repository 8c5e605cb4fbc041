"""Shape distributions: comparing point sets (e.g. canonical forms) without a correspondence.

A shape distribution (Osada et al. 2002) is the histogram of all pairwise distances of a point set,
divided by their mean. It is invariant to rigid motions, reflections and uniform scaling, so two
canonical forms (:mod:`lbo_notebooks.analyses._mds`) of poses of one shape have nearly the same one, whatever
their vertex order or resolution.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Array, Integer, Number, Satisfies, validated

__all__ = ["shape_distribution", "shape_distribution_distances"]


@validated(
    bins=Integer(1),
    max_ratio=Number(0, open_low=True),
    points=(
        Array(2, cols_name="d", meaning="n points in d dimensions"),
        Satisfies(lambda P: P.shape[0] >= 2,
                  message=lambda name, P: f"a shape distribution needs at least two points, got {P.shape[0]}."),
    ),
)
def shape_distribution(points: ArrayLike, *, bins: int = 30, max_ratio: float = 3.0) -> NDArray[np.float64]:
    """Histogram (a density) of all pairwise Euclidean distances, divided by their mean.

    A *shape distribution* (Osada et al. 2002) of a point set: invariant to rigid motions, to
    reflections and - because distances are divided by their mean - to uniform scaling. Applied to
    canonical forms it compares shapes independently of pose, with no vertex correspondence.
    O(n^2) time, O(n^2) memory for the distances (use a few thousand points).

    Parameters
    ----------
    points : (n, d) array
        At least two points.
    bins : int, default 30
        Number of equal bins on ``[0, max_ratio]``.
    max_ratio : float, default 3.0
        Largest distance / mean distance counted (larger ones fall outside the histogram).

    Returns
    -------
    ndarray, shape (bins,)
        Density values: ``sum(h) * max_ratio / bins`` is the fraction of pairs within range.

    Examples
    --------
    >>> P = np.random.default_rng(0).normal(size=(200, 3))
    >>> h = shape_distribution(P)
    >>> bool(np.allclose(h, shape_distribution(-2.0 * P[:, ::-1] + 7.0)))
    True
    """
    from scipy.spatial.distance import pdist

    d = pdist(points)
    mean = d.mean()
    if mean <= 0:
        raise ValueError("all points coincide; their shape distribution is undefined.")
    counts, _ = np.histogram(d / mean, bins=int(bins), range=(0.0, float(max_ratio)))
    return counts / (d.size * float(max_ratio) / int(bins))


_POINT_SETS = "{name} must be a list of one or more (n, d) point arrays, got {value!r:.60}."


@validated(point_sets=(
    Satisfies(lambda sets: not isinstance(sets, (str, bytes)) and iter(sets) is not None, convert=list,
              message=_POINT_SETS),
    Satisfies(lambda sets: len(sets) >= 1, message=_POINT_SETS),
))
def shape_distribution_distances(point_sets: list[ArrayLike], **kwargs: Any) -> NDArray[np.float64]:
    """The L1 distances between the :func:`shape_distribution` of every pair of point sets.

    ``kwargs`` go to :func:`shape_distribution`. Returns a symmetric (s, s) matrix with a zero
    diagonal; the point sets may have different numbers of points.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> ball, line = rng.normal(size=(300, 3)), np.outer(np.linspace(0, 1, 300), [1.0, 2.0, 0.0])
    >>> D = shape_distribution_distances([ball, 3 * ball, line])
    >>> bool(D[0, 1] < 1e-12 < D[0, 2])
    True
    """
    H = np.array([shape_distribution(P, **kwargs) for P in point_sets])
    width = float(kwargs.get("max_ratio", 3.0)) / int(kwargs.get("bins", 30))
    return np.abs(H[:, None, :] - H[None, :, :]).sum(-1) * width
