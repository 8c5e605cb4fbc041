import numpy as np
import pytest

from lbo_notebooks import Mesh, classical_mds, farthest_point_sampling, fast_classical_scaling, gram_error, shapes
from lbo_notebooks.analyses import procrustes_error


@pytest.fixture(scope="module")
def bumpy():
    mesh = shapes.bumpy_sphere(3)
    return mesh, classical_mds(mesh, 3, method="exact")


def test_flat_patch_is_recovered_up_to_a_rigid_motion():
    # On a flat convex patch geodesic distance is Euclidean, so classical scaling is exact and the
    # embedding is the patch itself, up to rotation, reflection and translation -- up to the
    # boundary error of the Neumann biharmonic interpolation, which shrinks with more samples.
    plane = shapes.rectangle(2.0, 1.0, 24, 12)
    sampling = farthest_point_sampling(plane, 80, method="exact", return_distances=True)
    errors = [procrustes_error(fast_classical_scaling(plane, dim=2, n_samples=q, sampling=sampling), plane.vertices[:, :2]) for q in (40, 80)]
    assert errors[0] < 0.025 and errors[1] < 0.7 * errors[0]


def test_close_to_classical_mds(bumpy):
    mesh, X = bumpy
    Z, details = fast_classical_scaling(mesh, n_samples=100, method="exact", return_details=True)
    assert gram_error(Z, X) < 0.02
    assert details["eigenvalues"][2] > 2 * details["eigenvalues"][3]  # the comparison is meaningful


def test_more_samples_do_better(bumpy):
    mesh, X = bumpy
    sampling = farthest_point_sampling(mesh, 120, method="exact", return_distances=True)
    errors = [gram_error(fast_classical_scaling(mesh, n_samples=q, sampling=sampling), X) for q in (20, 120)]
    assert errors[1] < errors[0]


def test_invariant_to_units_and_rigid_motion(bumpy):
    mesh, _ = bumpy
    rot = np.linalg.qr(np.random.default_rng(3).normal(size=(3, 3)))[0]
    moved = Mesh(3.0 * mesh.vertices @ rot.T + 1.0, mesh.faces)
    Z = fast_classical_scaling(mesh, n_samples=60, method="exact")
    Zm = fast_classical_scaling(moved, n_samples=60, method="exact")
    assert gram_error(Zm / 3.0, Z) < 1e-8


def test_sampling_is_not_modified(bumpy):
    mesh, _ = bumpy
    samples, fields = farthest_point_sampling(mesh, 30, method="exact", return_distances=True)
    before = fields.copy()
    fast_classical_scaling(mesh, n_samples=30, sampling=(samples, fields))
    assert np.array_equal(fields, before)


def test_bad_arguments(bumpy):
    mesh, _ = bumpy
    with pytest.raises(ValueError, match="n_samples"):
        fast_classical_scaling(mesh, n_samples=1)
    with pytest.raises(ValueError, match="n_samples"):
        fast_classical_scaling(mesh, n_samples=mesh.n_vertices + 1)
    with pytest.raises(ValueError, match="dim"):
        fast_classical_scaling(mesh, dim=0)
    with pytest.raises(ValueError, match="dim"):
        fast_classical_scaling(mesh, dim=10, n_samples=5)
    for mu in (0.0, -1.0, np.nan, True):
        with pytest.raises(ValueError, match="mu"):
            fast_classical_scaling(mesh, mu=mu)
    with pytest.raises(ValueError, match="sampling"):
        fast_classical_scaling(mesh, n_samples=10, sampling=(np.arange(5), np.zeros((5, mesh.n_vertices))))
    with pytest.raises(ValueError, match="Mesh"):
        fast_classical_scaling(np.zeros((10, 10)))


def test_spline_interpolation_equals_the_direct_biharmonic_solve():
    # M = (S.T S + mu E)^-1 S.T with E = W A^-1 W, solved directly, against the smoothing-spline
    # form that only needs the factorisation of W.
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    from lbo_notebooks.analyses._fast_classical_scaling import _interpolation_operator
    from lbo_notebooks.operators import mass_matrix, stiffness_matrix

    for mesh in (shapes.bumpy_sphere(2), shapes.rectangle(2.0, 1.0, 16, 8)):
        samples = farthest_point_sampling(mesh, 25, select="graph")
        M, mu_abs = _interpolation_operator(mesh, samples, 1e-3)
        W, a = stiffness_matrix(mesh), mass_matrix(mesh, "voronoi").diagonal()
        S = sp.csr_matrix((np.ones(25), (np.arange(25), samples)), shape=(25, mesh.n_vertices))
        direct = spla.spsolve((S.T @ S + mu_abs * W @ sp.diags(1 / a) @ W).tocsc(), S.T.toarray())
        assert np.abs(M - direct).max() < 1e-8 * np.abs(direct).max()


def test_a_given_sampling_must_hold_vertex_indices():
    """Fractional sample indices used to be truncated without a word."""
    mesh = shapes.icosphere(2)
    n = mesh.n_vertices
    for samples in (np.arange(10) + 0.5, np.arange(10) + n, -np.arange(1, 11)):
        with pytest.raises(ValueError, match=r"^sampling must be .*integer vertex indices in 0\.\.161"):
            fast_classical_scaling(mesh, n_samples=10, sampling=(samples, np.ones((10, n))))
    with pytest.raises(ValueError, match=r"got something that is not a pair of arrays\.$"):
        fast_classical_scaling(mesh, n_samples=10, sampling=5)
