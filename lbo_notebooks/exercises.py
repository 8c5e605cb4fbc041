"""Self-checks for the notebooks' exercises: feedback on an attempt, never the answer.

Each exercise in the notebooks ends with a call such as ``exercises.check_stiffness(my_stiffness)``.
The check compares the student's answer with the library (or with the exact value), and says one of

- **correct**, sometimes with a remark (e.g. which of two valid mass matrices was built);
- **wrong**, with a hint aimed at the typical mistake: a factor of two, a wrong sign, a transpose,
  the Euclidean inner product where the ``A`` inner product belongs, a missing diagonal, ...;
- **not attempted**, when the answer is still the placeholder the student edition leaves
  (``...``, ``None``, ``NotImplemented``, a function that raises ``NotImplementedError`` or
  returns nothing). This never raises, so the student edition runs top to bottom unanswered.

Messages never contain the reference value. In Jupyter the feedback is shown as one coloured
line (IPython's display machinery; plain text elsewhere), and the check returns a
:class:`Feedback` whose ``correct`` attribute the autograder asserts (the hidden tests of the
notebooks, see docs/exercises.md). :func:`solution` shows the instructor's solution of an
exercise on purpose, read from the instructor edition (``notebooks/``) when it is available.

This module needs neither the grader nor IPython; the checks import the heavier parts of the
library (creatures, spectra) only when an attempt has to be compared with them.

Examples
--------
>>> from lbo_notebooks import exercises
>>> exercises.check_area_factor(..., scale=1.6, show=False).status
'not attempted'
>>> exercises.check_area_factor(1.6, scale=1.6, show=False).status
'wrong'
>>> exercises.check_area_factor(1.6**2, scale=1.6, show=False).correct
True
"""

from __future__ import annotations

import html
import json
import re
from collections.abc import Callable, Mapping
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

__all__ = [
    "Feedback", "CORRECT", "WRONG", "NOT_ATTEMPTED", "MIME_TYPE", "solution",
    "check_edge_count", "check_area_factor", "check_stretch_growth", "check_smallest_angles", "check_leg_area",
    "check_stiffness", "check_mass", "check_convergence_factor", "check_coefficients", "check_consistent_mass",
    "check_eigenvalue_scaling", "check_zero_eigenvalues",
    "check_repair_counts", "check_operator_choice", "check_cloud_eigenvalue", "check_largest_component",
    "check_neighbors_effect", "check_cloud_pieces",
]

CORRECT, WRONG, NOT_ATTEMPTED = "correct", "wrong", "not attempted"
MIME_TYPE = "application/vnd.lbo-notebooks.feedback+json"
"""Extra MIME type of the displayed feedback: ``{"exercise", "status"}``, for scripts that read outputs."""

_STYLE = {CORRECT: ("#1a7f37", "✔"), WRONG: ("#b42318", "✘"), NOT_ATTEMPTED: ("#8a6d00", "…")}


class Feedback:
    """The result of a check: exercise id, status and a message (which never gives the answer away).

    Attributes
    ----------
    exercise : str
        The exercise's id, e.g. ``"02-stiffness"`` (its cells in the notebook carry the grade ids
        ``"02-stiffness-answer"`` and ``"02-stiffness-check"``).
    status : {"correct", "wrong", "not attempted"}
    message : str
        One or two sentences, with inline code in backticks.

    Examples
    --------
    >>> fb = Feedback("01-edges", "wrong", "Off by a factor of two.")
    >>> fb.correct, fb.attempted
    (False, True)
    >>> print(fb)
    01-edges · wrong: Off by a factor of two.
    """

    __slots__ = ("exercise", "status", "message", "_shown_at")

    def __init__(self, exercise: str, status: str, message: str) -> None:
        if status not in _STYLE:
            raise ValueError(f"status must be one of {tuple(_STYLE)}, got {status!r}.")
        self.exercise, self.status, self.message = exercise, status, message
        self._shown_at: int | None = None

    @property
    def correct(self) -> bool:
        return self.status == CORRECT

    @property
    def attempted(self) -> bool:
        return self.status != NOT_ATTEMPTED

    def __str__(self) -> str:
        return f"{self.exercise} · {self.status}: {self.message}"

    def __repr__(self) -> str:
        return f"Feedback({self.exercise!r}, {self.status!r}, {self.message!r})"

    def _repr_html_(self) -> str:
        colour, mark = _STYLE[self.status]
        text = re.sub(r"`([^`]+)`", r"<code>\1</code>", html.escape(self.message, quote=False))
        reveal = ("" if self.correct else
                  f' <span style="opacity: 0.6">(to see a solution: <code>exercises.solution("{html.escape(self.exercise)}")</code>)</span>')
        return (f'<div class="lbo-feedback" data-exercise="{html.escape(self.exercise)}" data-status="{self.status}" '
                f'style="border-left: 4px solid {colour}; padding: 2px 8px; margin: 2px 0">'
                f'<b style="color: {colour}">{mark} {self.status}</b> · exercise {html.escape(self.exercise)}: {text}{reveal}</div>')

    def _bundle(self) -> dict[str, Any]:
        return {"text/plain": str(self), "text/html": self._repr_html_(),
                MIME_TYPE: {"exercise": self.exercise, "status": self.status}}

    def _ipython_display_(self) -> None:
        # A check shows its feedback itself; returned as a cell's last value, it is not shown twice.
        shell = _shell()
        if shell is not None and self._shown_at == shell.execution_count:
            return
        _show(self)


def _shell() -> Any:
    try:
        from IPython import get_ipython
    except ImportError:  # pragma: no cover - IPython is a dependency of JupyterLab
        return None
    return get_ipython()


def _show(feedback: Feedback) -> None:
    shell = _shell()
    if shell is None:
        print(feedback)
        return
    from IPython.display import display

    display(feedback._bundle(), raw=True)
    feedback._shown_at = shell.execution_count


def _result(exercise: str, status: str, message: str, show: bool) -> Feedback:
    feedback = Feedback(exercise, status, message)
    if show:
        _show(feedback)
    return feedback


# --- the answer as given -------------------------------------------------------------------------

def _is_placeholder(x: Any) -> bool:
    return x is None or x is Ellipsis or x is NotImplemented or (isinstance(x, str) and x.strip() in ("", "..."))


def _unanswered(x: Any) -> str | None:
    """Why ``x`` counts as not attempted (a message), or None if it is an attempt."""
    if _is_placeholder(x):
        return "Replace the `...` placeholder with your answer and run the cell again."
    parts = list(x.values()) if isinstance(x, Mapping) else list(x) if isinstance(x, (list, tuple)) else []
    if parts and all(_is_placeholder(p) for p in parts):
        return "Replace the `...` placeholders with your answers and run the cell again."
    return None


class _Stop(Exception):
    """Raised inside a check to finish it early with this feedback status and message."""

    def __init__(self, status: str, message: str) -> None:
        super().__init__(message)
        self.status, self.message = status, message


def _run(exercise: str, show: bool, body: Callable[[], str]) -> Feedback:
    """Run a check's body: it returns the message of a correct answer or raises _Stop."""
    try:
        return _result(exercise, CORRECT, body(), show)
    except _Stop as stop:
        return _result(exercise, stop.status, stop.message, show)


def _attempt(x: Any) -> None:
    why = _unanswered(x)
    if why is not None:
        raise _Stop(NOT_ATTEMPTED, why)
    if isinstance(x, (Mapping, list, tuple)):
        parts = list(x.values()) if isinstance(x, Mapping) else list(x)
        if any(_is_placeholder(p) for p in parts):
            raise _Stop(WRONG, "Some parts are still `...`: fill in every part.")


def _number(x: Any, what: str = "a number") -> float:
    try:
        value = float(np.asarray(x, dtype=np.float64).reshape(()))
    except (TypeError, ValueError):
        raise _Stop(WRONG, f"Expected {what}, got {type(x).__name__}.") from None
    if not np.isfinite(value):
        raise _Stop(WRONG, f"Expected {what}, got {value}.")
    return value


def _call(function: Any, *args: Any) -> Any:
    """Call the student's function; placeholders and stubs count as not attempted."""
    if _is_placeholder(function):
        raise _Stop(NOT_ATTEMPTED, "Write the function, then run the cell again.")
    if not callable(function):
        raise _Stop(WRONG, f"Pass the function itself (without calling it); got {type(function).__name__}.")
    try:
        value = function(*args)
    except NotImplementedError:
        raise _Stop(NOT_ATTEMPTED, "The function body is still the stub: write it, then run the cell again.") from None
    except Exception as err:  # the student's bug, reported, not raised
        raise _Stop(WRONG, f"Your function raised {type(err).__name__}: {err}") from None
    if _is_placeholder(value):
        raise _Stop(NOT_ATTEMPTED, "Your function returns nothing: still the stub, or a missing `return`?")
    return value


def _near(x: float, target: float, rtol: float = 1e-2) -> bool:
    return abs(x - target) <= rtol * abs(target)


def _choice(exercise: str, answer: Any, options: Mapping[str, str | None], show: bool) -> Feedback:
    """A multiple-choice answer: ``options`` maps each choice to its hint (None: the right one)."""
    def body() -> str:
        _attempt(answer)
        if not isinstance(answer, str) or answer.strip().lower() not in options:
            raise _Stop(WRONG, "Answer with one of: " + ", ".join(f'"{o}"' for o in options) + ".")
        hint = options[answer.strip().lower()]
        if hint is not None:
            raise _Stop(WRONG, hint)
        return "Right."
    return _run(exercise, show, body)


# --- 01 · the shape collection -------------------------------------------------------------------

def check_edge_count(n_edges: Any, mesh: Any, *, show: bool = True) -> Feedback:
    """Exercise 01-edges: the number of edges of a closed triangle mesh, from its faces alone.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> ball = shapes.icosphere(1)
    >>> check_edge_count(3 * ball.n_faces // 2, ball, show=False).correct
    True
    >>> "two" in check_edge_count(3 * ball.n_faces, ball, show=False).message
    True
    """
    def body() -> str:
        _attempt(n_edges)
        e, f = len(mesh.edges), mesh.n_faces
        got = _number(n_edges, "a whole number")
        if got == e:
            chi = mesh.n_vertices - e + f
            return f"Right: each triangle has three edges and each edge borders two triangles, so E = 3F/2; here V - E + F = {chi}."
        if got == 3 * f:
            raise _Stop(WRONG, "Off by a factor of two: three edges per triangle counts every edge twice, once from each of the two triangles it borders.")
        if got == e / 2:
            raise _Stop(WRONG, "Off by a factor of two (too few): you divided once too often.")
        raise _Stop(WRONG, "Count the edge slots (three per triangle), then ask how many triangles share each edge of a closed surface.")
    return _run("01-edges", show, body)


def check_area_factor(prediction: Any, scale: float, *, show: bool = True) -> Feedback:
    """Exercise 01-area: by what factor does the area of a part grow when the part is scaled by ``scale``?"""
    def body() -> str:
        _attempt(prediction)
        got = _number(prediction)
        if _near(got, scale**2):
            return "Right: lengths grow by s, areas by s²."
        if _near(got, scale):
            raise _Stop(WRONG, "That is the factor of the lengths; an area has two length dimensions.")
        if _near(got, scale**3):
            raise _Stop(WRONG, "That is how a volume scales; a surface area has two length dimensions.")
        if _near(got, scale**-2) or _near(got, 1 / scale):
            raise _Stop(WRONG, "The part gets bigger, so its area grows: check the direction of your factor.")
        raise _Stop(WRONG, "Think of a square of side L scaled by s: what is its new area?")
    return _run("01-area", show, body)


