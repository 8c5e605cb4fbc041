"""Self-checks of notebook 04 (your own data: repair, operators, point clouds).

The checks take the student's answer and return a :class:`~lbo_notebooks.exercises.feedback.Feedback`;
see :mod:`lbo_notebooks.exercises` for how an exercise works.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from .feedback import (Feedback, WRONG, Stop, run_check, require_attempt, as_number, close_to, choose, number_judge,
                       pick, recap, right)

__all__ = [
    "check_repair_counts", "check_operator_choice", "check_cloud_eigenvalue",
    "check_largest_component", "check_neighbors_effect", "check_cloud_pieces", "check_recap_your_data",
]

# --- 04 · your own data --------------------------------------------------------------------------

_REPAIR_PARTS = ("polygons_split", "vertices_welded", "degenerate_faces", "duplicate_faces",
                 "unreferenced_vertices", "non_manifold_edges", "n_components")
_REPAIR_HINTS: dict[str, Callable[[int, int], str | None]] = {
    "polygons_split": lambda got, true: "Only faces with more than three corners are split: how many quads did we write?",
    "vertices_welded": lambda got, true: ("Welding merges vertices with exactly the same coordinates: we wrote one exact copy of a vertex."
                                          if got == 0 else "Only exact copies are welded; noisy neighbours are different vertices."),
    "degenerate_faces": lambda got, true: ("A face whose three corners lie on one line has zero area too, like a face with a repeated corner."
                                           if got == true - 1 else "Count the zero-area faces: those with a repeated corner, and the flat (collinear) one."),
    "duplicate_faces": lambda got, true: ("One copy of each duplicated face is kept: count the faces removed, not the faces involved."
                                          if got == 2 * true else "A face written again with its corners reversed has the same three vertices: it is a duplicate."),
    "unreferenced_vertices": lambda got, true: (
        "Not only the vertices no face ever used: a vertex is also orphaned when every face that used it is "
        "removed or was never written (think of the flat face's corners, and of what the holes cut out)."
        if got < true else "Welded copies are counted as welded, not as unreferenced; count the vertices no face uses after the repair."),
    "non_manifold_edges": lambda got, true: ("Each fin has three edges, but only the one it shares with the sphere has three faces; "
                                             "its two other edges have one face each (a boundary)." if got == 3 * true
                                             else "An edge is non-manifold when more than two faces share it: where do the fins meet the sphere?"),
    "n_components": lambda got, true: ("The fins hang from edges of the sphere: they are part of its piece." if got > true
                                       else "Count every piece: the sphere (with its fins) and each flake of dust, the quad included."),
}


def check_repair_counts(prediction: Any, mesh: Any, *, show: bool = True) -> Feedback:
    """Exercise 04-repair: predicted counts of what ``clean=True`` repairs, against ``clean_mesh``'s report.

    ``prediction`` is a dict with the keys ``polygons_split``, ``vertices_welded``, ``degenerate_faces``,
    ``duplicate_faces``, ``unreferenced_vertices``, ``non_manifold_edges`` and ``n_components``;
    ``mesh`` is what was written to the file (``(vertices, faces)``, faces may be polygons).

    Examples
    --------
    >>> v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [5, 5, 5]]
    >>> counts = dict(polygons_split=0, vertices_welded=0, degenerate_faces=0, duplicate_faces=1,
    ...               unreferenced_vertices=1, non_manifold_edges=0, n_components=1)
    >>> check_repair_counts(counts, (v, [[0, 1, 2], [1, 3, 2], [2, 1, 0]]), show=False).correct
    True
    """
    def body() -> str:
        require_attempt(prediction)
        if not isinstance(prediction, Mapping):
            raise Stop(WRONG, "Give a dict with one count per key: " + ", ".join(_REPAIR_PARTS) + ".")
        missing = [k for k in _REPAIR_PARTS if k not in prediction]
        if missing:
            raise Stop(WRONG, "Some keys are missing: " + ", ".join(missing) + ".")
        from ..geometry._repair import clean_mesh

        _, report = clean_mesh(mesh)
        wrong = []
        for key in _REPAIR_PARTS:
            got, true = as_number(prediction[key], f"a whole number for {key}"), int(getattr(report, key))
            if got != true:
                wrong.append((key, int(got) if got == int(got) else got, true))
        if not wrong:
            return "Right: every count, including the vertices orphaned by the faces that were cut away or removed."
        key, got, true = wrong[0]
        others = f" ({len(wrong) - 1} other count{'s' if len(wrong) > 2 else ''} also off.)" if len(wrong) > 1 else ""
        raise Stop(WRONG, f"{key}: {_REPAIR_HINTS[key](got, true)}{others}")
    return run_check("04-repair", show, body)


def _operator_hint(name: str, mesh: Any, defects: list[str], answer: str) -> str:
    if answer == "robust":  # the mesh is fine for the cotangent Laplacian
        if mesh.n_components > 1:
            return (f"{name}: several pieces are no defect: the cotangent matrix is block-diagonal, one block "
                    "(and one zero eigenvalue) per piece.")
        if np.any(mesh.edge_face_counts == 1):
            return (f"{name}: a boundary (a hole) is no defect: an edge on it has one face, and its cotangent "
                    "weight then has one opposite angle instead of two.")
        return f"{name}: none of the defects `lbo.operators.cotan_defects` checks is there."
    text = " ".join(defects)
    if "non-manifold edge" in text:
        return (f"{name}: an edge shared by three faces has three opposite angles; the cotangent weight ½(cot a + cot b) "
                "is written for an edge between two triangles.")
    if "non-manifold vert" in text:
        return (f"{name}: every edge has at most two faces, but at one vertex the surface is pinched: two fans of "
                "triangles meet there at a single point, so around it the surface is not a disc.")
    return f"{name}: look at the smallest angles and the areas of its triangles: cotangents blow up near 0° and 180°."


def check_operator_choice(choice: Any, meshes: Mapping[str, Any], *, show: bool = True) -> Feedback:
    """Exercise 04-operator: which Laplacian ``eigenbasis(mesh, k)`` uses for each mesh, ``"cotan"`` or ``"robust"``.

    ``choice`` maps each name of ``meshes`` to ``"cotan"`` or ``"robust"``; the truth is whether
    :func:`lbo_notebooks.operators.cotan_defects` finds a defect.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> check_operator_choice({"ball": "cotan"}, {"ball": shapes.icosphere(1)}, show=False).correct
    True
    >>> check_operator_choice({"ball": ...}, {"ball": shapes.icosphere(1)}, show=False).status
    'not attempted'
    """
    def body() -> str:
        require_attempt(choice)
        entries = ", ".join(f'"{k}"' for k in meshes)
        if not isinstance(choice, Mapping):
            raise Stop(WRONG, f"Give a dict with one entry per mesh: {entries}.")
        given = {(k.strip().lower() if isinstance(k, str) else k): v for k, v in choice.items()}
        if len(given) != len(choice) or set(given) != set(meshes):
            raise Stop(WRONG, f"Give a dict with one entry per mesh (and nothing else): {entries}.")
        from ..operators._robust import cotan_defects

        for name, mesh in meshes.items():
            answer = given[name]
            if not isinstance(answer, str) or answer.strip().lower() not in ("cotan", "robust"):
                raise Stop(WRONG, f'{name}: answer "cotan" or "robust".')
            answer = answer.strip().lower()
            defects = cotan_defects(mesh)
            if answer != ("robust" if defects else "cotan"):
                raise Stop(WRONG, _operator_hint(name, mesh, defects, answer))
        return ("Right: what makes `eigenbasis` leave the cotangent Laplacian is local (an edge with more than two faces, "
                "a pinched vertex, needle or zero-area triangles: what `lbo.operators.cotan_defects` checks); holes and "
                "separate pieces are no defects.")
    return run_check("04-operator", show, body)


def _sphere_eigenvalue(k: int) -> float:
    ell = int(np.floor(np.sqrt(k)))  # indices l^2 .. l^2 + 2l belong to l (multiplicity 2l + 1)
    return float(ell * (ell + 1))


def _rounding_of(got: float, target: float) -> bool:
    """True when ``got``, as typed (its shortest decimal form), is ``target`` rounded to the digits
    it shows: -0.059 for -0.05935, 0.02 for 0.0193 (never 0, and never a computed value with more
    than six significant digits).

    Examples
    --------
    >>> _rounding_of(0.02, 0.0193), _rounding_of(0.019, 0.0193), _rounding_of(0.03, 0.0193), _rounding_of(0.0, 0.0193)
    (True, True, False, False)
    """
    from decimal import Decimal

    if got == 0 or not np.isfinite(got) or np.sign(got) != np.sign(target):
        return False
    digits = Decimal(repr(float(got))).as_tuple()
    if len(digits.digits) > 6 or not isinstance(digits.exponent, int):
        return False
    return abs(got - target) <= 0.5 * 10.0 ** digits.exponent * (1 + 1e-9)


def _near(got: float, target: float, rtol: float) -> bool:
    """Within ``rtol`` of ``target`` (relative), or ``target`` rounded by hand to the digits shown."""
    return abs(got - target) <= rtol * abs(target) + 1e-15 or _rounding_of(got, target)


def _more_digits(got: float) -> str:
    return (f"{got:g} is the right value rounded too coarsely for the check: give more digits "
            "(at least three significant ones), or the value Python computes.")


def check_cloud_eigenvalue(relative_error: Any, values: Any, k: int = 9, *, show: bool = True) -> Feedback:
    """Exercise 04-cloud: the signed relative error ``(λ_k - exact) / exact`` of eigenvalue ``k`` of the unit sphere.

    ``values`` are the computed eigenvalues (``values[0]`` the zero one); the exact value is
    ℓ(ℓ+1) for the ℓ with ℓ² ≤ k < (ℓ+1)².

    Examples
    --------
    >>> values = [0, 2, 2, 2, 6, 6, 6, 6, 6, 11.4]
    >>> check_cloud_eigenvalue(11.4 / 12 - 1, values, 9, show=False).correct
    True
    >>> "2ℓ+1" in check_cloud_eigenvalue(11.4 / 90 - 1, values, 9, show=False).message
    True
    """
    def body() -> str:
        require_attempt(relative_error)
        got = as_number(relative_error)
        lam, exact = float(np.asarray(values, dtype=np.float64)[k]), _sphere_eigenvalue(k)
        ref = lam / exact - 1
        near = lambda x: _near(got, x, 1e-3)  # noqa: E731
        if abs(got - ref) <= 1e-3 * abs(ref) + 1e-12:
            side = "below" if ref < 0 else "above"
            return f"Right: λ_{k} belongs to ℓ = {int(np.sqrt(k))}, and the cloud's value lies {side} ℓ(ℓ+1)."
        if _rounding_of(got, ref):
            raise Stop(WRONG, _more_digits(got))
        if near(-ref):
            raise Stop(WRONG, "Wrong sign: (computed - exact) / exact is negative when the computed value is below the exact one.")
        if near(abs(ref)):
            raise Stop(WRONG, "That is the size of the error; give it with its sign, (computed - exact) / exact.")
        if near(100 * ref):
            raise Stop(WRONG, "That is a percentage; give the fraction.")
        if near(lam - exact):
            raise Stop(WRONG, "That is the absolute error; divide by the exact value.")
        if near(exact / lam - 1):
            raise Stop(WRONG, "Upside down: divide by the exact value, not by the computed one.")
        if any(near(lam / (j * (j + 1)) - 1) for j in range(1, 12) if j * (j + 1) != exact):
            which = next(j for j in range(1, 12) if j * (j + 1) != exact and near(lam / (j * (j + 1)) - 1))
            if which == k:
                raise Stop(WRONG, f"The index k = {k} is not ℓ: the value ℓ(ℓ+1) is repeated 2ℓ+1 times "
                            "(once for ℓ = 0, three times for ℓ = 1, ...). Count which ℓ index k falls in.")
            raise Stop(WRONG, "You compared with the wrong ℓ: ℓ(ℓ+1) is repeated 2ℓ+1 times, and index 0 is ℓ = 0. "
                        "Count again which ℓ this index falls in.")
        raise Stop(WRONG, "Find ℓ for this index (ℓ(ℓ+1) is repeated 2ℓ+1 times, from index 0), then compute (computed - exact) / exact.")
    return run_check("04-cloud", show, body)


def check_largest_component(n_zeros: Any, worst_error: Any, path: Any, *, show: bool = True) -> Feedback:
    """Exercise 04-largest: zero eigenvalues of the scan's largest piece, and the worst relative error of the next 15.

    The check loads ``path`` with ``clean=True, keep_largest_component=True`` and compares
    eigenvalues 1 to 15 with ℓ(ℓ+1) of the unit sphere (the worst ``|λ/exact - 1|``, within 2%).
    """
    def body() -> str:
        require_attempt([n_zeros, worst_error])
        zeros = as_number(n_zeros, "a whole number of zero eigenvalues")
        worst = as_number(worst_error, "the worst relative error (a number)")
        import warnings

        from ..geometry._files import load_mesh
        from ..spectral._spectrum import eigenbasis

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            values = eigenbasis(load_mesh(path, clean=True, keep_largest_component=True), 16, progress=False).values
        exact = np.array([_sphere_eigenvalue(k) for k in range(16)])
        true_zeros = int(np.sum(np.abs(values) < 1e-8 * values[-1]))
        ref = float(np.max(np.abs(values[1:] / exact[1:] - 1)))
        if zeros != true_zeros:
            if zeros > true_zeros:
                raise Stop(WRONG, "keep_largest_component=True drops the flakes: how many pieces are left, "
                            "and how many functions constant on each piece?")
            raise Stop(WRONG, "A constant function still has zero energy: at least one eigenvalue is zero.")
        if close_to(worst, ref, 0.02):
            return "Right: one piece, one zero eigenvalue, then the sphere's spectrum, a little off (noise, holes, fins, and the discretisation itself)."
        if _rounding_of(worst, ref):
            raise Stop(WRONG, _more_digits(worst))
        if _near(worst, 100 * ref, 0.02):
            raise Stop(WRONG, "That is a percentage; give the fraction.")
        if worst > 10 * ref:
            raise Stop(WRONG, "Much too large: with one piece the spectrum starts at index 0, so compare values[1:16] with "
                        "exact[1:16] (index for index), and leave out the zero eigenvalue.")
        raise Stop(WRONG, "Take max |λ_k / ℓ(ℓ+1) - 1| over k = 1, ..., 15, with the eigenvalues of the largest piece.")
    return run_check("04-largest", show, body)


def check_neighbors_effect(answer: Any, *, show: bool = True) -> Feedback:
    """Exercise 04-neighbors: with ``n_neighbors=10``, do the cloud's eigenvalues get "closer" to ℓ(ℓ+1) or "further"?"""
    return choose("04-neighbors", answer, {
        "further": right("With 10 neighbours each point's local patch is built from fewer points, a cruder operator "
                         "here: the next cell measures a larger worst error than with 30."),
        "closer": "Run the cell after the check and compare the worst relative errors for 10 and 30 neighbours.",
        "same": "The neighbourhoods change, and so does the operator: run it and compare the errors.",
    }, show)


