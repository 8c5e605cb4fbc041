"""Self-checks of notebook 01 (the shape collection), and the reading of answers as typed that the
checks of 03 (:mod:`~lbo_notebooks.exercises.laplace_beltrami`) share.

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .feedback import (
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, close_to,
    choose, pick, number_judge, recap, right,
)

__all__ = [
    "check_recap_shapes",
    "check_edge_count",
    "check_area_factor",
    "check_stretch_growth",
    "check_smallest_angles",
    "check_leg_area",
]

# --- answers as typed: hand-rounded numbers and dict keys ------------------------------------------

def _shown_decimals(answer: Any) -> int | None:
    """How many decimals ``answer`` shows as typed (``2.6`` -> 1, ``3`` -> 0, ``1e-05`` -> 5), or None
    for a value with more than six significant digits (computed, not typed)."""
    from decimal import Decimal

    if isinstance(answer, (bool, np.bool_)):
        return None
    if isinstance(answer, (int, np.integer)):
        return 0
    try:
        value = float(answer)
    except (TypeError, ValueError, OverflowError):
        return None
    if not np.isfinite(value):
        return None
    digits = Decimal(repr(value)).as_tuple()
    if len(digits.digits) > 6 or not isinstance(digits.exponent, int):
        return None
    return -digits.exponent


def rounding_of(answer: Any, exact: float) -> bool:
    """True when ``answer`` is ``exact`` rounded by hand to the digits it shows (``2.6`` or ``3`` for
    2.56; never 0). Such an answer is right as far as it goes: its message asks for more digits,
    not for another method.

    Examples
    --------
    >>> rounding_of(2.6, 2.56), rounding_of(3, 2.56), rounding_of(3.0, 2.56), rounding_of(0, 0.25)
    (True, True, False, False)
    """
    decimals = _shown_decimals(answer)
    if decimals is None:
        return False
    value = float(answer)
    if value == 0 or np.sign(value) != np.sign(exact):
        return False
    return abs(value - exact) <= 0.5 * 10.0 ** (-decimals) * (1 + 1e-9)


def more_digits(where: str = "") -> str:
    return (f"{where}right as far as the digits you gave go, but rounded too coarsely to grade: give more "
            "digits (or the value Python computes).")


def _number_key(key: Any) -> float | None:
    """A dict key as a number (``2000``, ``np.int64(2000)``, ``2000.0``, ``"2000"``), or None."""
    if isinstance(key, (bool, np.bool_)):
        return None
    try:
        array = np.asarray(key, dtype=np.float64)
        value = float(array) if array.ndim == 0 else np.nan
    except Exception:  # noqa: BLE001 - any key type: a check never raises
        return None
    return value if np.isfinite(value) else None


def _numbered(answer: Any, what: str, example: str) -> dict[float, Any]:
    """``{number: value}`` of a dict answer whose keys must be numbers (Stop with a clear message else)."""
    if not isinstance(answer, Mapping) or not answer:
        raise Stop(WRONG, f"Give a dict {{{what}: value}}, e.g. {example}.")
    numbered: dict[float, Any] = {}
    for key, value in answer.items():
        number = _number_key(key)
        if number is None:
            raise Stop(WRONG, f"The keys of the dict are the {what}s, as numbers ({example}); got the key {key!r}.")
        if number in numbered:
            raise Stop(WRONG, f"The {what} {key!r} appears twice among the keys.")
        numbered[number] = value
    return numbered


def _entry(numbered: dict[float, Any], wanted: float) -> tuple[bool, Any]:
    """(found, value) of the entry whose key is ``wanted`` (keys compared as numbers, to round-off)."""
    for key, value in numbered.items():
        if abs(key - wanted) <= 1e-9 * max(abs(wanted), 1.0):
            return True, value
    return False, None


class WrappedReasons(dict):  # type: ignore[type-arg]
    """The reasons of a wrapped choice judge (``pick(...).reasons``), looked up the way the wrapper
    reads an answer, so that :func:`~lbo_notebooks.exercises.feedback.recap` finds the reason of a
    right answer written another way (``"Joint_Bands"``)."""

    def __init__(self, judge: Any, read: Any) -> None:
        super().__init__(getattr(judge, "reasons", {}))
        self._read = read

    def get(self, key: Any, default: Any = None) -> Any:
        read = self._read(key)
        return super().get(read.strip().lower() if isinstance(read, str) else key, default)


def loose(judge: Any) -> Any:
    """A choice judge that also takes ``"Joint  Bands"`` or ``"joint_bands"`` (case, spaces, underscores)."""
    def read(answer: Any) -> Any:
        return " ".join(answer.replace("_", " ").split()) if isinstance(answer, str) else answer

    def tidy(answer: Any) -> str | None:
        return judge(read(answer))
    tidy.reasons = WrappedReasons(judge, read)  # type: ignore[attr-defined]
    return tidy


# --- 01 · the shape collection -------------------------------------------------------------------

RECAP_SHAPES = [
    loose(pick({"faces": right("a pose moves only the vertex positions: the faces are the very same array in every pose, "
                               "one triangulation."),
                 "vertices": "a pose moves the vertices; what is the very same array in every pose?",
                 "both": "a pose moves the vertices; only one of the two arrays is shared."})),
    number_judge(2.0, [(0.0, "that is a torus (genus 1); the creatures are genus 0."),
                       (1.0, "that is a disc; the creatures are closed surfaces of genus 0.")],
                 "V − E + F of a closed genus-0 surface."),
    loose(pick({"joint bands": right("a vertex whose whole one-ring lies outside the joint bands moves rigidly with its "
                                     "bone, so its edges keep their length."),
                 "everywhere": "a vertex whose whole one-ring is outside the bands moves rigidly with its bone: its "
                               "edges keep their length.",
                 "tips": "the stretch goes where a joint's weight blends from 0 to 1; is that at the tips of the "
                         "limbs?"})),
]
"""The judges of the recap's three questions (a hint, or None when right); the graded test reuses them."""


