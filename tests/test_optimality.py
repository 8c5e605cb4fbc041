import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from lbo_notebooks import Mesh, eigenbasis, mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.spectral import a_orthonormalize
from lbo_notebooks.analyses import complement_ratio, min_rayleigh_quotient
from lbo_notebooks.analyses import (
    dirichlet_energy,
    error_bound,
    kernel_basis,
    representation_error,
    witness_function,
    worst_case_ratio,
)

from .strategies import wavy_sheet

EPS = np.finfo(float).eps


@pytest.fixture(scope="module")
def blob():
    """A non-symmetric closed surface, 162 vertices, with its full dense spectrum."""
    m = shapes.bumpy_sphere(2)
    return m, eigenbasis(m, m.n_vertices)


@pytest.fixture(scope="module")
def sheet():
    """An open surface with boundary (Neumann), 80 vertices, full spectrum, consistent mass."""
    m = wavy_sheet(3, 9, 7)
    return m, eigenbasis(m, m.n_vertices, mass_kind="consistent")


def perturbed_eigenbasis(spectrum, n, eps, seed=0):
    """The first n eigenvectors plus noise, keeping the constant so that C(V) is finite."""
    rng = np.random.default_rng(seed)
    scale = np.abs(spectrum.vectors[:, 1:n]).mean()
    B = np.array(spectrum.vectors[:, :n])
    B[:, 1:] += eps * scale * rng.normal(size=(B.shape[0], n - 1))
    return B


def schur_oracle(basis, W, A):
    """Independent dense evaluation of C(V) from the Schur complement (docs/maths.md, "Optimality")."""
    Wd, Ad = W.toarray(), A.toarray()
    Q = scipy.linalg.orth(basis)
    S = Wd - Wd @ Q @ np.linalg.pinv(Q.T @ Wd @ Q) @ Q.T @ Wd
    Z = scipy.linalg.null_space((Ad @ basis).T)  # {r : r is A-orthogonal to V}
    mu = scipy.linalg.eigh(Z.T @ S @ Z, Z.T @ Ad @ Z, eigvals_only=True)[0]
    return 1.0 / mu


# --- the bound ---------------------------------------------------------------------------------
def test_dirichlet_energy_of_a_linear_function_is_exact():
    m = shapes.rectangle(2.0, 1.0, 8, 4)
    W = stiffness_matrix(m)
    f = 3.0 * m.vertices[:, 0] - 2.0 * m.vertices[:, 1]
    assert dirichlet_energy(W, f) == pytest.approx(13.0 * m.area, rel=1e-12)
    both = dirichlet_energy(W, np.column_stack([f, m.vertices[:, 0]]))
    np.testing.assert_allclose(both, [13.0 * m.area, m.area], rtol=1e-12)


def test_representation_error_is_the_tail_of_the_expansion(blob):
    # Parseval in the A inner product with the complete eigenbasis: the squared error after n
    # terms is the sum of the squared coefficients from n on, and the bound is sum lam c^2 / lam[n].
    m, s = blob
    f = np.sin(2 * m.vertices[:, 0]) + m.vertices[:, 1] ** 2
    c = s.project(f)
    for n in (1, 5, 40, 120):
        assert representation_error(s, f, n) == pytest.approx(np.sum(c[n:] ** 2), rel=1e-9)
        assert error_bound(s, f, n) == pytest.approx(np.sum(s.values * c**2) / s.values[n], rel=1e-9)


@settings(max_examples=12, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), n=st.integers(1, 150), smooth=st.booleans(), sheet_mesh=st.booleans())
def test_bound_holds_for_random_functions(blob, sheet, seed, n, smooth, sheet_mesh):
    m, s = sheet if sheet_mesh else blob
    n = min(n, s.k - 1)
    rng = np.random.default_rng(seed)
    f = rng.normal(size=(m.n_vertices, 3))
    if smooth:  # a few implicit heat steps
        K = (s.mass + 0.05 * m.area * s.stiffness).tocsc()
        for _ in range(3):
            f = sp.linalg.spsolve(K, s.mass @ f)
    err, bound = representation_error(s, f, n), error_bound(s, f, n)
    assert err.shape == bound.shape == (3,)
    # slack: round-off of the squared A-norm of the residual, relative to ||f||_A^2
    assert np.all(err <= bound * (1 + 1e-9) + m.n_vertices * EPS * np.einsum("ij,ij->j", f, s.mass @ f))
    # vectorised over columns = column by column
    assert representation_error(s, f[:, 1], n) == pytest.approx(err[1], rel=1e-12)


