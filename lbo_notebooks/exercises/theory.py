"""Self-checks of notebooks 05 and 06 (optimality: the theorem, then the worst-case constant and ties), 07 (min–max)
and 06 (scale-invariant metrics).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

import numpy as np

from .feedback import (
    pick, number_judge, recap,
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, call_attempt, close_to, choose,
)

__all__ = [
    "check_projection", "check_energy_bound", "check_shifted_basis", "check_consistent_optimality",
    "check_extra_function", "check_worst_ratio", "check_recap_optimality", "check_stationary_frame",
    "check_recap_ties", "check_plane_minimum",
    "check_plane_range", "check_lowest_family", "check_dual_value", "check_interlacing",
    "check_consistent_minmax", "check_recap_min_max", "check_gauss_bonnet", "check_curvature_scaling",
    "check_metric_scaling", "check_best_alpha", "check_floor_fraction", "check_sphere_alpha",
    "check_consistent_invariance", "check_recap_scale_invariant",
]

# --- notebooks 05-08 ---
# 05–06 · the optimality theorem, 07 · the min-max principle, 08 · scale-invariant metrics.


def _theory_ratio_one(exercise: str, value: Any, below: str, above: str, show: bool, rtol: float = 1e-6) -> Feedback:
    """A normalised constant that must come out as exactly 1 (to ``rtol``): hints for below and above."""
    def body() -> str:
        require_attempt(value)
        got = as_number(value)
        if abs(got - 1) <= rtol:
            return "Right: exactly 1, to round-off: each eigenbasis is optimal for its own pair (W, A)."
        if 0 < got < 0.1:
            raise Stop(WRONG, "Normalise: multiply by λ_n (`values[n]`, n the number of basis functions or constraints), so that the optimum reads 1.")
        raise Stop(WRONG, below if got < 1 else above)
    return run_check(exercise, show, body)


def _vector(x: Any, what: str) -> np.ndarray:
    try:
        value = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError):
        raise Stop(WRONG, f"Expected {what}, got {type(x).__name__}.") from None
    if value.ndim != 1 or not np.all(np.isfinite(value)):
        raise Stop(WRONG, f"Expected {what} (a finite 1-D array), got shape {value.shape}.")
    return value


# --- 05–06 · the optimality theorem -------------------------------------------------------------------

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
                if stop.status == WRONG and re.search(r"shape|mismatch|align|dimension", stop.message):
                    raise Stop(WRONG, stop.message + " Check the transposes: Φ_n = `vectors[:, :n]` is (vertices × n), "
                                "the coefficients are Φ_nᵀ (A f), one per eigenfunction, and the projection Φ_n times them.") from None
                raise
            try:
                p = np.asarray(p, dtype=np.float64)
            except (TypeError, ValueError):
                raise Stop(WRONG, f"Return an array (one value per vertex), got {type(p).__name__}.") from None
            Af = mass @ f
            c = phi[:, :n].T @ Af
            ref = phi[:, :n] @ c
            scale = max(np.linalg.norm(ref), 1e-300)

            def near(other: np.ndarray) -> bool:
                return p.shape == other.shape and np.linalg.norm(p - other) <= 1e-8 * max(scale, np.linalg.norm(other))
            if p.shape == (n,):
                if near(c):
                    raise Stop(WRONG, "Those are the n coefficients c = Φ_nᵀ A f; the projection is the function they describe, Φ_n c (one value per vertex).")
                if near(phi[:, :n].T @ f):
                    raise Stop(WRONG, "Those are coefficients, and with the Euclidean inner product Φ_nᵀ f: return the projection Φ_n c, with c = Φ_nᵀ A f.")
            if p.shape != (n_vertices,):
                raise Stop(WRONG, f"Return one value per vertex, shape ({n_vertices},); got shape {p.shape}.")
            if near(ref):
                continue
            if near(phi[:, :n] @ (phi[:, :n].T @ f)):
                raise Stop(WRONG, "That is Φ_n Φ_nᵀ f, the Euclidean inner product: the eigenvectors are A-orthonormal, so the coefficients are Φ_nᵀ A f.")
            if near(phi[:, :n] @ (phi[:, :n].T @ (f / mass.diagonal()))):
                raise Stop(WRONG, "You divided by the vertex areas; the A inner product multiplies by them (`spectrum.mass @ f`).")
            if near(mass @ (phi[:, :n] @ (phi[:, :n].T @ f))):
                raise Stop(WRONG, "The mass matrix is in the wrong place: A multiplies f inside the coefficients, Φ_nᵀ (A f), not the result.")
            for m, hint in ((n + 1, "one eigenfunction too many"), (n - 1, "one eigenfunction too few")):
                if near(phi[:, :m] @ (phi[:, :m].T @ Af)):
                    raise Stop(WRONG, f"Off by one ({hint}): the first n eigenfunctions are φ_0 .. φ_(n-1), `vectors[:, :n]`.")
            if near(phi[:, 1:n + 1] @ (phi[:, 1:n + 1].T @ Af)) or near(phi[:, 1:n] @ (phi[:, 1:n].T @ Af)):
                raise Stop(WRONG, "You left out φ_0, the constant: it is the first of the n eigenfunctions (indices from 0).")
            if near(phi @ (phi.T @ Af)):
                raise Stop(WRONG, "You used every eigenfunction the spectrum has; use only the first n.")
            if near(f - ref):
                raise Stop(WRONG, "That is the error f − P_n f; return the projection P_n f itself.")
            raise Stop(WRONG, f"Not the A-orthogonal projection (first seen with n = {n}): coefficients c = Φ_nᵀ A f, then Φ_n c.")
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
        raise Stop(WRONG, "The bound is fᵀ W f / λ_n: the Dirichlet energy (W = `spectrum.stiffness`) over `values[n]`.")
    return run_check("05-bound", show, body)


def check_shifted_basis(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-shifted: C(V) λ_n for V = span(φ_1 .. φ_n), the eigenbasis without the constant."""
    return choose("06-shifted", answer, {
        "below": "Nothing is below 1: the theorem holds for every n-dimensional V.",
        "one": "Equality needs the *right* n functions. Which function of zero energy is missing from V, and what is its error?",
        "above": "Think of the worst function: one of zero energy that V cannot represent at all. What is error / energy for it?",
        "infinite": None,
    }, show)


