"""Self-checks of notebooks 07 (the min-max principle) and 08 (scale-invariant metrics).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

import numpy as np

from .feedback import (
    ratio_one,
    pick, recap,
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, close_to, choose,
    unanswered, as_array, call_attempt, right,
)
from .basics import WrappedReasons

__all__ = [
    "check_plane_minimum",
    "check_plane_range",
    "check_lowest_family",
    "check_dual_value",
    "check_interlacing",
    "check_consistent_minmax",
    "check_recap_min_max",
    "check_angle_defects",
    "check_gauss_bonnet",
    "check_curvature_scaling",
    "check_metric_scaling",
    "check_best_alpha",
    "check_floor_fraction",
    "check_sphere_alpha",
    "check_consistent_invariance",
    "check_recap_scale_invariant",
]


# --- 07 · the min-max principle -------------------------------------------------------------------

def _compressed(M: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Eigenvalues of M restricted to the plane orthogonal to ``normal`` (ascending)."""
    u = normal / np.linalg.norm(normal)
    basis = np.linalg.svd(np.eye(3) - np.outer(u, u))[0][:, :2]
    return np.linalg.eigvalsh(basis.T @ M @ basis)


# What 07's and 08's checks (and graders, lbo_notebooks/exercises/grading/nb07.py, nb08.py) share:
# choices written any way, and numbers rounded by hand judged on their precision, not their method.

_SUBSCRIPTS = str.maketrans("₀₁₂₃₄₅₆₇₈₉ₙ", "0123456789n")


def _squeezed(text: str) -> str:
    key = text.strip().lower().translate(_SUBSCRIPTS).replace("lambda", "lam").replace("λ", "lam")
    key = re.sub(r"[\s_{}]+", "", key)
    return re.sub(r"(?<=[a-z])-(?=[a-z])", "", key)


def _canonical(answer: Any, options: Any) -> Any:
    """The option ``answer`` names, whatever its case, spaces, hyphens or underscores ("Near optimal",
    "λ_0", "lam0"); anything else unchanged.

    >>> _canonical(" Near optimal", ["white", "near-optimal"]), _canonical("λ₀", ["lam_0", "lam_1"])
    ('near-optimal', 'lam_0')
    """
    if not isinstance(answer, str):
        return answer
    key = _squeezed(answer)
    return next((option for option in options if _squeezed(option) == key), answer)


def _rounding_of(x: float, exact: float) -> int | None:
    """The significant digits of ``x`` when it is ``exact`` rounded or cut by hand to the decimals it
    shows (0.111 for 1/9, 6.28 for 2π, 55 for 54.74), else None (a computed value, or not a rounding).

    >>> _rounding_of(0.111, 1 / 9), _rounding_of(6.3, 2 * np.pi), _rounding_of(0.112, 1 / 9), _rounding_of(1 / 9, 0.1)
    (3, 2, None, None)
    """
    text = np.format_float_positional(abs(x), trim="-")
    whole, _, decimals = text.partition(".")
    if x == 0 or len(decimals) > 12 or not np.isfinite(exact):
        return None
    unit = 10.0 ** -len(decimals)
    cut = np.trunc(exact / unit * (1 + 1e-12)) * unit
    if abs(x - exact) <= 0.5 * unit * (1 + 1e-9) or abs(x - cut) <= 1e-9 * unit:
        return max(len((whole + decimals).lstrip("0")), 1)
    return None


def _precision(x: float, exact: float, tol: float, digits: int | None) -> str | None:
    """"right" (within ``tol``, or a hand rounding to at least ``digits`` significant digits),
    "coarse" (a hand rounding with fewer), or None (neither)."""
    if abs(x - exact) <= tol:
        return "right"
    shown = _rounding_of(x, exact)
    if shown is None:
        return None
    return "right" if digits is not None and shown >= digits else "coarse"


def _near(x: float, slip: float, rtol: float = 1e-6) -> bool:
    """``x`` is the slip's value, computed or rounded by hand to two digits or more."""
    return close_to(x, slip, rtol) or (_rounding_of(x, slip) or 0) >= 2


