"""Self-checks of notebook 11 (regularized PCA).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .feedback import (
    pick, recap, as_array, named_option, right,
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, call_attempt, close_to,
)

__all__ = [
    "check_rpca_limits",
    "check_dirichlet_energies",
    "check_validation_choice",
    "check_mu_scaling",
    "check_rpca_objective",
    "check_rpca_basis",
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


# --- 11-rpca-basis: the regularized PCA basis as a generalized symmetric eigenproblem ----------------

BASIS_TOL = 1e-6
"""How far (A-norm, per A-unit column) a column of 11-rpca-basis may lie outside the eigenspace it
belongs to, and how far ``Pᵀ A P`` may be from ``I``: far above a dense or Lanczos solver's
round-off on the small meshes used, far below any slip."""


def _dense(M: Any) -> np.ndarray:
    import scipy.sparse as sp

    M = M.toarray() if sp.issparse(M) else np.asarray(M, dtype=np.float64)
    return (M + M.T) / 2


def _pencil_eigenpairs(X: Any, W: Any, A: Any, mu: float, *, data: str = "AXXA", sign: float = -1.0,
                       generalized: bool = True, center: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Every eigenpair of ``(A X Xᵀ A − μ W) p = σ A p``, σ descending, ``Pᵀ A P = I`` (dense; small
    meshes). The keywords build the usual slips instead: ``data="XX"`` (no A in the data term),
    ``sign=+1`` (``+ μ W``), ``generalized=False`` (the standard problem ``L p = σ p``),
    ``center=True`` (the data centred first)."""
    import scipy.linalg

    Xd = np.asarray(X, dtype=np.float64)
    Xd = Xd[:, None] if Xd.ndim == 1 else Xd
    Ad = _dense(A)
    if center:
        a = Ad.sum(axis=1)
        Xd = Xd - (a @ Xd) / a.sum()
    U = Ad @ Xd if data == "AXXA" else Xd
    L = _dense(U @ U.T + sign * float(mu) * _dense(W))
    values, vectors = scipy.linalg.eigh(L, Ad) if generalized else np.linalg.eigh(L)
    return values[::-1], vectors[:, ::-1]


def _pencil_matrix(X: Any, W: Any, A: Any, mu: float) -> np.ndarray:
    Xd = np.asarray(X, dtype=np.float64)
    U = _dense(A) @ (Xd[:, None] if Xd.ndim == 1 else Xd)
    return _dense(U @ U.T - float(mu) * _dense(W))


def _cluster_end(values: np.ndarray, j: int) -> tuple[int, int]:
    """Indices ``[start, stop)`` of the eigenvalues equal to ``values[j]`` (to round-off): one
    eigenspace, in which any A-orthonormal basis is as good as any other."""
    tol = 1e-8 * abs(values[j]) + 1e-11 * np.abs(values).max()
    same = np.flatnonzero(np.abs(values - values[j]) <= tol)
    return int(same.min()), int(same.max()) + 1


def _outside(P: np.ndarray, V: np.ndarray, Ad: np.ndarray) -> np.ndarray:
    """A-norm of the part of each column of ``P`` outside span ``V`` (``V`` any full-rank basis)."""
    G = V.T @ Ad @ V
    try:
        R = np.linalg.cholesky((G + G.T) / 2)
    except np.linalg.LinAlgError:
        return np.full(P.shape[1], np.inf)
    Q = np.linalg.solve(R, V.T).T  # A-orthonormal basis of span V
    residual = P - Q @ (Q.T @ (Ad @ P))
    return np.sqrt(np.maximum(np.einsum("ij,ij->j", residual, Ad @ residual), 0.0))


def _columns_in_place(P: np.ndarray, values: np.ndarray, vectors: np.ndarray, Ad: np.ndarray) -> bool:
    """Column j of ``P`` lies in the eigenspace of the j-th largest σ, for every j: the right basis
    up to the sign of each column and the choice of basis inside repeated eigenvalues."""
    for j in range(P.shape[1]):
        start, stop = _cluster_end(values, j)
        if _outside(P[:, [j]], vectors[:, start:stop], Ad)[0] > BASIS_TOL:
            return False
    return True


