import dataclasses

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp

from lbo_notebooks import Mesh, eigenbasis, mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.spectral import count_below, slice_eigsh
from lbo_notebooks.spectral._engine.slicing import Pencil, plan_sets
from lbo_notebooks.spectral._engine.factor import SliceFactor


def operators(mesh):
    return stiffness_matrix(mesh), mass_matrix(mesh)


def dense_values(W, A):
    return scipy.linalg.eigh(W.toarray(), A.toarray(), eigvals_only=True)


def check_pairs(W, A, values, vectors):
    """Residuals and A-orthonormality relative to the scale of the operators."""
    eps = np.finfo(float).eps
    n, k = vectors.shape
    scale = abs(W).sum(axis=1).max() + abs(values).max() * abs(A).sum(axis=1).max()
    residual = W @ vectors - (A @ vectors) * values
    assert np.abs(residual).max() <= 1e6 * eps * scale * np.abs(vectors).max()
    gram = vectors.T @ (A @ vectors)
    assert np.abs(gram - np.eye(k)).max() <= 1e5 * eps * np.sqrt(k)


def start(n):
    return 1.0 + 0.5 * np.cos(np.arange(n, dtype=np.float64))


@pytest.mark.parametrize("mesh", [shapes.icosphere(3), shapes.bumpy_sphere(3), shapes.torus(1.0, 0.4, 30, 12)])
def test_count_below_is_the_inertia(mesh):
    W, A = operators(mesh)
    exact = dense_values(W, A)
    for value in np.quantile(exact, [0.01, 0.2, 0.5, 0.9]) * 1.0001:
        assert count_below(W, A, value) == np.count_nonzero(exact < value)


@pytest.mark.parametrize("slice_size", [5, 12, 60])
def test_agrees_with_the_dense_solver_and_finds_every_eigenvalue(slice_size):
    W, A = operators(shapes.bumpy_sphere(3))
    exact = dense_values(W, A)
    k = 80  # several slices for slice_size 5 and 12: k larger than one slice holds
    values, vectors, n_below = slice_eigsh(W, A, k, v0=start(W.shape[0]), shift=0.01, slice_size=slice_size)
    np.testing.assert_allclose(values[1:], exact[1:k], rtol=1e-8)
    assert abs(values[0]) <= 1e-8 * values[1]
    assert n_below >= k and count_below(W, A, 0.5 * (exact[n_below - 1] + exact[n_below])) == n_below
    check_pairs(W, A, values, vectors)


def test_agrees_with_plain_arpack_through_eigenbasis():
    mesh = shapes.bumpy_sphere(4)
    ours = eigenbasis(mesh, 120, solver="slicing")
    plain = eigenbasis(mesh, 120, solver="arpack")
    np.testing.assert_allclose(ours.values[1:], plain.values[1:], rtol=1e-8)
    # Same A-orthogonal projector on every well-separated leading subspace.
    for m in (10, 60, 119):
        if ours.values[m] / ours.values[m - 1] - 1 > 1e-3:
            p = ours.vectors[:, :m].T @ (ours.mass @ plain.vectors[:, :m])
            assert abs(np.linalg.svd(p, compute_uv=False).min() - 1) < 1e-6


def test_sphere_multiplicities_survive_slices_that_cut_through_clusters():
    W, A = operators(shapes.icosphere(4))
    k = 64  # l = 0..7
    values, vectors, _ = slice_eigsh(W, A, k, v0=start(W.shape[0]), shift=0.01, slice_size=7)
    l = np.repeat(np.arange(8), 2 * np.arange(8) + 1)
    exact = l * (l + 1.0)
    assert np.all(np.abs(values[1:] / exact[1:] - 1) < 0.03)  # O(h^2) discretisation error
    for j in range(1, 8):  # the inertia between clusters is exactly (l + 1)^2
        between = 0.5 * (j * (j - 1) + j * (j + 1))
        assert count_below(W, A, between) == j * j
        assert np.count_nonzero(values < between) == j * j
    check_pairs(W, A, values, vectors)


