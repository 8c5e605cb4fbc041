"""Self-checks of the two spectral MDS notebooks: canonical forms (09_spectral_mds) and accuracy,
cost and resolution (10_spectral_mds_at_scale).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works. The canonical-forms notebook has two
builds: classical MDS of an n x n distance matrix (section 2), and the small step of spectral MDS:
from the eigenbasis ``Phi`` and the k x k coefficients ``alpha`` of ``D2 ~ Phi alpha Phi.T`` to the
embedding, through a k x k eigenproblem (section 2, later).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from .feedback import (Feedback, WRONG, Stop, run_check, require_attempt, as_number, as_array, call_attempt, close_to,
                       choose, pick, number_judge, recap, right)

__all__ = [
    "check_classical_memory", "check_classical_mds", "check_small_scaling", "check_fmm_gap", "check_gram_2d",
    "check_landmark_samples", "check_recap_canonical_forms", "check_mu_range", "check_equal_size",
    "check_recap_mds_at_scale",
]


def _rounded_from(got: float, ref: float) -> bool:
    """Whether ``got`` is ``ref`` rounded to the digits ``got`` shows (a value copied from a printout),
    its last digit no coarser than the leading digit of ``ref``: then a miss is a matter of precision.

    Examples
    --------
    >>> _rounded_from(0.004, 0.0040349), _rounded_from(0.0041, 0.0040349), _rounded_from(1000.0, 705.0)
    (True, False, False)
    """
    from decimal import Decimal, InvalidOperation

    try:
        if got == 0 or not np.isfinite(got) or not np.isfinite(ref) or ref == 0:
            return False
        exponent = Decimal(np.format_float_positional(got, unique=True, trim="-")).normalize().as_tuple().exponent
    except (InvalidOperation, TypeError, ValueError):
        return False
    unit = 10.0 ** int(exponent)
    return unit <= abs(ref) and abs(got - ref) <= 0.5 * unit * (1 + 1e-9)


_MORE_DIGITS = ("Right to the digits you gave, but too coarse to judge: give more digits (the value your code "
                "computes, not a rounded copy).")


# --- 09-memory -----------------------------------------------------------------------------------

def check_classical_memory(gigabytes: Any, n: int, *, show: bool = True) -> Feedback:
    """Exercise 09-memory: the memory classical MDS needs on ``n`` vertices, in GB (10⁹ bytes).

    Two n x n float64 matrices (the squared distances and B), 8 bytes per entry.

    Examples
    --------
    >>> check_classical_memory(2 * 8 * 10_000**2 / 1e9, 10_000, show=False).correct
    True
    >>> "two" in check_classical_memory(8 * 10_000**2 / 1e9, 10_000, show=False).message
    True
    """
    def body() -> str:
        require_attempt(gigabytes)
        got = as_number(gigabytes, "a number of gigabytes")
        ref = 2 * 8 * float(n) ** 2 / 1e9
        if close_to(got, ref, 0.02):
            return "Right: two n × n matrices of 8-byte floats; n² makes every tenfold in n a hundredfold in memory."
        for slip, hint in (
            (ref / 2, "Half of it: classical MDS keeps *two* n × n matrices (D² and B), each entry 8 bytes (float64)."),
            (ref * 1e9, "That is in bytes; give gigabytes (10⁹ bytes)."),
            (ref * 1e3, "That is in megabytes; give gigabytes (10⁹ bytes)."),
            (ref / 1.073741824, "That is in GiB (2³⁰ bytes); the question asks for GB (10⁹ bytes)."),
            (ref / 8, "You counted entries, not bytes: a float64 takes 8 bytes."),
            (ref / 16, "You counted the entries of one matrix: there are two, 8 bytes per entry."),
            (2 * 8 * n / 1e9, "Memory grows like n², not n: each matrix has n × n entries."),
        ):
            if close_to(got, slip, 0.02):
                raise Stop(WRONG, hint)
        if _rounded_from(got, ref):
            raise Stop(WRONG, _MORE_DIGITS)
        raise Stop(WRONG, "Count the entries of two n × n matrices, times 8 bytes, and divide by 10⁹.")
    return run_check("09-memory", show, body)


# --- 09-classical-mds: build it yourself ----------------------------------------------------------

MDS_GRAM_TOL = 1e-7
"""How closely a built classical MDS must agree: the Gram error (``gram_error``: relative Frobenius
error of the centred Gram matrices, blind to rotations, reflections and translations) at most this.
Dense ``eigh`` and Lanczos at its default tolerance come within about 1e-12."""


def _double_centred(D2: np.ndarray) -> np.ndarray:
    row = D2.mean(axis=1)
    return -0.5 * (D2 - row[:, None] - row[None, :] + row.mean())


def mds_slips(D: np.ndarray, dim: int) -> tuple[np.ndarray, list[tuple[np.ndarray, str]]]:
    """Classical MDS of the distances ``D`` (computed here with dense ``eigh``), and the typical
    slips as (embedding, hint); a slip with the same Gram matrix as the answer on ``D`` is left out."""
    from ..analyses._embedding_error import gram_error

    D = 0.5 * (D + D.T)
    B = _double_centred(D**2)
    G, U = _top(B, dim)
    ref = U * np.sqrt(np.maximum(G, 0.0))

    def embed(matrix: np.ndarray, power: Callable[[np.ndarray], np.ndarray] = lambda g: np.sqrt(np.maximum(g, 0.0))) -> np.ndarray:
        g, u = _top(matrix, dim)
        return u * power(g)

    w, V = np.linalg.eigh(B)
    by_size = np.argsort(-np.abs(w))[:dim]
    n = len(D)
    slips = [
        (embed(_double_centred(D)), "The distances are not squared: B = −½ J D² J double-centres the *squared* distances "
                                    "(`D**2`, entry by entry)."),
        (U * np.sqrt(np.maximum(2 * G, 0.0)), "Off by a factor √2 (your Gram matrix is twice the right one): "
                                              "B = −½ J D² J, mind the ½."),
        (embed(-B), "Those are the directions of B's most negative eigenvalues: a wrong sign (B = −½ J D² J), or "
                    "the smallest eigenpairs (`np.linalg.eigh` sorts ascending); keep the largest."),
        (embed(-0.5 * D**2), "Not double-centred: B = −½ J D² J with J = I − 𝟏𝟏ᵀ/n centres the rows *and* the columns."),
        (embed(B, lambda g: np.maximum(g, 0.0)), "The eigenvalues are not square-rooted: X = U Γ^½ (so that X Xᵀ = U Γ Uᵀ)."),
        (embed(B, lambda g: np.ones_like(g)), "Each eigenvector must be scaled by the square root of its eigenvalue: "
                                              "X = U Γ^½, not U."),
        (embed(B, lambda g: 1 / np.sqrt(np.maximum(g, 1e-12 * g.max()))), "Γ^(−½) where Γ^½ belongs: X = U Γ^½."),
        (embed(B, lambda g: np.sqrt(np.abs(g))), "A negative eigenvalue is clipped to zero (its direction contributes "
                                                 "nothing), not replaced by its absolute value."),
        (V[:, by_size] * np.sqrt(np.maximum(w[by_size], 0.0)),
         "Those are the eigenvalues largest in *magnitude* (`eigsh`'s default `which=\"LM\"`); keep the largest "
         "(`which=\"LA\"`): a negative eigenvalue can be large."),
        (embed(-0.5 * (np.eye(n) - 1 / n) @ D**2), "Centred on one side only: B = −½ J D² J, with J on both sides."),
    ]
    kept = []
    with np.errstate(all="ignore"):
        for X, hint in slips:
            if np.all(np.isfinite(X)) and np.any(X) and gram_error(X, ref) > 1e3 * MDS_GRAM_TOL:
                kept.append((X, hint))
    return ref, kept


def _mds_embedding(value: Any, n: int, dim: int) -> np.ndarray:
    """The returned embedding as an (n, dim) float array, or Stop with what is wrong with its form."""
    X = as_array(value, "a NumPy array of shape (n, dim), one row per point", finite=False)
    if dim == 1 and X.shape == (n,):
        X = X[:, None]
    if X.shape == (dim, n) and dim != n:
        raise Stop(WRONG, f"Transposed: return one row per point, shape ({n}, {dim}), not ({dim}, {n}).")
    if X.ndim == 2 and X.shape[0] == n and X.shape[1] != dim:
        raise Stop(WRONG, f"Asked for dim = {dim}, you returned {X.shape[1]} columns: use the `dim` argument.")
    if X.shape != (n, dim):
        raise Stop(WRONG, f"Return one row per point and one column per dimension, shape ({n}, {dim}); got {X.shape}.")
    if not np.all(np.isfinite(X)):
        raise Stop(WRONG, "NaN or infinity in your embedding: the square root of a negative eigenvalue? B has negative "
                          "eigenvalues when the distances are not Euclidean (and round-off ones when they are): clip "
                          "them to zero first, `np.sqrt(np.maximum(values, 0))`.")
    if not np.any(X):
        raise Stop(WRONG, "Your embedding is all zeros: keep B's *largest* eigenvalues (`np.linalg.eigh` sorts ascending).")
    return X


def judge_classical_mds(function: Any, cases: Any, call: Any = call_attempt) -> str:
    """The message of a correct ``function(D, dim)`` on every ``(D, dims, where)`` of ``cases``
    (``call(function, D, dim)`` runs it on a copy), else Stop with the hint of the first miss."""
    from ..analyses._embedding_error import gram_error

    for D, dims, where in cases:
        n = len(D)
        for dim in dims:
            X = _mds_embedding(call(function, D.copy(), dim), n, dim)
            ref, slips = mds_slips(D, dim)
            with np.errstate(all="ignore"):
                if gram_error(X, ref) <= MDS_GRAM_TOL:
                    continue
                seen = f" (seen on {where}, dim = {dim}.)"
                for slip, hint in slips:
                    if gram_error(X, slip) <= 1e-6:
                        raise Stop(WRONG, hint + seen)
                if np.linalg.norm(X - X.mean(axis=0)) <= 1e-6 * np.linalg.norm(ref):
                    raise Stop(WRONG, "Your embedding is (nearly) a single point: those are B's *smallest* eigenvalues, "
                                      "about 0 for Euclidean distances (`np.linalg.eigh` sorts ascending); keep the "
                                      "dim largest." + seen)
            raise Stop(WRONG, "Not classical MDS (Gram error above 1e-7). The steps: B = −½ J D² J with D² the squared "
                              "distances, the dim largest eigenpairs B = U Γ Uᵀ, negative eigenvalues clipped to 0, "
                              "then X = U Γ^½." + seen)
    return ("Right: classical MDS, up to a rotation or reflection (judged by the Gram matrix X Xᵀ), with the negative "
            "eigenvalues of non-Euclidean distances clipped.")


def _visible_mds_cases() -> list[tuple[np.ndarray, tuple[int, ...], str]]:
    """What the visible check of 09-classical-mds runs on: 25 points in ℝ³ (dim 3 and 2) and the
    graph distances of a 7-cycle (not Euclidean: B has negative eigenvalues; dim 2)."""
    from scipy.spatial.distance import cdist

    P = np.random.default_rng(909).normal(size=(25, 3)) * [2.0, 1.0, 0.5]
    k = np.arange(7)
    ring = np.minimum(np.abs(k[:, None] - k[None, :]), 7 - np.abs(k[:, None] - k[None, :])).astype(float)
    return [(cdist(P, P), (3, 2), "25 points in ℝ³"), (ring, (2,), "the graph distances of a 7-cycle")]


def check_classical_mds(classical_mds: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-classical-mds: the student's ``classical_mds(D, dim)`` against classical MDS.

    Judged by the Gram error (any rotation, reflection or translation is right) on 25 points in ℝ³
    and on the graph distances of a 7-cycle (negative eigenvalues); a wrong one is matched against
    the typical slips (distances not squared, the ½, the order of the eigenpairs, the square roots,
    the centring, negative eigenvalues not clipped).

    Examples
    --------
    >>> def mine(D, dim):
    ...     n = len(D)
    ...     J = np.eye(n) - 1 / n
    ...     w, U = np.linalg.eigh(-0.5 * J @ (D * D) @ J)
    ...     return U[:, ::-1][:, :dim] * np.sqrt(np.maximum(w[::-1][:dim], 0))
    >>> check_classical_mds(mine, show=False).correct
    True
    >>> "squared" in check_classical_mds(lambda D, dim: mine(np.sqrt(D), dim), show=False).message
    True
    """
    def body() -> str:
        return judge_classical_mds(classical_mds, _visible_mds_cases())
    return run_check("09-classical-mds", show, body)


