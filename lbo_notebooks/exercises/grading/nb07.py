"""Graded tests of notebook 07 (the min–max principle): see :mod:`lbo_notebooks.exercises.grading`.

Every answer of 07 is a value (no *build it yourself*). Each grader rebuilds what the exercise is
about from the notebook's definitions (the 3×3 matrix ``M`` of section 2 from its seed; nothing of
the kernel), and judges the answer as the visible check does, in the graded run's fresh process.
The notebook's own claims that the old hidden tests re-asserted (random planes, the tilt, random
subspaces of the mesh, the consistent mass) are tested as library facts in
tests/test_grading_07.py.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import minmax_and_metrics
from ._registry import Verdict, from_feedback, grader, recap_verdict


def _frame() -> tuple[np.ndarray, np.ndarray]:
    """Section 2's matrix, as the notebook builds it: eigenvalues 1, 2.5, 4 in the frame of a QR of
    seed-0 noise; and its eigenvectors v_0, v_1, v_2 (rows), from ``np.linalg.eigh`` as there."""
    Q, _ = np.linalg.qr(np.random.default_rng(0).normal(size=(3, 3)))
    M = Q @ np.diag([1.0, 2.5, 4.0]) @ Q.T
    return M, np.linalg.eigh(M)[1].T


@grader("07-range", kind="predict")
def _range(plane_range: Any) -> Verdict:
    M, _ = _frame()
    return from_feedback(minmax_and_metrics.check_plane_range(plane_range, M, show=False))


@grader("07-plane", kind="compute")
def _plane(plane_value: Any) -> Verdict:
    M, (v0, v1, _) = _frame()
    return from_feedback(minmax_and_metrics.check_plane_minimum(plane_value, M, v0 + 2 * v1, show=False))


@grader("07-family", kind="predict")
def _family(lowest_family: Any) -> Verdict:
    return from_feedback(minmax_and_metrics.check_lowest_family(lowest_family, show=False))


@grader("07-dual", kind="predict")
def _dual(dual_value: Any) -> Verdict:
    M, _ = _frame()
    return from_feedback(minmax_and_metrics.check_dual_value(dual_value, M, show=False))


@grader("07-interlacing", kind="choice")
def _interlacing(interlacing_bound: Any) -> Verdict:
    # The choice only; the written explanation (cell 07-interlacing-explain) is graded by a person.
    return from_feedback(minmax_and_metrics.check_interlacing(interlacing_bound, show=False))


@grader("07-consistent", kind="compute")
def _consistent(consistent_minmax: Any) -> Verdict:
    return from_feedback(minmax_and_metrics.check_consistent_minmax(consistent_minmax, show=False))


@grader("07-recap", kind="recap")
def _recap_min_max(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict([q1, q2, q3], minmax_and_metrics.recap_min_max_judges())