def check_recap_shapes(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 01: (1) what all poses of a creature share, (2) the Euler characteristic of
    every creature mesh, (3) where the stretch of a pose lies.

    Examples
    --------
    >>> check_recap_shapes("faces", 2, "joint bands", show=False).correct
    True
    """
    return recap("01-recap", [q1, q2, q3], RECAP_SHAPES, show)


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
        require_attempt(n_edges)
        e, f = len(mesh.edges), mesh.n_faces
        got = as_number(n_edges, "a whole number")
        if got == e:
            chi = mesh.n_vertices - e + f
            return f"Right: each triangle has three edges and each edge borders two triangles, so E = 3F/2; here V - E + F = {chi}."
        if got == 3 * f:
            raise Stop(WRONG, "Off by a factor of two: three edges per triangle counts every edge twice, once from each of the two triangles it borders.")
        if got == e / 2:
            raise Stop(WRONG, "Off by a factor of two (too few): you divided once too often.")
        raise Stop(WRONG, "Count the edge slots (three per triangle), then ask how many triangles share each edge of a closed surface.")
    return run_check("01-edges", show, body)


def check_area_factor(prediction: Any, scale: float, *, show: bool = True) -> Feedback:
    """Exercise 01-area: by what factor does the area of a part grow when the part is scaled by ``scale``?

    Examples
    --------
    >>> check_area_factor(1.6**2, scale=1.6, show=False).correct
    True
    >>> "more digits" in check_area_factor(2.6, scale=1.6, show=False).message
    True
    """
    def body() -> str:
        require_attempt(prediction)
        got = as_number(prediction)
        if close_to(got, scale**2):
            return "Right: lengths grow by s, areas by s²."
        if rounding_of(prediction, scale**2):
            raise Stop(WRONG, more_digits("That is "))
        if close_to(got, scale):
            raise Stop(WRONG, "That is the factor of the lengths; an area has two length dimensions.")
        if close_to(got, scale**3):
            raise Stop(WRONG, "That is how a volume scales; a surface area has two length dimensions.")
        if close_to(got, scale**-2) or close_to(got, 1 / scale):
            raise Stop(WRONG, "The part gets bigger, so its area grows: check the direction of your factor.")
        raise Stop(WRONG, "Think of a square of side L scaled by s: what is its new area?")
    return run_check("01-area", show, body)


def check_stretch_growth(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 01-stretch: what happens to the worst edge stretch when a bend's angle doubles?"""
    return choose("01-stretch", answer, {
        "same": "The stretch rθ/L depends on the angle θ: a larger bend over the same band stretches more.",
        "double": right("The outer side stretches by about rθ/L, linear in the angle θ for a fixed radius r and band "
                        "length L: twice the bend, about twice the stretch."),
        "quadruple": "rθ/L is linear in θ, not quadratic: you may be thinking of an area.",
        "half": "A larger bend stretches the outer side more, not less.",
    }, show)


ANGLE_SIZES = (2_000, 3_000)
"""The sizes exercise 01-angles names; the third one is the notebook's ``N``."""


def asked_sizes(angles: Any) -> dict[int, Any]:
    """``{number of vertices: answer}`` of exercise 01-angles (Stop with a clear message on a bad key)."""
    sizes: dict[int, Any] = {}
    for key, value in _numbered(angles, "number of vertices", "{2_000: ..., 3_000: ..., N: ...}").items():
        if key != round(key) or not 1_000 <= key <= 50_000:
            raise Stop(WRONG, f"The keys are the numbers of vertices you built the dog with, whole numbers from "
                              f"1,000 to 50,000; got {key:g}.")
        sizes[round(key)] = value
    return sizes


def smallest_angle(species: str, n_vertices: int) -> float:
    from ..shapes._creatures import creature
    from ..operators._cotangent import corner_angles

    return float(np.degrees(corner_angles(creature(species, n_vertices=n_vertices))).min())


def angle_hint(n: int, answer: Any, exact: float) -> str | None:
    """None when ``answer`` is the smallest angle ``exact`` (degrees) to 0.05°, else a hint."""
    try:
        got = as_number(answer, f"a number (degrees) for n = {n}")
    except Stop as stop:
        return stop.message
    if abs(got - exact) <= 0.05 + 1e-9 * exact:  # right to a tenth of a degree
        return None
    radians = np.radians(exact)
    if close_to(got, radians, 1e-3) or rounding_of(answer, radians):
        return f"n = {n}: this looks like radians: convert with `np.degrees`."
    if rounding_of(answer, exact):
        return more_digits(f"n = {n}: ")
    if got > 60:
        return (f"n = {n}: every triangle has an angle of at most 60°, so the smallest angle cannot exceed 60°: take the "
                "minimum over all corners.")
    return f"n = {n}: not the smallest corner angle of that mesh; `corner_angles(mesh)` gives every corner's angle."


def check_smallest_angles(angles: Any, species: str = "dog", *, show: bool = True) -> Feedback:
    """Exercise 01-angles: the smallest triangle angle (degrees) of ``creature(species, n_vertices=n)``,
    ``{n: angle}`` for n = 2,000, 3,000 and the notebook's ``N`` (every size required).

    Examples
    --------
    >>> check_smallest_angles({2_000: 40.0}, show=False).message
    'Give the smallest angle for every size asked: 2,000, 3,000 and N vertices, one entry each.'
    >>> check_smallest_angles({"two thousand": 40.0}, show=False).status
    'wrong'
    """
    def body() -> str:
        require_attempt(angles)
        sizes = asked_sizes(angles)
        if any(n not in sizes for n in ANGLE_SIZES) or len(sizes) < len(ANGLE_SIZES) + 1:
            raise Stop(WRONG, "Give the smallest angle for every size asked: 2,000, 3,000 and N vertices, one entry each.")
        for n, answer in sorted(sizes.items()):
            hint = angle_hint(n, answer, smallest_angle(species, n))
            if hint is not None:
                raise Stop(WRONG, hint)
        return "Right: those are the smallest corner angles of the meshes you built."
    return run_check("01-angles", show, body)


LEG_SCALES = (0.7, 1.0, 1.3)
"""The leg scales exercise 01-legs asks about."""


def _leg_split(species: str, n_vertices: int, *, any_corner: bool = False) -> tuple[float, float]:
    """(leg area, rest area) of the standing template: the triangles whose three corners (or, the
    typical slip, any corner) lie in the legs."""
    from ..shapes._creatures import creature, creature_parts

    template = creature(species, n_vertices=n_vertices)
    parts = creature_parts(species, n_vertices=n_vertices)
    in_legs = (parts["front_legs"] | parts["hind_legs"])[template.faces]
    legs = in_legs.any(axis=1) if any_corner else in_legs.all(axis=1)
    return float(template.face_areas[legs].sum()), float(template.face_areas[~legs].sum())


def _leg_hint(s: float, answer: Any, species: str, n_vertices: int) -> str | None:
    """None when ``answer`` is the predicted total area (leg area) s² + (rest) to 1e-4, else a hint."""
    where = f"s = {s:g}: "
    try:
        got = as_number(answer, f"a number (an area) for s = {s:g}")
    except Stop as stop:
        return stop.message
    leg, rest = _leg_split(species, n_vertices)
    exact = leg * s**2 + rest
    if abs(got - exact) <= 1e-4 * exact:
        return None
    if rounding_of(answer, exact):
        return more_digits(where)
    if s != 1 and close_to(got, s * leg + rest, 1e-3):
        return where + "the legs' area grows by s², not s."
    if s != 1 and close_to(got, s**2 * (leg + rest), 1e-3):
        return where + "only the legs are scaled; the rest of the body keeps its area."
    if close_to(got, s**2 * leg, 1e-3):
        return where + "add the area of the rest of the body."
    if s != 1:
        leg_any, rest_any = _leg_split(species, n_vertices, any_corner=True)
        if close_to(got, s**2 * leg_any + rest_any, 1e-3):
            return where + "the legs are the triangles whose *three* corners are in the legs, not any one of them."
        from ..shapes._creatures import creature

        if close_to(got, creature(species, parts={"legs": s}, n_vertices=n_vertices).area, 1e-4):
            return (where + "that is the area of the built shape; the exercise asks for the prediction from the "
                    "standing dog's leg area and the rest, to compare with it.")
    return where + "not (leg area) × s² + (rest) of the standing dog; the legs are the triangles whose three corners are in them."


def check_leg_area(predicted: Any, n_vertices: int, species: str = "dog", *, show: bool = True) -> Feedback:
    """Exercise 01-legs: the predicted total area ``{s: area}`` for legs scaled by s = 0.7, 1.0 and 1.3
    (every scale required), (leg area) s² + (rest) from the standing template.

    Examples
    --------
    >>> check_leg_area({1.0: 2.0}, n_vertices=2000, show=False).message
    'Give a prediction for every scale asked: s = 0.7, 1.0 and 1.3.'
    """
    def body() -> str:
        require_attempt(predicted)
        scales = _numbered(predicted, "scale s", "{0.7: ..., 1.0: ..., 1.3: ...}")
        entries = [_entry(scales, s) for s in LEG_SCALES]
        if not all(found for found, _ in entries):
            raise Stop(WRONG, "Give a prediction for every scale asked: s = 0.7, 1.0 and 1.3.")
        for s, (_, answer) in zip(LEG_SCALES, entries):
            hint = _leg_hint(s, answer, species, n_vertices)
            if hint is not None:
                raise Stop(WRONG, hint)
        return ("Right: (leg area) × s² + (rest) at every scale; the built shapes come within 1% of it (the blend "
                "band at the hips and shoulders is not scaled by exactly s²).")
    return run_check("01-legs", show, body)
