"""Descriptors, functional maps and matching: closed forms, invariances, held-out creature pairs."""

import io
import sys

import numpy as np
import pytest
import scipy.optimize
import scipy.spatial

import lbo_notebooks as lbo
from lbo_notebooks.analyses import _functional_maps as fm
from lbo_notebooks.analyses import _matching as matching_module
from lbo_notebooks.analyses import gps, hks, hks_times, wks

from .kernel import cell_outputs, is_widget


def shuffled(mesh, seed):
    """The same surface with its vertices in a random order, and the permutation used."""
    perm = np.random.default_rng(seed).permutation(mesh.n_vertices)
    return lbo.Mesh(mesh.vertices[perm], np.argsort(perm)[mesh.faces]), perm


def mirrored(mesh):
    """Reflection y -> -y, faces reversed so that normals still point outward."""
    return lbo.Mesh(mesh.vertices * [1.0, -1.0, 1.0], mesh.faces[:, ::-1])


@pytest.fixture(scope="module")
def dog():
    return lbo.creature("dog", "standing", n_vertices=2000)


@pytest.fixture(scope="module")
def dog_walking():
    return lbo.creature("dog", "walking", n_vertices=2000)


# --- descriptors -----------------------------------------------------------------------------
@pytest.mark.parametrize("t", [0.3, 1.0, 3.0])
def test_hks_of_the_unit_sphere_is_the_closed_form(t):
    s = lbo.eigenbasis(lbo.shapes.icosphere(4), 49)  # l = 0..6
    exact = sum((2 * l + 1) / (4 * np.pi) * np.exp(-l * (l + 1) * t) for l in range(40))
    h = hks(s, [t])[:, 0]
    # Discretisation: eigenvalues of icosphere(4) are within 0.5% of l(l+1), the lumped mass
    # varies by a few percent per vertex; truncation at l = 6 costs exp(-56 t) < 1e-7.
    assert np.abs(h / exact - 1).max() < 1e-2


def test_hks_default_times_follow_the_scale():
    sphere = lbo.shapes.icosphere(3)
    s1, s2 = lbo.eigenbasis(sphere, 16), lbo.eigenbasis(sphere.with_vertices(2 * sphere.vertices), 16)
    np.testing.assert_allclose(hks_times(s2), 4 * hks_times(s1), rtol=1e-9)
    np.testing.assert_allclose(hks(s2), hks(s1) / 4, rtol=1e-8)  # phi^2 scales with 1 / area


def test_descriptors_are_invariant_to_rigid_motion_and_vertex_order(dog):
    s = lbo.eigenbasis(dog, 40)
    rot = np.linalg.qr(np.random.default_rng(0).normal(size=(3, 3)))[0]
    moved = lbo.eigenbasis(dog.with_vertices(dog.vertices @ rot.T + [1.0, -2.0, 0.5]), 40)
    permuted, perm = shuffled(dog, 3)
    sp = lbo.eigenbasis(permuted, 40)
    for f in (hks, wks):
        ref = f(s)
        np.testing.assert_allclose(f(moved), ref, rtol=1e-6, atol=1e-8 * ref.max())
        np.testing.assert_allclose(f(sp), ref[perm], rtol=1e-6, atol=1e-8 * ref.max())
    # GPS depends on eigenvector signs; the sign rule commutes with permutations.
    np.testing.assert_allclose(gps(sp, 10), gps(s, 10)[perm], atol=1e-6 * np.abs(gps(s, 10)).max())


def test_wks_rows_are_weighted_averages_of_phi_squared(dog):
    s = lbo.eigenbasis(dog, 30)
    w = wks(s, n_energies=10)
    # Each column integrates to 1 against the mass: sum_i g_i <phi_i^2, 1>_A / sum_i g_i = 1.
    np.testing.assert_allclose(np.asarray(s.mass.sum(axis=0)).ravel() @ w, 1.0, rtol=1e-9)


