"""Self-checks of notebook 00 (start here).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from functools import lru_cache
from typing import Any

import numpy as np

from .feedback import (
    as_array, Feedback, WRONG, Stop, run_check, require_attempt, as_number, close_to,
)

__all__ = [
    "check_sphere_eigenvalues",
    "check_mesh_size",
    "check_eigenfunction",
    "check_load_error",
]


# --- 00 · start here -------------------------------------------------------------------------------

def check_sphere_eigenvalues(values: Any, *, show: bool = True) -> Feedback:
    """Exercise 00-sphere: the first nine eigenvalues of the unit sphere, ℓ(ℓ+1) repeated 2ℓ+1 times.

    Examples
    --------
    >>> check_sphere_eigenvalues([0, 2, 2, 2, 6, 6, 6, 6, 6], show=False).correct
    True
    >>> "ℓ(ℓ+1)" in check_sphere_eigenvalues([0, 1, 1, 1, 4, 4, 4, 4, 4], show=False).message
    True
    """
    def body() -> str:
        require_attempt(values)
        got = as_array(values, "a list of nine numbers")
        exact = np.repeat([l * (l + 1) for l in range(3)], [2 * l + 1 for l in range(3)]).astype(float)
        if got.ndim == 2 and 1 in got.shape:
            got = got.ravel()
        if got.shape != (9,):
            raise Stop(WRONG, "Give nine numbers: λ_0, ..., λ_8, each eigenvalue written as often as it repeats.")
        if np.allclose(got, exact, rtol=1e-6, atol=1e-9):
            return "Right: ℓ = 0 (the constant, λ = 0), then 2 three times and 6 five times."
        if np.all(np.abs(got - exact) <= 0.02 * np.maximum(exact, 1.0)):
            raise Stop(WRONG, "Those are the mesh's measured eigenvalues (within 1% of the sphere's); write the exact "
                              "values ℓ(ℓ+1) of the unit sphere, the prediction they are compared with.")
        if np.allclose(got, np.repeat([l * l for l in range(3)], [2 * l + 1 for l in range(3)])):
            raise Stop(WRONG, "Those are ℓ², the eigenvalues are ℓ(ℓ+1).")
        if np.any(np.diff(got) < 0):
            raise Stop(WRONG, "List them in increasing order, as `eigenbasis` returns them.")
        if abs(got[0]) > 1e-9:
            raise Stop(WRONG, "The first is λ_0 = 0 (ℓ = 0): a constant function has no energy.")
        if np.allclose(got, [l * (l + 1) for l in range(9)]):
            raise Stop(WRONG, "Each ℓ(ℓ+1) repeats 2ℓ+1 times (three functions for ℓ = 1, five for ℓ = 2).")
        raise Stop(WRONG, "Write ℓ(ℓ+1) for ℓ = 0, 1, 2, ..., each 2ℓ+1 times, until you have nine.")
    return run_check("00-sphere", show, body)


def check_mesh_size(counts: Any, mesh: Any, *, show: bool = True) -> Feedback:
    """Exercise 00-size: ``(number of vertices, number of triangles)`` of ``mesh``.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> ball = shapes.icosphere(1)
    >>> check_mesh_size((ball.n_vertices, ball.n_faces), ball, show=False).correct
    True
    >>> "Swapped" in check_mesh_size((ball.n_faces, ball.n_vertices), ball, show=False).message
    True
    """
    def body() -> str:
        require_attempt(counts)
        pair = list(counts.ravel()) if isinstance(counts, np.ndarray) and counts.size == 2 else counts  # np.array([V, F]) too
        if isinstance(pair, Mapping) or not isinstance(pair, (tuple, list)) or len(pair) != 2:
            raise Stop(WRONG, "Give two numbers, in this order: (vertices, triangles).")
        nv, nf = (as_number(c, "a whole number") for c in pair)
        if any(abs(c - round(c)) > 1e-9 * max(1.0, abs(c)) for c in (nv, nf)):
            raise Stop(WRONG, "Counts are whole numbers: the number of rows of `vertices` and of `faces`.")
        nv, nf = int(round(nv)), int(round(nf))
        v, f, e = mesh.n_vertices, mesh.n_faces, len(mesh.edges)
        if (nv, nf) == (v, f):
            return f"Right: V - E + F = {v - e + f} for this closed surface, as for a sphere."
        if (nv, nf) == (f, v):
            raise Stop(WRONG, "Swapped: vertices first, then triangles.")
        for got, n, name in ((nv, v, "vertex"), (nf, f, "triangle")):
            if got == 3 * n:
                raise Stop(WRONG, f"Three times too many {name} entries: you counted the numbers in the array "
                                   f"(three per {name}), not its rows.")
        if nf == e:
            raise Stop(WRONG, "That second number counts the edges; count the triangles (rows of `faces`).")
        if nv == v and nf == 3:
            raise Stop(WRONG, "3 is the number of coordinates of a vertex (the second entry of `vertices.shape`); "
                              "count the triangles: the rows of `faces`.")
        raise Stop(WRONG, "Count the rows of `mesh.vertices` and `mesh.faces` (or read `mesh.summary()`).")
    return run_check("00-size", show, body)


@lru_cache(maxsize=2)
def _torus_spectrum(k: int) -> Any:
    from .. import shapes
    from ..spectral._spectrum import eigenbasis

    return eigenbasis(shapes.torus(), k)


def check_eigenfunction(phi: Any, index: int = 6, *, show: bool = True) -> Feedback:
    """Exercise 00-torus: ``phi`` is an eigenfunction φ_index of ``shapes.torus()`` (read back from a file).

    Judged by its Rayleigh quotient and residual, so any sign (or rotation in a repeated
    eigenvalue) is accepted.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> phi = eigenbasis(shapes.torus(), 7).vectors[:, 6]
    >>> check_eigenfunction(-phi, 6, show=False).correct
    True
    """
    def body() -> str:
        require_attempt(phi)
        spectrum = _torus_spectrum(max(16, index + 3))
        n = spectrum.n_vertices
        f = as_array(phi, "an array with one value per vertex")
        if f.ndim == 2 and 1 in f.shape:
            f = f.ravel()
        if f.shape != (n,):
            raise Stop(WRONG, f"Expected one value per vertex of the torus, shape ({n},), got {f.shape}: "
                               "one column of `spectrum.vectors`.")
        W, A = spectrum.stiffness, spectrum.mass
        norm2 = float(f @ (A @ f))
        if norm2 <= 0:
            raise Stop(WRONG, "That function is zero.")
        r = float(f @ (W @ f)) / norm2
        residual = np.linalg.norm(W @ f - r * (A @ f)) / max(np.linalg.norm(W @ f), 1e-300)
        lam = spectrum.values
        if residual > 1e-5:
            raise Stop(WRONG, "Not an eigenfunction of W φ = λ A φ: take one column of `eigenbasis(mesh, k).vectors`.")
        if close_to(r, lam[index], 1e-6):
            return f"Right: an eigenfunction with the eigenvalue λ_{index}."
        hit = int(np.argmin(np.abs(lam - r)))
        if hit < index:
            raise Stop(WRONG, f"An eigenfunction, but of a smaller eigenvalue: indices start at 0 (φ_0 is the constant), "
                               f"so φ_{index} is column {index}, and you need k ≥ {index + 1}.")
        raise Stop(WRONG, f"An eigenfunction, but of a larger eigenvalue: φ_{index} is column {index} of `vectors`.")
    return run_check("00-torus", show, body)


# What load_mesh says of a face whose vertex does not exist: an index outside the file's range
# (OFF and PLY count from 0, OBJ from 1 and refuses 0 outright; a Mesh built from arrays says it too).
_MISSING_VERTEX = re.compile(r"vertex ind(?:ex|ices) .*outside -?\d+\.\.-?\d+|vertex index 0; OBJ indices are 1-based", re.S)


def _without_path(message: str) -> str:
    """A file's MeshError without the path it starts with (``'/tmp/x/bad.off': ...``), so that
    nothing in a (random, temporary) folder name can decide a check."""
    import ast

    if message[:1] in ("'", '"'):
        for end in range(1, len(message)):
            if message[end] == message[0] and message[end + 1 : end + 3] == ": ":
                try:
                    if isinstance(ast.literal_eval(message[: end + 1]), str):
                        return message[end + 3 :]
                except (ValueError, SyntaxError):
                    continue
    return message


def check_load_error(error: Any, *, show: bool = True) -> Feedback:
    """Exercise 00-missing: the exception ``load_mesh`` raised for a face naming a vertex that does not exist."""
    from ..geometry._mesh import MeshError

    def body() -> str:
        require_attempt(error)
        if isinstance(error, MeshError):
            if _MISSING_VERTEX.search(_without_path(str(error))):
                return "Right: a `MeshError` that names the face and the vertex index that does not exist."
            raise Stop(WRONG, "That `MeshError` is about another defect of the file: read its message. Make one face "
                              "use an index past the last vertex (faces count vertices from 0).")
        raise Stop(WRONG, not_a_mesh_error(error))
    return run_check("00-missing", show, body)


def not_a_mesh_error(error: Any) -> str:
    """The hint for an answer to 00-missing that is not a ``MeshError`` (the check and the graded
    test share it)."""
    from ..geometry._mesh import Mesh

    if isinstance(error, type):
        return "That is an exception class; keep the exception object: `except lbo.MeshError as err: error = err`."
    if isinstance(error, str):
        return "Keep the exception object itself (`error = err` inside the `except` block), not its text."
    if isinstance(error, Mesh):
        return ("`load_mesh` returned a mesh: no face of your file refers to a missing vertex. "
                "Faces count vertices from 0, so a file with 3 vertices has indices 0, 1, 2.")
    if isinstance(error, BaseException):
        return (f"`load_mesh` refuses a broken mesh with a `MeshError`; you kept a {type(error).__name__}. "
                "Is the file's path right, and its header (counts of vertices and faces) consistent?")
    return f"Expected the exception object, got {type(error).__name__}."
