"""The graded tests of notebook 07 (the min–max principle), with answers written as students write
them: the instructor's solution, correct answers written differently, typical wrong ones,
placeholders; see lbo_notebooks/exercises/grading/nb07.py. Also the notebook's claims that the old
hidden tests asserted, kept here as facts of the library (they belong to no student's answer)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from .grading_support import answers, assert_full, assert_zero, full_points, graded, solution_of, stub_of, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "07_min_max.ipynb"


def solution(exercise: str) -> str:
    return solution_of(NOTEBOOK, exercise)


def student_edition(exercise: str) -> str:
    return stub_of(NOTEBOOK, exercise)


@pytest.fixture(scope="module")
def notebook():
    """What the answer cells use from the notebook's earlier cells (sections 2 and 3), rebuilt as there."""
    import lbo_notebooks as lbo
    from lbo_notebooks import shapes
    from lbo_notebooks.analyses import _minmax as minmax

    Q, _ = np.linalg.qr(np.random.default_rng(0).normal(size=(3, 3)))
    M = Q @ np.diag([1.0, 2.5, 4.0]) @ Q.T
    v0, v1, v2 = np.linalg.eigh(M)[1].T
    blob = shapes.bumpy_sphere(4)
    s = lbo.eigenbasis(blob, 31)
    return {"Q": Q, "M": M, "lam": np.linalg.eigvalsh(M), "v0": v0, "v1": v1, "v2": v2, "blob": blob, "s": s,
            "solver": minmax.ConstrainedRayleigh(s.stiffness, s.mass), "random_subspace": minmax.random_subspace,
            "optimal_subspace": minmax.optimal_subspace, "ConstrainedRayleigh": minmax.ConstrainedRayleigh,
            "min_rayleigh_quotient": minmax.min_rayleigh_quotient}


_full = assert_full
_zero = assert_zero


def test_points_follow_the_kinds():
    exercises = ("07-range", "07-plane", "07-family", "07-dual", "07-interlacing", "07-consistent", "07-recap")
    assert [full_points(e) for e in exercises] == [1, 2, 1, 1, 1, 2, 3]


def test_the_graded_run_ignores_a_patched_kernel(monkeypatch):
    """Through the real fresh process: patching the checks here (the kernel) changes no grade."""
    from lbo_notebooks import exercises

    monkeypatch.setattr(exercises.Feedback, "correct", property(lambda self: True))
    assert graded("07-range", plane_range=[1.0, 2.5]) == 1.0
    assert graded("07-family", lowest_family="smooth") == 0.0


# --- 07-range (predict) ------------------------------------------------------------------------------

def test_range(notebook):
    lam, M = notebook["lam"], notebook["M"]
    _full("07-range", **answers(solution("07-range"), "plane_range", **notebook))
    _full("07-range", plane_range=[1.0, 2.5])                                 # typed by hand, a list
    _full("07-range", **answers("plane_range = np.linalg.eigvalsh(M)[:2]", "plane_range", M=M))  # an array
    _full("07-range", plane_range=(np.float32(1), min(lam[1:])))
    _zero("07-range", "range of R itself", plane_range=(lam[0], lam[2]))
    _zero("07-range", "contain v_0", plane_range=(lam[1], lam[1]))
    _zero("07-range", "lowest value first", plane_range=(lam[1], lam[0]))
    _zero("07-range", "pair", plane_range=lam)
    _zero("07-range", "span(v_0, v_1)", plane_range=(1.0, 3.0))
    _zero("07-range", status="not attempted", **answers(student_edition("07-range"), "plane_range"))
    assert verdict("07-range", plane_range=(1, 4)) == verdict("07-range", plane_range=(1, 4))


# --- 07-plane (compute) ------------------------------------------------------------------------------

