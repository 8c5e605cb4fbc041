import warnings

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from lbo_notebooks import mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.spectral._engine.factor import SymmetricFactor, fill_reducing_order, symmetric_lu
from lbo_notebooks.spectral._solvers import mesh_order


@pytest.fixture(scope="module")
def operators():
    mesh = shapes.bumpy_sphere(3)
    return stiffness_matrix(mesh), mass_matrix(mesh)


def test_order_is_a_deterministic_permutation(operators):
    W, _ = operators
    order = fill_reducing_order(W)
    assert np.array_equal(np.sort(order), np.arange(W.shape[0]))
    assert np.array_equal(order, fill_reducing_order(W.copy()))
    assert fill_reducing_order(sp.eye(2)).tolist() == [0, 1]
    assert fill_reducing_order(sp.csr_matrix((0, 0))).size == 0
    path = sp.diags([np.ones(9), np.ones(9)], [-1, 1]).tocsr()  # no stored diagonal: nothing to warn about
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert sorted(fill_reducing_order(path).tolist()) == list(range(10))


def test_order_depends_on_the_pattern_only(operators):
    W, A = operators
    assert np.array_equal(fill_reducing_order(W - 3.0 * A), fill_reducing_order(abs(W) + abs(A)))


@pytest.mark.parametrize("shift", [-0.5, 7.0, 31.0])
def test_solves_match_an_independent_sparse_solve(operators, shift):
    W, A = operators
    M = W - shift * A
    factor = symmetric_lu(M)
    rng = np.random.default_rng(0)
    b = rng.standard_normal(M.shape[0])
    B = rng.standard_normal((M.shape[0], 3))
    reference = spla.spsolve(M.tocsc(), B)
    x, X = factor.solve(b), factor.solve(B)
    assert np.linalg.norm(X - reference) <= 1e-9 * np.linalg.norm(reference)
    assert np.linalg.norm(M @ x - b) <= 1e-10 * (abs(M).sum(axis=1).max() * np.linalg.norm(x))
    # A vector and a block column agree to round-off (BLAS-2 and BLAS-3 paths round differently).
    column = factor.solve(B)[:, 0]
    assert np.linalg.norm(factor.solve(B[:, 0]) - column) <= 1e-12 * np.linalg.norm(column)


def test_negative_pivots_are_the_inertia(operators):
    W, A = operators
    exact = scipy.linalg.eigh(W.toarray(), A.toarray(), eigvals_only=True)
    for value in np.quantile(exact, [0.1, 0.4, 0.8]) * 1.0001:
        assert symmetric_lu(W - value * A).n_negative == np.count_nonzero(exact < value)


def test_a_shared_order_gives_the_same_solution(operators):
    W, A = operators
    order = fill_reducing_order(abs(W) + abs(A))
    b = np.cos(np.arange(W.shape[0]))
    own, shared = symmetric_lu(W + 2.0 * A).solve(b), symmetric_lu(W + 2.0 * A, order).solve(b)
    assert np.linalg.norm(own - shared) <= 1e-12 * np.linalg.norm(own)


