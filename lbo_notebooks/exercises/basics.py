"""Self-checks of notebooks 01 (the shape collection) and 03 (the Laplace–Beltrami operator).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import lru_cache
from typing import Any

import numpy as np

from .feedback import (
    Feedback, WRONG, Stop, run_check, require_attempt, as_number, call_attempt, close_to,
    same_values, choose, pick, number_judge, recap,
)

__all__ = [
    "check_edge_count", "check_area_factor", "check_stretch_growth", "check_smallest_angles",
    "check_leg_area", "check_stiffness", "check_mass", "check_convergence_factor",
    "check_coefficients", "check_consistent_mass", "check_eigenvalue_scaling",
    "check_zero_eigenvalues", "check_recap_shapes", "check_recap_lbo",
]

# --- 01 · the shape collection -------------------------------------------------------------------

def check_recap_shapes(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 01: (1) what all poses of a creature share, (2) the Euler characteristic of
    every creature mesh, (3) where the stretch of a pose lies.

    Examples
    --------
    >>> check_recap_shapes("faces", 2, "joint bands", show=False).correct
    True
    """
    return recap("01-recap", [q1, q2, q3], [
        pick({"faces": None,
               "vertices": "a pose moves the vertices; what is the very same array in every pose?",
               "both": "a pose moves the vertices; only one of the two arrays is shared."}),
        number_judge(2.0, [(0.0, "that is a torus (genus 1); the creatures are genus 0."),
                           (1.0, "that is a disc; the creatures are closed surfaces of genus 0.")],
                     "V − E + F of a closed genus-0 surface."),
        pick({"joint bands": None,
               "everywhere": "a vertex whose whole one-ring is outside the bands moves rigidly with its bone: its edges "
                             "keep their length.",
               "tips": "the stretch goes where a joint's weight blends from 0 to 1; is that at the tips of the limbs?"}),
    ], show)


def check_edge_count(n_edges: Any, mesh: Any, *, show: bool = True) -> Feedback:
    """Exercise 01-edges: the number of edges of a closed triangle mesh, from its faces alone.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> ball = shapes.icosphere(1)
    >>> check_edge_count(3 * ball.n_faces // 2, ball, show=False).correct
    True
    >>> "two" in check_edge_count(3 * ball.n_faces, ball, show=False).message
    True
    """
    def body() -> str:
        require_attempt(n_edges)
        e, f = len(mesh.edges), mesh.n_faces
        got = as_number(n_edges, "a whole number")
        if got == e:
            chi = mesh.n_vertices - e + f
            return f"Right: each triangle has three edges and each edge borders two triangles, so E = 3F/2; here V - E + F = {chi}."
        if got == 3 * f:
            raise Stop(WRONG, "Off by a factor of two: three edges per triangle counts every edge twice, once from each of the two triangles it borders.")
        if got == e / 2:
            raise Stop(WRONG, "Off by a factor of two (too few): you divided once too often.")
        raise Stop(WRONG, "Count the edge slots (three per triangle), then ask how many triangles share each edge of a closed surface.")
    return run_check("01-edges", show, body)


def check_area_factor(prediction: Any, scale: float, *, show: bool = True) -> Feedback:
    """Exercise 01-area: by what factor does the area of a part grow when the part is scaled by ``scale``?"""
    def body() -> str:
        require_attempt(prediction)
        got = as_number(prediction)
        if close_to(got, scale**2):
            return "Right: lengths grow by s, areas by s²."
        if close_to(got, scale):
            raise Stop(WRONG, "That is the factor of the lengths; an area has two length dimensions.")
        if close_to(got, scale**3):
            raise Stop(WRONG, "That is how a volume scales; a surface area has two length dimensions.")
        if close_to(got, scale**-2) or close_to(got, 1 / scale):
            raise Stop(WRONG, "The part gets bigger, so its area grows: check the direction of your factor.")
        raise Stop(WRONG, "Think of a square of side L scaled by s: what is its new area?")
    return run_check("01-area", show, body)


