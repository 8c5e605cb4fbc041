import numpy as np
import pytest
import scipy.linalg
import scipy.sparse.linalg as spla

from lbo_notebooks import mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.spectral import slice_eigsh
from lbo_notebooks.spectral._engine.factor import SliceFactor
from lbo_notebooks.spectral._engine.krylov import nearest_eigenpairs


def operators(mesh):
    return stiffness_matrix(mesh), mass_matrix(mesh)


def dense(W, A):
    return scipy.linalg.eigh(W.toarray(), A.toarray())


def solver(W, A, shift):
    return SliceFactor.of(W, A, shift).lu.solve


def check_orthonormal(A, vectors):
    gram = vectors.T @ (A @ vectors)
    assert np.abs(gram - np.eye(vectors.shape[1])).max() <= 1e3 * np.finfo(float).eps * np.sqrt(vectors.shape[1])


@pytest.mark.parametrize("block_size", [1, 4, 8])
def test_the_nearest_eigenpairs_agree_with_the_dense_solver(block_size):
    W, A = operators(shapes.bumpy_sphere(3))
    exact, exact_vectors = dense(W, A)
    shift = 0.5 * (exact[40] + exact[41]) + 0.3 * (exact[41] - exact[40])  # off-centre, between two eigenvalues
    values, vectors = nearest_eigenpairs(solver(W, A, shift), W, A, shift, 30, start=np.ones(W.shape[0]), block_size=block_size)
    nearest = np.sort(np.argsort(np.abs(exact - shift))[:30])
    np.testing.assert_allclose(values, exact[nearest], rtol=1e-10)
    check_orthonormal(A, vectors)
    # The same invariant subspace: all principal angles to the dense eigenvectors vanish.
    overlap = vectors.T @ (A @ exact_vectors[:, nearest])
    assert np.linalg.svd(overlap, compute_uv=False).min() > 1 - 1e-8


def test_clusters_are_found_whole_when_the_block_covers_their_exact_multiplicity():
    # l = 3 on the sphere is 7-fold and l = 4 9-fold; the icosphere's symmetry splits them into
    # exactly repeated eigenvalues of multiplicity 3 + 4 and 4 + 5, so a block of 5 finds them all
    # (a block of 4 finds the 5-fold one only through round-off, which differs between BLAS builds).
    W, A = operators(shapes.icosphere(4))
    shift = 15.0  # between l(l+1) = 12 and 20
    values, _ = nearest_eigenpairs(solver(W, A, shift), W, A, shift, 16, start=np.ones(W.shape[0]), block_size=5)
    assert np.count_nonzero(np.abs(values / 12 - 1) < 0.02) == 7
    assert np.count_nonzero(np.abs(values / 20 - 1) < 0.02) == 9


def test_slicing_recovers_a_multiplicity_larger_than_the_block():
    # Sets of blocks of 4 on an icosphere meet 5-fold eigenvalues: where round-off does not bring
    # the fifth copy, the count exposes it and the window is redone with a larger block.
    W, A = operators(shapes.icosphere(4))
    exact = dense(W, A)[0]
    values, _, _ = slice_eigsh(W, A, 120, v0=np.ones(W.shape[0]), shift=0.01, slice_size=30)
    np.testing.assert_allclose(values[1:], exact[1:120], rtol=1e-8)


def test_a_window_returns_exactly_the_eigenvalues_inside_it():
    W, A = operators(shapes.torus(1.0, 0.4, 60, 24))  # exact double eigenvalues (rotations)
    exact, _ = dense(W, A)
    low, high = 0.5 * (exact[30] + exact[31]), 0.5 * (exact[70] + exact[71])
    shift = 0.5 * (low + high) + 1e-3 * (high - low)
    values, vectors = nearest_eigenpairs(
        solver(W, A, shift), W, A, shift, 30, start=np.ones(W.shape[0]), window=(low, high)
    )
    np.testing.assert_allclose(values, exact[31:71], rtol=1e-10)  # 40 found although 30 were expected
    check_orthonormal(A, vectors)


def test_thick_restarts_reach_the_same_answer():
    W, A = operators(shapes.bumpy_sphere(3))
    exact, _ = dense(W, A)
    shift = 0.5 * (exact[60] + exact[61])
    start = np.ones(W.shape[0])
    roomy, _ = nearest_eigenpairs(solver(W, A, shift), W, A, shift, 20, start=start)
    tight, _ = nearest_eigenpairs(solver(W, A, shift), W, A, shift, 20, start=start, max_basis=28)
    np.testing.assert_allclose(tight, roomy, rtol=1e-10)


def test_small_problems_are_solved_densely_and_deterministically():
    W, A = operators(shapes.icosphere(1))  # 42 vertices: a Krylov space would be most of the space
    exact, _ = dense(W, A)
    values, vectors = nearest_eigenpairs(solver(W, A, 7.0), W, A, 7.0, 12, start=np.ones(42))
    nearest = np.sort(np.argsort(np.abs(exact - 7.0))[:12])
    np.testing.assert_allclose(values, exact[nearest], rtol=1e-10)
    W, A = operators(shapes.bumpy_sphere(3))
    a = nearest_eigenpairs(solver(W, A, 30.0), W, A, 30.0, 20, start=np.ones(W.shape[0]))
    b = nearest_eigenpairs(solver(W, A, 30.0), W, A, 30.0, 20, start=np.ones(W.shape[0]))
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])


