"""Self-checks of notebook 03 (the Laplace–Beltrami operator: the cotangent stiffness and mass
matrices, their spectrum).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np

from .basics import loose, more_digits, rounding_of
from .feedback import (
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, as_array, call_attempt, close_to,
    same_values, choose, pick, number_judge, recap, plain, right,
)

__all__ = [
    "check_stiffness",
    "check_mass",
    "check_eigensolve",
    "check_convergence_factor",
    "check_coefficients",
    "check_consistent_mass",
    "check_eigenvalue_scaling",
    "check_zero_eigenvalues",
    "check_recap_lbo",
]


# --- 03 · the Laplace–Beltrami operator ----------------------------------------------------------

@lru_cache(maxsize=1)
def _test_meshes() -> tuple[Any, ...]:
    """Small meshes the build-it-yourself checks run on: a right triangle, an irregular closed
    surface and an open sheet with obtuse triangles."""
    from .. import shapes
    from ..geometry._mesh import Mesh

    rng = np.random.default_rng(28)
    triangle = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    ball = shapes.icosphere(1)
    blob = ball.with_vertices(ball.vertices * rng.uniform(0.8, 1.25, size=(ball.n_vertices, 1)))
    sheet = shapes.rectangle(2.0, 1.0, 4, 3)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.12, 0.12, size=(len(v), 2))
    v[:, 2] = 0.2 * np.sin(v[:, 0])
    return triangle, blob, sheet.with_vertices(v)


def as_matrix(value: Any, n: int, name: str) -> np.ndarray:
    import scipy.sparse as sp

    if sp.issparse(value):
        value = value.toarray()
    try:
        m = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise Stop(WRONG, f"{name} should be a matrix (NumPy array or scipy.sparse); got {type(value).__name__}.") from None
    if m.shape != (n, n):
        raise Stop(WRONG, f"{name} should be n × n, one row and one column per vertex (n = {n}); got shape {m.shape}.")
    return m


def diagnose_stiffness(m: np.ndarray, ref: np.ndarray) -> str | None:
    """None if m is the stiffness matrix ref, else a hint at what is off."""
    if same_values(m, ref):
        return None
    if same_values(m, 2 * ref):
        return "Twice too large: W_ij = -½ (cot a + cot b); did you drop the ½, or add each triangle twice?"
    if same_values(m, ref / 2):
        return "Half too small: an interior edge has two opposite angles, one in each of its triangles; add both cotangents."
    if same_values(m, -ref):
        return "Wrong sign: W is positive semidefinite, with negative off-diagonal entries -½ (cot a + cot b) and a positive diagonal."
    d, d_ref = np.diag(m), np.diag(ref)
    off, off_ref = m - np.diag(d), ref - np.diag(d_ref)
    if not np.allclose(m, m.T, rtol=0, atol=1e-10 * np.abs(ref).max()):
        if same_values(off + off.T, off_ref):
            return "Only one of W_ij and W_ji is filled in: W is symmetric, so add each edge's weight at (i, j) and at (j, i)."
        return "W should be symmetric (the weight of edge ij is the weight of edge ji); yours is not."
    scale = max(np.abs(off_ref).max(), 1e-300)
    for factor, hint in ((1, None), (2, "twice too large (the ½)"), (0.5, "half too small (one of the two opposite angles missing)"),
                         (-1, "of the wrong sign (they are -½ (cot a + cot b) ≤ 0 for acute angles)")):
        if np.abs(off - factor * off_ref).max() <= 1e-8 * scale:
            if hint is not None:
                return f"The off-diagonal entries are {hint}."
            if np.abs(d).max() <= 1e-12 * scale:
                return "The diagonal is missing: each row of W sums to zero, so W_ii = -Σ_j W_ij."
            if np.abs(d + d_ref).max() <= 1e-8 * scale:
                return "The diagonal has the wrong sign: W_ii = -Σ_{j≠i} W_ij, which is positive."
            return "The off-diagonal entries are right but the diagonal is not: each row of W sums to zero."
    if np.abs(m.sum(axis=1)).max() > 1e-8 * np.abs(ref).max():
        return "The rows of W should sum to zero (constants have no energy); yours do not."
    return ("Not the cotangent weights: edge ij uses the angles *opposite* it (at the third corner of each of its "
            "triangles), cot = cos/sin. Try your function on the worked triangle first.")


def check_stiffness(stiffness: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-stiffness: the student's ``stiffness(mesh)`` against ``operators.stiffness_matrix``.

    Run on three small meshes (a right triangle, an irregular closed surface, an open sheet with
    obtuse triangles); the hint names the first thing that differs.

    Examples
    --------
    >>> from lbo_notebooks import operators
    >>> check_stiffness(operators.stiffness_matrix, show=False).correct
    True
    >>> print(check_stiffness(lambda mesh: 2 * operators.stiffness_matrix(mesh), show=False).message)
    Twice too large: W_ij = -½ (cot a + cot b); did you drop the ½, or add each triangle twice? (first seen on the right triangle.)
    """
    from ..operators._cotangent import stiffness_matrix

    def body() -> str:
        for mesh in _test_meshes():
            m = as_matrix(call_attempt(stiffness, mesh), mesh.n_vertices, "W")
            hint = diagnose_stiffness(m, stiffness_matrix(mesh).toarray())
            if hint is not None:
                where = "the right triangle" if mesh.n_faces == 1 else f"a mesh of {mesh.n_vertices} vertices"
                raise Stop(WRONG, f"{hint} (first seen on {where}.)")
        return "Right: it matches `operators.stiffness_matrix` on a triangle, a closed surface and an open sheet."
    return run_check("03-stiffness", show, body)