def _spans_top(P: np.ndarray, values: np.ndarray, vectors: np.ndarray, Ad: np.ndarray) -> bool:
    """The columns of ``P`` lie in the span of the top ``m`` eigenvectors (with the whole eigenspace
    the m-th belongs to), in any order."""
    m = P.shape[1]
    stop = _cluster_end(values, m - 1)[1]
    return bool(np.all(_outside(P, vectors[:, :stop], Ad) <= BASIS_TOL))


def rpca_basis_hint(value: Any, X: Any, W: Any, A: Any, mu: float, m: int) -> str | None:
    """None when ``value`` is a right answer of 11-rpca-basis for ``(X, W, A, mu, m)``, else the hint.

    Right: an (n, m) array, ``Pᵀ A P = I``, column j an eigenvector of the j-th largest σ of
    ``(A X Xᵀ A − μ W) p = σ A p``; any sign per column and any A-orthonormal basis of a repeated
    eigenvalue's eigenspace (also one cut by m) are right.
    """
    if isinstance(value, (tuple, list)) and len(value) == 2 and all(np.ndim(v) >= 1 for v in value):
        return "Return the basis P alone (an (n, m) array), not a pair such as (eigenvalues, basis)."
    P = as_array(value, "an (n, m) array: one basis function per column")
    n = np.shape(X)[0]
    if P.shape == (m, n) and m != n:
        return f"Transposed: one basis function per *column*, shape ({n}, {m})."
    if P.shape != (n, m):
        return f"Expected shape ({n}, {m}) (one row per vertex, m = {m} columns), got {P.shape}."
    Ad = _dense(A)
    values, vectors = _pencil_eigenpairs(X, W, A, mu)
    gram = P.T @ Ad @ P
    norms = np.sqrt(np.maximum(np.diag(gram), 0.0))
    if np.any(norms <= 1e-300):
        return "A column of your basis is zero."
    if np.abs(gram - np.eye(m)).max() > BASIS_TOL:
        unit = P / norms
        if _spans_top(unit, values, vectors, Ad) and _columns_in_place(unit, values, vectors, Ad):
            euclid = np.abs(P.T @ P - np.eye(m)).max() <= BASIS_TOL
            return ("The directions are right but not normalised in the A inner product: the basis must satisfy "
                    "Pᵀ A P = I" + (" (yours has Pᵀ P = I, the Euclidean one)" if euclid else "") +
                    ". `scipy.linalg.eigh(L, A)` returns vectors normalised that way.")
        P = unit  # judge the directions, to name the slip
    elif _columns_in_place(P, values, vectors, Ad):
        L = _pencil_matrix(X, W, A, mu)
        got, best = float(np.trace(P.T @ L @ P)), float(values[:m].sum())
        if abs(got - best) <= 1e-8 * float(np.abs(values[:m]).sum()):
            return None
        return "Not optimal: trace(Pᵀ (A X Xᵀ A − μ W) P) is below the sum of the m largest σ."  # pragma: no cover
    if _spans_top(P, values, vectors, Ad):
        if _columns_in_place(P[:, ::-1], values, vectors, Ad):
            return "The right functions in ascending order: order the columns by *decreasing* σ (`eigh` returns them ascending)."
        return "The right functions in the wrong order: column j must belong to the j-th largest σ (decreasing σ)."
    bottom = (values[::-1], vectors[:, ::-1])
    if _spans_top(P, *bottom, Ad):
        return ("Those are the eigenvectors of the m *smallest* σ; the minimiser takes the m largest of "
                "(A X Xᵀ A − μ W) p = σ A p (the objective is a constant minus trace(Pᵀ (A X Xᵀ A − μ W) P)).")
    slips = (
        (dict(sign=+1.0), "The smoothness term has the wrong sign: the matrix is A X Xᵀ A − μ W (roughness is penalised)."),
        (dict(data="XX"), "The data term lacks the mass matrix: it is A X Xᵀ A (the A inner products Aᵀx), not X Xᵀ."),
        (dict(generalized=False), "That solves the standard problem L p = σ p; the constraint Pᵀ A P = I makes it the "
                                  "*generalized* one, L p = σ A p (`scipy.linalg.eigh(L, A)`)."),
        (dict(center=True), "Your data were centred first; the exercise takes X as given (the notebook's solver centres only "
                            "when asked to)."),
    )
    for keywords, hint in slips:
        if _spans_top(P, *_pencil_eigenpairs(X, W, A, mu, **keywords), Ad):
            return hint
    if float(mu) != 1.0 and _spans_top(P, *_pencil_eigenpairs(X, W, A, 1.0), Ad):
        return "μ is missing: the matrix is A X Xᵀ A − μ W."
    return ("Not the top m generalized eigenvectors of (A X Xᵀ A − μ W) p = σ A p: build the matrix from `A @ X` and "
            "`W`, solve with A on the right-hand side, keep the m largest σ.")