def test_nested_dissection_leaves_less_fill_than_minimum_degree():
    mesh = shapes.torus(1.0, 0.4, 160, 64)  # 10k vertices
    M = (stiffness_matrix(mesh) + mass_matrix(mesh)).tocsc()
    mmd = spla.splu(M, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    assert symmetric_lu(M, fill_reducing_order(M)).nnz < 0.9 * (mmd.L.nnz + mmd.U.nnz)
    assert symmetric_lu(M).nnz == mmd.L.nnz + mmd.U.nnz  # a 10k mesh, no order given: SuperLU's own


def test_large_matrices_are_ordered_by_nested_dissection():
    mesh = shapes.torus(1.0, 0.4, 240, 96)  # 23k vertices, no order given: ordered by METIS
    M = stiffness_matrix(mesh) + mass_matrix(mesh)
    factor = symmetric_lu(M)
    assert np.array_equal(factor.order, fill_reducing_order(M))
    b = np.sin(np.arange(mesh.n_vertices))
    x = factor.solve(b)
    assert np.linalg.norm(M @ x - b) <= 1e-10 * np.linalg.norm(x) * abs(M).sum(axis=1).max()


def test_bad_input_is_refused_and_not_modified(operators):
    W, A = operators
    M = (W + A).tocsr()
    before = M.copy()
    factor = SymmetricFactor(M)
    with pytest.raises(ValueError, match="rhs must have shape"):
        factor.solve(np.ones(3))
    with pytest.raises(ValueError, match="order must be a permutation"):
        SymmetricFactor(M, order=np.arange(3))
    with pytest.raises(ValueError, match="order must be a permutation"):
        SymmetricFactor(M, order=np.zeros(M.shape[0], dtype=int))
    with pytest.raises(ValueError, match="square"):
        fill_reducing_order(sp.csr_matrix((3, 4)))
    with pytest.raises(RuntimeError):  # exactly singular: SuperLU's own error, callers name the cause
        symmetric_lu(sp.csr_matrix(np.array([[1.0, 1.0], [1.0, 1.0]])))
    b = np.ones(M.shape[0])
    factor.solve(b)
    assert (M != before).nnz == 0 and np.array_equal(b, np.ones(M.shape[0]))


def test_mesh_order_is_the_order_of_the_operators_pattern_made_once():
    mesh = shapes.bumpy_sphere(3)
    order = mesh_order(mesh)
    assert mesh_order(mesh) is order  # cached on the mesh
    W, A = stiffness_matrix(mesh), mass_matrix(mesh)
    # The edge graph is the pattern of W (and of every W - b A): the same METIS order.
    assert np.array_equal(order, fill_reducing_order(abs(W) + abs(A)))
    # Shared by a shifted matrix and by the matrix with vertex 0 pinned (the heat method's Poisson step).
    M = W - 9.0 * A
    x = symmetric_lu(M, order).solve(np.ones(M.shape[0]))
    assert np.linalg.norm(M @ x - 1.0) <= 1e-10 * abs(M).sum(axis=1).max() * np.linalg.norm(x)
    P = (W + 1e-3 * A).tocsr()[1:, 1:]
    y = symmetric_lu(P, order[order != 0] - 1).solve(np.ones(P.shape[0]))
    assert np.linalg.norm(P @ y - 1.0) <= 1e-10 * abs(P).sum(axis=1).max() * np.linalg.norm(y)


def test_reading_the_inertia_leaves_no_copy_of_the_factor_behind(operators):
    # SciPy keeps the CSC copies of L and U it builds on first access: a second copy of the
    # factor. The pivots and the fill are read once and those copies emptied; solves still work.
    import tracemalloc

    W, A = operators
    M = W - 7.0 * A
    exact = scipy.linalg.eigh(W.toarray(), A.toarray(), eigvals_only=True)
    tracemalloc.start()
    try:
        factor = symmetric_lu(M, fill_reducing_order(M))
        before = tracemalloc.get_traced_memory()[0]
        assert factor.n_negative == np.count_nonzero(exact < 7.0)
        kept = tracemalloc.get_traced_memory()[0] - before
    finally:
        tracemalloc.stop()
    assert kept < 0.1 * 12 * factor.nnz  # the pivots (n floats), not nnz(L + U) values and indices
    reference = SymmetricFactor(M, fill_reducing_order(M))
    assert factor.nnz == reference.nnz > M.nnz  # nnz read after the inertia, and before it
    assert reference.n_negative == factor.n_negative
    x = factor.solve(np.ones(M.shape[0]))
    assert np.linalg.norm(M @ x - 1.0) <= 1e-10 * abs(M).sum(axis=1).max() * np.linalg.norm(x)