def test_near_degenerate_clusters():
    # A sphere stretched by 1e-5 splits each 2l+1 cluster by ~1e-5 relative: all members must be found.
    sphere = shapes.icosphere(3)
    mesh = Mesh(sphere.vertices * np.array([1.0, 1.0 + 1e-5, 1.0 - 1e-5]), sphere.faces)
    W, A = operators(mesh)
    exact = dense_values(W, A)
    values, vectors, _ = slice_eigsh(W, A, 49, v0=start(W.shape[0]), shift=0.01, slice_size=6)
    np.testing.assert_allclose(values[1:], exact[1:49], rtol=1e-8)
    check_pairs(W, A, values, vectors)


def test_torus_pairs_with_sets_reaching_past_the_neighbouring_shift():
    # Exact double eigenvalues (rotational symmetry) and Lanczos sets wider than one interval.
    W, A = operators(shapes.torus(1.0, 0.4, 100, 32))
    exact = dense_values(W, A)
    values, vectors, _ = slice_eigsh(W, A, 300, v0=start(W.shape[0]), shift=0.01, slice_size=60)
    np.testing.assert_allclose(values[1:], exact[1:300], rtol=1e-8)
    check_pairs(W, A, values, vectors)


def test_k_close_to_n():
    W, A = operators(shapes.icosphere(2))
    n = W.shape[0]
    exact = dense_values(W, A)
    k = n - 12
    values, vectors, _ = slice_eigsh(W, A, k, v0=start(n), shift=0.01, slice_size=40)
    np.testing.assert_allclose(values[1:], exact[1:k], rtol=1e-8)
    check_pairs(W, A, values, vectors)


def test_partial_multiple_eigenvalue_from_lanczos_is_caught_and_recovered():
    # Lanczos at -s with 11 vectors returns 3 of the 5 l=2 eigenvalues of this icosphere and four
    # l=3 ones instead; the inertia count at the next shift exposes it and the slice is redone.
    W, A = operators(shapes.icosphere(3))
    values, vectors, _ = slice_eigsh(W, A, 9, v0=start(W.shape[0]), shift=0.01 * 4 * np.pi / A.sum())
    np.testing.assert_allclose(values[1:], dense_values(W, A)[1:9], rtol=1e-8)
    check_pairs(W, A, values, vectors)


def test_deterministic():
    W, A = operators(shapes.bumpy_sphere(3))
    a = eigenbasis((W, A), 50, solver="slicing")
    b = eigenbasis((W, A), 50, solver="slicing")
    assert np.array_equal(a.values, b.values) and np.array_equal(a.vectors, b.vectors)


def test_bad_arguments():
    W, A = operators(shapes.icosphere(2))
    n = W.shape[0]
    for k in (0, n, 2.5, True):
        with pytest.raises(ValueError, match="k must be"):
            slice_eigsh(W, A, k, v0=start(n), shift=0.01)
    with pytest.raises(ValueError, match="shift must be"):
        slice_eigsh(W, A, 5, v0=start(n), shift=-1.0)
    with pytest.raises(ValueError, match="slice_size"):
        slice_eigsh(W, A, 5, v0=start(n), shift=0.01, slice_size=0)
    with pytest.raises(ValueError, match="v0 must be"):
        slice_eigsh(W, A, 5, v0=np.ones(3), shift=0.01)
    with pytest.raises(ValueError, match="positive semidefinite"):
        slice_eigsh(-W, A, 5, v0=start(n), shift=0.01)
    # One eigenvalue (the constant's, 0) below -shift: only the first interval's count can tell.
    with pytest.raises(ValueError, match="positive semidefinite"):
        slice_eigsh(W - 0.02 * A, A, 5, v0=start(n), shift=0.01)
    with pytest.raises(ValueError, match="solver must be"):
        eigenbasis(shapes.icosphere(2), 5, solver="lapack")
    for tol in (0.0, -1e-8, 1.0, np.nan, True, "1e-8"):
        with pytest.raises(ValueError, match="tol must be"):
            slice_eigsh(W, A, 5, v0=start(n), shift=0.01, tol=tol)
        with pytest.raises(ValueError, match="tol must be"):
            eigenbasis(shapes.icosphere(2), 5, tol=tol)
    with pytest.raises(ValueError, match="order must be a permutation"):
        slice_eigsh(W, A, 5, v0=start(n), shift=0.01, order=np.zeros(n, dtype=np.intp))


