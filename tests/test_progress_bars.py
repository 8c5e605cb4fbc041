"""Progress bars of eigenbases, spectral MDS and regularized PCA sweeps (issue 30, item 2).

One rule for every long call (:mod:`lbo_notebooks._support.progress`): ``progress=True`` always shows a
bar, ``False`` never, ``None`` only for large meshes and only where someone watches (a notebook,
or a terminal). pytest captures stderr, which is no terminal: nothing may appear there.
(``match`` and ``zoomout`` are tested the same way in test_matching.py.)
"""

from __future__ import annotations

import io
import sys
import threading

import numpy as np
import pytest

import lbo_notebooks as lbo
from lbo_notebooks import shapes
from lbo_notebooks.analyses import _mds as mds
from lbo_notebooks.analyses import _rpca as rpca
from lbo_notebooks.spectral import _spectrum as spectrum
from lbo_notebooks.spectral import slice_eigsh
from lbo_notebooks.spectral._engine.slicing import plan_sets

from .kernel import cell_outputs, is_widget


class _Terminal(io.StringIO):
    """A stderr that says it is a terminal."""

    def isatty(self):
        return True


@pytest.fixture(scope="module")
def sphere():
    return shapes.bumpy_sphere(2)


@pytest.fixture(scope="module")
def solver(sphere):
    W, A = lbo.stiffness_matrix(sphere), lbo.mass_matrix(sphere)
    return rpca.RegularizedPCA(np.hstack([sphere.vertices, sphere.vertices**2]), W, A, center=True)


@pytest.fixture(scope="module")
def sparse_sphere():
    return shapes.bumpy_sphere(3)  # 642 vertices: above DENSE_LIMIT, so ARPACK or slicing runs


def smds(mesh, progress=None):
    return mds.spectral_mds(mesh, n_samples=30, k=20, progress=progress)


def test_bars_only_when_asked_under_pytest(sphere, solver, capsys):
    quiet = smds(sphere)
    assert capsys.readouterr().err == ""  # default: small mesh, and pytest's stderr is no terminal
    np.testing.assert_array_equal(smds(sphere, progress=False), quiet)
    assert capsys.readouterr().err == ""
    np.testing.assert_array_equal(smds(sphere, progress=True), quiet)  # the bar changes nothing
    assert "spectral MDS" in capsys.readouterr().err

    swept = solver.sweep(6, betas=[0.2, 0.8])
    assert capsys.readouterr().err == ""
    solver.sweep(6, betas=[0.2, 0.8], progress=False)
    assert capsys.readouterr().err == ""
    shown = solver.sweep(6, betas=[0.2, 0.8], progress=True)
    assert "regularized PCA" in capsys.readouterr().err
    for a, b in zip(swept, shown):
        np.testing.assert_array_equal(a.basis, b.basis)
    assert [r.mu for r in solver.sweep(6, mus=[1e-3, 1e-2], progress=True)] == [1e-3, 1e-2]
    capsys.readouterr()


@pytest.mark.parametrize(("k", "solver", "stage"), [(20, "auto", "ARPACK"), (40, "slicing", "Lanczos sets")])
def test_eigenbasis_bar_only_when_asked_under_pytest(sparse_sphere, k, solver, stage, capsys):
    quiet = lbo.eigenbasis(sparse_sphere, k, solver=solver)
    assert capsys.readouterr().err == ""  # default: a short call, and pytest's stderr is no terminal
    for progress in (False, True):
        s = lbo.eigenbasis(sparse_sphere, k, solver=solver, progress=progress)
        np.testing.assert_array_equal(s.values, quiet.values)  # the bar changes nothing, bit for bit
        np.testing.assert_array_equal(s.vectors, quiet.vectors)
        err = capsys.readouterr().err
        if progress:  # the label, the stage it went through, and every pair found at the end
            assert "eigenbasis" in err and stage in err and f"{k}/{k}" in err, err
        else:
            assert err == ""


def test_eigenbasis_bar_rule_for_long_calls():
    # Measured (spectrum._is_long): 10k vertices at k = 100 take under a second, no bar; 10k at
    # k = 300, 25k at k = 120, and 40k or more at any k take two seconds or more.
    assert not spectrum._is_long(10_242, 100)
    assert not spectrum._is_long(25_000, 100)
    assert not spectrum._is_long(9_999, 10_000)  # a small mesh never gets a bar by default
    assert spectrum._is_long(10_242, 300)
    assert spectrum._is_long(25_000, 120)
    assert spectrum._is_long(40_962, 20)
    assert spectrum._is_long(50_000, 300)


