"""Procedural surfaces generated in code: the package's embedded, network-free data.

Every function here is deterministic and returns a validated :class:`~lbo_notebooks.Mesh`.
The four-legged creatures and their poses live in :mod:`lbo_notebooks.shapes._creatures`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .._support.validation import Integer, Number, validated
from ..geometry._mesh import Mesh

__all__ = ["icosphere", "ellipsoid", "torus", "jittered_torus", "rectangle", "disk", "bumpy_sphere", "scan_like"]


_POSITIVE = Number(0, open_low=True, what="a positive finite number")


def _at_least(low: int) -> Integer:
    return Integer(low, what="an integer >= {low}")


def _icosahedron() -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    t = (1.0 + 5.0**0.5) / 2.0
    v = np.array(
        [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
         [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]],
        dtype=np.float64,
    )
    f = np.array(
        [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
         [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]],
        dtype=np.int64,
    )
    return v / np.linalg.norm(v, axis=1, keepdims=True), f


def _subdivide(v: NDArray[np.float64], f: NDArray[np.int64]) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Split every triangle into four at its edge midpoints, projecting new points to the sphere."""
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    e.sort(axis=1)
    edges, inverse = np.unique(e, axis=0, return_inverse=True)
    mid = v[edges[:, 0]] + v[edges[:, 1]]
    mid /= np.linalg.norm(mid, axis=1, keepdims=True)
    m = len(f)
    idx = len(v) + inverse.ravel()
    a, b, c = idx[:m], idx[m : 2 * m], idx[2 * m :]  # midpoints of edges 01, 12, 20
    new_faces = np.concatenate(
        [np.stack([f[:, 0], a, c], 1), np.stack([f[:, 1], b, a], 1), np.stack([f[:, 2], c, b], 1), np.stack([a, b, c], 1)]
    )
    return np.vstack([v, mid]), new_faces


@validated(subdivisions=Integer(0, 8), radius=_POSITIVE)
def icosphere(subdivisions: int = 3, radius: float = 1.0) -> Mesh:
    """A sphere made by subdividing an icosahedron: ``10 * 4**subdivisions + 2`` vertices.

    Examples
    --------
    >>> icosphere(5).n_vertices
    10242
    """
    v, f = _icosahedron()
    for _ in range(subdivisions):
        v, f = _subdivide(v, f)
    return Mesh(radius * v, f)


@validated(a=_POSITIVE, b=_POSITIVE, c=_POSITIVE)
def ellipsoid(a: float = 1.0, b: float = 0.7, c: float = 0.5, subdivisions: int = 4) -> Mesh:
    """An ellipsoid with semi-axes ``a, b, c``: an icosphere stretched along x, y, z.

    Examples
    --------
    >>> ellipsoid(2, 1, 1, subdivisions=2).bounding_box[1].round(6).tolist()
    [2.0, 1.0, 1.0]
    """
    axes = np.array([a, b, c])
    sphere = icosphere(subdivisions)
    return Mesh(sphere.vertices * axes, sphere.faces)