_GAP_RADII = (1.5, 1.75, 2.0)  # the outer radii exercise 04-gap asks about


def _radius_key(key: Any) -> float | None:
    """A dict key as a radius (1.5, np.float64(1.5), "1.5"), or None when it is not a number."""
    if isinstance(key, bool):
        return None
    try:
        value = float(np.asarray(key, dtype=np.float64).reshape(()))
    except Exception:  # noqa: BLE001 - any key type: the check never raises
        return None
    return value if np.isfinite(value) else None


def check_cloud_pieces(pieces: Any, n_neighbors: int = 30, radii: tuple[float, ...] = _GAP_RADII, *,
                       show: bool = True) -> Feedback:
    """Exercise 04-gap: ``{radius: number of pieces}`` the point cloud of two concentric spheres shows.

    The inner sphere is ``shapes.icosphere(3)`` (radius 1), the outer the same points scaled by
    the radius; the pieces are the zero eigenvalues of the point-cloud Laplacian. The dict must
    hold exactly the ``radii`` asked (1.5, 1.75 and 2 in the notebook), each once.

    Examples
    --------
    >>> check_cloud_pieces({2.5: 2}, radii=(2.5,), show=False).correct
    True
    >>> check_cloud_pieces({2.5: 2}, show=False).message
    'Radius 2.5 was not asked: give exactly the radii 1.5, 1.75 and 2, one entry each.'
    """
    asked = ", ".join(f"{r:g}" for r in radii[:-1]) + (" and " if len(radii) > 1 else "") + f"{radii[-1]:g}"

    def body() -> str:
        require_attempt(pieces)
        if not isinstance(pieces, Mapping) or not pieces:
            raise Stop(WRONG, f"Give a dict {{radius of the outer sphere: number of pieces}} for the radii {asked}.")
        given: dict[float, Any] = {}
        for key, got in pieces.items():
            radius = _radius_key(key)
            if radius is None:
                raise Stop(WRONG, f"The keys are the outer radii, numbers such as {radii[0]:g}; got {key!r}.")
            match = next((r for r in radii if abs(radius - r) <= 1e-9 * r), None)
            if match is None:
                above = "" if radius > 1 else " (the outer sphere's radius is above 1)"
                raise Stop(WRONG, f"Radius {radius:g} was not asked{above}: give exactly the radii {asked}, one entry each.")
            if match in given:
                raise Stop(WRONG, f"Radius {match:g} appears twice: give one entry per radius.")
            given[match] = got
        missing = [f"{r:g}" for r in radii if r not in given]
        if missing:
            which = f"radius {missing[0]}" if len(missing) == 1 else "radii " + ", ".join(missing)
            raise Stop(WRONG, f"Missing {which}: give the number of pieces for every radius asked, {asked}.")
        from .. import shapes
        from ..geometry._pointcloud import PointCloud
        from ..spectral._spectrum import eigenbasis

        inner = shapes.icosphere(3).vertices
        for radius in radii:
            got = as_number(given[radius], f"a whole number for radius {radius:g}")
            values = eigenbasis(PointCloud(np.vstack([inner, radius * inner])), 3, n_neighbors=n_neighbors,
                                progress=False).values
            true = int(np.sum(np.abs(values) < 1e-8 * values[-1]))
            if got == true:
                continue
            if got > true:
                raise Stop(WRONG, f"Radius {radius:g}: a neighbourhood is the {n_neighbors} nearest points, however far they are. "
                            "The outer sphere's points are sparser, so their neighbourhoods reach further: can they reach the inner sphere?")
            raise Stop(WRONG, f"Radius {radius:g}: the gap is wider than the outer points' neighbourhoods reach, so no patch joins the spheres.")
        return "Right: the spheres separate once the gap is wider than an outer point's neighbourhood reaches."
    return run_check("04-gap", show, body)