def _pure_voronoi(mesh: Any) -> np.ndarray:
    """Circumcentric Voronoi areas without the mixed rule for obtuse triangles (a typical attempt)."""
    from ..operators._cotangent import face_cotangents

    v, f = mesh.vertices, mesh.faces
    cot = face_cotangents(mesh)
    sq = np.stack([np.sum((v[f[:, (k + 1) % 3]] - v[f[:, (k + 2) % 3]]) ** 2, axis=1) for k in range(3)], axis=1)
    corner = np.stack([(sq[:, (k + 2) % 3] * cot[:, (k + 2) % 3] + sq[:, (k + 1) % 3] * cot[:, (k + 1) % 3]) / 8
                       for k in range(3)], axis=1)
    return np.bincount(f.ravel(), weights=corner.ravel(), minlength=mesh.n_vertices)


LUMPED_KINDS = ("voronoi", "barycentric")
"""The lumped mass matrices exercise 03-mass accepts (either one, the same on every mesh)."""


def _lumped_kinds(m: np.ndarray, mesh: Any) -> set[str]:
    """The lumped mass matrices of ``mesh`` that ``m`` is (to round-off)."""
    from ..operators._cotangent import mass_matrix

    return {kind for kind in LUMPED_KINDS if same_values(m, mass_matrix(mesh, kind).toarray())}


def _mass_hint(m: np.ndarray, mesh: Any, where: str) -> str:
    """Why ``m`` is not a lumped mass matrix of ``mesh`` (on ``where``, e.g. "a mesh of 42 vertices")."""
    from ..operators._cotangent import mass_matrix

    n = mesh.n_vertices
    if np.allclose(m, np.eye(n)):
        return ("That is the identity, the Euclidean inner product: it weighs every vertex alike, whatever the size of "
                "its triangles. A weighs each vertex by its share of the area.")
    if same_values(m, mass_matrix(mesh, "consistent").toarray()):
        return ("That is the consistent (full) mass matrix, a valid one, but the exercise asks for a lumped (diagonal) "
                "one: give each vertex its share of area on the diagonal.")
    d = np.diag(m)
    if np.abs(m - np.diag(d)).max() > 1e-12 * max(np.abs(d).max(), 1e-300):
        return f"A lumped mass matrix is diagonal; yours has off-diagonal entries (on {where})."
    if same_values(d, _pure_voronoi(mesh)):
        return (f"That is the pure Voronoi area, wrong at obtuse triangles (on {where}): use the mixed rule (half the "
                "triangle's area to an obtuse corner, a quarter to the others).")
    if (d < 0).any():
        return "Negative areas: a triangle's area is ½ ‖(p1 - p0) × (p2 - p0)‖, a norm, never negative."
    for kind in ("barycentric", "voronoi"):
        ref = mass_matrix(mesh, kind).diagonal()
        for factor, hint in ((2, "Twice too large: a triangle's area is *half* the norm of the cross product."),
                             (3, "Three times too large: each triangle's area is shared among its three corners."),
                             (6, ("Six times too large: a triangle's area is half the norm of the cross product, and "
                                  "it is shared among three corners.")),
                             (0.5, "Half too small: a triangle's area is ½ ‖(p1 - p0) × (p2 - p0)‖ (only one ½)."),
                             (1 / 3, "Three times too small: every corner of a triangle gets a share, not only one.")):
            if same_values(d, factor * ref):
                return hint
    ratio = d.sum() / mesh.area
    if not close_to(ratio, 1, 1e-8):
        return f"The diagonal should share out the surface area; on {where} it sums to {ratio:.3g} × the area."
    return (f"The total is right but the shares are not (on {where}): a third of each triangle to each corner "
            "(barycentric), or the mixed Voronoi rule.")