@validated(
    major_radius=_POSITIVE,
    minor_radius=(_POSITIVE, Number(high=lambda major_radius, **_: major_radius, open_high=True,
                                    message="minor_radius ({value}) must be smaller than major_radius ({high}) "
                                    "for a ring torus.")),
    n_major=_at_least(3),
    n_minor=_at_least(3),
)
def torus(major_radius: float = 1.0, minor_radius: float = 0.4, n_major: int = 64, n_minor: int = 24) -> Mesh:
    """A ring torus (genus 1) sampled on an ``n_major x n_minor`` periodic grid.

    Examples
    --------
    >>> torus(n_major=32, n_minor=12).euler_characteristic
    0
    """
    R, r, nu, nv = major_radius, minor_radius, n_major, n_minor
    u = 2 * np.pi * np.arange(nu) / nu
    w = 2 * np.pi * np.arange(nv) / nv
    U, V = np.meshgrid(u, w, indexing="ij")
    verts = np.stack([(R + r * np.cos(V)) * np.cos(U), (R + r * np.cos(V)) * np.sin(U), r * np.sin(V)], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    p00 = i * nv + j
    p10 = ((i + 1) % nu) * nv + j
    p01 = i * nv + (j + 1) % nv
    p11 = ((i + 1) % nu) * nv + (j + 1) % nv
    faces = np.concatenate([np.stack([p00, p10, p11], -1).reshape(-1, 3), np.stack([p00, p11, p01], -1).reshape(-1, 3)])
    return Mesh(verts, faces)


@validated(
    n_minor=Integer(3),
    jitter=Number(0, 1, open_high=True, what="in [0, 1) (a fraction of the grid step; 1 could fold triangles)"),
    major_radius=Number(),
    minor_radius=(Number(), Number(0, lambda major_radius, **_: major_radius, open_low=True, open_high=True,
                                   message="need 0 < minor_radius < major_radius, got {value} and {high}.")),
)
def jittered_torus(
    n_minor: int, jitter: float = 0.0, *, major_radius: float = 1.0, minor_radius: float = 0.4, seed: int = 0
) -> tuple[Mesh, NDArray[np.float64]]:
    """A torus whose vertices are moved at random *within* the surface, and its exact curvature.

    The grid has ``n_major = round(2.5 n_minor)`` columns (near-equilateral triangles). Each
    vertex's angles (u, v) are shifted by ``jitter`` times a uniform random fraction in
    [-1/2, 1/2] of the grid step, and the vertex is placed on the exact torus, so the surface is
    exact and only the triangulation is irregular. Returns the mesh and the true Gaussian
    curvature ``K = cos v / (r (R + r cos v))`` at every vertex: an oracle for how well angle
    defects measure ``|K|`` where it is small (near the top and bottom circles, ``cos v = 0``).

    Examples
    --------
    >>> mesh, K = jittered_torus(8, 0.5)
    >>> mesh.n_vertices, mesh.euler_characteristic, bool(np.isclose(K.max(), 1 / (0.4 * 1.4)))
    (160, 0, True)
    """
    R, r = major_radius, minor_radius
    nv, nu = n_minor, int(round(2.5 * n_minor))
    # the same (u-major, v-minor) vertex order and faces as torus
    faces = torus(R, r, nu, nv).faces
    rng = np.random.default_rng(seed)
    u = 2 * np.pi * (np.repeat(np.arange(nu), nv) + jitter * rng.uniform(-0.5, 0.5, nu * nv)) / nu
    v = 2 * np.pi * (np.tile(np.arange(nv), nu) + jitter * rng.uniform(-0.5, 0.5, nu * nv)) / nv
    ring = R + r * np.cos(v)
    vertices = np.column_stack([ring * np.cos(u), ring * np.sin(u), r * np.sin(v)])
    return Mesh(vertices, faces), np.cos(v) / (r * ring)


@validated(a=_POSITIVE, b=_POSITIVE, nx=_at_least(1), ny=_at_least(1))
def rectangle(a: float = 1.0, b: float = 1.0, nx: int = 10, ny: int = 10) -> Mesh:
    """The flat rectangle ``[0, a] x [0, b]`` (z = 0) as ``nx x ny`` cells, each split by one diagonal.

    Every cell is cut along the same diagonal, whose cotangent weight is then zero: ``W`` is the
    5-point stencil and the Neumann eigenvalues are known exactly (docs/maths.md, "Operators").

    Examples
    --------
    >>> m = rectangle(2.0, 1.0, 4, 2)
    >>> m.n_vertices, m.n_faces, m.area
    (15, 16, 2.0)
    """
    x = np.linspace(0.0, a, nx + 1)
    y = np.linspace(0.0, b, ny + 1)
    X, Y = np.meshgrid(x, y, indexing="ij")
    verts = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    p00 = i * (ny + 1) + j
    p10 = (i + 1) * (ny + 1) + j
    p01 = i * (ny + 1) + j + 1
    p11 = (i + 1) * (ny + 1) + j + 1
    faces = np.concatenate([np.stack([p00, p10, p11], -1).reshape(-1, 3), np.stack([p00, p11, p01], -1).reshape(-1, 3)])
    return Mesh(verts, faces)


@validated(radius=_POSITIVE, n_rings=_at_least(1))
def disk(radius: float = 1.0, n_rings: int = 16) -> Mesh:
    """A flat disk (z = 0) of near-equilateral triangles: ring ``i`` carries ``6 i`` vertices.

    Examples
    --------
    >>> disk(n_rings=4).n_vertices
    61
    """
    pts = [np.zeros((1, 2))]
    for i in range(1, n_rings + 1):
        t = 2 * np.pi * (np.arange(6 * i) / (6 * i)) + (0.5 * np.pi / (6 * i)) * (i % 2)
        pts.append((radius * i / n_rings) * np.stack([np.cos(t), np.sin(t)], axis=1))
    xy = np.concatenate(pts)
    from scipy.spatial import Delaunay

    faces = Delaunay(xy).simplices.astype(np.int64)
    p = xy[faces]
    cross = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 1, 1] - p[:, 0, 1]) * (p[:, 2, 0] - p[:, 0, 0])
    faces[cross < 0] = faces[cross < 0][:, [0, 2, 1]]
    faces = faces[np.lexsort(faces.T[::-1])]
    return Mesh(np.column_stack([xy, np.zeros(len(xy))]), faces)


