import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lbo_notebooks import eigenbasis, shapes
from lbo_notebooks.analyses import min_rayleigh_quotient, optimal_subspace, random_subspace, rayleigh_quotient

from .strategies import wavy_sheet


@pytest.fixture(scope="module")
def blob():
    m = shapes.bumpy_sphere(2, seed=4)
    return m, eigenbasis(m, m.n_vertices)


@pytest.fixture(scope="module")
def sheet():
    m = wavy_sheet(8, 8, 8)
    return m, eigenbasis(m, 40, mass_kind="consistent")


def random_symmetric(seed):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(3, 3))
    return X + X.T


# --- the 3 x 3 picture -------------------------------------------------------------------------
@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**31 - 1))
def test_planes_in_3d_never_beat_lam2(seed):
    M = random_symmetric(seed)
    lam, vec = np.linalg.eigh(M)
    normal = np.random.default_rng(seed + 1).normal(size=3)
    value = min_rayleigh_quotient(M, np.eye(3), orthogonal_to=normal)
    assert lam[0] - 1e-12 <= value <= lam[1] + 1e-12  # interlacing, Courant-Fischer
    # equality for the plane orthogonal to the first eigenvector
    assert min_rayleigh_quotient(M, np.eye(3), orthogonal_to=vec[:, 0]) == pytest.approx(lam[1], abs=1e-12)


def test_plane_minimum_matches_the_closed_form():
    # For M = diag(a, b, c) and the plane orthogonal to u, the minimum is the smaller root of the
    # secular equation sum u_i^2 / (d_i - mu) = 0; check against a brute-force scan of the circle.
    M = np.diag([1.0, 2.0, 4.0])
    u = np.array([0.3, -0.5, 0.8])
    u /= np.linalg.norm(u)
    e1 = np.cross(u, [1.0, 0, 0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u, e1)
    t = np.linspace(0, np.pi, 200001)
    circle = np.outer(np.cos(t), e1) + np.outer(np.sin(t), e2)
    brute = np.min(np.einsum("ij,jk,ik->i", circle, M, circle))
    value, f = min_rayleigh_quotient(M, np.eye(3), orthogonal_to=u, return_vector=True)
    assert value == pytest.approx(brute, abs=1e-9)
    assert abs(f @ u) < 1e-12 and f @ M @ f == pytest.approx(value, rel=1e-12)


# --- Courant-Fischer on a mesh ---------------------------------------------------------------------
@settings(max_examples=12, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), n=st.integers(1, 40), smooth=st.booleans())
def test_random_subspaces_interlace(blob, seed, n, smooth):
    m, s = blob
    pool = s.vectors[:, : 2 * n] if smooth else None
    C = random_subspace(m.n_vertices, n, seed=seed, pool=pool)
    value = min_rayleigh_quotient(s.stiffness, s.mass, orthogonal_to=C)
    # Cauchy interlacing: lam[0] <= min over a codimension-n subspace <= lam[n]
    assert s.values[0] - 1e-10 * s.values[n] <= value <= s.values[n] * (1 + 1e-10)


@pytest.mark.parametrize("n", [0, 1, 5, 17])
def test_the_optimal_subspace_attains_lam_n(blob, sheet, n):
    for _, s in (blob, sheet):
        for method in ("dense", "sparse"):
            value, f = min_rayleigh_quotient(s.stiffness, s.mass, optimal_subspace(s, n), method=method, return_vector=True)
            assert value == pytest.approx(s.values[n], rel=1e-9, abs=1e-12 * s.values[-1])  # abs: lam_0 = 0
            if n and abs(s.values[n + 1] - s.values[n]) > 1e-6 * s.values[n]:  # simple eigenvalue
                assert abs(f @ s.mass @ s.vectors[:, n]) == pytest.approx(1.0, abs=1e-6)


def test_random_subspaces_lie_below_and_smooth_ones_come_closer(blob):
    m, s = blob
    n = 10
    rough = [min_rayleigh_quotient(s.stiffness, s.mass, random_subspace(m.n_vertices, n, seed=k)) for k in range(20)]
    near = [
        min_rayleigh_quotient(s.stiffness, s.mass, random_subspace(m.n_vertices, n, seed=k, pool=s.vectors[:, : n + 2]))
        for k in range(20)
    ]
    assert max(rough) < s.values[n] and max(near) <= s.values[n] * (1 + 1e-10)
    assert np.median(near) > np.median(rough)


def test_dense_and_sparse_agree():
    m = shapes.bumpy_sphere(3, seed=1)
    s = eigenbasis(m, 30)
    for C in (None, s.vectors[:, :12], random_subspace(m.n_vertices, 25, seed=3), random_subspace(m.n_vertices, 8, seed=4, pool=s.vectors[:, :20])):
        dense = min_rayleigh_quotient(s.stiffness, s.mass, C, method="dense")
        sparse = min_rayleigh_quotient(s.stiffness, s.mass, C, method="sparse")
        assert sparse == pytest.approx(dense, rel=1e-10, abs=1e-12 * s.values[-1])


