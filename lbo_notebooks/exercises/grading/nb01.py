"""Graded tests of notebook 01 (shapes): see :mod:`lbo_notebooks.exercises.grading`.

Every context is rebuilt from the notebook's definitions: the dog is
``creature("dog", n_vertices=N)`` with the notebook's ``N = 5000`` (the creatures are deterministic,
so the graded run meshes exactly the dog the notebook shows), never the kernel's ``dog``.
"""

from __future__ import annotations

from typing import Any

from .. import basics
from ..feedback import WRONG, Stop, require_attempt
from ._registry import Verdict, from_feedback, grader, recap_verdict

N = 5000
"""The notebook's ``N``: the size of the dog the graded exercises are about."""

_AT_N = f" Graded on the notebook's dog, N = {N} vertices (if you changed N, set it back)."


def _dog() -> Any:
    from ...shapes._creatures import creature

    return creature("dog", n_vertices=N)


@grader("01-edges", kind="compute")
def _edges(n_edges: Any) -> Verdict:
    feedback = basics.check_edge_count(n_edges, _dog(), show=False)
    if feedback.status == WRONG:
        raise Stop(WRONG, feedback.message + _AT_N)
    return from_feedback(feedback)


@grader("01-stretch", kind="predict")
def _stretch(stretch: Any) -> Verdict:
    return from_feedback(basics.check_stretch_growth(stretch, show=False))


@grader("01-area", kind="predict")
def _area(area_factor: Any) -> Verdict:
    return from_feedback(basics.check_area_factor(area_factor, scale=1.6, show=False))


@grader("01-angles", kind="compute")
def _angles(smallest_angles: Any) -> Verdict:
    require_attempt(smallest_angles)
    sizes = basics.asked_sizes(smallest_angles)
    asked = (*basics.ANGLE_SIZES, N)
    if any(n not in sizes for n in basics.ANGLE_SIZES) or len(sizes) < len(asked):
        raise Stop(WRONG, "Give the smallest angle for every size asked: 2,000, 3,000 and N vertices, one entry each.")
    if N not in sizes:
        raise Stop(WRONG, f"The third size is the notebook's N = {N}: the graded run builds the dog at 2,000, 3,000 "
                          f"and {N:,} vertices (if you changed N, set it back).")
    for n in asked:
        hint = basics.angle_hint(n, sizes[n], basics.smallest_angle("dog", n))
        if hint is not None:
            raise Stop(WRONG, hint)
    return Verdict(1.0, "Right: the smallest corner angles of the dog at all three sizes.")


@grader("01-legs", kind="compute")
def _legs(predicted_area: Any) -> Verdict:
    return from_feedback(basics.check_leg_area(predicted_area, n_vertices=N, show=False))


@grader("01-recap", kind="recap")
def _recap_shapes(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict([q1, q2, q3], basics.RECAP_SHAPES)
