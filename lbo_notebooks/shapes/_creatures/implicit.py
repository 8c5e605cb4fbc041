"""The creatures' implicit surface: a smooth union of round cones and ellipsoids.

The signed-distance-like field of each primitive, their smooth minimum along the skeleton, the
field sampled on a grid for marching cubes, and Newton projection of points onto its zero set.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .tables import Primitive, Species

# ------------------------------------------------------------------------------------------
# Implicit surface
# ------------------------------------------------------------------------------------------
_FAR = 10.0  # distance value used where a primitive is too far away to matter


def _rotation_matrices(rotvec: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rodrigues' formula for rotation vectors of shape (..., 3) -> matrices (..., 3, 3)."""
    rotvec = np.asarray(rotvec, dtype=np.float64)
    theta = np.linalg.norm(rotvec, axis=-1)
    safe = np.where(theta > 0, theta, 1.0)
    k = rotvec / safe[..., None]
    K = np.zeros(rotvec.shape[:-1] + (3, 3))
    K[..., 0, 1], K[..., 0, 2] = -k[..., 2], k[..., 1]
    K[..., 1, 0], K[..., 1, 2] = k[..., 2], -k[..., 0]
    K[..., 2, 0], K[..., 2, 1] = -k[..., 1], k[..., 0]
    s, c = np.sin(theta)[..., None, None], np.cos(theta)[..., None, None]
    return np.eye(3) + s * K + (1 - c) * (K @ K)


def primitive_distance(prim: Primitive, p: NDArray[np.float64]) -> NDArray[np.float64]:
    """Signed distance (exact for round cones, first-order for ellipsoids) of points p (N, 3)."""
    if prim.kind == "ellipsoid":
        R = _rotation_matrices(np.array(prim.tilt))
        q = (p - np.array(prim.a)) @ R  # coordinates in the ellipsoid's frame
        r = np.array(prim.radii)
        k0 = np.linalg.norm(q / r, axis=1)
        k1 = np.maximum(np.linalg.norm(q / r**2, axis=1), 1e-12)
        return k0 * (k0 - 1.0) / k1
    squash = np.array([1.0, prim.squash, 1.0])
    a, b = np.array(prim.a) / squash, np.array(prim.b) / squash
    q = p / squash - a
    length = float(np.linalg.norm(b - a))
    u = (b - a) / length
    y = q @ u
    x = np.sqrt(np.maximum(np.einsum("ij,ij->i", q, q) - y * y, 0.0))
    s = (prim.ra - prim.rb) / length
    c = np.sqrt(1.0 - s * s)
    along = -x * s + y * c  # position along the tangent line of the cone's side
    d = x * c + y * s - prim.ra
    d = np.where(along < 0.0, np.sqrt(x * x + y * y) - prim.ra, d)
    d = np.where(along > length * c, np.sqrt(x * x + (y - length) ** 2) - prim.rb, d)
    return d * (0.5 * (1.0 + prim.squash))


def _primitive_box(prim: Primitive, margin: float) -> NDArray[np.float64]:
    """Axis-aligned bounding box (2, 3) of a primitive, grown by ``margin``."""
    if prim.kind == "ellipsoid":
        r = max(prim.radii)
        lo, hi = np.array(prim.a) - r, np.array(prim.a) + r
    else:
        r = max(prim.ra, prim.rb)
        lo = np.minimum(prim.a, prim.b) - r
        hi = np.maximum(prim.a, prim.b) + r
    return np.stack([lo - margin, hi + margin])


def _smooth_min(a: NDArray[np.float64], b: NDArray[np.float64], k: float) -> NDArray[np.float64]:
    """C2 polynomial smooth minimum: equals min(a, b) where |a - b| >= k."""
    h = np.maximum(k - np.abs(a - b), 0.0) / k
    return np.minimum(a, b) - h**3 * (k / 6.0)


def _combine(spec: Species, distances: list[NDArray[np.float64]]) -> NDArray[np.float64]:
    """Blend primitive distances bottom-up: a node joins each child subtree with its own radius."""
    prims = spec.primitives
    subtree: dict[int, NDArray[np.float64]] = {}
    for i in range(len(prims) - 1, -1, -1):
        own = distances[i]
        children = [c for c in range(i + 1, len(prims)) if prims[c].parent == i]
        value = own
        for c in children:
            value = np.minimum(value, _smooth_min(own, subtree.pop(c), prims[c].blend))
        subtree[i] = value
    return subtree[0]


def _field(spec: Species, p: NDArray[np.float64]) -> NDArray[np.float64]:
    """The creature's implicit function at points p (N, 3): negative inside."""
    margin = max(pr.blend for pr in spec.primitives) + 0.02
    distances = []
    for prim in spec.primitives:
        lo, hi = _primitive_box(prim, margin)
        inside = np.all((p >= lo) & (p <= hi), axis=1)
        d = np.full(len(p), _FAR)
        d[inside] = primitive_distance(prim, p[inside])
        distances.append(d)
    return _combine(spec, distances)


def field_on_grid(spec: Species) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Sample the implicit function on a regular grid; returns (values (nx, ny, nz), origin).

    The function is first sampled on a grid four times coarser; fine grid points whose nearest
    coarse value is far from zero only need the sign (the function grows at most about as fast
    as the distance), so the exact evaluation is limited to a shell around the surface.
    """
    h = spec.spacing
    boxes = np.array([_primitive_box(pr, 0.0) for pr in spec.primitives])
    origin = boxes[:, 0].min(axis=0) - 3 * h
    shape = np.ceil((boxes[:, 1].max(axis=0) + 3 * h - origin) / h).astype(int) + 1
    axes = [origin[k] + h * np.arange(shape[k]) for k in range(3)]
    step = 4
    coarse_axes = [a[::step] for a in axes]
    coarse_grid = np.meshgrid(*coarse_axes, indexing="ij")
    coarse = _field(spec, np.stack([g.ravel() for g in coarse_grid], axis=1)).reshape(coarse_grid[0].shape)
    nearest = [np.minimum(np.rint(np.arange(shape[k]) / step).astype(int), len(coarse_axes[k]) - 1) for k in range(3)]
    upsampled = coarse[np.ix_(*nearest)]
    values = np.where(upsampled > 0, _FAR, -_FAR)
    shell = np.abs(upsampled) < 2.0 * step * h
    index = np.nonzero(shell)
    points = np.stack([axes[k][index[k]] for k in range(3)], axis=1)
    values[index] = _field(spec, points)
    return values, origin


def project_to_surface(spec: Species, p: NDArray[np.float64], iterations: int = 3) -> NDArray[np.float64]:
    """Newton steps ``p -= F grad F / |grad F|^2`` onto the zero level set (finite-difference gradient)."""
    eps = 1e-5
    offsets = np.vstack([np.eye(3), -np.eye(3)]) * eps
    p = p.copy()
    for _ in range(iterations):
        stacked = np.concatenate([p] + [p + o for o in offsets])
        values = _field(spec, stacked).reshape(7, len(p))
        grad = (values[1:4] - values[4:7]).T / (2 * eps)
        g2 = np.maximum(np.einsum("ij,ij->i", grad, grad), 1e-12)
        step = (values[0] / g2)[:, None] * grad
        # Never move more than a fraction of the grid spacing (guards against creases).
        norm = np.linalg.norm(step, axis=1, keepdims=True)
        p -= step * np.minimum(1.0, spec.spacing / np.maximum(norm, 1e-300))
    return p

