"""Graded tests of notebook 06 (the worst-case constant, and ties): see :mod:`lbo_notebooks.exercises.grading`."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import theory
from ._registry import Verdict, from_feedback, grader, student_call
from ._registry import recap_verdict

# What a build of C(V) must not call: the library's worst-case constant (public, its dense and
# sparse routes, the regularised solver of the sparse route) and the constrained minimum of the
# Rayleigh quotient, which would do the last eigen-solve of the Schur route (1/C(V) is its value
# for S). The trap (minmax.complement_ratio) goes through that minimum too.
_WORST_CASE = (
    "lbo_notebooks.analyses._optimality:worst_case_ratio",
    "lbo_notebooks.analyses._optimality:_worst_case_dense",
    "lbo_notebooks.analyses._optimality:_worst_case_sparse",
    "lbo_notebooks.analyses._optimality:_RegularisedStiffnessSolver.solve",
    "lbo_notebooks.analyses._optimality:_RegularisedStiffnessSolver.matvec",
    "lbo_notebooks.analyses._minmax:min_rayleigh_quotient", "lbo_notebooks.analyses._minmax:_min_dense",
    "lbo_notebooks.analyses._minmax:ConstrainedRayleigh.minimum",
    "lbo_notebooks.analyses._minmax:ConstrainedRayleigh._min_sparse",
)


@grader("06-shifted", kind="predict")
def _shifted(shifted_verdict: Any) -> Verdict:
    return from_feedback(theory.check_shifted_basis(shifted_verdict, show=False))


def _unseen_bases() -> list[tuple[object, object, np.ndarray, str]]:
    """(W, A, V, where) no notebook cell and no visible check uses. A bumpy sphere of 162 vertices
    with its first ten eigenvectors in a mixed-up basis (the optimum, C(V) = 1/λ_10), twelve of
    them perturbed (the constant kept), the polynomials of degree <= 2 in x, y, z (not
    A-orthonormal), and the same without the constant (∞); an open sheet with a random basis
    that holds the constant; two separate pieces with a random basis holding the global constant
    only (∞: each piece's constant is in W's kernel) and one holding both pieces' constants."""
    import scipy.linalg

    from ... import shapes
    from ...operators._cotangent import mass_matrix, stiffness_matrix
    from .. import laplace_beltrami

    rng = np.random.default_rng(6060)
    blob = shapes.bumpy_sphere(2)
    W, A = stiffness_matrix(blob), mass_matrix(blob)
    _, phi = scipy.linalg.eigh(W.toarray(), A.toarray(), subset_by_index=[0, 12])
    mixed = phi[:, :10] @ (np.eye(10) + 0.2 * rng.normal(size=(10, 10)))
    perturbed = phi[:, :12].copy()
    perturbed[:, 1:] += np.abs(phi[:, 1:12]).mean() * rng.normal(size=(blob.n_vertices, 11))
    x, y, z = (blob.vertices - blob.vertices.mean(axis=0)).T
    polynomials = np.column_stack([np.ones_like(x), x, y, z, x * y, y * z, z * x, x * x - y * y, x * x - z * z])
    sheet = shapes.rectangle(1.6, 1.0, 10, 6)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.03, 0.03, size=(len(v), 2))
    v[:, 2] = 0.15 * np.cos(2 * v[:, 0] + v[:, 1])
    sheet = sheet.with_vertices(v)
    random_sheet = np.column_stack([np.ones(sheet.n_vertices), rng.normal(size=(sheet.n_vertices, 7))])
    pieces = laplace_beltrami._two_spheres()
    half = pieces.n_vertices // 2
    first = (np.arange(pieces.n_vertices) < half).astype(float)
    noise = rng.normal(size=(pieces.n_vertices, 4))
    Wp, Ap = stiffness_matrix(pieces), mass_matrix(pieces)
    where = f"a bumpy sphere of {blob.n_vertices} vertices"
    return [(W, A, mixed, f"{where}, its first ten eigenvectors in a mixed-up basis"),
            (W, A, perturbed, f"{where}, a perturbed eigenbasis"),
            (W, A, polynomials, f"{where}, the polynomials of degree ≤ 2"),
            (W, A, polynomials[:, 1:], f"{where}, the polynomials without the constant"),
            (stiffness_matrix(sheet), mass_matrix(sheet), random_sheet,
             f"an open sheet of {sheet.n_vertices} vertices, a random basis with the constant"),
            (Wp, Ap, np.column_stack([np.ones(pieces.n_vertices), noise]),
             "two separate pieces, a random basis with the constant"),
            (Wp, Ap, np.column_stack([first, 1 - first, noise]),
             "two separate pieces, a random basis with the constant of each piece")]


@grader("06-schur", kind="build", replaces=_WORST_CASE)
def _schur(my_worst_case: object) -> Verdict:
    message = theory.judge_worst_case(my_worst_case, _unseen_bases(), call=lambda f, W, A, V: student_call(f, W, A, V),
                                      seen="graded on {}, which the notebook does not show")
    return Verdict(1.0, message.replace("Right:", "Right on seven bases the notebook does not show (a bumpy sphere, "
                                        "an open sheet, two separate pieces):", 1))


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
    from ...analyses._competitor_bases import polynomial_basis
    from ...operators._cotangent import mass_matrix, stiffness_matrix

    from ...shapes._creatures import creature

    dog = creature("dog", n_vertices=2000)  # the notebook's dog, rebuilt (as in nb05)
    P = polynomial_basis(dog, 100)[:, :20]
    return from_feedback(theory.check_worst_ratio(worst_ratio, P, stiffness_matrix(dog), mass_matrix(dog), show=False))


@grader("06-ties-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict((q1, q2, q3), theory.RECAP_TIES)