def check_stretch_growth(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 01-stretch: what happens to the worst edge stretch when a bend's angle doubles?"""
    return choose("01-stretch", answer, {
        "same": "The stretch rθ/L depends on the angle θ: a larger bend over the same band stretches more.",
        "double": None,
        "quadruple": "rθ/L is linear in θ, not quadratic: you may be thinking of an area.",
        "half": "A larger bend stretches the outer side more, not less.",
    }, show)


def check_smallest_angles(angles: Any, species: str = "dog", *, show: bool = True) -> Feedback:
    """Exercise 01-angles: the smallest triangle angle (degrees) of ``creature(species, n_vertices=n)``, per size n."""
    def body() -> str:
        require_attempt(angles)
        if not isinstance(angles, Mapping) or not angles:
            raise Stop(WRONG, "Give a dict {number of vertices asked for: smallest angle in degrees}.")
        from ..creatures import creature
        from ..operators import corner_angles

        for n, got in angles.items():
            got = as_number(got, f"a number for n = {n}")
            exact = float(np.degrees(corner_angles(creature(species, n_vertices=int(n)))).min())
            if close_to(got, exact, 1e-3):
                continue
            if close_to(got, np.radians(exact), 1e-3):
                raise Stop(WRONG, "These look like radians: convert with `np.degrees`.")
            if got > 60:
                raise Stop(WRONG, f"n = {n}: every triangle has an angle of at most 60°, so the smallest angle cannot exceed 60°: take the minimum over all corners.")
            raise Stop(WRONG, f"n = {n}: not the smallest corner angle of that mesh; `corner_angles(mesh)` gives every corner's angle.")
        return "Right: those are the smallest corner angles of the meshes you built."
    return run_check("01-angles", show, body)


def check_leg_area(predicted: Any, n_vertices: int, species: str = "dog", *, show: bool = True) -> Feedback:
    """Exercise 01-legs: predicted total area for legs scaled by s, ``{s: area}``, against the built shapes (1%)."""
    def body() -> str:
        require_attempt(predicted)
        if not isinstance(predicted, Mapping) or not predicted:
            raise Stop(WRONG, "Give a dict {scale s: predicted total area}.")
        from ..creatures import creature, creature_parts

        template = creature(species, n_vertices=n_vertices)
        parts = creature_parts(species, n_vertices=n_vertices)
        legs = (parts["front_legs"] | parts["hind_legs"])[template.faces].all(axis=1)
        leg, rest = template.face_areas[legs].sum(), template.face_areas[~legs].sum()
        for s, got in predicted.items():
            s, got = float(s), as_number(got, f"a number for s = {s}")
            actual = creature(species, parts={"legs": s}, n_vertices=n_vertices).area
            if close_to(got, actual, 0.015):
                continue
            if s != 1 and close_to(got, s * leg + rest, 0.005):
                raise Stop(WRONG, f"s = {s}: the legs' area grows by s², not s.")
            if s != 1 and close_to(got, s**2 * (leg + rest), 0.005):
                raise Stop(WRONG, f"s = {s}: only the legs are scaled; the rest of the body keeps its area.")
            if s != 1 and close_to(got, s**2 * leg, 0.05):
                raise Stop(WRONG, f"s = {s}: add the area of the rest of the body.")
            raise Stop(WRONG, f"s = {s}: off by more than 1.5% from the scaled shape's area; prediction = (leg area) × s² + (rest).")
        return "Right: within 1.5% for every scale (the blend band at the hips and shoulders is not scaled by exactly s²)."
    return run_check("01-legs", show, body)


# --- 03 · the Laplace–Beltrami operator ----------------------------------------------------------

@lru_cache(maxsize=1)
def _test_meshes() -> tuple[Any, ...]:
    """Small meshes the build-it-yourself checks run on: a right triangle, an irregular closed
    surface and an open sheet with obtuse triangles."""
    from .. import shapes
    from ..mesh import Mesh

    rng = np.random.default_rng(28)
    triangle = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    ball = shapes.icosphere(1)
    blob = ball.with_vertices(ball.vertices * rng.uniform(0.8, 1.25, size=(ball.n_vertices, 1)))
    sheet = shapes.rectangle(2.0, 1.0, 4, 3)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.12, 0.12, size=(len(v), 2))
    v[:, 2] = 0.2 * np.sin(v[:, 0])
    return triangle, blob, sheet.with_vertices(v)


