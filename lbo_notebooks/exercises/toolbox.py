"""Self-checks of notebook 12 (the spectral toolbox: descriptors, functional maps, matching).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .feedback import (
    pick, plain, recap, as_array, named_option,
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, call_attempt, close_to,
    same_values, choose, right,
)

__all__ = [
    "check_hks",
    "check_functional_map",
    "check_zoomout_step",
    "check_truncation_bound",
    "check_alpha_choice",
    "check_mirror_maps",
    "check_zoomout",
    "check_recap_toolbox",
]


# --- 12 · the spectral toolbox ---------------------------------------------------------------------

def check_hks(hks_function: Any, spectrum: Any, *, show: bool = True) -> Feedback:
    """Exercise 12-hks: the student's ``hks_function(spectrum, times)`` against :func:`~lbo_notebooks.analyses.hks`.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis, analyses
    >>> s = eigenbasis(shapes.bumpy_sphere(2), 12)
    >>> check_hks(analyses.hks, s, show=False).correct
    True
    >>> "φ_i(x)²" in check_hks(lambda s, t: s.vectors @ np.exp(-np.outer(s.values, t)), s, show=False).message
    True
    """
    from ..analyses._descriptors import hks, hks_times

    def body() -> str:
        times = hks_times(spectrum, 4)
        ref = hks(spectrum, times)
        with np.errstate(over="ignore", invalid="ignore"):
            h = call_attempt(hks_function, spectrum, times.copy())
        hint = hks_hint(h, spectrum, times, ref)
        if hint is not None:
            raise Stop(WRONG, hint)
        return "Right: h_t(x) = Σ_i e^(−λ_i t) φ_i(x)², every eigenpair including the constant φ_0."
    return run_check("12-hks", show, body)


def hks_hint(value: Any, spectrum: Any, times: np.ndarray, ref: np.ndarray) -> str | None:
    """None when ``value`` is the HKS ``ref`` of ``spectrum`` at ``times``, else what is off."""
    h = as_array(value, "an array of shape (vertices, times)", finite=False)
    if not np.all(np.isfinite(h)):
        return "Your values overflow or are NaN: e^(+λ t) grows without bound; heat decays, e^(−λ_i t)."
    if h.shape == ref.shape[::-1] and h.shape != ref.shape:
        return f"Transposed: one row per vertex and one column per time, shape {ref.shape}."
    if h.shape != ref.shape:
        return f"Expected shape {ref.shape} (one row per vertex, one column per time), got {h.shape}."
    if same_values(h, ref, 1e-6):
        return None
    phi, lam = spectrum.vectors, np.maximum(spectrum.values, 0.0)
    with np.errstate(over="ignore", invalid="ignore"):
        decay = np.exp(-np.outer(lam, times))
        growth = np.exp(np.outer(lam, times))
        mass = np.asarray(spectrum.mass.diagonal())
        candidates = (
            (phi @ decay, "Square the eigenfunctions: the sum is over φ_i(x)², not φ_i(x)."),
            (np.abs(phi) @ decay, "Square the eigenfunctions: φ_i(x)², not |φ_i(x)|."),
            ((phi**2) @ growth, "exp(+λ t) grows; heat decays: e^(−λ_i t)."),
            ((phi[:, 1:] ** 2) @ decay[1:], "The sum starts at i = 0: the constant φ_0 (λ_0 = 0) keeps its share of heat at every time."),
            ((phi**2)[:, :-1] @ decay[:-1], "Use every computed eigenpair: the last one is missing."),
            (mass[:, None] * ((phi**2) @ decay), "No mass matrix: the HKS is a value at each vertex, not an integral."),
            ((phi**2) @ np.exp(-lam)[:, None] * times[None, :], "The time goes inside the exponential: e^(−λ_i t)."),
        )
    for candidate, hint in candidates:
        if np.all(np.isfinite(candidate)) and same_values(h, candidate, 1e-6):
            return hint
    return ("Not Σ_i e^(−λ_i t) φ_i(x)²: try it on one vertex and one time by hand, "
            "with `spectrum.values` and `spectrum.vectors`.")


def check_functional_map(fmap: Any, source: Any, target: Any, k: int = 20, *, show: bool = True) -> Feedback:
    """Exercise 12-fmap: the student's ``fmap(p2p, source, target, k)`` against ``functional_maps.map_from_points``.

    Tried on a random permutation ``p2p`` (``p2p[j]``: the source vertex of target vertex ``j``),
    so that a map used the wrong way round shows.
    """
    from ..analyses._functional_maps import map_from_points

    def body() -> str:
        k_ = min(int(k), source.k, target.k)
        n1, n2 = source.n_vertices, target.n_vertices
        rng = np.random.default_rng(9)
        p2p = rng.permutation(n1)[:n2] if n2 <= n1 else rng.integers(0, n1, n2)
        ref = map_from_points(p2p, source, target, k_source=k_, k_target=k_)
        hint = fmap_hint(call_attempt(fmap, p2p.copy(), source, target, k_), p2p, source, target, ref)
        if hint is not None:
            raise Stop(WRONG, hint)
        return "Right: C = Φ₂ᵀ A₂ Π Φ₁, the A₂ inner products of the pulled-back source functions with the target's."
    return run_check("12-fmap", show, body)


def fmap_hint(value: Any, p2p: np.ndarray, source: Any, target: Any, ref: np.ndarray) -> str | None:
    """None when ``value`` is the functional map ``ref`` of ``p2p`` (k × k), else what is off."""
    k_ = ref.shape[0]
    n1, n2 = source.n_vertices, target.n_vertices
    C = as_array(value, "a k × k matrix")
    if C.shape != ref.shape:
        return f"Expected a {k_} × {k_} matrix (k functions on each side), got shape {C.shape}."
    if same_values(C, ref, 1e-6):
        return None
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
    for candidate, hint in candidates:
        if np.all(np.isfinite(candidate)) and same_values(C, candidate, 1e-6):
            return hint
    return ("Not Φ₂ᵀ A₂ Π Φ₁: pull the first k source eigenfunctions back (Φ₁[p2p]), then take their A₂ inner "
            "products with the first k target eigenfunctions.")


def check_zoomout_step(zoomout_step: Any, source: Any, target: Any, k: int = 20, *, show: bool = True) -> Feedback:
    """Exercise 12-zoomout-step: the student's ``zoomout_step(C, source, target) -> (C_next, p2p)``, one
    ZoomOut iteration, against ``analyses.points_from_map`` then ``map_from_points`` at ``k + 1``.

    Tried on a ``k × k`` map near the true one from ``source`` to ``target`` with the target's vertices
    shuffled (so that a point map read the wrong way round shows) and perturbed (so that ``C`` is
    not orthogonal and ``Cᵀ`` differs from ``C⁻¹``). The point map is judged by its distances (any
    nearest neighbour counts, a tie either way), ``C_next`` as the map of the student's own point map.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis, analyses as fm
    >>> s = eigenbasis(shapes.bumpy_sphere(2), 12)
    >>> def step(C, source, target):
    ...     k = len(C)
    ...     p2p = fm.points_from_map(C, source, target)
    ...     return fm.map_from_points(p2p, source, target, k_source=k + 1, k_target=k + 1), p2p
    >>> check_zoomout_step(step, s, s, 8, show=False).correct
    True
    >>> not_grown = lambda C, s1, s2: (np.eye(len(C)), fm.points_from_map(C, s1, s2))
    >>> check_zoomout_step(not_grown, s, s, 8, show=False).message
    'Not grown: the next map has one more function on each side, (9, 9) here.'
    """
    from ..analyses._functional_maps import map_from_points
    from ..spectral._spectrum import Spectrum

    def body() -> str:
        k_ = min(int(k), source.k - 1, target.k - 1)
        n2 = target.n_vertices
        rng = np.random.default_rng(12)
        perm = rng.permutation(n2)  # vertex i of the shuffled target is vertex perm[i] of `target`
        mass, stiffness = target.mass.tocsr(), target.stiffness.tocsr()
        shuffled = Spectrum(target.values.copy(), target.vectors[perm].copy(), stiffness[perm][:, perm].tocsr(),
                            mass[perm][:, perm].tocsr())
        truth = perm if source.n_vertices == n2 else rng.integers(0, source.n_vertices, n2)
        C = map_from_points(truth, source, shuffled, k_source=k_, k_target=k_)
        C = C + 0.1 * rng.standard_normal(C.shape)
        value = call_attempt(zoomout_step, C.copy(), source, shuffled)
        hint = zoomout_step_hint(value, C, source, shuffled)
        if hint is not None:
            raise Stop(WRONG, hint)
        return ("Right: p2p[i] is the source vertex whose row of Φ₁Cᵀ is nearest to row i of Φ₂, and C_next = "
                "Φ₂ᵀ A₂ Π Φ₁ with k + 1 functions on each side.")
    return run_check("12-zoomout-step", show, body)


ZOOMOUT_NN_RTOL = 1e-5
"""A target vertex counts as matched to a nearest image when its squared distance exceeds the least
one by at most this fraction of the embedding's mean squared norm: ties and single precision pass."""