def test_a_looser_tolerance_keeps_the_eigenvalues_and_the_span():
    # tol bounds each pair's residual; eigenvalues converge as its square, and the basis is
    # A-orthonormalised afterwards either way.
    mesh = shapes.bumpy_sphere(4)
    tight = eigenbasis(mesh, 120, solver="slicing")
    loose = eigenbasis(mesh, 120, solver="slicing", tol=1e-8)
    np.testing.assert_allclose(loose.values[1:], tight.values[1:], rtol=1e-10)
    gram = loose.vectors.T @ (loose.mass @ loose.vectors)
    assert np.abs(gram - np.eye(120)).max() <= 1e-12
    m = 100
    while tight.values[m] / tight.values[m - 1] - 1 < 1e-3:  # a well-separated leading subspace
        m -= 1
    p = tight.vectors[:, :m].T @ (tight.mass @ loose.vectors[:, :m])
    assert 1 - np.linalg.svd(p, compute_uv=False).min() < 1e-10
    arpack = eigenbasis(mesh, 60, solver="arpack", tol=1e-8)
    np.testing.assert_allclose(arpack.values[1:], tight.values[1:60], rtol=1e-10)


def test_a_mesh_and_its_operators_give_the_same_basis():
    # eigenbasis(mesh) orders the factorisations by the mesh's edge graph (shared with the heat
    # method); eigenbasis((W, A)) orders W's pattern: the same graph, so the same result.
    mesh = shapes.bumpy_sphere(3)
    a = eigenbasis(mesh, 100, solver="slicing")
    b = eigenbasis(operators(mesh), 100, solver="slicing")
    assert np.array_equal(a.values, b.values) and np.array_equal(a.vectors, b.vectors)


@dataclasses.dataclass(frozen=True)
class LanczosRun:
    """One call of the public block Lanczos (krylov.nearest_eigenpairs) as slice_eigsh made it."""

    shift: float
    low: float
    high: float
    deflated: bool


def lanczos_runs(monkeypatch, change=None) -> list:
    """Record every Lanczos run slice_eigsh starts (a set's or a completion's), in the order they start.

    ``change(run, values, vectors)`` may alter what a set's run returns (e.g. drop a pair).
    """
    import lbo_notebooks.spectral._engine.eigensolver as eigensolver

    original, runs = eigensolver.nearest_eigenpairs, []

    def recorded(solve, W, A, shift, nev, **kwargs):
        run = LanczosRun(float(shift), *map(float, kwargs["window"]), kwargs.get("deflate") is not None)
        runs.append(run)
        values, vectors = original(solve, W, A, shift, nev, **kwargs)
        return (values, vectors) if change is None or run.deflated else change(run, values, vectors)

    monkeypatch.setattr(eigensolver, "nearest_eigenpairs", recorded)
    return runs


def test_sets_start_from_the_top_of_the_spectrum(monkeypatch):
    # Higher windows take longer: they are placed and started first, so that a worker is not left
    # with the longest set at the end. The result does not depend on the order.
    started = lanczos_runs(monkeypatch)
    W, A = operators(shapes.bumpy_sphere(3))
    values, _, _ = slice_eigsh(W, A, 80, v0=start(W.shape[0]), shift=0.01, slice_size=20, workers=1)
    shifts = [run.shift for run in started]
    assert len(shifts) == 4 and shifts == sorted(shifts, reverse=True)
    np.testing.assert_allclose(values[1:], dense_values(W, A)[1:80], rtol=1e-8)