def judge_mass(mass: Any, meshes: Any, call: Any = call_attempt) -> str:
    """The message of a correct lumped ``mass`` on every mesh of ``meshes`` (``call(mass, mesh)``
    runs it), else Stop with the hint of the first mesh where it is wrong."""
    matches = set(LUMPED_KINDS)
    for mesh, where in meshes:
        m = as_matrix(call(mass, mesh), mesh.n_vertices, "A")
        kinds = _lumped_kinds(m, mesh)
        if matches & kinds:
            matches &= kinds
            continue
        if kinds:
            raise Stop(WRONG, f"One rule for every mesh: on {where} yours is the {' / '.join(sorted(kinds))} mass, "
                              "on an earlier mesh the other one.")
        raise Stop(WRONG, _mass_hint(m, mesh, where))
    which = "mixed Voronoi" if "voronoi" in matches else "barycentric"
    return f"Right: that is the {which} mass matrix (both lumped masses are accepted; the library's default is mixed Voronoi)."


def check_mass(mass: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-mass: the student's lumped ``mass(mesh)`` against the Voronoi or barycentric mass.

    Either lumped mass is accepted (the message says which one was built).

    Examples
    --------
    >>> from lbo_notebooks import operators
    >>> check_mass(lambda mesh: operators.mass_matrix(mesh, "barycentric"), show=False).correct
    True
    >>> import numpy as np
    >>> "Euclidean" in check_mass(lambda mesh: np.eye(mesh.n_vertices), show=False).message
    True
    """
    def body() -> str:
        meshes = [(mesh, "the right triangle" if mesh.n_faces == 1 else f"a mesh of {mesh.n_vertices} vertices")
                  for mesh in _test_meshes()]
        return judge_mass(mass, meshes)
    return run_check("03-mass", show, body)


# --- the generalised eigenproblem W phi = lam A phi (exercise 03-eigensolve) ---------------------

EIGEN_RTOL = 1e-7
"""How closely a built eigensolver must agree (about seven digits): each eigenvalue within
``EIGEN_RTOL`` times the largest one asked for, ``vectors.T @ A @ vectors`` within ``EIGEN_RTOL``
of the identity, and each pair's residual ``||W phi - lam A phi||`` within ``EIGEN_RTOL`` times
``||W||_1 ||phi||`` (a backward error: it does not depend on how ``phi`` is scaled). ``eigsh``
at its default tolerance and dense ``eigh`` come within 1e-13."""


def _two_spheres() -> Any:
    """Two disjoint pieces: a unit icosphere(1) and a bumpy, larger copy of it beside it."""
    from .. import shapes
    from ..geometry._mesh import Mesh

    ball = shapes.icosphere(1)
    rng = np.random.default_rng(41)
    other = 1.3 * ball.vertices * rng.uniform(0.9, 1.1, size=(ball.n_vertices, 1)) + [3.0, 0.0, 0.0]
    return Mesh(np.vstack([ball.vertices, other]), np.vstack([ball.faces, ball.faces + ball.n_vertices]))


@lru_cache(maxsize=1)
def _eigen_problems() -> tuple[tuple[Any, Any, int, str], ...]:
    """The pencils the visible check of 03-eigensolve runs on, as (W, A, k, where): the icosphere(1)
    (an exactly threefold eigenvalue, k = 4), the irregular blob and the open sheet of
    :func:`_test_meshes`, the sheet with the *consistent* (non-diagonal) mass."""
    from .. import shapes
    from ..operators._cotangent import mass_matrix, stiffness_matrix

    _, blob, sheet = _test_meshes()
    ball = shapes.icosphere(1)
    return ((stiffness_matrix(ball), mass_matrix(ball), 4, "the icosphere of 42 vertices, with a threefold eigenvalue"),
            (stiffness_matrix(blob), mass_matrix(blob), 7, f"an irregular closed surface of {blob.n_vertices} vertices"),
            (stiffness_matrix(sheet), mass_matrix(sheet, "consistent"), 5,
             f"an open sheet of {sheet.n_vertices} vertices with the consistent (non-diagonal) mass"))


def eigen_reference(W: Any, A: Any) -> tuple[np.ndarray, np.ndarray]:
    """Every eigenpair of ``W phi = lam A phi`` (dense ``scipy.linalg.eigh``; small pencils only)."""
    import scipy.linalg

    return scipy.linalg.eigh(W.toarray(), A.toarray())


def _eigen_parts(answer: Any, n: int, k: int) -> tuple[np.ndarray, np.ndarray]:
    """``(values, vectors)`` of an answer as float arrays of shapes (k,) and (n, k), or a 'wrong' stop."""
    answer = plain(answer)
    if not isinstance(answer, (tuple, list)) or len(answer) != 2:
        what = f"a {type(answer).__name__}" if not isinstance(answer, (tuple, list)) else f"{len(answer)} items"
        raise Stop(WRONG, f"Return a tuple `(values, vectors)`: the k eigenvalues and the n × k matrix of eigenvectors; "
                          f"got {what}.")
    values = as_array(answer[0], "the eigenvalues (a NumPy array of shape (k,)) first")
    vectors = as_array(answer[1], "the eigenvectors (an array of shape (n, k)) second")
    if values.ndim == 2 and vectors.ndim == 1:
        raise Stop(WRONG, "Swapped: return `(values, vectors)`, the eigenvalues first.")
    if values.ndim == 2 and 1 in values.shape:
        values = values.ravel()  # a row or a column of eigenvalues
    if values.ndim != 1:
        raise Stop(WRONG, f"The eigenvalues should be a 1-D array of shape (k,) = ({k},); got shape {values.shape}.")
    if values.size != k:
        raise Stop(WRONG, f"Asked for k = {k} eigenpairs, got {values.size} eigenvalues.")
    if vectors.shape == (k, n) and k != n:
        raise Stop(WRONG, f"The eigenvectors are the *columns*: shape (n, k) = ({n}, {k}), not ({k}, {n}). A transpose?")
    if vectors.shape != (n, k):
        raise Stop(WRONG, f"The eigenvectors should form an array of shape (n, k) = ({n}, {k}), one column per "
                          f"eigenvalue; got shape {vectors.shape}.")
    return values, vectors


def _eigenvalue_hint(v: np.ndarray, ref: np.ndarray, W: Any, k: int, tol: float, scale: float) -> str:
    """Why the sorted eigenvalues ``v`` are not the ``k`` smallest ``ref`` (ascending, all of them)."""
    def near(a: np.ndarray, b: np.ndarray) -> bool:
        return a.shape == b.shape and bool(np.abs(a - b).max() <= tol)

    top = max(abs(ref[-1]), scale)
    if near(v, ref[-k:]) or (v.min() > ref[k] and np.abs(v[:, None] - ref[None, -2 * k:]).min(axis=1).max() <= EIGEN_RTOL * top):
        return ("These are the *largest* eigenvalues, where Lanczos converges first. Ask for the eigenvalues nearest "
                "a small negative shift σ instead (shift-invert: `sigma=`, with `which=\"LM\"`).")
    if near(v, np.sort(-ref[:k])):
        return "Wrong sign: W is positive semidefinite, so every eigenvalue of Wφ = λAφ is ≥ 0."
    standard = np.linalg.eigvalsh(W.toarray())
    if near(v, standard[:k]) or near(v, standard[-k:]):
        return ("These are eigenvalues of W alone (Wφ = λφ): the problem is generalised, Wφ = λAφ; pass the mass "
                "matrix too (`M=A`).")
    if near(v, ref[1:k + 1]):
        return ("λ₀ = 0 is missing: the constant function has zero energy and is the first eigenvector; the k smallest "
                "include it.")
    if np.all(v != 0):
        shift = ref[:k] - np.sort(1 / v)
        if np.ptp(shift) <= tol and abs(shift.mean()) <= scale:
            return ("These are the eigenvalues ν = 1/(λ − σ) of the shift-inverted operator: turn them back, "
                    "λ = σ + 1/ν (`eigsh` does this itself when you pass `sigma=`).")
    if np.abs(v[:, None] - ref[None, :]).min(axis=1).max() <= tol:
        return ("Each of your values is an eigenvalue, but they are not the k smallest: a copy of a repeated eigenvalue "
                "is missing, or the shift σ is not just below 0 (shift-invert finds the eigenvalues nearest σ).")
    return ("Not the k smallest eigenvalues of Wφ = λAφ. Solve with W as the matrix and A as the mass (`M=A`), "
            "around a small negative shift σ, and keep what the solver returns for λ.")


def judge_eigenpairs(answer: Any, W: Any, A: Any, k: int, reference: tuple[np.ndarray, np.ndarray]) -> None:
    """None when ``answer`` is the ``k`` smallest eigenpairs of ``W phi = lam A phi``, else Stop with a hint.

    ``answer`` must be ``(values, vectors)``, ``values`` ascending (shape (k,)), ``vectors`` (n, k)
    A-orthonormal with column j an eigenvector of ``values[j]``. Any sign of each eigenvector and
    any A-orthonormal basis of a repeated eigenvalue's eigenspace are right: the eigenvalues are
    compared with ``reference`` (every eigenpair, :func:`eigen_reference`) relative to the largest
    one asked for, the vectors by their residuals and ``vectors.T @ A @ vectors`` (see
    :data:`EIGEN_RTOL`), and, where ``lam[k-1] < lam[k]``, their span with the reference's.
    """
    ref, ref_vectors = reference
    n = W.shape[0]
    values, vectors = _eigen_parts(answer, n, k)
    scale = float(max(np.abs(ref[:k]).max(), abs(ref[-1]) * 1e-12, 1e-300))
    tol = EIGEN_RTOL * scale
    if np.any(np.diff(values) < -tol):
        if np.abs(np.sort(values) - ref[:k]).max() <= tol:
            raise Stop(WRONG, "Right eigenvalues, but not in ascending order: sort them, and reorder the eigenvectors with "
                              "the same permutation (`order = np.argsort(values)`).")
    if np.abs(np.sort(values) - ref[:k]).max() > tol:
        raise Stop(WRONG, _eigenvalue_hint(np.sort(values), ref, W, k, tol, scale))
    norm_w = float(abs(W).sum(axis=0).max())  # ||W||_1 >= ||W||_2 for a symmetric W
    lengths = np.linalg.norm(vectors, axis=0)
    if np.any(lengths == 0):
        raise Stop(WRONG, "A column of your eigenvectors is zero: an eigenvector is nonzero.")
    Av = A @ vectors
    residual = np.linalg.norm(W @ vectors - Av * values, axis=0) / (norm_w * lengths)
    if residual.max() > EIGEN_RTOL:
        quotients = np.einsum("ij,ij->j", vectors, W @ vectors) / np.einsum("ij,ij->j", vectors, Av)
        own = np.linalg.norm(W @ vectors - Av * quotients, axis=0) / (norm_w * lengths)
        if own.max() <= EIGEN_RTOL:
            raise Stop(WRONG, "Each column is an eigenvector, but not of the eigenvalue at its index: reorder the vectors "
                              "with the values (the same permutation for both).")
        plain_residual = np.linalg.norm(W @ vectors - vectors * (np.einsum("ij,ij->j", vectors, W @ vectors) / lengths**2),
                                        axis=0) / (norm_w * lengths)
        if plain_residual.max() <= EIGEN_RTOL:
            raise Stop(WRONG, "These are eigenvectors of W alone (Wφ = λφ): the problem is Wφ = λAφ; pass the mass "
                              "matrix too (`M=A`).")
        j = int(np.argmax(residual))
        raise Stop(WRONG, f"Column {j} is not an eigenvector of values[{j}]: ‖Wφ − λAφ‖ is {residual[j]:.0e} × ‖W‖ ‖φ‖ "
                          "(round-off, about 1e-13, for an eigenpair).")
    gram = vectors.T @ Av
    if np.abs(gram - np.eye(k)).max() > EIGEN_RTOL:
        if np.abs(vectors.T @ vectors - np.eye(k)).max() <= 1e-6:
            raise Stop(WRONG, "Orthonormal in the Euclidean sense (ΦᵀΦ = I), but the eigenvectors of Wφ = λAφ are "
                              "normalised in the A inner product: φᵀAφ = 1, so that ΦᵀAΦ = I.")
        diagonal = np.diag(gram)
        if np.abs(gram - np.diag(diagonal)).max() <= EIGEN_RTOL * diagonal.max():
            raise Stop(WRONG, "A-orthogonal, but not A-normalised: divide each eigenvector by its A-norm √(φᵀAφ).")
        raise Stop(WRONG, "The eigenvectors are not A-orthogonal (ΦᵀAΦ should be I). Eigenvectors of different "
                          "eigenvalues are A-orthogonal by themselves; within a repeated eigenvalue choose an "
                          "A-orthonormal basis.")
    if ref[k] - ref[k - 1] > 1e-6 * scale:  # a gap after the k-th: the span is determined
        cosines = np.linalg.svd(ref_vectors[:, :k].T @ Av, compute_uv=False)
        if cosines.min() < 1 - EIGEN_RTOL:
            raise Stop(WRONG, "The vectors do not span the eigenspace of the k smallest eigenvalues.")
    return None


def judge_eigensolve(eigensolve: Any, problems: Any, call: Any = call_attempt, seen: str = "first seen on {}") -> str:
    """The message of a correct ``eigensolve(W, A, k)`` on every ``(W, A, k, where)`` of ``problems``
    (``call(eigensolve, W, A, k)`` runs it on copies), else Stop with the hint of the first miss,
    followed by ``seen`` (formatted with its ``where``) in parentheses."""
    for W, A, k, where in problems:
        try:
            answer = call(eigensolve, W.copy(), A.copy(), k)
        except Stop as stop:
            if stop.status == WRONG and "singular" in stop.message.lower():
                raise Stop(WRONG, f"{stop.message} W is singular (the constants are in its kernel): factorise "
                                  f"W − σA with a small *negative* shift σ, not σ = 0. ({seen.format(where)}.)") from None
            raise
        try:
            judge_eigenpairs(answer, W, A, k, eigen_reference(W, A))
        except Stop as stop:
            raise Stop(stop.status, f"{stop.message} ({seen.format(where)}.)") from None
    return ("Right: the k smallest eigenpairs, ascending and A-orthonormal, also where an eigenvalue is repeated "
            "and with a non-diagonal mass.")


def check_eigensolve(eigensolve: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-eigensolve: the student's ``my_eigenbasis(W, A, k)``, the k smallest eigenpairs of
    ``W phi = lam A phi`` as ``(values, vectors)``.

    Run on three small pencils (an icosphere with a threefold eigenvalue, an irregular blob, an
    open sheet with the consistent mass) against dense ``eigh``; any signs and any A-orthonormal
    basis of a repeated eigenvalue are accepted (:func:`judge_eigenpairs`).

    Examples
    --------
    >>> import scipy.linalg
    >>> def dense(W, A, k):
    ...     return scipy.linalg.eigh(W.toarray(), A.toarray(), subset_by_index=[0, k - 1])
    >>> check_eigensolve(dense, show=False).correct
    True
    >>> print(check_eigensolve(lambda W, A, k: dense(W, A, k)[::-1], show=False).message)
    Swapped: return `(values, vectors)`, the eigenvalues first. (first seen on the icosphere of 42 vertices, with a threefold eigenvalue.)
    """
    return run_check("03-eigensolve", show, lambda: judge_eigensolve(eigensolve, _eigen_problems()))


def check_convergence_factor(factor: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-convergence: by what factor does an O(h²) error drop when h is halved?"""
    def body() -> str:
        require_attempt(factor)
        got = as_number(factor)
        if close_to(got, 4.0, 0.1):
            return "Right: error ∝ h², so halving h divides it by 2² = 4."
        if close_to(got, 2.0, 0.1):
            raise Stop(WRONG, "That is first order, error ∝ h; this discretisation is second order, error ∝ h².")
        if close_to(got, 0.25, 0.1) or close_to(got, 0.5, 0.1):
            raise Stop(WRONG, "Give the factor by which the error *drops* (a number above 1): error_before / error_after.")
        if close_to(got, 8.0, 0.1) or close_to(got, 16.0, 0.1):
            raise Stop(WRONG, "That would be a higher order than h²: error ∝ h^p drops by 2^p when h halves, with p = 2 here.")
        raise Stop(WRONG, "If error ≈ C h^p and h becomes h/2, by what factor does the error change? Here p = 2.")
    return run_check("03-convergence", show, body)


def coefficient_hint(coefficients: Any, spectrum: Any, f: Any, rtol: float = 1e-6) -> str | None:
    """None when ``coefficients`` are those of ``f`` in ``spectrum``'s basis (Φᵀ A f, to ``rtol`` of
    their largest), else a hint. A list, a tuple or a column of them is accepted."""
    phi, mass = spectrum.vectors, spectrum.mass
    g = np.asarray(f, dtype=np.float64)
    ref = spectrum.project(g)
    try:
        c = np.asarray(coefficients, dtype=np.float64)
    except (TypeError, ValueError):
        return f"Expected an array of coefficients, got {type(coefficients).__name__}."
    if c.ndim == 2 and c.size == ref.size and 1 in c.shape:
        c = c.ravel()  # a column (or a row) of the coefficients
    if c.shape != ref.shape:
        if c.shape == g.shape:
            return (f"One coefficient per eigenfunction: the result has length k = {ref.shape[0]}, not one value per "
                    "vertex. A transpose (Φ instead of Φᵀ) or a reconstruction Φ c instead of c?")
        return f"Expected shape {ref.shape} (one coefficient per eigenfunction), got {c.shape}."
    if not np.all(np.isfinite(c)):
        return "Some coefficients are NaN or infinite."
    scale = max(np.abs(ref).max(), 1e-300)
    near = lambda other: np.abs(c - other).max() <= rtol * scale  # noqa: E731
    if near(ref):
        return None
    if near(phi.T @ g):
        return ("That is Φᵀ f, the Euclidean inner product: the eigenvectors are A-orthonormal, so the coefficients "
                "need the mass matrix.")
    if near(-ref):
        return "Wrong sign."
    if near(2 * ref) or near(ref / 2):
        return "Off by a factor of two."
    if near(phi.T @ (g / mass.diagonal())):
        return "You divided by the mass; the A inner product multiplies by it."
    return "Not Φᵀ A f: take the A inner product ⟨φ_i, f⟩_A = φ_iᵀ A f for each eigenfunction φ_i."


def check_coefficients(coefficients: Any, spectrum: Any, f: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-coefficients: the coefficients of ``f`` in the eigenbasis, written by hand.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(2), 9)
    >>> f = shapes.icosphere(2).vertices[:, 2]
    >>> check_coefficients(s.vectors.T @ (s.mass @ f), s, f, show=False).correct
    True
    >>> "Euclidean" in check_coefficients(s.vectors.T @ f, s, f, show=False).message
    True
    """
    def body() -> str:
        require_attempt(coefficients)
        hint = coefficient_hint(coefficients, spectrum, f)
        if hint is not None:
            raise Stop(WRONG, hint)
        return "Right: c = Φᵀ A f, the A inner product of f with each eigenfunction."
    return run_check("03-coefficients", show, body)


def check_consistent_mass(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-consistent: do the consistent-mass eigenvalues of the sphere lie above or below ℓ(ℓ+1)?"""
    return choose("03-consistent", answer, {
        "above": right("The consistent-mass eigenvalues for ℓ = 2 … 5 all lie above ℓ(ℓ+1), the lumped ones below; "
                       "now explain why, below the check."),
        "below": "Look at the computed values again: the lumped ones are below, the consistent ones are not.",
        "equal": "Neither discretisation is exact on a sphere made of flat triangles.",
    }, show)


def check_eigenvalue_scaling(factor: Any, scale: float = 2.0, *, show: bool = True) -> Feedback:
    """Exercise 03-scaling: the factor by which every eigenvalue changes when the shape is scaled by ``scale``."""
    def body() -> str:
        require_attempt(factor)
        got = as_number(factor)
        if close_to(got, scale**-2, 1e-3):
            return "Right: λ has units of 1/length², so scaling lengths by s divides every eigenvalue by s²."
        if rounding_of(factor, scale**-2):
            raise Stop(WRONG, more_digits("That is "))
        if close_to(got, scale**2, 1e-3):
            raise Stop(WRONG, "Upside down: a bigger shape vibrates more slowly, so its eigenvalues get smaller.")
        if close_to(got, 1 / scale, 1e-3) or close_to(got, scale, 1e-3):
            raise Stop(WRONG, "λ has units of 1/length² (think of π²/a² on an interval of length a), not 1/length.")
        if close_to(got, 1.0, 1e-3):
            raise Stop(WRONG, "Scaling is not an isometry: lengths change, and so does the spectrum.")
        raise Stop(WRONG, "What are the units of λ in W φ = λ A φ? (W is unitless on a surface; A is an area.)")
    return run_check("03-scaling", show, body)


def check_zero_eigenvalues(torus: Any, two_spheres: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-kernel: the number of zero eigenvalues of a torus and of two disjoint spheres."""
    def body() -> str:
        require_attempt([torus, two_spheres])
        t, s = as_number(torus, "a whole number"), as_number(two_spheres, "a whole number")
        if (t, s) == (1, 2):
            return "Right: one zero eigenvalue per connected component (a constant on each); the genus does not matter."
        if t != 1:
            raise Stop(WRONG, "The torus: the handle does not matter, only how many pieces the surface has; a zero eigenvalue means zero energy, a function constant on each piece.")
        raise Stop(WRONG, "Two disjoint spheres: a function constant on each sphere separately has zero energy too.")
    return run_check("03-kernel", show, body)


def _zero_weight(answer: Any) -> str | None:
    """Judge of recap question 1: the weight is zero (round-off of ``1 / np.tan(np.pi / 2)`` accepted)."""
    try:
        value = as_number(answer)
    except Stop as stop:
        return stop.message
    if abs(value) <= 1e-9:
        return None
    if close_to(value, 0.5) or close_to(value, 1.0):
        return "cot 90° = cos 90° / sin 90°: what is cos 90°?"
    if not np.isfinite(value) or abs(value) > 1e6:
        return "the cotangent, cos/sin, is finite at 90°; it is the tangent that blows up."
    return "the triangle gives the edge ½ cot θ, θ the angle opposite it; what is cot 90°?"


RECAP_LBO = [
    _zero_weight,
    number_judge(1.0, [(4.0, ("W is made of cotangents of angles, and scaling keeps every angle; it is the mass A "
                              "(areas) that grows by s².")),
                       (2.0, "W is made of cotangents of angles, and scaling keeps every angle."),
                       (0.25, ("that is the factor of the eigenvalues (exercise 03-scaling); W alone is made of "
                               "cotangents of angles.")),
                       (0.5, "W is made of cotangents of angles, and scaling keeps every angle.")],
                 "W_ij = −½ (cot a + cot b) depends on the angles only: what does scaling do to an angle?"),
    loose(pick({"a": "`Phi.T @ f` is the Euclidean inner product, the classic bug: the eigenvectors are "
                      "A-orthonormal.",
                 "b": right("the eigenvectors are A-orthonormal, so the coefficient of f on φ_k is the A inner "
                            "product φ_kᵀ A f."),
                 "c": "the A inner product multiplies by A, it does not divide by it."})),
]
"""The judges of the recap's three questions; the graded test reuses them."""


def check_recap_lbo(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 03 (the LBO): (1) the weight a triangle gives the edge opposite a right angle,
    (2) the factor by which W changes when the mesh is scaled by 2, (3) the coefficients' formula.

    Examples
    --------
    >>> check_recap_lbo(0, 1, "b", show=False).correct
    True
    >>> "angles" in check_recap_lbo(0, 4, "b", show=False).message
    True
    """
    return recap("03-lbo-recap", [q1, q2, q3], RECAP_LBO, show)