def _nearest_everywhere(p2p: np.ndarray, queries: np.ndarray, points: np.ndarray) -> int:
    """How many rows of ``queries`` are *not* matched by ``p2p`` to a nearest row of ``points``
    (exhaustive search in double precision, a tie either way counts as nearest)."""
    squared = np.einsum("ij,ij->i", points, points)
    best = np.empty(len(queries))
    for start in range(0, len(queries), 512):  # blocks of queries: |q - p|^2 = |q|^2 - 2 q.p + |p|^2
        q = queries[start:start + 512]
        best[start:start + 512] = np.maximum(
            (np.einsum("ij,ij->i", q, q)[:, None] - 2 * q @ points.T + squared).min(axis=1), 0.0)
    got = np.einsum("ij,ij->i", queries - points[p2p], queries - points[p2p])
    scale = float(np.mean(np.einsum("ij,ij->i", queries, queries)) + np.mean(np.einsum("ij,ij->i", points, points)))
    return int(np.count_nonzero(got > best + ZOOMOUT_NN_RTOL * scale))


def zoomout_step_hint(value: Any, C: np.ndarray, source: Any, target: Any) -> str | None:
    """None when ``value`` is ``(C_next, p2p)``, one ZoomOut iteration from ``C`` (k × k), else what is off.

    ``p2p`` must match every target vertex to a source vertex whose row of ``Φ₁[:, :k] Cᵀ`` is
    nearest to its row of ``Φ₂[:, :k]``; ``C_next`` must be ``map_from_points`` of that ``p2p`` at
    ``k + 1`` (the student's own point map: with ties, another nearest neighbour is as right).
    """
    k_ = C.shape[0]
    n1, n2 = source.n_vertices, target.n_vertices
    value = plain(value)
    if not isinstance(value, (tuple, list)) or len(value) != 2:
        if isinstance(value, np.ndarray) and value.ndim == 2:
            return "Return the pair `(C_next, p2p)`: the point map read off C as well as the new map."
        return f"Expected the pair `(C_next, p2p)`, got {type(value).__name__}."
    first, second = (np.asarray(v) if isinstance(v, (np.ndarray, list, tuple)) else v for v in value)
    if getattr(first, "ndim", None) == 1 and getattr(second, "ndim", None) == 2:
        return "Swapped: return `(C_next, p2p)`, the map first (as `fm.zoomout` returns `(C, p2p)`)."
    C_next = as_array(first, "C_next, a (k+1) × (k+1) matrix")
    p = as_array(second, "p2p, an integer array with one source vertex per target vertex")
    # --- the point map
    if p.shape == (n1,) and n1 != n2:
        return ("`p2p` has one entry per source vertex: it gives, for every target vertex i (row i of Φ₂[:, :k]), "
                "its source vertex p2p[i].")
    if p.shape != (n2,):
        return f"Expected `p2p` of shape ({n2},), one source vertex per target vertex, got shape {p.shape}."
    if not np.all(p == np.round(p)) or p.min() < 0 or p.max() >= n1:
        return f"`p2p` must hold source vertex indices, integers from 0 to {n1 - 1}."
    p = p.astype(np.int64)
    P1, P2 = source.vectors[:, :k_], target.vectors[:, :k_]
    images = P1 @ C.T  # row j: the coefficients C gives the delta at source vertex j
    bad = _nearest_everywhere(p, P2, images)
    if bad:
        candidates = [
            (P2, P1 @ C, ("Transposed C: the delta at source vertex j has coefficients Φ₁[j], and C sends them to "
                          "C Φ₁[j]; as rows, Φ₁[:, :k] Cᵀ, not Φ₁ C.")),
            (P2 @ C, P1, ("That compares Φ₂ C with Φ₁, the target rows carried back by Cᵀ; carry the source rows "
                          "forward instead: rows of Φ₁[:, :k] Cᵀ against rows of Φ₂[:, :k].")),
            (P2, P1, "C is not used: compare the target rows Φ₂[:, :k] with the source rows carried by C, Φ₁[:, :k] Cᵀ."),
        ]
        for queries, points, hint in candidates:
            if _nearest_everywhere(p, queries, points) == 0:
                return hint
        if n1 == n2 and _nearest_everywhere(p, images, P2) == 0:
            return ("The point map goes the wrong way: that is the nearest target vertex of each source vertex. "
                    "p2p[i] is the source vertex of target vertex i: search the source images for each target row.")
        return (f"Not the nearest neighbours: {bad} of {n2} target vertices are not matched to a source vertex whose "
                "row of Φ₁[:, :k] Cᵀ is nearest to their row of Φ₂[:, :k] (k = the size of C).")
    # --- the next map
    if C_next.shape == (k_, k_):
        return f"Not grown: the next map has one more function on each side, ({k_ + 1}, {k_ + 1}) here."
    if C_next.shape in ((target.k, source.k), (min(target.k, source.k),) * 2) and C_next.shape != (k_ + 1, k_ + 1):
        return (f"That uses every computed eigenfunction ({C_next.shape}); the next map takes the first k + 1 on each "
                f"side, ({k_ + 1}, {k_ + 1}) here.")
    if C_next.shape != (k_ + 1, k_ + 1):
        return f"Expected `C_next` of shape ({k_ + 1}, {k_ + 1}), one more function on each side, got {C_next.shape}."
    k1 = k_ + 1
    ref = target.vectors[:, :k1].T @ (target.mass @ source.vectors[p, :k1])
    hint = fmap_hint(C_next, p, source, target, ref)
    if hint is not None:
        return f"`C_next`, the map of your `p2p` with k + 1 functions: {hint}"
    return None


