import numpy as np
import pytest
import scipy.sparse as sp

from lbo_notebooks import Mesh, eigenbasis, mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.inner_product import fix_signs

# l(l+1) with multiplicity 2l+1: the first 36 eigenvalues of the unit sphere (l = 0..5).
L = np.repeat(np.arange(6), 2 * np.arange(6) + 1)
SPHERE = (L * (L + 1.0))[:36]


@pytest.fixture(scope="module")
def sphere5():
    return eigenbasis(shapes.icosphere(5), 36)


def test_sphere_first_36_eigenvalues_within_half_a_percent(sphere5):
    assert abs(sphere5.values[0]) < 1e-8 * sphere5.values[1]
    assert np.max(np.abs(sphere5.values[1:] / SPHERE[1:] - 1)) < 5e-3


def test_sphere_multiplicities(sphere5):
    # Gaps inside each l cluster are tiny compared with the gaps between clusters.
    v = sphere5.values
    for l in range(1, 6):
        cluster = v[l * l : (l + 1) ** 2]
        assert np.ptp(cluster) < 0.01 * l * (l + 1)


@pytest.mark.parametrize("mass", ["voronoi", "consistent"])
def test_sphere_convergence_is_second_order(mass):
    # Skip l=1: superconvergent with lumped mass (docs/maths.md, "Operators").
    errors = []
    for s in (2, 3, 4):
        values = eigenbasis(shapes.icosphere(s), 36, mass_kind=mass).values
        errors.append(np.max(np.abs(values[4:] / SPHERE[4:] - 1)))
    rates = np.log2(np.array(errors[:-1]) / np.array(errors[1:])) # h halves per subdivision
    assert np.all(rates > 1.8), rates


def test_lumped_lies_below_and_consistent_above_on_the_sphere():
    m = shapes.icosphere(3)
    lumped = eigenbasis(m, 36, mass_kind="voronoi").values[4:]
    consistent = eigenbasis(m, 36, mass_kind="consistent").values[4:]
    assert np.all(lumped < SPHERE[4:]) and np.all(consistent > SPHERE[4:])


def test_rectangle_matches_the_exact_discrete_oracle():
    a, b, nx, ny = 2.0, 1.0, 48, 30
    spec = eigenbasis(shapes.rectangle(a, b, nx, ny), 40)
    hx, hy = a / nx, b / ny
    m, n = np.meshgrid(np.arange(nx + 1), np.arange(ny + 1), indexing="ij")
    exact = np.sort(((4 / hx**2) * np.sin(m * np.pi * hx / (2 * a)) ** 2 + (4 / hy**2) * np.sin(n * np.pi * hy / (2 * b)) ** 2).ravel())
    np.testing.assert_allclose(spec.values, exact[:40], rtol=1e-10, atol=1e-10)
    continuum = np.sort((np.pi**2 * (m**2 / a**2 + n**2 / b**2)).ravel())[:10]
    np.testing.assert_allclose(spec.values[:10], continuum, rtol=2e-2, atol=1e-10)


def test_vectors_are_mass_orthonormal_not_euclidean_orthonormal():
    spec = eigenbasis(shapes.bumpy_sphere(4), 30)
    Phi, A = spec.vectors, spec.mass
    np.testing.assert_allclose(Phi.T @ (A @ Phi), np.eye(30), atol=1e-10)
    assert np.abs(Phi.T @ Phi - np.eye(30)).max() > 0.1
    np.testing.assert_allclose(spec.stiffness @ Phi, (A @ Phi) * spec.values, atol=1e-8 * spec.values[-1])
    assert np.all(np.diff(spec.values) >= 0)


def test_dense_and_sparse_paths_agree(monkeypatch):
    m = shapes.bumpy_sphere(3)  # 642 vertices: above DENSE_LIMIT, so the sparse path
    sparse = eigenbasis(m, 20)
    import lbo_notebooks.solver_policy as solver_policy

    monkeypatch.setattr(solver_policy, "DENSE_LIMIT", 10**9)
    dense = eigenbasis(m, 20)
    np.testing.assert_allclose(sparse.values, dense.values, rtol=1e-9, atol=1e-9)
    # Non-degenerate eigenvectors agree including sign (deterministic sign rule).
    np.testing.assert_allclose(sparse.vectors[:, :8], dense.vectors[:, :8], atol=1e-6)