@pytest.mark.parametrize("mesh, k, slice_size", [(shapes.disk(n_rings=30), 100, 100), (shapes.bumpy_sphere(3), 80, 20)])
def test_windows_are_centred_on_their_shifts(monkeypatch, mesh, k, slice_size):
    # Lanczos converges last at the window edge farthest from its shift: every set's shift lies
    # inside its window and no window is lopsided below its shift (the lowest reaches down to the
    # floor, its shift well inside it), together the windows cover the spectrum from below its
    # lowest eigenvalue to above lam_k, neighbouring windows overlap, and the result is unchanged.
    runs = lanczos_runs(monkeypatch)
    W, A = operators(mesh)
    values, vectors, _ = slice_eigsh(W, A, k, v0=start(W.shape[0]), shift=0.01, slice_size=slice_size, workers=2)
    sets = sorted((run for run in runs if not run.deflated), key=lambda run: run.shift)
    assert len(sets) == plan_sets(k, slice_size, 2) and not any(run.deflated for run in runs)
    lowest, *others = sets
    assert -0.01 <= lowest.low < values[0] and sets[-1].high > values[-1]  # the floor .. past lam_k
    assert 0.3 < (lowest.shift - lowest.low) / (lowest.high - lowest.low) < 0.8
    for window in others:
        assert window.low < window.shift < window.high
        assert window.shift - window.low <= window.high - window.shift + 1e-12 * window.high  # not lopsided down
    for below, above in zip([lowest, *others], others):
        assert above.low < below.high and below.shift < above.low
    np.testing.assert_allclose(values[1:], dense_values(W, A)[1:k], rtol=1e-8)
    check_pairs(W, A, values, vectors)


@pytest.mark.parametrize("slice_size", [10, 40])
def test_windows_next_to_big_clusters_hold_what_their_sets_expect(slice_size):
    # Two copies of an icosphere: eigenvalues 2 (2l + 1)-fold, up to 34 copies at k = 300. A window
    # sized from the density between two shifts, or reaching past the shift above into a cluster,
    # held three times the pairs its set was sized for and its Lanczos run did not converge.
    sphere = shapes.icosphere(3)
    mesh = Mesh(np.vstack([sphere.vertices, sphere.vertices + [3.0, 0.0, 0.0]]), np.vstack([sphere.faces, sphere.faces + sphere.n_vertices]))
    W, A = operators(mesh)
    values, vectors, _ = slice_eigsh(W, A, 300, v0=start(W.shape[0]), shift=0.01, slice_size=slice_size, workers=2)
    exact = dense_values(W, A)[:300]
    np.testing.assert_allclose(values[2:], exact[2:], rtol=1e-8)
    # Pairs of different sets are A-orthogonal up to residual / gap (the Lanczos tolerance is 1e-10):
    # here up to 5e-10 with 30 sets (1-3e-11 before the windows were centred), above check_pairs'
    # 1e5 eps sqrt(k); a missed or doubled pair would be O(1). eigenbasis re-orthonormalises.
    eps = np.finfo(float).eps
    scale = abs(W).sum(axis=1).max() + abs(values).max() * abs(A).sum(axis=1).max()
    assert np.abs(W @ vectors - (A @ vectors) * values).max() <= 1e6 * eps * scale * np.abs(vectors).max()
    assert np.abs(vectors.T @ (A @ vectors) - np.eye(300)).max() < 1e-8


def test_a_shift_is_placed_beside_a_cluster_it_cannot_split():
    from lbo_notebooks.spectral._engine.slicing import place_shift

    W, A = operators(shapes.icosphere(3))  # l = 2: five eigenvalues near 6, counts 4 -> 9 across them
    pencil = Pencil(W, A, None, start(W.shape[0]), 1e-10)
    first = SliceFactor(shift=-0.01, n_below=0, lu=None)
    above = SliceFactor.of(W, A, 9.0, None)
    assert above.n_below == 9
    placed = place_shift(pencil, 6.0, 0.5, first, above, 1.0)
    assert placed is not None and placed.n_below == 4  # below the cluster, the nearer side that fits
    # Between two counts on either side of the same cluster no shift fits: None, not a loop.
    low, high = SliceFactor.of(W, A, 5.0, None), SliceFactor.of(W, A, 7.0, None)
    assert (low.n_below, high.n_below) == (4, 9)
    assert place_shift(pencil, 6.0, 0.5, low, high, 1.0) is None


