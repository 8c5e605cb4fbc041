"""Graded tests of notebook 11 (regularized PCA): see :mod:`lbo_notebooks.exercises.grading`.

The value exercises (11-energy, 11-validation) are judged against the notebook's own context,
rebuilt here from its definitions (the dog of 3,000 vertices, training on *standing* and
*walking*, the sweep over ``betas``), never from the student's kernel: a few seconds
each for the poses, the PCA limit and the sweep on one core.
The builds (11-objective, 11-rpca-basis) are
judged on shapes, data, bases and weights the notebook never shows, with the library's routes to
the objective and to the basis unavailable.
"""

from __future__ import annotations

import functools
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..feedback import WRONG, Stop, as_number, pick
from ..regularized_pca import (
    RECAP_RPCA,
    objective_hint,
    rpca_basis_hint,
    check_dirichlet_energies,
    check_mu_scaling,
    check_rpca_limits,
    check_validation_choice,
)
from ._registry import Verdict, from_feedback, grader, recap_verdict, student_call

# The notebook's definitions (cells of sections 2-4).
N_VERTICES, M = 3000, 100
TRAIN, VALIDATION = ("standing", "walking"), "galloping"
BETAS = (1e-6, 1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 1e-2, 0.1, 0.9)


@functools.lru_cache(maxsize=1)
def _dog() -> SimpleNamespace:
    """Section 2: the six poses, W and A of the standing dog, the solver of the two training poses."""
    from ...shapes import _creatures as creatures
    from ... import operators
    from ...analyses._rpca import RegularizedPCA

    poses = creatures.creature_poses("dog", n_vertices=N_VERTICES)
    reference = poses["standing"]
    W, A = operators.stiffness_matrix(reference), operators.mass_matrix(reference)
    unseen = [name for name in poses if name not in (*TRAIN, VALIDATION)]
    X = np.hstack([poses[name].vertices for name in TRAIN])
    return SimpleNamespace(poses=poses, W=W, A=A, unseen=unseen, solver=RegularizedPCA(X, W, A, center=True))


@functools.lru_cache(maxsize=1)
def _pca_limit() -> Any:
    """Section 3: ``pca = solver.solve(m, 0.0)``, the mu -> 0 limit."""
    return _dog().solver.solve(M, 0.0)


@functools.lru_cache(maxsize=1)
def _sweep() -> SimpleNamespace:
    """Section 4: the errors of the sweep and of the eigenbasis on the unseen poses."""
    from ...spectral._inner_product import reconstruction_error
    from ...spectral._spectrum import eigenbasis

    dog = _dog()
    targets = [dog.poses[name].vertices for name in dog.unseen]
    results = dict(zip(BETAS, dog.solver.sweep(M, betas=list(BETAS))))
    errors = {beta: reconstruction_error(r.basis, dog.A, targets) for beta, r in results.items()}
    err_lbo = reconstruction_error(eigenbasis((dog.W, dog.A), M).vectors, dog.A, targets)
    return SimpleNamespace(errors=errors, err_lbo=err_lbo, unseen=dog.unseen)


@grader("11-energy", kind="compute")
def _energy(energies: Any) -> Verdict:
    dog, pca = _dog(), _pca_limit()
    from_feedback(check_dirichlet_energies(energies, pca.basis, dog.W, dog.A, show=False))
    return Verdict(1.0, "Right: p_jᵀ W p_j for the 100 functions of `pca.basis` (rebuilt from the notebook's definitions).")


@grader("11-limits", kind="predict")
def _limits(limit_at_0: Any, limit_at_1: Any, best_beta: Any) -> Verdict:
    return from_feedback(check_rpca_limits(limit_at_0, limit_at_1, best_beta, show=False))


@grader("11-validation", kind="compute")
def _validation(chosen_beta: Any, beats_by_four: Any) -> Verdict:
    sweep = _sweep()
    feedback = check_validation_choice(chosen_beta, beats_by_four, sweep.errors, sweep.err_lbo, sweep.unseen, show=False)
    from_feedback(feedback)
    return Verdict(1.0, "Right: the β chosen on tail_raised, and its verdict on the two other unseen poses "
                        "(the sweep rebuilt from the notebook's definitions).")


@grader("11-scale", kind="predict")
def _scale(mu_factor: Any) -> Verdict:
    return from_feedback(check_mu_scaling(mu_factor, scale=2.0, show=False))