BOUND_RTOL = 1e-4
"""Relative tolerance of 12-bound: a value rounded to five significant digits passes."""


def _typed_rounding(got: float, exact: float) -> bool:
    """True when ``got`` shows few significant digits (a value typed by hand) and is ``exact`` rounded
    to them: right as far as it goes, too coarse to be judged."""
    if got == 0 or not np.isfinite(exact) or exact == 0:
        return False
    digits = next((d for d in range(1, 16) if float(f"{got:.{d - 1}e}") == got), 16)
    if digits > 8:
        return False  # a computed value, not a typed one
    unit = 10.0 ** (np.floor(np.log10(abs(got))) - digits + 1)
    return abs(got - exact) <= 0.5 * unit * (1 + 1e-9)


def check_truncation_bound(bound: Any, spectrum: Any, f: Any, k: int, *, show: bool = True) -> Feedback:
    """Exercise 12-bound: the optimality bound on the share of ‖f‖²_A lost by the first ``k`` eigenfunctions."""
    from ..analyses._optimality import dirichlet_energy

    def body() -> str:
        require_attempt(bound)
        got = as_number(bound, "a number (a fraction of ‖f‖²_A)")
        g = np.asarray(f, dtype=np.float64)
        W, A, lam = spectrum.stiffness, spectrum.mass, spectrum.values
        energy, norm2 = float(dirichlet_energy(W, g)), float(g @ (A @ g))
        ref = energy / lam[k] / norm2
        if close_to(got, ref, BOUND_RTOL):
            return f"Right: ‖∇f‖²/λ_{k} as a fraction of ‖f‖²_A (the first k functions are φ_0 ... φ_{k - 1})."
        if _typed_rounding(got, ref):
            raise Stop(WRONG, "Right to the digits you gave, but too coarse to judge: give more digits (at least five "
                               "significant ones), or let Python compute the value.")
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
        if isinstance(alpha, (bool, np.bool_)):
            raise Stop(WRONG, "Answer with a number: 0, 0.4 or 1.")
        got = as_number(alpha, "one of 0, 0.4, 1")
        if close_to(got, 1.0, 1e-9):
            return "Right on this pair: with α = 1 a part scaled by s has the same metric |K| g (K by 1/s², lengths² by s²)."
        if abs(got) <= 1e-9:
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
        given = [named_option(value, options) for value in (with_orientation, without_orientation)]
        if None in given:
            raise Stop(WRONG, "Answer each with \"i -> i\" or \"same position\".")
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
        "larger": right("ZoomOut reads the point map off 80 frequencies instead of 30, refining it step by step: the next cell measures the smaller error it gives."),
        "same": "ZoomOut adds 50 more frequencies to the map, and the point map is read off them: does that change nothing?",
        "smaller": "Refinement with more (smooth, well-captured) functions sharpens the point map; why would it make it worse?",
    }, show)


