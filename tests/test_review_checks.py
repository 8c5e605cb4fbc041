"""Checks found on review to reject right answers (kept apart from test_exercises.py, owned elsewhere)."""

import numpy as np

from lbo_notebooks.exercises import theory


def test_plane_range_accepts_an_array_pair():
    M = np.diag([1.0, 2.5, 4.0])
    lam = np.linalg.eigvalsh(M)
    assert theory.check_plane_range(lam[:2], M, show=False).correct          # the natural slice
    assert theory.check_plane_range(np.array([1.0, 4.0]), M, show=False).status == "wrong"
    assert "pair" in theory.check_plane_range(lam, M, show=False).message     # three numbers: not a pair