def _more_digits(digits: int, what: str = "That") -> str:
    return f"{what} is rounded too coarsely to judge: give more digits (at least {digits} significant), or let Python compute it."


def _number_question(target: float, near: list[tuple[float, str]], otherwise: str, *, rtol: float = 1e-3,
                     digits: int = 3) -> Any:
    """A recap's number question: None when right (a hand rounding to ``digits`` significant digits is
    right), the hint of a slip, "more digits" for a coarser rounding, else ``otherwise``."""
    def judge(answer: Any) -> str | None:
        try:
            value = as_number(answer)
        except Stop as stop:
            return stop.message
        verdict = _precision(value, target, rtol * abs(target), digits)
        if verdict == "right":
            return None
        hint = next((hint for slip, hint in near if _near(value, slip, rtol)), None)
        if hint is not None:
            return hint
        return _more_digits(digits, "this") if verdict == "coarse" else otherwise
    return judge


def _choice_question(options: Mapping[str, str | None]) -> Any:
    """A recap's choice question, the choice written any way (see :func:`_canonical`)."""
    judge = pick(options)

    def choice_judge(answer: Any) -> str | None:
        return judge(_canonical(answer, options))
    choice_judge.reasons = WrappedReasons(judge, lambda key: _canonical(key, options))  # type: ignore[attr-defined]
    return choice_judge


def check_plane_minimum(value: Any, M: Any, normal: Any, *, show: bool = True) -> Feedback:
    """Exercise 07-plane: the minimum of R(x) = xᵀ M x / xᵀ x on the plane orthogonal to ``normal``.

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
        require_attempt(value)
        got = as_number(value)
        M_, u = np.asarray(M, dtype=np.float64), np.asarray(normal, dtype=np.float64)
        low, high = _compressed(M_, u)
        lam = np.linalg.eigvalsh(M_)
        if close_to(got, low, 1e-6):
            return "Right: the smaller eigenvalue of M restricted to the plane; below λ_1, as every plane but the optimal ones."
        for slip, hint in (
            (lam[1], "That is λ_1, the value of an optimal plane (normal v_0); this normal is not v_0."),
            (float(u @ M_ @ u / (u @ u)), "That is R at the normal, which is not in the plane: minimise over the vectors orthogonal to u."),
            (high, "That is the maximum of R on the plane, where a min(...) also lands when one of its candidates "
                   "is not a unit vector (xᵀMx without dividing by xᵀx): the question asks for the minimum of R."),
            (lam[0], "λ_0 needs v_0 in the plane, i.e. the normal orthogonal to v_0: is it?"),
        ):
            if close_to(got, slip, 1e-6):
                raise Stop(WRONG, hint)
        if got > high * (1 + 1e-6) or got < lam[0] * (1 - 1e-6) - 1e-12 * abs(lam[-1]):
            raise Stop(WRONG, "No vector gives that value of R = xᵀMx / xᵀx: did you use xᵀMx without dividing by xᵀx (a vector that is not unit length)?")
        raise Stop(WRONG, "Write the plane as two orthonormal vectors orthogonal to u (columns of B); the minimum is the smaller eigenvalue of the 2×2 matrix Bᵀ M B.")
    return run_check("07-plane", show, body)


def check_plane_range(answer: Any, M: Any, *, show: bool = True) -> Feedback:
    """Exercise 07-range: the interval of min-over-a-plane values, (lowest, highest), over all planes."""
    def body() -> str:
        require_attempt(answer)
        pair = tuple(answer.ravel()) if isinstance(answer, np.ndarray) and answer.size == 2 else answer   # lam[:2] too
        if not isinstance(pair, (list, tuple)) or len(pair) != 2:
            raise Stop(WRONG, "Give a pair (lowest, highest).")
        low, high = (as_number(a) for a in pair)
        lam = np.linalg.eigvalsh(np.asarray(M, dtype=np.float64))
        if low > high:
            raise Stop(WRONG, "Give the lowest value first.")
        if close_to(low, lam[0], 1e-6) and close_to(high, lam[1], 1e-6):
            return "Right: a plane containing v_0 gives λ_0; no plane gives more than λ_1, which the plane orthogonal to v_0 reaches."
        if close_to(low, lam[0], 1e-6) and close_to(high, lam[2], 1e-6):
            raise Stop(WRONG, "That is the range of R itself on the sphere. The *minimum* on a plane is lower: every plane meets span(v_0, v_1) in a line.")
        if not close_to(low, lam[0], 1e-6):
            raise Stop(WRONG, "The lowest: can a plane contain v_0? What is the minimum on it then?")
        raise Stop(WRONG, "The highest: every plane meets span(v_0, v_1) in a line (two planes through 0 in 3-D always do); what is R there at most?")
    return run_check("07-range", show, body)


def check_lowest_family(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 07-family: which family of random constraints leaves the lowest minima."""
    options = {
        "white": right("Noise is nearly A-orthogonal to every smooth function, so white-noise constraints remove "
                       "almost none of the low-energy functions: the minimum stays low."),
        "smooth": "Smooth constraints remove smooth, low-energy functions. What do rough constraints remove?",
        "near-optimal": "Constraints near φ_0 .. φ_(n-1) are nearly the optimal ones of Courant–Fischer: they come closest to λ_n.",
    }
    return choose("07-family", _canonical(answer, options), options, show)