def test_plane(notebook):
    _full("07-plane", **answers(solution("07-plane"), "plane_value", **notebook))
    code = """
        import scipy.linalg
        B = scipy.linalg.null_space((v0 + 2 * v1)[None, :])      # two orthonormal vectors of the plane
        plane_value = np.linalg.eigvalsh(B.T @ M @ B)[0]
    """
    _full("07-plane", **answers(code, "plane_value", **notebook))
    code = """
        w = 2 * v0 - v1                                          # in the plane, orthogonal to v2
        candidates = [w @ M @ w / (w @ w), v2 @ M @ v2]
        plane_value = min(candidates)
    """
    _full("07-plane", **answers(code, "plane_value", **notebook))
    _full("07-plane", plane_value=1.3)                           # (4 · 1 + 2.5) / 5, by hand
    _full("07-plane", plane_value="1.3")


def test_plane_wrong_answers(notebook):
    M, (v0, v1) = notebook["M"], (notebook["v0"], notebook["v1"])
    u = v0 + 2 * v1
    w = 2 * v0 - v1
    _zero("07-plane", "optimal plane", plane_value=2.5)          # λ_1
    _zero("07-plane", "at the normal", plane_value=u @ M @ u / (u @ u))
    _zero("07-plane", "maximum", plane_value=4.0)
    _zero("07-plane", "dividing by xᵀx", plane_value=w @ M @ w)  # not a unit vector
    _zero("07-plane", "v_0", plane_value=1.0)
    _zero("07-plane", "2×2", plane_value=1.5)
    _zero("07-plane", status="not attempted", **answers(student_edition("07-plane"), "plane_value"))
    assert verdict("07-plane", plane_value=1.5) == verdict("07-plane", plane_value=1.5)


def test_plane_minimum_agrees_with_the_library(notebook):
    """The old hidden test's claim: `min_rayleigh_quotient` on that plane gives the exact value."""
    from lbo_notebooks.analyses import min_rayleigh_quotient

    M, u = notebook["M"], notebook["v0"] + 2 * notebook["v1"]
    assert abs(min_rayleigh_quotient(M, np.eye(3), u) - 1.3) < 1e-12 * 4


# --- 07-family (predict) -----------------------------------------------------------------------------

def test_family():
    _full("07-family", **answers(solution("07-family"), "lowest_family"))
    for right in ("White", " white ", np.str_("WHITE")):
        _full("07-family", lowest_family=right)
    _zero("07-family", "rough", lowest_family="smooth")
    _zero("07-family", "optimal ones", lowest_family="near-optimal")
    _zero("07-family", "optimal ones", lowest_family="Near optimal")
    _zero("07-family", "one of", lowest_family="noise")
    _zero("07-family", "one of", lowest_family=0)
    _zero("07-family", status="not attempted", **answers(student_edition("07-family"), "lowest_family"))
    assert verdict("07-family", lowest_family="smooth") == verdict("07-family", lowest_family="smooth")


# --- 07-dual (predict, then compute) --------------------------------------------------------------------

def test_dual(notebook):
    lam = notebook["lam"]
    _full("07-dual", **answers(solution("07-dual"), "dual_value", **notebook))
    _full("07-dual", dual_value=2.5)
    code = """
        U = np.column_stack([v0, v1])
        dual_value = np.linalg.eigvalsh(U.T @ M @ U).max()
    """
    _full("07-dual", **answers(code, "dual_value", **notebook))
    _zero("07-dual", "largest maximum", dual_value=lam[2])
    _zero("07-dual", "span(v_1, v_2)", dual_value=lam[0])
    _zero("07-dual", "from above", dual_value=2.51)              # the smallest of some random planes
    _zero("07-dual", "Bᵀ M B", dual_value=3.3)
    _zero("07-dual", "number", dual_value="lam_1")
    _zero("07-dual", status="not attempted", **answers(student_edition("07-dual"), "dual_value"))
    assert verdict("07-dual", dual_value=4.0) == verdict("07-dual", dual_value=4.0)


def test_dual_claims_of_the_old_hidden_test(notebook):
    """No random plane's maximum is below λ_1, and span(v_0, v_1) reaches it."""
    M, lam = notebook["M"], notebook["lam"]
    planes = (np.linalg.qr(np.random.default_rng(100 + k).normal(size=(3, 2)))[0] for k in range(300))
    assert min(np.linalg.eigvalsh(U.T @ M @ U)[-1] for U in planes) >= lam[1] * (1 - 1e-12)
    U01 = np.column_stack([notebook["v0"], notebook["v1"]])
    assert abs(np.linalg.eigvalsh(U01.T @ M @ U01)[-1] - lam[1]) < 1e-12 * lam[2]


