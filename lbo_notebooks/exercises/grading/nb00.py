"""Graded tests of notebook 00 (start here): see :mod:`lbo_notebooks.exercises.grading`.

Nothing here needs open3d, the notebook's folder or its temporary files: each context is rebuilt
from the prompt's definitions (the 642-vertex sphere's exact eigenvalues, ``shapes.bumpy_sphere(3)``
for the mesh read back from ``blob.ply``, ``shapes.torus()`` for the torus read back from an
``.obj`` file, which keeps the float64 coordinates exactly), and the exception of 00-missing is
judged on what its own message says.
"""

from __future__ import annotations

import ast
import re
from typing import Any

from ..feedback import NOT_ATTEMPTED, WRONG, Stop, is_placeholder
from ._registry import Verdict, from_feedback, grader


@grader("00-sphere", kind="predict")
def _sphere(sphere_values: Any) -> Verdict:
    from ..start_here import check_sphere_eigenvalues

    # The exact values ℓ(ℓ+1) need no mesh: the check compares with them, not with the kernel's spectrum.
    return from_feedback(check_sphere_eigenvalues(sphere_values, show=False))


@grader("00-size", kind="compute")
def _size(size: Any) -> Verdict:
    from ... import shapes
    from ..start_here import check_mesh_size

    # `loaded` is blob = shapes.bumpy_sphere(3) written to PLY and read back; the notebook asserts
    # the same vertices and faces, so the counts are the blob's (not the kernel's `loaded`).
    return from_feedback(check_mesh_size(size, shapes.bumpy_sphere(3), show=False))


@grader("00-torus", kind="explore")
def _torus(phi6: Any) -> Verdict:
    from ..start_here import check_eigenfunction

    # Judged on shapes.torus() rebuilt here (an .obj round trip keeps its arrays exactly:
    # tests/test_grading_00.py checks it): the Rayleigh quotient and residual of W φ = λ A φ,
    # so any sign or scale of φ_6 is right, and φ_5 or φ_7 are not.
    return from_feedback(check_eigenfunction(phi6, 6, show=False))


# What a MeshError says of a face whose vertex does not exist (mesh.py, formats/*.py): the index
# as the file writes it and the range it must lie in, or OBJ's refusal of index 0.
_ONE_INDEX = re.compile(r"uses vertex index (-?\d+), outside (-?\d+)\.\.(-?\d+)")
_FIRST_FACE = re.compile(r"faces use vertex indices outside (-?\d+)\.\.(-?\d+) \(first: (?:face|triangle) \d+ = "
                         r"\[(-?\d+), (-?\d+), (-?\d+)\]")
_OBJ_ZERO = "uses vertex index 0; OBJ indices are 1-based"


def _without_path(message: str) -> str:
    """The message without the file's path it starts with (``'/tmp/x/bad.off': ...``): nothing in
    a random temporary folder's name may decide the grade."""
    if message[:1] in ("'", '"'):
        for end in range(1, len(message)):
            if message[end] == message[0] and message[end + 1 : end + 3] == ": ":
                try:
                    if isinstance(ast.literal_eval(message[: end + 1]), str):
                        return message[end + 3 :]
                except (ValueError, SyntaxError, MemoryError, RecursionError):
                    continue
    return message


def _names_a_missing_vertex(body: str) -> bool:
    """The message names a vertex index and a range that index lies outside of (a negative OBJ
    index counts back from the end, so -4 of three vertices is missing and -1 is not)."""
    one = _ONE_INDEX.search(body)
    if one:
        index, low, high = (int(g) for g in one.groups())
        if index < 0 and low == 1:  # OBJ: -k is the k-th vertex from the end
            return -index > high
        return not low <= index <= high
    first = _FIRST_FACE.search(body)
    if first:
        low, high, *corners = (int(g) for g in first.groups())
        return any(not low <= c <= high for c in corners)
    return _OBJ_ZERO in body


@grader("00-missing", kind="explore")
def _missing(error: Any) -> Verdict:
    from ...geometry._mesh import MeshError

    if is_placeholder(error):
        raise Stop(NOT_ATTEMPTED, "Replace the `...` placeholder with the exception `load_mesh` raises and run the cell again.")
    if isinstance(error, MeshError):
        try:
            body = _without_path(str(error))
        except Exception:  # noqa: BLE001 - an exception object whose str() fails
            raise Stop(WRONG, "That exception has no readable message.") from None
        if _names_a_missing_vertex(body):
            return Verdict(1.0, "Right: a `MeshError` that names the face, the vertex index that does not exist and "
                                "the range of the file's indices.")
        raise Stop(WRONG, "That `MeshError` is about another defect of the file: read its message. Make one face use "
                          "an index past the last vertex (faces count vertices from 0 in OFF and PLY, from 1 in OBJ).")
    from ..start_here import not_a_mesh_error

    raise Stop(WRONG, not_a_mesh_error(error))
