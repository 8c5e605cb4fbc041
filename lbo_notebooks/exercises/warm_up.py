"""Self-checks of the warm-up notebook (the Laplacian of a graph and of a string, before the mesh).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.

Examples
--------
>>> check_edge_energy(..., [0, 1, 4], show=False).status
'not attempted'
>>> check_edge_energy(10, [0, 1, 4], show=False).correct
True
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from .basics import WrappedReasons
from .feedback import Feedback, WRONG, Stop, run_check, require_attempt, as_number, close_to, pick, number_judge, recap, right

__all__ = ["check_edge_energy", "check_cycle_multiplicity", "check_step_decay", "check_recap_graph"]


def _path_energy(f: np.ndarray) -> float:
    """Sum over the edges of the path graph (vertex i joined to i + 1) of (f_i - f_{i+1})²."""
    return float(np.sum(np.diff(f) ** 2))


def check_edge_energy(value: Any, f: Any, *, show: bool = True) -> Feedback:
    """Exercise 02-edge-energy: the energy ``fᵀ L f`` of ``f`` on the path graph with ``len(f)`` vertices.

    Examples
    --------
    >>> check_edge_energy(10, [0, 1, 4], show=False).correct
    True
    >>> "twice" in check_edge_energy(20, [0, 1, 4], show=False).message
    True
    """
    def body() -> str:
        require_attempt(value)
        g = np.asarray(f, dtype=np.float64)
        got, energy = as_number(value), _path_energy(g)
        if close_to(got, energy, 1e-9):
            return "Right: fᵀ L f is the sum, over the edges, of the squared differences across each edge."
        if close_to(got, 2 * energy, 1e-9):
            raise Stop(WRONG, "Twice too large: every edge counts once. (Summing over ordered pairs (i, j) and (j, i) counts each edge twice.)")
        if close_to(got, float(np.sum(np.abs(np.diff(g)))), 1e-9):
            raise Stop(WRONG, "Square each difference before adding: the energy is Σ (f_i − f_j)² over the edges.")
        if close_to(got, float(g @ g), 1e-9):
            raise Stop(WRONG, "That is ‖f‖² = Σ f_i², the size of f; the energy measures how much f *changes* along the edges.")
        if close_to(got, -energy, 1e-9) or got < 0:
            raise Stop(WRONG, "An energy is a sum of squares: it is never negative.")
        raise Stop(WRONG, f"List the {len(g) - 1} edges of the path (vertex i to vertex i + 1), square the difference of f across each, and add.")
    return run_check("02-edge-energy", show, body)


def check_cycle_multiplicity(count: Any, n: int = 12, value: float = 2.0, *, show: bool = True) -> Feedback:
    """Exercise 02-cycle-pair: how many eigenvectors of the cycle graph with ``n`` vertices have eigenvalue ``value``?

    The eigenvalues are ``2 - 2 cos(2πk/n)``, k = 0 … n−1.

    Examples
    --------
    >>> check_cycle_multiplicity(2, show=False).correct
    True
    >>> "n − k" in check_cycle_multiplicity(1, show=False).message
    True
    """
    def body() -> str:
        require_attempt(count)
        got = as_number(count, "a whole number")
        if abs(got - round(got)) > 1e-9 * max(1.0, abs(got)):
            raise Stop(WRONG, "A count of eigenvectors is a whole number: how many k in 0 … n − 1 solve the equation?")
        got = int(round(got))
        k = np.arange(n)
        exact = int(np.sum(np.isclose(2 - 2 * np.cos(2 * np.pi * k / n), value, rtol=0, atol=1e-12 * 4)))
        if got == exact:
            return ("Right: the frequencies k and n − k give the same eigenvalue, one cosine and one sine wave; "
                    "only k = 0 (and k = n/2 for even n) stand alone.")
        if got == 1:
            raise Stop(WRONG, "2 − 2cos(2πk/n) takes the same value at k and at n − k: a cosine wave and a sine wave of the same frequency.")
        if got < 1:
            raise Stop(WRONG, f"Solve 2 − 2cos(2πk/n) = {value:g} for k in 0 … n − 1: there are solutions.")
        raise Stop(WRONG, f"Too many: solve 2 − 2cos(2πk/n) = {value:g} for the whole numbers k in 0 … n − 1 only.")
    return run_check("02-cycle-pair", show, body)


def _step_error_ratio(n_beads: int = 200, jump: float = 0.4, n: int = 20) -> float:
    """``‖f − P_n f‖² / ‖f − P_2n f‖²`` for the step ``x > jump`` on the path with ``n_beads`` beads
    (eigenvectors: cosines at the midpoints)."""
    x = (np.arange(n_beads) + 0.5) / n_beads
    phi = np.cos(np.pi * np.outer(np.arange(n_beads) + 0.5, np.arange(n_beads)) / n_beads)
    phi /= np.linalg.norm(phi, axis=0)
    c = phi.T @ (x > jump).astype(float)
    return float(np.sum(c[n:] ** 2) / np.sum(c[2 * n:] ** 2))


def check_step_decay(factor: Any, *, show: bool = True) -> Feedback:
    """Exercise 02-step-decay: by what factor does the step's squared error drop from n = 20 to n = 40 terms?

    The step ``x > 0.4`` on the 200-bead path has coefficients of size about 1/k, so the squared error
    (the tail of Σ c_k²) falls like 1/n. Accepted within 15% of the actual ratio.

    Examples
    --------
    >>> check_step_decay(2, show=False).correct
    True
    >>> "1/n²" in check_step_decay(4, show=False).message
    True
    """
    def body() -> str:
        require_attempt(factor)
        got, actual = as_number(factor), _step_error_ratio()
        if close_to(got, actual, 0.15):
            return "Right: coefficients of size 1/k leave a tail Σ_{k≥n} 1/k² ≈ 1/n, so doubling n only halves the error."
        if got <= 1:
            raise Stop(WRONG, "Give error(n = 20) / error(n = 40): more terms leave less out, so the factor is above 1.")
        if close_to(got, 4.0, 0.2):
            raise Stop(WRONG, "That is an error ∝ 1/n², the rate of a function with a kink (coefficients ∝ 1/k²); a jump's are only ∝ 1/k.")
        if got > 6:
            raise Stop(WRONG, "That is how a smooth signal behaves; a jump's coefficients shrink only like 1/k. What is Σ_{k≥n} 1/k², roughly?")
        raise Stop(WRONG, "With coefficients of size 1/k the squared error is the tail Σ_{k≥n} 1/k²: how does that scale with n?")
    return run_check("02-step-decay", show, body)


def check_recap_graph(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of the warm-up: (1) the eigenvalues' factor when every weight doubles, (2) the largest
    eigenvalue of an even cycle, (3) which eigenvalue the bound divides by after n terms.

    Examples
    --------
    >>> check_recap_graph(2, 4, "lam_n", show=False).correct
    True
    >>> check_recap_graph(4, 4, "lam_n", show=False).message.startswith("2 of 3 right")
    True
    """
    return recap("02-graph-recap", [q1, q2, q3], GRAPH_RECAP, show)