# --- 09-scaling: build it yourself ------------------------------------------------------------------

def _top(S: np.ndarray, dim: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``dim`` largest eigenpairs of a symmetric matrix, descending."""
    G, U = np.linalg.eigh(0.5 * (S + S.T))
    return G[::-1][:dim], U[:, ::-1][:, :dim]


def scaling_slips(phi: np.ndarray, alpha: np.ndarray, dim: int) -> tuple[np.ndarray, list[tuple[Any, str]]]:
    """The embedding by the k x k route, and the typical slips as (embedding or predicate, hint)."""
    J_phi = phi - phi.mean(axis=0)
    Q, R = np.linalg.qr(J_phi)
    S = -0.5 * (R @ alpha @ R.T)
    G, U = _top(S, dim)
    ref = Q @ (U * np.sqrt(np.maximum(G, 0.0)))

    def embed(Qx: np.ndarray, Sx: np.ndarray) -> np.ndarray:
        g, u = _top(Sx, dim)
        return Qx @ (u * np.sqrt(np.abs(g)))

    Q0, R0 = np.linalg.qr(phi)
    Ge, Ue = _top(-0.5 * alpha, dim)
    slips = [
        (embed(Q0, -0.5 * (R0 @ alpha @ R0.T)),
         "Not double-centred: B = −½ J D² J, so factor J Φ (`phi - phi.mean(axis=0)`), not Φ."),
        (Q @ (U * np.sqrt(np.maximum(2 * G, 0.0))),
         "Off by a factor √2 (your Gram matrix is twice the right one): B = −½ J D² J, mind the ½."),
        (embed(Q, 0.5 * (R @ alpha @ R.T)),
         "Those are the directions of B's most negative eigenvalues: a wrong sign (B = −½ J D² J, so the small matrix is "
         "−½ R α Rᵀ), or the smallest eigenpairs (`np.linalg.eigh` sorts ascending); keep the largest."),
        (Q @ (U * np.maximum(G, 0.0)),
         "The eigenvalues are not square-rooted: X = Q U_m G_m^½ (the Gram matrix X Xᵀ is Q U G Uᵀ Qᵀ)."),
        (Q @ (U / np.sqrt(np.maximum(G, 1e-300))),
         "G_m^(-½) where G_m^½ belongs: X = Q U_m G_m^½."),
        (J_phi @ (Ue * np.sqrt(np.maximum(Ge, 0.0))),
         "Φ is A-orthonormal (Φᵀ A Φ = I), not orthonormal: Φᵀ Φ ≠ I, and B is a plain n × n matrix. "
         "Factor J Φ = Q R (Euclidean) and eigendecompose −½ R α Rᵀ."),
        (embed(Q, -0.5 * (R.T @ alpha @ R)),
         "A transpose: the small matrix is −½ R α Rᵀ (R from J Φ = Q R), not −½ Rᵀ α R."),
        (J_phi @ (U * np.sqrt(np.maximum(G, 0.0))),
         "The last step maps back with Q, the orthonormal factor of J Φ = Q R: X = Q U_m G_m^½, not J Φ U_m G_m^½."),
    ]
    return ref, slips


def check_small_scaling(scaling: Any, phi: Any, alpha: Any, X_library: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-scaling: the student's ``scaling(phi, alpha, dim)``, spectral MDS's k x k step.

    ``phi`` (n x k, A-orthonormal eigenvectors) and ``alpha`` (k x k, ``D2 ~ Phi alpha Phi.T``)
    are those :func:`~lbo_notebooks.analyses.spectral_mds` used (``sampled="rows"``), and
    ``X_library`` its embedding. The attempt is compared with it by the Gram error (no alignment
    needed), then with ``dim = 2``; a wrong one is matched against the typical slips (missing
    double centring, the −½, square roots, the order of eigenpairs, Φᵀ Φ taken for I, a transpose).

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> phi = rng.normal(size=(50, 6)); a = rng.normal(size=(6, 6)); alpha = -(a @ a.T)
    >>> def mine(phi, alpha, dim):
    ...     Q, R = np.linalg.qr(phi - phi.mean(axis=0))
    ...     G, U = np.linalg.eigh(-0.5 * R @ alpha @ R.T)
    ...     return Q @ U[:, ::-1][:, :dim] * np.sqrt(G[::-1][:dim])
    >>> check_small_scaling(mine, phi, alpha, mine(phi, alpha, 3), show=False).correct
    True
    """
    from ..analyses._embedding_error import gram_error

    def body() -> str:
        phi_, alpha_ = np.asarray(phi, dtype=np.float64), np.asarray(alpha, dtype=np.float64)
        alpha_ = 0.5 * (alpha_ + alpha_.T)
        library = np.asarray(X_library, dtype=np.float64)
        n, k = phi_.shape
        for dim, reference in ((library.shape[1], library), (2, None)):
            X = call_attempt(scaling, phi_.copy(), alpha_.copy(), dim)
            try:
                X = np.asarray(X, dtype=np.float64)
            except (TypeError, ValueError):
                raise Stop(WRONG, f"Return an array, one row per vertex (n × dim); got {type(X).__name__}.") from None
            ref, slips = scaling_slips(phi_, alpha_, dim)
            if reference is None:
                reference = ref
            if X.shape == (dim, n):
                raise Stop(WRONG, f"Transposed: return one row per vertex, shape ({n}, {dim}), not ({dim}, {n}).")
            if X.shape == (k, dim):
                raise Stop(WRONG, "That is a k × dim matrix of coefficients (C = U_m G_m^½); the embedding is Q C, one row per vertex.")
            if dim == 2 and X.shape == (n, library.shape[1]):
                raise Stop(WRONG, "Asked for dim = 2, you returned the same number of columns as before: use the `dim` argument, not a fixed number.")
            if X.shape != (n, dim):
                raise Stop(WRONG, f"Return one row per vertex and one column per dimension, shape ({n}, {dim}); got {X.shape}.")
            if not np.all(np.isfinite(X)):
                raise Stop(WRONG, "NaN in your embedding: a square root of a negative eigenvalue? `np.linalg.eigh` sorts "
                                  "ascending, and B has negative eigenvalues at the bottom; keep the largest.")
            if np.linalg.norm(X) == 0:
                raise Stop(WRONG, "Your embedding is all zeros.")
            if gram_error(X, reference) <= 1e-6:
                continue
            for slip, hint in slips:
                if gram_error(X, slip) <= 1e-6:
                    raise Stop(WRONG, hint + ("" if dim != 2 else " (seen with dim = 2)"))
            if dim == 2:
                raise Stop(WRONG, "Right for dim = 3 but not for dim = 2: use the `dim` argument, not a fixed 3.")
            raise Stop(WRONG, "Not the library's embedding (Gram error above 1e-6). The steps: J Φ = Q R, B̃ = −½ R α Rᵀ, "
                              "the top eigenpairs B̃ = U G Uᵀ, then X = Q U_m G_m^½.")
        return ("Right: the library's embedding, from a k × k eigenproblem. B = −½ J Φ α Φᵀ J = Q B̃ Qᵀ with B̃ = −½ R α Rᵀ, "
                "and nothing n × n was formed.")
    return run_check("09-scaling", show, body)


# --- closing exercises ------------------------------------------------------------------------------

def check_fmm_gap(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-fmm: SMDS with fast-marching samples, against heat classical MDS: closer, same or farther."""
    return choose("09-fmm", answer, {
        "closer": "What is the reference computed from? Changing the sampled distances to another method changes "
                  "what is being approximated, not only how well.",
        "same": "The sampled distances enter D² directly: another geodesic method gives other numbers.",
        "farther": right("The reference is built from heat-method distances; fast marching has its own errors, so the "
                         "Gram error also measures the two methods' disagreement."),
    }, show)


def check_gram_2d(value: Any, X_smds: Any, X_classical: Any, *, show: bool = True) -> Feedback:
    """Exercise 10-two-d: the Gram error of 2-D spectral MDS against 2-D classical MDS.

    Both methods keep the top eigenpairs of one matrix, so their 2-D embeddings are the first two
    columns of the 3-D ones (up to signs); the reference is computed from those. Right within 1%
    (the typical slips are 8% and more away on the notebook's dog); a value copied from a printout
    that is right to its digits but coarser than that is asked for more digits.
    """
    from ..analyses._embedding_error import gram_error, procrustes_error

    def body() -> str:
        require_attempt(value)
        got = as_number(value, "a Gram error (a number)")
        S, C = np.asarray(X_smds, dtype=np.float64), np.asarray(X_classical, dtype=np.float64)
        ref = gram_error(S[:, :2], C[:, :2])
        if close_to(got, ref, 1e-2):
            return "Right: the Gram error of the two 2-D embeddings, as small as in 3-D."
        for slip, hint in (
            (gram_error(S[:, :2], C), "You compared with the 3-D classical embedding: compare like with like, both in 2-D."),
            (gram_error(S, C), "That is the 3-D Gram error; embed with `dim=2`."),
            (gram_error(C[:, :2], S[:, :2]), "The reference is classical MDS: `gram_error(Z, X)` takes the reference second."),
            (procrustes_error(S[:, :2], C[:, :2]), "That is the Procrustes error; the question asks for the Gram error."),
            (100 * ref, "That is a percentage; give the fraction."),
        ):
            if close_to(got, slip, 1e-2):
                raise Stop(WRONG, hint)
        if _rounded_from(got, ref):
            raise Stop(WRONG, _MORE_DIGITS)
        raise Stop(WRONG, "Use `gram_error(Z, X)` with Z the 2-D spectral MDS (`spectral_mds(..., dim=2)`) and X the 2-D classical MDS.")
    return run_check("10-two-d", show, body)


def check_landmark_samples(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 09-landmarks: landmark MDS with twice SMDS's samples: more, as, or less accurate than SMDS."""
    return choose("09-landmarks", answer, {
        "more": "Landmark MDS uses only the samples' distances to place each vertex, by triangulation; it interpolates "
                "nothing. Does doubling the samples make up for that?",
        "as": "Twice as many samples is a lot, but landmark MDS uses them differently: it interpolates nothing.",
        "less": right("Landmark MDS places each vertex from its distances to the samples alone, while SMDS "
                      "interpolates the whole squared-distance matrix: twice the samples do not make up for that."),
    }, show)


# --- recap ------------------------------------------------------------------------------------------

def _size(k: int, q: int) -> Callable[[Any], str | None]:
    def judge(answer: Any) -> str | None:
        try:
            got = as_number(answer)
        except Stop as stop:
            return stop.message
        if abs(got - (k + q)) < 1e-6:
            return None
        if abs(got - k) < 1e-6:
            return "k × k is the size with projected rows or pairs; the sampled fields add their own columns."
        if abs(got - q) < 1e-6:
            return "the eigenfunctions' columns count too."
        if any(abs(got - x) < 1e-6 for x in (k * k, (k + q) ** 2, k * q)):
            return "give the side of the square matrix, not its number of entries."
        return "count the columns of J [Φ, Fᵀ]."
    return judge


def recap_canonical_forms_judges(k: int = 200, q: int = 300) -> list[Callable[[Any], str | None]]:
    """The judges of the three questions of 09-recap (each: None when right, else a hint); shared by
    the visible check and the graded test (which gives a point per question)."""
    return [
        _size(int(k), int(q)),
        pick({"orthogonal map": right("equal geodesic distances give equal double-centred Gram matrices, so the "
                                      "embeddings agree up to an orthogonal map, reflections included."),
               "rigid motion": "almost: classical MDS cannot tell a shape from its mirror image, so reflections "
                               "are allowed too.",
               "scaling": "geodesic distances do not change when a pose bends, so neither does their scale.",
               "nothing": "classical MDS of equal distances gives equal Gram matrices."}),
        pick({"canonical forms": right("in section 3's control the farthest same-species pair of canonical forms is "
                                       "closer than the nearest pair across species; for raw poses it is not."),
               "raw poses": "a raw pose mixes the pose into the shape: section 3's control shows a pose farther from "
                            "its own species than the two species are apart.",
               "both": "look at section 3's control: one of the two fails."}),
    ]


def check_recap_canonical_forms(q1: Any, q2: Any, q3: Any, *, k: int = 200, q: int = 300, show: bool = True) -> Feedback:
    """Recap of the canonical-forms notebook: (1) the side of the small eigenproblem with fields
    (k, q the defaults), (2) how the canonical forms of two isometric poses differ, (3) which of
    canonical forms and raw poses separate the two species by their shape distributions."""
    return recap("09-recap", [q1, q2, q3], recap_canonical_forms_judges(k, q), show)


# --- the second notebook: accuracy, cost and resolution --------------------------------------------

def check_mu_range(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 10-mu: how much the Gram error of the paper's form (biharmonic energy) changes when
    the smoothness weight grows 500-fold: "less than half", "about double" or "more than tenfold"."""
    return choose("10-mu", answer, {
        "less than half": right("The biharmonic penalty on coefficient i grows like λᵢ²: it falls on the rough "
                                "eigenfunctions, hardly on the smooth ones that carry a distance field."),
        "about double": "The biharmonic penalty on coefficient i grows like λᵢ²: it weighs the rough eigenfunctions far "
                        "more than the smooth ones that carry most of a distance field.",
        "more than tenfold": "μ trades fitting the samples against smoothness, but the distance fields are smooth "
                             "already: what does a stronger penalty take away from them?",
    }, show)


def check_equal_size(n_c: Any, n: int, k: int = 200, q: int = 300, *, show: bool = True) -> Feedback:
    """Exercise 10-equal-size: the number of vertices ``n_c`` at which classical MDS's two n_c x n_c
    matrices hold as many floats as spectral MDS's n x (k + q) arrays Φ and F.

    Examples
    --------
    >>> check_equal_size((2000 * 500 / 2) ** 0.5, 2000, show=False).correct
    True
    >>> "two" in check_equal_size((2000 * 500) ** 0.5, 2000, show=False).message
    True
    """
    def body() -> str:
        require_attempt(n_c)
        got = as_number(n_c, "a number of vertices")
        floats = float(n) * (k + q)
        ref = np.sqrt(floats / 2)
        if close_to(got, ref, 0.01):
            return ("Right: 2 n_c² = n (k + q), so n_c grows only like √n: the same floats buy classical MDS "
                    "a far coarser mesh.")
        for slip, hint in (
            (np.sqrt(floats), "Classical MDS keeps *two* n_c × n_c matrices (D² and B): 2 n_c² = n (k + q)."),
            (np.sqrt(n * k / 2), "Spectral MDS keeps the sampled fields F (q × n) beside Φ (n × k): count both."),
            (np.sqrt(n * q / 2), "Spectral MDS keeps the eigenbasis Φ (n × k) beside F (q × n): count both."),
            (floats / 2, "n_c² is the number of entries of one matrix; take the square root to get vertices."),
            (floats, "That is the number of floats spectral MDS keeps; solve 2 n_c² = that for n_c."),
        ):
            if close_to(got, slip, 0.01):
                raise Stop(WRONG, hint)
        if _rounded_from(got, ref):
            raise Stop(WRONG, _MORE_DIGITS)
        raise Stop(WRONG, "Set the floats of two n_c × n_c matrices equal to those of the n × (k + q) arrays, and solve for n_c.")
    return run_check("10-equal-size", show, body)


def recap_mds_at_scale_judges() -> list[Callable[[Any], str | None]]:
    """The judges of the three questions of 10-cost-recap (each: None when right, else a hint); shared
    by the visible check and the graded test (which gives a point per question)."""
    return [
        pick({"yes": "with rows the embedding lives in the span of the eigenfunctions; see the dashed floor in the plot of "
                       "eigenfunctions and samples.",
               "no": right("with rows the embedding lies in the span of the 25 eigenfunctions: no number of samples "
                           "takes it below that span's floor, the dashed line.")}),
        number_judge(2.0, [(1.0, "that is how spectral MDS's memory grows (n × (k + q) arrays); classical MDS keeps "
                                 "n × n matrices."),
                           (3.0, "count the entries of an n × n matrix.")],
                     "count the entries of an n × n matrix."),
        pick({"spectral": right("at equal array size classical MDS must run on a much coarser mesh, whose errors its "
                                "canonical form carries, while spectral MDS keeps the full mesh."),
               "classical": "at equal array size classical MDS must run on a much coarser mesh, and a canonical form "
                            "carries the errors of the mesh it was computed on."}),
    ]


def check_recap_mds_at_scale(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of the accuracy-and-cost notebook: (1) whether more samples get projected rows with 25
    eigenfunctions under 1%, (2) the exponent of classical MDS's memory in n, (3) which canonical form
    is closer to the full-resolution answer at equal array size."""
    return recap("10-cost-recap", [q1, q2, q3], recap_mds_at_scale_judges(), show)