def test_bound_is_attained_by_the_next_eigenfunction(blob):
    m, s = blob
    for n in (1, 7, 30):
        phi = s.vectors[:, n]
        assert representation_error(s, phi, n) == pytest.approx(1.0, rel=1e-10)
        assert error_bound(s, phi, n) == pytest.approx(1.0, rel=1e-9)


def test_bound_rejects_bad_input(blob):
    m, s = blob
    f = m.vertices[:, 0]
    with pytest.raises(ValueError, match="lam\\[k\\]"):
        error_bound(s, f, 0)
    with pytest.raises(ValueError, match="more than k eigenpairs"):
        error_bound(s, f, s.k)
    with pytest.raises(ValueError, match="integer"):
        error_bound(s, f, 2.5)
    with pytest.raises(ValueError, match="between 0 and k"):
        representation_error(s, f, s.k + 1)
    with pytest.raises(ValueError, match="NaN"):
        error_bound(s, np.full(m.n_vertices, np.nan), 3)
    with pytest.raises(ValueError, match="shape"):
        representation_error(s, f[:-1], 3)
    with pytest.raises(ValueError, match="Spectrum"):
        representation_error((s.stiffness, s.mass), f, 3)


# --- A-orthonormalisation --------------------------------------------------------------------------
def test_a_orthonormalize_keeps_the_flag_of_spans_and_does_not_touch_input(sheet):
    m, s = sheet
    A = s.mass
    X = np.column_stack([m.vertices, m.vertices[:, 0] * m.vertices[:, 1]])
    before = X.copy()
    Q = a_orthonormalize(X, A, prepend=np.ones(m.n_vertices))
    np.testing.assert_array_equal(X, before)
    np.testing.assert_allclose(Q.T @ A @ Q, np.eye(5), atol=1e-12)
    # Gram-Schmidt is triangular: the first j columns span the first j inputs.
    full = np.column_stack([np.ones(m.n_vertices), X])
    for j in range(1, 6):
        coef = np.linalg.lstsq(Q[:, :j], full[:, :j], rcond=None)[0]
        assert np.abs(Q[:, :j] @ coef - full[:, :j]).max() < 1e-10 * np.abs(full).max()


def test_a_orthonormalize_survives_ill_conditioning_and_flags_dependence(blob):
    m, s = blob
    x = m.vertices[:, 0] / np.abs(m.vertices[:, 0]).max()
    V = np.column_stack([x**k for k in range(12)])  # monomials: condition number ~1e8
    Q = a_orthonormalize(V, s.mass)
    assert np.abs(Q.T @ s.mass @ Q - np.eye(12)).max() < m.n_vertices * EPS
    dependent = np.column_stack([V[:, :3], V[:, 1] - 2 * V[:, 2]])
    with pytest.raises(ValueError, match="rank-deficient: column 3"):
        a_orthonormalize(dependent, s.mass)
    assert a_orthonormalize(dependent, s.mass, drop_dependent=True).shape == (m.n_vertices, 3)


# --- the worst-case constant -----------------------------------------------------------------------
@pytest.mark.parametrize("n", [1, 2, 9, 25, 60])
def test_eigenbasis_is_optimal_to_1e8(blob, sheet, n):
    for _, s in (blob, sheet):
        for method in ("dense", "sparse"):
            c = worst_case_ratio(s.vectors[:, :n], s.stiffness, s.mass, method=method)
            assert c * s.values[n] == pytest.approx(1.0, abs=1e-8)


def test_sparse_eigenbasis_on_a_larger_mesh():
    s = eigenbasis(shapes.bumpy_sphere(4), 41)  # 2562 vertices, ARPACK eigenvectors
    c = worst_case_ratio(s.vectors[:, :40], s.stiffness, s.mass)
    assert c * s.values[40] == pytest.approx(1.0, abs=1e-8)


def test_matches_an_independent_schur_complement_oracle(blob, sheet):
    for _, s in (blob, sheet):
        B = perturbed_eigenbasis(s, 12, 0.5, seed=1)
        expected = schur_oracle(B, s.stiffness, s.mass)
        for method in ("dense", "sparse"):
            assert worst_case_ratio(B, s.stiffness, s.mass, method=method) == pytest.approx(expected, rel=1e-9)