def test_descriptor_bad_input():
    s = lbo.eigenbasis(lbo.shapes.icosphere(2), 10)
    with pytest.raises(ValueError, match="Spectrum"):
        hks(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="positive"):
        hks(s, [-1.0])
    with pytest.raises(ValueError, match="sigma"):
        wks(s, [0.0, 1.0])
    with pytest.raises(ValueError, match="between 2"):
        gps(s, 11)
    a = lbo.shapes.icosphere(1)
    two = lbo.Mesh(np.vstack([a.vertices, a.vertices + 3.0]), np.vstack([a.faces, a.faces + a.n_vertices]))
    with pytest.raises(lbo.MeshError, match="components"):
        wks(lbo.eigenbasis(two, 10))


# --- functional maps -------------------------------------------------------------------------
def test_map_of_a_rotated_sphere_is_orthogonal_and_block_diagonal():
    sphere = lbo.shapes.icosphere(3)
    rot = np.linalg.qr(np.random.default_rng(1).normal(size=(3, 3)))[0]
    s1, s2 = lbo.eigenbasis(sphere, 16), lbo.eigenbasis(sphere.with_vertices(sphere.vertices @ rot.T), 16)
    C = fm.map_from_points(np.arange(sphere.n_vertices), s1, s2)
    # Identity map: C = Phi_2.T A Phi_1, orthogonal because both bases span the same space...
    np.testing.assert_allclose(C @ C.T, np.eye(16), atol=1e-6)
    # ... and block diagonal by degree l (eigenspaces of dimension 1, 3, 5, 7): the rotation
    # mixes functions only inside an eigenspace.
    degree = np.repeat(np.arange(4), [1, 3, 5, 7])
    off = degree[:, None] != degree[None, :]
    assert np.abs(C[off]).max() < 1e-3
    assert np.abs(np.abs(C[0, 0]) - 1) < 1e-9


def test_map_of_a_shuffled_copy_is_a_signed_identity(dog):
    s = lbo.eigenbasis(dog, 20)
    shuffled_dog, perm = shuffled(dog, 5)
    s2 = lbo.eigenbasis(shuffled_dog, 20)
    C = fm.map_from_points(perm, s, s2)
    np.testing.assert_allclose(C, np.eye(20), atol=1e-6)  # deterministic signs survive shuffling


def test_estimate_map_is_the_minimiser_of_its_energy(dog, dog_walking):
    k, p = 6, 4
    s1, s2 = lbo.eigenbasis(dog, k), lbo.eigenbasis(dog_walking, k)
    D1, D2 = wks(s1, n_energies=p), wks(s2, n_energies=p)
    w_lap, w_comm, w_or = 0.3, 0.2, 0.5
    C = fm.estimate_map(dog, dog_walking, s1, s2, D1, D2, k=k, laplacian_weight=w_lap,
                        commutativity_weight=w_comm, orientation_weight=w_or, n_operators=p)
    # The same energy written out directly, minimised by a generic optimiser.
    unit = [fm._unit_columns(D, s.mass) for D, s in ((D1, s1), (D2, s2))]
    A, B = s1.project(unit[0], k), s2.project(unit[1], k)
    lam = (s1.values[None, :k] - s2.values[:k, None]) ** 2
    lam /= np.linalg.norm(lam)
    X, Y = fm.multiplication_operators(s1, unit[0], k), fm.multiplication_operators(s2, unit[1], k)
    O1, O2 = fm.orientation_operators(dog, s1, unit[0], k), fm.orientation_operators(dog_walking, s2, unit[1], k)

    def energy(c):
        Cm = c.reshape(k, k)
        e = np.sum((Cm @ A - B) ** 2) + w_lap * np.sum(lam * Cm**2)
        e += w_comm * sum(np.sum((Cm @ x - y @ Cm) ** 2) for x, y in zip(X, Y))
        return e + w_or * sum(np.sum((Cm @ x - y @ Cm) ** 2) for x, y in zip(O1, O2))

    ref = scipy.optimize.minimize(energy, np.zeros(k * k), method="BFGS", options={"gtol": 1e-10}).x
    assert energy(C.ravel()) <= energy(ref) * (1 + 1e-8)
    np.testing.assert_allclose(C.ravel(), ref, atol=1e-4 * np.abs(ref).max())


