"""The graded tests of notebook 08 (scale-invariant metrics), with answers written as students write
them: the instructor's solution, correct answers written differently, typical wrong ones (hand-rounded
values among them: judged on their precision, not their method), placeholders; see
lbo_notebooks/exercises/grading/nb08.py. Also the notebook's claims that the old hidden tests
asserted, kept here as facts of the library (they belong to no student's answer)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from .grading_support import answers, assert_full, assert_zero, full_points, graded, solution_of, stub_of, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "08_scale_invariant.ipynb"
TWO_PI = 2 * np.pi


def solution(exercise: str) -> str:
    return solution_of(NOTEBOOK, exercise)


def student_edition(exercise: str) -> str:
    return stub_of(NOTEBOOK, exercise)


@pytest.fixture(scope="module")
def horse():
    """The notebook's horse; the grader's own rebuild (cached in its module), so that it is built once."""
    from lbo_notebooks.exercises.grading import load_graders

    load_graders("08-floor")
    from lbo_notebooks.exercises.grading import nb08

    return nb08._horse()


@pytest.fixture(scope="module")
def floor_count(horse):
    from lbo_notebooks.operators import _curvature as curvature

    at_floor = curvature.metric_curvature(horse, floor=1.0) <= 4 * np.pi / horse.area * (1 + 1e-12)
    return int(at_floor.sum()), horse.n_vertices


_full = assert_full
_zero = assert_zero


def test_points_follow_the_kinds():
    exercises = ("08-curvature", "08-gauss-bonnet", "08-scaling", "08-best", "08-floor", "08-sphere",
                 "08-consistent", "08-recap")
    assert [full_points(e) for e in exercises] == [1, 1, 1, 1, 2, 1, 1, 3]


def test_the_graded_run_ignores_a_patched_kernel(monkeypatch):
    """Through the real fresh process: patching the checks here (the kernel) changes no grade."""
    from lbo_notebooks import exercises

    monkeypatch.setattr(exercises.Feedback, "correct", property(lambda self: True))
    assert graded("08-gauss-bonnet", torus_total=0, disk_total=6.28) == 1.0
    assert graded("08-curvature", curvature_factor=1 / 3) == 0.0


# --- 08-curvature (predict, then compute) --------------------------------------------------------------

def test_curvature():
    _full("08-curvature", **answers(solution("08-curvature"), "curvature_factor"))
    code = """
        ring = shapes.torus()
        K, K3 = lbo.gaussian_curvature(ring), lbo.gaussian_curvature(ring.with_vertices(3 * ring.vertices))
        i = np.argmax(np.abs(K))
        curvature_factor = K3[i] / K[i]
    """
    _full("08-curvature", **answers(code, "curvature_factor"))
    for right in (3.0**-2, 0.111, 0.1111, np.float32(1 / 9), "0.111111"):
        _full("08-curvature", curvature_factor=right)


def test_curvature_wrong_answers():
    _zero("08-curvature", "principal curvatures", curvature_factor=1 / 3)
    _zero("08-curvature", "principal curvatures", curvature_factor=0.33)      # 1/3 rounded: still that slip
    _zero("08-curvature", "upside down", curvature_factor=9)
    _zero("08-curvature", "upside down", curvature_factor=3)
    _zero("08-curvature", "per unit area", curvature_factor=1)
    _zero("08-curvature", "δ_i", curvature_factor=0.5)
    message = _zero("08-curvature", "more digits", curvature_factor=0.11)       # 1/9, rounded too coarsely
    assert "δ_i" not in message
    _zero("08-curvature", status="not attempted", **answers(student_edition("08-curvature"), "curvature_factor"))
    assert verdict("08-curvature", curvature_factor=0.11) == verdict("08-curvature", curvature_factor=0.11)


def test_curvature_claim_of_the_old_hidden_test():
    """Scaling the torus by 3 divides K by 9 at every vertex."""
    import lbo_notebooks as lbo
    from lbo_notebooks import shapes

    ring = shapes.torus()
    K_ring = lbo.gaussian_curvature(ring)
    K_big = lbo.gaussian_curvature(ring.with_vertices(3 * ring.vertices))
    assert np.allclose(K_big, K_ring / 9, rtol=1e-10, atol=1e-12 * np.abs(K_ring).max())


# --- 08-gauss-bonnet (predict, then run) -----------------------------------------------------------------

def test_gauss_bonnet():
    _full("08-gauss-bonnet", **answers(solution("08-gauss-bonnet"), "torus_total", "disk_total"))
    code = """
        totals = []
        for mesh in (shapes.torus(), shapes.disk()):
            a = lbo.mass_matrix(mesh, "voronoi").diagonal()
            totals.append(float(lbo.gaussian_curvature(mesh) @ a))
        torus_total, disk_total = totals
    """
    _full("08-gauss-bonnet", **answers(code, "torus_total", "disk_total"))
    _full("08-gauss-bonnet", torus_total=0, disk_total=6.28)                  # 2π, by hand
    _full("08-gauss-bonnet", torus_total=0.0, disk_total=6.2832)
    _full("08-gauss-bonnet", torus_total=-0.0, disk_total=2 * np.pi * 1)


def test_gauss_bonnet_wrong_answers():
    _zero("08-gauss-bonnet", "euler characteristics", torus_total=0, disk_total=1)
    _zero("08-gauss-bonnet", "torus", torus_total=4 * np.pi, disk_total=TWO_PI)   # χ = 2, a sphere's
    _zero("08-gauss-bonnet", "torus", torus_total=TWO_PI, disk_total=0)           # swapped
    _zero("08-gauss-bonnet", "disk", torus_total=0, disk_total=4 * np.pi)
    _zero("08-gauss-bonnet", "disk", torus_total=0, disk_total=np.pi)
    message = _zero("08-gauss-bonnet", "more digits", torus_total=0, disk_total=6.3)
    assert "V − E + F" not in message
    _zero("08-gauss-bonnet", status="not attempted",
          **answers(student_edition("08-gauss-bonnet"), "torus_total", "disk_total"))
    _zero("08-gauss-bonnet", "every part", torus_total=0, disk_total=...)
    assert verdict("08-gauss-bonnet", torus_total=0, disk_total=1) == verdict("08-gauss-bonnet", torus_total=0, disk_total=1)


def test_gauss_bonnet_claim_of_the_old_hidden_test():
    """Σ K_i a_i is 2πχ to round-off: 0 on the torus, 2π on the disk."""
    import lbo_notebooks as lbo
    from lbo_notebooks import shapes

    for mesh, total in ((shapes.torus(), 0.0), (shapes.disk(), TWO_PI)):
        Ka = lbo.gaussian_curvature(mesh) * lbo.mass_matrix(mesh, "voronoi").diagonal()
        assert abs(Ka.sum() - total) < 1e-12 * np.abs(Ka).sum()


# --- 08-scaling (predict, then run) -----------------------------------------------------------------------

RIGHT_FACTORS = {a: 3.0 ** (-2 * (1 - a)) for a in (0.0, 0.4, 1.0)}


def test_scaling():
    _full("08-scaling", **answers(solution("08-scaling"), "metric_factors"))
    _full("08-scaling", metric_factors={0: 1 / 9, 0.4: 3**-1.2, 1: 1})                 # int keys
    _full("08-scaling", metric_factors={0.0: 0.111, 0.4: 0.268, 1.0: 1.0})               # rounded by hand, 3 digits
    _full("08-scaling", metric_factors={np.float64(a): np.float32(f) for a, f in RIGHT_FACTORS.items()})
    _full("08-scaling", metric_factors={"0": 1 / 9, "0.4": 3**-1.2, "1": 1})            # numbers as strings
    _full("08-scaling", metric_factors=[1 / 9, 3**-1.2, 1.0])                            # in the question's order
    _full("08-scaling", metric_factors={**RIGHT_FACTORS, 0.7: 3.0**-0.6})                # one more α, right too


def test_scaling_wrong_answers():
    _zero("08-scaling", "upside down", metric_factors={**RIGHT_FACTORS, 0.4: 3.0**1.2})
    _zero("08-scaling", "not s", metric_factors={**RIGHT_FACTORS, 0.4: 3.0**-0.6})
    _zero("08-scaling", "regular metric", metric_factors={**RIGHT_FACTORS, 1.0: 1 / 9})
    _zero("08-scaling", "only α = 1", metric_factors={**RIGHT_FACTORS, 0.4: 1.0})
    _zero("08-scaling", "missing", metric_factors={0.0: 1 / 9, 1.0: 1.0})               # incomplete
    _zero("08-scaling", "keys", "'alpha=0'", metric_factors={"alpha=0": 1 / 9, 0.4: 3**-1.2, 1.0: 1.0})
    _zero("08-scaling", "keys", metric_factors={None: 1 / 9, 0.4: 3**-1.2, 1.0: 1.0})
    _zero("08-scaling", "more digits", metric_factors={**RIGHT_FACTORS, 0.4: 0.27})
    _zero("08-scaling", "dict", metric_factors=[1 / 9, 1.0])
    _zero("08-scaling", status="not attempted", **answers(student_edition("08-scaling"), "metric_factors"))
    _zero("08-scaling", "every part", metric_factors={**RIGHT_FACTORS, 0.4: ...})
    given = {**RIGHT_FACTORS, 0.4: 3.0**1.2}
    assert verdict("08-scaling", metric_factors=given) == verdict("08-scaling", metric_factors=given)


# --- 08-best (predict, then run) ---------------------------------------------------------------------------

def test_best():
    _full("08-best", **answers(solution("08-best"), "best_alpha_curved"))
    for right in (1.0, "1", np.int64(1), " 1.0 "):
        _full("08-best", best_alpha_curved=right)
    _zero("08-best", "evenly", best_alpha_curved=0)
    _zero("08-best", "compromise", best_alpha_curved=0.4)
    _zero("08-best", "compromise", best_alpha_curved="0.4")
    _zero("08-best", "one of", best_alpha_curved=0.7)
    _zero("08-best", "one of", best_alpha_curved="the scale-invariant one")
    _zero("08-best", status="not attempted", **answers(student_edition("08-best"), "best_alpha_curved"))
    assert verdict("08-best", best_alpha_curved=0.4) == verdict("08-best", best_alpha_curved=0.4)


# --- 08-floor (compute, then explain: a value, and a written answer graded by a person) ---------------------

def test_floor_solution(horse):
    import lbo_notebooks as lbo

    _full("08-floor", **answers(solution("08-floor"), "floor_fraction", horse=horse, operators=lbo.operators, lbo=lbo))


def test_floor_written_differently(horse, floor_count):
    from lbo_notebooks.operators import _curvature as curvature

    count, n = floor_count
    code = """
        rho = curvature.metric_curvature(horse, floor=1.0)
        floor_fraction = np.isclose(rho, 4 * np.pi / horse.area, rtol=1e-9).sum() / horse.n_vertices
    """
    _full("08-floor", **answers(code, "floor_fraction", horse=horse, curvature=curvature))
    code = """
        level = 1.0 * 4 * np.pi / horse.area
        below = [r for r in curvature.metric_curvature(horse) if r <= level]   # the default floor, then compare
        floor_fraction = len(below) / horse.n_vertices
    """
    _full("08-floor", **answers(code, "floor_fraction", horse=horse, curvature=curvature))
    _full("08-floor", floor_fraction=float(f"{count / n:.4f}"))            # rounded by hand, enough digits
    _full("08-floor", floor_fraction=str(count / n))


def test_floor_wrong_answers(horse, floor_count):
    from lbo_notebooks.operators import _curvature as curvature

    count, n = floor_count
    _zero("08-floor", "percentage", floor_fraction=100 * count / n)
    _zero("08-floor", "percentage", floor_fraction=float(f"{100 * count / n:.1f}"))
    _zero("08-floor", "above", floor_fraction=1 - count / n)
    _zero("08-floor", "number of vertices", floor_fraction=count)
    code = "floor_fraction = np.mean(curvature.metric_curvature(horse, floor=1.0) <= 1.0)   # the floor itself"
    _zero("08-floor", "4π / area", **answers(code, "floor_fraction", horse=horse, curvature=curvature))
    _zero("08-floor", "metric_curvature", floor_fraction=(count + 40) / n)
    for coarse in (float(f"{count / n:.3f}"), float(f"{count / n:.2f}")):
        message = _zero("08-floor", "more digits", "decimals", floor_fraction=coarse)
        assert "metric_curvature" not in message
    _zero("08-floor", "number", floor_fraction="about 15%")
    _zero("08-floor", status="not attempted", **answers(student_edition("08-floor"), "floor_fraction"))
    assert verdict("08-floor", floor_fraction=0.2) == verdict("08-floor", floor_fraction=0.2)


def test_floor_has_a_written_answer_after_its_check():
    cells = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
    ids = [c["metadata"].get("nbgrader", {}).get("grade_id") for c in cells]
    k = ids.index("08-floor-check")
    written = cells[k + 1]
    meta = written["metadata"]["nbgrader"]
    assert written["cell_type"] == "markdown" and ids[k + 1] == "08-floor-explain"
    assert meta["grade"] and meta["solution"] and not meta["locked"] and meta["points"] == 2
    text = "".join(written["source"])
    assert text.startswith("**Model answer.**") and "**Rubric (2 points).** 1 point:" in text
    assert "in the cell below the check" in "".join(cells[ids.index("08-floor-answer") - 1]["source"])
    assert "# The floor only matters" not in solution("08-floor")    # the explanation moved out of the code


# --- 08-sphere, 08-consistent (predict, then run) -------------------------------------------------------------

def test_sphere():
    _full("08-sphere", **answers(solution("08-sphere"), "sphere_verdict"))
    for right in ("Equal", " EQUAL ", np.str_("equal")):
        _full("08-sphere", sphere_verdict=right)
    _zero("08-sphere", "|K|^α", sphere_verdict="scaled")
    _zero("08-sphere", "|K|^α", sphere_verdict="Unrelated")
    _zero("08-sphere", "one of", sphere_verdict="the same")
    _zero("08-sphere", "one of", sphere_verdict=1)
    _zero("08-sphere", status="not attempted", **answers(student_edition("08-sphere"), "sphere_verdict"))
    assert verdict("08-sphere", sphere_verdict="scaled") == verdict("08-sphere", sphere_verdict="scaled")


def test_consistent():
    _full("08-consistent", **answers(solution("08-consistent"), "consistent_invariant"))
    for right in ("Yes", " YES"):
        _full("08-consistent", consistent_invariant=right)
    _zero("08-consistent", "ρ_t", consistent_invariant="no")
    _zero("08-consistent", "ρ_t", consistent_invariant="No ")
    _zero("08-consistent", "one of", consistent_invariant=True)
    _zero("08-consistent", "one of", consistent_invariant="approximately")
    _zero("08-consistent", status="not attempted",
          **answers(student_edition("08-consistent"), "consistent_invariant"))
    assert verdict("08-consistent", consistent_invariant="no") == verdict("08-consistent", consistent_invariant="no")


# --- 08-recap (recap, partial credit) --------------------------------------------------------------------------

def test_recap_solution_and_other_spellings():
    _full("08-recap", **answers(solution("08-recap"), "q1", "q2", "q3"))
    _full("08-recap", q1=1 / 4, q2="a", q3="Regular")
    _full("08-recap", q1="0.25", q2=" A ", q3="REGULAR")
    _full("08-recap", q1=np.float32(2.0**-2), q2="A", q3="regular ")


@pytest.mark.parametrize("given, points, hints", [
    ((0.5, "A", "regular"), 2.0, ["question 1", "1/r²"]),
    ((4, "A", "regular"), 2.0, ["question 1", "upside down"]),
    ((0.3, "A", "regular"), 2.0, ["question 1", "more digits"]),                  # 0.25 rounded too coarsely
    ((0.25, "W", "regular"), 2.0, ["question 2", "conformally"]),
    ((0.25, "both", "scale invariant"), 1.0, ["question 2", "question 3", "section 6"]),
    ((0.25, ..., ...), 1.0, ["not answered"]),
])
def test_recap_partial_credit(given, points, hints):
    got, _, message = verdict("08-recap", q1=given[0], q2=given[1], q3=given[2])
    assert got == points, message
    for hint in hints:
        assert hint in message.lower(), message
    assert "0.25" not in message and '"regular"' not in message                 # never the right answers


def test_recap_all_wrong_and_placeholders():
    _zero("08-recap", "0 of 3", q1=0.5, q2="W", q3="scale-invariant")
    _zero("08-recap", "one of", q1="a quarter", q2="the mass", q3="neither")
    _zero("08-recap", status="not attempted", **answers(student_edition("08-recap"), "q1", "q2", "q3"))
    assert verdict("08-recap", q1=0.5, q2="A", q3="regular") == verdict("08-recap", q1=0.5, q2="A", q3="regular")


# --- 08-angle-defects (build it yourself) ----------------------------------------------------------

DEFECTS = {
    "arccos of the normalised dot product, a loop over faces": """
        def my_angle_defects(mesh):
            delta = np.full(mesh.n_vertices, 2 * np.pi)
            delta[mesh.boundary_vertices] = np.pi
            for tri in mesh.faces:
                for k in range(3):
                    a = mesh.vertices[tri[(k + 1) % 3]] - mesh.vertices[tri[k]]
                    b = mesh.vertices[tri[(k + 2) % 3]] - mesh.vertices[tri[k]]
                    cos = a @ b / (np.linalg.norm(a) * np.linalg.norm(b))
                    delta[tri[k]] -= np.arccos(np.clip(cos, -1, 1))
            return delta
    """,
    "law of cosines from edge lengths, boundary from the edges": """
        from collections import Counter

        def my_angle_defects(m):
            V, F = m.vertices, m.faces
            l = np.stack([np.linalg.norm(V[F[:, (k + 1) % 3]] - V[F[:, (k + 2) % 3]], axis=1) for k in range(3)], 1)
            sums = np.zeros(len(V))
            for k in range(3):  # the angle at corner k is opposite the edge of length l[:, k]
                b, c = l[:, (k + 1) % 3], l[:, (k + 2) % 3]
                np.add.at(sums, F[:, k], np.arccos((b**2 + c**2 - l[:, k] ** 2) / (2 * b * c)))
            edges = Counter(tuple(sorted((f[i], f[(i + 1) % 3]))) for f in F.tolist() for i in range(3))
            rim = {v for e, count in edges.items() if count == 1 for v in e}
            full = [np.pi if i in rim else 2 * np.pi for i in range(len(V))]
            return np.array(full) - sums
    """,
    "half-angle tangents, a Python list": """
        def my_angle_defects(mesh):
            p = mesh.vertices[mesh.faces]
            theta = np.zeros(mesh.faces.shape)
            for k in range(3):
                u = p[:, (k + 1) % 3] - p[:, k]
                w = p[:, (k + 2) % 3] - p[:, k]
                u = u / np.linalg.norm(u, axis=1, keepdims=True)
                w = w / np.linalg.norm(w, axis=1, keepdims=True)
                theta[:, k] = 2 * np.arctan2(np.linalg.norm(u - w, axis=1), np.linalg.norm(u + w, axis=1))
            sums = np.bincount(mesh.faces.ravel(), theta.ravel(), mesh.n_vertices)
            on_rim = np.isin(np.arange(mesh.n_vertices), mesh.boundary_vertices)
            return list(np.where(on_rim, np.pi, 2 * np.pi) - sums)
    """,
}

HELPERS = """
def my_sums(mesh):
    p = mesh.vertices[mesh.faces]
    total = np.zeros(mesh.n_vertices)
    for k in range(3):
        a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
        np.add.at(total, mesh.faces[:, k], np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), (a * b).sum(1)))
    return total