@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), n=st.integers(2, 60))
def test_any_other_basis_is_worse(blob, seed, n):
    m, s = blob
    rng = np.random.default_rng(seed)
    B = np.column_stack([np.ones(m.n_vertices), rng.normal(size=(m.n_vertices, n - 1))])
    assert worst_case_ratio(B, s.stiffness, s.mass) * s.values[n] > 1 + 1e-6


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), n=st.integers(2, 40), eps=st.floats(1e-3, 1.0))
def test_nearby_bases_are_worse_and_the_sup_is_a_sup(blob, seed, n, eps):
    m, s = blob
    B = perturbed_eigenbasis(s, n, eps, seed)
    c, worst = worst_case_ratio(B, s.stiffness, s.mass, return_vector=True)
    assert c * s.values[n] > 1.0
    Q = a_orthonormalize(B, s.mass)

    def ratio(f):
        r = f - Q @ (Q.T @ (s.mass @ f))
        return np.einsum("ij,ij->j", r, s.mass @ r) / np.einsum("ij,ij->j", f, s.stiffness @ f)

    # the returned function attains C(V) and no random function exceeds it
    assert ratio(worst[:, None])[0] == pytest.approx(c, rel=1e-9)
    f = np.random.default_rng(seed + 1).normal(size=(m.n_vertices, 200))
    assert np.all(ratio(f) <= c * (1 + 1e-12))


def test_infinite_without_the_constant(blob):
    m, s = blob
    assert worst_case_ratio(s.vectors[:, 1:10], s.stiffness, s.mass) == np.inf
    assert worst_case_ratio(s.vectors[:, 1:10], s.stiffness, s.mass, method="sparse") == np.inf
    c, f = worst_case_ratio(s.vectors[:, 1:10], s.stiffness, s.mass, return_vector=True)
    # zero energy at working precision (round-off of f.W.f is ~ n eps ||W|| ||f||^2), unit error
    zero = m.n_vertices * EPS * sp.linalg.norm(s.stiffness, 1) * (f @ f)
    assert c == np.inf and dirichlet_energy(s.stiffness, f) < zero


def test_two_components_need_both_constants():
    a, b = shapes.icosphere(1), shapes.icosphere(1, radius=2.0)
    m = Mesh(np.vstack([a.vertices, b.vertices + [5.0, 0, 0]]), np.vstack([a.faces, b.faces + a.n_vertices]))
    W, A = stiffness_matrix(m), mass_matrix(m)
    K = kernel_basis(W)
    assert K.shape == (84, 2)
    s = eigenbasis(m, 12)
    assert abs(s.values[1]) < 1e-10  # two zero eigenvalues
    assert worst_case_ratio(np.ones((84, 1)), W, A) == np.inf
    for method in ("dense", "sparse"):
        c = worst_case_ratio(s.vectors[:, :8], W, A, method=method)
        assert c * s.values[8] == pytest.approx(1.0, abs=1e-8)


def test_the_trap_is_measurably_smaller_than_the_exact_constant(blob):
    # Regression test: W restricted to the complement of V (instead of the Schur complement)
    # underestimates C(V) for a basis that W does not map into A V.
    m, s = blob
    n = 20
    B = perturbed_eigenbasis(s, n, 1.0, seed=0)  # exact ~5.0, trap ~1.06
    exact = worst_case_ratio(B, s.stiffness, s.mass) * s.values[n]
    trap = complement_ratio(B, s.stiffness, s.mass) * s.values[n]
    assert 1.0 <= trap and exact > 1.5 * trap, (exact, trap)
    assert exact == pytest.approx(schur_oracle(B, s.stiffness, s.mass) * s.values[n], rel=1e-9)
    # ... and the two coincide for an eigenbasis
    assert complement_ratio(s.vectors[:, :n], s.stiffness, s.mass) * s.values[n] == pytest.approx(1.0, abs=1e-8)
    assert complement_ratio(B, s.stiffness, s.mass) == pytest.approx(
        1.0 / min_rayleigh_quotient(s.stiffness, s.mass, orthogonal_to=B), rel=1e-12
    )


@pytest.mark.parametrize("mass", ["voronoi", "consistent"])
def test_dense_and_sparse_agree(mass):
    m = shapes.bumpy_sphere(3, seed=2)  # 642 vertices
    s = eigenbasis(m, 31, mass_kind=mass)
    rng = np.random.default_rng(5)
    for B in (
        s.vectors[:, :30],
        perturbed_eigenbasis(s, 30, 0.2),
        np.column_stack([np.ones(m.n_vertices), m.vertices, rng.normal(size=(m.n_vertices, 10))]),
    ):
        dense = worst_case_ratio(B, s.stiffness, s.mass, method="dense")
        sparse = worst_case_ratio(B, s.stiffness, s.mass, method="sparse")
        assert sparse == pytest.approx(dense, rel=1e-10)