def check_recap_your_data(q1: Any, q2: Any, q3: Any, *, show: bool = True) -> Feedback:
    """Recap of notebook 04: (1) the zero eigenvalues of a scan in four pieces, (2) the operator
    ``eigenbasis`` picks for a mesh with an edge of three faces, (3) what a point cloud makes of two
    sheets closer than its neighbourhoods reach.

    Examples
    --------
    >>> check_recap_your_data(4, "robust", "fused", show=False).correct
    True
    """
    return recap("04-recap", [q1, q2, q3], recap_judges(), show)


def recap_judges() -> list[Callable[[Any], str | None]]:
    """The judges of the recap's three questions (each: an answer -> None when right, else a hint),
    shared by :func:`check_recap_your_data` and the graded test (partial credit)."""
    return [
        number_judge(4.0, [(1.0, "each connected component carries its own constant function with zero energy."),
                           (0.0, "a constant function has zero energy on every piece."),
                           (3.0, "the shape's own constant counts too: one zero per connected component.")],
                     "one zero eigenvalue per connected component."),
        pick({"robust": right("an edge with three faces is non-manifold, where the cotangent weight ½ (cot α + cot β) "
                              "is not defined, so `eigenbasis` falls back to the tufted Laplacian."),
               "cotan": "the cotangent weight ½ (cot α + cot β) is written for an edge between two triangles."}),
        pick({"fused": right("the point-cloud operator sees only Euclidean distances: neighbourhoods that reach across "
                             "the gap connect the local patches of both sheets."),
               "separate": "a neighbourhood is the nearest points, whatever sheet they lie on: the local patches "
                           "join the sheets."}),
    ]
