"""Self-checks of notebook 11 (regularized PCA).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .feedback import (
    pick, recap, as_array, named_option,
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, call_attempt, close_to,
)

__all__ = [
    "check_rpca_limits",
    "check_dirichlet_energies",
    "check_validation_choice",
    "check_mu_scaling",
    "check_rpca_objective",
    "check_recap_rpca",
]


# --- 11 · regularized PCA --------------------------------------------------------------------------

_BASES = ("pca (6)", "pca + smooth", "eigenbasis")


def check_rpca_limits(at_zero: Any, at_one: Any, best: Any, *, show: bool = True) -> Feedback:
    """Exercise 11-limits: the bases at β → 0 and β → 1 (of m = 100 functions), and where the best β lies."""
    def body() -> str:
        require_attempt([at_zero, at_one, best])
        answers = {}
        for name, value, options in (("β → 0", at_zero, _BASES), ("β → 1", at_one, _BASES),
                                     ("the best β", best, ("small", "intermediate", "large"))):
            answers[name] = named_option(value, options)
            if answers[name] is None:
                raise Stop(WRONG, f"{name}: answer with one of " + ", ".join(f'"{o}"' for o in options) + ".")
        a0, a1, b = answers.values()
        if a0 == "eigenbasis" and a1 != "eigenbasis":
            raise Stop(WRONG, "β → 0 puts all the weight on the data term and β → 1 on smoothness: check which end is which.")
        if a0 == "pca (6)":
            raise Stop(WRONG, "β → 0: the basis still has m = 100 functions, and the data fill only six of them. "
                               "What chooses the other 94 while μ is small but positive?")
        if a0 != "pca + smooth":
            raise Stop(WRONG, "β → 0: the data term dominates, but it is blind to 94 of the 100 directions.")
        if a1 != "eigenbasis":
            raise Stop(WRONG, "β → 1 (μ → ∞): only the Dirichlet energy counts. Which A-orthonormal basis has the smallest energies?")
        if b != "intermediate":
            raise Stop(WRONG, "The limits are right. For the best β: each end ignores one of the two terms. Can "
                               "the validation pose be rebuilt from the training data alone, or from smoothness alone?")
        return "Right: the PCA directions then the smoothest complement, the eigenbasis, and a weight in between."
    return run_check("11-limits", show, body)


def check_dirichlet_energies(energies: Any, basis: Any, stiffness: Any, mass: Any, *, show: bool = True) -> Feedback:
    """Exercise 11-energy: the Dirichlet energies ``p_jᵀ W p_j`` of the columns of ``basis``.

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
        require_attempt(energies)
        P = np.asarray(basis, dtype=np.float64)
        e = as_array(energies, "an array of energies, one per function")
        WP = stiffness @ P
        ref = np.einsum("ij,ij->j", P, WP)
        scale = max(np.abs(ref).max(), 1e-300)
        if e.shape == (P.shape[1], P.shape[1]) and P.shape[1] > 1:
            raise Stop(WRONG, "One energy per function: the diagonal of Pᵀ W P, not the whole matrix.")
        if e.size == ref.size and e.ndim == 2 and 1 in e.shape:
            e = e.ravel()  # a column or a row of the energies
        if e.shape != ref.shape:
            raise Stop(WRONG, f"One energy per column of the basis (length {ref.shape[0]}), got shape {e.shape}.")
        near = lambda other: bool(np.abs(e - other).max() <= 1e-6 * max(np.abs(other).max(), scale))  # noqa: E731
        if near(ref):
            return "Right: E(p_j) = p_jᵀ W p_j, the squared norm of the gradient."
        if near(np.einsum("ij,ij->j", P, mass @ P)):
            raise Stop(WRONG, "That is p_jᵀ A p_j, the A-norm (1 for an A-orthonormal basis); the energy uses W.")
        if near(np.einsum("ij,ij->j", P, P)):
            raise Stop(WRONG, "That is p_jᵀ p_j, with neither W nor A; the energy is p_jᵀ W p_j.")
        if near(np.sqrt(np.abs(ref))):
            raise Stop(WRONG, "The square root: the energy is ‖∇p‖², not ‖∇p‖.")
        if near(2 * ref) or near(ref / 2):
            raise Stop(WRONG, "Off by a factor of two: here the energy is p_jᵀ W p_j, without a ½.")
        if np.abs(e).max() <= 1e-6 * scale:  # (W p_j summed over the vertices is 0 too: W's rows sum to 0)
            raise Stop(WRONG, "All (nearly) zero: only a constant function has no energy; p_jᵀ W p_j is positive for the others.")
        if near(np.abs(WP).sum(axis=0)):
            raise Stop(WRONG, "W p_j is a vector; the energy is the number p_jᵀ (W p_j).")
        raise Stop(WRONG, "Not p_jᵀ W p_j for each column p_j of the basis (`np.einsum(\"ij,ij->j\", ...)` does all columns at once).")
    return run_check("11-energy", show, body)