@validated(n_bumps=_at_least(0), height=Number(-0.9, 2, open_low=True, open_high=True))
def bumpy_sphere(subdivisions: int = 4, n_bumps: int = 7, height: float = 0.35, seed: int = 0) -> Mesh:
    """A closed, genus-0, non-symmetric blob: an icosphere pushed out by Gaussian bumps.

    The bump centres, widths and heights come from ``numpy.random.default_rng(seed)``, so the
    same arguments give the same surface.

    Examples
    --------
    >>> m = bumpy_sphere(3)
    >>> m.n_vertices, m.euler_characteristic
    (642, 2)
    """
    rng = np.random.default_rng(seed)
    sphere = icosphere(subdivisions)
    u = sphere.vertices
    centres = rng.normal(size=(n_bumps, 3))
    centres /= np.linalg.norm(centres, axis=1, keepdims=True)
    widths = rng.uniform(0.35, 0.7, n_bumps)
    heights = height * rng.uniform(0.4, 1.0, n_bumps)
    d2 = ((u[:, None, :] - centres[None, :, :]) ** 2).sum(-1)
    radius = 1.0 + (heights * np.exp(-d2 / widths**2)).sum(axis=1)
    # A mild anisotropic stretch removes the remaining symmetry of the sphere.
    return Mesh(u * radius[:, None] * np.array([1.25, 1.0, 0.85]), sphere.faces)


@validated(subdivisions=Integer(0, 7), n_holes=_at_least(0))
def scan_like(subdivisions: int = 6, n_holes: int = 12, seed: int = 0) -> Mesh:
    """A mesh shaped like a raw scan's: three pieces, two of them holed spheres, one a torus.

    Two icospheres side by side, each with ``n_holes`` round holes (the faces whose centres lie
    within 0.12 of random unit directions from ``numpy.random.default_rng(seed)``), and a torus
    above them; vertices left without faces are dropped. At the default 6 subdivisions it has about
    100,000 vertices: a scan-sized input for loaders and benchmarks.

    Examples
    --------
    >>> m = scan_like(3, n_holes=4)
    >>> m.n_components, len(m.boundary_edges) > 0
    (3, True)
    """
    rng = np.random.default_rng(seed)
    sphere = icosphere(subdivisions)
    ring = max(8, 2 ** (subdivisions + 1))
    tube = torus(1.0, 0.3, n_major=int(1.25 * ring), n_minor=ring)
    centroids = sphere.vertices[sphere.faces].mean(axis=1)
    vertices, faces, offset = [], [], 0
    for shift in ([0.0, 0.0, 0.0], [3.0, 0.0, 0.0]):
        centres = rng.normal(size=(n_holes, 3))
        centres /= np.linalg.norm(centres, axis=1, keepdims=True)
        hole = (np.linalg.norm(centroids[:, None, :] - centres[None], axis=2) < 0.12).any(axis=1)
        vertices.append(sphere.vertices + shift)
        faces.append(sphere.faces[~hole] + offset)
        offset += sphere.n_vertices
    vertices.append(tube.vertices + [0.0, 3.0, 0.0])
    faces.append(tube.faces + offset)
    v, f = np.concatenate(vertices), np.concatenate(faces)
    used = np.zeros(len(v), dtype=bool)
    used[f.ravel()] = True
    return Mesh(v[used], (np.cumsum(used) - 1)[f])
