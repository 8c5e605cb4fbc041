import numpy as np
import pytest
import scipy.sparse as sp

from lbo_notebooks import eigenbasis, mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.analyses import _competitor_bases as bases
from lbo_notebooks.analyses import worst_case_ratio

from .strategies import wavy_sheet

ALL = [
    bases.lbo_basis,
    bases.random_smooth_basis,
    bases.pca_basis,
    bases.umbrella_basis,
    bases.identity_mass_basis,
    bases.polynomial_basis,
    lambda m, k, mass_kind="voronoi": bases.metric_basis(m, k, _heavier_on_the_sides(mass_kind), mass_kind=mass_kind),
]


def _heavier_on_the_sides(mass):
    # A conformal factor rho scales the mass as D A D with D = diag(sqrt(rho)): symmetric for
    # every mass kind (D A alone is not symmetric when A is the consistent mass).
    def metric(m):
        d = sp.diags(np.sqrt(1.0 + m.vertices[:, 0] ** 2))
        return d @ mass_matrix(m, mass) @ d

    return metric
IDS = ["eigen", "random", "pca", "umbrella", "identity", "polynomial", "metric"]


@pytest.fixture(scope="module")
def blob():
    m = shapes.bumpy_sphere(3, seed=3)  # 642 vertices, no symmetry
    return m, eigenbasis(m, 41)


@pytest.mark.parametrize("make", ALL, ids=IDS)
@pytest.mark.parametrize("mass", ["voronoi", "consistent"])
def test_a_orthonormal_with_the_constant_first(make, mass):
    m = wavy_sheet(2, 8, 6)  # open surface, 63 vertices
    A = mass_matrix(m, mass)
    B = make(m, 12, mass_kind=mass)
    assert B.shape == (m.n_vertices, 12)
    np.testing.assert_allclose(B.T @ A @ B, np.eye(12), atol=1e-10)
    assert np.ptp(B[:, 0]) < 1e-12 * np.abs(B[:, 0]).max() and B[0, 0] > 0
    np.testing.assert_array_equal(B, make(m, 12, mass_kind=mass))  # deterministic


@pytest.mark.parametrize("make", ALL[1:], ids=IDS[1:])
def test_every_competitor_is_worse_than_the_eigenbasis(blob, make):
    m, s = blob
    B = make(m, 40)
    W, A = stiffness_matrix(m), mass_matrix(m)
    assert worst_case_ratio(s.vectors[:, :40], W, A) * s.values[40] == pytest.approx(1.0, abs=1e-8)
    for n in (10, 40):
        assert worst_case_ratio(B[:, :n], W, A) * s.values[n] > 1.0 + 1e-4


def test_random_smooth_functions_are_smooth_and_seeded(blob):
    m, s = blob
    W, A = stiffness_matrix(m), mass_matrix(m)
    B = bases.random_smooth_basis(m, 20, seed=1)
    assert not np.allclose(B, bases.random_smooth_basis(m, 20, seed=2))
    noise = bases._constant_first(m, A, np.random.default_rng(1).normal(size=(m.n_vertices, 19)), 20)
    energy = lambda X: np.einsum("ij,ij->j", X, W @ X)[1:]  # unit A-norm: Rayleigh quotients
    assert np.median(energy(B)) < 0.15 * np.median(energy(noise))


def test_pca_recovers_the_span_of_its_samples(blob):
    m, s = blob
    A = mass_matrix(m)
    rng = np.random.default_rng(0)
    generators = np.column_stack([m.vertices, np.sin(m.vertices[:, 0])])
    samples = generators @ rng.normal(size=(4, 30)) + 2.0  # + a constant: removed first
    B = bases.pca_basis(m, 5, samples=samples)
    full = np.column_stack([np.ones(m.n_vertices), generators])
    residual = full - B @ (B.T @ (A @ full))
    assert np.abs(residual).max() < 1e-10 * np.abs(full).max()
    with pytest.raises(ValueError, match="fewer than k - 1 = 5"):
        bases.pca_basis(m, 6, samples=samples)


