"""Graded tests of notebook 03 (the Laplace–Beltrami operator): see :mod:`lbo_notebooks.exercises.grading`.

The three builds run on meshes neither the notebook nor the visible checks use, with the library's
operators or eigensolvers (and the other installed libraries that compute the same) made
unavailable; the values are judged against the notebook's objects rebuilt from their definitions.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import laplace_beltrami
from ..feedback import NOT_ATTEMPTED, WRONG, Stop, require_attempt, unanswered
from ._registry import Verdict, from_feedback, grader, student_call


def _everywhere(package: str, names: tuple[str, ...], modules: dict[str, str] | None = None) -> tuple[str, ...]:
    """``package:name`` and, where the function is defined in a submodule (which is where a pickled
    reference to it points), ``package.submodule:name`` too."""
    modules = modules or {}
    targets = []
    for name in names:
        targets.append(f"{package}:{name}")
        where = modules.get(name, modules.get("*"))
        if where is not None:
            targets.append(f"{package}.{where.replace('@', name)}:{name}")
    return tuple(targets)


# What a build of the cotangent stiffness must not call: the library's operator, the private
# function behind it (the eigensolver and every other route to W go through it), the cotangents
# and angles it is made of, the gradient route (W = Gᵀ diag(a) G), and the other installed
# libraries that build the same matrix (also by the submodule path a pickled reference uses).
_STIFFNESS = (
    "lbo_notebooks.operators._cotangent:stiffness_matrix", "lbo_notebooks.operators._cotangent:_stiffness",
    "lbo_notebooks.operators._cotangent:face_cotangents",
    "lbo_notebooks.operators._cotangent:_face_cotangents",
    "lbo_notebooks.operators._cotangent:corner_angles",
    "lbo_notebooks.operators._laplace_beltrami:laplace_beltrami",
    "lbo_notebooks.operators._robust:robust_operators",
    "lbo_notebooks.analyses._heat_method:face_gradient_operator",
    "lbo_notebooks.analyses._heat_method:_gradient",
    *_everywhere("igl", ("cotmatrix", "cotmatrix_entries", "cotmatrix_intrinsic", "intrinsic_delaunay_cotmatrix",
                         "grad"), {"*": "pyigl_core"}),
    *_everywhere("robust_laplacian", ("mesh_laplacian",), {"*": "core"}),
    *_everywhere("gpytoolbox", ("cotangent_laplacian", "cotangent_weights", "cotangent_laplacian_intrinsic",
                                "cotangent_weights_intrinsic", "grad"), {"*": "@"}),
    *_everywhere("potpourri3d", ("cotan_laplacian",), {"*": "mesh"}),
)

# What a build of a lumped mass must not call: the library's mass (public, private, the mixed
# Voronoi helper, the curvature module's routes to it, the eigensolver's route), and the other
# libraries' mass matrices. Face areas (``mesh.face_areas``, a cross product) stay allowed, and so
# do the cotangents (the mixed Voronoi rule needs them).
_MASS = (
    "lbo_notebooks.operators._cotangent:mass_matrix", "lbo_notebooks.operators._cotangent:_mass",
    "lbo_notebooks.operators._cotangent:_voronoi_corner_areas",
    "lbo_notebooks.operators._curvature:_voronoi_areas",
    "lbo_notebooks.operators._curvature:metric_mass_matrix",
    "lbo_notebooks.operators._laplace_beltrami:laplace_beltrami",
    "lbo_notebooks.operators._robust:robust_operators",
    *_everywhere("igl", ("massmatrix", "massmatrix_intrinsic", "voronoi_mass"), {"*": "pyigl_core"}),
    *_everywhere("robust_laplacian", ("mesh_laplacian",), {"*": "core"}),
    *_everywhere("gpytoolbox", ("massmatrix", "massmatrix_intrinsic"), {"*": "@"}),
    *_everywhere("potpourri3d", ("vertex_areas",), {"*": "mesh"}),
)


# What a build of the generalised eigensolve must not call: every route of the library to
# eigenpairs of (W, A) (the public eigenbasis and the function behind it, spectrum slicing and the
# block Lanczos it runs, the bases and the constrained minimum that deflation would turn into a
# solver, regularized PCA's Ritz pairs) and the other installed libraries' solvers of the same
# pencil. SciPy's eigsh / eigh are what the exercise asks for, and stay.
_EIGENSOLVE = (
    "lbo_notebooks.spectral._spectrum:eigenbasis", "lbo_notebooks.spectral._spectrum:_solve_in_unit_area",
    "lbo_notebooks.spectral._engine.eigensolver:slice_eigsh", "lbo_notebooks.spectral._engine.eigensolver:_window_set",
    "lbo_notebooks.spectral._engine.eigensolver:_stitch",
    "lbo_notebooks.spectral._engine.krylov:nearest_eigenpairs",
    "lbo_notebooks.analyses._competitor_bases:lbo_basis",
    "lbo_notebooks.analyses._competitor_bases:_smallest_eigenvectors",
    "lbo_notebooks.analyses._minmax:min_rayleigh_quotient", "lbo_notebooks.analyses._minmax:_min_dense",
    "lbo_notebooks.analyses._minmax:ConstrainedRayleigh.minimum",
    "lbo_notebooks.analyses._minmax:ConstrainedRayleigh._min_sparse",
    "lbo_notebooks.analyses._rpca_sparse:rayleigh_ritz",
    "lbo_notebooks.analyses._rpca_sparse:data_eigenpairs",
    "lbo_notebooks.analyses._rpca_sparse:complement_lanczos", "lbo_notebooks.analyses._rpca:regularized_pca",
    "pyFM.mesh.laplacian:laplacian_spectrum", "lapy.solver:Solver.eigs",
)


def _unseen_meshes() -> list[Any]:
    """Meshes no notebook cell and no visible check uses: a bumpy torus, an open patch with
    obtuse triangles and boundary edges, and a lone obtuse triangle. Fresh objects at every call,
    so no cached operator is reachable from them."""
    from ... import shapes
    from ...geometry._mesh import Mesh

    rng = np.random.default_rng(3031)
    ring = shapes.torus()
    bumpy = ring.with_vertices(ring.vertices * rng.uniform(0.9, 1.1, size=(ring.n_vertices, 1)))
    sheet = shapes.rectangle(1.5, 1.0, 5, 4)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.08, 0.08, size=(len(v), 2))
    v[:, 2] = 0.3 * np.cos(2 * v[:, 1])
    obtuse = Mesh([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.3, 0.1]], [[0, 1, 2]])
    return [bumpy, sheet.with_vertices(v), obtuse]


def _fresh(mesh: Any) -> Any:
    """A copy of ``mesh`` with an empty operator cache, for the student's function."""
    from ...geometry._mesh import Mesh

    return Mesh(mesh.vertices.copy(), mesh.faces.copy())