def test_no_shift_placed_is_an_error_and_eigenbasis_falls_back_to_arpack(monkeypatch):
    import lbo_notebooks.spectral._engine.eigensolver as eigensolver

    monkeypatch.setattr(eigensolver, "place_shift", lambda *args: None)
    mesh = shapes.bumpy_sphere(3)
    W, A = operators(mesh)
    with pytest.raises(RuntimeError, match="could not place a shift"):
        slice_eigsh(W, A, 60, v0=start(W.shape[0]), shift=0.01)
    with pytest.warns(RuntimeWarning, match="Falling back to one ARPACK run"):
        fallback = eigenbasis(mesh, 100)
    np.testing.assert_allclose(fallback.values[1:], eigenbasis(mesh, 100, solver="arpack").values[1:], rtol=1e-12)


def test_inputs_are_not_modified():
    W, A = operators(shapes.bumpy_sphere(3))
    W0, A0 = W.copy(), A.copy()
    slice_eigsh(W, A, 20, v0=start(W.shape[0]), shift=0.01, slice_size=8)
    assert (W != W0).nnz == 0 and (A != A0).nnz == 0


def test_a_cluster_larger_than_the_remaining_count_is_stepped_over():
    # k = 101 on a sphere: l = 0..9 fill exactly 100 eigenvalues, the 101st opens the 21-fold
    # l = 10 cluster, so no shift gains exactly one new eigenvalue (this once looped and failed).
    sphere = shapes.icosphere(4)
    sliced = eigenbasis(sphere, 101, solver="slicing")
    plain = eigenbasis(sphere, 101, solver="arpack")
    assert np.abs(sliced.values - plain.values).max() <= 1e-8 * plain.values[-1]
    assert count_below(sliced.stiffness, sliced.mass, sliced.values[-1] * (1 + 1e-6)) >= 101


def test_the_top_is_certified_from_a_gap_when_the_window_top_count_is_unavailable(monkeypatch):
    # Usually the count at the top of the last window certifies lam_k; when that point is an
    # eigenvalue (no count: its factorisation is singular), a count in a gap above lam_k must do
    # it instead. The top window is the first one slicing.plan_window plans (from the top down).
    import lbo_notebooks.spectral._engine.eigensolver as eigensolver

    plan, factor, windows, refused = eigensolver.plan_window, Pencil.factor, [], []

    def planned(*args, **kwargs):
        windows.append(plan(*args, **kwargs))
        return windows[-1]

    def singular_at_the_top(pencil, shift):
        if windows and shift == windows[0].high and not refused:
            refused.append(shift)
            raise ValueError("W - shift A is singular: the shift is an eigenvalue")
        return factor(pencil, shift)

    W, A = operators(shapes.bumpy_sphere(3))
    exact = dense_values(W, A)
    monkeypatch.setattr(eigensolver, "plan_window", planned)
    monkeypatch.setattr(Pencil, "factor", singular_at_the_top)
    values, vectors, n_below = slice_eigsh(W, A, 70, v0=start(W.shape[0]), shift=0.01, slice_size=30)
    assert refused == [windows[0].high]  # the count at the top of the top window was not available
    np.testing.assert_allclose(values[1:], exact[1:70], rtol=1e-8)
    assert n_below >= 70 and count_below(W, A, 0.5 * (exact[n_below - 1] + exact[n_below])) == n_below
    check_pairs(W, A, values, vectors)


