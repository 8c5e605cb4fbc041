import igl
import numpy as np
import pytest
import robust_laplacian
import scipy.sparse as sp
from hypothesis import given, settings

from lbo_notebooks import Mesh, mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.operators import face_cotangents

from .strategies import random_meshes

EPS = np.finfo(float).eps


def test_worked_triangle_by_hand():
    # Right isosceles triangle: angles 90, 45, 45 degrees -> cotangents 0, 1, 1.
    m = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    np.testing.assert_allclose(face_cotangents(m), [[0.0, 1.0, 1.0]], atol=8 * EPS)  # entries are O(1)
    expected = 0.5 * np.array([[2, -1, -1], [-1, 1, 0], [-1, 0, 1]], dtype=float)
    np.testing.assert_allclose(stiffness_matrix(m).toarray(), expected, atol=8 * EPS)
    # Voronoi: right angle at vertex 0 gets |t|/2, the others |t|/4.
    np.testing.assert_allclose(mass_matrix(m, "voronoi").diagonal(), [0.25, 0.125, 0.125])
    np.testing.assert_allclose(mass_matrix(m, "barycentric").diagonal(), [1 / 6] * 3)
    np.testing.assert_allclose(mass_matrix(m, "consistent").toarray(), np.array([[2, 1, 1], [1, 2, 1], [1, 1, 2]]) / 24)


def test_obtuse_triangle_voronoi_rule():
    m = Mesh([[0, 0, 0], [4, 0, 0], [2, 0.5, 0]], [[0, 1, 2]])  # obtuse at vertex 2
    np.testing.assert_allclose(mass_matrix(m).diagonal(), m.area * np.array([0.25, 0.25, 0.5]))


def test_dirichlet_energy_of_a_linear_function_on_a_flat_mesh():
    m = shapes.disk(n_rings=6)
    f = 2.0 * m.vertices[:, 0] - 3.0 * m.vertices[:, 1]
    assert f @ stiffness_matrix(m) @ f == pytest.approx(13.0 * m.area, rel=1e-12)


@pytest.mark.parametrize("mesh", [shapes.bumpy_sphere(3), shapes.torus(n_major=24, n_minor=10), shapes.disk(n_rings=6)],
                         ids=["bumpy", "torus", "disk"])
def test_matches_libigl(mesh):
    np.testing.assert_allclose(stiffness_matrix(mesh).toarray(), -igl.cotmatrix(mesh.vertices, mesh.faces).toarray(), atol=1e-10)
    for kind, igl_kind in [("voronoi", igl.MASSMATRIX_TYPE_VORONOI), ("barycentric", igl.MASSMATRIX_TYPE_BARYCENTRIC)]:
        ref = igl.massmatrix(mesh.vertices, mesh.faces, igl_kind)
        np.testing.assert_allclose(mass_matrix(mesh, kind).toarray(), ref.toarray(), atol=1e-10)


def test_matches_robust_laplacian_on_a_delaunay_mesh():
    # robust-laplacian uses the intrinsic Delaunay triangulation: identical to the cotangent
    # Laplacian when the mesh is already Delaunay (as an icosphere is) and mollification is off.
    m = shapes.icosphere(3)
    L, M = robust_laplacian.mesh_laplacian(m.vertices, m.faces, mollify_factor=0.0)
    np.testing.assert_allclose(stiffness_matrix(m).toarray(), L.toarray(), atol=1e-10)
    np.testing.assert_allclose(mass_matrix(m, "barycentric").toarray(), M.toarray(), atol=1e-10)


@settings(max_examples=40, deadline=None)
@given(random_meshes())
def test_properties_on_random_meshes(mesh):
    W = stiffness_matrix(mesh)
    assert abs(W - W.T).max() < 1e-12 * max(1.0, abs(W).max())
    np.testing.assert_allclose(W @ np.ones(mesh.n_vertices), 0.0, atol=1e-10 * abs(W).max())
    assert np.linalg.eigvalsh(W.toarray()).min() > -1e-10 * abs(W).max()
    for kind in ("voronoi", "barycentric", "consistent"):
        A = mass_matrix(mesh, kind)
        assert A.sum() == pytest.approx(mesh.area, rel=1e-12)
    assert np.all(mass_matrix(mesh, "voronoi").diagonal() > 0)


def test_results_are_csr_and_fresh_copies():
    m = shapes.icosphere(1)
    W1, W2 = stiffness_matrix(m), stiffness_matrix(m)
    assert sp.isspmatrix_csr(W1) and sp.isspmatrix_csr(mass_matrix(m, "consistent"))
    W1.data[:] = 0.0
    assert abs(W2).max() > 0 and abs(stiffness_matrix(m)).max() > 0


def test_bad_mass_kind():
    with pytest.raises(ValueError, match="voronoi"):
        mass_matrix(shapes.icosphere(1), "lumped")


def test_invariance_to_rigid_motion_and_permutation():
    m = shapes.bumpy_sphere(2)
    rng = np.random.default_rng(1)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    moved = Mesh(m.vertices @ q.T + [1.0, -2.0, 3.0], m.faces)
    W = stiffness_matrix(m)
    # cotangents of a moved triangle carry round-off ~ eps * |position| / edge length
    atol = 1e3 * EPS * np.abs(moved.vertices).max() / m.mean_edge_length * abs(W).max()
    np.testing.assert_allclose(stiffness_matrix(moved).toarray(), W.toarray(), atol=atol)
    perm = rng.permutation(m.n_vertices)
    inv = np.argsort(perm)
    permuted = Mesh(m.vertices[perm], inv[m.faces])
    P = sp.eye(m.n_vertices, format="csr")[perm]
    np.testing.assert_allclose((P @ W @ P.T).toarray(), stiffness_matrix(permuted).toarray(), atol=8 * EPS * abs(W).max())
    np.testing.assert_allclose(mass_matrix(permuted).diagonal(), mass_matrix(m).diagonal()[perm])


@pytest.mark.parametrize("name", ["stiffness_matrix", "mass_matrix", "face_cotangents", "corner_angles",
                                  "cotan_defects", "non_manifold_vertices", "metric_curvature"])
@pytest.mark.parametrize("not_a_mesh", [np.eye(3), None, (np.eye(3), np.array([[0, 1, 2]]))])
def test_every_operator_names_a_non_mesh_argument(name, not_a_mesh):
    """A (vertices, faces) pair or an array gets the fix, not an AttributeError from deep inside."""
    import lbo_notebooks as lbo

    with pytest.raises(ValueError, match=r"^mesh must be an lbo_notebooks\.Mesh, got \w+; build one with"):
        getattr(lbo.operators, name)(not_a_mesh)
