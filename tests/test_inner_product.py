"""The shared A-inner-product algebra: orthonormaliser, sign rule, solver conventions."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from lbo_notebooks import eigenbasis, mass_matrix, shapes
from lbo_notebooks.inner_product import (
    DENSE_LIMIT,
    a_orthonormalize,
    check_operators,
    default_shift,
    fix_signs,
    start_vector,
    use_dense,
)


@pytest.fixture(scope="module")
def bumpy():
    mesh = shapes.bumpy_sphere(2)
    return mesh, mass_matrix(mesh, "consistent")


def _a_orthonormality_error(Q, A):
    return np.abs(Q.T @ (A @ Q) - np.eye(Q.shape[1])).max()


def test_refine_finishes_nearly_orthonormal_columns_in_order(bumpy):
    mesh, A = bumpy
    Q = a_orthonormalize(np.column_stack([np.ones(mesh.n_vertices), mesh.vertices, mesh.vertices**2]), A)
    eps = np.finfo(float).eps
    noisy = Q + 1e-10 * np.random.default_rng(0).normal(size=Q.shape)
    refined = a_orthonormalize(noisy, A, refine=True)
    assert _a_orthonormality_error(refined, A) < 50 * eps * Q.shape[1]
    # triangular: the columns keep their order and meaning (each moves by about the noise)
    assert np.abs(refined - Q).max() < 1e-8 * np.abs(Q).max()
    # same span and same triangular structure as Gram-Schmidt, to round-off
    np.testing.assert_allclose(refined, a_orthonormalize(noisy, A), atol=1e-12 * np.abs(Q).max())


def test_refine_falls_back_to_gram_schmidt_on_general_input(bumpy):
    mesh, A = bumpy
    X = np.column_stack([np.ones(mesh.n_vertices), mesh.vertices])
    np.testing.assert_array_equal(a_orthonormalize(X, A, refine=True), a_orthonormalize(X, A))
    with pytest.raises(ValueError, match="rank-deficient"):
        a_orthonormalize(np.column_stack([X, X[:, 1] + X[:, 2]]), A, refine=True)


def test_input_is_not_modified(bumpy):
    mesh, A = bumpy
    X = np.array(mesh.vertices)
    before = X.copy()
    a_orthonormalize(X, A)
    fix_signs(X, A)
    np.testing.assert_array_equal(X, before)


def test_sign_rule_is_permutation_invariant_and_idempotent(bumpy):
    mesh, A = bumpy
    s = eigenbasis(mesh, 12, mass_kind="consistent")
    perm = np.random.default_rng(1).permutation(mesh.n_vertices)
    P = sp.csr_matrix((np.ones(mesh.n_vertices), (np.arange(mesh.n_vertices), perm)))
    flipped = -s.vectors
    np.testing.assert_array_equal(fix_signs(flipped, s.mass), s.vectors)  # the rule, not the input, decides
    np.testing.assert_array_equal(fix_signs(s.vectors, s.mass), s.vectors)
    permuted = fix_signs(flipped[perm], P @ s.mass @ P.T)
    np.testing.assert_array_equal(permuted, s.vectors[perm])


def test_solver_conventions():
    A = sp.identity(5, format="csr") * 2.0  # area 10
    assert default_shift(A) == pytest.approx(1e-2 * 4 * np.pi / 10, rel=1e-15)
    assert default_shift(4.0 * A) == pytest.approx(default_shift(A) / 4, rel=1e-15)  # scales like 1 / area
    v0 = start_vector(1000)
    assert v0.min() > 0 and np.ptp(v0) > 0.9  # never orthogonal to constants, not constant
    assert use_dense(DENSE_LIMIT) and not use_dense(DENSE_LIMIT + 1)
    assert use_dense(10**6, "dense") and not use_dense(3, "sparse")
    with pytest.raises(ValueError, match="method must be"):
        use_dense(10, "lanczos")


def test_check_operators_names_the_problem():
    W = sp.csr_matrix(np.array([[1.0, -1.0], [-1.0, 1.0]]))
    with pytest.raises(ValueError, match="symmetric"):
        check_operators(W, sp.csr_matrix(np.array([[1.0, 0.5], [0.0, 1.0]])))
    with pytest.raises(ValueError, match="scipy.sparse"):
        check_operators(W.toarray(), sp.identity(2))
    with pytest.raises(ValueError, match="non-positive diagonal"):
        check_operators(W, sp.diags([1.0, 0.0]))
    dense_ok, _ = check_operators(W.toarray(), np.eye(2), allow_dense=True)
    assert abs(dense_ok - W).max() == 0