def test_worst_case_ratio_rejects_bad_input(blob):
    m, s = blob
    W, A = s.stiffness, s.mass
    B = np.array(s.vectors[:, :5])
    before = B.copy()
    worst_case_ratio(B, W, A)
    np.testing.assert_array_equal(B, before)
    with pytest.raises(ValueError, match="2-D"):
        worst_case_ratio(B[:, 0], W, A)
    with pytest.raises(ValueError, match="shape"):
        worst_case_ratio(B[:-1], W, A)
    with pytest.raises(ValueError, match="NaN"):
        worst_case_ratio(np.where(B > 0.1, np.nan, B), W, A)
    with pytest.raises(ValueError, match="rank-deficient"):
        worst_case_ratio(np.column_stack([B, B[:, 1] + B[:, 2]]), W, A)
    with pytest.raises(ValueError, match="columns"):
        worst_case_ratio(np.ones((m.n_vertices, m.n_vertices)), W, A)
    with pytest.raises(ValueError, match="method"):
        worst_case_ratio(B, W, A, method="lobpcg")
    with pytest.raises(ValueError, match="symmetric"):
        worst_case_ratio(B, sp.triu(W).tocsr(), A)
    with pytest.raises(ValueError, match="sparse"):
        worst_case_ratio(B, W.toarray(), A)


# --- the witness argument -----------------------------------------------------------------------------
@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), n=st.integers(1, 60))
def test_witness_function_proves_the_lower_bound(blob, seed, n):
    m, s = blob
    B = np.random.default_rng(seed).normal(size=(m.n_vertices, n))
    f = witness_function(s, B)
    assert np.abs(B.T @ s.mass @ f).max() < 1e-9 * np.abs(B).max()  # A-orthogonal to V
    c = s.project(f)
    assert np.sum(c[: n + 1] ** 2) == pytest.approx(1.0, rel=1e-10)  # in span(phi_0..phi_n)
    assert f @ s.stiffness @ f <= s.values[n] * (1 + 1e-10)  # energy <= lam[n] * error


def test_witness_function_needs_enough_eigenpairs(blob):
    m, _ = blob
    s = eigenbasis(m, 5)
    with pytest.raises(ValueError, match="n \\+ 1 = 6"):
        witness_function(s, s.vectors[:, :5])


def test_the_trap_is_exact_on_a_tilted_eigenbasis_that_w_does_not_map_into_a_v(blob):
    # "W maps V into A V" is sufficient for the trap to be exact, not necessary: the tilt
    # phi_{n-1} + eps phi_m (eps below the closed-form threshold) keeps C(V) lam_n = 1 and the trap
    # equal to it, although W Q leaves A V by a sizeable fraction (docs/maths.md, "Optimality").
    m, s = blob
    n, mm = 10, 15
    lam = s.values
    eps_star = np.sqrt(lam[n - 1] * (lam[mm] - lam[n]) / (lam[mm] * (lam[n] - lam[n - 1])))
    V = np.array(s.vectors[:, :n])
    V[:, n - 1] += 0.5 * eps_star * s.vectors[:, mm]
    Q = a_orthonormalize(V, s.mass)
    WQ = s.stiffness @ Q
    outside = np.linalg.norm(WQ - s.mass @ Q @ (Q.T @ WQ)) / np.linalg.norm(WQ)
    assert outside > 0.05
    assert worst_case_ratio(V, s.stiffness, s.mass) * lam[n] == pytest.approx(1.0, abs=1e-10)
    assert complement_ratio(V, s.stiffness, s.mass) * lam[n] == pytest.approx(1.0, abs=1e-10)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_ky_fan_the_eigenframe_has_the_least_total_energy(blob, sheet, seed):
    # The paper's eq. (6): trace(Q^T W Q) >= lam_0 + ... + lam_{n-1} over A-orthonormal n-frames,
    # with equality for the eigenframe and its rotations, and a second-order excess near it.
    rng = np.random.default_rng(seed)
    for m, s in (blob, sheet):
        n = 8
        lam_sum = s.values[:n].sum()
        rotation = np.linalg.qr(rng.normal(size=(n, n)))[0]
        assert np.trace((s.vectors[:, :n] @ rotation).T @ s.stiffness @ s.vectors[:, :n] @ rotation) == pytest.approx(
            lam_sum, rel=1e-10
        )
        random_frame = a_orthonormalize(rng.normal(size=(m.n_vertices, n)), s.mass)
        assert np.trace(random_frame.T @ s.stiffness @ random_frame) > lam_sum
        noise = rng.normal(size=(m.n_vertices, n)) * np.abs(s.vectors[:, :n]).mean()
        excess = [
            np.trace(Q.T @ s.stiffness @ Q) / lam_sum - 1
            for Q in (a_orthonormalize(s.vectors[:, :n] + e * noise, s.mass) for e in (1e-3, 2e-3))
        ]
        assert excess[0] > 0 and excess[1] / excess[0] == pytest.approx(4.0, rel=2e-2)
