"""Hypothesis strategies for random valid triangle meshes (shared by the test modules)."""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st
from scipy.spatial import ConvexHull

from lbo_notebooks import Mesh, shapes


def convex_hull_mesh(seed: int, n_points: int) -> Mesh:
    """A closed genus-0 mesh: the convex hull of random points on an anisotropic sphere."""
    rng = np.random.default_rng(seed)
    p = rng.normal(size=(n_points, 3))
    p /= np.linalg.norm(p, axis=1, keepdims=True)
    p *= rng.uniform(0.5, 2.0, size=3)
    hull = ConvexHull(p)
    faces = hull.simplices.copy()
    centre = p.mean(axis=0)
    normals = np.cross(p[faces[:, 1]] - p[faces[:, 0]], p[faces[:, 2]] - p[faces[:, 0]])
    outward = np.einsum("ij,ij->i", normals, p[faces[:, 0]] - centre) > 0
    faces[~outward] = faces[~outward][:, [0, 2, 1]]
    used = np.unique(faces)
    remap = np.full(len(p), -1)
    remap[used] = np.arange(used.size)
    return Mesh(p[used], remap[faces])


def wavy_sheet(seed: int, nx: int, ny: int) -> Mesh:
    """An open mesh with boundary: a rectangle with random smooth height and jittered vertices."""
    rng = np.random.default_rng(seed)
    base = shapes.rectangle(rng.uniform(0.5, 3.0), rng.uniform(0.5, 3.0), nx, ny)
    v = base.vertices.copy()
    h = min(v[:, 0].max() / nx, v[:, 1].max() / ny)
    v[:, :2] += rng.uniform(-0.2, 0.2, size=(len(v), 2)) * h
    a, b = rng.normal(size=2)
    v[:, 2] = 0.3 * np.sin(a * v[:, 0] + b * v[:, 1])
    return Mesh(v, base.faces)


@st.composite
def random_meshes(draw: st.DrawFn) -> Mesh:
    seed = draw(st.integers(0, 2**31 - 1))
    if draw(st.booleans()):
        return convex_hull_mesh(seed, draw(st.integers(8, 80)))
    return wavy_sheet(seed, draw(st.integers(2, 9)), draw(st.integers(2, 9)))


def corrupted_copies(source: bytes, rng: np.random.Generator, count: int = 24):
    """``count`` damaged copies of a file's bytes, in turn truncated, overwritten or padded."""
    for k in range(count):
        data = bytearray(source)
        if k % 3 == 0:
            data = data[: rng.integers(len(data))]
        elif k % 3 == 1:
            for _ in range(rng.integers(1, 8)):
                data[rng.integers(len(data))] = rng.integers(256)
        else:
            at = rng.integers(len(data))
            data[at:at] = bytes(rng.integers(0, 256, rng.integers(1, 20), dtype=np.uint8))
        yield k, bytes(data)