def test_orientation_term_tells_a_shape_from_its_mirror_image(dog, dog_walking):
    k = 20
    s1 = lbo.eigenbasis(dog, k)
    D1 = fm._unit_columns(wks(s1, n_energies=10), s1.mass)

    def preserving_and_reversing(other):
        s2 = lbo.eigenbasis(other, k)
        C = fm.map_from_points(np.arange(other.n_vertices), s1, s2)  # the true map
        D2 = fm._unit_columns(wks(s2, n_energies=10), s2.mass)
        O1, O2 = fm.orientation_operators(dog, s1, D1, k), fm.orientation_operators(other, s2, D2, k)
        keep = sum(np.linalg.norm(C @ a - b @ C) ** 2 for a, b in zip(O1, O2))
        flip = sum(np.linalg.norm(C @ a + b @ C) ** 2 for a, b in zip(O1, O2))
        return keep, flip

    keep, flip = preserving_and_reversing(dog_walking)
    assert keep < 0.1 * flip  # a pose change keeps the orientation
    keep, flip = preserving_and_reversing(mirrored(dog))
    assert flip < 1e-6 * keep  # the mirror image reverses it: exactly, since it is an exact reflection


def test_functional_map_bad_input(dog):
    s = lbo.eigenbasis(dog, 10)
    with pytest.raises(ValueError, match="shape"):
        fm.map_from_points(np.arange(5), s, s)
    with pytest.raises(ValueError, match="outside"):
        fm.map_from_points(np.full(dog.n_vertices, dog.n_vertices), s, s)
    with pytest.raises(ValueError, match="k must be"):
        fm.estimate_map(dog, dog, s, s, wks(s), wks(s), k=11)
    with pytest.raises(ValueError, match="same number of columns"):
        fm.estimate_map(dog, dog, s, s, wks(s), wks(s)[:, :3], k=5)
    with pytest.raises(ValueError, match="non-negative"):
        fm.estimate_map(dog, dog, s, s, wks(s), wks(s), k=5, orientation_weight=-1.0)


# --- matching --------------------------------------------------------------------------------
# Held-out pairs: species, resolution and poses differ from the dog standing/walking pair of the
# notebook and the benchmark; the defaults of `match` were not tuned on any of them.
@pytest.mark.parametrize(
    "species, n_vertices, source_pose, target_pose",
    [("horse", 3000, "standing", "galloping"), ("dog", 2500, "sitting", "head_turned")],
)
def test_match_recovers_shuffled_pose_pairs(species, n_vertices, source_pose, target_pose):
    source = lbo.creature(species, source_pose, n_vertices=n_vertices)
    target, perm = shuffled(lbo.creature(species, target_pose, n_vertices=n_vertices), 11)
    p2p = lbo.match(source, target)
    err = lbo.matching_error(source, p2p, perm)
    assert err.mean() < 0.05


def test_match_of_a_shuffled_copy_is_exact(dog):
    target, perm = shuffled(dog, 2)
    p2p = lbo.match(dog, target, k=20, k_final=30)
    assert np.mean(p2p == perm) > 0.99


