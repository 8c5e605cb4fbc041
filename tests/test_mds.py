"""Classical, landmark and spectral MDS: exact recovery, convergence to classical MDS, clear errors."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.distance import cdist

from lbo_notebooks import Mesh, MeshError, eigenbasis, shapes
from lbo_notebooks.analyses import farthest_point_sampling, geodesic_distances
from lbo_notebooks.analyses import growth_exponent, least_cost, measure_cost
from lbo_notebooks.analyses import shape_distribution, shape_distribution_distances
from lbo_notebooks.analyses import gram_error, procrustes_error
from lbo_notebooks.analyses._mds import (
    classical_mds,
    landmark_mds,
    SMDS_DEFAULTS,
    scale_mu,
    spectral_mds,
)


@pytest.fixture(scope="module")
def blob():
    """A 162-vertex non-symmetric blob with its full heat-distance matrix, eigenbasis and FPS."""
    m = shapes.bumpy_sphere(2)
    n = m.n_vertices
    D = geodesic_distances(m, np.arange(n))
    samples, fields = farthest_point_sampling(m, n, return_distances=True)
    return m, D, classical_mds(D), eigenbasis(m, n), (samples, fields)


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    return np.linalg.qr(rng.normal(size=(3, 3)))[0]


# --- accuracy metrics --------------------------------------------------------------------------
def test_gram_error_matches_the_dense_definition():
    rng = np.random.default_rng(0)
    X, Z = rng.normal(size=(40, 3)), rng.normal(size=(40, 2))
    Xc, Zc = X - X.mean(0), Z - Z.mean(0)
    dense = np.linalg.norm(Zc @ Zc.T - Xc @ Xc.T) / np.linalg.norm(Xc @ Xc.T)
    assert gram_error(Z, X) == pytest.approx(dense, rel=1e-12)


def test_error_values_on_known_perturbations():
    rng = np.random.default_rng(1)
    X = rng.normal(size=(60, 3))
    assert gram_error(2.0 * X, X) == pytest.approx(3.0)  # ||4G - G|| / ||G||
    assert procrustes_error(1.1 * X, X) == pytest.approx(0.1)


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), reflect=st.booleans())
def test_errors_ignore_rigid_motions(seed, reflect):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(30, 3))
    Q = random_rotation(rng) * (-1.0 if reflect else 1.0)
    Z = X @ Q + rng.normal(size=3)
    assert gram_error(Z, X) < 1e-10 and procrustes_error(Z, X) < 1e-10


def test_metric_input_errors():
    with pytest.raises(ValueError, match="same vertices"):
        gram_error(np.ones((3, 2)), np.ones((4, 2)))
    with pytest.raises(ValueError, match="same dimension"):
        procrustes_error(np.ones((3, 2)), np.ones((3, 3)))
    with pytest.raises(ValueError, match="NaN"):
        gram_error(np.full((3, 2), np.nan), np.ones((3, 2)))


# --- classical MDS -----------------------------------------------------------------------------
@pytest.mark.parametrize("n", [50, 600])  # dense eigh and Lanczos paths
def test_classical_mds_recovers_points_up_to_rigid_motion(n):
    rng = np.random.default_rng(n)
    P = rng.normal(size=(n, 3)) * [3.0, 2.0, 1.0]
    D = cdist(P, P)
    D_before = D.copy()
    X = classical_mds(D, dim=3)
    assert procrustes_error(X, P) < 1e-10
    assert np.abs(cdist(X, X) - D).max() < 1e-9 * D.max()
    assert np.array_equal(D, D_before)  # the caller's matrix is untouched
    assert np.abs(X.mean(axis=0)).max() < 1e-10 * np.abs(X).max()


def test_classical_mds_of_a_plane_in_3d_gives_a_flat_third_axis():
    rng = np.random.default_rng(2)
    P = np.column_stack([rng.normal(size=(80, 2)), np.zeros(80)]) @ random_rotation(rng)
    X = classical_mds(cdist(P, P), dim=3)
    assert np.abs(X[:, 2]).max() < 1e-6 * np.abs(X).max() and procrustes_error(X, P) < 1e-6


def test_classical_mds_from_a_mesh_equals_from_its_matrix(blob):
    m, D, X, _, _ = blob
    assert np.allclose(classical_mds(m), X)


def test_classical_mds_refuses_sizes_that_do_not_fit(blob):
    m, D, *_ = blob
    with pytest.raises(MemoryError, match=r"needs \d+\.\d\d GiB"):
        classical_mds(D, memory_budget=1e4)
    with pytest.raises(MemoryError, match="spectral_mds"):
        classical_mds(m, memory_budget=1e4)  # refused before any distance is computed


@pytest.mark.parametrize(
    "D, match",
    [(np.ones((3, 4)), "square"), (-np.ones((4, 4)), "non-negative"), (np.full((4, 4), np.inf), "NaN or inf")],
)
def test_classical_mds_bad_matrices(D, match):
    with pytest.raises(ValueError, match=match):
        classical_mds(D, dim=2)


def test_classical_mds_bad_dim():
    with pytest.raises(ValueError, match="dim=5 must be smaller"):
        classical_mds(np.zeros((5, 5)), dim=5)


# --- landmark MDS ------------------------------------------------------------------------------
def test_landmark_mds_with_every_vertex_is_classical_mds(blob):
    # with symmetric distances (heat distances are not exactly symmetric) the two coincide
    m, D, X, _, (samples, fields) = blob
    S = 0.5 * (D + D.T)
    assert gram_error(landmark_mds(S[samples], landmarks=samples), classical_mds(S)) < 1e-10


def test_landmark_mds_converges_to_classical(blob):
    m, D, X, _, (samples, fields) = blob
    errs = [gram_error(landmark_mds(fields[:q], landmarks=samples[:q]), X) for q in (10, 20, 40, 162)]
    # measured 0.12, 0.05, 0.034, 0.018 (not 0: heat distances are not exactly symmetric)
    assert all(a > b for a, b in zip(errs, errs[1:])) and errs[-1] < 0.03


def test_landmark_mds_leaves_the_callers_distances_alone(blob):
    m, D, X, _, (samples, fields) = blob
    before = fields.copy()
    landmark_mds(fields[:20], landmarks=samples[:20])
    assert np.array_equal(fields, before)


def test_landmark_mds_from_a_mesh(blob):
    m, D, X, _, _ = blob
    Z = landmark_mds(m, n_samples=40)
    assert Z.shape == (m.n_vertices, 3) and gram_error(Z, X) < 0.06


def test_landmark_mds_errors(blob):
    m, *_ = blob
    with pytest.raises(ValueError, match="more than the mesh's 162 vertices"):
        landmark_mds(m, n_samples=163)
    with pytest.raises(ValueError, match="landmarks="):
        landmark_mds(np.ones((3, 10)))
    with pytest.raises(ValueError, match="dim=3 must be smaller than the number of landmarks"):
        landmark_mds(m, n_samples=3)


# --- spectral MDS ------------------------------------------------------------------------------
@pytest.mark.parametrize("sampled", ["fields", "rows", "pairs"])
def test_spectral_mds_with_the_full_basis_and_all_samples_is_classical(blob, sampled):
    # k = q = n and mu -> 0: Phi M interpolates every column exactly (Phi M = I up to the sample
    # order), so D2 is reproduced and SMDS is classical MDS.
    m, D, X, spec, sampling = blob
    n = m.n_vertices
    Z = spectral_mds(m, k=n, n_samples=n, mu=1e-10, sampled=sampled, spectrum=spec, sampling=sampling)
    assert gram_error(Z, X) < 1e-6


def test_rows_need_fewer_samples_than_pairs(blob):
    # A sampled row is projected onto the eigenfunctions exactly; only the pairs must be interpolated
    # both ways. With as many samples as eigenfunctions, rows are far closer to classical MDS.
    m, D, X, spec, sampling = blob
    err = {s: gram_error(spectral_mds(m, k=40, n_samples=40, sampled=s, spectrum=spec, sampling=sampling), X)
           for s in ("rows", "pairs")}
    assert err["rows"] < 0.5 * err["pairs"]


def test_fields_are_classical_scaling_of_the_interpolated_matrix(blob):
    # Oracle in n x n: D2 ~ (Phi M F + F.T M.T Phi.T) / 2 formed densely, B = -1/2 J D2 J and its
    # top three eigenpairs must be what the (k + q)-dimensional reduction gives.
    m, D, X, spec, sampling = blob
    n, k, q = m.n_vertices, 30, 60
    Z, info = spectral_mds(m, k=k, n_samples=q, mu=0.3, spectrum=spec, sampling=sampling, return_details=True)
    assert info["sampled"] == "fields" and info["alpha"] is None
    phi, lam, S = spec.vectors[:, :k], np.maximum(spec.values[:k], 0.0), sampling[0][:q]
    M = np.linalg.solve(phi[S].T @ phi[S] + info["mu_abs"] * np.diag(lam**2), phi[S].T)
    D2 = phi @ M @ sampling[1][:q] ** 2
    J = np.eye(n) - 1.0 / n
    w, V = np.linalg.eigh(-0.25 * J @ (D2 + D2.T) @ J)
    assert gram_error(Z, V[:, -3:] * np.sqrt(w[-3:])) < 1e-10
    assert np.allclose(info["eigenvalues"], w[::-1][:4], rtol=1e-10)


def test_fields_break_the_floor_of_the_eigenfunctions(blob):
    # Rows and pairs embed in span(Phi): no better than the classical embedding projected onto it.
    # Fields add the sampled distance fields to the span, and go below that floor with few
    # eigenfunctions (measured: k = 20, q = 120: floor 1.6%, fields 0.7%, rows 1.6%).
    m, D, X, spec, sampling = blob
    Q = np.linalg.qr(spec.vectors[:, :20])[0]
    floor = gram_error(Q @ (Q.T @ X), X)
    err = {s: gram_error(spectral_mds(m, k=20, n_samples=120, sampled=s, spectrum=spec, sampling=sampling), X)
           for s in ("fields", "rows")}
    assert err["rows"] >= floor * (1 - 1e-9) and err["fields"] < 0.6 * floor


def test_spectral_mds_leaves_the_given_sampling_untouched(blob):
    m, D, X, spec, sampling = blob
    before = sampling[1].copy()
    for sampled in ("fields", "rows", "pairs"):
        spectral_mds(m, k=30, n_samples=60, sampled=sampled, spectrum=spec, sampling=sampling)
    assert np.array_equal(sampling[1], before)


def test_defaults_are_the_signature_defaults():
    import inspect

    params = inspect.signature(spectral_mds).parameters
    assert all(params[name].default == SMDS_DEFAULTS[name] for name in ("energy", "mu", "sampled"))


def test_spectral_mds_converges_with_eigenfunctions(blob):
    m, D, X, spec, sampling = blob
    errs = [gram_error(spectral_mds(m, k=k, n_samples=162, spectrum=spec, sampling=sampling), X)
            for k in (10, 20, 40, 80)]
    # measured (exact distances) 0.10, 0.033, 0.012, 0.0066
    assert all(a > b for a, b in zip(errs, errs[1:])) and errs[-1] < 0.015


def test_spectral_mds_converges_with_samples(blob):
    m, D, X, spec, sampling = blob
    errs = [gram_error(spectral_mds(m, k=40, n_samples=q, spectrum=spec, sampling=sampling), X)
            for q in (20, 40, 80, 162)]
    assert all(a > b for a, b in zip(errs, errs[1:])) and errs[-1] < 0.02


def test_spectral_mds_is_rigid_and_scale_covariant(blob):
    # mu is dimensionless: scaling the shape by s scales the canonical form by s, nothing else.
    m, D, X, _, _ = blob
    rng = np.random.default_rng(5)
    moved = m.with_vertices(3.0 * m.vertices @ random_rotation(rng) + 1.0)
    Z = spectral_mds(m, n_samples=60, k=40)
    Zm = spectral_mds(moved, n_samples=60, k=40)
    assert procrustes_error(Zm / 3.0, Z) < 1e-6


def test_spectral_mds_own_looser_eigenbasis_changes_nothing_that_matters():
    # spectral_mds computes its eigenbasis with tol = SMDS_EIGEN_TOL (1e-6): the same embedding as
    # with the default 1e-10 basis, to far below its own (sub-percent) error.
    from lbo_notebooks.analyses import SMDS_EIGEN_TOL

    assert SMDS_EIGEN_TOL == 1e-6
    m = shapes.bumpy_sphere(4)
    Z = spectral_mds(m, n_samples=180, k=120)
    Z_tight = spectral_mds(m, n_samples=180, k=120, spectrum=eigenbasis(m, 120))
    assert gram_error(Z, Z_tight) < 1e-8


def test_spectral_mds_details_and_determinism(blob):
    m, *_ = blob
    Z1, info = spectral_mds(m, n_samples=50, k=30, return_details=True)
    Z2 = spectral_mds(m, n_samples=50, k=30)
    assert np.array_equal(Z1, Z2)
    assert info["eigengap"] > 1 and info["eigenvalues"].shape == (4,) and info["samples"].shape == (50,)
    assert set(info["timings"]) == {"eigenbasis", "sampling", "embedding", "total"} and info["mu_abs"] > 0
    assert info["sampled"] == "fields" and info["alpha"] is None
    _, rows = spectral_mds(m, n_samples=50, k=30, sampled="rows", return_details=True)
    assert rows["alpha"].shape == (30, 30) and np.array_equal(rows["alpha"], rows["alpha"].T)


@pytest.mark.parametrize("sampled", ["rows", "pairs"])
@pytest.mark.parametrize("energy, power", [("dirichlet", 1), ("biharmonic", 2)])
def test_energy_is_the_penalty_of_the_interpolation(blob, energy, power, sampled):
    # Independent oracle: M solves the stacked least-squares problem [Phi_s; sqrt(mu_abs) Lam^(p/2)] M
    # = [I; 0], i.e. values at the samples are interpolated by the coefficients c minimising
    # ||Phi_s c - d||^2 + mu_abs sum lam_i^p c_i^2. Pairs: alpha = M D_s M.T. Rows: each sampled row's
    # coefficients are its A-inner products with the eigenfunctions, alpha = M (D2[S, :] A Phi).
    m, D, X, spec, sampling = blob
    k, q, mu = 30, 60, 0.3
    Z, info = spectral_mds(m, n_samples=q, k=k, mu=mu, energy=energy, sampled=sampled, spectrum=spec,
                           sampling=sampling, return_details=True)
    phi_s, lam = spec.vectors[sampling[0][:q], :k], np.maximum(spec.values[:k], 0.0)
    mu_abs = scale_mu(mu, phi_s, lam, energy=energy)
    assert info["mu_abs"] == pytest.approx(mu_abs, rel=1e-12)
    stacked = np.vstack([phi_s, np.sqrt(mu_abs) * np.diag(lam ** (power / 2))])
    M = np.linalg.lstsq(stacked, np.vstack([np.eye(q), np.zeros((k, q))]), rcond=None)[0]
    S = sampling[0][:q]
    if sampled == "pairs":
        ds = D[np.ix_(S, S)] ** 2
        alpha = M @ (0.5 * (ds + ds.T)) @ M.T
    else:
        phi = spec.vectors[:, :k]
        coefficients = np.array([[np.sum(D[s] ** 2 * spec.mass.diagonal() * phi[:, j]) for j in range(k)] for s in S])
        alpha = M @ coefficients
        alpha = 0.5 * (alpha + alpha.T)
    assert info["sampled"] == sampled
    assert np.linalg.norm(info["alpha"] - alpha) <= 1e-9 * np.linalg.norm(alpha)


def test_biharmonic_is_less_sensitive_to_mu(blob):
    # A 100-fold range of mu moves the biharmonic interpolant less than the Dirichlet one (docs/maths.md, "Multidimensional scaling").
    m, D, X, spec, sampling = blob
    spread = {}
    for energy in ("dirichlet", "biharmonic"):
        errs = [gram_error(spectral_mds(m, n_samples=100, k=40, mu=mu, energy=energy, spectrum=spec,
                                        sampling=sampling), X) for mu in (0.01, 0.1, 1.0)]
        spread[energy] = max(errs) - min(errs)
    assert spread["biharmonic"] < spread["dirichlet"]


def test_scale_mu_is_dimensionless():
    rng = np.random.default_rng(0)
    phi_s, lam = rng.normal(size=(30, 10)), np.linspace(0, 9, 10)
    assert scale_mu(0.05, 2 * phi_s, lam / 4) == pytest.approx(16 * scale_mu(0.05, phi_s, lam))
    # biharmonic: mu_abs lam^2 must scale like Phi_s.T Phi_s, so mu_abs gains a second factor 4
    assert scale_mu(0.05, 2 * phi_s, lam / 4, energy="biharmonic") == pytest.approx(
        64 * scale_mu(0.05, phi_s, lam, energy="biharmonic"))


def test_spectral_mds_errors(blob):
    m, D, X, spec, sampling = blob
    with pytest.raises(ValueError, match="more than the mesh's 162 vertices"):
        spectral_mds(m, n_samples=200, k=20)
    with pytest.raises(ValueError, match="dim=20 must be smaller than k"):
        spectral_mds(m, dim=20, k=20, n_samples=50)
    with pytest.raises(ValueError, match="mu must be a positive number"):
        spectral_mds(m, k=20, n_samples=50, mu=0.0)
    for bad in ("laplacian", None, ["biharmonic"]):
        with pytest.raises(ValueError, match="energy must be one of"):
            spectral_mds(m, k=20, n_samples=50, energy=bad)
    for bad in ("columns", None, True):
        with pytest.raises(ValueError, match="sampled must be 'fields'"):
            spectral_mds(m, k=20, n_samples=50, sampled=bad)
    with pytest.raises(ValueError, match="spectrum has 10 eigenpairs"):
        spectral_mds(m, k=20, n_samples=50, spectrum=eigenbasis(m, 10))
    with pytest.raises(ValueError, match="k >= 50"):
        spectral_mds(m, k=20, n_samples=50, sampling=(sampling[0][:10], sampling[1][:10]))


def test_disconnected_mesh_is_refused():
    a = shapes.icosphere(1)
    two = Mesh(np.vstack([a.vertices, a.vertices + 3.0]), np.vstack([a.faces, a.faces + a.n_vertices]))
    for call in (lambda: spectral_mds(two, k=10, n_samples=20),
                 lambda: landmark_mds(two, n_samples=10),
                 lambda: classical_mds(two)):
        with pytest.raises(MeshError, match="keep_largest_component"):
            call()


# --- shape distributions and cost measurement ---------------------------------------------------
def test_shape_distribution_is_a_density_invariant_to_similarities():
    rng = np.random.default_rng(3)
    P = rng.normal(size=(150, 3))
    h = shape_distribution(P, bins=40, max_ratio=50.0)        # every ratio is in range
    assert np.sum(h) * 50.0 / 40 == pytest.approx(1.0, rel=1e-12)
    moved = 0.3 * P @ random_rotation(rng) - 2.0
    assert np.allclose(shape_distribution(moved), shape_distribution(P), rtol=0, atol=1e-12 * shape_distribution(P).max())
    # two points: every distance equals the mean, so all the mass is in the bin holding 1
    h2 = shape_distribution([[0.0, 0.0], [1.0, 1.0]], bins=3, max_ratio=3.0)
    assert np.array_equal(h2, [0.0, 1.0, 0.0])


def test_shape_distribution_distances_and_errors():
    rng = np.random.default_rng(4)
    sets = [rng.normal(size=(80, 3)), rng.uniform(size=(60, 3)), rng.normal(size=(80, 3)) * [1, 1, 0.01]]
    D = shape_distribution_distances(sets, bins=20)
    assert np.allclose(D, D.T) and np.all(np.diag(D) == 0) and np.all(D[~np.eye(3, dtype=bool)] > 0)
    assert np.all(D <= 2 + 1e-12)  # L1 distance of two densities on the same bins
    for bad, match in [([[0.0, 0.0]], "at least two points"), ([[1.0, 2.0], [1.0, 2.0]], "coincide")]:
        with pytest.raises(ValueError, match=match):
            shape_distribution(bad)
    with pytest.raises(ValueError, match="bins must be"):
        shape_distribution(sets[0], bins=0)
    # a generator of point sets is a list of them; nothing, a number or a string is not
    assert np.array_equal(shape_distribution_distances(iter(sets), bins=20), D)
    for bad in ([], 5, "points"):
        with pytest.raises(ValueError, match="point_sets must be a list of one or more"):
            shape_distribution_distances(bad)


def test_growth_exponent_and_cost():
    n = np.array([100.0, 300.0, 900.0])
    assert growth_exponent(n, 5 * n**1.5) == pytest.approx(1.5, abs=1e-12)
    with pytest.raises(ValueError, match="positive"):
        growth_exponent([1, 2], [0.0, 1.0])
    with pytest.raises(ValueError, match="same length"):
        growth_exponent([1, 2, 3], [1.0, 2.0])
    # classical MDS holds two n x n float64 matrices at once: the trace must see them
    D = cdist(*(2 * [np.random.default_rng(0).normal(size=(300, 3))]))
    cost = measure_cost(classical_mds, D)
    assert cost["peak_bytes"] >= 2 * 8 * 300**2 and cost["result"].shape == (300, 3) and cost["cpu_seconds"] >= 0
    with pytest.raises(ValueError, match="function must be the function to measure"):
        measure_cost(D)  # the arguments without the function


@pytest.mark.parametrize("timed", [False, pytest.param(True, marks=pytest.mark.timing)], ids=["result", "cpu-seconds"])
def test_least_cost_keeps_the_cheapest_run(timed):
    import time

    pauses = iter([0.0, 0.05, 0.0])
    calls = []

    def busy() -> int:
        # CPU time, not sleep: the second call is the expensive one
        end = time.process_time() + next(pauses)
        while time.process_time() < end:
            pass
        calls.append(1)
        return len(calls)

    cost = least_cost(2, busy)
    assert len(calls) == 2 and cost["result"] == 1
    assert not timed or cost["cpu_seconds"] < 0.05  # a CPU time: opt-in (LBO_TIMING_TESTS=1, tests/conftest.py)
    with pytest.raises(ValueError, match="runs"):
        least_cost(0, busy)


def test_signature_defaults_are_the_documented_ones():
    import inspect

    params = inspect.signature(spectral_mds).parameters
    assert params["mu"].default == SMDS_DEFAULTS["mu"] and params["energy"].default == SMDS_DEFAULTS["energy"]
    m = shapes.icosphere(1)  # 42 vertices: the default k and q are capped at n
    assert params["sampled"].default == SMDS_DEFAULTS["sampled"] == "fields"
    _, info = spectral_mds(m, return_details=True)
    assert info["samples"].shape == (42,)
    _, info = spectral_mds(m, sampled="rows", return_details=True)
    assert info["alpha"].shape == (42, 42)