def my_full(mesh):
    full = np.full(mesh.n_vertices, 2 * np.pi)
    full[mesh.boundary_vertices] = np.pi
    return full
"""

DEFECT_SLIPS = {
    "no boundary rule": ("my_angle_defects = lambda mesh: 2 * np.pi - my_sums(mesh)", "boundary"),
    "sign": ("my_angle_defects = lambda mesh: my_sums(mesh) - my_full(mesh)", "sign"),
    "the angle sums": ("my_angle_defects = my_sums", "angle sums"),
    "degrees": ("my_angle_defects = lambda mesh: np.degrees(my_full(mesh) - my_sums(mesh))", "degrees"),
    "divided by the barycentric area": ("""
        def my_angle_defects(mesh):
            a = np.bincount(mesh.faces.ravel(), np.repeat(mesh.face_areas / 3, 3), mesh.n_vertices)
            return (my_full(mesh) - my_sums(mesh)) / a
    """, "not divided by any area"),
    "the angle given to the next corner": ("""
        def my_angle_defects(mesh):
            p, f = mesh.vertices[mesh.faces], mesh.faces
            total = np.zeros(mesh.n_vertices)
            for k in range(3):
                a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
                theta = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), (a * b).sum(1))
                np.add.at(total, f[:, (k + 1) % 3], theta)
            return my_full(mesh) - total
    """, "corner"),
    "arccos without normalising": ("""
        def my_angle_defects(mesh):
            p, f = mesh.vertices[mesh.faces], mesh.faces
            total = np.zeros(mesh.n_vertices)
            for k in range(3):
                a, b = p[:, (k + 1) % 3] - p[:, k], p[:, (k + 2) % 3] - p[:, k]
                np.add.at(total, f[:, k], np.arccos(np.clip((a * b).sum(1), -1, 1)))
            return my_full(mesh) - total
    """, "atan2"),
    "per corner, not per vertex": ("""
        def my_angle_defects(mesh):
            return np.zeros(mesh.faces.shape)
    """, "per corner"),
    "raises": ("def my_angle_defects(mesh):\n    return mesh.angles\n", "AttributeError"),
}

DEFECT_LIBRARY = {
    "the function itself": ("my_angle_defects = lbo.angle_defects", "angle_defects"),
    "a wrapper": ("def my_angle_defects(mesh):\n    return np.array(lbo.angle_defects(mesh))\n", "angle_defects"),
    "the curvature times the area": ("""
        def my_angle_defects(mesh):
            return lbo.gaussian_curvature(mesh) * lbo.mass_matrix(mesh).diagonal()
    """, "gaussian_curvature"),
    "the library's corner angles": ("""
        from lbo_notebooks.operators import corner_angles

        def my_angle_defects(mesh):
            return my_full(mesh) - np.bincount(mesh.faces.ravel(), corner_angles(mesh).ravel(), mesh.n_vertices)
    """, "corner_angles"),
    "the library's cotangents": ("""
        from lbo_notebooks import operators

        def my_angle_defects(mesh):
            theta = np.arctan2(1.0, operators.face_cotangents(mesh))
            return my_full(mesh) - np.bincount(mesh.faces.ravel(), theta.ravel(), mesh.n_vertices)
    """, "face_cotangents"),
    "the private defects": ("""
        from lbo_notebooks.operators import _curvature as curvature

        my_angle_defects = lambda mesh: curvature._angle_defects(mesh)
    """, "_angle_defects"),
    "the visible check's reference": ("""
        from lbo_notebooks.exercises import minmax_and_metrics

        my_angle_defects = lambda mesh: minmax_and_metrics.defect_slips(mesh)[0]
    """, "defect_slips"),
    "gpytoolbox": ("""
        from gpytoolbox import angle_defect

        def my_angle_defects(mesh):
            return angle_defect(mesh.vertices, mesh.faces)
    """, "angle_defect"),
    "igl": ("""
        import igl

        def my_angle_defects(mesh):
            return my_full(mesh) - np.bincount(mesh.faces.ravel(), igl.internal_angles(mesh.vertices, mesh.faces).ravel(),
                                               mesh.n_vertices)
    """, "internal_angles"),
}


def _defects(code):
    import textwrap

    return answers(HELPERS + textwrap.dedent(code), "my_angle_defects")


def test_angle_defects_points():
    assert full_points("08-angle-defects") == 5


def test_angle_defects_solution():
    assert "Right on four meshes" in _full("08-angle-defects", **answers(solution("08-angle-defects"), "my_angle_defects"))


@pytest.mark.parametrize("name", list(DEFECTS))
def test_angle_defects_written_differently(name):
    _full("08-angle-defects", **_defects(DEFECTS[name]))


@pytest.mark.parametrize("name", list(DEFECT_SLIPS))
def test_angle_defects_slips(name):
    code, hint = DEFECT_SLIPS[name]
    message = _zero("08-angle-defects", hint, **_defects(code))
    assert "does not show" in message or name in ("raises", "per corner, not per vertex")  # the form, on any mesh


@pytest.mark.parametrize("name", list(DEFECT_LIBRARY))
def test_angle_defects_library_calls(name):
    code, where = DEFECT_LIBRARY[name]
    _zero("08-angle-defects", "build it yourself", "not available", where, **_defects(code))


def test_angle_defects_placeholders():
    _zero("08-angle-defects", status="not attempted", **answers(student_edition("08-angle-defects"), "my_angle_defects"))
    _zero("08-angle-defects", status="not attempted", my_angle_defects=...)


def test_angle_defects_graded_run_and_determinism():
    given = _defects(DEFECTS["half-angle tangents, a Python list"])
    assert verdict("08-angle-defects", **given) == verdict("08-angle-defects", **given)
    assert graded("08-angle-defects", **given) == 5.0
    import lbo_notebooks as lbo

    assert graded("08-angle-defects", my_angle_defects=lbo.angle_defects) == 0.0


def test_angle_defects_unseen_meshes():
    """The grader's meshes: the four kinds the prompt's grading promises (χ = 2, 0, 1 with boundary,
    obtuse triangles), none of them a mesh of the notebook, and every blocked function resolves."""
    from lbo_notebooks.exercises.grading import _registry, load_graders, nb08
    from lbo_notebooks.operators import corner_angles

    meshes = [mesh for mesh, _ in nb08._unseen_meshes()]
    assert [m.euler_characteristic for m in meshes] == [2, 0, 1, 2]
    assert len(meshes[2].boundary_vertices) > 0 and (corner_angles(meshes[3]) > np.pi / 2).sum() > 50
    for target in load_graders("08-angle-defects")["08-angle-defects"].replaces:
        module = target.partition(":")[0]
        import importlib.util

        installed = importlib.util.find_spec(module.split(".")[0]) is not None
        assert (_registry._resolve(target) is not None) == installed, target


def test_angle_defects_visible_check():
    from lbo_notebooks.operators import _curvature as curvature
    from lbo_notebooks.exercises import minmax_and_metrics as mm

    assert mm.check_angle_defects(curvature.angle_defects, show=False).correct
    own = _defects(DEFECTS["arccos of the normalised dot product, a loop over faces"])["my_angle_defects"]
    assert mm.check_angle_defects(own, show=False).correct
    slip = _defects(DEFECT_SLIPS["no boundary rule"][0])["my_angle_defects"]
    feedback = mm.check_angle_defects(slip, show=False)
    assert feedback.status == "wrong" and "boundary" in feedback.message
    assert mm.check_angle_defects(..., show=False).status == "not attempted"
    assert mm.check_angle_defects(lambda mesh: 1 / 0, show=False).status == "wrong"
    assert mm.check_angle_defects("not a function", show=False).status == "wrong"


def test_gauss_bonnet_on_the_grader_meshes():
    """Σ δ = 2πχ, with the boundary's turning on the open patch: the identity the notebook's cell
    checks on the student's defects."""
    from lbo_notebooks.operators import _curvature as curvature
    from lbo_notebooks.exercises.grading import nb08

    for mesh, _ in nb08._unseen_meshes():
        delta = curvature.angle_defects(mesh)
        assert abs(delta.sum() - 2 * np.pi * mesh.euler_characteristic) < 1e-12 * np.abs(delta).sum()