def check_consistent_optimality(value: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-consistent: C(V) λ_n of the consistent-mass eigenbasis for its own (W, A): exactly 1."""
    return _theory_ratio_one(
        "06-consistent", value,
        "Below 1 is impossible (the theorem): is λ_n `values[n]`, with n the number of basis functions?",
        "The eigenbasis is optimal for the pair it solves: pass the consistent spectrum's own `stiffness` and `mass` "
        "to `worst_case_ratio`, and multiply by its `values[n]`.", show)


def check_extra_function(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 05-extra: where V = span(Φ_n, g) sits, between Φ_n and Φ_(n+1)."""
    return choose("05-extra", answer, {
        "beats": "V has n + 1 functions: the theorem for n + 1 says no (n + 1)-dimensional space beats Φ_(n+1).",
        "between": None,
        "worse": "V contains span Φ_n: projecting onto a larger space never increases the error.",
    }, show)


def check_worst_ratio(ratio: Any, basis: Any, stiffness: Any, mass: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-worst: the error / energy of the worst function of ``basis``, which must equal C(V)."""
    from ..optimality import worst_case_ratio

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
        if got > c:
            raise Stop(WRONG, "Above C(V), which is a supremum: check the error ‖f − P_V f‖²_A (A-norm) and the energy fᵀ W f.")
        raise Stop(WRONG, "Below C(V): use the function `worst_case_ratio(..., return_vector=True)` returns, and the A-norm of f − P_V f.")
    return run_check("06-worst", show, body)


def check_recap_optimality(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 05 (the theorem): (1) which `values[...]` after 10 terms, (2) the bound for white
    noise, (3) whether the direct argument needs an orthonormal basis."""
    return recap("05-recap", [q1, q2, q3], [
        number_judge(10, [(9, "after 10 terms φ_0 .. φ_9 are used; the bound divides by the first one left out."),
                            (11, "indices start at 0: count again which eigenvalue is the first one left out.")],
                       "the first eigenvalue whose eigenfunction is left out, in 0-based indexing."),
        pick({"tight": "noise has a huge Dirichlet energy; compare the bound with ‖f‖²_A itself.",
                      "vacuous": None,
                      "violated": "the bound holds for every function, smooth or not."}),
        pick({"yes": "the direct argument only counts conditions: n of them cannot kill an (n + 1)-dimensional span, "
                             "orthonormal basis or not (section 7 checks a non-orthonormal one).",
                      "no": None}),
    ], show)


def check_stationary_frame(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 06-stationary: how the excess total energy of a perturbed eigenframe grows when the noise doubles."""
    return choose("06-stationary", answer, {
        "same": "The excess is zero without noise and positive with it, so it must grow with ε: how fast, near a minimum?",
        "double": "That would be first order in ε; at a minimum the first-order change of the energy vanishes.",
        "quadruple": None,
        "eightfold": "Near a minimum the leading change is the second-order term, not a third-order one.",
    }, show)


def check_recap_ties(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of the ties notebook (06): (1) only eigenspaces tie?, (2) what `complement_ratio` gives,
    (3) the power of the tilt angle in a near-tie's excess."""
    return recap("06-ties-recap", [q1, q2, q3], [
        pick({"yes": "section 3 found an interval of tilted eigenbases that tie, none of them an eigenspace.",
              "no": None}),
        pick({"exactly": "it ignores the part of f inside V, which can cancel energy: exact only in special cases.",
              "lower": None,
              "upper": "ignoring the part of f inside V can only overestimate the energy of the worst function."}),
        number_judge(2, [(1, "a first-order tilt does not change the error of the worst functions (they are A-orthogonal to V)."),
                         (4, "that is the factor when the angle doubles, not the power.")],
                     "the eigenspace minimises C(V), so the excess starts at the lowest order that does not vanish."),
    ], show)


# --- 07 · the min-max principle -------------------------------------------------------------------

def _compressed(M: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """Eigenvalues of M restricted to the plane orthogonal to ``normal`` (ascending)."""
    u = normal / np.linalg.norm(normal)
    basis = np.linalg.svd(np.eye(3) - np.outer(u, u))[0][:, :2]
    return np.linalg.eigvalsh(basis.T @ M @ basis)


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
        pair = tuple(answer) if isinstance(answer, np.ndarray) and answer.shape == (2,) else answer   # lam[:2] too
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
    return choose("07-family", answer, {
        "white": None,
        "smooth": "Smooth constraints remove smooth, low-energy functions. What do rough constraints remove?",
        "near-optimal": "Constraints near φ_0 .. φ_(n-1) are nearly the optimal ones of Courant–Fischer: they come closest to λ_n.",
    }, show)


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
    return choose("07-interlacing", answer, {
        "lam_0": None,
        "lam_1": "Find a codimension-2 subspace that contains the constant function: what is its minimum?",
    }, show)


def check_consistent_minmax(value: Any, *, show: bool = True) -> Feedback:
    """Exercise 07-consistent: min of R on the optimal subspace over λ_10, consistent mass: exactly 1."""
    return _theory_ratio_one(
        "07-consistent", value,
        "Below 1 on the optimal subspace: use the consistent spectrum throughout (its `stiffness`, `mass`, and `optimal_subspace(sc, 10)`), "
        "and divide by `sc.values[10]`.",
        "Above λ_n is impossible (Courant–Fischer): divide by `values[10]` for 10 constraints.", show)


def check_recap_min_max(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 07: (1) the Courant–Fischer bound, (2) uniqueness, (3) a critical angle in degrees."""
    t_star = float(np.degrees(np.arctan(np.sqrt(2.0))))
    return recap("07-recap", [q1, q2, q3], [
        pick({"lam_n-1": "the bound is the eigenvalue whose index is the codimension.",
                      "lam_n": None,
                      "lam_n+1": "the bound is the eigenvalue whose index is the codimension."}),
        pick({"yes": "section 2 tilted an optimal plane and found a whole arc of maximisers.", "no": None}),
        number_judge(t_star, [(np.degrees(np.arctan(2.0)), "tan² t* is the ratio, not tan t*."),
                                (np.degrees(np.arctan(np.sqrt(0.5))), "the ratio is (λ_2 − λ_1)/(λ_1 − λ_0), upside down?"),
                                (np.arctan(np.sqrt(2.0)), "give degrees, not radians.")],
                       "tan² t* = (λ_2 − λ_1)/(λ_1 − λ_0); give t* in degrees."),
    ], show)


# --- 08 · scale-invariant metrics -----------------------------------------------------------------

def check_gauss_bonnet(torus: Any, disk: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-gauss-bonnet: Σ K_i a_i for a torus and a disk (2πχ)."""
    def body() -> str:
        require_attempt([torus, disk])
        t, d = as_number(torus), as_number(disk)
        two_pi = 2 * np.pi
        tol = 1e-6 * two_pi
        if abs(t) <= tol and abs(d - two_pi) <= tol:
            return "Right: Σ K_i a_i = 2πχ, with χ = 0 for the torus and 1 for the disk."
        if abs(t) <= tol and close_to(d, 1, 1e-6):
            raise Stop(WRONG, "Those look like Euler characteristics: the total curvature is 2π times χ.")
        if abs(t) > tol:
            raise Stop(WRONG, "The torus: count V − E + F of a square grid wrapped around both ways (each square is two triangles).")
        raise Stop(WRONG, "The disk: χ = V − E + F of a flat triangulated disk (one triangle will do), times 2π.")
    return run_check("08-gauss-bonnet", show, body)


def check_curvature_scaling(factor: Any, scale: float = 3.0, *, show: bool = True) -> Feedback:
    """Exercise 08-curvature: the factor by which Gaussian curvature changes when a shape is scaled by ``scale``."""
    def body() -> str:
        require_attempt(factor)
        got = as_number(factor)
        if close_to(got, scale**-2, 1e-6):
            return "Right: K = 1/(R₁R₂), two lengths in the denominator; the angle defect is unchanged and the area grows by s²."
        if close_to(got, 1 / scale, 1e-6):
            raise Stop(WRONG, "K is a product of two principal curvatures, each 1/length: think of 1/R² on a sphere.")
        if close_to(got, scale**2, 1e-6) or close_to(got, scale, 1e-6):
            raise Stop(WRONG, "Upside down: a bigger sphere is flatter.")
        if close_to(got, 1.0, 1e-6):
            raise Stop(WRONG, "The angle defect does not change, but K is the defect per unit area.")
        raise Stop(WRONG, "K_i = δ_i / a_i: how do the angle defect δ_i and the vertex area a_i change?")
    return run_check("08-curvature", show, body)


def check_metric_scaling(factors: Any, scale: float = 3.0, *, show: bool = True) -> Feedback:
    """Exercise 08-scaling: ``{alpha: factor}``, how the eigenvalues of ``|K|^alpha g`` change under scaling by ``scale``."""
    def body() -> str:
        require_attempt(factors)
        if not isinstance(factors, Mapping) or not factors:
            raise Stop(WRONG, "Give a dict {alpha: new eigenvalue / old eigenvalue}.")
        for alpha, got in factors.items():
            a, got = float(alpha), as_number(got, f"a number for alpha = {alpha}")
            ref = scale ** (-2 * (1 - a))
            if close_to(got, ref, 1e-6):
                continue
            if a != 1 and close_to(got, 1 / ref, 1e-6):
                raise Stop(WRONG, f"alpha = {alpha}: upside down. A_α grows, so the eigenvalues of W φ = λ A_α φ shrink.")
            if a != 1 and close_to(got, scale ** -(1 - a), 1e-6):
                raise Stop(WRONG, f"alpha = {alpha}: areas scale by s², not s.")
            if a != 0 and close_to(got, scale**-2, 1e-6):
                raise Stop(WRONG, f"alpha = {alpha}: that is the regular metric's factor; ρ shrinks by s⁻² too, and A_α holds ρ^α.")
            if a != 1 and close_to(got, 1.0, 1e-6):
                raise Stop(WRONG, f"alpha = {alpha}: only α = 1 cancels the area's s² completely.")
            raise Stop(WRONG, f"alpha = {alpha}: W does not change; A_α = diag(ρ^α a) with a → s² a and ρ → s⁻² ρ.")
        missing = [a for a in (0.0, 0.4, 1.0) if not any(close_to(float(given), a, 1e-9) for given in factors)]
        if missing:
            raise Stop(WRONG, "Right so far; now give the factor for every α the exercise asks: "
                              + ", ".join(f"{a:g}" for a in missing) + " missing.")
        return "Right: A_α grows by s^(2(1−α)), so λ scales by s^(−2(1−α)); α = 1 is exactly invariant."
    return run_check("08-scaling", show, body)


def check_best_alpha(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-best: which α rebuilds the most curved 10% of the horse best (0, 0.4 or 1)."""
    options = {"0": "The regular basis spreads its functions evenly by area; the curved 10% has little area.",
               "0.4": "A compromise is rarely the best at one extreme: which metric gives the curved tips the most area?",
               "1": None}

    def body() -> str:
        require_attempt(answer)
        try:
            key = f"{float(answer):g}"
        except (TypeError, ValueError):
            key = str(answer).strip()
        if key not in options:
            raise Stop(WRONG, "Answer with one of: 0, 0.4, 1.")
        if options[key] is not None:
            raise Stop(WRONG, options[key])
        return "Right: |K| g gives the curved tips most of its area, so its eigenbasis spends its functions there."
    return run_check("08-best", show, body)


def check_floor_fraction(fraction: Any, mesh: Any, floor: float = 1.0, *, show: bool = True) -> Feedback:
    """Exercise 08-floor: the fraction of vertices at the curvature floor ``floor``."""
    from ..curvature import metric_curvature

    def body() -> str:
        require_attempt(fraction)
        got = as_number(fraction)
        level = floor * 4 * np.pi / mesh.area
        ref = float(np.mean(metric_curvature(mesh, floor=floor) <= level * (1 + 1e-12)))
        if abs(got - ref) <= 1e-9:
            return "Right: that is the share of vertices whose one-ring |K| is below the floor."
        if abs(got - 100 * ref) <= 1e-7:
            raise Stop(WRONG, "That is a percentage; give a fraction between 0 and 1.")
        if abs(got - (1 - ref)) <= 1e-9:
            raise Stop(WRONG, "That is the fraction *above* the floor.")
        if got == 0 and ref > 0:
            raise Stop(WRONG, "None at the floor? Compare with a tolerance (`np.isclose`, or `<=` the floor times 1 + 1e-12), not `==`: the floor is computed in floating point.")
        raise Stop(WRONG, f"Compare `curvature.metric_curvature(mesh, floor={floor:g})` with the floor value {floor:g} · 4π / area (vertices at the floor equal it).")
    return run_check("08-floor", show, body)


def check_sphere_alpha(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-sphere: how the α = 1 eigenvalues of the unit sphere compare with the regular ones."""
    return choose("08-sphere", answer, {
        "equal": None,
        "scaled": "What is |K|^α on the unit sphere, and so what does g_α = |K|^α g become?",
        "unrelated": "What is |K|^α on the unit sphere, and so what does g_α = |K|^α g become?",
    }, show)


def check_consistent_invariance(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 08-consistent: is the consistent (per-triangle) α = 1 metric scale-invariant too?"""
    return choose("08-consistent", answer, {
        "yes": None,
        "no": "Scaling by s: what happens to a triangle's area, to its ρ_t, and so to ρ_t × area?",
    }, show)


def check_recap_scale_invariant(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 08: (1) K of a sphere of radius 2, (2) what α changes, (3) which spectrum is steadier under poses."""
    return recap("08-recap", [q1, q2, q3], [
        number_judge(0.25, [(0.5, "K is 1/R², not 1/R."), (4.0, "upside down: a bigger sphere is flatter.")],
                       "K = 1/R² on a sphere of radius R."),
        pick({"w": "the Dirichlet energy is conformally invariant in 2-D: the cotangent weights do not change.",
                      "a": None,
                      "both": "the Dirichlet energy is conformally invariant in 2-D: one of the two does not change."}),
        pick({"regular": None,
                      "scale-invariant": "section 6 measured it: the poses stretch the joints a little and |K| amplifies it."}),
    ], show)