def test_matching_error_and_curve(dog):
    n = dog.n_vertices
    assert not lbo.matching_error(dog, np.arange(n), np.arange(n)).any()
    # Exact geodesics are symmetric: the error of sending everything to vertex 0 is the distance
    # field of vertex 0. (Heat-method distances are not symmetric near the source.)
    sphere = lbo.shapes.icosphere(3)
    m = sphere.n_vertices
    far = lbo.matching_error(sphere, np.zeros(m, dtype=int), np.arange(m), method="exact")
    direct = lbo.geodesic_distances(sphere, [0], method="exact")[0] / np.sqrt(sphere.area)
    np.testing.assert_allclose(far, direct, rtol=1e-6, atol=1e-9 * direct.max())
    t, frac = lbo.error_curve(far)
    assert np.all(np.diff(frac) >= 0) and frac[0] == 1 / m  # only vertex 0 has zero error
    with pytest.raises(ValueError, match="same length"):
        lbo.matching_error(dog, np.arange(n), np.arange(n - 1))
    with pytest.raises(ValueError, match="outside"):
        lbo.matching_error(dog, np.arange(n) + 1, np.arange(n))
    with pytest.raises(ValueError, match="non-negative"):
        lbo.error_curve([-1.0])


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"k": 1}, "k must"),
        ({"k_final": 2.5}, "k_final must"),
        ({"alpha": 2.0}, "alpha"),
        ({"n_descriptors": 0}, "n_descriptors"),
        ({"laplacian_weight": -1.0}, "laplacian_weight"),
        ({"orientation_weight": float("nan")}, "orientation_weight"),
        ({"zoomout_step": 0}, "zoomout_step"),
        ({"n_samples": 10}, "n_samples"),
        ({"progress": "yes"}, "progress"),
    ],
)
def test_match_names_the_bad_argument_before_computing_anything(dog, monkeypatch, kwargs, name):
    def computed(*args, **kw):
        raise AssertionError("match computed an eigenbasis before checking its arguments")

    monkeypatch.setattr(matching_module, "eigenbasis", computed)
    with pytest.raises(ValueError, match=name):
        lbo.match(dog, dog, **kwargs)


def test_match_bad_input(dog):
    with pytest.raises(ValueError, match="Mesh"):
        lbo.match(dog.vertices, dog)
    with pytest.raises(ValueError, match="at least k"):
        lbo.match(dog, dog, k=30, k_final=20)
    with pytest.raises(ValueError, match="alpha"):
        lbo.match(dog, dog, alpha=2.0)


# --- nearest neighbours and sampled ZoomOut ---------------------------------------------------
def test_nearest_rows_is_the_exhaustive_nearest_neighbour():
    rng = np.random.default_rng(4)
    points, queries = rng.normal(size=(3000, 40)), rng.normal(size=(2500, 40))
    exact = scipy.spatial.distance.cdist(queries, points).argmin(axis=1)
    np.testing.assert_array_equal(fm._nearest_rows(queries, points), exact)
    # Single precision: the same points up to near-ties, and never a farther one by more than rounding.
    single = fm._nearest_rows(queries, points, dtype=np.float32)
    d = np.linalg.norm(queries - points[single], axis=1), np.linalg.norm(queries - points[exact], axis=1)
    assert np.mean(single == exact) > 0.999
    np.testing.assert_allclose(d[0], d[1], rtol=1e-5)
    # The blocks of queries are shared among threads: the same answer for any number of them.
    for workers in (1, 2, 3):
        np.testing.assert_array_equal(fm._nearest_rows(queries, points, dtype=np.float32, workers=workers), single)


def test_points_from_map_is_the_k_d_tree_answer(dog, dog_walking):
    # The previous implementation queried a cKDTree; the blocked search must find the same points.
    s1, s2 = lbo.eigenbasis(dog, 40), lbo.eigenbasis(dog_walking, 40)
    C = fm.map_from_points(np.arange(dog.n_vertices), s1, s2)
    tree = scipy.spatial.cKDTree(s1.vectors @ C.T)
    dist, ref = tree.query(s2.vectors)
    p2p = fm.points_from_map(C, s1, s2)
    assert np.mean(p2p == ref) > 0.999
    np.testing.assert_allclose(np.linalg.norm(s2.vectors - s1.vectors[p2p] @ C.T, axis=1), dist, rtol=1e-5)


