"""Graded tests of notebook 08 (scale-invariant metrics): see :mod:`lbo_notebooks.exercises.grading`.

08-angle-defects is a *build it yourself*: the student's angle defects are judged on four meshes
the notebook does not show (a bumpy sphere, a bumpy torus, an open curved patch, a flattened
ellipsoid with obtuse triangles) with every route of the library (and of the other installed
libraries) to corner angles or defects made unavailable. Every other answer is a value. 08-floor is judged on the notebook's horse
rebuilt from its definition (``creature("horse", n_vertices=4000)``, a few seconds: the cost of this
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
from ._registry import Verdict, from_feedback, grader, recap_verdict, student_call


@functools.lru_cache(maxsize=1)
def _horse() -> Any:
    """The notebook's horse (section 1), rebuilt in the graded run."""
    from ...shapes._creatures import creature

    return creature("horse", n_vertices=4000)


# What a build of the angle defects must not call: the curvature module's defects and every route
# through them (the curvature, the one-ring |K|, the conformal factor, the metric's mass), the corner
# angles and the cotangents they are made of (an angle is arctan2(1, cot)), the visible check's own
# reference, and the other installed libraries' angles and defects (also by the submodule path a
# pickled reference uses). The mesh's vertices, faces, face areas and boundary stay allowed.
_DEFECTS = (
    "lbo_notebooks.operators._curvature:angle_defects", "lbo_notebooks.operators._curvature:_angle_defects",
    "lbo_notebooks.operators._curvature:gaussian_curvature",
    "lbo_notebooks.operators._curvature:_gaussian_curvature",
    "lbo_notebooks.operators._curvature:_kappa", "lbo_notebooks.operators._curvature:_rho",
    "lbo_notebooks.operators._curvature:metric_curvature",
    "lbo_notebooks.operators._curvature:conformal_factor",
    "lbo_notebooks.operators._curvature:metric_mass_matrix",
    "lbo_notebooks.operators._cotangent:corner_angles", "lbo_notebooks.operators._cotangent:face_cotangents",
    "lbo_notebooks.operators._cotangent:_face_cotangents",
    "lbo_notebooks.exercises.minmax_and_metrics:defect_slips",
    "lbo_notebooks.exercises.minmax_and_metrics:_angles_by_hand",
    "igl:gaussian_curvature", "igl.pyigl_core:gaussian_curvature", "igl:internal_angles",
    "igl.pyigl_core:internal_angles", "igl:principal_curvature", "igl.pyigl_core:principal_curvature",
    "gpytoolbox:angle_defect", "gpytoolbox.angle_defect:angle_defect",
    "gpytoolbox:angle_defect_intrinsic", "gpytoolbox.angle_defect_intrinsic:angle_defect_intrinsic",
    "gpytoolbox:tip_angles", "gpytoolbox.tip_angles:tip_angles",
    "gpytoolbox:tip_angles_intrinsic", "gpytoolbox.tip_angles_intrinsic:tip_angles_intrinsic",
    "lapy:TriaMesh.curvature", "lapy:TriaMesh.curvature_tria",
)


def _unseen_meshes() -> list[tuple[Any, str]]:
    """Meshes no cell of 08 and no visible check uses, fresh at every call (so no cached angle is
    reachable from them): a bumpy sphere (χ = 2), a bumpy torus (χ = 0), an open curved patch
    with boundary (χ = 1) and a flattened ellipsoid whose rim triangles are obtuse (χ = 2)."""
    import numpy as np

    from ... import shapes

    rng = np.random.default_rng(8081)
    ball = shapes.bumpy_sphere(2, seed=5)
    ball = ball.with_vertices(ball.vertices * rng.uniform(0.95, 1.05, size=(ball.n_vertices, 1)))
    ring = shapes.torus(1.0, 0.35, 20, 9)
    ring = ring.with_vertices(ring.vertices * rng.uniform(0.93, 1.07, size=(ring.n_vertices, 1)))
    patch = shapes.rectangle(1.2, 0.8, 7, 5)
    v = patch.vertices.copy()
    v[:, :2] += rng.uniform(-0.05, 0.05, size=(len(v), 2))
    v[:, 2] = 0.4 * np.exp(-4 * ((v[:, 0] - 0.5) ** 2 + (v[:, 1] - 0.4) ** 2)) + 0.2 * v[:, 0] * v[:, 1]
    flat = shapes.icosphere(2)
    flat = flat.with_vertices(flat.vertices * [1.3, 0.9, 0.12])
    return [(ball, f"a bumpy sphere of {ball.n_vertices} vertices"), (ring, f"a bumpy torus of {ring.n_vertices} vertices"),
            (patch.with_vertices(v), f"an open curved patch of {patch.n_vertices} vertices"),
            (flat, f"a flattened ellipsoid of {flat.n_vertices} vertices with obtuse triangles")]


def _fresh(mesh: Any) -> Any:
    from ...geometry._mesh import Mesh

    return Mesh(mesh.vertices.copy(), mesh.faces.copy())


@grader("08-angle-defects", kind="build", replaces=_DEFECTS)
def _angle_defects(my_angle_defects: Any) -> Verdict:
    meshes = [(mesh, f"{where}, which the notebook does not show") for mesh, where in _unseen_meshes()]
    message = minmax_and_metrics.judge_angle_defects(my_angle_defects, meshes,
                                                     call=lambda f, mesh: student_call(f, _fresh(mesh)))
    return Verdict(1.0, message.replace("Right:", "Right on four meshes the notebook does not show (a bumpy sphere, a "
                                        "bumpy torus, an open patch, obtuse triangles):", 1))


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
