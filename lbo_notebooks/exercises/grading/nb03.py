"""Graded tests of notebook 03 (the Laplace–Beltrami operator): see :mod:`lbo_notebooks.exercises.grading`."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..feedback import WRONG, Stop
from ._registry import Verdict, grader, student_call

# What a build of the cotangent stiffness must not call: the library's operator and the private
# function behind it (the eigensolver and every other route to W go through it), and the other
# installed libraries that build the same matrix.
_STIFFNESS = ("lbo_notebooks.operators:stiffness_matrix", "lbo_notebooks.operators:_stiffness",
              "igl:cotmatrix", "robust_laplacian:mesh_laplacian", "gpytoolbox:cotangent_laplacian",
              "potpourri3d:cotan_laplacian")


def _unseen_meshes() -> list[Any]:
    """Meshes no notebook cell and no visible check uses: a bumpy torus, an open patch with
    obtuse triangles and boundary edges, and a lone obtuse triangle. Fresh objects at every call,
    so no cached operator is reachable from them."""
    from ... import shapes
    from ...mesh import Mesh

    rng = np.random.default_rng(3031)
    ring = shapes.torus()
    bumpy = ring.with_vertices(ring.vertices * rng.uniform(0.9, 1.1, size=(ring.n_vertices, 1)))
    sheet = shapes.rectangle(1.5, 1.0, 5, 4)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.08, 0.08, size=(len(v), 2))
    v[:, 2] = 0.3 * np.cos(2 * v[:, 1])
    obtuse = Mesh([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.3, 0.1]], [[0, 1, 2]])
    return [bumpy, sheet.with_vertices(v), obtuse]


@grader("03-stiffness", kind="build", replaces=_STIFFNESS)
def _stiffness(my_stiffness: Any) -> Verdict:
    from ...mesh import Mesh
    from ...operators import stiffness_matrix
    from ..basics import _diagnose_stiffness, _matrix

    for mesh in _unseen_meshes():
        ref = stiffness_matrix(mesh).toarray()
        fresh = Mesh(mesh.vertices.copy(), mesh.faces.copy())
        got = _matrix(student_call(my_stiffness, fresh), mesh.n_vertices, "W")
        hint = _diagnose_stiffness(got, ref)
        if hint is not None:
            raise Stop(WRONG, f"{hint} (graded on a mesh of {mesh.n_vertices} vertices the notebook does not show.)")
    return Verdict(1.0, "Right on three meshes the notebook does not show (a torus, an open sheet, an obtuse triangle).")