def check_recap_toolbox(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Exercise 12-recap: three multiple-choice questions on notebook 12, each answered with a letter."""
    return recap("12-recap", [q1, q2, q3], [pick(q) for q in RECAP_TOOLBOX], show)


RECAP_TOOLBOX: list[Mapping[str, str | None]] = [  # 12-recap: {choice: hint, or the right one's reason}
    {"a": "Each eigenfunction is defined up to sign, and inside a cluster only up to rotation: compare φ_8 in section 1.",
     "b": right("the HKS uses only the eigenvalues and the squared eigenfunctions summed over each eigenspace, and a change of pose barely moves either."),
     "c": "The eigenfunctions change with the pose (signs, mixing); the HKS uses only squares and eigenvalues."},
    {"a": right("the coefficients on shape 2's A₂-orthonormal basis are Φ₂ᵀ A₂ g, here for the pulled-back functions g = Π Φ₁."),
     "b": "Which basis is A₂-orthonormal, and so needs A₂ to take coefficients?",
     "c": "Π pulls functions from shape 1 back to shape 2, so it acts on Φ₁, between A₂ and Φ₁."},
    {"a": "A functional map of size k sees only k coefficients; what bounds the rest?",
     "b": "Eigenfunctions are not invariant (signs, mixing: section 1); the reason is a bound on what lies beyond φ_(k−1).",
     "c": right("the part of f beyond its first k coefficients has squared norm at most ‖∇f‖²/λ_k (notebook 05): small for a smooth f.")},
]