@pytest.mark.parametrize("where", ["below the lowest shift", "above the top shift"])
def test_a_pair_a_set_missed_is_completed_without_redoing_the_set(monkeypatch, where):
    # Lanczos may return only part of an exactly repeated eigenvalue. Here a set is made to drop
    # the pair nearest its shift: the inertia count exposes the gap, and only the missing pair is
    # looked for (A-orthogonally to the found ones), instead of running the whole set again.
    W, A = operators(shapes.bumpy_sphere(3))
    exact = dense_values(W, A)

    def dropping(run, values, vectors):
        lowest, top = run.low < 0, run.shift > 25
        side = values < run.shift if where == "below the lowest shift" else values > run.shift
        if (lowest and where == "below the lowest shift") or (top and where == "above the top shift"):
            drop = np.flatnonzero(side)[np.argmin(np.abs(values[side] - run.shift))]
            keep = np.arange(values.size) != drop
            return values[keep], vectors[:, keep]
        return values, vectors

    runs = lanczos_runs(monkeypatch, dropping)
    values, vectors, n_below = slice_eigsh(W, A, 60, v0=start(W.shape[0]), shift=0.01, slice_size=20, workers=2)
    np.testing.assert_allclose(values[1:], exact[1:60], rtol=1e-8)
    # Residuals as tight as everywhere; across sets the pairs are A-orthogonal up to residual / gap
    # (here 2e-10 between two sets' pairs with or without the drop; eigenbasis refines it away).
    scale = abs(W).sum(axis=1).max() + abs(values).max() * abs(A).sum(axis=1).max()
    residual = W @ vectors - (A @ vectors) * values
    assert np.abs(residual).max() <= 1e6 * np.finfo(float).eps * scale * np.abs(vectors).max()
    assert np.abs(vectors.T @ (A @ vectors) - np.eye(60)).max() < 1e-8
    assert n_below >= 60 and count_below(W, A, values[-1] * (1 + 1e-9)) <= n_below
    sets = [run for run in runs if not run.deflated]
    assert len(sets) == plan_sets(60, 20, 2) and len({run.shift for run in sets}) == len(sets)  # every set ran once: none was redone
    assert len(runs) - len(sets) == 1  # one completion, deflated against the found pairs


def test_below_nested_dissection_min_the_first_factorisation_orders_the_rest(monkeypatch):
    """On a small mesh (642 vertices) no METIS run: SuperLU's minimum degree orders the first shift's
    matrix, and every later factorisation reuses that order (the same fill, no ordering step)."""
    from lbo_notebooks.spectral import _solvers as solvers
    from lbo_notebooks.spectral._engine import eigensolver, factor as sparse_factor

    def no_metis(*args):
        raise AssertionError("METIS ran on a small mesh")

    monkeypatch.setattr(eigensolver, "fill_reducing_order", no_metis)
    monkeypatch.setattr(solvers, "mesh_order", no_metis)
    orders: list = []
    original = sparse_factor.symmetric_lu
    monkeypatch.setattr(sparse_factor, "symmetric_lu", lambda matrix, order=None: orders.append(order) or original(matrix, order))
    mesh = shapes.bumpy_sphere(3)
    W, A = operators(mesh)
    values, vectors, _ = slice_eigsh(W, A, 60, v0=start(W.shape[0]), shift=0.01, slice_size=20, workers=2)
    assert orders[0] is None and len(orders) >= 4
    assert all(order is orders[1] for order in orders[1:])  # one order, made by the first factorisation
    np.testing.assert_allclose(values[1:], dense_values(W, A)[1:60], rtol=1e-9)
    check_pairs(W, A, values, vectors)
    # eigenbasis (forced to slice; its own METIS order is refused above too) gives the same spectrum
    assert abs(eigenbasis(mesh, 60, solver="slicing").values[-1] / values[-1] - 1) < 1e-12