def check_stretch_growth(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 01-stretch: what happens to the worst edge stretch when a bend's angle doubles?"""
    return _choice("01-stretch", answer, {
        "same": "The stretch rθ/L depends on the angle θ: a larger bend over the same band stretches more.",
        "double": None,
        "quadruple": "rθ/L is linear in θ, not quadratic: you may be thinking of an area.",
        "half": "A larger bend stretches the outer side more, not less.",
    }, show)


def check_smallest_angles(angles: Any, species: str = "dog", *, show: bool = True) -> Feedback:
    """Exercise 01-angles: the smallest triangle angle (degrees) of ``creature(species, n_vertices=n)``, per size n."""
    def body() -> str:
        _attempt(angles)
        if not isinstance(angles, Mapping) or not angles:
            raise _Stop(WRONG, "Give a dict {number of vertices asked for: smallest angle in degrees}.")
        from .creatures import creature
        from .operators import corner_angles

        for n, got in angles.items():
            got = _number(got, f"a number for n = {n}")
            exact = float(np.degrees(corner_angles(creature(species, n_vertices=int(n)))).min())
            if _near(got, exact, 1e-3):
                continue
            if _near(got, np.radians(exact), 1e-3):
                raise _Stop(WRONG, "These look like radians: convert with `np.degrees`.")
            if got > 60:
                raise _Stop(WRONG, f"n = {n}: every triangle has an angle of at most 60°, so the smallest angle cannot exceed 60°: take the minimum over all corners.")
            raise _Stop(WRONG, f"n = {n}: not the smallest corner angle of that mesh; `corner_angles(mesh)` gives every corner's angle.")
        return "Right: those are the smallest corner angles of the meshes you built."
    return _run("01-angles", show, body)


def check_leg_area(predicted: Any, n_vertices: int, species: str = "dog", *, show: bool = True) -> Feedback:
    """Exercise 01-legs: predicted total area for legs scaled by s, ``{s: area}``, against the built shapes (1%)."""
    def body() -> str:
        _attempt(predicted)
        if not isinstance(predicted, Mapping) or not predicted:
            raise _Stop(WRONG, "Give a dict {scale s: predicted total area}.")
        from .creatures import creature, creature_parts

        template = creature(species, n_vertices=n_vertices)
        parts = creature_parts(species, n_vertices=n_vertices)
        legs = (parts["front_legs"] | parts["hind_legs"])[template.faces].all(axis=1)
        leg, rest = template.face_areas[legs].sum(), template.face_areas[~legs].sum()
        for s, got in predicted.items():
            s, got = float(s), _number(got, f"a number for s = {s}")
            actual = creature(species, parts={"legs": s}, n_vertices=n_vertices).area
            if _near(got, actual, 0.015):
                continue
            if s != 1 and _near(got, s * leg + rest, 0.005):
                raise _Stop(WRONG, f"s = {s}: the legs' area grows by s², not s.")
            if s != 1 and _near(got, s**2 * (leg + rest), 0.005):
                raise _Stop(WRONG, f"s = {s}: only the legs are scaled; the rest of the body keeps its area.")
            if s != 1 and _near(got, s**2 * leg, 0.05):
                raise _Stop(WRONG, f"s = {s}: add the area of the rest of the body.")
            raise _Stop(WRONG, f"s = {s}: off by more than 1.5% from the scaled shape's area; prediction = (leg area) × s² + (rest).")
        return "Right: within 1.5% for every scale (the blend band at the hips and shoulders is not scaled by exactly s²)."
    return _run("01-legs", show, body)


# --- 02 · the Laplace–Beltrami operator ----------------------------------------------------------

@lru_cache(maxsize=1)
def _test_meshes() -> tuple[Any, ...]:
    """Small meshes the build-it-yourself checks run on: a right triangle, an irregular closed
    surface and an open sheet with obtuse triangles."""
    from . import shapes
    from .mesh import Mesh

    rng = np.random.default_rng(28)
    triangle = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    ball = shapes.icosphere(1)
    blob = ball.with_vertices(ball.vertices * rng.uniform(0.8, 1.25, size=(ball.n_vertices, 1)))
    sheet = shapes.rectangle(2.0, 1.0, 4, 3)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.12, 0.12, size=(len(v), 2))
    v[:, 2] = 0.2 * np.sin(v[:, 0])
    return triangle, blob, sheet.with_vertices(v)


def _matrix(value: Any, n: int, name: str) -> np.ndarray:
    import scipy.sparse as sp

    if sp.issparse(value):
        value = value.toarray()
    try:
        m = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise _Stop(WRONG, f"{name} should be a matrix (NumPy array or scipy.sparse); got {type(value).__name__}.") from None
    if m.shape != (n, n):
        raise _Stop(WRONG, f"{name} should be n × n, one row and one column per vertex (n = {n}); got shape {m.shape}.")
    return m


def _same(m: np.ndarray, ref: np.ndarray, rtol: float = 1e-8) -> bool:
    return bool(np.abs(m - ref).max() <= rtol * max(np.abs(ref).max(), 1e-300))


def _diagnose_stiffness(m: np.ndarray, ref: np.ndarray) -> str | None:
    """None if m is the stiffness matrix ref, else a hint at what is off."""
    if _same(m, ref):
        return None
    if _same(m, 2 * ref):
        return "Twice too large: W_ij = -½ (cot a + cot b); did you drop the ½, or add each triangle twice?"
    if _same(m, ref / 2):
        return "Half too small: an interior edge has two opposite angles, one in each of its triangles; add both cotangents."
    if _same(m, -ref):
        return "Wrong sign: W is positive semidefinite, with negative off-diagonal entries -½ (cot a + cot b) and a positive diagonal."
    d, d_ref = np.diag(m), np.diag(ref)
    off, off_ref = m - np.diag(d), ref - np.diag(d_ref)
    if not np.allclose(m, m.T, rtol=0, atol=1e-10 * np.abs(ref).max()):
        if _same(off + off.T, off_ref):
            return "Only one of W_ij and W_ji is filled in: W is symmetric, so add each edge's weight at (i, j) and at (j, i)."
        return "W should be symmetric (the weight of edge ij is the weight of edge ji); yours is not."
    scale = max(np.abs(off_ref).max(), 1e-300)
    for factor, hint in ((1, None), (2, "twice too large (the ½)"), (0.5, "half too small (one of the two opposite angles missing)"),
                         (-1, "of the wrong sign (they are -½ (cot a + cot b) ≤ 0 for acute angles)")):
        if np.abs(off - factor * off_ref).max() <= 1e-8 * scale:
            if hint is not None:
                return f"The off-diagonal entries are {hint}."
            if np.abs(d).max() <= 1e-12 * scale:
                return "The diagonal is missing: each row of W sums to zero, so W_ii = -Σ_j W_ij."
            if np.abs(d + d_ref).max() <= 1e-8 * scale:
                return "The diagonal has the wrong sign: W_ii = -Σ_{j≠i} W_ij, which is positive."
            return "The off-diagonal entries are right but the diagonal is not: each row of W sums to zero."
    if np.abs(m.sum(axis=1)).max() > 1e-8 * np.abs(ref).max():
        return "The rows of W should sum to zero (constants have no energy); yours do not."
    return ("Not the cotangent weights: edge ij uses the angles *opposite* it (at the third corner of each of its "
            "triangles), cot = cos/sin. Try your function on the worked triangle first.")


def check_stiffness(stiffness: Any, *, show: bool = True) -> Feedback:
    """Exercise 02-stiffness: the student's ``stiffness(mesh)`` against ``operators.stiffness_matrix``.

    Run on three small meshes (a right triangle, an irregular closed surface, an open sheet with
    obtuse triangles); the hint names the first thing that differs.

    Examples
    --------
    >>> from lbo_notebooks import operators
    >>> check_stiffness(operators.stiffness_matrix, show=False).correct
    True
    >>> print(check_stiffness(lambda mesh: 2 * operators.stiffness_matrix(mesh), show=False).message)
    Twice too large: W_ij = -½ (cot a + cot b); did you drop the ½, or add each triangle twice? (first seen on the right triangle.)
    """
    from .operators import stiffness_matrix

    def body() -> str:
        for mesh in _test_meshes():
            m = _matrix(_call(stiffness, mesh), mesh.n_vertices, "W")
            hint = _diagnose_stiffness(m, stiffness_matrix(mesh).toarray())
            if hint is not None:
                where = "the right triangle" if mesh.n_faces == 1 else f"a mesh of {mesh.n_vertices} vertices"
                raise _Stop(WRONG, f"{hint} (first seen on {where}.)")
        return "Right: it matches `operators.stiffness_matrix` on a triangle, a closed surface and an open sheet."
    return _run("02-stiffness", show, body)


def _pure_voronoi(mesh: Any) -> np.ndarray:
    """Circumcentric Voronoi areas without the mixed rule for obtuse triangles (a typical attempt)."""
    from .operators import face_cotangents

    v, f = mesh.vertices, mesh.faces
    cot = face_cotangents(mesh)
    sq = np.stack([np.sum((v[f[:, (k + 1) % 3]] - v[f[:, (k + 2) % 3]]) ** 2, axis=1) for k in range(3)], axis=1)
    corner = np.stack([(sq[:, (k + 2) % 3] * cot[:, (k + 2) % 3] + sq[:, (k + 1) % 3] * cot[:, (k + 1) % 3]) / 8
                       for k in range(3)], axis=1)
    return np.bincount(f.ravel(), weights=corner.ravel(), minlength=mesh.n_vertices)


def check_mass(mass: Any, *, show: bool = True) -> Feedback:
    """Exercise 02-mass: the student's lumped ``mass(mesh)`` against the Voronoi or barycentric mass.

    Either lumped mass is accepted (the message says which one was built).

    Examples
    --------
    >>> from lbo_notebooks import operators
    >>> check_mass(lambda mesh: operators.mass_matrix(mesh, "barycentric"), show=False).correct
    True
    >>> import numpy as np
    >>> "Euclidean" in check_mass(lambda mesh: np.eye(mesh.n_vertices), show=False).message
    True
    """
    from .operators import mass_matrix

    def body() -> str:
        matches = {"voronoi": True, "barycentric": True}
        for mesh in _test_meshes():
            n = mesh.n_vertices
            m = _matrix(_call(mass, mesh), n, "A")
            for kind in matches:
                matches[kind] &= _same(m, mass_matrix(mesh, kind).toarray())
            if any(matches.values()):
                continue
            where = "the right triangle" if mesh.n_faces == 1 else f"a mesh of {n} vertices"
            if np.allclose(m, np.eye(n)):
                raise _Stop(WRONG, "That is the identity, the Euclidean inner product: it weighs every vertex alike, whatever the size of its triangles. A weighs each vertex by its share of the area.")
            if _same(m, mass_matrix(mesh, "consistent").toarray()):
                raise _Stop(WRONG, "That is the consistent (full) mass matrix, a valid one, but the exercise asks for a lumped (diagonal) one: give each vertex its share of area on the diagonal.")
            d = np.diag(m)
            if np.abs(m - np.diag(d)).max() > 1e-12 * np.abs(d).max():
                raise _Stop(WRONG, f"A lumped mass matrix is diagonal; yours has off-diagonal entries (on {where}).")
            if (d < 0).any():
                raise _Stop(WRONG, "Negative areas: a triangle's area is ½ ‖(p1 - p0) × (p2 - p0)‖, a norm, never negative.")
            for kind in ("barycentric", "voronoi"):
                ref = mass_matrix(mesh, kind).diagonal()
                for factor, hint in ((2, "Twice too large: a triangle's area is *half* the norm of the cross product."),
                                     (3, "Three times too large: each triangle's area is shared among its three corners."),
                                     (6, "Six times too large: a triangle's area is half the norm of the cross product, and it is shared among three corners."),
                                     (0.5, "Half too small: a triangle's area is ½ ‖(p1 - p0) × (p2 - p0)‖ (only one ½)."),
                                     (1 / 3, "Three times too small: every corner of a triangle gets a share, not only one.")):
                    if _same(d, factor * ref):
                        raise _Stop(WRONG, hint)
            if _same(d, _pure_voronoi(mesh)):
                raise _Stop(WRONG, f"That is the pure Voronoi area, wrong at obtuse triangles (on {where}): use the mixed rule (half the triangle's area to an obtuse corner, a quarter to the others).")
            ratio = d.sum() / mesh.area
            raise _Stop(WRONG, f"The diagonal should share out the surface area; on {where} it sums to {ratio:.3g} × the area." if not _near(ratio, 1, 1e-8)
                        else f"The total is right but the shares are not (on {where}): a third of each triangle to each corner (barycentric), or the mixed Voronoi rule.")
        which = "mixed Voronoi" if matches["voronoi"] else "barycentric"
        return f"Right: that is the {which} mass matrix (both lumped masses are accepted; the library's default is mixed Voronoi)."
    return _run("02-mass", show, body)


def check_convergence_factor(factor: Any, *, show: bool = True) -> Feedback:
    """Exercise 02-convergence: by what factor does an O(h²) error drop when h is halved?"""
    def body() -> str:
        _attempt(factor)
        got = _number(factor)
        if _near(got, 4.0, 0.1):
            return "Right: error ∝ h², so halving h divides it by 2² = 4."
        if _near(got, 2.0, 0.1):
            raise _Stop(WRONG, "That is first order, error ∝ h; this discretisation is second order, error ∝ h².")
        if _near(got, 0.25, 0.1) or _near(got, 0.5, 0.1):
            raise _Stop(WRONG, "Give the factor by which the error *drops* (a number above 1): error_before / error_after.")
        if _near(got, 8.0, 0.1) or _near(got, 16.0, 0.1):
            raise _Stop(WRONG, "That would be a higher order than h²: error ∝ h^p drops by 2^p when h halves, with p = 2 here.")
        raise _Stop(WRONG, "If error ≈ C h^p and h becomes h/2, by what factor does the error change? Here p = 2.")
    return _run("02-convergence", show, body)