def check_dual_value(value: Any, M: Any, *, show: bool = True) -> Feedback:
    """Exercise 07-dual: the exact min over planes of the max of R on the plane (for the 3×3 M)."""
    def body() -> str:
        require_attempt(value)
        got = as_number(value)
        lam = np.linalg.eigvalsh(np.asarray(M, dtype=np.float64))
        if close_to(got, lam[1], 1e-6):
            return "Right: λ_1 = min over planes of the max, reached by span(v_0, v_1): the dual (max-min ↔ min-max) form."
        if lam[1] < got <= lam[1] * 1.05:
            raise Stop(WRONG, "Close: random planes approach it from above. Which plane reaches the exact value?")
        if close_to(got, lam[2], 1e-6):
            raise Stop(WRONG, "λ_2 is the largest maximum (planes containing v_2); the question asks for the smallest one.")
        if close_to(got, lam[0], 1e-6):
            raise Stop(WRONG, "A plane's maximum is at least R on the line where it meets span(v_1, v_2).")
        raise Stop(WRONG, "The maximum on a plane is the larger eigenvalue of Bᵀ M B (B: two orthonormal vectors spanning it); minimise it over planes.")
    return run_check("07-dual", show, body)


def check_interlacing(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 07-interlacing: the lower bound of the minimum over a codimension-2 subspace."""
    options = {
        "lam_0": right("R ≥ λ_0 holds for every f, but nothing forces more: some codimension-2 subspaces reach λ_0 "
                       "(explain which, below the check)."),
        "lam_1": "Find a codimension-2 subspace that contains the constant function: what is its minimum?",
    }
    return choose("07-interlacing", _canonical(answer, options), options, show)


def check_consistent_minmax(value: Any, *, show: bool = True) -> Feedback:
    """Exercise 07-consistent: min of R on the optimal subspace over λ_10, consistent mass: exactly 1."""
    throughout = ("use the consistent spectrum throughout (its `stiffness`, `mass`, and `optimal_subspace(sc, 10)`), "
                  "and divide by `sc.values[10]`.")
    number = None if unanswered(value) is not None else _finite_or_none(value)
    if number is not None and 1 + 1e-6 < number < 1.2:  # a mix of the two spectra, or λ_9 for λ_10: just above 1
        return run_check("07-consistent", show, lambda: _stop(
            "Just above 1, which Courant–Fischer rules out: divide by λ_10 (10 constraints), and take the minimum and "
            "λ_10 from the same pair (W, A), i.e. " + throughout))
    return ratio_one("07-consistent", value, "Below 1 on the optimal subspace: " + throughout,
                             "Above λ_n is impossible (Courant–Fischer): divide by `values[10]` for 10 constraints.", show)


def _finite_or_none(value: Any) -> float | None:
    try:
        return as_number(value)
    except Stop:
        return None


def _stop(message: str) -> str:
    raise Stop(WRONG, message)


def recap_min_max_judges() -> list[Any]:
    """The three judges of 07's recap (shared with its grader): t* to three significant digits."""
    t_star = float(np.degrees(np.arctan(np.sqrt(2.0))))
    return [
        _choice_question({"lam_n-1": "the bound is the eigenvalue whose index is the codimension.",
                          "lam_n": right("Courant–Fischer: n constraints cannot exclude every function of "
                                         "span(φ_0 … φ_n), and there R(f) ≤ λ_n."),
                          "lam_n+1": "the bound is the eigenvalue whose index is the codimension."}),
        _choice_question({"yes": "section 2 tilted an optimal plane and found a whole arc of maximisers.",
                          "no": right("an optimal plane tilted up to the critical angle t* keeps the optimal minimum: "
                                      "section 2 found a whole arc of maximisers.")}),
        _number_question(t_star, [(np.degrees(np.arctan(2.0)), "tan² t* is the ratio, not tan t*."),
                                  (np.degrees(np.arctan(np.sqrt(0.5))), "the ratio is (λ_2 − λ_1)/(λ_1 − λ_0), upside down?"),
                                  (np.arctan(np.sqrt(2.0)), "give degrees, not radians.")],
                         "tan² t* = (λ_2 − λ_1)/(λ_1 − λ_0); give t* in degrees."),
    ]


def check_recap_min_max(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 07: (1) the Courant–Fischer bound, (2) uniqueness, (3) a critical angle in degrees."""
    return recap("07-recap", [q1, q2, q3], recap_min_max_judges(), show)


# --- 08 · scale-invariant metrics -----------------------------------------------------------------

# --- 08-angle-defects: build it yourself ------------------------------------------------------------

DEFECT_TOL = 1e-8
"""How closely a built angle defect must agree, as a fraction of the full angle 2π at every vertex
(the defects' own scale: they are angles, and near zero on flat parts). ``atan2`` and ``arccos``
of well-shaped triangles agree with the library to about 1e-15."""


def _angles_by_hand(mesh: Any) -> np.ndarray:
    """The corner angles (m, 3), column k at ``faces[:, k]``, computed here (not the library's)."""
    p = mesh.vertices[mesh.faces]
    angles = np.empty(mesh.faces.shape)
    for k in range(3):
        a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
        angles[:, k] = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))
    return angles


def defect_slips(mesh: Any) -> tuple[np.ndarray, list[tuple[np.ndarray, str]]]:
    """The angle defects of ``mesh`` (2π − Σθ inside, π − Σθ on the boundary) and the typical
    slips, as (values, hint); a slip equal to the defects on ``mesh`` (no boundary, say) is left out."""
    from ..operators._cotangent import mass_matrix

    n, f = mesh.n_vertices, mesh.faces
    angles = _angles_by_hand(mesh)
    total = np.bincount(f.ravel(), weights=angles.ravel(), minlength=n)
    on_boundary = np.zeros(n, dtype=bool)
    on_boundary[mesh.boundary_vertices] = True
    full = np.where(on_boundary, np.pi, 2 * np.pi)
    ref = full - total
    # the angle at corner k given to the next corner's vertex instead of its own
    shifted = np.bincount(f[:, [1, 2, 0]].ravel(), weights=angles.ravel(), minlength=n)
    slips = [
        (-ref, "Wrong sign: the defect is what is *missing* from the full angle, 2π − Σθ (π − Σθ on the boundary); "
               "positive on a convex vertex."),
        (total, "Those are the angle sums Σθ: the defect is the full angle minus them, 2π − Σθ (π − Σθ on the boundary)."),
        (2 * np.pi - total, "Right inside, wrong on the boundary: a boundary vertex's full angle is π, not 2π, so its "
                            "defect is π − Σθ (a flat sheet then has defects only along its edge)."),
        (np.pi - total, "Right on the boundary, wrong inside: an interior vertex's full angle is 2π, so its defect is "
                        "2π − Σθ."),
        (np.degrees(ref), "Those are degrees: give the angles in radians (360° is 2π)."),
        (full - shifted, "Each angle belongs to the vertex at its corner: the angle at corner k of a face is the one "
                         "between the two edges leaving `faces[:, k]`."),
        (full - total / 2, "Half the angle sums: add every angle once, the whole angle at its corner."),
    ]
    for kind in ("voronoi", "barycentric"):
        slips.append((ref / mass_matrix(mesh, kind).diagonal(),
                      "That is the curvature δ_i / a_i: the exercise asks for the defect itself, not divided by any area."))
    scale = 2 * np.pi * DEFECT_TOL
    return ref, [(v, hint) for v, hint in slips if np.abs(v - ref).max() > scale]


def _defect_values(value: Any, n: int, n_faces: int) -> np.ndarray:
    """The returned defects as a float array of shape (n,), or Stop with what is wrong with its form."""
    values = as_array(value, "a NumPy array of n angle defects, one per vertex", finite=False)
    if values.shape in ((n, 1), (1, n)):
        values = values.ravel()
    if values.shape == (n_faces, 3) and n_faces != n:
        raise Stop(WRONG, "One value per corner of each face (m × 3): sum each vertex's corner angles into one "
                          "value per vertex (`np.bincount` or `np.add.at` with `mesh.faces.ravel()`).")
    if values.shape == (n, n):
        raise Stop(WRONG, f"Return a 1-D array of n = {n} values, not an n × n matrix.")
    if values.shape != (n,):
        raise Stop(WRONG, f"Return one value per vertex, a NumPy array of shape ({n},); got shape {values.shape}.")
    if not np.all(np.isfinite(values)):
        raise Stop(WRONG, "NaN or infinity in your defects: `np.arccos` of a cosine a hair above 1? Clip it to [−1, 1], "
                          "or take θ = atan2(‖a × b‖, a · b).")
    return values


def judge_angle_defects(function: Any, meshes: Any, call: Any = call_attempt) -> str:
    """The message of a correct ``function(mesh)`` on every ``(mesh, where)`` of ``meshes``
    (``call(function, mesh)`` runs it), else Stop with the hint of the first mesh where it is wrong."""
    for mesh, where in meshes:
        got = _defect_values(call(function, mesh), mesh.n_vertices, mesh.n_faces)
        ref, slips = defect_slips(mesh)
        scale = 2 * np.pi * DEFECT_TOL
        error = np.abs(got - ref)
        if error.max() <= scale:
            continue
        for slip, hint in slips:
            if np.abs(got - slip).max() <= scale:
                raise Stop(WRONG, f"{hint} (seen on {where}.)")
        total = 2 * np.pi * mesh.euler_characteristic
        if abs(got.sum() - total) <= scale * mesh.n_vertices:
            raise Stop(WRONG, f"The total is right (Gauss–Bonnet: 2πχ) but not every vertex is (seen on {where}): take "
                              "θ = atan2(‖a × b‖, a · b) with a, b the two edges leaving the corner.")
        on_boundary = np.zeros(mesh.n_vertices, dtype=bool)
        on_boundary[mesh.boundary_vertices] = True
        if on_boundary.any() and error[~on_boundary].max() <= scale:
            raise Stop(WRONG, f"Right inside, wrong on the boundary (seen on {where}): there the defect is π − Σθ.")
        raise Stop(WRONG, f"Not the angle defects (seen on {where}): at each corner θ = atan2(‖a × b‖, a · b), a and b "
                          "the two edges leaving it; sum each vertex's angles, and subtract the sum from 2π (π on the "
                          "boundary).")
    return ("Right: the angle defects, 2π − Σθ inside and π − Σθ on the boundary, on closed and open meshes alike.")


def _visible_defect_meshes() -> list[tuple[Any, str]]:
    """What the visible check of 08-angle-defects runs on: a right triangle, an irregular closed
    surface and a curved open sheet."""
    from .. import shapes
    from ..geometry._mesh import Mesh

    rng = np.random.default_rng(808)
    triangle = Mesh([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]])
    ball = shapes.icosphere(1)
    blob = ball.with_vertices(ball.vertices * rng.uniform(0.85, 1.2, size=(ball.n_vertices, 1)))
    sheet = shapes.rectangle(2.0, 1.0, 5, 3)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.1, 0.1, size=(len(v), 2))
    v[:, 2] = 0.3 * np.sin(2 * v[:, 0]) * v[:, 1]
    return [(triangle, "a right triangle"), (blob, f"an irregular closed surface of {blob.n_vertices} vertices"),
            (sheet.with_vertices(v), f"a curved open sheet of {sheet.n_vertices} vertices")]