def _where(mesh: Any) -> str:
    return "a lone obtuse triangle" if mesh.n_faces == 1 else f"a mesh of {mesh.n_vertices} vertices"


_UNSEEN = "three meshes the notebook does not show (a torus, an open sheet, an obtuse triangle)"


@grader("03-stiffness", kind="build", replaces=_STIFFNESS)
def _stiffness(my_stiffness: Any) -> Verdict:
    from ...operators._cotangent import stiffness_matrix

    for mesh in _unseen_meshes():
        ref = stiffness_matrix(mesh).toarray()
        got = laplace_beltrami.as_matrix(student_call(my_stiffness, _fresh(mesh)), mesh.n_vertices, "W")
        hint = laplace_beltrami.diagnose_stiffness(got, ref)
        if hint is not None:
            raise Stop(WRONG, f"{hint} (graded on {_where(mesh)} the notebook does not show.)")
    return Verdict(1.0, f"Right on {_UNSEEN}.")


@grader("03-mass", kind="build", replaces=_MASS)
def _mass(my_mass: Any) -> Verdict:
    meshes = [(mesh, f"{_where(mesh)} the notebook does not show") for mesh in _unseen_meshes()]
    message = laplace_beltrami.judge_mass(my_mass, meshes, call=lambda f, mesh: student_call(f, _fresh(mesh)))
    return Verdict(1.0, message.replace("Right:", f"Right on {_UNSEEN}:", 1))