def check_coefficients(coefficients: Any, spectrum: Any, f: Any, *, show: bool = True) -> Feedback:
    """Exercise 02-coefficients: the coefficients of ``f`` in the eigenbasis, written by hand.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(2), 9)
    >>> f = shapes.icosphere(2).vertices[:, 2]
    >>> check_coefficients(s.vectors.T @ (s.mass @ f), s, f, show=False).correct
    True
    >>> "Euclidean" in check_coefficients(s.vectors.T @ f, s, f, show=False).message
    True
    """
    def body() -> str:
        _attempt(coefficients)
        phi, mass = spectrum.vectors, spectrum.mass
        g = np.asarray(f, dtype=np.float64)
        ref = spectrum.project(g)
        try:
            c = np.asarray(coefficients, dtype=np.float64)
        except (TypeError, ValueError):
            raise _Stop(WRONG, f"Expected an array of coefficients, got {type(coefficients).__name__}.") from None
        if c.shape != ref.shape:
            if c.shape == g.shape:
                raise _Stop(WRONG, f"One coefficient per eigenfunction: the result has length k = {ref.shape[0]}, not one value per vertex. A transpose (Φ instead of Φᵀ) or a reconstruction Φ c instead of c?")
            raise _Stop(WRONG, f"Expected shape {ref.shape} (one coefficient per eigenfunction), got {c.shape}.")
        scale = max(np.abs(ref).max(), 1e-300)
        near = lambda other: np.abs(c - other).max() <= 1e-6 * scale  # noqa: E731
        if near(ref):
            return "Right: c = Φᵀ A f, the A inner product of f with each eigenfunction."
        if near(phi.T @ g):
            raise _Stop(WRONG, "That is Φᵀ f, the Euclidean inner product: the eigenvectors are A-orthonormal, so the coefficients need the mass matrix.")
        if near(-ref):
            raise _Stop(WRONG, "Wrong sign.")
        if near(2 * ref) or near(ref / 2):
            raise _Stop(WRONG, "Off by a factor of two.")
        if near(phi.T @ (g / mass.diagonal())):
            raise _Stop(WRONG, "You divided by the mass; the A inner product multiplies by it.")
        raise _Stop(WRONG, "Not Φᵀ A f: take the A inner product ⟨φ_i, f⟩_A = φ_iᵀ A f for each eigenfunction φ_i.")
    return _run("02-coefficients", show, body)


