"""Graded tests of notebook 01 (shapes): see :mod:`lbo_notebooks.exercises.grading`."""

from __future__ import annotations

from typing import Any

from .. import basics
from ._registry import Verdict, from_feedback, grader


@grader("01-stretch", kind="predict")
def _stretch(stretch: Any) -> Verdict:
    return from_feedback(basics.check_stretch_growth(stretch, show=False))
