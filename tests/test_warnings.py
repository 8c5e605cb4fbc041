"""Every warning the package emits goes through lbo_notebooks._support.warning.warn and points at the caller's line."""

from __future__ import annotations

import inspect
import warnings

import pytest

import lbo_notebooks as lbo
from lbo_notebooks import shapes


@pytest.fixture(scope="module")
def sphere():
    return shapes.icosphere(2)


# --- every warning points at the caller's line ---------------------------------------------------
def _warned_here(record, category):
    """The warnings of ``category`` in ``record``, with the file and line they point at."""
    return [(w.filename, w.lineno) for w in record if issubclass(w.category, category)]


def test_the_robust_laplacian_warning_points_at_the_callers_line():
    from lbo_notebooks.operators import LaplacianWarning

    v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [1, 1, 1]]
    fin = lbo.Mesh(v, [[0, 1, 2], [1, 0, 3], [0, 1, 4], [1, 2, 5]], check=False)  # three fins on edge 0-1
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1
        lbo.eigenbasis(fin, 3)
    assert _warned_here(record, LaplacianWarning) == [(__file__, line)]


def test_a_fallback_warning_points_at_the_callers_line(monkeypatch):
    import lbo_notebooks.spectral._engine.eigensolver as eigensolver
    from lbo_notebooks.spectral._solvers import use_dense

    def no_slices(*args, **kwargs):
        raise RuntimeError("slicing failed (test).")

    monkeypatch.setattr(eigensolver, "slice_eigsh", no_slices)
    sphere = lbo.shapes.icosphere(3)
    assert not use_dense(sphere.n_vertices)  # the sparse path, where solver="auto" slices k = 100
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1
        lbo.eigenbasis(sphere, 100)
    assert _warned_here(record, RuntimeWarning) == [(__file__, line)]


def test_every_warning_in_the_package_goes_through_the_one_helper():
    """A fixed stacklevel goes stale when a wrapper is added; _support.warning.warn walks out of the package."""
    import pathlib
    import re

    root = pathlib.Path(lbo.__file__).parent
    direct = {
        str(path.relative_to(root))
        for path in root.rglob("*.py")
        if path.name != "warning.py" and re.search(r"warnings\.warn\(", path.read_text())
    }
    assert not direct, direct
