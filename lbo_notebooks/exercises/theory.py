"""Self-checks of notebooks 05 and 06 (optimality: the theorem, then the worst-case constant and ties;
07 and 08 are in :mod:`~lbo_notebooks.exercises.minmax_and_metrics`).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

import re
from functools import lru_cache
from collections.abc import Mapping
from typing import Any

import numpy as np

from .feedback import (
    ratio_one,
    pick, number_judge, recap,
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, call_attempt, close_to, choose, right,
)
from .basics import WrappedReasons

__all__ = [
    "check_projection",
    "check_energy_bound",
    "check_shifted_basis",
    "check_consistent_optimality",
    "check_extra_function",
    "check_worst_ratio",
    "check_worst_case",
    "check_recap_optimality",
    "check_stationary_frame",
    "check_recap_ties",
]



def _vector(x: Any, what: str) -> np.ndarray:
    try:
        value = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError):
        raise Stop(WRONG, f"Expected {what}, got {type(x).__name__}.") from None
    if value.ndim != 1 or not np.all(np.isfinite(value)):
        raise Stop(WRONG, f"Expected {what} (a finite 1-D array), got shape {value.shape}.")
    return value


# --- 05–06 · the optimality theorem -------------------------------------------------------------------

MORE_DIGITS = ("Right to the digits you typed, but too coarse to grade: give more digits (the computed value "
               "itself, or at least 7 significant digits).")


def _typed_unit(value: float) -> float | None:
    """The unit of the last digit of ``value`` as typed by hand (0.0123 -> 1e-4, 1200 -> 100), or None
    when it shows 12 or more significant digits (a computed value, not a typed one)."""
    text = np.format_float_positional(abs(float(value)), unique=True, trim="-")
    digits = text.replace(".", "").lstrip("0")
    if not digits or len(digits) >= 12:
        return None
    if "." in text:
        return 10.0 ** -len(text.split(".")[1])
    return 10.0 ** (len(text) - len(text.rstrip("0")))


def rounded_from(value: float, ref: float) -> bool:
    """Whether ``value`` is ``ref`` rounded, or cut, to the digits it shows: a hand-copied value right
    to its digits, for which "give more digits" (:data:`MORE_DIGITS`) is the hint, not one about the method.

    Examples
    --------
    >>> rounded_from(0.0098, 0.00977483), rounded_from(0.0097, 0.00977483), rounded_from(0.0099, 0.00977483)
    (True, True, False)
    """
    unit = _typed_unit(value)
    if unit is None or value == 0 or np.sign(value) != np.sign(ref):
        return False
    gap = (value - ref) * np.sign(ref)  # |value| - |ref|: a cut value lies below, a rounded one within half a unit
    return bool(-unit * (1 - 1e-9) < gap <= unit / 2 * (1 + 1e-9))

def projection_slip(p: Any, phi: np.ndarray, mass: Any, f: np.ndarray, n: int) -> str | None:
    """None when ``p`` is the A-orthogonal projection Φ_n Φ_nᵀ A f of ``f``; else the hint that names
    the slip (Euclidean inner product, coefficients instead of the projection, wrong n, ...)."""
    try:
        p = np.asarray(p, dtype=np.float64)
    except Exception:  # noqa: BLE001 - whatever the function returned
        return f"Return an array (one value per vertex), got {type(p).__name__}."
    n_vertices = phi.shape[0]
    if p.shape in ((n_vertices, 1), (1, n_vertices)):
        p = p.ravel()  # a column (or row) of values per vertex is one value per vertex too
    Af = mass @ f
    c = phi[:, :n].T @ Af
    ref = phi[:, :n] @ c
    scale = max(np.linalg.norm(ref), 1e-300)

    def near(other: np.ndarray) -> bool:
        return p.shape == other.shape and bool(np.linalg.norm(p - other) <= 1e-8 * max(scale, np.linalg.norm(other)))
    if p.shape == (n,):
        if near(c):
            return "Those are the n coefficients c = Φ_nᵀ A f; the projection is the function they describe, Φ_n c (one value per vertex)."
        if near(phi[:, :n].T @ f):
            return "Those are coefficients, and with the Euclidean inner product Φ_nᵀ f: return the projection Φ_n c, with c = Φ_nᵀ A f."
    if p.shape != (n_vertices,):
        return f"Return one value per vertex, shape ({n_vertices},); got shape {p.shape}."
    if near(ref):
        return None
    if near(phi[:, :n] @ (phi[:, :n].T @ f)):
        return "That is Φ_n Φ_nᵀ f, the Euclidean inner product: the eigenvectors are A-orthonormal, so the coefficients are Φ_nᵀ A f."
    diagonal = np.asarray(mass.diagonal(), dtype=np.float64)
    if np.all(diagonal > 0) and near(phi[:, :n] @ (phi[:, :n].T @ (f / diagonal))):
        return "You divided by the vertex areas; the A inner product multiplies by them (`spectrum.mass @ f`)."
    if near(mass @ (phi[:, :n] @ (phi[:, :n].T @ f))):
        return "The mass matrix is in the wrong place: A multiplies f inside the coefficients, Φ_nᵀ (A f), not the result."
    for m, hint in ((n + 1, "one eigenfunction too many"), (n - 1, "one eigenfunction too few")):
        if near(phi[:, :m] @ (phi[:, :m].T @ Af)):
            return f"Off by one ({hint}): the first n eigenfunctions are φ_0 .. φ_(n-1), `vectors[:, :n]`."
    if near(phi[:, 1:n + 1] @ (phi[:, 1:n + 1].T @ Af)) or near(phi[:, 1:n] @ (phi[:, 1:n].T @ Af)):
        return "You left out φ_0, the constant: it is the first of the n eigenfunctions (indices from 0)."
    if near(phi @ (phi.T @ Af)):
        return "You used every eigenfunction the spectrum has; use only the first n."
    if near(f - ref):
        return "That is the error f − P_n f; return the projection P_n f itself."
    return f"Not the A-orthogonal projection (first seen with n = {n}): coefficients c = Φ_nᵀ A f, then Φ_n c."


def projection_call_stop(stop: Stop) -> Stop:
    """A call of the student's projection that failed: a shape error gets the transposes hint."""
    if stop.status == WRONG and re.search(r"shape|mismatch|align|dimension", stop.message):
        return Stop(WRONG, stop.message + " Check the transposes: Φ_n = `vectors[:, :n]` is (vertices × n), "
                    "the coefficients are Φ_nᵀ (A f), one per eigenfunction, and the projection Φ_n times them.")
    return stop