# --- 07-interlacing (explain: a choice, and a written answer graded by a person) ----------------------------

def test_interlacing(notebook):
    _full("07-interlacing", **answers(solution("07-interlacing"), "interlacing_bound", **notebook))
    for right in ("LAM_0", "λ_0", "lam0", " lam_0 "):
        _full("07-interlacing", interlacing_bound=right)
    _zero("07-interlacing", "constant", interlacing_bound="lam_1")
    _zero("07-interlacing", "constant", interlacing_bound="λ₁")
    _zero("07-interlacing", "one of", interlacing_bound="lam_2")
    _zero("07-interlacing", "one of", interlacing_bound=0)
    _zero("07-interlacing", status="not attempted",
          **answers(student_edition("07-interlacing"), "interlacing_bound"))
    assert verdict("07-interlacing", interlacing_bound="lam_1") == verdict("07-interlacing", interlacing_bound="lam_1")


def test_interlacing_has_a_written_answer_after_its_check():
    cells = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
    ids = [c["metadata"].get("nbgrader", {}).get("grade_id") for c in cells]
    k = ids.index("07-interlacing-check")
    written = cells[k + 1]
    meta = written["metadata"]["nbgrader"]
    assert written["cell_type"] == "markdown" and ids[k + 1] == "07-interlacing-explain"
    assert meta["grade"] and meta["solution"] and not meta["locked"] and meta["points"] == 2
    text = "".join(written["source"])
    assert text.startswith("**Model answer.**") and "**Rubric (2 points).** 1 point:" in text
    assert "in the cell below the check" in "".join(cells[ids.index("07-interlacing-answer") - 1]["source"])


def test_interlacing_claims_of_the_old_hidden_test(notebook):
    """A codimension-2 subspace whose constraints are A-orthogonal to the constant has minimum 0 = λ_0
    (the model answer's subspace); codimension-1 minima lie in [λ_0, λ_1]."""
    solver, s, blob, random_subspace = (notebook[k] for k in ("solver", "s", "blob", "random_subspace"))
    assert solver.minimum(random_subspace(blob.n_vertices, 2, seed=4, pool=s.vectors[:, 1:8])) < 1e-8 * s.values[1]
    assert all(0 <= solver.minimum(random_subspace(blob.n_vertices, 1, seed=k)) <= s.values[1] * (1 + 1e-10)
               for k in range(5))


# --- 07-consistent (compute) ---------------------------------------------------------------------------

def test_consistent(notebook):
    _full("07-consistent", **answers(solution("07-consistent"), "consistent_minmax", **notebook))
    code = """
        from lbo_notebooks.analyses import min_rayleigh_quotient
        spec = lbo.eigenbasis(blob, 12, mass_kind="consistent")
        low = min_rayleigh_quotient(spec.stiffness, spec.mass, orthogonal_to=spec.vectors[:, :10])
        consistent_minmax = low / spec.values[10]
    """
    _full("07-consistent", **answers(code, "consistent_minmax", **notebook))
    _full("07-consistent", consistent_minmax=1)
    _full("07-consistent", consistent_minmax=np.float64(1.0000000001))


def test_consistent_wrong_answers(notebook):
    blob, s = notebook["blob"], notebook["s"]
    import lbo_notebooks as lbo
    from lbo_notebooks.analyses import ConstrainedRayleigh, optimal_subspace

    sc = lbo.eigenbasis(blob, 12, mass_kind="consistent")
    low = ConstrainedRayleigh(sc.stiffness, sc.mass).minimum(optimal_subspace(sc, 10))
    lumped_low = notebook["solver"].minimum(optimal_subspace(sc, 10))    # the lumped solver, consistent subspace
    _zero("07-consistent", "values[10]", consistent_minmax=low)            # not divided
    _zero("07-consistent", "values[10]", consistent_minmax=low / sc.values[9])   # off by one
    _zero("07-consistent", "consistent spectrum", consistent_minmax=low / s.values[10])   # the lumped λ_10
    _zero("07-consistent", "consistent spectrum", consistent_minmax=lumped_low / sc.values[10])
    _zero("07-consistent", "values[10]", consistent_minmax=sc.values[10])   # λ_10 alone
    _zero("07-consistent", status="not attempted", **answers(student_edition("07-consistent"), "consistent_minmax"))
    assert verdict("07-consistent", consistent_minmax=low) == verdict("07-consistent", consistent_minmax=low)


