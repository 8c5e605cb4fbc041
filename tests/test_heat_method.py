"""The batched heat method: operator identities, exact oracles, batch = one at a time."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from lbo_notebooks import Mesh, MeshError, shapes
from lbo_notebooks.analyses import GeodesicSolver, farthest_point_sampling, geodesic_distances
from lbo_notebooks.analyses._heat_method import HeatMethod, face_gradient_operator, solve_poisson
from lbo_notebooks.operators import stiffness_matrix


@pytest.fixture(scope="module")
def bumpy() -> Mesh:
    return shapes.bumpy_sphere(3)


def test_gradient_is_exact_on_linear_functions(bumpy):
    G, areas = face_gradient_operator(bumpy)
    direction = np.array([0.3, -1.2, 0.7])
    g = (G @ (bumpy.vertices @ direction)).reshape(3, -1).T
    # on each face the gradient is the direction's component in the face's plane
    normals = np.cross(*(bumpy.vertices[bumpy.faces[:, i]] - bumpy.vertices[bumpy.faces[:, 0]] for i in (1, 2)))
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    tangent = direction - (normals @ direction)[:, None] * normals
    assert np.abs(g - tangent).max() < 1e-10 * np.linalg.norm(direction)
    assert np.allclose(areas, bumpy.face_areas, rtol=1e-12)


def test_gradient_operator_gives_the_cotangent_stiffness(bumpy):
    G, areas = face_gradient_operator(bumpy)
    W = G.T @ sp.diags(np.tile(areas, 3)) @ G
    reference = stiffness_matrix(bumpy)
    assert abs(W - reference).max() < 1e-12 * abs(reference).max()


def test_zero_area_face_gets_zero_gradient():
    m = Mesh([[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 1, 0]], [[0, 1, 3], [0, 1, 2]], check=False)
    G, areas = face_gradient_operator(m)
    assert areas[1] == 0 and np.all(np.isfinite(G.data)) and abs(G[[1, 3, 5]]).max() == 0


def test_poisson_solution_and_pinned_vertex(bumpy):
    rng = np.random.default_rng(0)
    b = rng.standard_normal((bumpy.n_vertices, 3))
    b -= b.mean(axis=0)
    phi = solve_poisson(bumpy, b)
    W = stiffness_matrix(bumpy)
    assert np.abs(W @ phi - b).max() < 1e-10 * np.abs(b).max()
    assert np.all(phi[0] == 0)
    assert np.allclose(solve_poisson(bumpy, b[:, 1]), phi[:, 1], rtol=0, atol=1e-12 * np.abs(phi).max())


def test_large_meshes_share_one_metis_order_between_poisson_and_eigenbasis(monkeypatch):
    # On a large mesh (22k vertices) the pinned Poisson matrix takes the mesh's cached METIS order
    # (vertex 0 dropped), which eigenbasis reuses; the intrinsic Delaunay heat matrix, whose
    # flipped edges cross that order's separators, gets its own.
    import lbo_notebooks.spectral._engine.factor as sparse_factor
    from lbo_notebooks import eigenbasis
    from lbo_notebooks.spectral import _solvers as solvers

    calls = []
    original = sparse_factor.fill_reducing_order
    counted = lambda matrix: calls.append(1) or original(matrix)  # noqa: E731
    monkeypatch.setattr(sparse_factor, "fill_reducing_order", counted)  # the factorisation's own order
    monkeypatch.setattr(solvers, "fill_reducing_order", counted)  # the mesh's order
    torus = shapes.torus(1.0, 0.4, 200, 110)
    rng = np.random.default_rng(1)
    b = rng.standard_normal((torus.n_vertices, 2))
    b -= b.mean(axis=0)
    phi = solve_poisson(torus, b)
    assert np.abs(stiffness_matrix(torus) @ phi - b).max() < 1e-10 * np.abs(b).max()
    HeatMethod(torus).distances([0])
    eigenbasis(torus, 100, solver="slicing")
    assert len(calls) == 2  # the mesh's order (Poisson, eigenbasis) and the heat matrix's


def test_sphere_distances_match_great_circles():
    sphere = shapes.icosphere(4)
    v = sphere.vertices / np.linalg.norm(sphere.vertices, axis=1, keepdims=True)
    src = [0, 17, 400]
    exact = np.arccos(np.clip(v[src] @ v.T, -1, 1))
    d = HeatMethod(sphere).distances(np.array(src))
    # Measured 0.034 max, 0.014 mean on icosphere(4) (h ~ 0.05); exact polyhedral geodesics are
    # 0.031 / 0.013 from the polyhedron's distances (the polyhedron is not the sphere).
    assert np.abs(d - exact).max() < 0.045 and np.abs(d - exact).mean() < 0.02
    assert np.all(d >= 0) and np.all(d[np.arange(3), src] == 0)


@pytest.mark.parametrize("mesh", [shapes.icosphere(3), shapes.bumpy_sphere(3)], ids=["sphere", "bumpy"])
def test_agrees_with_potpourri3d(mesh):
    # An independent implementation (geometry-central, intrinsic Delaunay throughout). Measured:
    # 1e-5 of the diameter on the icosphere, 0.5% on the bumpy sphere, whose non-Delaunay
    # triangles we keep for the gradient and Poisson steps.
    import potpourri3d as pp3d

    src = [0, 17, 400]
    reference = pp3d.MeshHeatMethodDistanceSolver(mesh.vertices, mesh.faces)
    theirs = np.vstack([reference.compute_distance(s) for s in src])
    ours = HeatMethod(mesh).distances(np.array(src))
    assert np.abs(ours - theirs).max() < 0.01 * theirs.max()


def test_flat_rectangle_distances_are_nearly_euclidean():
    plane = shapes.rectangle(2.0, 1.0, 40, 20)
    src = np.array([0, 300, 820])
    d = HeatMethod(plane).distances(src)
    euclid = np.linalg.norm(plane.vertices[src][:, None] - plane.vertices[None], axis=2)
    exact = geodesic_distances(plane, src, method="exact")
    assert np.allclose(exact, euclid, atol=1e-9)
    # The heat method smooths near the source and at the insulated boundary: about 2.7% of the
    # diameter measured (potpourri3d's heat method: the same 2.7%).
    assert np.abs(d - euclid).max() < 0.04 * euclid.max()


def test_a_block_equals_one_source_at_a_time(bumpy):
    heat = HeatMethod(bumpy)
    src = np.arange(0, bumpy.n_vertices, 97)
    together = heat.distances(src)
    alone = np.vstack([heat.distances(np.array([s])) for s in src])
    assert np.abs(together - alone).max() < 1e-10 * together.max()


def test_one_thread_or_two_give_the_same_bits(bumpy, monkeypatch):
    import lbo_notebooks.analyses._heat_method as heat_method

    heat = HeatMethod(bumpy)
    src = np.arange(0, bumpy.n_vertices, 13)
    monkeypatch.setattr(heat_method, "default_workers", lambda: 2)
    two = heat.distances(src)
    monkeypatch.setattr(heat_method, "default_workers", lambda: 1)
    assert np.array_equal(heat.distances(src), two)


def test_bad_arguments(bumpy):
    with pytest.raises(ValueError, match="t_coef"):
        HeatMethod(bumpy, t_coef=0.0)
    with pytest.raises(ValueError, match="Mesh"):
        HeatMethod(bumpy.vertices)
    heat = HeatMethod(bumpy)
    with pytest.raises(ValueError, match="vertex indices"):
        heat.distances(np.array([0, bumpy.n_vertices]))
    with pytest.raises(ValueError, match="vertex indices"):
        heat.distances(np.array([0.5]))
    with pytest.raises(ValueError, match="shape"):
        heat.distances(np.array([0, 1]), out=np.empty((3, bumpy.n_vertices)))


def test_solver_uses_blocks_with_and_without_progress(bumpy):
    solver = GeodesicSolver(bumpy, "heat")
    src = np.arange(0, bumpy.n_vertices, 31)
    quiet = solver.distances(src, progress=False)
    shown = solver.distances(src, progress=True)
    assert np.array_equal(quiet, shown)
    assert np.allclose(solver.distance(int(src[5])), quiet[5], rtol=0, atol=1e-10 * quiet.max())


def test_scale_and_rigid_motion():
    sphere = shapes.bumpy_sphere(2)
    rot = np.linalg.qr(np.random.default_rng(1).normal(size=(3, 3)))[0]
    moved = Mesh(2.5 * sphere.vertices @ rot.T - 4.0, sphere.faces)
    src = np.array([0, 50])
    assert np.allclose(HeatMethod(moved).distances(src) / 2.5, HeatMethod(sphere).distances(src), rtol=0, atol=1e-9)


def test_vertex_on_degenerate_faces_only_is_a_mesh_error():
    # vertex 4 lies on the segment 1-2 and belongs to a single zero-area face
    V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0.5, 0.5, 0]]
    m = Mesh(V, [[0, 1, 2], [1, 3, 2], [1, 2, 4]], check=False)
    with pytest.raises(MeshError, match="degenerate"):
        HeatMethod(m)


# --- farthest-point sampling in graph distance ---------------------------------------------------
def test_graph_selection_is_nested_distinct_and_covers_like_geodesic_selection(bumpy):
    s40, d40 = farthest_point_sampling(bumpy, 40, start=3, select="graph", return_distances=True)
    s10 = farthest_point_sampling(bumpy, 10, start=3, select="graph")
    assert s40[0] == 3 and np.array_equal(s40[:10], s10) and len(set(s40.tolist())) == 40
    _, g40 = farthest_point_sampling(bumpy, 40, start=3, return_distances=True)
    radius_graph, radius_geodesic = d40.min(axis=0).max(), g40.min(axis=0).max()
    assert radius_graph < 1.25 * radius_geodesic
    assert np.allclose(d40, GeodesicSolver(bumpy, "heat").distances(s40), rtol=0, atol=1e-12 * d40.max())


def test_graph_selection_picks_the_graph_farthest_vertex(bumpy):
    from scipy.sparse.csgraph import dijkstra

    from lbo_notebooks.analyses._geodesics import _edge_graph

    s = farthest_point_sampling(bumpy, 6, select="graph")
    d = dijkstra(_edge_graph(bumpy), indices=s)
    for i in range(1, 6):
        nearest = d[:i].min(axis=0)
        assert nearest[s[i]] == pytest.approx(nearest.max())


def test_bad_selection(bumpy):
    with pytest.raises(ValueError, match="select must be"):
        farthest_point_sampling(bumpy, 3, select="random")


@pytest.mark.parametrize("method", ["heat", "exact"])
def test_targets_keep_only_those_columns(method):
    mesh = shapes.bumpy_sphere(2)
    src, targets = np.array([0, 40, 90]), np.array([5, 0, 150, 5])
    full = geodesic_distances(mesh, src, method)
    assert np.array_equal(geodesic_distances(mesh, src, method, targets=targets), full[:, targets])
    with pytest.raises(ValueError, match="target vertex 162 is out of range"):
        geodesic_distances(mesh, src, method, targets=[mesh.n_vertices])


def test_spectral_mds_defaults_equal_an_explicit_graph_sampling():
    from lbo_notebooks.analyses import spectral_mds

    mesh = shapes.bumpy_sphere(2)
    sampling = farthest_point_sampling(mesh, 60, select="graph", return_distances=True)
    assert np.array_equal(spectral_mds(mesh, n_samples=60, k=30), spectral_mds(mesh, n_samples=60, k=30, sampling=sampling))


def test_no_sources_give_the_empty_answer(bumpy):
    """An empty request used to fail with the thread pool's "max_workers must be greater than 0"."""
    solver = HeatMethod(bumpy)
    assert solver.distances(np.array([], dtype=np.int64)).shape == (0, bumpy.n_vertices)
    assert solver.distances([], targets=[0, 5]).shape == (0, 2)
