"""Progress bars of spectral MDS and of regularized PCA sweeps (issue 30, item 2).

One rule for every long call (:mod:`lbo_notebooks._progress`): ``progress=True`` always shows a
bar, ``False`` never, ``None`` only for large meshes and only where someone watches (a notebook,
or a terminal). pytest captures stderr, which is no terminal: nothing may appear there.
(``match`` and ``zoomout`` are tested the same way in test_matching.py.)
"""

from __future__ import annotations

import io
import sys

import numpy as np
import pytest

import lbo_notebooks as lbo
from lbo_notebooks import mds, rpca, shapes


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


def test_default_bars_in_a_terminal_only_for_large_meshes(sphere, solver, monkeypatch):
    terminal = _Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    smds(sphere)
    solver.sweep(6, betas=[0.5])
    assert terminal.getvalue() == ""  # 162 vertices: too small for a bar
    monkeypatch.setattr(mds, "LARGE_MESH", 100)  # as if the sphere were large
    monkeypatch.setattr(rpca, "LARGE_MESH", 100)
    smds(sphere)
    assert "spectral MDS" in terminal.getvalue()
    solver.sweep(6, betas=[0.5])
    assert "regularized PCA" in terminal.getvalue()
    log = io.StringIO()  # redirected to a file: nothing, even for a large mesh
    monkeypatch.setattr(sys, "stderr", log)
    smds(sphere)
    solver.sweep(6, betas=[0.5])
    assert log.getvalue() == ""


def test_bad_progress_argument(sphere, solver):
    with pytest.raises(ValueError, match="progress"):
        smds(sphere, progress="yes")
    with pytest.raises(ValueError, match="progress"):
        solver.sweep(6, betas=[0.5], progress=1)


def test_default_bars_show_in_a_notebook():
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    code = (
        "import numpy as np\n"
        "import lbo_notebooks as lbo\n"
        "from lbo_notebooks import mds, rpca\n"
        "mds.LARGE_MESH = rpca.LARGE_MESH = 100\n"
        "sphere = lbo.shapes.bumpy_sphere(2)\n"
        "X = mds.spectral_mds(sphere, n_samples=30, k=20)\n"
        "W, A = lbo.stiffness_matrix(sphere), lbo.mass_matrix(sphere)\n"
        "results = rpca.RegularizedPCA(sphere.vertices, W, A).sweep(6, betas=[0.2, 0.8])"
    )
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(code)])
    nbclient.NotebookClient(nb, timeout=300, kernel_name="python3").execute()
    outputs = nb.cells[0].outputs
    assert not any(o.get("output_type") == "error" for o in outputs), outputs
    widgets = [o for o in outputs if "application/vnd.jupyter.widget-view+json" in o.get("data", {})]
    assert len(widgets) >= 2, outputs  # one bar for each call
