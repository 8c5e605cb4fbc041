"""The shared A-inner-product algebra: orthonormaliser, sign rule, solver conventions."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from lbo_notebooks import eigenbasis, mass_matrix, shapes
from lbo_notebooks.spectral._inner_product import (
    a_orthonormalize,
    check_operators,
    fix_signs,
    fix_signs_in_place,
)
from lbo_notebooks.spectral._mass_products import DiagonalMass, cholesky_qr, mass_operator
from lbo_notebooks.spectral._engine.policy import default_shift, start_vector, use_dense


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
    assert use_dense(50) and not use_dense(50_000)  # a small problem dense, a mesh-sized one sparse
    assert all(use_dense(n) >= use_dense(n + 1) for n in range(1, 5000, 7))  # one switch, dense below it
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


# --- lumped mass as a row scaling; in-place finishing of an eigensolver's own output -------------
def test_mass_operator_is_a_row_scaling_only_for_a_diagonal_mass(bumpy):
    mesh, consistent = bumpy
    lumped = mass_matrix(mesh, "voronoi")
    rng = np.random.default_rng(0)
    X = rng.normal(size=(mesh.n_vertices, 5))
    op = mass_operator(lumped)
    assert isinstance(op, DiagonalMass) and mass_operator(op) is op
    for Y in (X, np.asfortranarray(X), X[:, 0]):
        product = op @ Y
        assert np.allclose(product, lumped @ Y, rtol=1e-15, atol=0)
        if Y.ndim == 2 and not Y.flags.c_contiguous:
            assert product.flags.f_contiguous                            # a Krylov block keeps its order
    assert mass_operator(consistent) is consistent                       # off-diagonal entries: left as it is
    stored_zeros = sp.csr_matrix(lumped + 0.0 * consistent)              # explicit zeros off the diagonal
    assert isinstance(mass_operator(stored_zeros), DiagonalMass)


@pytest.mark.parametrize("kind", ["voronoi", "consistent"])
def test_cholesky_qr_refines_in_place_and_mixes_only_earlier_columns(bumpy, kind):
    mesh = bumpy[0]
    A = mass_matrix(mesh, kind)
    exact = a_orthonormalize(np.random.default_rng(1).normal(size=(mesh.n_vertices, 12)), A)
    rng = np.random.default_rng(2)
    V = exact + 1e-10 * rng.normal(size=exact.shape)
    before = V.copy()
    fresh = cholesky_qr(V, A, out=np.empty(V.shape))
    assert np.array_equal(V, before)                                     # out= elsewhere: V untouched
    assert _a_orthonormality_error(fresh, A) < 1e-14
    # Q = V L^-T with L lower triangular: column j is a combination of columns 0..j of V only
    coefficients = np.linalg.lstsq(V, fresh, rcond=None)[0]
    assert np.abs(np.tril(coefficients, -1)).max() < 1e-8
    in_place = cholesky_qr(V, A, out=V)
    assert in_place is V and np.allclose(V, fresh, rtol=0, atol=1e-14)
    far = np.random.default_rng(3).normal(size=exact.shape)              # not nearly orthonormal
    assert cholesky_qr(far, A, out=far) is None and np.isfinite(far).all()


def test_fix_signs_in_place_is_fix_signs_without_the_copy(bumpy):
    V = np.random.default_rng(4).normal(size=(bumpy[0].n_vertices, 7))
    expected = fix_signs(V, bumpy[1])
    out = fix_signs_in_place(V, bumpy[1])
    assert out is V and np.array_equal(V, expected)
    for bad in (np.ones(5), np.ones((5, 2), dtype=int)):
        with pytest.raises(ValueError, match="2-D float64"):
            fix_signs_in_place(bad)


def test_a_norms_names_a_wrong_shape(bumpy):
    from lbo_notebooks.spectral import a_norms

    mesh, A = bumpy
    n = mesh.n_vertices
    assert a_norms(np.ones((n, 2)), A).shape == (2,)
    for bad in (np.ones(n), np.ones((2, n)), np.ones((n - 1, 2))):
        with pytest.raises(ValueError, match=rf"^X must have shape \({n}, c\): one column per function; got"):
            a_norms(bad, A)


def test_fix_signs_names_a_wrong_shape_and_keeps_nan_columns(bumpy):
    mesh, A = bumpy
    n = mesh.n_vertices
    with pytest.raises(ValueError, match=rf"^vectors must have shape \({n},\) or \({n}, k\)"):
        fix_signs(np.ones((5, 2)), A)
    with pytest.raises(ValueError, match=r"^mass must be None or a square matrix"):
        fix_signs(np.ones(n), "lumped")
    assert np.isnan(fix_signs(np.full((n, 1), np.nan), A)).all()  # unchanged behaviour: no check on values