def check_projection(project: Any, spectrum: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-projection: the student's ``project(spectrum, f, n)``, the A-orthogonal projection P_n f.

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
                p = call_attempt(project, spectrum, f, n)
            except Stop as stop:
                raise projection_call_stop(stop) from None
            hint = projection_slip(p, phi, mass, f, n)
            if hint is not None:
                raise Stop(WRONG, hint)
        return "Right: P_n f = Φ_n Φ_nᵀ A f, and its error f − P_n f is A-orthogonal to φ_0 .. φ_(n-1)."
    return run_check("05-projection", show, body)


def check_energy_bound(value: Any, spectrum: Any, f: Any, n: int, *, show: bool = True) -> Feedback:
    """Exercise 05-bound: the theorem's bound f^T W f / λ_n for ``f`` after ``n`` terms (0-based λ)."""
    def body() -> str:
        require_attempt(value)
        got = as_number(value)
        g = np.asarray(f, dtype=np.float64)
        lam = np.asarray(spectrum.values)
        energy, norm2 = float(g @ (spectrum.stiffness @ g)), float(g @ (spectrum.mass @ g))
        ref = energy / lam[n]
        if close_to(got, ref, 1e-6):
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
            if close_to(got, slip, 1e-6):
                raise Stop(WRONG, hint)
        if rounded_from(got, ref):
            raise Stop(WRONG, MORE_DIGITS)
        raise Stop(WRONG, "The bound is fᵀ W f / λ_n: the Dirichlet energy (W = `spectrum.stiffness`) over `values[n]`.")
    return run_check("05-bound", show, body)


def check_shifted_basis(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-shifted: C(V) λ_n for V = span(φ_1 .. φ_n), the eigenbasis without the constant."""
    return choose("06-shifted", answer, {
        "below": "Nothing is below 1: the theorem holds for every n-dimensional V.",
        "one": "Equality needs the *right* n functions. Which function of zero energy is missing from V, and what is its error?",
        "above": "Think of the worst function: one of zero energy that V cannot represent at all. What is error / energy for it?",
        "infinite": right("The constant has zero energy and is A-orthogonal to V, so V misses all of it: a nonzero "
                          "error over zero energy."),
    }, show)


def check_consistent_optimality(value: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-consistent: C(V) λ_n of the consistent-mass eigenbasis for its own (W, A): exactly 1."""
    return ratio_one(
        "06-consistent", value,
        "Below 1 is impossible (the theorem): is λ_n `values[n]`, with n the number of basis functions?",
        "The eigenbasis is optimal for the pair it solves: pass the consistent spectrum's own `stiffness` and `mass` "
        "to `worst_case_ratio`, and multiply by its `values[n]`.", show)


def check_extra_function(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-extra: where V = span(Φ_n, g) sits, between Φ_n and Φ_(n+1)."""
    return choose("05-extra", answer, {
        "beats": "V has n + 1 functions: the theorem for n + 1 says no (n + 1)-dimensional space beats Φ_(n+1).",
        "between": right("V contains span Φ_n, so C(V) ≤ 1/λ_n, and no (n + 1)-dimensional space beats Φ_(n+1), so "
                         "C(V) ≥ 1/λ_(n+1)."),
        "worse": "V contains span Φ_n: projecting onto a larger space never increases the error.",
    }, show)


def check_worst_ratio(ratio: Any, basis: Any, stiffness: Any, mass: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-worst: the error / energy of the worst function of ``basis``, which must equal C(V)."""
    from ..analyses._optimality import worst_case_ratio

    def body() -> str:
        require_attempt(ratio)
        got = as_number(ratio)
        c, worst = worst_case_ratio(basis, stiffness, mass, return_vector=True)
        Q = np.asarray(basis)
        energy = float(worst @ (stiffness @ worst))

        def a_norm2(x: np.ndarray) -> float:
            return float(x @ (mass @ x))
        if close_to(got, c, 1e-6):
            return "Right: the worst function attains the supremum, error / energy = C(V)."
        for slip, hint in (
            (a_norm2(worst - Q @ (Q.T @ worst)) / energy, "The projection needs the A inner product: P_V f = Q Qᵀ A f."),
            (a_norm2(worst) / energy, "That is ‖f‖²_A / energy: the error is of f − P_V f, what the basis misses."),
            (1 / c, "Upside down: error over energy."),
        ):
            if close_to(got, slip, 1e-6):
                raise Stop(WRONG, hint)
        if rounded_from(got, c):
            raise Stop(WRONG, MORE_DIGITS)
        if got > c:
            raise Stop(WRONG, "Above C(V), which is a supremum: check the error ‖f − P_V f‖²_A (A-norm) and the energy fᵀ W f.")
        raise Stop(WRONG, "Below C(V): use the function `worst_case_ratio(..., return_vector=True)` returns, and the A-norm of f − P_V f.")
    return run_check("06-worst", show, body)


# --- 06 · the worst-case constant from the Schur complement (exercise 06-schur) --------------------

WORST_RTOL = 1e-6
"""How close a built C(V) must come to the exact one (relative); the dense Schur route gives 1e-10."""

def _dense_pencil_parts(V: np.ndarray, W: Any, A: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(Wd, Ad, Q, S): dense W and A, an A-orthonormal Q of span V and the Schur complement S."""
    from ..spectral._inner_product import a_orthonormalize

    Wd, Ad = W.toarray(), A.toarray()
    Q = a_orthonormalize(V, A)
    WQ = Wd @ Q
    S = Wd - WQ @ np.linalg.pinv(Q.T @ WQ, hermitian=True) @ WQ.T
    return Wd, Ad, Q, (S + S.T) / 2


def _reciprocal_min(left: np.ndarray, right: np.ndarray) -> float:
    """1 / (smallest eigenvalue of the pencil (left, right)), infinite for a zero minimum."""
    import scipy.linalg

    mu = float(scipy.linalg.eigh((left + left.T) / 2, (right + right.T) / 2, eigvals_only=True, subset_by_index=[0, 0])[0])
    return np.inf if mu <= 1e-12 * max(np.abs(np.diag(left)).max(), 1e-300) else 1.0 / mu


def worst_case_slips(V: np.ndarray, W: Any, A: Any) -> list[tuple[float, str]]:
    """The values of the usual wrong routes to C(V) (small meshes, dense), each with its hint."""
    import scipy.linalg

    Wd, Ad, Q, S = _dense_pencil_parts(V, W, A)
    Z = scipy.linalg.null_space((Ad @ Q).T)  # the A-orthogonal complement of V
    Ze = scipy.linalg.null_space(Q.T)  # the Euclidean one
    return [
        (_reciprocal_min(Z.T @ Wd @ Z, Z.T @ Ad @ Z),
         "That is the trap: W on the complement of V is the energy of r alone. Minimise the energy of r + v over v in "
         "V first: the Schur complement S = W − WQ(QᵀWQ)⁺QᵀW."),
        (_reciprocal_min(Ze.T @ S @ Ze, Ze.T @ Ad @ Ze),
         "The complement must be A-orthogonal to V (Qᵀ A r = 0), not Euclidean-orthogonal (Qᵀ r = 0)."),
        (_reciprocal_min(Z.T @ S @ Z, Z.T @ Z),
         "The error is measured in the A-norm: divide by rᵀ A r, not by rᵀ r."),
    ]


def _worst_case_where(value: float, ref: float, V: np.ndarray, W: Any, A: Any, pieces: int) -> str | None:
    """None when ``value`` is C(V) = ``ref`` (``numpy.inf`` itself when it is infinite, as the prompt
    asks), else the hint."""
    if np.isnan(value):
        return "Your C(V) is NaN."
    if np.isinf(ref):
        if value == np.inf:
            return None
        if value < 0:
            return ("C(V) is never negative. Here the minimum of rᵀSr / rᵀAr is zero (to round-off, maybe a tiny negative "
                    "number): W's kernel is not in V, and C(V) = ∞. Return `np.inf` then.")
        if pieces > 1:
            return ("On a mesh of several pieces, W's kernel holds the constant of each piece (zero energy on each one): when "
                    "one of them is not in V, C(V) = ∞. Return `np.inf` then.")
        return ("The constant function is not in V here: it has zero energy and a nonzero error, so C(V) = ∞. Return "
                "`np.inf` then (a huge finite 1/μ from a μ that is zero to round-off is not it).")
    if np.isinf(value):
        return "C(V) is finite here: W's kernel (the constant on each piece of the mesh) lies in V."
    if value <= 0:
        return "C(V) is a ratio of an error and an energy, both ≥ 0, and it is finite here: positive."
    if abs(value - ref) <= WORST_RTOL * ref:
        return None
    if abs(1 / value - ref) <= WORST_RTOL * ref:
        return "Upside down: C(V) = 1/μ, μ the smallest eigenvalue of the Schur pencil."
    for slip, hint in worst_case_slips(V, W, A):
        if np.isfinite(slip) and abs(value - slip) <= WORST_RTOL * slip:
            return hint
    return ("Not C(V): with Q an A-orthonormal basis of V, 1/C(V) is the smallest eigenvalue μ of (ZᵀSZ) y = μ (ZᵀAZ) y, "
            "S = W − WQ(QᵀWQ)⁺QᵀW and Z a basis of the A-orthogonal complement of V.")


def judge_worst_case(worst_case: Any, problems: Any, call: Any = call_attempt, seen: str = "first seen on {}") -> str:
    """The message of a correct ``worst_case(W, A, V)`` on every ``(W, A, V, where)`` of ``problems``
    (``call(worst_case, W, A, V)`` runs it, on copies), else Stop with the first miss's hint and
    ``seen`` formatted with its ``where``. The exact C(V) is ``worst_case_ratio``'s (dense)."""
    from ..analyses._optimality import kernel_basis, worst_case_ratio

    problems = list(problems)
    refs = [worst_case_ratio(V, W, A, method="dense") for W, A, V, _ in problems]
    for (W, A, V, where), ref in zip(problems, refs):
        got = call(worst_case, W.copy(), A.copy(), np.array(V))
        if isinstance(got, (tuple, list)) and len(got) == 2:
            raise Stop(WRONG, f"Return C(V) alone, one number (a float), not a pair. ({seen.format(where)}.)")
        value = as_number(got, "C(V), a float (`np.inf` when it is infinite)") if not (
            isinstance(got, (float, np.floating)) and np.isinf(got)) else float(got)
        hint = _worst_case_where(value, ref, np.asarray(V, dtype=np.float64), W, A, kernel_basis(W).shape[1])
        if hint is not None:
            raise Stop(WRONG, f"{hint} ({seen.format(where)}.)")
    return ("Right: C(V) from the Schur complement, for the eigenbasis (the optimum 1/λ_n), perturbed and other bases, "
            "and ∞ when V misses W's kernel.")


@lru_cache(maxsize=1)
def _worst_case_problems() -> tuple[tuple[Any, Any, np.ndarray, str], ...]:
    """The (W, A, V, where) the visible check of 06-schur runs on: a small torus with its first six
    eigenvectors mixed by an invertible matrix (C(V) = 1/λ_6), the same perturbed (the constant
    kept), and eigenvectors 1..6 (no constant: C(V) = ∞)."""
    import scipy.linalg

    from .. import shapes
    from ..operators._cotangent import mass_matrix, stiffness_matrix

    ring = shapes.torus(n_major=16, n_minor=8)
    W, A = stiffness_matrix(ring), mass_matrix(ring)
    _, phi = scipy.linalg.eigh(W.toarray(), A.toarray(), subset_by_index=[0, 7])
    rng = np.random.default_rng(606)
    mixed = phi[:, :6] @ (np.eye(6) + 0.3 * rng.normal(size=(6, 6)))
    perturbed = phi[:, :6].copy()
    perturbed[:, 1:] += 0.3 * np.abs(phi[:, 1:6]).mean() * rng.normal(size=(ring.n_vertices, 5))
    where = f"a torus of {ring.n_vertices} vertices"
    return ((W, A, mixed, f"{where}, its first six eigenvectors mixed"),
            (W, A, perturbed, f"{where}, a perturbed eigenbasis"),
            (W, A, phi[:, 1:7], f"{where}, eigenvectors 1 to 6"))


def check_worst_case(worst_case: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-schur: the student's ``my_worst_case(W, A, V)``, the exact C(V) from the Schur complement.

    Run on a small torus: the eigenbasis in a mixed-up basis (C(V) = 1/λ_6), a perturbed one, and
    one without the constant (C(V) = ∞); the hint names the usual wrong routes (the trap that
    uses W instead of the Schur complement, a Euclidean complement or norm, 1/C).

    Examples
    --------
    >>> from lbo_notebooks.analyses._optimality import worst_case_ratio
    >>> check_worst_case(lambda W, A, V: worst_case_ratio(V, W, A), show=False).correct
    True
    >>> check_worst_case(lambda W, A, V: 1 / worst_case_ratio(V, W, A), show=False).status
    'wrong'
    """
    return run_check("06-schur", show, lambda: judge_worst_case(worst_case, _worst_case_problems()))


def _words(answer: Any, synonyms: Mapping[str, Any] | None = None) -> Any:
    """A recap answer as the judges compare it: ``True``/``False`` as "yes"/"no", a string lower-case
    with single spaces, without a leading article or a trailing "bound", then mapped by ``synonyms``;
    anything else unchanged."""
    if isinstance(answer, (bool, np.bool_)):
        return "yes" if answer else "no"
    if not isinstance(answer, str):
        return answer
    key = re.sub(r"(?<=[a-z])-(?=[a-z])", " ", " ".join(answer.lower().split()))
    key = re.sub(r"^(an?|the) ", "", key)
    key = re.sub(r" bound$", "", key)
    return (synonyms or {}).get(key, key)


def _lenient(judge: Any, synonyms: Mapping[str, Any] | None = None) -> Any:
    def lenient_judge(answer: Any) -> str | None:
        return judge(_words(answer, synonyms))
    # recap looks a reason up by the answer as text: "true"/"false" are the booleans' yes/no.
    lenient_judge.reasons = WrappedReasons(  # type: ignore[attr-defined]
        judge, lambda key: _words({"true": True, "false": False}.get(key, key), synonyms))
    return lenient_judge


RECAP_OPTIMALITY = (
    number_judge(10, [(9, "after 10 terms φ_0 .. φ_9 are used; the bound divides by the first one left out."),
                      (11, "indices start at 0: count again which eigenvalue is the first one left out.")],
                 "the first eigenvalue whose eigenfunction is left out, in 0-based indexing."),
    _lenient(pick({"tight": "noise has a huge Dirichlet energy; compare the bound with ‖f‖²_A itself.",
                   "vacuous": right("white noise has a huge Dirichlet energy: fᵀWf / λ_n exceeds ‖f‖²_A, which bounds "
                                    "the error anyway."),
                   "violated": "the bound holds for every function, smooth or not."})),
    _lenient(pick({"yes": "the witness argument only counts conditions: n of them cannot kill an (n + 1)-dimensional span, "
                          "orthonormal basis or not (section 7 checks a non-orthonormal one).",
                   "no": right("the witness only needs n conditions on an (n + 1)-dimensional span, whatever the n "
                               "functions; section 7 checks a non-orthonormal expansion.")})),
)
"""The judges of the three questions of 05-recap (each: None when right, else the hint)."""


def check_recap_optimality(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 05 (the theorem): (1) which `values[...]` after 10 terms, (2) the bound for white
    noise, (3) whether the witness argument needs an orthonormal basis."""
    return recap("05-recap", [q1, q2, q3], list(RECAP_OPTIMALITY), show)


def check_stationary_frame(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-stationary: how the excess total energy of a perturbed eigenframe grows when the noise doubles."""
    return choose("06-stationary", answer, {
        "same": "The excess is zero without noise and positive with it, so it must grow with ε: how fast, near a minimum?",
        "double": "That would be first order in ε; at a minimum the first-order change of the energy vanishes.",
        "quadruple": right("The eigenframe minimises the total energy, so the first-order change vanishes and the "
                           "excess grows like ε²: twice the noise, about four times the excess."),
        "eightfold": "Near a minimum the leading change is the second-order term, not a third-order one.",
    }, show)


_POWERS = {"linear": 1, "first": 1, "first order": 1, "linearly": 1, "quadratic": 2, "quadratically": 2,
           "second": 2, "second order": 2, "squared": 2, "square": 2, "2nd": 2, "1st": 1, "θ^2": 2, "θ²": 2}

RECAP_TIES = (
    _lenient(pick({"yes": "section 3 found an interval of tilted eigenbases that tie, none of them an eigenspace.",
                   "no": right("the tilted eigenbases of section 3, span(φ_0 … φ_{n−2}, φ_{n−1} + ε φ_m), tie for an "
                               "interval of ε, and none of them is an eigenspace.")})),
    _lenient(pick({"exactly": "it ignores the part of f inside V, which can cancel energy: exact only in special cases.",
                   "lower": right("using W instead of the Schur complement ignores the part of f inside V, which can "
                                  "cancel energy: the ratio it maximises never exceeds C(V)."),
                   "upper": "ignoring the part of f inside V can only overestimate the energy of the worst function."}),
             {"exact": "exactly"}),
    _lenient(number_judge(2, [(1, "a first-order tilt does not change the error of the worst functions (they are A-orthogonal to V)."),
                              (4, "that is the factor when the angle doubles, not the power.")],
                          "the eigenspace minimises C(V), so the excess starts at the lowest order that does not vanish."),
             _POWERS),
)
"""The judges of the three questions of 06-ties-recap (each: None when right, else the hint)."""


def check_recap_ties(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of the ties notebook (06): (1) only eigenspaces tie?, (2) what `complement_ratio` gives,
    (3) the power of the tilt angle in a near-tie's excess."""
    return recap("06-ties-recap", [q1, q2, q3], list(RECAP_TIES), show)