def test_rayleigh_quotient_of_eigenvectors(sheet):
    m, s = sheet
    np.testing.assert_allclose(rayleigh_quotient(s.stiffness, s.mass, s.vectors[:, 1:]), s.values[1:], rtol=1e-9)
    assert rayleigh_quotient(s.stiffness, s.mass, s.vectors[:, 3]) == pytest.approx(s.values[3], rel=1e-9)


def test_random_subspace_is_seeded():
    np.testing.assert_array_equal(random_subspace(50, 4, seed=7), random_subspace(50, 4, seed=7))
    assert not np.allclose(random_subspace(50, 4, seed=7), random_subspace(50, 4, seed=8))
    assert random_subspace(50, 0).shape == (50, 0)


def test_bad_input(blob):
    m, s = blob
    W, A = s.stiffness, s.mass
    with pytest.raises(ValueError, match="orthogonal_to must have shape"):
        min_rayleigh_quotient(W, A, np.ones((5, 2)))
    with pytest.raises(ValueError, match="NaN"):
        min_rayleigh_quotient(W, A, np.full(m.n_vertices, np.nan))
    with pytest.raises(ValueError, match="rank-deficient"):
        min_rayleigh_quotient(W, A, np.column_stack([np.ones(m.n_vertices)] * 2))
    with pytest.raises(ValueError, match="symmetric"):
        min_rayleigh_quotient(np.triu(np.ones((3, 3))), np.eye(3))
    with pytest.raises(ValueError, match="method"):
        min_rayleigh_quotient(W, A, method="fast")
    with pytest.raises(ValueError, match="k must be an integer in 0..9"):
        random_subspace(10, 10)
    with pytest.raises(ValueError, match="pool"):
        random_subspace(m.n_vertices, 5, pool=s.vectors[:, :3])
    with pytest.raises(ValueError, match="0 <= k < spectrum.k"):
        optimal_subspace(s, s.k)
    with pytest.raises(ValueError, match="zero"):
        rayleigh_quotient(W, A, np.zeros(m.n_vertices))


def test_solver_object_reuses_its_factorisation():
    from lbo_notebooks.analyses import ConstrainedRayleigh

    m = shapes.bumpy_sphere(3, seed=5)
    s = eigenbasis(m, 12)
    solver = ConstrainedRayleigh(s.stiffness, s.mass)
    for n in (0, 3, 11):
        assert solver.minimum(s.vectors[:, :n]) == pytest.approx(s.values[n], rel=1e-9, abs=1e-12 * s.values[-1])
    C = random_subspace(m.n_vertices, 6, seed=2)
    assert solver.minimum(C) == pytest.approx(min_rayleigh_quotient(s.stiffness, s.mass, C, method="dense"), rel=1e-10)


def test_rotating_plane_reaches_lam2_only_at_zero():
    from lbo_notebooks.plotting import plane_normal
    from lbo_notebooks.plotting import plane_slider

    M = random_symmetric(11)
    lam = np.linalg.eigvalsh(M)
    angles = np.arange(0, 181, 5)
    mins = np.array([min_rayleigh_quotient(M, np.eye(3), plane_normal(M, a)) for a in angles])
    assert mins[0] == pytest.approx(lam[1], abs=1e-12) and mins[-1] == pytest.approx(lam[1], abs=1e-12)
    assert np.all(mins[1:-1] < lam[1] - 1e-6)
    w = plane_slider(M)
    w.slider.value = 90
    assert "min on the plane" in w.figure.layout.title.text
    with pytest.raises(ValueError, match="symmetric 3 x 3"):
        plane_normal(np.ones((2, 2)), 0.0)


def test_the_teaching_plane_minimum_is_the_library_minimum():
    """teaching.plane_circle solves the 2 x 2 problem by hand; min_rayleigh_quotient is the general one."""
    from lbo_notebooks.plotting._rayleigh_plane import plane_circle, plane_normal

    M = np.array([[2.0, 0.3, 0.1], [0.3, 1.0, -0.2], [0.1, -0.2, 4.0]])
    for angle in (0.0, 25.0, 60.0, 90.0):
        normal = plane_normal(M, angle)
        _, point, value = plane_circle(M, normal)
        expected, f = min_rayleigh_quotient(M, np.eye(3), orthogonal_to=normal, method="dense", return_vector=True)
        assert value == pytest.approx(expected, rel=1e-13)
        np.testing.assert_allclose(point, 1.01 * f, rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match="nonzero 3-vector"):
        plane_circle(M, [0.0, 0.0, 0.0])
