"""Self-checks of notebooks 00 (start here), 11 (regularized PCA) and 12 (the spectral toolbox).

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
    pick, recap,
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, call_attempt, close_to,
    same_values, choose,
)

__all__ = [
    "check_sphere_eigenvalues", "check_mesh_size", "check_eigenfunction", "check_load_error",
    "check_rpca_limits", "check_dirichlet_energies", "check_validation_choice", "check_mu_scaling",
    "check_rpca_objective", "check_recap_rpca", "check_hks", "check_functional_map",
    "check_truncation_bound", "check_alpha_choice", "check_mirror_maps", "check_zoomout",
    "check_recap_toolbox",
]

# --- notebooks 00, 11, 12 ---


def _array(value: Any, what: str, *, finite: bool = True) -> np.ndarray:
    """The student's answer as a float array (sparse matrices densified), or a 'wrong' stop."""
    import scipy.sparse as sp

    if sp.issparse(value):
        value = value.toarray()
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise Stop(WRONG, f"Expected {what}, got {type(value).__name__}.") from None
    if finite and not np.all(np.isfinite(arr)):
        raise Stop(WRONG, "Your answer has NaN or infinite entries.")
    return arr


def _recap(exercise: str, answers: list[Any], questions: list[Mapping[str, str | None]], show: bool) -> Feedback:
    """Several multiple-choice questions in one check, each ``{choice: hint or None}``."""
    return recap(exercise, answers, [pick(q) for q in questions], show)


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
        got = _array(values, "a list of nine numbers")
        exact = np.repeat([l * (l + 1) for l in range(3)], [2 * l + 1 for l in range(3)]).astype(float)
        if got.shape != (9,):
            raise Stop(WRONG, "Give nine numbers: λ_0, ..., λ_8, each eigenvalue written as often as it repeats.")
        if np.allclose(got, exact):
            return "Right: ℓ = 0 (the constant, λ = 0), then 2 three times and 6 five times."
        if np.allclose(got, np.repeat([l * l for l in range(3)], [2 * l + 1 for l in range(3)])):
            raise Stop(WRONG, "Those are ℓ², the eigenvalues are ℓ(ℓ+1).")
        if np.any(np.diff(got) < 0):
            raise Stop(WRONG, "List them in increasing order, as `eigenbasis` returns them.")
        if got[0] != 0:
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
        if not isinstance(counts, (tuple, list)) or len(counts) != 2:
            raise Stop(WRONG, "Give two numbers: (vertices, triangles).")
        nv, nf = (as_number(c, "a whole number") for c in counts)
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
        raise Stop(WRONG, "Count the rows of `mesh.vertices` and `mesh.faces` (or read `mesh.summary()`).")
    return run_check("00-size", show, body)


@lru_cache(maxsize=2)
def _torus_spectrum(k: int) -> Any:
    from .. import shapes
    from ..spectrum import eigenbasis

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
        f = _array(phi, "an array with one value per vertex")
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


def check_load_error(error: Any, *, show: bool = True) -> Feedback:
    """Exercise 00-missing: the exception ``load_mesh`` raised for a face naming a vertex that does not exist."""
    from ..mesh import Mesh, MeshError

    def body() -> str:
        require_attempt(error)
        if isinstance(error, MeshError):
            if _MISSING_VERTEX.search(str(error)):
                return "Right: a `MeshError` that names the face and the vertex index that does not exist."
            raise Stop(WRONG, "That `MeshError` is about another defect of the file: read its message. Make one face "
                              "use an index past the last vertex (faces count vertices from 0).")
        if isinstance(error, type):
            raise Stop(WRONG, "That is an exception class; keep the exception object: `except lbo.MeshError as err: error = err`.")
        if isinstance(error, str):
            raise Stop(WRONG, "Keep the exception object itself (`error = err` inside the `except` block), not its text.")
        if isinstance(error, Mesh):
            raise Stop(WRONG, "`load_mesh` returned a mesh: no face of your file refers to a missing vertex. "
                               "Faces count vertices from 0, so a file with 3 vertices has indices 0, 1, 2.")
        if isinstance(error, BaseException):
            raise Stop(WRONG, f"`load_mesh` refuses a broken mesh with a `MeshError`; you caught a {type(error).__name__}. "
                               "Is the file's header (counts of vertices and faces) consistent?")
        raise Stop(WRONG, f"Expected the exception object, got {type(error).__name__}.")
    return run_check("00-missing", show, body)


