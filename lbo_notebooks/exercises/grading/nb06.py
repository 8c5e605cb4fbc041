"""Graded tests of notebook 06 (the worst-case constant, and ties): see :mod:`lbo_notebooks.exercises.grading`."""

from __future__ import annotations

from typing import Any

from .. import theory
from ._registry import Verdict, from_feedback, grader
from ._registry import recap_verdict


@grader("06-shifted", kind="predict")
def _shifted(shifted_verdict: Any) -> Verdict:
    return from_feedback(theory.check_shifted_basis(shifted_verdict, show=False))


@grader("06-stationary", kind="predict")
def _stationary(stationary_verdict: Any) -> Verdict:
    return from_feedback(theory.check_stationary_frame(stationary_verdict, show=False))


@grader("06-consistent", kind="compute")
def _consistent(consistent_ratio: Any) -> Verdict:
    # C(V) λ_50 of the consistent-mass eigenbasis for its own pair (W, A) is 1 by the theorem (to
    # round-off): the value is judged against that, nothing of the kernel is needed.
    return from_feedback(theory.check_consistent_optimality(consistent_ratio, show=False))


@grader("06-worst", kind="explore")
def _worst(worst_ratio: Any) -> Verdict:
    # The notebook's P = competitors["polynomials"][:, :20], W, A = s.stiffness, s.mass, rebuilt:
    # competitor_bases(dog, 100)["polynomials"] is polynomial_basis(dog, 100), whose first 20
    # columns are those of the notebook (Gram-Schmidt in column order); s = eigenbasis(dog, 101)
    # holds the dog's stiffness_matrix and mass_matrix. Building only these takes a tenth of the
    # time of all six competitors.
    from ...bases import polynomial_basis
    from ...operators import mass_matrix, stiffness_matrix

    from ...creatures import creature

    dog = creature("dog", n_vertices=2000)  # the notebook's dog, rebuilt (as in nb05)
    P = polynomial_basis(dog, 100)[:, :20]
    return from_feedback(theory.check_worst_ratio(worst_ratio, P, stiffness_matrix(dog), mass_matrix(dog), show=False))


@grader("06-ties-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict((q1, q2, q3), theory.RECAP_TIES)
