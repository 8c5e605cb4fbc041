"""Tests for lbo_notebooks.analyses._rpca: regularized PCA against its closed form and its limits.

Oracles: dense ``scipy.linalg.eigh`` of the n x n pencil (the closed form), the Laplace–Beltrami
eigenbasis (mu -> inf), PCA of the data plus the smoothest A-orthogonal functions (mu -> 0), the
objective identity of docs/maths.md, "Regularized PCA", and random feasible perturbations (optimality).
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp

from lbo_notebooks import eigenbasis, mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.spectral import principal_angles, reconstruct, reconstruction_error
from lbo_notebooks.analyses import (
    RegularizedPCA,
    beta_from_mu,
    mu_from_beta,
    regularized_pca,
)


def _poses(v: np.ndarray) -> np.ndarray:
    """Two smooth 'poses' of the same triangulation: a twist and a bend of the vertices."""
    ang = 0.5 * v[:, 0]
    twisted = np.column_stack(
        [v[:, 0], v[:, 1] * np.cos(ang) - v[:, 2] * np.sin(ang), v[:, 1] * np.sin(ang) + v[:, 2] * np.cos(ang)]
    )
    bent = v + 0.25 * np.column_stack([0.3 * v[:, 1] ** 2, np.zeros(len(v)), v[:, 0] ** 2])
    return np.hstack([twisted, bent])


@pytest.fixture(scope="module")
def setup():
    mesh = shapes.bumpy_sphere(3)  # 642 vertices, no symmetry: simple eigenvalues
    W, A = stiffness_matrix(mesh), mass_matrix(mesh)
    X = _poses(mesh.vertices)
    return mesh, W, A, X


def _dense_top(X, W, A, mu, m):
    U = A @ X
    L = U @ U.T - mu * W.toarray()
    n = W.shape[0]
    w, V = scipy.linalg.eigh(L, A.toarray(), subset_by_index=[n - m - 1, n - 1])
    return w[::-1], V[:, ::-1]


def _centred(X, A):
    a = np.asarray(A.sum(axis=1)).ravel()
    return X - (a @ X) / a.sum()


def _objective(P, X, W, A, mu):
    U = A @ X
    return float(np.sum((P.T @ U) ** 2) - mu * np.trace(P.T @ (W @ P)))


# --- closed form ------------------------------------------------------------------------------
@pytest.mark.parametrize("beta", [1e-4, 0.05, 0.6])
def test_sparse_path_matches_dense_eigh(setup, beta):
    mesh, W, A, X = setup
    m = 40
    solver = RegularizedPCA(X, W, A, center=True)
    res = solver.solve(m, beta=beta, method="sparse")
    w, V = _dense_top(solver.data, W, A, res.mu, m)
    assert (w[m - 1] - w[m]) > 1e-3 * abs(w[m - 1])  # a real gap: the span is well defined
    assert principal_angles(res.basis, V[:, :m], A).max() < 1e-8
    np.testing.assert_allclose(res.values, w[:m], rtol=0, atol=1e-8 * abs(w[0]))
    # Each column is an eigenvector, not just the span.
    cos = np.abs(np.einsum("ij,ij->j", res.basis, A @ V[:, :m]))
    np.testing.assert_allclose(cos, 1.0, atol=1e-8)


def test_uncentred_data_and_consistent_mass(setup):
    mesh, W, _, X = setup
    A = mass_matrix(mesh, "consistent")  # not diagonal: the A inner product must be used throughout
    mu = 1e-3
    P, values = regularized_pca(X, W, A, 30, mu, return_values=True, method="sparse")
    w, V = _dense_top(X, W, A, mu, 30)
    assert principal_angles(P, V[:, :30], A).max() < 1e-8
    np.testing.assert_allclose(values, w[:30], atol=1e-8 * abs(w[0]))
    np.testing.assert_allclose(P.T @ A @ P, np.eye(30), atol=1e-10)


def test_auto_method_is_dense_on_small_meshes_and_agrees(setup):
    mesh, W, A, X = setup
    dense = regularized_pca(X, W, A, 20, 1e-2, center=True)
    sparse = regularized_pca(X, W, A, 20, 1e-2, center=True, method="sparse")
    np.testing.assert_allclose(dense, sparse, atol=1e-7)  # same signs too (fix_signs)


@pytest.mark.parametrize("method", ["dense", "sparse"])
def test_basis_is_a_orthonormal_and_deterministic(setup, method):
    mesh, W, A, X = setup
    P1 = regularized_pca(X, W, A, 25, beta=0.3, center=True, method=method)
    P2 = regularized_pca(X.copy(), W, A, 25, beta=0.3, center=True, method=method)
    np.testing.assert_allclose(P1.T @ A @ P1, np.eye(25), atol=1e-10)
    np.testing.assert_array_equal(P1, P2)


def test_objective_identity(setup):
    # sum_i ||P P^T A x_i - x_i||_A^2 + mu sum_j P_j^T W P_j = trace(X^T A X) - trace(P^T (A X X^T A - mu W) P)
    mesh, W, A, X = setup
    mu = 3e-3
    P = regularized_pca(X, W, A, 15, mu)
    R = P @ (P.T @ (A @ X)) - X
    lhs = np.einsum("ij,ij->", R, A @ R) + mu * np.trace(P.T @ (W @ P))
    rhs = np.trace(X.T @ (A @ X)) - _objective(P, X, W, A, mu)
    assert lhs == pytest.approx(rhs, rel=1e-10)


def test_closed_form_beats_random_feasible_perturbations(setup):
    mesh, W, A, X = setup
    mu, m = 2e-3, 12
    P = regularized_pca(X, W, A, m, mu, center=True)
    Xc = _centred(X, A)
    best = _objective(P, Xc, W, A, mu)
    rng = np.random.default_rng(7)
    a = np.asarray(A.sum(axis=1)).ravel()
    for _ in range(5):
        D = rng.standard_normal(P.shape) / np.sqrt(a)[:, None]
        values = []
        for t in [0.0, 1e-3, 1e-2, 0.1, 0.3]:
            Q = P + t * D
            Q = Q @ np.linalg.inv(np.linalg.cholesky(Q.T @ (A @ Q)).T)  # feasible: Q^T A Q = I
            values.append(_objective(Q, Xc, W, A, mu))
        assert values[0] == pytest.approx(best, rel=1e-12)
        assert np.all(np.diff(values) <= 1e-12 * abs(best))  # monotone away from the optimum
        assert values[-1] < best
    # Rotations inside the span leave the objective unchanged (it depends on the span only).
    rot = np.linalg.qr(rng.standard_normal((m, m)))[0]
    assert _objective(P @ rot, Xc, W, A, mu) == pytest.approx(best, rel=1e-12)


# --- the two limits -----------------------------------------------------------------------------
def test_large_mu_gives_the_eigenbasis(setup):
    mesh, W, A, X = setup
    m = 20
    spectrum = eigenbasis((W, A), m + 1)
    exact = regularized_pca(X, W, A, m, beta=1.0)
    assert principal_angles(exact, spectrum.vectors[:, :m], A).max() < 1e-8
    angles = []
    for beta in [0.9, 0.999, 0.99999]:
        P = regularized_pca(X, W, A, m, beta=beta, center=True, method="sparse")
        angles.append(principal_angles(P, spectrum.vectors[:, :m], A).max())
    assert angles[0] > angles[1] > angles[2]  # converging ...
    assert angles[2] < 1e-3  # ... to the eigenbasis
    assert angles[1] / angles[2] > 30  # at rate O(1 / mu)


def test_small_mu_gives_pca_then_smoothest_complement(setup):
    mesh, W, A, X = setup
    m = 20
    solver = RegularizedPCA(X, W, A, center=True)
    Xc = solver.data
    # PCA oracle: the top eigenvectors of X^T A X mapped back to vertices.
    g, E = np.linalg.eigh(Xc.T @ (A @ Xc))
    pca = Xc @ E[:, ::-1] / np.sqrt(g[::-1])
    r = int((g > 1e-12 * g.max()).sum())
    assert r == 6  # two poses x three coordinates: the rank subtlety
    for method in ["dense", "sparse"]:
        zero = solver.solve(m, 0.0, method=method)
        assert zero.n_data == r
        assert principal_angles(zero.basis[:, :r], pca[:, :r], A).max() < 1e-8
        # The rest is A-orthogonal to the data, and the smoothest such functions.
        assert np.abs(zero.basis[:, r:].T @ (A @ Xc)).max() < 1e-10 * np.abs(zero.basis[:, :r].T @ (A @ Xc)).max()
        energy = np.einsum("ij,ij->j", zero.basis[:, r:], W @ zero.basis[:, r:])
        assert energy[0] == pytest.approx(0.0, abs=1e-10 * energy[1])  # the constant comes first
        assert np.all(np.diff(energy) > 0)
    dense0 = solver.solve(m, 0.0, method="dense").basis
    sparse0 = solver.solve(m, 0.0, method="sparse").basis
    assert principal_angles(dense0, sparse0, A).max() < 1e-8
    # mu -> 0 converges to that limit, PCA directions first.
    angles = []
    for beta in [1e-3, 1e-5, 1e-7]:
        P = solver.solve(m, beta=beta, method="sparse").basis
        angles.append(principal_angles(P, dense0, A).max())
    assert angles[0] > angles[1] > angles[2]
    assert angles[2] < 1e-4
    # At the smallest weight the first r columns are the PCA directions. (At beta = 1e-3 they are
    # not yet: the weakest data direction has already dropped below the constant function.)
    assert principal_angles(P[:, :r], pca[:, :r], A).max() < 1e-4


def test_pca_only_when_m_within_rank(setup):
    mesh, W, A, X = setup
    P, values = regularized_pca(X, W, A, 4, 0.0, center=True, return_values=True)
    Xc = _centred(X, A)
    g = np.linalg.eigvalsh(Xc.T @ (A @ Xc))[::-1]
    np.testing.assert_allclose(values, g[:4], rtol=1e-10)


# --- the dimensionless weight -------------------------------------------------------------------
def test_beta_means_the_same_at_every_scale(setup):
    mesh, W, A, X = setup
    s = 3.0
    P1 = regularized_pca(X, W, A, 15, beta=0.2, center=True)
    P2 = regularized_pca(s * X, W, s**2 * A, 15, beta=0.2, center=True)  # the shape scaled by s
    np.testing.assert_allclose(P2, P1 / s, atol=1e-8)
    mu = mu_from_beta(0.2, X, A, 15, center=True)
    assert beta_from_mu(mu, X, A, 15, center=True) == pytest.approx(0.2)
    assert mu_from_beta(0.0, X, A, 15) == 0.0 and np.isinf(mu_from_beta(1.0, X, A, 15))
    solver = RegularizedPCA(X, W, A, center=True)
    assert solver.mu_from_beta(0.2, 15) == pytest.approx(mu)
    assert solver.beta_from_mu(mu, 15) == pytest.approx(0.2)


def test_sweep_reuses_the_factorisation(setup):
    mesh, W, A, X = setup
    solver = RegularizedPCA(X, W, A, center=True)
    results = solver.sweep(10, betas=[0.1, 0.5])
    again = solver.solve(10, beta=0.5)
    np.testing.assert_allclose(results[1].basis, again.basis, atol=1e-12)
    assert results[0].mu < results[1].mu


# --- evaluation protocol ------------------------------------------------------------------------
def test_reconstruction_error_protocol(setup):
    mesh, W, A, X = setup
    poses = [X[:, :3], X[:, 3:]]
    P = regularized_pca(X, W, A, 10, 0.0, center=True)  # contains the span of the (centred) data
    np.testing.assert_allclose(reconstruction_error(P, A, poses), 0.0, atol=1e-10)
    rec = reconstruct(P, A, poses[0] + 5.0)  # translations are removed and restored
    np.testing.assert_allclose(rec, poses[0] + 5.0, atol=1e-10 * np.abs(poses[0] + 5.0).max())
    spectrum = eigenbasis((W, A), 10)
    e = reconstruction_error(spectrum.vectors, A, mesh.vertices)
    assert isinstance(e, float) and 0 < e < 1
    assert reconstruction_error(spectrum.vectors, A, mesh.vertices + [1.0, -2.0, 3.0]) == pytest.approx(e, rel=1e-12)
    # by hand: relative A-norm after removing A-weighted centroids
    a = np.asarray(A.sum(axis=1)).ravel()
    Y = mesh.vertices - (a @ mesh.vertices) / a.sum()
    R = Y - spectrum.vectors @ (spectrum.vectors.T @ (A @ Y))
    assert e == pytest.approx(np.sqrt(np.sum(R * (A @ R)) / np.sum(Y * (A @ Y))), rel=1e-12)
    with pytest.raises(ValueError, match="A-orthonormal"):
        reconstruction_error(np.ones((mesh.n_vertices, 2)), A, mesh.vertices)


def test_principal_angles_known_angle(setup):
    mesh, W, A, X = setup
    spectrum = eigenbasis((W, A), 3)
    e1, e2 = spectrum.vectors[:, 1], spectrum.vectors[:, 2]
    for theta in [1e-9, 0.3, 1.2]:
        angles = principal_angles(e1[:, None], (np.cos(theta) * e1 + np.sin(theta) * e2)[:, None], A)
        assert angles[0] == pytest.approx(theta, rel=1e-6)


# --- clear errors -------------------------------------------------------------------------------
def test_clear_errors(setup):
    mesh, W, A, X = setup
    n = mesh.n_vertices
    with pytest.raises(ValueError, match="k must be between 1"):
        regularized_pca(X, W, A, n + 1, 1.0)
    with pytest.raises(ValueError, match="k must be between 1"):
        regularized_pca(X, W, A, 0, 1.0)
    with pytest.raises(ValueError, match=r"data must have shape"):
        regularized_pca(X[:-1], W, A, 5, 1.0)
    with pytest.raises(ValueError, match="same size"):
        regularized_pca(X, W, sp.identity(n - 1, format="csr"), 5, 1.0)
    with pytest.raises(ValueError, match="mu must be >= 0"):
        regularized_pca(X, W, A, 5, -1e-3)
    bad = X.copy()
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="NaN"):
        regularized_pca(bad, W, A, 5, 1.0)
    with pytest.raises(ValueError, match="exactly one of mu"):
        regularized_pca(X, W, A, 5, 1.0, beta=0.5)
    with pytest.raises(ValueError, match="exactly one of mu"):
        regularized_pca(X, W, A, 5)
    with pytest.raises(ValueError, match=r"beta must be a number in \[0, 1\]"):
        regularized_pca(X, W, A, 5, beta=1.5)
    with pytest.raises(ValueError, match="method"):
        regularized_pca(X, W, A, 5, 1.0, method="lanczos")
    assert np.all(np.isfinite(X))  # inputs untouched


def test_a_result_built_by_hand_leaves_the_callers_arrays_writable():
    from lbo_notebooks.analyses import RPCAResult

    basis, values = np.ones((3, 2)), np.ones(2)
    result = RPCAResult(basis, values, mu=1.0, n_data=1)
    assert basis.flags.writeable and values.flags.writeable
    assert not result.basis.flags.writeable and np.shares_memory(result.basis, basis)