def test_consistent_claims_of_the_old_hidden_test(notebook):
    """Courant–Fischer with the consistent mass: a random codimension-10 subspace stays below λ_10."""
    import lbo_notebooks as lbo
    from lbo_notebooks.analyses import ConstrainedRayleigh, random_subspace

    blob = notebook["blob"]
    sc = lbo.eigenbasis(blob, 12, mass_kind="consistent")
    solver_c = ConstrainedRayleigh(sc.stiffness, sc.mass)
    assert solver_c.minimum(random_subspace(blob.n_vertices, 10, seed=1, pool=sc.vectors)) <= sc.values[10] * (1 + 1e-10)


# --- 07-recap (recap, partial credit) -----------------------------------------------------------------

T_STAR = float(np.degrees(np.arctan(np.sqrt(2.0))))   # 54.7356...


def test_recap_solution_and_other_spellings():
    _full("07-recap", **answers(solution("07-recap"), "q1", "q2", "q3"))
    _full("07-recap", q1="λ_n", q2="No", q3=54.74)
    _full("07-recap", q1="lam n", q2=" NO ", q3=54.7)
    _full("07-recap", q1="LAM_N", q2="no", q3=np.float32(T_STAR))


@pytest.mark.parametrize("given, points, hints", [
    (("lam_n+1", "no", T_STAR), 2.0, ["question 1", "codimension"]),
    (("lam_n", "yes", T_STAR), 2.0, ["question 2", "arc"]),
    (("lam_n", "no", float(np.degrees(np.arctan(2.0)))), 2.0, ["question 3", "ratio"]),
    (("lam_n", "no", float(np.arctan(np.sqrt(2.0)))), 2.0, ["question 3", "radians"]),
    (("lam_n", "no", 55), 2.0, ["question 3", "digits"]),                   # hand-rounded too coarsely
    (("lam_n-1", "yes", T_STAR), 1.0, ["question 1", "question 2"]),
    (("lam_n", ..., ...), 1.0, ["not answered"]),
])
def test_recap_partial_credit(given, points, hints):
    got, _, message = verdict("07-recap", q1=given[0], q2=given[1], q3=given[2])
    assert got == points, message
    for hint in hints:
        assert hint in message.lower(), message
    assert "54.7" not in message and '"lam_n"' not in message            # never the right answers


def test_recap_all_wrong_and_placeholders():
    _zero("07-recap", "0 of 3", q1="lam_n+1", q2="yes", q3=30.0)
    _zero("07-recap", "one of", q1="maybe", q2="perhaps", q3="about 55")
    _zero("07-recap", status="not attempted", **answers(student_edition("07-recap"), "q1", "q2", "q3"))
    assert verdict("07-recap", q1="lam_n", q2="yes", q3=55) == verdict("07-recap", q1="lam_n", q2="yes", q3=55)


def test_recap_claim_of_the_old_hidden_test(notebook):
    """The tilt of section 2 on eigenvalues 1, 2, 4: the minimum stays λ_1 = 2 up to t*, falls after."""
    from lbo_notebooks.analyses import min_rayleigh_quotient

    Q = notebook["Q"]
    M3 = Q @ np.diag([1.0, 2.0, 4.0]) @ Q.T
    w0, _, w2 = Q.T

    def tilt(t):
        return min_rayleigh_quotient(M3, np.eye(3), np.cos(np.radians(t)) * w0 + np.sin(np.radians(t)) * w2)

    assert abs(tilt(T_STAR - 0.5) - 2.0) < 1e-12 * 4 and tilt(T_STAR + 0.5) < 2.0 * (1 - 1e-6)