def test_the_first_factorisations_order_gives_the_same_fill_and_pencils_keep_it():
    from lbo_notebooks.spectral._engine.factor import symmetric_lu

    W, A = operators(shapes.torus(1.0, 0.4, 60, 24))
    own = symmetric_lu(W - 30.0 * A)
    reused = symmetric_lu(W - 70.0 * A, own.permutation)
    assert sorted(own.permutation.tolist()) == list(range(W.shape[0]))
    assert reused.nnz == own.nnz and np.array_equal(reused.permutation, own.permutation)
    pencil = Pencil(W, A, None, start(W.shape[0]), 1e-10)
    first = pencil.factor(30.0)
    assert np.array_equal(pencil.order, first.lu.permutation)
    assert np.array_equal(pencil.order, own.permutation)  # SuperLU's minimum degree depends on the pattern only
    second = pencil.factor(70.0)
    assert second.lu.order is pencil.order and second.n_below == count_below(W, A, 70.0)


_FAR_FLOOR_SCRIPT = r"""
import json, sys, time
import numpy as np, scipy.linalg
from lbo_notebooks import mass_matrix, shapes, stiffness_matrix
from lbo_notebooks.spectral import count_below, slice_eigsh
m = shapes.icosphere(3)
W, A = stiffness_matrix(m), mass_matrix(m)
exact = scipy.linalg.eigh(W.toarray(), A.toarray(), eigvals_only=True)
for k, shift in json.loads(sys.argv[1]):
    start = time.perf_counter()
    values, vectors, n_below = slice_eigsh(W, A, k, v0=np.ones(W.shape[0]), shift=shift)
    print(json.dumps({"k": k, "shift": shift, "error": float(np.abs(values - exact[:k]).max() / exact[k - 1]),
                      "gram": float(np.abs(vectors.T @ (A @ vectors) - np.eye(k)).max()),
                      "n_below": n_below, "seconds": time.perf_counter() - start}), flush=True)
"""


@pytest.mark.parametrize("timed", [False, pytest.param(True, marks=pytest.mark.timing)], ids=["result", "seconds"])
def test_a_floor_far_below_the_spectrum_neither_hangs_nor_drops_a_copy(timed):
    # shift is only the floor of slicing (no eigenvalue below -shift). A floor 100 or 1e3 times the
    # spectrum's scale below it once planned the first window from the floor's count, so that the
    # window held most of the spectrum and its Krylov basis grew without bound (no return in 240 s,
    # 1.5 GB). A subprocess with a deadline: a regression fails instead of hanging the suite.
    import json
    import os
    import subprocess
    import sys

    cases = [[10, 100.0], [16, 100.0], [30, 1000.0], [60, 300.0]]
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    try:
        done = subprocess.run([sys.executable, "-c", _FAR_FLOOR_SCRIPT, json.dumps(cases)], capture_output=True, text=True,
                              timeout=90, env=env)
    except subprocess.TimeoutExpired:
        pytest.fail("slice_eigsh with a floor far below the spectrum did not return within 90 s")
    assert done.returncode == 0, done.stderr[-2000:]
    runs = [json.loads(line) for line in done.stdout.splitlines()]
    assert len(runs) == len(cases)
    for run in runs:
        assert run["error"] <= 1e-9 and run["gram"] <= 1e-10 and run["n_below"] >= run["k"], run
        if timed:  # a wall time: opt-in (LBO_TIMING_TESTS=1, tests/conftest.py)
            assert run["seconds"] < 15, run


def test_count_below_refuses_a_value_that_is_not_a_number():
    W, A = operators(shapes.icosphere(2))
    for bad in ("4", float("nan"), float("inf"), True, None):
        with pytest.raises(ValueError, match=r"^value must be a finite number"):
            count_below(W, A, bad)
    with pytest.raises(ValueError, match="same size"):
        count_below(W, A[:10, :10], 1.0)


def test_slice_eigsh_names_bad_operators():
    W, A = operators(shapes.icosphere(2))
    v0 = np.ones(W.shape[0])
    with pytest.raises(ValueError, match=r"^stiffness must be a square \(n, n\) matrix"):
        slice_eigsh(None, A, 5, v0=v0, shift=0.1)
    with pytest.raises(ValueError, match=r"^mass must be a square matrix of the size of stiffness \(162, 162\), "
                                         r"got csr_matrix of shape \(5, 5\)"):
        slice_eigsh(W, A[:5, :5], 5, v0=v0, shift=0.1)