def check_consistent_mass(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 02-consistent: do the consistent-mass eigenvalues of the sphere lie above or below ℓ(ℓ+1)?"""
    return _choice("02-consistent", answer, {
        "above": None,
        "below": "Look at the computed values again: the lumped ones are below, the consistent ones are not.",
        "equal": "Neither discretisation is exact on a sphere made of flat triangles.",
    }, show)


def check_eigenvalue_scaling(factor: Any, scale: float = 2.0, *, show: bool = True) -> Feedback:
    """Exercise 02-scaling: the factor by which every eigenvalue changes when the shape is scaled by ``scale``."""
    def body() -> str:
        _attempt(factor)
        got = _number(factor)
        if _near(got, scale**-2, 1e-3):
            return "Right: λ has units of 1/length², so scaling lengths by s divides every eigenvalue by s²."
        if _near(got, scale**2, 1e-3):
            raise _Stop(WRONG, "Upside down: a bigger shape vibrates more slowly, so its eigenvalues get smaller.")
        if _near(got, 1 / scale, 1e-3) or _near(got, scale, 1e-3):
            raise _Stop(WRONG, "λ has units of 1/length² (think of π²/a² on an interval of length a), not 1/length.")
        if _near(got, 1.0, 1e-3):
            raise _Stop(WRONG, "Scaling is not an isometry: lengths change, and so does the spectrum.")
        raise _Stop(WRONG, "What are the units of λ in W φ = λ A φ? (W is unitless on a surface; A is an area.)")
    return _run("02-scaling", show, body)


def check_zero_eigenvalues(torus: Any, two_spheres: Any, *, show: bool = True) -> Feedback:
    """Exercise 02-kernel: the number of zero eigenvalues of a torus and of two disjoint spheres."""
    def body() -> str:
        _attempt([torus, two_spheres])
        t, s = _number(torus, "a whole number"), _number(two_spheres, "a whole number")
        if (t, s) == (1, 2):
            return "Right: one zero eigenvalue per connected component (a constant on each); the genus does not matter."
        if t != 1:
            raise _Stop(WRONG, "The torus: the handle does not matter, only how many pieces the surface has; a zero eigenvalue means zero energy, a function constant on each piece.")
        raise _Stop(WRONG, "Two disjoint spheres: a function constant on each sphere separately has zero energy too.")
    return _run("02-kernel", show, body)


# --- 03 · your own data --------------------------------------------------------------------------

_REPAIR_PARTS = ("polygons_split", "vertices_welded", "degenerate_faces", "duplicate_faces",
                 "unreferenced_vertices", "non_manifold_edges", "n_components")
_REPAIR_HINTS: dict[str, Callable[[int, int], str | None]] = {
    "polygons_split": lambda got, true: "Only faces with more than three corners are split: how many quads did we write?",
    "vertices_welded": lambda got, true: ("Welding merges vertices with exactly the same coordinates: we wrote one exact copy of a vertex."
                                          if got == 0 else "Only exact copies are welded; noisy neighbours are different vertices."),
    "degenerate_faces": lambda got, true: ("A face whose three corners lie on one line has zero area too, like a face with a repeated corner."
                                           if got == true - 1 else "Count the zero-area faces: those with a repeated corner, and the flat (collinear) one."),
    "duplicate_faces": lambda got, true: ("One copy of each duplicated face is kept: count the faces removed, not the faces involved."
                                          if got == 2 * true else "A face written again with its corners reversed has the same three vertices: it is a duplicate."),
    "unreferenced_vertices": lambda got, true: (
        "Not only the vertices no face ever used: a vertex is also orphaned when every face that used it is "
        "removed or was never written (think of the flat face's corners, and of what the holes cut out)."
        if got < true else "Welded copies are counted as welded, not as unreferenced; count the vertices no face uses after the repair."),
    "non_manifold_edges": lambda got, true: ("Each fin has three edges, but only the one it shares with the sphere has three faces; "
                                             "its two other edges have one face each (a boundary)." if got == 3 * true
                                             else "An edge is non-manifold when more than two faces share it: where do the fins meet the sphere?"),
    "n_components": lambda got, true: ("The fins hang from edges of the sphere: they are part of its piece." if got > true
                                       else "Count every piece: the sphere (with its fins) and each flake of dust, the quad included."),
}


def check_repair_counts(prediction: Any, mesh: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-repair: predicted counts of what ``clean=True`` repairs, against ``clean_mesh``'s report.

    ``prediction`` is a dict with the keys ``polygons_split``, ``vertices_welded``, ``degenerate_faces``,
    ``duplicate_faces``, ``unreferenced_vertices``, ``non_manifold_edges`` and ``n_components``;
    ``mesh`` is what was written to the file (``(vertices, faces)``, faces may be polygons).

    Examples
    --------
    >>> v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [5, 5, 5]]
    >>> counts = dict(polygons_split=0, vertices_welded=0, degenerate_faces=0, duplicate_faces=1,
    ...               unreferenced_vertices=1, non_manifold_edges=0, n_components=1)
    >>> check_repair_counts(counts, (v, [[0, 1, 2], [1, 3, 2], [2, 1, 0]]), show=False).correct
    True
    """
    def body() -> str:
        _attempt(prediction)
        if not isinstance(prediction, Mapping):
            raise _Stop(WRONG, "Give a dict with one count per key: " + ", ".join(_REPAIR_PARTS) + ".")
        missing = [k for k in _REPAIR_PARTS if k not in prediction]
        if missing:
            raise _Stop(WRONG, "Some keys are missing: " + ", ".join(missing) + ".")
        from .repair import clean_mesh

        _, report = clean_mesh(mesh)
        wrong = []
        for key in _REPAIR_PARTS:
            got, true = _number(prediction[key], f"a whole number for {key}"), int(getattr(report, key))
            if got != true:
                wrong.append((key, int(got) if got == int(got) else got, true))
        if not wrong:
            return "Right: every count, including the vertices orphaned by the faces that were cut away or removed."
        key, got, true = wrong[0]
        others = f" ({len(wrong) - 1} other count{'s' if len(wrong) > 2 else ''} also off.)" if len(wrong) > 1 else ""
        raise _Stop(WRONG, f"{key}: {_REPAIR_HINTS[key](got, true)}{others}")
    return _run("03-repair", show, body)


def _operator_hint(name: str, mesh: Any, defects: list[str], answer: str) -> str:
    if answer == "robust":  # the mesh is fine for the cotangent Laplacian
        if mesh.n_components > 1:
            return (f"{name}: several pieces are no defect: the cotangent matrix is block-diagonal, one block "
                    "(and one zero eigenvalue) per piece.")
        if np.any(mesh.edge_face_counts == 1):
            return (f"{name}: a boundary (a hole) is no defect: an edge on it has one face, and its cotangent "
                    "weight then has one opposite angle instead of two.")
        return f"{name}: none of the defects `lbo.robust.cotan_defects` checks is there."
    text = " ".join(defects)
    if "non-manifold edge" in text:
        return (f"{name}: an edge shared by three faces has three opposite angles; the cotangent weight ½(cot a + cot b) "
                "is written for an edge between two triangles.")
    if "non-manifold vert" in text:
        return (f"{name}: every edge has at most two faces, but at one vertex the surface is pinched: two fans of "
                "triangles meet there at a single point, so around it the surface is not a disc.")
    return f"{name}: look at the smallest angles and the areas of its triangles: cotangents blow up near 0° and 180°."


def check_operator_choice(choice: Any, meshes: Mapping[str, Any], *, show: bool = True) -> Feedback:
    """Exercise 03-operator: which Laplacian ``eigenbasis(mesh, k)`` uses for each mesh, ``"cotan"`` or ``"robust"``.

    ``choice`` maps each name of ``meshes`` to ``"cotan"`` or ``"robust"``; the truth is whether
    :func:`lbo_notebooks.robust.cotan_defects` finds a defect.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> check_operator_choice({"ball": "cotan"}, {"ball": shapes.icosphere(1)}, show=False).correct
    True
    >>> check_operator_choice({"ball": ...}, {"ball": shapes.icosphere(1)}, show=False).status
    'not attempted'
    """
    def body() -> str:
        _attempt(choice)
        if not isinstance(choice, Mapping) or set(choice) != set(meshes):
            raise _Stop(WRONG, "Give a dict with one entry per mesh: " + ", ".join(f'"{k}"' for k in meshes) + ".")
        from .robust import cotan_defects

        for name, mesh in meshes.items():
            answer = choice[name]
            if not isinstance(answer, str) or answer.strip().lower() not in ("cotan", "robust"):
                raise _Stop(WRONG, f'{name}: answer "cotan" or "robust".')
            answer = answer.strip().lower()
            defects = cotan_defects(mesh)
            if answer != ("robust" if defects else "cotan"):
                raise _Stop(WRONG, _operator_hint(name, mesh, defects, answer))
        return ("Right: what makes `eigenbasis` leave the cotangent Laplacian is local (an edge with more than two faces, "
                "a pinched vertex, needle or zero-area triangles: what `lbo.robust.cotan_defects` checks); holes and "
                "separate pieces are no defects.")
    return _run("03-operator", show, body)


def _sphere_eigenvalue(k: int) -> float:
    ell = int(np.floor(np.sqrt(k)))  # indices l^2 .. l^2 + 2l belong to l (multiplicity 2l + 1)
    return float(ell * (ell + 1))


def check_cloud_eigenvalue(relative_error: Any, values: Any, k: int = 9, *, show: bool = True) -> Feedback:
    """Exercise 03-cloud: the signed relative error ``(λ_k - exact) / exact`` of eigenvalue ``k`` of the unit sphere.

    ``values`` are the computed eigenvalues (``values[0]`` the zero one); the exact value is
    ℓ(ℓ+1) for the ℓ with ℓ² ≤ k < (ℓ+1)².

    Examples
    --------
    >>> values = [0, 2, 2, 2, 6, 6, 6, 6, 6, 11.4]
    >>> check_cloud_eigenvalue(11.4 / 12 - 1, values, 9, show=False).correct
    True
    >>> "2ℓ+1" in check_cloud_eigenvalue(11.4 / 90 - 1, values, 9, show=False).message
    True
    """
    def body() -> str:
        _attempt(relative_error)
        got = _number(relative_error)
        lam, exact = float(np.asarray(values, dtype=np.float64)[k]), _sphere_eigenvalue(k)
        ref = lam / exact - 1
        near = lambda x: abs(got - x) <= 1e-3 * abs(ref) + 1e-12  # noqa: E731
        if near(ref):
            side = "below" if ref < 0 else "above"
            return f"Right: λ_{k} belongs to ℓ = {int(np.sqrt(k))}, and the cloud's value lies {side} ℓ(ℓ+1)."
        if near(-ref):
            raise _Stop(WRONG, "Wrong sign: (computed - exact) / exact is negative when the computed value is below the exact one.")
        if near(abs(ref)):
            raise _Stop(WRONG, "That is the size of the error; give it with its sign, (computed - exact) / exact.")
        if near(100 * ref):
            raise _Stop(WRONG, "That is a percentage; give the fraction.")
        if near(lam - exact):
            raise _Stop(WRONG, "That is the absolute error; divide by the exact value.")
        if near(exact / lam - 1):
            raise _Stop(WRONG, "Upside down: divide by the exact value, not by the computed one.")
        if any(near(lam / (j * (j + 1)) - 1) for j in range(1, 12) if j * (j + 1) != exact):
            which = next(j for j in range(1, 12) if j * (j + 1) != exact and near(lam / (j * (j + 1)) - 1))
            if which == k:
                raise _Stop(WRONG, f"The index k = {k} is not ℓ: the value ℓ(ℓ+1) is repeated 2ℓ+1 times "
                            "(once for ℓ = 0, three times for ℓ = 1, ...). Count which ℓ index k falls in.")
            raise _Stop(WRONG, "You compared with the wrong ℓ: ℓ(ℓ+1) is repeated 2ℓ+1 times, and index 0 is ℓ = 0. "
                        "Count again which ℓ this index falls in.")
        raise _Stop(WRONG, "Find ℓ for this index (ℓ(ℓ+1) is repeated 2ℓ+1 times, from index 0), then compute (computed - exact) / exact.")
    return _run("03-cloud", show, body)


def check_largest_component(n_zeros: Any, worst_error: Any, path: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-largest: zero eigenvalues of the scan's largest piece, and the worst relative error of the next 15.

    The check loads ``path`` with ``clean=True, keep_largest_component=True`` and compares
    eigenvalues 1 to 15 with ℓ(ℓ+1) of the unit sphere (the worst ``|λ/exact - 1|``, within 2%).
    """
    def body() -> str:
        _attempt([n_zeros, worst_error])
        zeros = _number(n_zeros, "a whole number of zero eigenvalues")
        worst = _number(worst_error, "the worst relative error (a number)")
        import warnings

        from .io import load_mesh
        from .spectrum import eigenbasis

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            values = eigenbasis(load_mesh(path, clean=True, keep_largest_component=True), 16).values
        exact = np.array([_sphere_eigenvalue(k) for k in range(16)])
        true_zeros = int(np.sum(np.abs(values) < 1e-8 * values[-1]))
        ref = float(np.max(np.abs(values[1:] / exact[1:] - 1)))
        if zeros != true_zeros:
            if zeros > true_zeros:
                raise _Stop(WRONG, "keep_largest_component=True drops the flakes: how many pieces are left, "
                            "and how many functions constant on each piece?")
            raise _Stop(WRONG, "A constant function still has zero energy: at least one eigenvalue is zero.")
        if _near(worst, ref, 0.02):
            return "Right: one piece, one zero eigenvalue, then the sphere's spectrum, a little off (noise, holes, fins, and the discretisation itself)."
        if _near(worst, 100 * ref, 0.02):
            raise _Stop(WRONG, "That is a percentage; give the fraction.")
        if worst > 10 * ref:
            raise _Stop(WRONG, "Much too large: with one piece the spectrum starts at index 0, so compare values[1:16] with "
                        "exact[1:16] (index for index), and leave out the zero eigenvalue.")
        raise _Stop(WRONG, "Take max |λ_k / ℓ(ℓ+1) - 1| over k = 1, ..., 15, with the eigenvalues of the largest piece.")
    return _run("03-largest", show, body)


def check_neighbors_effect(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-neighbors: with ``n_neighbors=10``, do the cloud's eigenvalues get "closer" to ℓ(ℓ+1) or "further"?"""
    return _choice("03-neighbors", answer, {
        "further": None,
        "closer": "Run the cell after the check and compare the worst relative errors for 10 and 30 neighbours.",
        "same": "The neighbourhoods change, and so does the operator: run it and compare the errors.",
    }, show)


def check_cloud_pieces(pieces: Any, n_neighbors: int = 30, *, show: bool = True) -> Feedback:
    """Exercise 03-gap: ``{radius: number of pieces}`` the point cloud of two concentric spheres shows.

    The inner sphere is ``shapes.icosphere(3)`` (radius 1), the outer the same points scaled by
    the radius; the pieces are the zero eigenvalues of the point-cloud Laplacian.

    Examples
    --------
    >>> check_cloud_pieces({2.5: 2}, show=False).correct
    True
    """
    def body() -> str:
        _attempt(pieces)
        if not isinstance(pieces, Mapping) or not pieces:
            raise _Stop(WRONG, "Give a dict {radius of the outer sphere: number of pieces}.")
        from . import shapes
        from .pointcloud import PointCloud
        from .spectrum import eigenbasis

        inner = shapes.icosphere(3).vertices
        for radius, got in sorted(pieces.items()):
            got = _number(got, f"a whole number for radius {radius}")
            if not float(radius) > 1:
                raise _Stop(WRONG, f"Radius {radius}: the outer sphere's radius is above 1.")
            values = eigenbasis(PointCloud(np.vstack([inner, float(radius) * inner])), 3, n_neighbors=n_neighbors).values
            true = int(np.sum(np.abs(values) < 1e-8 * values[-1]))
            if got == true:
                continue
            if got > true:
                raise _Stop(WRONG, f"Radius {radius}: a neighbourhood is the {n_neighbors} nearest points, however far they are. "
                            "The outer sphere's points are sparser, so their neighbourhoods reach further: can they reach the inner sphere?")
            raise _Stop(WRONG, f"Radius {radius}: the gap is wider than the outer points' neighbourhoods reach, so no patch joins the spheres.")
        return "Right: the spheres separate once the gap is wider than an outer point's neighbourhood reaches."
    return _run("03-gap", show, body)


# --- revealing a solution on purpose -------------------------------------------------------------

_REGION = re.compile(r"^[ \t]*(?:#+|<!--)\s*BEGIN SOLUTION.*?$\n(.*?)^[ \t]*(?:#+|<!--)\s*END SOLUTION.*?$",
                     re.MULTILINE | re.DOTALL)


def _instructor_notebooks() -> Path | None:
    here = Path(__file__).resolve().parent.parent / "notebooks"
    return here if here.is_dir() else None


def solution(exercise: str, *, show: bool = True) -> str:
    """The instructor's solution of one exercise, on purpose: try first, then look.

    Reads the solution regions (``### BEGIN SOLUTION`` ... ``### END SOLUTION``) of the cells with
    the grade id ``<exercise>-answer`` (and ``<exercise>-explain``) in the instructor edition,
    ``notebooks/`` of the checkout the package is installed from. The student edition has no
    solutions in it; where no checkout is at hand (a handed-out edition), this says so.

    Parameters
    ----------
    exercise : str
        The exercise id shown by its check, e.g. ``"02-mass"``.
    show : bool
        Display the solution (as Markdown in Jupyter, as text elsewhere).

    Returns
    -------
    str
        The solution's text.

    Examples
    --------
    >>> "BEGIN SOLUTION" not in solution("02-scaling", show=False)
    True
    """
    folder = _instructor_notebooks()
    if folder is None:
        text = "The solutions are not part of this edition (no instructor notebooks found next to the package)."
    else:
        number = exercise.split("-", 1)[0]
        pieces = []
        for path in sorted(folder.glob(f"{number}_*.ipynb")):
            for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
                grade_id = cell.get("metadata", {}).get("nbgrader", {}).get("grade_id", "")
                if grade_id in (f"{exercise}-answer", f"{exercise}-explain"):
                    source = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
                    for region in _REGION.findall(source):
                        pieces.append(f"```python\n{region.rstrip()}\n```" if cell["cell_type"] == "code" else region.strip())
        text = "\n\n".join(pieces) if pieces else f"No solution found for exercise {exercise!r}."
    if show:
        shell = _shell()
        if shell is None:
            print(text)
        else:
            from IPython.display import Markdown, display

            display(Markdown(f"**Solution of exercise {exercise}**\n\n{text}"))
    return text


# --- notebooks 04-06 ---
# 04 · the optimality theorem, 05 · the min-max principle, 06 · scale-invariant metrics.

__all__ += [
    "check_projection", "check_energy_bound", "check_shifted_basis", "check_consistent_optimality",
    "check_extra_function", "check_worst_ratio", "check_recap_04",
    "check_plane_minimum", "check_plane_range", "check_lowest_family", "check_dual_value", "check_interlacing",
    "check_consistent_minmax", "check_recap_05",
    "check_gauss_bonnet", "check_curvature_scaling", "check_metric_scaling", "check_best_alpha",
    "check_floor_fraction", "check_sphere_alpha", "check_consistent_invariance", "check_recap_06",
]


def _theory_pick(options: Mapping[str, str | None]) -> Callable[[Any], str | None]:
    """A judge for one choice question: the hint of a wrong choice, None for the right one."""
    def judge(answer: Any) -> str | None:
        key = str(answer).strip().lower() if isinstance(answer, (str, int, float)) else None
        if key not in options:
            return "answer with one of: " + ", ".join(f'"{o}"' for o in options) + "."
        return options[key]
    return judge


def _theory_number(target: float, near: list[tuple[float, str]], otherwise: str, rtol: float = 1e-3) -> Callable[[Any], str | None]:
    """A judge for one number question: None if ``target`` (relative ``rtol``), else the hint of the nearest slip."""
    def judge(answer: Any) -> str | None:
        try:
            value = _number(answer)
        except _Stop as stop:
            return stop.message
        if _near(value, target, rtol):
            return None
        return next((hint for slip, hint in near if _near(value, slip, rtol)), otherwise)
    return judge


def _theory_recap(exercise: str, answers: list[Any], judges: list[Callable[[Any], str | None]], show: bool) -> Feedback:
    """A recap of several questions in one check: correct when all are, else the hints of the wrong ones."""
    def body() -> str:
        _attempt(answers)
        wrong = [f"Question {k}: {hint}" for k, (answer, judge) in enumerate(zip(answers, judges), 1)
                 if (hint := judge(answer)) is not None]
        if wrong:
            raise _Stop(WRONG, f"{len(answers) - len(wrong)} of {len(answers)} right. " + " ".join(wrong))
        return f"Right, all {len(answers)}."
    return _run(exercise, show, body)


def _theory_ratio_one(exercise: str, value: Any, below: str, above: str, show: bool, rtol: float = 1e-6) -> Feedback:
    """A normalised constant that must come out as exactly 1 (to ``rtol``): hints for below and above."""
    def body() -> str:
        _attempt(value)
        got = _number(value)
        if abs(got - 1) <= rtol:
            return "Right: exactly 1, to round-off: each eigenbasis is optimal for its own pair (W, A)."
        if 0 < got < 0.1:
            raise _Stop(WRONG, "Normalise: multiply by λ_n (`values[n]`, n the number of basis functions or constraints), so that the optimum reads 1.")
        raise _Stop(WRONG, below if got < 1 else above)
    return _run(exercise, show, body)


def _vector(x: Any, what: str) -> np.ndarray:
    try:
        value = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError):
        raise _Stop(WRONG, f"Expected {what}, got {type(x).__name__}.") from None
    if value.ndim != 1 or not np.all(np.isfinite(value)):
        raise _Stop(WRONG, f"Expected {what} (a finite 1-D array), got shape {value.shape}.")
    return value


# --- 04 · the optimality theorem -------------------------------------------------------------------

def check_projection(project: Any, spectrum: Any, *, show: bool = True) -> Feedback:
    """Exercise 04-projection: the student's ``project(spectrum, f, n)``, the A-orthogonal projection P_n f.

    Tried with two functions and two values of n against ``Φ_n Φ_nᵀ A f``; the hint names the slip
    (Euclidean inner product, coefficients instead of the projection, wrong n, a transpose, ...).

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(2), 12)
    >>> check_projection(lambda s, f, n: s.reconstruct(f, n), s, show=False).correct
    True
    >>> "Euclidean" in check_projection(lambda s, f, n: s.vectors[:, :n] @ (s.vectors[:, :n].T @ f), s, show=False).message
    True
    """
    def body() -> str:
        phi, mass = np.asarray(spectrum.vectors), spectrum.mass
        n_vertices, k = phi.shape
        rng = np.random.default_rng(0)
        for n in (min(7, k - 2), min(4, k - 2)):
            f = rng.normal(size=n_vertices) + phi[:, : k // 2] @ rng.normal(size=k // 2)
            try:
                p = _call(project, spectrum, f, n)
            except _Stop as stop:
                if stop.status == WRONG and re.search(r"shape|mismatch|align|dimension", stop.message):
                    raise _Stop(WRONG, stop.message + " Check the transposes: Φ_n = `vectors[:, :n]` is (vertices × n), "
                                "the coefficients are Φ_nᵀ (A f), one per eigenfunction, and the projection Φ_n times them.") from None
                raise
            try:
                p = np.asarray(p, dtype=np.float64)
            except (TypeError, ValueError):
                raise _Stop(WRONG, f"Return an array (one value per vertex), got {type(p).__name__}.") from None
            Af = mass @ f
            c = phi[:, :n].T @ Af
            ref = phi[:, :n] @ c
            scale = max(np.linalg.norm(ref), 1e-300)

            def near(other: np.ndarray) -> bool:
                return p.shape == other.shape and np.linalg.norm(p - other) <= 1e-8 * max(scale, np.linalg.norm(other))
            if p.shape == (n,):
                if near(c):
                    raise _Stop(WRONG, "Those are the n coefficients c = Φ_nᵀ A f; the projection is the function they describe, Φ_n c (one value per vertex).")
                if near(phi[:, :n].T @ f):
                    raise _Stop(WRONG, "Those are coefficients, and with the Euclidean inner product Φ_nᵀ f: return the projection Φ_n c, with c = Φ_nᵀ A f.")
            if p.shape != (n_vertices,):
                raise _Stop(WRONG, f"Return one value per vertex, shape ({n_vertices},); got shape {p.shape}.")
            if near(ref):
                continue
            if near(phi[:, :n] @ (phi[:, :n].T @ f)):
                raise _Stop(WRONG, "That is Φ_n Φ_nᵀ f, the Euclidean inner product: the eigenvectors are A-orthonormal, so the coefficients are Φ_nᵀ A f.")
            if near(phi[:, :n] @ (phi[:, :n].T @ (f / mass.diagonal()))):
                raise _Stop(WRONG, "You divided by the vertex areas; the A inner product multiplies by them (`spectrum.mass @ f`).")
            if near(mass @ (phi[:, :n] @ (phi[:, :n].T @ f))):
                raise _Stop(WRONG, "The mass matrix is in the wrong place: A multiplies f inside the coefficients, Φ_nᵀ (A f), not the result.")
            for m, hint in ((n + 1, "one eigenfunction too many"), (n - 1, "one eigenfunction too few")):
                if near(phi[:, :m] @ (phi[:, :m].T @ Af)):
                    raise _Stop(WRONG, f"Off by one ({hint}): the first n eigenfunctions are φ_0 .. φ_(n-1), `vectors[:, :n]`.")
            if near(phi[:, 1:n + 1] @ (phi[:, 1:n + 1].T @ Af)) or near(phi[:, 1:n] @ (phi[:, 1:n].T @ Af)):
                raise _Stop(WRONG, "You left out φ_0, the constant: it is the first of the n eigenfunctions (indices from 0).")
            if near(phi @ (phi.T @ Af)):
                raise _Stop(WRONG, "You used every eigenfunction the spectrum has; use only the first n.")
            if near(f - ref):
                raise _Stop(WRONG, "That is the error f − P_n f; return the projection P_n f itself.")
            raise _Stop(WRONG, f"Not the A-orthogonal projection (first seen with n = {n}): coefficients c = Φ_nᵀ A f, then Φ_n c.")
        return "Right: P_n f = Φ_n Φ_nᵀ A f, and its error f − P_n f is A-orthogonal to φ_0 .. φ_(n-1)."
    return _run("04-projection", show, body)


def check_energy_bound(value: Any, spectrum: Any, f: Any, n: int, *, show: bool = True) -> Feedback:
    """Exercise 04-bound: the theorem's bound f^T W f / λ_n for ``f`` after ``n`` terms (0-based λ)."""
    def body() -> str:
        _attempt(value)
        got = _number(value)
        g = np.asarray(f, dtype=np.float64)
        lam = np.asarray(spectrum.values)
        energy, norm2 = float(g @ (spectrum.stiffness @ g)), float(g @ (spectrum.mass @ g))
        ref = energy / lam[n]
        if _near(got, ref, 1e-6):
            return "Right: the energy fᵀ W f over λ_n = `values[n]`, the first eigenvalue whose eigenfunction is left out."
        for slip, hint in (
            (energy / lam[n - 1], "Off by one: after n terms φ_0 .. φ_(n-1) are used, and the bound divides by the first one left out, λ_n = `values[n]`."),
            (energy / lam[n + 1], "Off by one the other way: indices start at 0, so the eigenvalue after n terms is `values[n]`."),
            (energy, "That is the energy fᵀ W f; the bound divides it by λ_n."),
            (energy * lam[n], "Divide the energy by λ_n, do not multiply."),
            (norm2 / lam[n], "fᵀ A f is the squared norm, not the energy: the bound uses the Dirichlet energy fᵀ W f (the stiffness)."),
            (ref / norm2, "That is the bound relative to ‖f‖²_A; give the bound itself."),
            (np.sqrt(ref), "That is the square root: the bound is on the *squared* error."),
        ):
            if _near(got, slip, 1e-6):
                raise _Stop(WRONG, hint)
        raise _Stop(WRONG, "The bound is fᵀ W f / λ_n: the Dirichlet energy (W = `spectrum.stiffness`) over `values[n]`.")
    return _run("04-bound", show, body)


def check_shifted_basis(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 04-shifted: C(V) λ_n for V = span(φ_1 .. φ_n), the eigenbasis without the constant."""
    return _choice("04-shifted", answer, {
        "below": "Nothing is below 1: the theorem holds for every n-dimensional V.",
        "one": "Equality needs the *right* n functions. Which function of zero energy is missing from V, and what is its error?",
        "above": "Think of the worst function: one of zero energy that V cannot represent at all. What is error / energy for it?",
        "infinite": None,
    }, show)


def check_consistent_optimality(value: Any, *, show: bool = True) -> Feedback:
    """Exercise 04-consistent: C(V) λ_n of the consistent-mass eigenbasis for its own (W, A): exactly 1."""
    return _theory_ratio_one(
        "04-consistent", value,
        "Below 1 is impossible (the theorem): is λ_n `values[n]`, with n the number of basis functions?",
        "The eigenbasis is optimal for the pair it solves: pass the consistent spectrum's own `stiffness` and `mass` "
        "to `worst_case_ratio`, and multiply by its `values[n]`.", show)


def check_extra_function(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 04-extra: where V = span(Φ_n, g) sits, between Φ_n and Φ_(n+1)."""
    return _choice("04-extra", answer, {
        "beats": "V has n + 1 functions: the theorem for n + 1 says no (n + 1)-dimensional space beats Φ_(n+1).",
        "between": None,
        "worse": "V contains span Φ_n: projecting onto a larger space never increases the error.",
    }, show)


def check_worst_ratio(ratio: Any, basis: Any, stiffness: Any, mass: Any, *, show: bool = True) -> Feedback:
    """Exercise 04-worst: the error / energy of the worst function of ``basis``, which must equal C(V)."""
    from .optimality import worst_case_ratio

    def body() -> str:
        _attempt(ratio)
        got = _number(ratio)
        c, worst = worst_case_ratio(basis, stiffness, mass, return_vector=True)
        Q = np.asarray(basis)
        energy = float(worst @ (stiffness @ worst))

        def a_norm2(x: np.ndarray) -> float:
            return float(x @ (mass @ x))
        if _near(got, c, 1e-6):
            return "Right: the worst function attains the supremum, error / energy = C(V)."
        for slip, hint in (
            (a_norm2(worst - Q @ (Q.T @ worst)) / energy, "The projection needs the A inner product: P_V f = Q Qᵀ A f."),
            (a_norm2(worst) / energy, "That is ‖f‖²_A / energy: the error is of f − P_V f, what the basis misses."),
            (1 / c, "Upside down: error over energy."),
        ):
            if _near(got, slip, 1e-6):
                raise _Stop(WRONG, hint)
        if got > c:
            raise _Stop(WRONG, "Above C(V), which is a supremum: check the error ‖f − P_V f‖²_A (A-norm) and the energy fᵀ W f.")
        raise _Stop(WRONG, "Below C(V): use the function `worst_case_ratio(..., return_vector=True)` returns, and the A-norm of f − P_V f.")
    return _run("04-worst", show, body)


def check_recap_04(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 04: (1) which `values[...]` after 10 terms, (2) the bound for white noise, (3) ties."""
    return _theory_recap("04-recap", [q1, q2, q3], [
        _theory_number(10, [(9, "after 10 terms φ_0 .. φ_9 are used; the bound divides by the first one left out."),
                            (11, "indices start at 0: count again which eigenvalue is the first one left out.")],
                       "the first eigenvalue whose eigenfunction is left out, in 0-based indexing."),
        _theory_pick({"tight": "noise has a huge Dirichlet energy; compare the bound with ‖f‖²_A itself.",
                      "vacuous": None,
                      "violated": "the bound holds for every function, smooth or not."}),
        _theory_pick({"yes": "section 5 found ties that are not eigenspaces (tilted eigenbases, polynomials on the icosphere).",
                      "no": None}),
    ], show)


# --- 05 · the min-max principle -------------------------------------------------------------------

def _compressed(M: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Eigenvalues of M restricted to the plane orthogonal to ``normal`` (ascending)."""
    u = normal / np.linalg.norm(normal)
    basis = np.linalg.svd(np.eye(3) - np.outer(u, u))[0][:, :2]
    return np.linalg.eigvalsh(basis.T @ M @ basis)


def check_plane_minimum(value: Any, M: Any, normal: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-plane: the minimum of R(x) = xᵀ M x / xᵀ x on the plane orthogonal to ``normal``.

    Examples
    --------
    >>> import numpy as np
    >>> M = np.diag([1.0, 2.5, 4.0]); u = np.array([1.0, 2.0, 0.0])
    >>> check_plane_minimum(1.3, M, u, show=False).correct
    True
    >>> "optimal plane" in check_plane_minimum(2.5, M, u, show=False).message
    True
    """
    def body() -> str:
        _attempt(value)
        got = _number(value)
        M_, u = np.asarray(M, dtype=np.float64), np.asarray(normal, dtype=np.float64)
        low, high = _compressed(M_, u)
        lam = np.linalg.eigvalsh(M_)
        if _near(got, low, 1e-6):
            return "Right: the smaller eigenvalue of M restricted to the plane; below λ_1, as every plane but the optimal ones."
        for slip, hint in (
            (lam[1], "That is λ_1, the value of the optimal plane (normal v_0); this normal is not v_0."),
            (float(u @ M_ @ u / (u @ u)), "That is R at the normal, which is not in the plane: minimise over the vectors orthogonal to u."),
            (high, "That is the maximum on the plane; the question asks for the minimum."),
            (lam[0], "λ_0 needs v_0 in the plane, i.e. the normal orthogonal to v_0: is it?"),
        ):
            if _near(got, slip, 1e-6):
                raise _Stop(WRONG, hint)
        raise _Stop(WRONG, "Write the plane as two orthonormal vectors orthogonal to u (columns of B); the minimum is the smaller eigenvalue of the 2×2 matrix Bᵀ M B.")
    return _run("05-plane", show, body)


def check_plane_range(answer: Any, M: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-range: the interval of min-over-a-plane values, (lowest, highest), over all planes."""
    def body() -> str:
        _attempt(answer)
        if not isinstance(answer, (list, tuple)) or len(answer) != 2:
            raise _Stop(WRONG, "Give a pair (lowest, highest).")
        low, high = (_number(a) for a in answer)
        lam = np.linalg.eigvalsh(np.asarray(M, dtype=np.float64))
        if low > high:
            raise _Stop(WRONG, "Give the lowest value first.")
        if _near(low, lam[0], 1e-6) and _near(high, lam[1], 1e-6):
            return "Right: a plane containing v_0 gives λ_0; no plane gives more than λ_1, which the plane orthogonal to v_0 reaches."
        if _near(low, lam[0], 1e-6) and _near(high, lam[2], 1e-6):
            raise _Stop(WRONG, "That is the range of R itself on the sphere. The *minimum* on a plane is lower: every plane meets span(v_0, v_1) in a line.")
        if not _near(low, lam[0], 1e-6):
            raise _Stop(WRONG, "The lowest: can a plane contain v_0? What is the minimum on it then?")
        raise _Stop(WRONG, "The highest: every plane meets span(v_0, v_1) in a line (two planes through 0 in 3-D always do); what is R there at most?")
    return _run("05-range", show, body)


def check_lowest_family(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-family: which family of random constraints leaves the lowest minima."""
    return _choice("05-family", answer, {
        "white": None,
        "smooth": "Smooth constraints remove smooth, low-energy functions. What do rough constraints remove?",
        "near-optimal": "Constraints near φ_0 .. φ_(n-1) are nearly the optimal ones of Courant–Fischer: they come closest to λ_n.",
    }, show)


def check_dual_value(value: Any, M: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-dual: the exact min over planes of the max of R on the plane (for the 3×3 M)."""
    def body() -> str:
        _attempt(value)
        got = _number(value)
        lam = np.linalg.eigvalsh(np.asarray(M, dtype=np.float64))
        if _near(got, lam[1], 1e-6):
            return "Right: λ_1 = min over planes of the max, reached by span(v_0, v_1): the dual (max-min ↔ min-max) form."
        if lam[1] < got <= lam[1] * 1.05:
            raise _Stop(WRONG, "Close: random planes approach it from above. Which plane reaches the exact value?")
        if _near(got, lam[2], 1e-6):
            raise _Stop(WRONG, "λ_2 is the largest maximum (planes containing v_2); the question asks for the smallest one.")
        if _near(got, lam[0], 1e-6):
            raise _Stop(WRONG, "A plane's maximum is at least R on the line where it meets span(v_1, v_2).")
        raise _Stop(WRONG, "The maximum on a plane is the larger eigenvalue of Bᵀ M B (B: two orthonormal vectors spanning it); minimise it over planes.")
    return _run("05-dual", show, body)


def check_interlacing(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-interlacing: the lower bound of the minimum over a codimension-2 subspace."""
    return _choice("05-interlacing", answer, {
        "lam_0": None,
        "lam_1": "Find a codimension-2 subspace that contains the constant function: what is its minimum?",
    }, show)


def check_consistent_minmax(value: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-consistent: min of R on the optimal subspace over λ_10, consistent mass: exactly 1."""
    return _theory_ratio_one(
        "05-consistent", value,
        "Below 1 on the optimal subspace: use the consistent spectrum throughout (its `stiffness`, `mass`, and `optimal_subspace(sc, 10)`), "
        "and divide by `sc.values[10]`.",
        "Above λ_n is impossible (Courant–Fischer): divide by `values[10]` for 10 constraints.", show)


def check_recap_05(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 05: (1) the Courant–Fischer bound, (2) uniqueness, (3) a critical angle in degrees."""
    t_star = float(np.degrees(np.arctan(np.sqrt(2.0))))
    return _theory_recap("05-recap", [q1, q2, q3], [
        _theory_pick({"lam_n-1": "the bound is the eigenvalue whose index is the codimension.",
                      "lam_n": None,
                      "lam_n+1": "the bound is the eigenvalue whose index is the codimension."}),
        _theory_pick({"yes": "section 2 tilted the optimal plane and found a whole arc of maximisers.", "no": None}),
        _theory_number(t_star, [(np.degrees(np.arctan(2.0)), "tan² t* is the ratio, not tan t*."),
                                (np.degrees(np.arctan(np.sqrt(0.5))), "the ratio is (λ_2 − λ_1)/(λ_1 − λ_0), upside down?"),
                                (np.arctan(np.sqrt(2.0)), "give degrees, not radians.")],
                       "tan² t* = (λ_2 − λ_1)/(λ_1 − λ_0); give t* in degrees."),
    ], show)


# --- 06 · scale-invariant metrics -----------------------------------------------------------------

def check_gauss_bonnet(torus: Any, disk: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-gauss-bonnet: Σ K_i a_i for a torus and a disk (2πχ)."""
    def body() -> str:
        _attempt([torus, disk])
        t, d = _number(torus), _number(disk)
        two_pi = 2 * np.pi
        tol = 1e-6 * two_pi
        if abs(t) <= tol and abs(d - two_pi) <= tol:
            return "Right: Σ K_i a_i = 2πχ, with χ = 0 for the torus and 1 for the disk."
        if abs(t) <= tol and _near(d, 1, 1e-6):
            raise _Stop(WRONG, "Those look like Euler characteristics: the total curvature is 2π times χ.")
        if abs(t) > tol:
            raise _Stop(WRONG, "The torus: count V − E + F of a square grid wrapped around both ways (each square is two triangles).")
        raise _Stop(WRONG, "The disk: χ = V − E + F of a flat triangulated disk (one triangle will do), times 2π.")
    return _run("06-gauss-bonnet", show, body)


def check_curvature_scaling(factor: Any, scale: float = 3.0, *, show: bool = True) -> Feedback:
    """Exercise 06-curvature: the factor by which Gaussian curvature changes when a shape is scaled by ``scale``."""
    def body() -> str:
        _attempt(factor)
        got = _number(factor)
        if _near(got, scale**-2, 1e-6):
            return "Right: K = 1/(R₁R₂), two lengths in the denominator; the angle defect is unchanged and the area grows by s²."
        if _near(got, 1 / scale, 1e-6):
            raise _Stop(WRONG, "K is a product of two principal curvatures, each 1/length: think of 1/R² on a sphere.")
        if _near(got, scale**2, 1e-6) or _near(got, scale, 1e-6):
            raise _Stop(WRONG, "Upside down: a bigger sphere is flatter.")
        if _near(got, 1.0, 1e-6):
            raise _Stop(WRONG, "The angle defect does not change, but K is the defect per unit area.")
        raise _Stop(WRONG, "K_i = δ_i / a_i: how do the angle defect δ_i and the vertex area a_i change?")
    return _run("06-curvature", show, body)


def check_metric_scaling(factors: Any, scale: float = 3.0, *, show: bool = True) -> Feedback:
    """Exercise 06-scaling: ``{alpha: factor}``, how the eigenvalues of |K|^alpha g change under scaling by ``scale``."""
    def body() -> str:
        _attempt(factors)
        if not isinstance(factors, Mapping) or not factors:
            raise _Stop(WRONG, "Give a dict {alpha: new eigenvalue / old eigenvalue}.")
        for alpha, got in factors.items():
            a, got = float(alpha), _number(got, f"a number for alpha = {alpha}")
            ref = scale ** (-2 * (1 - a))
            if _near(got, ref, 1e-6):
                continue
            if a != 1 and _near(got, 1 / ref, 1e-6):
                raise _Stop(WRONG, f"alpha = {alpha}: upside down. A_α grows, so the eigenvalues of W φ = λ A_α φ shrink.")
            if a != 1 and _near(got, scale ** -(1 - a), 1e-6):
                raise _Stop(WRONG, f"alpha = {alpha}: areas scale by s², not s.")
            if a != 0 and _near(got, scale**-2, 1e-6):
                raise _Stop(WRONG, f"alpha = {alpha}: that is the regular metric's factor; ρ shrinks by s⁻² too, and A_α holds ρ^α.")
            if a != 1 and _near(got, 1.0, 1e-6):
                raise _Stop(WRONG, f"alpha = {alpha}: only α = 1 cancels the area's s² completely.")
            raise _Stop(WRONG, f"alpha = {alpha}: W does not change; A_α = diag(ρ^α a) with a → s² a and ρ → s⁻² ρ.")
        return "Right: A_α grows by s^(2(1−α)), so λ scales by s^(−2(1−α)); α = 1 is exactly invariant."
    return _run("06-scaling", show, body)


def check_best_alpha(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-best: which α rebuilds the most curved 10% of the horse best (0, 0.4 or 1)."""
    options = {"0": "The regular basis spreads its functions evenly by area; the curved 10% has little area.",
               "0.4": "A compromise is rarely the best at one extreme: which metric gives the curved tips the most area?",
               "1": None}

    def body() -> str:
        _attempt(answer)
        try:
            key = f"{float(answer):g}"
        except (TypeError, ValueError):
            key = str(answer).strip()
        if key not in options:
            raise _Stop(WRONG, "Answer with one of: 0, 0.4, 1.")
        if options[key] is not None:
            raise _Stop(WRONG, options[key])
        return "Right: |K| g gives the curved tips most of its area, so its eigenbasis spends its functions there."
    return _run("06-best", show, body)


def check_floor_fraction(fraction: Any, mesh: Any, floor: float = 1.0, *, show: bool = True) -> Feedback:
    """Exercise 06-floor: the fraction of vertices at the curvature floor ``floor``."""
    from .curvature import metric_curvature

    def body() -> str:
        _attempt(fraction)
        got = _number(fraction)
        level = floor * 4 * np.pi / mesh.area
        ref = float(np.mean(metric_curvature(mesh, floor=floor) <= level * (1 + 1e-12)))
        if abs(got - ref) <= 1e-9:
            return "Right: that is the share of vertices whose one-ring |K| is below the floor."
        if abs(got - 100 * ref) <= 1e-7:
            raise _Stop(WRONG, "That is a percentage; give a fraction between 0 and 1.")
        if abs(got - (1 - ref)) <= 1e-9:
            raise _Stop(WRONG, "That is the fraction *above* the floor.")
        if got == 0 and ref > 0:
            raise _Stop(WRONG, "None at the floor? Compare with a tolerance (`np.isclose`, or `<=` the floor times 1 + 1e-12), not `==`: the floor is computed in floating point.")
        raise _Stop(WRONG, f"Compare `curvature.metric_curvature(mesh, floor={floor:g})` with the floor value {floor:g} · 4π / area (vertices at the floor equal it).")
    return _run("06-floor", show, body)


def check_sphere_alpha(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-sphere: how the α = 1 eigenvalues of the unit sphere compare with the regular ones."""
    return _choice("06-sphere", answer, {
        "equal": None,
        "scaled": "What is |K|^α on the unit sphere, and so what does g_α = |K|^α g become?",
        "unrelated": "What is |K|^α on the unit sphere, and so what does g_α = |K|^α g become?",
    }, show)


def check_consistent_invariance(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-consistent: is the consistent (per-triangle) α = 1 metric scale-invariant too?"""
    return _choice("06-consistent", answer, {
        "yes": None,
        "no": "Scaling by s: what happens to a triangle's area, to its ρ_t, and so to ρ_t × area?",
    }, show)


def check_recap_06(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 06: (1) K of a sphere of radius 2, (2) what α changes, (3) which spectrum is steadier under poses."""
    return _theory_recap("06-recap", [q1, q2, q3], [
        _theory_number(0.25, [(0.5, "K is 1/R², not 1/R."), (4.0, "upside down: a bigger sphere is flatter.")],
                       "K = 1/R² on a sphere of radius R."),
        _theory_pick({"w": "the Dirichlet energy is conformally invariant in 2-D: the cotangent weights do not change.",
                      "a": None,
                      "both": "the Dirichlet energy is conformally invariant in 2-D: one of the two does not change."}),
        _theory_pick({"regular": None,
                      "scale-invariant": "section 6 measured it: the poses stretch the joints a little and |K| amplifies it."}),
    ], show)


# --- notebooks 00, 08, 09 ---
# (Appended section: its checks are added to __all__ here, so that the list at the top stays untouched.)

__all__ += [
    "check_sphere_eigenvalues", "check_mesh_size", "check_eigenfunction", "check_load_error",
    "check_rpca_limits", "check_dirichlet_energies", "check_validation_choice", "check_mu_scaling",
    "check_rpca_objective", "check_recap_08",
    "check_hks", "check_functional_map", "check_truncation_bound", "check_alpha_choice", "check_mirror_maps",
    "check_zoomout", "check_recap_09",
]


def _array(value: Any, what: str, *, finite: bool = True) -> np.ndarray:
    """The student's answer as a float array (sparse matrices densified), or a 'wrong' stop."""
    import scipy.sparse as sp

    if sp.issparse(value):
        value = value.toarray()
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise _Stop(WRONG, f"Expected {what}, got {type(value).__name__}.") from None
    if finite and not np.all(np.isfinite(arr)):
        raise _Stop(WRONG, "Your answer has NaN or infinite entries.")
    return arr


def _recap(exercise: str, answers: list[Any], questions: list[Mapping[str, str | None]], show: bool) -> Feedback:
    """Several multiple-choice questions in one check, each ``{choice: hint or None}`` (None: the right
    one); the feedback gives the hints of the questions answered wrongly, never the right choice."""
    def body() -> str:
        _attempt(answers)
        hints = []
        for q, (given, options) in enumerate(zip(answers, questions), 1):
            if not isinstance(given, str) or given.strip().lower() not in options:
                hints.append(f"Question {q}: answer with one of " + ", ".join(f'"{o}"' for o in options) + ".")
            elif (hint := options[given.strip().lower()]) is not None:
                hints.append(f"Question {q}: {hint}")
        if hints:
            raise _Stop(WRONG, f"{len(answers) - len(hints)} of {len(answers)} right. " + " ".join(hints))
        return f"Right, all {len(answers)}."
    return _run(exercise, show, body)


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
        _attempt(values)
        got = _array(values, "a list of nine numbers")
        exact = np.repeat([l * (l + 1) for l in range(3)], [2 * l + 1 for l in range(3)]).astype(float)
        if got.shape != (9,):
            raise _Stop(WRONG, "Give nine numbers: λ_0, ..., λ_8, each eigenvalue written as often as it repeats.")
        if np.allclose(got, exact):
            return "Right: ℓ = 0 (the constant, λ = 0), then 2 three times and 6 five times."
        if np.allclose(got, np.repeat([l * l for l in range(3)], [2 * l + 1 for l in range(3)])):
            raise _Stop(WRONG, "Those are ℓ², the eigenvalues are ℓ(ℓ+1).")
        if np.any(np.diff(got) < 0):
            raise _Stop(WRONG, "List them in increasing order, as `eigenbasis` returns them.")
        if got[0] != 0:
            raise _Stop(WRONG, "The first is λ_0 = 0 (ℓ = 0): a constant function has no energy.")
        if np.allclose(got, [l * (l + 1) for l in range(9)]):
            raise _Stop(WRONG, "Each ℓ(ℓ+1) repeats 2ℓ+1 times (three functions for ℓ = 1, five for ℓ = 2).")
        raise _Stop(WRONG, "Write ℓ(ℓ+1) for ℓ = 0, 1, 2, ..., each 2ℓ+1 times, until you have nine.")
    return _run("00-sphere", show, body)


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
        _attempt(counts)
        if not isinstance(counts, (tuple, list)) or len(counts) != 2:
            raise _Stop(WRONG, "Give two numbers: (vertices, triangles).")
        nv, nf = (_number(c, "a whole number") for c in counts)
        v, f, e = mesh.n_vertices, mesh.n_faces, len(mesh.edges)
        if (nv, nf) == (v, f):
            return f"Right: V - E + F = {v - e + f} for this closed surface, as for a sphere."
        if (nv, nf) == (f, v):
            raise _Stop(WRONG, "Swapped: vertices first, then triangles.")
        for got, n, name in ((nv, v, "vertex"), (nf, f, "triangle")):
            if got == 3 * n:
                raise _Stop(WRONG, f"Three times too many {name} entries: you counted the numbers in the array "
                                   f"(three per {name}), not its rows.")
        if nf == e:
            raise _Stop(WRONG, "That second number counts the edges; count the triangles (rows of `faces`).")
        raise _Stop(WRONG, "Count the rows of `mesh.vertices` and `mesh.faces` (or read `mesh.summary()`).")
    return _run("00-size", show, body)


@lru_cache(maxsize=2)
def _torus_spectrum(k: int) -> Any:
    from . import shapes
    from .spectrum import eigenbasis

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
        _attempt(phi)
        spectrum = _torus_spectrum(max(16, index + 3))
        n = spectrum.n_vertices
        f = _array(phi, "an array with one value per vertex")
        if f.ndim == 2 and 1 in f.shape:
            f = f.ravel()
        if f.shape != (n,):
            raise _Stop(WRONG, f"Expected one value per vertex of the torus, shape ({n},), got {f.shape}: "
                               "one column of `spectrum.vectors`.")
        W, A = spectrum.stiffness, spectrum.mass
        norm2 = float(f @ (A @ f))
        if norm2 <= 0:
            raise _Stop(WRONG, "That function is zero.")
        r = float(f @ (W @ f)) / norm2
        residual = np.linalg.norm(W @ f - r * (A @ f)) / max(np.linalg.norm(W @ f), 1e-300)
        lam = spectrum.values
        if residual > 1e-5:
            raise _Stop(WRONG, "Not an eigenfunction of W φ = λ A φ: take one column of `eigenbasis(mesh, k).vectors`.")
        if _near(r, lam[index], 1e-6):
            return f"Right: an eigenfunction with the eigenvalue λ_{index}."
        hit = int(np.argmin(np.abs(lam - r)))
        if hit < index:
            raise _Stop(WRONG, f"An eigenfunction, but of a smaller eigenvalue: indices start at 0 (φ_0 is the constant), "
                               f"so φ_{index} is column {index}, and you need k ≥ {index + 1}.")
        raise _Stop(WRONG, f"An eigenfunction, but of a larger eigenvalue: φ_{index} is column {index} of `vectors`.")
    return _run("00-torus", show, body)


def check_load_error(error: Any, *, show: bool = True) -> Feedback:
    """Exercise 00-missing: the exception ``load_mesh`` raised for a face naming a vertex that does not exist."""
    from .mesh import Mesh, MeshError

    def body() -> str:
        _attempt(error)
        if isinstance(error, MeshError):
            return "Right: a `MeshError` that names the face and the vertex index that does not exist."
        if isinstance(error, type):
            raise _Stop(WRONG, "That is an exception class; keep the exception object: `except lbo.MeshError as err: error = err`.")
        if isinstance(error, str):
            raise _Stop(WRONG, "Keep the exception object itself (`error = err` inside the `except` block), not its text.")
        if isinstance(error, Mesh):
            raise _Stop(WRONG, "`load_mesh` returned a mesh: no face of your file refers to a missing vertex. "
                               "Faces count vertices from 0, so a file with 3 vertices has indices 0, 1, 2.")
        if isinstance(error, BaseException):
            raise _Stop(WRONG, f"`load_mesh` refuses a broken mesh with a `MeshError`; you caught a {type(error).__name__}. "
                               "Is the file's header (counts of vertices and faces) consistent?")
        raise _Stop(WRONG, f"Expected the exception object, got {type(error).__name__}.")
    return _run("00-missing", show, body)


# --- 08 · regularized PCA --------------------------------------------------------------------------

_BASES = ("pca (6)", "pca + smooth", "eigenbasis")


def check_rpca_limits(at_zero: Any, at_one: Any, best: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-limits: the bases at β → 0 and β → 1 (of m = 100 functions), and where the best β lies."""
    def body() -> str:
        _attempt([at_zero, at_one, best])
        answers = {}
        for name, value, options in (("β → 0", at_zero, _BASES), ("β → 1", at_one, _BASES),
                                     ("the best β", best, ("small", "intermediate", "large"))):
            if not isinstance(value, str) or value.strip().lower() not in options:
                raise _Stop(WRONG, f"{name}: answer with one of " + ", ".join(f'"{o}"' for o in options) + ".")
            answers[name] = value.strip().lower()
        a0, a1, b = answers.values()
        if a0 == "eigenbasis" and a1 != "eigenbasis":
            raise _Stop(WRONG, "β → 0 puts all the weight on the data term and β → 1 on smoothness: check which end is which.")
        if a0 == "pca (6)":
            raise _Stop(WRONG, "β → 0: the basis still has m = 100 functions, and the data fill only six of them. "
                               "What chooses the other 94 while μ is small but positive?")
        if a0 != "pca + smooth":
            raise _Stop(WRONG, "β → 0: the data term dominates, but it is blind to 94 of the 100 directions.")
        if a1 != "eigenbasis":
            raise _Stop(WRONG, "β → 1 (μ → ∞): only the Dirichlet energy counts. Which A-orthonormal basis has the smallest energies?")
        if b != "intermediate":
            raise _Stop(WRONG, "The limits are right. For the best β: each end ignores one of the two terms. Can "
                               "the validation pose be rebuilt from the training data alone, or from smoothness alone?")
        return "Right: the PCA directions then the smoothest complement, the eigenbasis, and a weight in between."
    return _run("08-limits", show, body)


def check_dirichlet_energies(energies: Any, basis: Any, stiffness: Any, mass: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-energy: the Dirichlet energies ``p_jᵀ W p_j`` of the columns of ``basis``.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(2), 9)
    >>> check_dirichlet_energies(s.values, s.vectors, s.stiffness, s.mass, show=False).correct
    True
    >>> "A-norm" in check_dirichlet_energies(np.ones(9), s.vectors, s.stiffness, s.mass, show=False).message
    True
    """
    def body() -> str:
        _attempt(energies)
        P = np.asarray(basis, dtype=np.float64)
        e = _array(energies, "an array of energies, one per function")
        WP = stiffness @ P
        ref = np.einsum("ij,ij->j", P, WP)
        scale = max(np.abs(ref).max(), 1e-300)
        if e.shape == (P.shape[1], P.shape[1]):
            raise _Stop(WRONG, "One energy per function: the diagonal of Pᵀ W P, not the whole matrix.")
        if e.shape != ref.shape:
            raise _Stop(WRONG, f"One energy per column of the basis (length {ref.shape[0]}), got shape {e.shape}.")
        near = lambda other: bool(np.abs(e - other).max() <= 1e-6 * max(np.abs(other).max(), scale))  # noqa: E731
        if near(ref):
            return "Right: E(p_j) = p_jᵀ W p_j, the squared norm of the gradient."
        if near(np.einsum("ij,ij->j", P, mass @ P)):
            raise _Stop(WRONG, "That is p_jᵀ A p_j, the A-norm (1 for an A-orthonormal basis); the energy uses W.")
        if near(np.einsum("ij,ij->j", P, P)):
            raise _Stop(WRONG, "That is p_jᵀ p_j, with neither W nor A; the energy is p_jᵀ W p_j.")
        if near(np.sqrt(np.abs(ref))):
            raise _Stop(WRONG, "The square root: the energy is ‖∇p‖², not ‖∇p‖.")
        if near(2 * ref) or near(ref / 2):
            raise _Stop(WRONG, "Off by a factor of two: here the energy is p_jᵀ W p_j, without a ½.")
        if near(np.abs(WP).sum(axis=0)) or near(WP.sum(axis=0)):
            raise _Stop(WRONG, "W p_j is a vector; the energy is the number p_jᵀ (W p_j).")
        raise _Stop(WRONG, "Not p_jᵀ W p_j for each column p_j of the basis (`np.einsum(\"ij,ij->j\", ...)` does all columns at once).")
    return _run("08-energy", show, body)


def check_validation_choice(chosen_beta: Any, beats_by_four: Any, errors: Mapping[float, Any], err_lbo: Any,
                            unseen: list[str], pose: str = "tail_raised", *, show: bool = True) -> Feedback:
    """Exercise 08-validation: β chosen on another validation pose, and whether it still beats the eigenbasis 4×.

    ``errors`` maps each swept β to the errors on the ``unseen`` poses, ``err_lbo`` the eigenbasis' errors.
    """
    def body() -> str:
        _attempt([chosen_beta, beats_by_four])
        betas = list(errors)
        i = unseen.index(pose)
        others = [j for j in range(len(unseen)) if j != i]
        ref = min(betas, key=lambda b: errors[b][i])
        got = _number(chosen_beta, "one of the swept β")
        if not any(_near(got, b, 1e-9) for b in betas):
            raise _Stop(WRONG, "Choose one of the swept weights `betas` (the sweep is already computed).")
        if not _near(got, ref, 1e-9):
            if _near(got, max(betas, key=lambda b: errors[b][i]), 1e-9):
                raise _Stop(WRONG, f"That β gives the *largest* error on {pose}: take the smallest.")
            if _near(got, min(betas, key=lambda b: np.mean(errors[b])), 1e-9):
                raise _Stop(WRONG, f"That β is best on all the unseen poses together (peeking): choose on {pose} alone.")
            if _near(got, min(betas, key=lambda b: np.mean([errors[b][j] for j in others])), 1e-9):
                raise _Stop(WRONG, f"That β is best on the *other* poses: choose on {pose} alone, then report on the others.")
            raise _Stop(WRONG, f"Not the β with the smallest error on {pose} (`errors[beta][unseen.index(\"{pose}\")]`).")
        if not isinstance(beats_by_four, (bool, np.bool_)):
            raise _Stop(WRONG, "Answer the second question with True or False.")
        truth = bool(np.all(np.asarray(errors[ref])[others] < np.asarray(err_lbo)[others] / 4))
        if bool(beats_by_four) != truth:
            raise _Stop(WRONG, "The β is right; compare its errors with a quarter of the eigenbasis' (`err_lbo`) on the two other poses.")
        return f"Right: the choice made on {pose}, and its verdict on the two poses it did not see."
    return _run("08-validation", show, body)


def check_mu_scaling(factor: Any, scale: float = 2.0, *, show: bool = True) -> Feedback:
    """Exercise 08-scale: the factor by which μ (for a fixed β) changes when the shape is scaled by ``scale``.

    Examples
    --------
    >>> check_mu_scaling(2.0**6, 2.0, show=False).correct
    True
    """
    def body() -> str:
        _attempt(factor)
        got, s = _number(factor), float(scale)
        if _near(got, s**6, 1e-3):
            return "Right: s_B grows by s⁴ (X by s, A by s²) and λ_ref shrinks by s² (it is ∝ 1/area): μ ∝ s⁶."
        if _near(got, s**-6, 1e-3):
            raise _Stop(WRONG, "Upside down: both changes make μ larger.")
        if _near(got, 1.0, 1e-3):
            raise _Stop(WRONG, "β is dimensionless and stays; μ = β/(1−β) · s_B/λ_ref carries units, so it changes.")
        if _near(got, s**4, 1e-3):
            raise _Stop(WRONG, "That is the growth of s_B alone; λ_ref = 4πm/area changes too.")
        if _near(got, s**2, 1e-3):
            raise _Stop(WRONG, "That accounts for λ_ref (or for the data) only: both s_B and λ_ref change.")
        if _near(got, s**3, 1e-3) or _near(got, s**5, 1e-3):
            raise _Stop(WRONG, "Check the powers: X → sX and A → s²A in s_B (the top eigenvalue of Xᵀ A X), and the area in λ_ref.")
        raise _Stop(WRONG, "μ = β/(1−β) · s_B/λ_ref: find how s_B (top eigenvalue of Xᵀ A X) and λ_ref = 4πm/area scale.")
    return _run("08-scale", show, body)


def _rpca_objective(P: np.ndarray, X: np.ndarray, W: Any, A: Any, mu: float) -> float:
    R = P @ (P.T @ (A @ X)) - X
    return float(np.sum(R * (A @ R)) + mu * np.sum(P * (W @ P)))


def check_rpca_objective(objective: Any, X: Any, W: Any, A: Any, P: Any, mu: float, *, show: bool = True) -> Feedback:
    """Exercise 08-objective: the student's ``objective(P, X, W, A, mu)`` against the regularized-PCA objective.

    Called on ``P`` and on its first half of columns with ``3 mu``; the hint names the usual slip.
    """
    def body() -> str:
        P_ = np.asarray(P, dtype=np.float64)
        X_ = np.asarray(X, dtype=np.float64)
        for basis, weight in ((P_, float(mu)), (P_[:, : max(1, P_.shape[1] // 2)], 3.0 * float(mu))):
            got = _number(_call(objective, basis, X_, W, A, weight), "a number (the value of the objective)")
            ref = _rpca_objective(basis, X_, W, A, weight)
            if _near(got, ref, 1e-8):
                continue
            fit = ref - weight * np.sum(basis * (W @ basis))
            smooth = weight * np.sum(basis * (W @ basis))
            R = basis @ (basis.T @ (A @ X_)) - X_
            R_euclid_proj = basis @ (basis.T @ X_) - X_
            candidates = (
                (fit, "The smoothness term μ Σ p_jᵀ W p_j is missing."),
                (fit - smooth, "The smoothness term has the wrong sign: it is a penalty, added."),
                (fit + weight * np.sum(basis * (A @ basis)), "The smoothness term uses A; the Dirichlet energy uses W."),
                (float(np.sum(R * R)) + smooth, "The residual is measured in the Euclidean norm; the objective uses ‖·‖_A (Rᵀ A R)."),
                (float(np.sum(R_euclid_proj * (A @ R_euclid_proj))) + smooth,
                 "The projection is P Pᵀ A x (the A inner product), not P Pᵀ x."),
                (fit + smooth / weight if weight else np.nan, "μ is missing in front of the energy."),
            )
            for value, hint in candidates:
                if np.isfinite(value) and _near(got, value, 1e-8):
                    raise _Stop(WRONG, hint)
            raise _Stop(WRONG, "Not Σ_i ‖P Pᵀ A x_i − x_i‖²_A + μ Σ_j p_jᵀ W p_j: check each term on its own "
                               "(with μ = 0 only the fit is left).")
        return "Right: the fit in the A-norm plus μ times the Dirichlet energies, on two bases and two weights."
    return _run("08-objective", show, body)


def check_recap_08(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-recap: three multiple-choice questions on notebook 08, each answered with a letter."""
    return _recap("08-recap", [q1, q2, q3], [
        {"a": "PCA on the coordinates then smoothed is not optimal for the combined objective; section 1 derives a closed form.",
         "b": None,
         "c": "Which term is maximised and which penalised? The eigenvalue problem keeps the *top* eigenvectors of a difference."},
        {"a": None,
         "b": "Centring removes only the constant direction; count the independent functions two poses give.",
         "c": "Smoothness plays no part in plain PCA; the trouble is in the data term alone."},
        {"a": "A dimensionless weight is not faster to compute: the solver factorises once either way.",
         "b": "μ is never negative here; what changes about μ when the shape is scaled?",
         "c": None},
    ], show)


# --- 09 · the spectral toolbox ---------------------------------------------------------------------

def check_hks(hks_function: Any, spectrum: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-hks: the student's ``hks_function(spectrum, times)`` against :func:`descriptors.hks`.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis, descriptors
    >>> s = eigenbasis(shapes.bumpy_sphere(2), 12)
    >>> check_hks(descriptors.hks, s, show=False).correct
    True
    >>> "φ_i(x)²" in check_hks(lambda s, t: s.vectors @ np.exp(-np.outer(s.values, t)), s, show=False).message
    True
    """
    from .descriptors import hks, hks_times

    def body() -> str:
        times = hks_times(spectrum, 4)
        ref = hks(spectrum, times)
        with np.errstate(over="ignore", invalid="ignore"):
            h = _array(_call(hks_function, spectrum, times.copy()), "an array of shape (vertices, times)", finite=False)
        if not np.all(np.isfinite(h)):
            raise _Stop(WRONG, "Your values overflow or are NaN: e^(+λ t) grows without bound; heat decays, e^(−λ_i t).")
        if h.shape == ref.shape[::-1]:
            raise _Stop(WRONG, f"Transposed: one row per vertex and one column per time, shape {ref.shape}.")
        if h.shape != ref.shape:
            raise _Stop(WRONG, f"Expected shape {ref.shape} (one row per vertex, one column per time), got {h.shape}.")
        if _same(h, ref, 1e-6):
            return "Right: h_t(x) = Σ_i e^(−λ_i t) φ_i(x)², every eigenpair including the constant φ_0."
        phi, lam = spectrum.vectors, np.maximum(spectrum.values, 0.0)
        decay = np.exp(-np.outer(lam, times))
        mass = np.asarray(spectrum.mass.diagonal())
        with np.errstate(over="ignore"):
            growth = np.exp(np.outer(lam, times))
        candidates = (
            (phi @ decay, "Square the eigenfunctions: the sum is over φ_i(x)², not φ_i(x)."),
            (np.abs(phi) @ decay, "Square the eigenfunctions: φ_i(x)², not |φ_i(x)|."),
            ((phi**2) @ growth, "exp(+λ t) grows; heat decays: e^(−λ_i t)."),
            ((phi[:, 1:] ** 2) @ decay[1:], "The sum starts at i = 0: the constant φ_0 (λ_0 = 0) keeps its share of heat at every time."),
            ((phi**2)[:, :-1] @ decay[:-1], "Use every computed eigenpair: the last one is missing."),
            (mass[:, None] * ((phi**2) @ decay), "No mass matrix: the HKS is a value at each vertex, not an integral."),
            ((phi**2) @ np.exp(-lam)[:, None] * times[None, :], "The time goes inside the exponential: e^(−λ_i t)."),
        )
        for value, hint in candidates:
            if np.all(np.isfinite(value)) and _same(h, value, 1e-6):
                raise _Stop(WRONG, hint)
        raise _Stop(WRONG, "Not Σ_i e^(−λ_i t) φ_i(x)²: try it on one vertex and one time by hand, "
                           "with `spectrum.values` and `spectrum.vectors`.")
    return _run("09-hks", show, body)


def check_functional_map(fmap: Any, source: Any, target: Any, k: int = 20, *, show: bool = True) -> Feedback:
    """Exercise 09-fmap: the student's ``fmap(p2p, source, target, k)`` against ``functional_maps.map_from_points``.

    Tried on a random permutation ``p2p`` (``p2p[j]``: the source vertex of target vertex ``j``),
    so that a map used the wrong way round shows.
    """
    from .functional_maps import map_from_points

    def body() -> str:
        k_ = min(int(k), source.k, target.k)
        n1, n2 = source.n_vertices, target.n_vertices
        rng = np.random.default_rng(9)
        p2p = rng.permutation(n1)[:n2] if n2 <= n1 else rng.integers(0, n1, n2)
        ref = map_from_points(p2p, source, target, k_source=k_, k_target=k_)
        C = _array(_call(fmap, p2p.copy(), source, target, k_), "a k × k matrix")
        if C.shape != ref.shape:
            raise _Stop(WRONG, f"Expected a {k_} × {k_} matrix (k functions on each side), got shape {C.shape}.")
        if _same(C, ref, 1e-6):
            return "Right: C = Φ₂ᵀ A₂ Π Φ₁, the A₂ inner products of the pulled-back source functions with the target's."
        P1, P2, A2 = source.vectors[:, :k_], target.vectors[:, :k_], target.mass
        candidates = [
            (ref.T, "Transposed: C takes source coefficients to target coefficients, so rows belong to the target (Φ₂ᵀ on the left)."),
            (P2.T @ P1[p2p], "That is Φ₂ᵀ Π Φ₁, the Euclidean inner product: the target's eigenfunctions are A₂-orthonormal, so A₂ belongs in the middle."),
            (P2.T @ (A2 @ P1[: n2]) if n1 >= n2 else np.full(ref.shape, np.nan),
             "Π is missing: the source functions must be pulled back to the target first, Φ₁[p2p] (row j takes the value at vertex p2p[j])."),
        ]
        if n1 == n2:
            inverse = np.argsort(p2p)
            candidates += [
                (P2.T @ (A2 @ P1[inverse]), "The point map is used the wrong way round: (Π f)_j = f(p2p[j]), so index the rows of Φ₁ by p2p itself."),
                (P2.T @ (source.mass @ P1[p2p]), "That uses the source's mass matrix A₁; the inner product is taken on the target, where Π Φ₁ lives: A₂."),
            ]
        try:
            lstsq = np.linalg.lstsq(P2, P1[p2p], rcond=None)[0]
            candidates.append((lstsq, "That is a Euclidean least-squares fit; with A₂-orthonormal Φ₂ the coefficients are Φ₂ᵀ A₂ (Π Φ₁)."))
        except np.linalg.LinAlgError:  # pragma: no cover - lstsq of a full-rank tall matrix
            pass
        for value, hint in candidates:
            if np.all(np.isfinite(value)) and _same(C, value, 1e-6):
                raise _Stop(WRONG, hint)
        raise _Stop(WRONG, "Not Φ₂ᵀ A₂ Π Φ₁: pull the first k source eigenfunctions back (Φ₁[p2p]), then take their A₂ inner "
                           "products with the first k target eigenfunctions.")
    return _run("09-fmap", show, body)


def check_truncation_bound(bound: Any, spectrum: Any, f: Any, k: int, *, show: bool = True) -> Feedback:
    """Exercise 09-bound: the optimality bound on the share of ‖f‖²_A lost by the first ``k`` eigenfunctions."""
    from .optimality import dirichlet_energy

    def body() -> str:
        _attempt(bound)
        got = _number(bound, "a number (a fraction of ‖f‖²_A)")
        g = np.asarray(f, dtype=np.float64)
        W, A, lam = spectrum.stiffness, spectrum.mass, spectrum.values
        energy, norm2 = float(dirichlet_energy(W, g)), float(g @ (A @ g))
        ref = energy / lam[k] / norm2
        if _near(got, ref, 1e-6):
            return f"Right: ‖∇f‖²/λ_{k} as a fraction of ‖f‖²_A (the first k functions are φ_0 ... φ_{k - 1})."
        candidates = (
            (energy / lam[k - 1] / norm2, "Off by one index: the first k functions are φ_0 ... φ_(k−1), so the bound divides by λ_k, the first one left out."),
            (energy / lam[k + 1] / norm2 if k + 1 < len(lam) else np.nan, "Off by one index: the bound divides by λ_k, the first eigenvalue left out (indices from 0)."),
            (energy / lam[k], "That is the bound on ‖f − P_k f‖²_A itself; the question asks for it as a fraction of ‖f‖²_A."),
            (energy / lam[k] / float(g @ g), "Divide by ‖f‖²_A = fᵀ A f, the A-norm, not fᵀ f."),
            (np.sqrt(energy / lam[k] / norm2), "Squared norms on both sides: no square root."),
            (float(g @ (A @ g)) / lam[k] / norm2, "The numerator is the Dirichlet energy fᵀ W f, not fᵀ A f."),
        )
        for value, hint in candidates:
            if np.isfinite(value) and _near(got, value, 1e-6):
                raise _Stop(WRONG, hint)
        c = spectrum.vectors[:, :k].T @ (A @ g)
        if _near(got, 1 - float(c @ c) / norm2, 1e-3):
            raise _Stop(WRONG, "That is the share actually lost (the projection); the question asks for the theorem's bound, from the energy alone.")
        raise _Stop(WRONG, "The bound is ‖∇f‖²/λ_k = fᵀ W f / λ_k; divide it by fᵀ A f.")
    return _run("09-bound", show, body)


def check_alpha_choice(alpha: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-alpha: which α of the metric |K|^α g matches the dog with a 1.6 times larger head best (0, 0.4 or 1)?"""
    def body() -> str:
        _attempt(alpha)
        got = _number(alpha, "one of 0, 0.4, 1")
        if _near(got, 1.0, 1e-9):
            return "Right on this pair: with α = 1 a part scaled by s has the same metric |K| g (K by 1/s², lengths² by s²)."
        if got == 0:
            raise _Stop(WRONG, "The regular metric sees a bigger head as more area and lower frequencies everywhere (section 1). "
                               "Which α makes a rescaled part look unchanged?")
        if _near(got, 0.4, 1e-9):
            raise _Stop(WRONG, "α = 0.4 compensates the rescaling only in part: K scales by 1/s², lengths² by s². Which α cancels them?")
        raise _Stop(WRONG, "Answer 0, 0.4 or 1.")
    return _run("09-alpha", show, body)


def check_mirror_maps(with_orientation: Any, without_orientation: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-mirror: which map ``match`` finds from the dog to its mirror, with and without the orientation term."""
    options = ("i -> i", "same position")

    def body() -> str:
        _attempt([with_orientation, without_orientation])
        given = []
        for value in (with_orientation, without_orientation):
            if not isinstance(value, str) or value.strip().lower() not in options:
                raise _Stop(WRONG, "Answer each with \"i -> i\" or \"same position\".")
            given.append(value.strip().lower())
        if given == ["same position", "i -> i"]:
            return ("Right: intrinsically the mirror is the dog itself, so without the orientation term i -> i is a perfect map; "
                    "it reverses orientation, and the term asks for a map that preserves it: the left–right swap.")
        if given == ["i -> i", "same position"]:
            raise _Stop(WRONG, "The other way round: which of the two maps reverses orientation (a mirror does)?")
        if given[0] == "i -> i":
            raise _Stop(WRONG, "With the orientation term: vertex i of the mirror is the *reflection* of vertex i, a map that reverses orientation.")
        raise _Stop(WRONG, "Without the orientation term only intrinsic quantities count: how do the mirror's descriptors at vertex i compare with the dog's?")
    return _run("09-mirror", show, body)


def check_zoomout(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-zoomout: without ZoomOut (``k_final=30``), is the mean error larger, the same or smaller?"""
    return _choice("09-zoomout", answer, {
        "larger": None,
        "same": "ZoomOut adds 50 more frequencies to the map, and the point map is read off them: does that change nothing?",
        "smaller": "Refinement with more (smooth, well-captured) functions sharpens the point map; why would it make it worse?",
    }, show)


def check_recap_09(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-recap: three multiple-choice questions on notebook 09, each answered with a letter."""
    return _recap("09-recap", [q1, q2, q3], [
        {"a": "Each eigenfunction is defined up to sign, and inside a cluster only up to rotation: compare φ_8 in section 1.",
         "b": None,
         "c": "The eigenfunctions change with the pose (signs, mixing); the HKS uses only squares and eigenvalues."},
        {"a": None,
         "b": "Which basis is A₂-orthonormal, and so needs A₂ to take coefficients?",
         "c": "Π pulls functions from shape 1 back to shape 2, so it acts on Φ₁, between A₂ and Φ₁."},
        {"a": "A functional map of size k sees only k coefficients; what bounds the rest?",
         "b": "Eigenfunctions are not invariant (signs, mixing: section 1); the reason is a bound on what lies beyond φ_(k−1).",
         "c": None},
    ], show)