def check_rpca_basis(basis_function: Any, X: Any, W: Any, A: Any, *, show: bool = True) -> Feedback:
    """Exercise 11-rpca-basis: the student's ``basis_function(X, W, A, mu, m)`` against the dense
    generalized eigendecomposition of ``(A X Xᵀ A − μ W, A)``.

    Run for two weights and sizes (``μ`` from ``β = 10⁻²`` with m = 12, and ten times that with
    m = 8); any sign per column and any basis inside a repeated eigenvalue are right.

    Examples
    --------
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> mesh = shapes.icosphere(2)
    >>> W, A = stiffness_matrix(mesh), mass_matrix(mesh)
    >>> X = np.hstack([mesh.vertices, mesh.vertices ** 2])
    >>> def solver(X, W, A, mu, m):
    ...     return _pencil_eigenpairs(X, W, A, mu)[1][:, :m]
    >>> check_rpca_basis(solver, X, W, A, show=False).correct
    True
    >>> ascending = lambda X, W, A, mu, m: solver(X, W, A, mu, m)[:, ::-1]
    >>> "ascending order" in check_rpca_basis(ascending, X, W, A, show=False).message
    True
    """
    from ..analyses._rpca import mu_from_beta

    def body() -> str:
        Xd = np.asarray(X, dtype=np.float64)
        for beta_scale, m in ((1.0, 12), (10.0, 8)):
            mu = beta_scale * mu_from_beta(1e-2, Xd, A, m)
            value = call_attempt(basis_function, Xd.copy(), W.copy(), A.copy(), float(mu), m)
            hint = rpca_basis_hint(value, Xd, W, A, mu, m)
            if hint is not None:
                raise Stop(WRONG, f"{hint} (m = {m}, μ = {mu:.3g}.)")
        return ("Right: the top generalized eigenvectors of (A X Xᵀ A − μ W, A), A-orthonormal, by decreasing σ, "
                "for two weights.")
    return run_check("11-rpca-basis", show, body)


def check_recap_rpca(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Exercise 11-recap: three multiple-choice questions on notebook 11, each answered with a letter."""
    return recap("11-recap", [q1, q2, q3], [pick(q) for q in RECAP_RPCA], show)


RECAP_RPCA: list[Mapping[str, str | None]] = [  # 11-recap: {choice: hint, or the right one's reason}
    {"a": "PCA on the coordinates then smoothed is not optimal for the combined objective; section 1 derives a closed form.",
     "b": right("with PᵀAP = I the objective is trace(XᵀAX) − trace(Pᵀ(A X Xᵀ A − μW)P): Ky Fan keeps the top "
                "generalized eigenvectors."),
     "c": "Which term is maximised and which penalised? The eigenvalue problem keeps the *top* eigenvectors of a difference."},
    {"a": right("two poses give six coordinate functions, so A X Xᵀ A has rank at most 6: any basis of its zero "
                "eigenspace is equally optimal for the data term."),
     "b": "Centring removes only the constant direction; count the independent functions two poses give.",
     "c": "Smoothness plays no part in plain PCA; the trouble is in the data term alone."},
    {"a": "A dimensionless weight is not faster to compute: the solver factorises once either way.",
     "b": "μ is never negative here; what changes about μ when the shape is scaled?",
     "c": right("the raw μ carries units (data² × area / energy), while β names one basis whatever the shape's size "
                "and units.")},
]