def test_sampled_zoomout_is_as_accurate_as_zoomout_on_every_vertex():
    source = lbo.creature("horse", "standing", n_vertices=3000)
    target, perm = shuffled(lbo.creature("horse", "galloping", n_vertices=3000), 11)
    every = lbo.matching_error(source, lbo.match(source, target, n_samples=None), perm).mean()
    assert np.array_equal(lbo.match(source, target), lbo.match(source, target, n_samples=None))  # < 5000 vertices
    sampled = lbo.matching_error(source, lbo.match(source, target, n_samples=1000), perm).mean()
    # Measured: 0.0011 on every vertex, 0.0019 on 1000 samples; an edge is about 0.02 sqrt(area).
    assert every < 0.005 and sampled < 0.005


def test_zoomout_bad_samples(dog):
    s = lbo.eigenbasis(dog, 12)
    with pytest.raises(ValueError, match="pair"):
        fm.zoomout(np.eye(6), s, s, samples=5)
    with pytest.raises(ValueError, match="outside"):
        fm.zoomout(np.eye(6), s, s, samples=(np.arange(100), np.arange(100) + dog.n_vertices))
    with pytest.raises(ValueError, match="at least 12"):
        fm.zoomout(np.eye(6), s, s, samples=(np.arange(100), np.arange(5)))


# --- progress bars ----------------------------------------------------------------------------
class _Terminal(io.StringIO):
    """A stderr that says it is a terminal."""

    def isatty(self):
        return True


def test_match_progress_bar_when_asked_and_silent_by_default(dog, capsys):
    target, _ = shuffled(dog, 2)
    lbo.match(dog, target, k=10, k_final=20)
    assert capsys.readouterr().err == ""  # default: a short call, and pytest's stderr is no terminal
    lbo.match(dog, target, k=10, k_final=20, progress=False)
    assert capsys.readouterr().err == ""
    lbo.match(dog, target, k=10, k_final=20, progress=True)
    assert "match" in capsys.readouterr().err
    s = lbo.eigenbasis(dog, 12)
    fm.zoomout(np.eye(6), s, s)
    assert capsys.readouterr().err == ""
    fm.zoomout(np.eye(6), s, s, progress=True)
    assert "ZoomOut" in capsys.readouterr().err


def test_default_progress_shows_in_a_terminal_only_for_long_calls(dog, monkeypatch):
    from lbo_notebooks._support import progress as _progress

    target, _ = shuffled(dog, 2)
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    lbo.match(dog, target, k=10, k_final=20)
    assert terminal.getvalue() == ""  # 2000 vertices: too short for a bar
    monkeypatch.setattr(matching_module, "LARGE_MESH", 1000)  # as if the dog were large
    lbo.match(dog, target, k=10, k_final=20)
    assert "match" in terminal.getvalue()
    log = io.StringIO()  # stderr redirected to a file: no bar even for a long call
    monkeypatch.setattr(sys, "stderr", log)
    with _progress.progress_bar(3, "quiet", None, long=True) as bar:
        bar.update(3)
    assert log.getvalue() == ""
    with pytest.raises(ValueError, match=r"^progress must be True \(always show a progress bar\), False"):
        lbo.match(dog, target, k=10, k_final=20, progress=1)


def test_default_progress_bar_shows_in_a_notebook():
    code = (
        "import lbo_notebooks as lbo\n"
        "from lbo_notebooks.analyses import _matching as matching\n"
        "matching.LARGE_MESH = 100\n"
        "dog = lbo.creature('dog', 'standing', n_vertices=2000)\n"
        "p2p = lbo.match(dog, dog, k=10, k_final=20)"
    )
    outputs = cell_outputs(code)
    assert any(is_widget(o) for o in outputs), outputs
    assert not any(o.get("output_type") == "error" for o in outputs)