def check_angle_defects(angle_defects: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-angle-defects: the student's ``angle_defects(mesh)``, one angle defect per vertex.

    Run on a right triangle, an irregular closed surface and a curved open sheet; the hint names the
    first thing that differs (a sign, the boundary rule, degrees, a division by the vertex area, ...).

    Examples
    --------
    >>> from lbo_notebooks.operators import angle_defects
    >>> check_angle_defects(angle_defects, show=False).correct
    True
    >>> print(check_angle_defects(lambda mesh: -angle_defects(mesh), show=False).message.split(":")[0])
    Wrong sign
    """
    def body() -> str:
        return judge_angle_defects(angle_defects, _visible_defect_meshes())
    return run_check("08-angle-defects", show, body)


def check_gauss_bonnet(torus: Any, disk: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-gauss-bonnet: Σ K_i a_i for a torus and a disk (2πχ)."""
    def body() -> str:
        require_attempt([torus, disk])
        t, d = as_number(torus), as_number(disk)
        two_pi = 2 * np.pi
        tol = 1e-6 * two_pi
        disk_is = _precision(d, two_pi, tol, 3)  # 2π rounded by hand to 6.28 is right, to 6.3 too coarse
        if abs(t) <= tol and disk_is == "right":
            return "Right: Σ K_i a_i = 2πχ, with χ = 0 for the torus and 1 for the disk."
        if abs(t) <= tol and close_to(d, 1, 1e-6):
            raise Stop(WRONG, "Those look like Euler characteristics: the total curvature is 2π times χ.")
        if abs(t) > tol:
            raise Stop(WRONG, "The torus: count V − E + F of a square grid wrapped around both ways (each square is two triangles).")
        if disk_is == "coarse":
            raise Stop(WRONG, _more_digits(3, "The torus is right; the disk"))
        raise Stop(WRONG, "The disk: χ = V − E + F of a flat triangulated disk (one triangle will do), times 2π.")
    return run_check("08-gauss-bonnet", show, body)


def check_curvature_scaling(factor: Any, scale: float = 3.0, *, show: bool = True) -> Feedback:
    """Exercise 08-curvature: the factor by which Gaussian curvature changes when a shape is scaled by ``scale``."""
    def body() -> str:
        require_attempt(factor)
        got = as_number(factor)
        verdict = _precision(got, scale**-2, 1e-6 * scale**-2, 3)  # 0.111 for 1/9 is right, 0.11 too coarse
        if verdict == "right":
            return "Right: K = 1/(R₁R₂), two lengths in the denominator; the angle defect is unchanged and the area grows by s²."
        if _near(got, 1 / scale):
            raise Stop(WRONG, "K is a product of two principal curvatures, each 1/length: think of 1/R² on a sphere.")
        if _near(got, scale**2) or _near(got, scale):
            raise Stop(WRONG, "Upside down: a bigger sphere is flatter.")
        if close_to(got, 1.0, 1e-6):
            raise Stop(WRONG, "The angle defect does not change, but K is the defect per unit area.")
        if verdict == "coarse":
            raise Stop(WRONG, _more_digits(3))
        raise Stop(WRONG, "K_i = δ_i / a_i: how do the angle defect δ_i and the vertex area a_i change?")
    return run_check("08-curvature", show, body)


def check_metric_scaling(factors: Any, scale: float = 3.0, *, show: bool = True) -> Feedback:
    """Exercise 08-scaling: ``{alpha: factor}``, how the eigenvalues of ``|K|^alpha g`` change under scaling by ``scale``."""
    def body() -> str:
        require_attempt(factors)
        asked = (0.0, 0.4, 1.0)
        answer = factors
        sequence = isinstance(answer, (list, tuple)) or isinstance(answer, np.ndarray) and answer.ndim == 1
        if sequence and len(answer) == len(asked):
            answer = dict(zip(asked, answer))  # three factors in the order of the question
        if not isinstance(answer, Mapping) or not answer:
            raise Stop(WRONG, "Give a dict {alpha: new eigenvalue / old eigenvalue}.")
        given = []
        for alpha, got in answer.items():
            try:
                a = float(alpha)
            except (TypeError, ValueError):
                a = float("nan")
            if not np.isfinite(a):
                raise Stop(WRONG, f"The keys are the values of α (numbers, as in the question); {alpha!r} is not one.")
            given.append(a)
            got = as_number(got, f"a number for alpha = {alpha}")
            ref = scale ** (-2 * (1 - a))
            verdict = _precision(got, ref, 1e-6 * ref, 3)  # rounded by hand to 3 significant digits: right
            if verdict == "right":
                continue
            if a != 1 and _near(got, 1 / ref):
                raise Stop(WRONG, f"alpha = {alpha}: upside down. A_α grows, so the eigenvalues of W φ = λ A_α φ shrink.")
            if a != 1 and _near(got, scale ** -(1 - a)):
                raise Stop(WRONG, f"alpha = {alpha}: areas scale by s², not s.")
            if a != 0 and _near(got, scale**-2):
                raise Stop(WRONG, f"alpha = {alpha}: that is the regular metric's factor; ρ shrinks by s⁻² too, and A_α holds ρ^α.")
            if a != 1 and close_to(got, 1.0, 1e-6):
                raise Stop(WRONG, f"alpha = {alpha}: only α = 1 cancels the area's s² completely.")
            if verdict == "coarse":
                raise Stop(WRONG, _more_digits(3, f"alpha = {alpha}: the factor"))
            raise Stop(WRONG, f"alpha = {alpha}: W does not change; A_α = diag(ρ^α a) with a → s² a and ρ → s⁻² ρ.")
        missing = [a for a in asked if not any(abs(g - a) <= 1e-9 for g in given)]
        if missing:
            raise Stop(WRONG, "Right so far; now give the factor for every α the exercise asks: "
                              + ", ".join(f"{a:g}" for a in missing) + " missing.")
        return "Right: A_α grows by s^(2(1−α)), so λ scales by s^(−2(1−α)); α = 1 is exactly invariant."
    return run_check("08-scaling", show, body)


def check_best_alpha(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-best: which α rebuilds the most curved 10% of the horse best (0, 0.4 or 1)."""
    options = {"0": "The regular basis spreads its functions evenly by area; the curved 10% has little area.",
               "0.4": "A compromise is rarely the best at one extreme: which metric gives the curved tips the most area?",
               "1": right("|K| g gives the curved tips most of its area, so its eigenbasis spends its functions there.")}

    def body() -> str:
        require_attempt(answer)
        try:
            key = f"{float(answer):g}"
        except (TypeError, ValueError):
            key = str(answer).strip()
        if key not in options:
            raise Stop(WRONG, "Answer with one of: 0, 0.4, 1.")
        if not isinstance(options[key], right):
            raise Stop(WRONG, options[key])
        return f"Right: {options[key]}"
    return run_check("08-best", show, body)


def check_floor_fraction(fraction: Any, mesh: Any, floor: float = 1.0, *, show: bool = True) -> Feedback:
    """Exercise 08-floor: the fraction of vertices at the curvature floor ``floor``."""
    from ..operators._curvature import metric_curvature

    def body() -> str:
        require_attempt(fraction)
        got = as_number(fraction)
        level = floor * 4 * np.pi / mesh.area
        at_floor = metric_curvature(mesh, floor=floor) <= level * (1 + 1e-12)
        ref = float(np.mean(at_floor))
        # Right when it names the vertex count: within half a vertex (0.1517 for 613 of 4040, not 0.152).
        half = 0.5 / at_floor.size
        decimals = int(np.ceil(np.log10(2 * at_floor.size)))
        if abs(got - ref) <= half:
            return "Right: that is the share of vertices whose one-ring |K| is below the floor."
        if abs(got - 100 * ref) <= 100 * half or _rounding_of(got, 100 * ref) is not None and got > 1:
            raise Stop(WRONG, "That is a percentage; give a fraction between 0 and 1.")
        if abs(got - (1 - ref)) <= half or (_rounding_of(got, 1 - ref) or 0) >= 2:
            raise Stop(WRONG, "That is the fraction *above* the floor.")
        if got == 0 and ref > 0:
            raise Stop(WRONG, "None at the floor? The floor value is `curvature_floor` × 4π / area, not `curvature_floor` itself; compare "
                              "with a tolerance (`np.isclose`, or `<=` the floor times 1 + 1e-12), not `==`: it is computed in floating point.")
        if got > 1 and abs(got - at_floor.sum()) <= 0.5:
            raise Stop(WRONG, "That is the number of vertices at the floor; give the fraction (divide by the number of vertices).")
        if _rounding_of(got, ref) is not None:
            raise Stop(WRONG, f"That is rounded too coarsely to name one count of vertices: give more digits (at least {decimals} "
                              "decimals), or let Python compute it.")
        raise Stop(WRONG, f"Compare `curvature.metric_curvature(mesh, floor={floor:g})` with the floor value {floor:g} · 4π / area (vertices at the floor equal it).")
    return run_check("08-floor", show, body)


def check_sphere_alpha(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-sphere: how the α = 1 eigenvalues of the unit sphere compare with the regular ones."""
    options = {
        "equal": right("On the unit sphere |K|^α = 1, so g_α = |K|^α g is the regular metric itself, up to the mesh's "
                       "estimate of K."),
        "scaled": "What is |K|^α on the unit sphere, and so what does g_α = |K|^α g become?",
        "unrelated": "What is |K|^α on the unit sphere, and so what does g_α = |K|^α g become?",
    }
    return choose("08-sphere", _canonical(answer, options), options, show)


def check_consistent_invariance(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-consistent: is the consistent (per-triangle) α = 1 metric scale-invariant too?"""
    options = {
        "yes": right("Scaling by s multiplies a triangle's area by s² and its ρ_t by s^(−2), so ρ_t × area is "
                     "unchanged, and W is unchanged too."),
        "no": "Scaling by s: what happens to a triangle's area, to its ρ_t, and so to ρ_t × area?",
    }
    return choose("08-consistent", _canonical(answer, options), options, show)


def check_recap_scale_invariant(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 08: (1) K of a sphere of radius 2, (2) what α changes, (3) which spectrum is steadier under poses."""
    return recap("08-recap", [q1, q2, q3], recap_scale_invariant_judges(), show)


def recap_scale_invariant_judges() -> list[Any]:
    """The three judges of 08's recap (shared with its grader)."""
    return [
        _number_question(0.25, [(0.5, "K is 1/R², not 1/R."), (4.0, "upside down: a bigger sphere is flatter.")],
                         "K = 1/R² on a sphere of radius R.", digits=2),
        _choice_question({"w": "the Dirichlet energy is conformally invariant in 2-D: the cotangent weights do not change.",
                          "a": right("the Dirichlet energy is conformally invariant in 2-D, so W_α = W and only the "
                                     "mass A_α changes."),
                          "both": "the Dirichlet energy is conformally invariant in 2-D: one of the two does not change."}),
        _choice_question({"regular": right("the poses stretch the joints a little and |K|, a second derivative, "
                                           "amplifies it: the scale-invariant spectrum moved about three to thirty times more."),
                          "scale-invariant": "section 6 measured it: the poses stretch the joints a little and |K| amplifies it."}),
    ]