# --- 11 · regularized PCA --------------------------------------------------------------------------

_BASES = ("pca (6)", "pca + smooth", "eigenbasis")


def check_rpca_limits(at_zero: Any, at_one: Any, best: Any, *, show: bool = True) -> Feedback:
    """Exercise 11-limits: the bases at β → 0 and β → 1 (of m = 100 functions), and where the best β lies."""
    def body() -> str:
        require_attempt([at_zero, at_one, best])
        answers = {}
        for name, value, options in (("β → 0", at_zero, _BASES), ("β → 1", at_one, _BASES),
                                     ("the best β", best, ("small", "intermediate", "large"))):
            if not isinstance(value, str) or value.strip().lower() not in options:
                raise Stop(WRONG, f"{name}: answer with one of " + ", ".join(f'"{o}"' for o in options) + ".")
            answers[name] = value.strip().lower()
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
        e = _array(energies, "an array of energies, one per function")
        WP = stiffness @ P
        ref = np.einsum("ij,ij->j", P, WP)
        scale = max(np.abs(ref).max(), 1e-300)
        if e.shape == (P.shape[1], P.shape[1]):
            raise Stop(WRONG, "One energy per function: the diagonal of Pᵀ W P, not the whole matrix.")
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
        if near(np.abs(WP).sum(axis=0)) or near(WP.sum(axis=0)):
            raise Stop(WRONG, "W p_j is a vector; the energy is the number p_jᵀ (W p_j).")
        raise Stop(WRONG, "Not p_jᵀ W p_j for each column p_j of the basis (`np.einsum(\"ij,ij->j\", ...)` does all columns at once).")
    return run_check("11-energy", show, body)


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
        if not isinstance(beats_by_four, (bool, np.bool_)):
            raise Stop(WRONG, "Answer the second question with True or False.")
        truth = bool(np.all(np.asarray(errors[ref])[others] < np.asarray(err_lbo)[others] / 4))
        if bool(beats_by_four) != truth:
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