# What a build of the objective must not call: the visible check's own objective, the library's
# A-orthogonal projections and reconstruction errors (the fit term in one call, also through a
# Spectrum made of P), and the regularized-PCA solvers.
_OBJECTIVE = (
    "lbo_notebooks.exercises.regularized_pca:_rpca_objective",
    "lbo_notebooks.spectral._inner_product:reconstruct",
    "lbo_notebooks.spectral._inner_product:reconstruction_error",
    "lbo_notebooks.spectral._spectrum:Spectrum.project",
    "lbo_notebooks.spectral._spectrum:Spectrum.reconstruct",
    "lbo_notebooks.spectral._spectrum:Spectrum.error",
    "lbo_notebooks.analyses._optimality:representation_error",
    "lbo_notebooks.analyses._rpca:regularized_pca",
    "lbo_notebooks.analyses._rpca:RegularizedPCA.solve",
    "lbo_notebooks.analyses._rpca:RegularizedPCA.sweep",
    "lbo_notebooks.analyses._rpca_sparse:rayleigh_ritz",
    "lbo_notebooks.analyses._rpca_sparse:data_eigenpairs",
    "lbo_notebooks.analyses._rpca_sparse:complement_lanczos",
)


def _unseen_problems() -> list[tuple[str, np.ndarray, np.ndarray, Any, Any, float]]:
    """(what, P, X, W, A, mu) on shapes the notebook and the visible check never use. Every P is
    A-orthonormal (the objective's constraint), none is the optimum for the mu it comes with, so
    neither the closed form's shortcut through the solver nor a swapped term passes by luck."""
    from ... import operators
    from ... import shapes
    from ...analyses._rpca import RegularizedPCA
    from ...spectral._spectrum import eigenbasis

    rng = np.random.default_rng(1107)
    problems = []
    # A torus and a stretched, bent copy as two poses; the basis of one weight, judged at another.
    ring = shapes.torus(n_major=32, n_minor=12)
    v = ring.vertices
    bent = v * [1.0, 1.15, 0.9] + 0.2 * np.sin(2 * v[:, [0]]) * [0.0, 0.0, 1.0]
    W, A = operators.stiffness_matrix(ring), operators.mass_matrix(ring)
    solver = RegularizedPCA(np.hstack([v, bent]), W, A, center=True)
    result = solver.solve(10, beta=1e-2)
    problems.append(("a torus, the basis of another weight", result.basis, solver.data, W, A, 3.7 * result.mu))
    # An ellipsoid: a rotated eigenbasis (A-orthonormal, not eigenfunctions), data not centred.
    oval = shapes.ellipsoid(1.0, 0.6, 0.45, subdivisions=2)
    s = eigenbasis(oval, 14)
    Q = np.linalg.qr(rng.standard_normal((14, 7)))[0]
    u = oval.vertices
    data = np.column_stack([u[:, 0] ** 2, u[:, 1] * u[:, 2], np.exp(u[:, 2]), u[:, 0] + 0.3 * rng.standard_normal(len(u))])
    problems.append(("an ellipsoid, a rotated basis, data not centred", s.vectors @ Q, data, s.stiffness, s.mass, 0.05))
    # An open, uneven sheet with mu = 0: the fit alone.
    sheet = shapes.rectangle(1.2, 0.8, 9, 7)
    w = sheet.vertices.copy()
    w[:, 2] = 0.2 * np.cos(3 * w[:, 0]) * w[:, 1]
    sheet = sheet.with_vertices(w)
    t = eigenbasis(sheet, 6)
    problems.append(("an open sheet with μ = 0", t.vectors, w, t.stiffness, t.mass, 0.0))
    return problems


@grader("11-objective", kind="build", replaces=_OBJECTIVE)
def _objective(my_objective: Any) -> Verdict:
    for what, P, X, W, A, mu in _unseen_problems():
        value = student_call(my_objective, P.copy(), X.copy(), W.copy(), A.copy(), float(mu))
        got = as_number(value, "a number (the value of the objective)")
        hint = objective_hint(got, P, X, W, A, float(mu))
        if hint is not None:
            raise Stop(WRONG, f"{hint} (Graded on {what}, inputs the notebook does not show.)")
    return Verdict(1.0, "Right on three problems the notebook does not show (a torus, an ellipsoid with a rotated "
                        "basis, an open sheet with μ = 0).")


