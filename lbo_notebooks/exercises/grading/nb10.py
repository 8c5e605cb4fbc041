"""Graded tests of notebook 10 (spectral MDS at scale): see :mod:`lbo_notebooks.exercises.grading`."""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from .. import canonical_forms
from ._registry import Verdict, from_feedback, grader
from ._answers import choice, number, recap_of_choices


@functools.lru_cache(maxsize=1)
def _dog() -> Any:
    """The notebook's dog, rebuilt from its definition (``lbo.creature("dog", "walking",
    n_vertices=2000)``), not taken from the kernel. A few seconds."""
    from ...shapes import _creatures as creatures

    return creatures.creature("dog", "walking", n_vertices=2000)


@functools.lru_cache(maxsize=1)
def _embeddings() -> tuple[np.ndarray, np.ndarray]:
    """(3-D spectral MDS with the defaults, 3-D classical MDS) of the rebuilt dog. The notebook reuses
    an eigenbasis of 300 pairs and 600 samples, of which the defaults take the first 200 and 300
    (nested sampling): the same embedding up to the eigensolver's tolerance (Gram errors agree to
    1e-9), for about a second less. 2-D embeddings are their first two columns (both keep the top
    eigenpairs of one matrix; tests/test_grading_10.py checks it)."""
    from ...analyses._mds import classical_mds, spectral_mds

    dog = _dog()
    return spectral_mds(dog, progress=False), classical_mds(dog, progress=False)


@grader("10-mu", kind="predict")
def _mu(mu_verdict: Any) -> Verdict:
    return from_feedback(canonical_forms.check_mu_range(choice(mu_verdict), show=False))


@grader("10-equal-size", kind="compute")
def _equal_size(n_c: Any) -> Verdict:
    # The prompt's defaults k = 200, q = 300 on the rebuilt dog's vertices.
    vertices = number(n_c, "a number of vertices")
    return from_feedback(canonical_forms.check_equal_size(vertices, _dog().n_vertices, 200, 300, show=False))


@grader("10-two-d", kind="compute")
def _two_d(e2: Any) -> Verdict:
    value = number(e2, "a Gram error (a number)")
    X_smds, X_classical = _embeddings()
    return from_feedback(canonical_forms.check_gram_2d(value, X_smds, X_classical, show=False))


@grader("10-cost-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_of_choices([q1, q2, q3], canonical_forms.recap_mds_at_scale_judges())
