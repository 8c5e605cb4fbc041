"""Graded tests of notebook 02 (the Laplacian of a graph and of a string): see
:mod:`lbo_notebooks.exercises.grading`.

Every context is the prompt's own definition, rebuilt here (not read from the kernel, where `f`,
`n` or `error` may have been changed while exploring): the path graph on five vertices with
f = (0, 1, 4, 9, 16), the cycle with 12 beads, the step ``x > 0.4`` on the 200-bead path.
"""

from __future__ import annotations

from typing import Any

from ._registry import Verdict, from_feedback, grader, recap_verdict


@grader("02-edge-energy", kind="compute")
def _edge_energy(path_energy: Any) -> Verdict:
    from ..warm_up import check_edge_energy

    return from_feedback(check_edge_energy(path_energy, [0, 1, 4, 9, 16], show=False))


@grader("02-cycle-pair", kind="predict")
def _cycle_pair(multiplicity: Any) -> Verdict:
    from ..warm_up import check_cycle_multiplicity

    # n = 12 and λ = 2 are the prompt's; the check counts the k in 0 … 11 with 2 - 2cos(2πk/12) = 2.
    return from_feedback(check_cycle_multiplicity(multiplicity, n=12, value=2.0, show=False))


@grader("02-step-decay", kind="predict")
def _step_decay(error_drop: Any) -> Verdict:
    from ..warm_up import check_step_decay

    # The check measures the ratio on the prompt's step (x > 0.4, 200 beads, n = 20 and 40).
    return from_feedback(check_step_decay(error_drop, show=False))


@grader("02-graph-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    from ..warm_up import GRAPH_RECAP

    return recap_verdict([q1, q2, q3], GRAPH_RECAP)
