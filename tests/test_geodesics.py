"""Geodesic distances against analytic oracles (great circles, straight lines) and FPS properties."""

from __future__ import annotations

import numpy as np
import pytest

from lbo_notebooks import Mesh, MeshError, shapes
from lbo_notebooks.analyses import farthest_point_sampling, geodesic_distances


def great_circle(mesh: Mesh, sources: list[int]) -> np.ndarray:
    v = mesh.vertices / np.linalg.norm(mesh.vertices, axis=1, keepdims=True)
    return np.arccos(np.clip(v[sources] @ v.T, -1.0, 1.0))


@pytest.fixture(scope="module")
def sphere3() -> Mesh:
    return shapes.icosphere(3)


@pytest.fixture(scope="module")
def two_spheres() -> Mesh:
    a = shapes.icosphere(1)
    return Mesh(np.vstack([a.vertices, a.vertices + 3.0]), np.vstack([a.faces, a.faces + a.n_vertices]))


# --- accuracy ----------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "method, max_tol, mean_tol",
    # Measured on icosphere(3) (642 vertices, h ~ 0.1): exact 0.0085 / 0.0036 (the polyhedron is
    # not the sphere), heat 0.051 / 0.022, fast marching 0.044 / 0.023.
    [("exact", 0.012, 0.005), ("heat", 0.07, 0.03), ("fmm", 0.06, 0.03)],
)
def test_sphere_matches_great_circles(sphere3, method, max_tol, mean_tol):
    src = [0, 17, 400]
    err = np.abs(geodesic_distances(sphere3, src, method) - great_circle(sphere3, src))
    assert err.max() < max_tol and err.mean() < mean_tol


@pytest.mark.parametrize("method, rate", [("exact", 3.0), ("heat", 1.5)])
def test_sphere_error_shrinks_with_refinement(method, rate):
    # exact polyhedral distances converge as O(h^2) to the sphere's, the heat method about O(h)
    errs = []
    for sub in (2, 3):
        m = shapes.icosphere(sub)
        errs.append(np.abs(geodesic_distances(m, [0, 5], method) - great_circle(m, [0, 5])).mean())
    assert errs[0] / errs[1] > rate


def test_exact_is_euclidean_on_a_flat_convex_domain():
    # On a flat convex polygon every geodesic is a straight segment: an exact oracle.
    m = shapes.rectangle(2.0, 1.0, 12, 7)
    src = [0, 40, m.n_vertices - 1]
    d = geodesic_distances(m, src, "exact")
    euclid = np.linalg.norm(m.vertices[src][:, None, :] - m.vertices[None, :, :], axis=2)
    assert np.abs(d - euclid).max() < 1e-9 * euclid.max()
    heat = geodesic_distances(m, src, "heat")
    assert np.abs(heat - euclid).max() < 0.1 * m.diagonal


def test_exact_distances_are_symmetric_and_zero_at_sources(sphere3):
    src = [3, 50, 211]
    d = geodesic_distances(sphere3, src, "exact")
    block = d[:, src]
    assert np.allclose(block, block.T, rtol=0, atol=1e-10 * block.max())
    assert np.all(np.diag(block) == 0) and np.all(d >= 0)


def test_scalar_source_gives_one_row(sphere3):
    d = geodesic_distances(sphere3, 7)
    assert d.shape == (1, sphere3.n_vertices)


def test_solver_is_cached_and_reused(monkeypatch):
    from lbo_notebooks.analyses import _geodesics as geodesics

    mesh = shapes.icosphere(2)
    built = []
    original = geodesics.GeodesicSolver.__init__

    def counting(self, *args, **kwargs):
        built.append(1)
        original(self, *args, **kwargs)

    monkeypatch.setattr(geodesics.GeodesicSolver, "__init__", counting)
    geodesic_distances(mesh, [0])
    geodesic_distances(mesh, [1, 2])
    assert len(built) == 1  # one factorisation serves every call on this mesh
    assert geodesics.geodesic_solver(mesh, "heat") is geodesics.geodesic_solver(mesh, "heat")
    geodesic_distances(mesh.with_vertices(2.0 * mesh.vertices), [0])
    assert len(built) == 2  # a new mesh gets its own solver


def test_rigid_motion_invariance(sphere3):
    rng = np.random.default_rng(3)
    Q = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    moved = sphere3.with_vertices(sphere3.vertices @ Q.T + 2.0)
    assert np.allclose(geodesic_distances(moved, [0, 9]), geodesic_distances(sphere3, [0, 9]), atol=1e-8)


# --- errors ------------------------------------------------------------------------------------
@pytest.mark.parametrize("bad", [642, -1, [0, 700], 1.5, [], [[0, 1]], [True]])
def test_bad_sources(sphere3, bad):
    with pytest.raises(ValueError, match="source"):
        geodesic_distances(sphere3, bad)


def test_bad_method(sphere3):
    with pytest.raises(ValueError, match="method must be one of"):
        geodesic_distances(sphere3, [0], method="dijkstra")


def test_disconnected_mesh_is_refused_with_a_fix(two_spheres):
    with pytest.raises(MeshError, match="2 connected components.*keep_largest_component"):
        geodesic_distances(two_spheres, [0])
    with pytest.raises(MeshError, match="connected"):
        farthest_point_sampling(two_spheres, 3)


def test_memory_budget_is_enforced(sphere3):
    with pytest.raises(MemoryError, match=r"needs 0\.00 GiB"):
        geodesic_distances(sphere3, np.arange(10), memory_budget=1000)


def test_sources_array_not_modified(sphere3):
    src = np.array([5, 0, 5])
    geodesic_distances(sphere3, src)
    assert src.tolist() == [5, 0, 5]


# --- farthest-point sampling -------------------------------------------------------------------
def test_fps_is_nested_distinct_and_starts_at_start(sphere3):
    s8, d8 = farthest_point_sampling(sphere3, 8, start=11, return_distances=True)
    s3 = farthest_point_sampling(sphere3, 3, start=11)
    assert s8[0] == 11 and len(set(s8.tolist())) == 8
    assert np.array_equal(s8[:3], s3)
    assert d8.shape == (8, sphere3.n_vertices) and np.all(d8[np.arange(8), s8] == 0)


def test_fps_picks_the_farthest_vertex(sphere3):
    s, d = farthest_point_sampling(sphere3, 5, method="exact", return_distances=True)
    # the second sample is the antipode of the first on a sphere
    assert np.linalg.norm(sphere3.vertices[s[0]] + sphere3.vertices[s[1]]) < 1e-9
    # every later sample maximises the distance to the earlier ones
    for i in range(1, 5):
        nearest = d[:i].min(axis=0)
        assert nearest[s[i]] == pytest.approx(nearest.max())


def test_fps_covers_evenly(sphere3):
    # 50 samples on the unit sphere: covering radius close to the ideal sqrt(4 pi / (50 pi)) ~ 0.28
    _, d = farthest_point_sampling(sphere3, 50, return_distances=True)
    radius = d.min(axis=0).max()
    assert 0.2 < radius < 0.5


@pytest.mark.parametrize("count", [0, 643, 2.0, True])
def test_fps_bad_count(sphere3, count):
    with pytest.raises(ValueError, match="k must be an integer between 1 and"):
        farthest_point_sampling(sphere3, count)


def test_fps_bad_start(sphere3):
    with pytest.raises(ValueError, match="out of range"):
        farthest_point_sampling(sphere3, 3, start=9999)