def _unseen_eigenproblems() -> list[tuple[Any, Any, int, str]]:
    """Pencils (W, A, k, where) no notebook cell and no visible check uses: the icosphere(2), whose
    first 16 eigenvalues come in exactly repeated groups of 1, 3, 5, 3 and 4 (icosahedral symmetry);
    a bumpy torus; an open sheet with the consistent (non-diagonal) mass; two disjoint pieces (a
    twofold zero eigenvalue). Each k ends below a gap of the spectrum, so the span is determined."""
    from ... import shapes
    from ...operators._cotangent import mass_matrix, stiffness_matrix

    rng = np.random.default_rng(3032)
    ball = shapes.icosphere(2)
    ring = shapes.torus(n_major=24, n_minor=10)
    bumpy = ring.with_vertices(ring.vertices * rng.uniform(0.92, 1.08, size=(ring.n_vertices, 1)))
    sheet = shapes.rectangle(1.5, 1.0, 12, 8)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.03, 0.03, size=(len(v), 2))
    v[:, 2] = 0.2 * np.sin(3 * v[:, 0]) * np.cos(2 * v[:, 1])
    sheet = sheet.with_vertices(v)
    pieces = laplace_beltrami._two_spheres()
    return [(stiffness_matrix(ball), mass_matrix(ball), 16, f"the icosphere of {ball.n_vertices} vertices"),
            (stiffness_matrix(bumpy), mass_matrix(bumpy), 12, f"a bumpy torus of {bumpy.n_vertices} vertices"),
            (stiffness_matrix(sheet), mass_matrix(sheet, "consistent"), 10,
             f"an open sheet of {sheet.n_vertices} vertices with the consistent mass"),
            (stiffness_matrix(pieces), mass_matrix(pieces), 5, f"a mesh of two separate pieces ({pieces.n_vertices} vertices)")]


@grader("03-eigensolve", kind="build", replaces=_EIGENSOLVE)
def _eigensolve(my_eigenbasis: Any) -> Verdict:
    message = laplace_beltrami.judge_eigensolve(
        my_eigenbasis, _unseen_eigenproblems(), call=lambda f, W, A, k: student_call(f, W, A, k),
        seen="graded on {} the notebook does not show")
    return Verdict(1.0, message.replace("Right:", "Right on four pencils the notebook does not show (an icosphere, a "
                                        "bumpy torus, an open sheet, two separate pieces):", 1))


@grader("03-convergence", kind="predict")
def _convergence(error_drop: Any) -> Verdict:
    return from_feedback(laplace_beltrami.check_convergence_factor(error_drop, show=False))


@grader("03-coefficients", kind="compute")
def _coefficients(coefficients: Any) -> Verdict:
    # The notebook's objects, rebuilt: blob = shapes.bumpy_sphere(4), blob_spectrum =
    # lbo.eigenbasis(blob, 50) (its signs are fixed deterministically) and f = its x coordinate.
    from ... import shapes
    from ...spectral._spectrum import eigenbasis

    require_attempt(coefficients)
    blob = shapes.bumpy_sphere(4)
    hint = laplace_beltrami.coefficient_hint(coefficients, eigenbasis(blob, 50), blob.vertices[:, 0], rtol=1e-5)
    if hint is not None:
        raise Stop(WRONG, hint)
    return Verdict(1.0, "Right: c = Φᵀ A f, the A inner products with the eigenfunctions.")


@grader("03-consistent", kind="compute")
def _consistent(consistent_side: Any) -> Verdict:
    return from_feedback(laplace_beltrami.check_consistent_mass(consistent_side, show=False))


@grader("03-scaling", kind="predict")
def _scaling(eigenvalue_factor: Any) -> Verdict:
    return from_feedback(laplace_beltrami.check_eigenvalue_scaling(eigenvalue_factor, scale=2, show=False))


@grader("03-kernel", kind="explore")
def _kernel(torus_zeros: Any, two_sphere_zeros: Any) -> Verdict:
    # The counts are the dimensions of the kernels (one per connected component); that the
    # notebook's meshes and threshold give them is asserted in tests/test_grading_03.py.
    return from_feedback(laplace_beltrami.check_zero_eigenvalues(torus_zeros, two_sphere_zeros, show=False))


@grader("03-lbo-recap", kind="recap")
def _recap_lbo(q1: Any, q2: Any, q3: Any) -> Verdict:
    answers = [q1, q2, q3]
    if unanswered(answers) is not None:
        raise Stop(NOT_ATTEMPTED, "Replace the `...` placeholders with your answers and run the cell again.")
    wrong = [f"Question {k}: {hint}" for k, (answer, judge) in enumerate(zip(answers, laplace_beltrami.RECAP_LBO), 1)
             if (hint := "not answered." if unanswered(answer) is not None else judge(answer)) is not None]
    if not wrong:
        return Verdict(1.0, "Right, all 3.")
    message = f"{3 - len(wrong)} of 3 right. " + " ".join(wrong)
    if len(wrong) == 3:
        raise Stop(WRONG, message)
    return Verdict((3 - len(wrong)) / 3, message)