# What a build of the regularized PCA basis must not call: every route of the library to the basis
# (the public solver and function, the private dense, sparse and limit paths behind them, the
# pencil's Ritz pairs, inverse iteration and complement Lanczos), the visible check's own dense
# eigendecomposition, and the library's eigensolvers, which solve any symmetric pencil handed to
# them (the detour eigenbasis((mu W - U Uᵀ, A), m)), as well as other installed libraries' ones.
# SciPy's eigh / eigsh are what the exercise asks for, and stay.
_RPCA_BASIS = (
    "lbo_notebooks.analyses._rpca:regularized_pca",
    "lbo_notebooks.analyses._rpca:RegularizedPCA.solve",
    "lbo_notebooks.analyses._rpca:RegularizedPCA.sweep",
    "lbo_notebooks.analyses._rpca:RegularizedPCA._solve_dense",
    "lbo_notebooks.analyses._rpca:RegularizedPCA._solve_sparse",
    "lbo_notebooks.analyses._rpca:RegularizedPCA._solve_pca_limit",
    "lbo_notebooks.analyses._rpca:RegularizedPCA._solve_infinite",
    "lbo_notebooks.analyses._rpca_sparse:rayleigh_ritz",
    "lbo_notebooks.analyses._rpca_sparse:data_eigenpairs",
    "lbo_notebooks.analyses._rpca_sparse:complement_lanczos",
    "lbo_notebooks.exercises.regularized_pca:_pencil_eigenpairs",
    "lbo_notebooks.spectral._spectrum:eigenbasis",
    "lbo_notebooks.spectral._spectrum:_solve_in_unit_area",
    "lbo_notebooks.spectral._engine.eigensolver:slice_eigsh",
    "lbo_notebooks.spectral._engine.eigensolver:_window_set",
    "lbo_notebooks.spectral._engine.eigensolver:_stitch",
    "lbo_notebooks.spectral._engine.krylov:nearest_eigenpairs",
    "lbo_notebooks.analyses._competitor_bases:lbo_basis",
    "lbo_notebooks.analyses._competitor_bases:_smallest_eigenvectors",
    "lbo_notebooks.analyses._minmax:min_rayleigh_quotient",
    "lbo_notebooks.analyses._minmax:_min_dense",
    "lbo_notebooks.analyses._minmax:ConstrainedRayleigh.minimum",
    "lbo_notebooks.analyses._minmax:ConstrainedRayleigh._min_sparse",
    "pyFM.mesh.laplacian:laplacian_spectrum",
    "lapy.solver:Solver.eigs",
)


@functools.lru_cache(maxsize=1)
def _unseen_rpca_problems() -> tuple[tuple[str, np.ndarray, Any, Any, float, int], ...]:
    """(what, X, W, A, mu, m) on shapes and data the notebook and the visible check never use (the
    notebook shows the dog and a bumpy sphere, always with centred data):

    - a torus and a bent, stretched copy as two poses, *not* centred;
    - an open, wavy sheet with four smooth functions as data (not poses);
    - the icosphere of 162 vertices with the constant function as the only data: σ = area for the
      constant, then ``−μ λ`` with the sphere's repeated eigenvalues (a 3-dimensional eigenspace
      and a 5-dimensional one that ``m = 7`` cuts), where any basis of an eigenspace is right.
    """
    from ... import operators
    from ... import shapes
    from ...analyses._rpca import mu_from_beta

    problems = []
    ring = shapes.torus(n_major=20, n_minor=10)
    v = ring.vertices
    bent = v * [1.1, 0.9, 1.2] + 0.25 * np.sin(1.5 * v[:, [1]]) * [1.0, 0.0, 0.0]
    X = np.hstack([v + [0.4, -0.3, 0.2], bent + [-0.2, 0.5, 0.3]])  # off the origin: not centred
    W, A = operators.stiffness_matrix(ring), operators.mass_matrix(ring)
    problems.append(("a torus and a bent copy, data not centred", X, W, A, mu_from_beta(3e-3, X, A, 15), 15))
    sheet = shapes.rectangle(1.4, 1.0, 12, 9)
    w = sheet.vertices.copy()
    w[:, 2] = 0.15 * np.sin(2.5 * w[:, 0]) * np.cos(2.0 * w[:, 1])
    sheet = sheet.with_vertices(w)
    x, y = w[:, 0], w[:, 1]
    F = np.column_stack([np.cos(3 * x), x * y, np.exp(y), np.sin(5 * x + 2 * y)])
    Ws, As = operators.stiffness_matrix(sheet), operators.mass_matrix(sheet)
    problems.append(("an open sheet with four functions as data", F, Ws, As, 0.8 * mu_from_beta(0.05, F, As, 10), 10))
    ball = shapes.icosphere(2)
    Wb, Ab = operators.stiffness_matrix(ball), operators.mass_matrix(ball)
    problems.append(("a sphere with the constant as data (repeated eigenvalues)", np.ones((ball.n_vertices, 1)), Wb, Ab,
                     0.3, 7))
    return tuple(problems)


_RPCA_UNSEEN = ("three problems the notebook does not show (a torus with data not centred, an open sheet with four "
                "functions, a sphere whose eigenspaces repeat)")


@grader("11-rpca-basis", kind="build", replaces=_RPCA_BASIS)
def _rpca_basis(my_rpca_basis: Any) -> Verdict:
    for what, X, W, A, mu, m in _unseen_rpca_problems():
        value = student_call(my_rpca_basis, X.copy(), W.copy(), A.copy(), float(mu), m)
        hint = rpca_basis_hint(value, X, W, A, mu, m)
        if hint is not None:
            raise Stop(WRONG, f"{hint} (Graded on {what}: {X.shape[0]} vertices, m = {m}, μ = {mu:.3g}; inputs the "
                              "notebook does not show.)")
    return Verdict(1.0, f"Right on {_RPCA_UNSEEN}.")


@grader("11-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict([q1, q2, q3], [pick(q) for q in RECAP_RPCA])