def test_slice_eigsh_reports_finished_sets_in_the_calling_thread(sparse_sphere):
    W, A = lbo.stiffness_matrix(sparse_sphere), lbo.mass_matrix(sparse_sphere)
    args = {"v0": np.ones(sparse_sphere.n_vertices), "shift": 0.01, "slice_size": 10, "workers": 2}
    plain = slice_eigsh(W, A, 40, **args)
    calls = []
    reported = slice_eigsh(W, A, 40, on_progress=lambda pairs: calls.append((pairs, threading.get_ident())), **args)
    for a, b in zip(plain, reported):
        np.testing.assert_array_equal(a, b)
    assert len(calls) == plan_sets(40, 10, 2) > 1  # one call per Lanczos set
    assert sum(pairs for pairs, _ in calls) == 40
    assert {thread for _, thread in calls} == {threading.get_ident()}


def test_default_bars_in_a_terminal_only_for_large_meshes(sphere, solver, sparse_sphere, monkeypatch):
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    smds(sphere)
    solver.sweep(6, betas=[0.5])
    lbo.eigenbasis(sparse_sphere, 100)
    assert terminal.getvalue() == ""  # 162 and 642 vertices: too small for a bar
    monkeypatch.setattr(spectrum, "LARGE_MESH", 100)  # as if the 642 vertices were 64,200
    lbo.eigenbasis(sparse_sphere, 20)
    assert "eigenbasis" in terminal.getvalue()
    monkeypatch.setattr(mds, "LARGE_MESH", 100)  # as if the sphere were large
    monkeypatch.setattr(rpca, "LARGE_MESH", 100)
    terminal.seek(0)
    terminal.truncate()
    smds(sparse_sphere)  # long for its eigenbasis too (642 >= 4 * 100): one bar all the same
    assert "spectral MDS" in terminal.getvalue()
    assert "eigenbasis:" not in terminal.getvalue()  # no second bar (its stage is named "eigenbasis")
    solver.sweep(6, betas=[0.5])
    assert "regularized PCA" in terminal.getvalue()
    log = io.StringIO()  # redirected to a file: nothing, even for a large mesh
    monkeypatch.setattr(sys, "stderr", log)
    smds(sphere)
    solver.sweep(6, betas=[0.5])
    lbo.eigenbasis(sparse_sphere, 20)
    assert log.getvalue() == ""


def test_bad_progress_argument(sphere, solver, sparse_sphere):
    for bad in ("yes", 1, np.bool_(True)):
        with pytest.raises(ValueError, match="progress"):
            lbo.eigenbasis(sparse_sphere, 20, progress=bad)
    with pytest.raises(ValueError, match="progress"):
        smds(sphere, progress="yes")
    with pytest.raises(ValueError, match="progress"):
        solver.sweep(6, betas=[0.5], progress=1)


def test_default_bars_show_in_a_notebook():
    code = (
        "import numpy as np\n"
        "import lbo_notebooks as lbo\n"
        "from lbo_notebooks.analyses import _mds as mds, _rpca as rpca\n"
        "from lbo_notebooks.spectral import _spectrum as spectrum\n"
        "mds.LARGE_MESH = rpca.LARGE_MESH = spectrum.LARGE_MESH = 100\n"
        "sphere = lbo.shapes.bumpy_sphere(2)\n"
        "X = mds.spectral_mds(sphere, n_samples=30, k=20)\n"
        "W, A = lbo.stiffness_matrix(sphere), lbo.mass_matrix(sphere)\n"
        "results = rpca.RegularizedPCA(sphere.vertices, W, A).sweep(6, betas=[0.2, 0.8])\n"
        "s = lbo.eigenbasis(lbo.shapes.bumpy_sphere(3), 20)"  # 642 vertices, as if 64,200
    )
    outputs = cell_outputs(code)
    assert not any(o.get("output_type") == "error" for o in outputs), outputs
    widgets = [o for o in outputs if is_widget(o)]
    assert len(widgets) == 3, outputs  # one bar for each call (none for spectral MDS's eigenbasis)


def test_every_call_with_a_progress_argument_checks_it(sphere):
    """One rule for ``progress`` (issue 42, item 7): the MDS, sampling and geodesic calls refuse 1 too."""
    from lbo_notebooks.analyses import classical_mds, fast_classical_scaling, landmark_mds

    calls = {
        "classical_mds": lambda: classical_mds(sphere, progress=1),
        "landmark_mds": lambda: landmark_mds(sphere, n_samples=10, progress=1),
        "fast_classical_scaling": lambda: fast_classical_scaling(sphere, n_samples=10, progress=1),
        "geodesic_distances": lambda: lbo.geodesic_distances(sphere, [0], progress=1),
        "farthest_point_sampling": lambda: lbo.farthest_point_sampling(sphere, 3, progress=1),
    }
    for name, call in calls.items():
        with pytest.raises(ValueError, match=r"^progress must be True \(always show a progress bar\)"):
            call()