def test_polynomials_skip_dependent_products_on_the_sphere():
    m = shapes.icosphere(3)
    A = mass_matrix(m)
    B = bases.polynomial_basis(m, 10)
    x, y, z = m.vertices.T
    quadrics = np.column_stack([np.ones_like(x), x, y, z, x * y, y * z, x * z, x**2 - y**2, x**2 - z**2])
    residual = quadrics - B[:, :9] @ (B[:, :9].T @ (A @ quadrics))
    assert np.abs(residual).max() < 1e-10  # 1 + 3 + 5 = 9 quadrics on the sphere, not 10
    cubic = x * y * z
    assert np.abs(cubic - B[:, :9] @ (B[:, :9].T @ (A @ cubic))).max() > 1e-3  # the 10th is cubic
    flat = shapes.rectangle(2.0, 1.0, 6, 6)
    Bf = bases.polynomial_basis(flat, 6)  # z is constant: only 1, x, y, x^2, xy, y^2
    np.testing.assert_allclose(Bf.T @ mass_matrix(flat) @ Bf, np.eye(6), atol=1e-10)
    with pytest.raises(ValueError, match="max_degree"):
        bases.polynomial_basis(flat, 40, max_degree=3)


def test_polynomials_on_the_sphere_are_nearly_optimal():
    # Spherical harmonics are polynomials: on a sphere the polynomial basis ties with the eigenbasis
    # (up to discretisation) at cluster boundaries, which is why notebook 05 uses a bumpy shape.
    m = shapes.icosphere(3)
    s = eigenbasis(m, 17)
    B = bases.polynomial_basis(m, 16)
    assert worst_case_ratio(B, s.stiffness, s.mass) * s.values[16] == pytest.approx(1.0, abs=0.02)


def test_metric_basis_is_pluggable(blob):
    m, s = blob
    W, A = stiffness_matrix(m), mass_matrix(m)
    same = bases.metric_basis(m, 15, A)  # same metric: the eigenbasis again
    assert worst_case_ratio(same, W, A) * s.values[15] == pytest.approx(1.0, abs=1e-8)
    assert np.allclose(bases.metric_basis(m, 15, (W, 2.0 * A)), bases.metric_basis(m, 15, lambda mm: 2.0 * mass_matrix(mm)))
    with pytest.raises(ValueError, match="metric must be"):
        bases.metric_basis(m, 15, "scale-invariant")
    with pytest.raises(ValueError, match="same size"):
        bases.metric_basis(m, 15, (W, A[:10, :10]))


def test_competitor_bases_and_bad_input(blob):
    m, _ = blob
    out = bases.competitor_bases(m, 8, metric=lambda mm: 3.0 * mass_matrix(mm))
    assert list(out)[0] == "LBO eigenbasis" and len(out) == 7
    assert all(B.shape == (m.n_vertices, 8) for B in out.values())
    with pytest.raises(ValueError, match="k must be"):
        bases.umbrella_basis(m, 0)
    with pytest.raises(ValueError, match="k must be"):
        bases.random_smooth_basis(m, m.n_vertices)
    with pytest.raises(ValueError, match="mass_kind must be one of"):
        bases.identity_mass_basis(m, 5, mass_kind="lumped")
    with pytest.raises(ValueError, match="Mesh"):
        bases.lbo_basis((stiffness_matrix(m), mass_matrix(m)), 5)
    with pytest.raises(ValueError, match="width"):
        bases.random_smooth_basis(m, 5, width=-1.0)


def test_sample_functions_satisfy_the_bound_and_are_what_they_say():
    from lbo_notebooks.analyses import geodesic_distances
    from lbo_notebooks.analyses import error_bound, representation_error

    m = shapes.icosphere(3)
    s = eigenbasis(m, 40)
    F, labels = bases.sample_functions(m, seed=2)
    assert F.shape == (m.n_vertices, 8) and len(labels) == 8
    assert np.array_equal(F[:, :3], m.vertices)
    source = int(np.argmax(m.vertices[:, 0]))
    assert np.allclose(F[:, 4], geodesic_distances(m, [source])[0])
    heat = F[:, 3]
    # Implicit heat steps conserve the integral A-mass of the unit spike and keep it positive,
    # peaked at the source.
    A = s.mass
    assert abs(np.sum(A @ heat) - A[source, source]) < 1e-10 * A[source, source]
    assert heat.min() > 0 and int(np.argmax(heat)) == source
    for n in (1, 5, 20, 39):
        assert np.all(representation_error(s, F, n) <= error_bound(s, F, n) * (1 + 1e-9))
    again, _ = bases.sample_functions(m, seed=2)
    assert np.array_equal(again, F)
    with pytest.raises(ValueError, match="heat_time"):
        bases.sample_functions(m, heat_time=-1.0)
    with pytest.raises(ValueError, match="Mesh"):
        bases.sample_functions(m.vertices)