def test_deterministic_and_rigid_motion_invariant():
    m = shapes.bumpy_sphere(4)
    a, b = eigenbasis(m, 20), eigenbasis(m, 20)
    np.testing.assert_array_equal(a.values, b.values)
    np.testing.assert_array_equal(a.vectors, b.vectors)
    rng = np.random.default_rng(3)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    moved = eigenbasis(Mesh(m.vertices @ q.T + 7.0, m.faces), 20)
    np.testing.assert_allclose(moved.values, a.values, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(moved.vectors[:, :10], a.vectors[:, :10], atol=1e-6)


def test_scaling_divides_eigenvalues_by_s_squared():
    m = shapes.bumpy_sphere(3)
    s = 3.7
    big = eigenbasis(m.with_vertices(s * m.vertices), 20).values
    np.testing.assert_allclose(big[1:], eigenbasis(m, 20).values[1:] / s**2, rtol=1e-9)


def test_vertex_permutation_permutes_rows():
    m = shapes.bumpy_sphere(3)
    perm = np.random.default_rng(0).permutation(m.n_vertices)
    permuted = Mesh(m.vertices[perm], np.argsort(perm)[m.faces])
    a, b = eigenbasis(m, 15), eigenbasis(permuted, 15)
    np.testing.assert_allclose(b.values, a.values, rtol=1e-10, atol=1e-10)
    np.testing.assert_allclose(b.vectors, a.vectors[perm], atol=1e-8)


def test_one_zero_eigenvalue_per_component_and_constant_first():
    s = shapes.icosphere(2)
    two = Mesh(np.vstack([s.vertices, s.vertices + 3]), np.vstack([s.faces, s.faces + s.n_vertices]))
    values = eigenbasis(two, 6).values
    assert np.sum(np.abs(values) < 1e-8 * values[-1]) == 2
    spec = eigenbasis(s, 4)
    np.testing.assert_allclose(spec.vectors[:, 0], 1 / np.sqrt(s.area), rtol=1e-8)


def test_project_reconstruct_error():
    m = shapes.bumpy_sphere(3)
    spec = eigenbasis(m, 60)
    f = m.vertices  # (n, 3): three functions at once
    c = spec.project(f, 10)
    assert c.shape == (10, 3)
    np.testing.assert_allclose(c, spec.vectors[:, :10].T @ (spec.mass @ f))
    r = spec.reconstruct(f, 10)
    resid = f - r
    np.testing.assert_allclose(spec.error(f, 10), np.sqrt(np.einsum("ij,ij->j", resid, spec.mass @ resid)))
    # Residual is A-orthogonal to the basis; errors decrease with n; a basis vector is exact.
    np.testing.assert_allclose(spec.vectors[:, :10].T @ (spec.mass @ resid), 0, atol=1e-10 * spec.error(f, 0).max())
    errs = [spec.error(f[:, 0], n) for n in (1, 5, 20, 60)]
    assert all(x > y for x, y in zip(errs, errs[1:]))
    assert spec.error(spec.vectors[:, 7], 8) < 1e-10  # relative: the vector has unit A-norm
    assert spec.error(f[:, 0], 0) == pytest.approx(np.sqrt(f[:, 0] @ spec.mass @ f[:, 0]))


def test_fix_signs_rule():
    A = sp.identity(4, format="csr")
    v = np.array([[1.0, -1.0], [-3.0, 1.0], [0.0, 2.0], [0.5, -1.0]])
    out = fix_signs(v, A)
    assert np.all(out.T ** 3 @ np.ones(4) >= 0)
    np.testing.assert_array_equal(np.abs(out), np.abs(v))
    antisymmetric = np.array([[1.0], [-1.0], [2.0], [-2.0]])  # zero third moment: largest entry positive
    assert fix_signs(antisymmetric, A)[2, 0] == 2.0


@pytest.mark.parametrize("k", [0, -1, 700, 2.5, True])
def test_bad_k(k):
    with pytest.raises(ValueError, match="k must be"):
        eigenbasis(shapes.icosphere(3), k)


def test_bad_inputs():
    m = shapes.icosphere(2)
    spec = eigenbasis(m, 10)
    with pytest.raises(ValueError, match="one value per vertex"):
        spec.project(np.ones(5))
    with pytest.raises(ValueError, match="NaN"):
        spec.project(np.full(m.n_vertices, np.nan))
    with pytest.raises(ValueError, match="between 0 and k"):
        spec.reconstruct(np.ones(m.n_vertices), 11)
    with pytest.raises(ValueError, match="mass_kind must be one of"):
        eigenbasis(m, 5, mass_kind="lumped")
    with pytest.raises(ValueError, match="alpha"):
        eigenbasis(m, 5, alpha=2.0)
    with pytest.raises(ValueError, match="shift"):
        eigenbasis(m, 5, shift=-1.0)
    with pytest.raises(ValueError, match="same size"):
        eigenbasis((stiffness_matrix(m), sp.identity(3)), 2)
    W = stiffness_matrix(m).tolil()
    W[0, 1] += 1.0
    with pytest.raises(ValueError, match="symmetric"):
        eigenbasis((W.tocsr(), mass_matrix(m)), 2)
    with pytest.raises(ValueError, match="Mesh or a"):
        eigenbasis(np.eye(3), 2)
    with pytest.raises(ValueError, match="read-only"):
        spec.values[0] = 1.0
