"""Graded tests of notebook 08 (scale-invariant metrics): see :mod:`lbo_notebooks.exercises.grading`.

Every answer of 08 is a value (no *build it yourself*). 08-floor is judged on the notebook's horse
rebuilt from its definition (``creature("horse", n_vertices=4000)``, about 5 s: the cost of this
notebook's slowest graded run), never on the kernel's ``horse``; the others need no context. A
number rounded by hand is judged on its precision (see ``minmax_and_metrics._precision``): a prediction right to
three significant digits is right (0.111 for 1/9, 6.28 for 2π), the floor fraction must name the
vertex count (to half a vertex), and a coarser rounding is told to give more digits. The notebook's
claims that the old hidden tests re-asserted (the curvature of the scaled torus, Gauss–Bonnet on the
torus and the disk) are tested as library facts in tests/test_grading_08.py.
"""

from __future__ import annotations

import functools
from typing import Any

from .. import minmax_and_metrics
from ..feedback import NOT_ATTEMPTED, Stop, is_placeholder
from ._registry import Verdict, from_feedback, grader, recap_verdict


@functools.lru_cache(maxsize=1)
def _horse() -> Any:
    """The notebook's horse (section 1), rebuilt in the graded run."""
    from ...creatures import creature

    return creature("horse", n_vertices=4000)


@grader("08-curvature", kind="predict")
def _curvature(curvature_factor: Any) -> Verdict:
    return from_feedback(minmax_and_metrics.check_curvature_scaling(curvature_factor, scale=3.0, show=False))


@grader("08-gauss-bonnet", kind="predict")
def _gauss_bonnet(torus_total: Any, disk_total: Any) -> Verdict:
    return from_feedback(minmax_and_metrics.check_gauss_bonnet(torus_total, disk_total, show=False))


@grader("08-scaling", kind="predict")
def _scaling(metric_factors: Any) -> Verdict:
    return from_feedback(minmax_and_metrics.check_metric_scaling(metric_factors, scale=3.0, show=False))


@grader("08-best", kind="predict")
def _best(best_alpha_curved: Any) -> Verdict:
    return from_feedback(minmax_and_metrics.check_best_alpha(best_alpha_curved, show=False))


@grader("08-floor", kind="compute")
def _floor(floor_fraction: Any) -> Verdict:
    # The fraction only; the written explanation (cell 08-floor-explain) is graded by a person.
    if is_placeholder(floor_fraction):  # before the horse is built: a blank answer costs nothing
        raise Stop(NOT_ATTEMPTED, "Replace the `...` placeholder with your answer and run the cell again.")
    return from_feedback(minmax_and_metrics.check_floor_fraction(floor_fraction, _horse(), floor=1.0, show=False))


@grader("08-sphere", kind="predict")
def _sphere(sphere_verdict: Any) -> Verdict:
    return from_feedback(minmax_and_metrics.check_sphere_alpha(sphere_verdict, show=False))


@grader("08-consistent", kind="predict")
def _consistent(consistent_invariant: Any) -> Verdict:
    return from_feedback(minmax_and_metrics.check_consistent_invariance(consistent_invariant, show=False))


@grader("08-recap", kind="recap")
def _recap_scale_invariant(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict([q1, q2, q3], minmax_and_metrics.recap_scale_invariant_judges())