def _matrix(value: Any, n: int, name: str) -> np.ndarray:
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


def _diagnose_stiffness(m: np.ndarray, ref: np.ndarray) -> str | None:
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
    from ..operators import stiffness_matrix

    def body() -> str:
        for mesh in _test_meshes():
            m = _matrix(call_attempt(stiffness, mesh), mesh.n_vertices, "W")
            hint = _diagnose_stiffness(m, stiffness_matrix(mesh).toarray())
            if hint is not None:
                where = "the right triangle" if mesh.n_faces == 1 else f"a mesh of {mesh.n_vertices} vertices"
                raise Stop(WRONG, f"{hint} (first seen on {where}.)")
        return "Right: it matches `operators.stiffness_matrix` on a triangle, a closed surface and an open sheet."
    return run_check("03-stiffness", show, body)


def _pure_voronoi(mesh: Any) -> np.ndarray:
    """Circumcentric Voronoi areas without the mixed rule for obtuse triangles (a typical attempt)."""
    from ..operators import face_cotangents

    v, f = mesh.vertices, mesh.faces
    cot = face_cotangents(mesh)
    sq = np.stack([np.sum((v[f[:, (k + 1) % 3]] - v[f[:, (k + 2) % 3]]) ** 2, axis=1) for k in range(3)], axis=1)
    corner = np.stack([(sq[:, (k + 2) % 3] * cot[:, (k + 2) % 3] + sq[:, (k + 1) % 3] * cot[:, (k + 1) % 3]) / 8
                       for k in range(3)], axis=1)
    return np.bincount(f.ravel(), weights=corner.ravel(), minlength=mesh.n_vertices)


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
    from ..operators import mass_matrix

    def body() -> str:
        matches = {"voronoi": True, "barycentric": True}
        for mesh in _test_meshes():
            n = mesh.n_vertices
            m = _matrix(call_attempt(mass, mesh), n, "A")
            for kind in matches:
                matches[kind] &= same_values(m, mass_matrix(mesh, kind).toarray())
            if any(matches.values()):
                continue
            where = "the right triangle" if mesh.n_faces == 1 else f"a mesh of {n} vertices"
            if np.allclose(m, np.eye(n)):
                raise Stop(WRONG, "That is the identity, the Euclidean inner product: it weighs every vertex alike, whatever the size of its triangles. A weighs each vertex by its share of the area.")
            if same_values(m, mass_matrix(mesh, "consistent").toarray()):
                raise Stop(WRONG, "That is the consistent (full) mass matrix, a valid one, but the exercise asks for a lumped (diagonal) one: give each vertex its share of area on the diagonal.")
            d = np.diag(m)
            if np.abs(m - np.diag(d)).max() > 1e-12 * np.abs(d).max():
                raise Stop(WRONG, f"A lumped mass matrix is diagonal; yours has off-diagonal entries (on {where}).")
            if (d < 0).any():
                raise Stop(WRONG, "Negative areas: a triangle's area is ½ ‖(p1 - p0) × (p2 - p0)‖, a norm, never negative.")
            for kind in ("barycentric", "voronoi"):
                ref = mass_matrix(mesh, kind).diagonal()
                for factor, hint in ((2, "Twice too large: a triangle's area is *half* the norm of the cross product."),
                                     (3, "Three times too large: each triangle's area is shared among its three corners."),
                                     (6, "Six times too large: a triangle's area is half the norm of the cross product, and it is shared among three corners."),
                                     (0.5, "Half too small: a triangle's area is ½ ‖(p1 - p0) × (p2 - p0)‖ (only one ½)."),
                                     (1 / 3, "Three times too small: every corner of a triangle gets a share, not only one.")):
                    if same_values(d, factor * ref):
                        raise Stop(WRONG, hint)
            if same_values(d, _pure_voronoi(mesh)):
                raise Stop(WRONG, f"That is the pure Voronoi area, wrong at obtuse triangles (on {where}): use the mixed rule (half the triangle's area to an obtuse corner, a quarter to the others).")
            ratio = d.sum() / mesh.area
            raise Stop(WRONG, f"The diagonal should share out the surface area; on {where} it sums to {ratio:.3g} × the area." if not close_to(ratio, 1, 1e-8)
                        else f"The total is right but the shares are not (on {where}): a third of each triangle to each corner (barycentric), or the mixed Voronoi rule.")
        which = "mixed Voronoi" if matches["voronoi"] else "barycentric"
        return f"Right: that is the {which} mass matrix (both lumped masses are accepted; the library's default is mixed Voronoi)."
    return run_check("03-mass", show, body)


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
        phi, mass = spectrum.vectors, spectrum.mass
        g = np.asarray(f, dtype=np.float64)
        ref = spectrum.project(g)
        try:
            c = np.asarray(coefficients, dtype=np.float64)
        except (TypeError, ValueError):
            raise Stop(WRONG, f"Expected an array of coefficients, got {type(coefficients).__name__}.") from None
        if c.shape != ref.shape:
            if c.shape == g.shape:
                raise Stop(WRONG, f"One coefficient per eigenfunction: the result has length k = {ref.shape[0]}, not one value per vertex. A transpose (Φ instead of Φᵀ) or a reconstruction Φ c instead of c?")
            raise Stop(WRONG, f"Expected shape {ref.shape} (one coefficient per eigenfunction), got {c.shape}.")
        scale = max(np.abs(ref).max(), 1e-300)
        near = lambda other: np.abs(c - other).max() <= 1e-6 * scale  # noqa: E731
        if near(ref):
            return "Right: c = Φᵀ A f, the A inner product of f with each eigenfunction."
        if near(phi.T @ g):
            raise Stop(WRONG, "That is Φᵀ f, the Euclidean inner product: the eigenvectors are A-orthonormal, so the coefficients need the mass matrix.")
        if near(-ref):
            raise Stop(WRONG, "Wrong sign.")
        if near(2 * ref) or near(ref / 2):
            raise Stop(WRONG, "Off by a factor of two.")
        if near(phi.T @ (g / mass.diagonal())):
            raise Stop(WRONG, "You divided by the mass; the A inner product multiplies by it.")
        raise Stop(WRONG, "Not Φᵀ A f: take the A inner product ⟨φ_i, f⟩_A = φ_iᵀ A f for each eigenfunction φ_i.")
    return run_check("03-coefficients", show, body)


def check_consistent_mass(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 03-consistent: do the consistent-mass eigenvalues of the sphere lie above or below ℓ(ℓ+1)?"""
    return choose("03-consistent", answer, {
        "above": None,
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
    return recap("03-lbo-recap", [q1, q2, q3], [
        _zero_weight,
        number_judge(1.0, [(4.0, "W is made of cotangents of angles, and scaling keeps every angle; it is the mass A (areas) that grows by s²."),
                           (2.0, "W is made of cotangents of angles, and scaling keeps every angle."),
                           (0.25, "that is the factor of the eigenvalues (exercise 03-scaling); W alone is made of cotangents of angles."),
                           (0.5, "W is made of cotangents of angles, and scaling keeps every angle.")],
                     "W_ij = −½ (cot a + cot b) depends on the angles only: what does scaling do to an angle?"),
        pick({"a": "`Phi.T @ f` is the Euclidean inner product, the classic bug: the eigenvectors are A-orthonormal.",
              "b": None,
              "c": "the A inner product multiplies by A, it does not divide by it."}),
    ], show)