def _yes_no(value: Any) -> bool | None:
    """A yes/no answer: True, False (also NumPy's) or the words "true"/"false"/"yes"/"no"; None otherwise."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, str):
        return {"true": True, "yes": True, "false": False, "no": False}.get(value.strip().lower())
    return None


def check_validation_choice(chosen_beta: Any, beats_by_four: Any, errors: Mapping[float, Any], err_lbo: Any,
                            unseen: list[str], pose: str = "tail_raised", *, show: bool = True) -> Feedback:
    """Exercise 11-validation: β chosen on another validation pose, and whether it still beats the eigenbasis 4×.

    ``errors`` maps each swept β to the errors on the ``unseen`` poses, ``err_lbo`` the eigenbasis' errors.
    """
    def body() -> str:
        require_attempt([chosen_beta, beats_by_four])
        betas = list(errors)
        i = unseen.index(pose)
        others = [j for j in range(len(unseen)) if j != i]
        ref = min(betas, key=lambda b: errors[b][i])
        got = as_number(chosen_beta, "one of the swept β")
        if not any(close_to(got, b, 1e-9) for b in betas):
            raise Stop(WRONG, "Choose one of the swept weights `betas` (the sweep is already computed).")
        if not close_to(got, ref, 1e-9):
            if close_to(got, max(betas, key=lambda b: errors[b][i]), 1e-9):
                raise Stop(WRONG, f"That β gives the *largest* error on {pose}: take the smallest.")
            if close_to(got, min(betas, key=lambda b: np.mean(errors[b])), 1e-9):
                raise Stop(WRONG, f"That β is best on all the unseen poses together (peeking): choose on {pose} alone.")
            if close_to(got, min(betas, key=lambda b: np.mean([errors[b][j] for j in others])), 1e-9):
                raise Stop(WRONG, f"That β is best on the *other* poses: choose on {pose} alone, then report on the others.")
            raise Stop(WRONG, f"Not the β with the smallest error on {pose} (`errors[beta][unseen.index(\"{pose}\")]`).")
        verdict = _yes_no(beats_by_four)
        if verdict is None:
            raise Stop(WRONG, "Answer the second question with True or False.")
        truth = bool(np.all(np.asarray(errors[ref])[others] < np.asarray(err_lbo)[others] / 4))
        if verdict != truth:
            raise Stop(WRONG, "The β is right; compare its errors with a quarter of the eigenbasis' (`err_lbo`) on the two other poses.")
        return f"Right: the choice made on {pose}, and its verdict on the two poses it did not see."
    return run_check("11-validation", show, body)


def check_mu_scaling(factor: Any, scale: float = 2.0, *, show: bool = True) -> Feedback:
    """Exercise 11-scale: the factor by which μ (for a fixed β) changes when the shape is scaled by ``scale``.

    Examples
    --------
    >>> check_mu_scaling(2.0**6, 2.0, show=False).correct
    True
    """
    def body() -> str:
        require_attempt(factor)
        got, s = as_number(factor), float(scale)
        if close_to(got, s**6, 1e-3):
            return "Right: s_B grows by s⁴ (X by s, A by s²) and λ_ref shrinks by s² (it is ∝ 1/area): μ ∝ s⁶."
        if close_to(got, s**-6, 1e-3):
            raise Stop(WRONG, "Upside down: both changes make μ larger.")
        if close_to(got, 1.0, 1e-3):
            raise Stop(WRONG, "β is dimensionless and stays; μ = β/(1−β) · s_B/λ_ref carries units, so it changes.")
        if close_to(got, s**4, 1e-3):
            raise Stop(WRONG, "That is the growth of s_B alone; λ_ref = 4πm/area changes too.")
        if close_to(got, s**2, 1e-3):
            raise Stop(WRONG, "That accounts for λ_ref (or for the data) only: both s_B and λ_ref change.")
        if close_to(got, s**3, 1e-3) or close_to(got, s**5, 1e-3):
            raise Stop(WRONG, "Check the powers: X → sX and A → s²A in s_B (the top eigenvalue of Xᵀ A X), and the area in λ_ref.")
        raise Stop(WRONG, "μ = β/(1−β) · s_B/λ_ref: find how s_B (top eigenvalue of Xᵀ A X) and λ_ref = 4πm/area scale.")
    return run_check("11-scale", show, body)


def _rpca_objective(P: np.ndarray, X: np.ndarray, W: Any, A: Any, mu: float) -> float:
    R = P @ (P.T @ (A @ X)) - X
    return float(np.sum(R * (A @ R)) + mu * np.sum(P * (W @ P)))


def objective_hint(got: float, P: np.ndarray, X: np.ndarray, W: Any, A: Any, mu: float) -> str | None:
    """None when ``got`` is the objective of ``P`` (to round-off), else the hint of the slip it matches."""
    ref = _rpca_objective(P, X, W, A, mu)
    smooth = mu * float(np.sum(P * (W @ P)))
    scale = float(np.sum(X * (A @ X))) + abs(smooth)  # the size of the terms, for a closed form's round-off
    if abs(got - ref) <= 1e-8 * abs(ref) + 1e-11 * scale:
        return None
    fit = ref - smooth
    R = P @ (P.T @ (A @ X)) - X
    R_euclid_proj = P @ (P.T @ X) - X
    candidates = (
        (fit, "The smoothness term μ Σ p_jᵀ W p_j is missing."),
        (fit - smooth, "The smoothness term has the wrong sign: it is a penalty, added."),
        (fit + mu * np.sum(P * (A @ P)), "The smoothness term uses A; the Dirichlet energy uses W."),
        (float(np.sum(R * R)) + smooth, "The residual is measured in the Euclidean norm; the objective uses ‖·‖_A (Rᵀ A R)."),
        (float(np.sum(R_euclid_proj * (A @ R_euclid_proj))) + smooth,
         "The projection is P Pᵀ A x (the A inner product), not P Pᵀ x."),
        (fit + smooth / mu if mu else np.nan, "μ is missing in front of the energy."),
    )
    for value, hint in candidates:
        if np.isfinite(value) and close_to(got, value, 1e-8):
            return hint
    return ("Not Σ_i ‖P Pᵀ A x_i − x_i‖²_A + μ Σ_j p_jᵀ W p_j: check each term on its own "
            "(with μ = 0 only the fit is left).")


def check_rpca_objective(objective: Any, X: Any, W: Any, A: Any, P: Any, mu: float, *, show: bool = True) -> Feedback:
    """Exercise 11-objective: the student's ``objective(P, X, W, A, mu)`` against the regularized-PCA objective.

    Called on ``P`` and on its first half of columns with ``3 mu``; the hint names the usual slip.
    """
    def body() -> str:
        P_ = np.asarray(P, dtype=np.float64)
        X_ = np.asarray(X, dtype=np.float64)
        for basis, weight in ((P_, float(mu)), (P_[:, : max(1, P_.shape[1] // 2)], 3.0 * float(mu))):
            got = as_number(call_attempt(objective, basis, X_, W, A, weight), "a number (the value of the objective)")
            hint = objective_hint(got, basis, X_, W, A, weight)
            if hint is not None:
                raise Stop(WRONG, hint)
        return "Right: the fit in the A-norm plus μ times the Dirichlet energies, on two bases and two weights."
    return run_check("11-objective", show, body)


def check_recap_rpca(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Exercise 11-recap: three multiple-choice questions on notebook 11, each answered with a letter."""
    return recap("11-recap", [q1, q2, q3], [pick(q) for q in RECAP_RPCA], show)


RECAP_RPCA: list[Mapping[str, str | None]] = [  # 11-recap: {choice: hint, None for the right one}
    {"a": "PCA on the coordinates then smoothed is not optimal for the combined objective; section 1 derives a closed form.",
     "b": None,
     "c": "Which term is maximised and which penalised? The eigenvalue problem keeps the *top* eigenvectors of a difference."},
    {"a": None,
     "b": "Centring removes only the constant direction; count the independent functions two poses give.",
     "c": "Smoothness plays no part in plain PCA; the trouble is in the data term alone."},
    {"a": "A dimensionless weight is not faster to compute: the solver factorises once either way.",
     "b": "μ is never negative here; what changes about μ when the shape is scaled?",
     "c": None},
]