def test_bad_nev():
    W, A = operators(shapes.icosphere(2))
    for nev in (0, W.shape[0]):
        with pytest.raises(ValueError, match="nev must be"):
            nearest_eigenpairs(solver(W, A, 1.0), W, A, 1.0, nev, start=np.ones(W.shape[0]))


def test_slicing_gives_the_same_bits_with_one_or_two_workers():
    W, A = operators(shapes.bumpy_sphere(4))
    start = np.ones(W.shape[0])
    one = slice_eigsh(W, A, 150, v0=start, shift=0.01, slice_size=40, workers=1)
    two = slice_eigsh(W, A, 150, v0=start, shift=0.01, slice_size=40, workers=2)
    assert np.array_equal(one[0], two[0]) and np.array_equal(one[1], two[1]) and one[2] == two[2]
    plain = np.sort(spla.eigsh(W, k=150, M=A, sigma=-0.01, which="LM")[0])
    np.testing.assert_allclose(one[0][1:], plain[1:], rtol=1e-8)


def test_deflation_returns_only_the_pairs_outside_the_deflated_span():
    # l = 4 on this icosphere is an exactly 5-fold and an exactly 4-fold eigenvalue near 20. With
    # three and two of their eigenvectors deflated, the run returns the other four and no copy of
    # the deflated ones: together they span the whole cluster.
    W, A = operators(shapes.icosphere(4))
    exact, exact_vectors = dense(W, A)
    cluster = np.flatnonzero(np.abs(exact / 20 - 1) < 0.05)
    assert cluster.size == 9
    deflated = exact_vectors[:, [cluster[0], cluster[1], cluster[2], cluster[5], cluster[6]]]
    shift = 20.2
    values, vectors = nearest_eigenpairs(
        solver(W, A, shift), W, A, shift, 4, start=np.ones(W.shape[0]), window=(19.5, 20.5), block_size=8,
        deflate=deflated, min_found=4,
    )
    np.testing.assert_allclose(values, exact[[cluster[3], cluster[4], cluster[7], cluster[8]]], rtol=1e-10)
    check_orthonormal(A, vectors)
    assert np.abs(deflated.T @ (A @ vectors)).max() < 1e-8
    together = np.hstack((deflated, vectors))
    overlap = together.T @ (A @ exact_vectors[:, cluster])
    assert np.linalg.svd(overlap, compute_uv=False).min() > 1 - 1e-8


def test_deflation_needs_vectors_of_the_operators_size():
    W, A = operators(shapes.icosphere(2))
    with pytest.raises(ValueError, match="deflate"):
        nearest_eigenpairs(solver(W, A, 3.0), W, A, 3.0, 4, start=np.ones(W.shape[0]), deflate=np.ones((5, 2)))


@pytest.mark.parametrize("timed", [False, pytest.param(True, marks=pytest.mark.timing)], ids=["memory", "seconds"])
def test_a_window_holding_far_more_than_expected_stays_bounded(timed):
    # A window that holds most of the spectrum (the planning of a set from a far floor did that)
    # once grew the basis past n, each restart larger (1.5 GB and no return in 240 s). Now the basis
    # never outgrows the space: the run ends, with the pairs or a RuntimeError, in bounded time.
    import json
    import os
    import subprocess
    import sys

    script = r"""
import json, time
import numpy as np
from lbo_notebooks import mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.spectral._engine.krylov import nearest_eigenpairs
from lbo_notebooks.spectral._engine.factor import SliceFactor
m = shapes.icosphere(3)
W, A = stiffness_matrix(m), mass_matrix(m) / 16.0
factor = SliceFactor.of(W, A, 62.356)
start = time.perf_counter()
try:
    values, _ = nearest_eigenpairs(factor.lu.solve, W, A, 62.356, 15, start=np.ones(W.shape[0]), window=(-1600.0, 3802.0))
    outcome = f"{values.size} pairs"
except RuntimeError as error:
    outcome = f"RuntimeError: {error}"
# VmHWM: this process's peak, not ru_maxrss (which keeps the forking pytest worker's across exec)
peak_kb = next(int(line.split()[1]) for line in open("/proc/self/status") if line.startswith("VmHWM:"))
print(json.dumps({"outcome": outcome, "seconds": time.perf_counter() - start, "peak_mb": peak_kb / 1024}))
"""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    try:
        done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60, env=env)
    except subprocess.TimeoutExpired:
        pytest.fail("nearest_eigenpairs with an over-full window did not return within 60 s")
    assert done.returncode == 0, done.stderr[-2000:]
    run = json.loads(done.stdout)
    assert run["peak_mb"] < 600, run
    if timed:  # a wall time: opt-in (LBO_TIMING_TESTS=1, tests/conftest.py)
        assert run["seconds"] < 20, run