def check_rpca_objective(objective: Any, X: Any, W: Any, A: Any, P: Any, mu: float, *, show: bool = True) -> Feedback:
    """Exercise 11-objective: the student's ``objective(P, X, W, A, mu)`` against the regularized-PCA objective.

    Called on ``P`` and on its first half of columns with ``3 mu``; the hint names the usual slip.
    """
    def body() -> str:
        P_ = np.asarray(P, dtype=np.float64)
        X_ = np.asarray(X, dtype=np.float64)
        for basis, weight in ((P_, float(mu)), (P_[:, : max(1, P_.shape[1] // 2)], 3.0 * float(mu))):
            got = as_number(call_attempt(objective, basis, X_, W, A, weight), "a number (the value of the objective)")
            ref = _rpca_objective(basis, X_, W, A, weight)
            if close_to(got, ref, 1e-8):
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
                if np.isfinite(value) and close_to(got, value, 1e-8):
                    raise Stop(WRONG, hint)
            raise Stop(WRONG, "Not Σ_i ‖P Pᵀ A x_i − x_i‖²_A + μ Σ_j p_jᵀ W p_j: check each term on its own "
                               "(with μ = 0 only the fit is left).")
        return "Right: the fit in the A-norm plus μ times the Dirichlet energies, on two bases and two weights."
    return run_check("11-objective", show, body)


def check_recap_rpca(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Exercise 11-recap: three multiple-choice questions on notebook 11, each answered with a letter."""
    return _recap("11-recap", [q1, q2, q3], [
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


# --- 12 · the spectral toolbox ---------------------------------------------------------------------

def check_hks(hks_function: Any, spectrum: Any, *, show: bool = True) -> Feedback:
    """Exercise 12-hks: the student's ``hks_function(spectrum, times)`` against :func:`descriptors.hks`.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis, descriptors
    >>> s = eigenbasis(shapes.bumpy_sphere(2), 12)
    >>> check_hks(descriptors.hks, s, show=False).correct
    True
    >>> "φ_i(x)²" in check_hks(lambda s, t: s.vectors @ np.exp(-np.outer(s.values, t)), s, show=False).message
    True
    """
    from ..descriptors import hks, hks_times

    def body() -> str:
        times = hks_times(spectrum, 4)
        ref = hks(spectrum, times)
        with np.errstate(over="ignore", invalid="ignore"):
            h = _array(call_attempt(hks_function, spectrum, times.copy()), "an array of shape (vertices, times)", finite=False)
        if not np.all(np.isfinite(h)):
            raise Stop(WRONG, "Your values overflow or are NaN: e^(+λ t) grows without bound; heat decays, e^(−λ_i t).")
        if h.shape == ref.shape[::-1]:
            raise Stop(WRONG, f"Transposed: one row per vertex and one column per time, shape {ref.shape}.")
        if h.shape != ref.shape:
            raise Stop(WRONG, f"Expected shape {ref.shape} (one row per vertex, one column per time), got {h.shape}.")
        if same_values(h, ref, 1e-6):
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
            if np.all(np.isfinite(value)) and same_values(h, value, 1e-6):
                raise Stop(WRONG, hint)
        raise Stop(WRONG, "Not Σ_i e^(−λ_i t) φ_i(x)²: try it on one vertex and one time by hand, "
                           "with `spectrum.values` and `spectrum.vectors`.")
    return run_check("12-hks", show, body)


def check_functional_map(fmap: Any, source: Any, target: Any, k: int = 20, *, show: bool = True) -> Feedback:
    """Exercise 12-fmap: the student's ``fmap(p2p, source, target, k)`` against ``functional_maps.map_from_points``.

    Tried on a random permutation ``p2p`` (``p2p[j]``: the source vertex of target vertex ``j``),
    so that a map used the wrong way round shows.
    """
    from ..functional_maps import map_from_points

    def body() -> str:
        k_ = min(int(k), source.k, target.k)
        n1, n2 = source.n_vertices, target.n_vertices
        rng = np.random.default_rng(9)
        p2p = rng.permutation(n1)[:n2] if n2 <= n1 else rng.integers(0, n1, n2)
        ref = map_from_points(p2p, source, target, k_source=k_, k_target=k_)
        C = _array(call_attempt(fmap, p2p.copy(), source, target, k_), "a k × k matrix")
        if C.shape != ref.shape:
            raise Stop(WRONG, f"Expected a {k_} × {k_} matrix (k functions on each side), got shape {C.shape}.")
        if same_values(C, ref, 1e-6):
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
            if np.all(np.isfinite(value)) and same_values(C, value, 1e-6):
                raise Stop(WRONG, hint)
        raise Stop(WRONG, "Not Φ₂ᵀ A₂ Π Φ₁: pull the first k source eigenfunctions back (Φ₁[p2p]), then take their A₂ inner "
                           "products with the first k target eigenfunctions.")
    return run_check("12-fmap", show, body)


def check_truncation_bound(bound: Any, spectrum: Any, f: Any, k: int, *, show: bool = True) -> Feedback:
    """Exercise 12-bound: the optimality bound on the share of ‖f‖²_A lost by the first ``k`` eigenfunctions."""
    from ..optimality import dirichlet_energy

    def body() -> str:
        require_attempt(bound)
        got = as_number(bound, "a number (a fraction of ‖f‖²_A)")
        g = np.asarray(f, dtype=np.float64)
        W, A, lam = spectrum.stiffness, spectrum.mass, spectrum.values
        energy, norm2 = float(dirichlet_energy(W, g)), float(g @ (A @ g))
        ref = energy / lam[k] / norm2
        if close_to(got, ref, 1e-6):
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
            if np.isfinite(value) and close_to(got, value, 1e-6):
                raise Stop(WRONG, hint)
        c = spectrum.vectors[:, :k].T @ (A @ g)
        if close_to(got, 1 - float(c @ c) / norm2, 1e-3):
            raise Stop(WRONG, "That is the share actually lost (the projection); the question asks for the theorem's bound, from the energy alone.")
        raise Stop(WRONG, "The bound is ‖∇f‖²/λ_k = fᵀ W f / λ_k; divide it by fᵀ A f.")
    return run_check("12-bound", show, body)


def check_alpha_choice(alpha: Any, *, show: bool = True) -> Feedback:
    """Exercise 12-alpha: which α of the metric ``|K|^α g`` matches the dog with a 1.6 times larger head best (0, 0.4 or 1)?"""
    def body() -> str:
        require_attempt(alpha)
        got = as_number(alpha, "one of 0, 0.4, 1")
        if close_to(got, 1.0, 1e-9):
            return "Right on this pair: with α = 1 a part scaled by s has the same metric |K| g (K by 1/s², lengths² by s²)."
        if got == 0:
            raise Stop(WRONG, "The regular metric sees a bigger head as more area and lower frequencies everywhere (section 1). "
                               "Which α makes a rescaled part look unchanged?")
        if close_to(got, 0.4, 1e-9):
            raise Stop(WRONG, "α = 0.4 compensates the rescaling only in part: K scales by 1/s², lengths² by s². Which α cancels them?")
        raise Stop(WRONG, "Answer 0, 0.4 or 1.")
    return run_check("12-alpha", show, body)


def check_mirror_maps(with_orientation: Any, without_orientation: Any, *, show: bool = True) -> Feedback:
    """Exercise 12-mirror: which map ``match`` finds from the dog to its mirror, with and without the orientation term."""
    options = ("i -> i", "same position")

    def body() -> str:
        require_attempt([with_orientation, without_orientation])
        given = []
        for value in (with_orientation, without_orientation):
            if not isinstance(value, str) or value.strip().lower() not in options:
                raise Stop(WRONG, "Answer each with \"i -> i\" or \"same position\".")
            given.append(value.strip().lower())
        if given == ["same position", "i -> i"]:
            return ("Right: intrinsically the mirror is the dog itself, so without the orientation term i -> i is a perfect map; "
                    "it reverses orientation, and the term asks for a map that preserves it: the left–right swap.")
        if given == ["i -> i", "same position"]:
            raise Stop(WRONG, "The other way round: which of the two maps reverses orientation (a mirror does)?")
        if given[0] == "i -> i":
            raise Stop(WRONG, "With the orientation term: vertex i of the mirror is the *reflection* of vertex i, a map that reverses orientation.")
        raise Stop(WRONG, "Without the orientation term only intrinsic quantities count: how do the mirror's descriptors at vertex i compare with the dog's?")
    return run_check("12-mirror", show, body)


def check_zoomout(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 12-zoomout: without ZoomOut (``k_final=30``), is the mean error larger, the same or smaller?"""
    return choose("12-zoomout", answer, {
        "larger": None,
        "same": "ZoomOut adds 50 more frequencies to the map, and the point map is read off them: does that change nothing?",
        "smaller": "Refinement with more (smooth, well-captured) functions sharpens the point map; why would it make it worse?",
    }, show)


def check_recap_toolbox(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Exercise 12-recap: three multiple-choice questions on notebook 12, each answered with a letter."""
    return _recap("12-recap", [q1, q2, q3], [
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