def _spaceless(judge: Callable[[Any], str | None]) -> Callable[[Any], str | None]:
    """The same choice judge, blind to spaces inside the answer ("lam_n - 1" is "lam_n-1")."""
    def read(answer: Any) -> Any:
        return "".join(answer.split()) if isinstance(answer, str) else answer

    def spaceless(answer: Any) -> str | None:
        return judge(read(answer))
    spaceless.reasons = WrappedReasons(judge, read)  # type: ignore[attr-defined]
    return spaceless


GRAPH_RECAP: list[Callable[[Any], str | None]] = [
    number_judge(2.0, [(4.0, "L is linear in the weights (the energy is Σ w_ij (f_i − f_j)²), not quadratic."),
                       (1.0, "the weights are in L: doubling them doubles L, and with it every eigenvalue."),
                       (0.5, "upside down: heavier weights make every energy larger.")],
                 "L is linear in the weights; what happens to the eigenvalues of 2L?"),
    number_judge(4.0, [(2.0, "that is 2 − 2cos(2πk/n) where the cosine is 0; where is it largest?"),
                       (0.0, "that is the smallest one, at k = 0 (the constant).")],
                 "2 − 2cos(2πk/n) is largest where the cosine is most negative; for even n that value is reached."),
    _spaceless(pick({"lam_n-1": "φ_0 … φ_{n−1} are kept; the bound divides by the eigenvalue of the first one left out.",
                     "lam_n": right("φ_0 … φ_{n−1} are kept (0-based), and ‖f − P_n f‖² ≤ fᵀLf / λ_n divides by "
                                    "the eigenvalue of φ_n, the first one left out."),
                     "lam_n+1": "φ_0 … φ_{n−1} are kept (0-based); the bound divides by the eigenvalue of the first one "
                                "left out."})),
]
"""The judges of the recap's three questions (each: the hint of a wrong answer, None for a right
one), shared by :func:`check_recap_graph` and its graded test."""
