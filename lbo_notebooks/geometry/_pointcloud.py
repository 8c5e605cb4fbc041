"""The :class:`PointCloud` value type: samples of a surface without triangles.

A point cloud gets a Laplace–Beltrami operator through
:func:`~lbo_notebooks.operators.point_cloud_operators`, so ``lbo.eigenbasis(cloud, k)`` returns the
same :class:`~lbo_notebooks.Spectrum` (``project``, ``reconstruct``, ``error``) as for a mesh.
"""

from __future__ import annotations

import hashlib
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._mesh import MeshError, check_coordinate_range, real_coordinates

__all__ = ["PointCloud", "MIN_POINTS", "LINE_TOLERANCE"]

#: A local triangulation of each point's neighbours needs a handful of points at least.
MIN_POINTS = 5

#: Points whose spread across their best-fitting line is below this fraction of their spread along
#: it lie on a line: no surface, and robust-laplacian crashes on them (measured: a cloud 1e-10 of
#: its length thick did, 1e-6 did not).
LINE_TOLERANCE = 1e-8


class PointCloud:
    """An immutable point cloud: ``points`` (n, 3) float64, finite and pairwise distinct.

    Parameters
    ----------
    points : array_like, shape (n, 3)
        Positions; copied, the caller's array is never modified. Extra columns (normals,
        colours) must be dropped first: ``PointCloud(data[:, :3])``.

    Raises
    ------
    MeshError
        For NaN/inf coordinates, repeated points, fewer than :data:`MIN_POINTS` points, a wrong
        shape, points that all lie on one line (within :data:`LINE_TOLERANCE`), or coordinates
        out of the usable range (:func:`~lbo_notebooks.geometry._mesh.check_coordinate_range`); the
        message names the problem and the fix.

    Examples
    --------
    >>> cloud = PointCloud([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]])
    >>> cloud.n_points, round(cloud.diagonal, 4)
    (5, 1.7321)
    """

    __slots__ = ("_points", "_cache")

    def __init__(self, points: ArrayLike) -> None:
        p = real_coordinates(points, "points")  # complex input is refused, not cut to its real part
        if p.ndim != 2 or p.shape[1] != 3:
            raise MeshError(
                f"points must have shape (n, 3), got {p.shape}; pass one xyz row per point "
                "(drop extra columns such as normals with points[:, :3])."
            )
        if p.shape[0] < MIN_POINTS:
            raise MeshError(f"a point cloud needs at least {MIN_POINTS} points for a Laplacian, got {p.shape[0]}.")
        bad = np.flatnonzero(~np.isfinite(p).all(axis=1))
        if bad.size:
            raise MeshError(
                f"{bad.size} points have non-finite (NaN or inf) coordinates (first: point {bad[0]}); "
                "drop them, e.g. points[np.isfinite(points).all(axis=1)], or load with load_points(path, clean=True)."
            )
        _, first, counts = np.unique(p, axis=0, return_index=True, return_counts=True)
        if np.any(counts > 1):
            dup = int(np.sort(first[counts > 1])[0])
            raise MeshError(
                f"{int((counts - 1).sum())} points repeat an earlier point exactly (first repeated: point {dup}); "
                "coincident points have no local surface. Drop them, e.g. np.unique(points, axis=0), "
                "or load with load_points(path, clean=True)."
            )
        check_coordinate_range(p, "point cloud")
        _check_not_on_a_line(p)
        p.setflags(write=False)
        object.__setattr__(self, "_points", p)
        object.__setattr__(self, "_cache", {})

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("PointCloud is immutable; build a new one.")

    @property
    def points(self) -> NDArray[np.float64]:
        """Positions, shape (n, 3), read-only."""
        return self._points

    @property
    def n_points(self) -> int:
        return int(self._points.shape[0])

    @property
    def bounding_box(self) -> NDArray[np.float64]:
        """Axis-aligned bounding box as a (2, 3) array: row 0 the minimum, row 1 the maximum."""
        return np.stack([self._points.min(axis=0), self._points.max(axis=0)])

    @property
    def diagonal(self) -> float:
        """Length of the bounding-box diagonal (a scale for tolerances)."""
        lo, hi = self.bounding_box
        return float(np.linalg.norm(hi - lo))

    def cached(self, key: str, compute: Any) -> Any:
        """Return ``compute(self)`` computed once per cloud and stored under ``key``."""
        if key not in self._cache:
            self._cache[key] = compute(self)
        return self._cache[key]

    def clear_cache(self) -> None:
        """Drop the operators computed from this cloud and kept on it; later calls recompute them."""
        self._cache.clear()

    def __len__(self) -> int:
        return self.n_points

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, PointCloud):
            return NotImplemented
        return np.array_equal(self._points, other._points)

    def __hash__(self) -> int:
        return int.from_bytes(hashlib.sha1(self._points.tobytes()).digest()[:8], "little")

    def __repr__(self) -> str:
        return f"PointCloud(n_points={self.n_points}, diagonal={self.diagonal:.4g})"


def _check_not_on_a_line(p: NDArray[np.float64]) -> None:
    """Raise :class:`MeshError` when all points lie on one straight line (within :data:`LINE_TOLERANCE`)."""
    centred = p - p.mean(axis=0)
    centred /= np.abs(centred).max()  # finite and > 0: the coordinates are in range and not all equal
    spread = np.linalg.svd(np.linalg.qr(centred, mode="r"), compute_uv=False)  # descending, from a 3 x 3 R
    if spread[1] <= LINE_TOLERANCE * spread[0]:
        raise MeshError(
            f"all {p.shape[0]} points lie on one straight line (their spread across it is "
            f"{spread[1] / spread[0]:.1e} of their spread along it): a point cloud must sample a surface for a "
            "Laplace-Beltrami operator. Check that the x, y, z columns are the right ones."
        )
