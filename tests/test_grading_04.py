"""The graded tests of notebook 04 (your own data) on answers the instructor did not write: correct
ones written differently earn full points, typical wrong ones earn none (the recap: partial credit),
placeholders count as not attempted, verdicts are deterministic, and the data the graders rebuild
is the notebook's. The claims the hidden tests used to make about the notebook's data are asserted
here as tests of the library."""

from __future__ import annotations

import json
import re
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

from lbo_notebooks.exercises.grading import nb04
from tests.grading_support import answers, assert_full, assert_zero, full_points, graded, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "04_your_own_data.ipynb"
EXERCISES = ("04-repair", "04-operator", "04-cloud", "04-largest", "04-neighbors", "04-gap", "04-recap")
REPAIR = {"polygons_split": 1, "vertices_welded": 1, "degenerate_faces": 5, "duplicate_faces": 5,
          "unreferenced_vertices": 10, "non_manifold_edges": 3, "n_components": 4}
OPERATOR = {"holes": "cotan", "two_pieces": "cotan", "fins": "robust", "pinched": "robust"}
PIECES = {1.5: 1, 1.75: 2, 2.0: 2}


def _cells() -> list[dict]:
    return json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]


def _answer_cell(exercise: str) -> str:
    (cell,) = [c for c in _cells() if c["metadata"].get("nbgrader", {}).get("grade_id") == f"{exercise}-answer"]
    return "".join(cell["source"])


def solution(exercise: str) -> str:
    """The instructor's answer cell as a student who wrote it would run it (markers stripped)."""
    lines = _answer_cell(exercise).splitlines()
    return "\n".join(line for line in lines if not re.match(r"\s*### (BEGIN|END) SOLUTION", line))


def placeholder(exercise: str) -> str:
    """The answer cell as the student edition hands it out: the placeholder lines only."""
    return _answer_cell(exercise).split("### BEGIN SOLUTION")[0]


@pytest.fixture(scope="module")
def notebook() -> dict:
    """The names the notebook's cells define before its exercises: the scan (arrays, file, loaded
    mesh), the candidates, the cloud's spectrum, the concentric spheres (plots and the dog left out)."""
    wanted = ("tempfile.mkdtemp()", "sphere = shapes.icosphere(4)", "scan = lbo.load_mesh(scan_path, clean=True)",
              "candidates = {", "cloud_spectrum = lbo.eigenbasis(cloud, 16)", "inner = shapes.icosphere(3)")
    namespace: dict = {}
    for cell in _cells():
        source = "".join(cell["source"])
        if cell["cell_type"] == "code" and not cell["metadata"].get("nbgrader") and any(w in source for w in wanted):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                exec(source, namespace)  # noqa: S102 - the notebook's own cells
    return {k: v for k, v in namespace.items() if not k.startswith("__")}


def context(notebook: dict, *names: str) -> dict:
    return {name: notebook[name] for name in names}


full = assert_full
zero = assert_zero


def test_points_follow_the_kinds():
    assert {e: full_points(e) for e in EXERCISES} == {
        "04-repair": 1, "04-operator": 1, "04-cloud": 2, "04-largest": 2, "04-neighbors": 1, "04-gap": 2,
        "04-recap": 3}
    written = {c["metadata"]["nbgrader"]["grade_id"]: c["metadata"]["nbgrader"]["points"] for c in _cells()
               if c["cell_type"] == "markdown" and c["metadata"].get("nbgrader")}
    assert written == {"04-operator-explain": 2, "04-gap-explain": 2}


# --- the data the graders rebuild is the notebook's ------------------------------------------------

def test_the_rebuilt_scan_and_its_file_are_the_notebooks(notebook):
    v, faces, _ = nb04.messy_scan()
    assert np.array_equal(v, notebook["v"]) and faces == [list(map(int, f)) for f in notebook["faces"]]
    with tempfile.TemporaryDirectory() as folder:
        text = nb04.write_scan(Path(folder), v, faces).read_text()
    assert text == notebook["scan_path"].read_text()
    rebuilt = nb04.candidates(notebook["scan"])
    for name, mesh in notebook["candidates"].items():
        assert np.array_equal(rebuilt[name].vertices, mesh.vertices) and np.array_equal(rebuilt[name].faces, mesh.faces)


def test_the_rebuilt_cloud_is_the_notebooks(notebook):
    _, _, rng = nb04.messy_scan()
    with tempfile.TemporaryDirectory() as folder:
        values = nb04.cloud_values(Path(folder), rng)
        assert Path(folder, "scan.xyz").read_text() == notebook["cloud_path"].read_text()
    assert np.allclose(values, notebook["cloud_spectrum"].values, rtol=1e-9, atol=1e-12)


# --- the notebook's claims, formerly in the hidden tests, as tests of the library ------------------

def test_operator_claims_the_candidates_defects_and_pieces(notebook):
    from lbo_notebooks.operators import cotan_defects

    v, faces, _ = nb04.messy_scan()
    with tempfile.TemporaryDirectory() as folder:
        meshes = nb04.candidates(nb04.load_scan(nb04.write_scan(Path(folder), v, faces)))
    assert [bool(cotan_defects(meshes[n])) for n in ("holes", "two_pieces", "fins", "pinched")] == [False, False, True, True]
    assert meshes["two_pieces"].n_components == 2 and meshes["pinched"].n_components == 1
    assert (meshes["holes"].edge_face_counts == 1).any()
    assert "non-manifold vert" in " ".join(cotan_defects(meshes["pinched"]))


def test_cloud_claims(notebook):
    """Eigenvalue 9 belongs to l = 3 (12), and the cloud's value lies below it."""
    assert notebook["exact"][9] == 12 and notebook["cloud_spectrum"].values[9] < 12


def test_largest_component_claims(notebook):
    from lbo_notebooks import eigenbasis, load_mesh

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        largest = load_mesh(notebook["scan_path"], clean=True, keep_largest_component=True)
        values = eigenbasis(largest, 16).values
    assert largest.n_components == 1
    assert np.sum(np.abs(values) < 1e-8 * values[-1]) == 1
    assert np.max(np.abs(values[1:] / notebook["exact"][1:] - 1)) < 0.03


def test_gap_claims_the_estimate_and_the_separation():
    """The written answer's estimate (a cap of 0.43 r: separation near r = 1.76) and what the
    library measures around it (one piece at 1.7, two at 1.75)."""
    from lbo_notebooks import PointCloud, eigenbasis, shapes

    inner = shapes.icosphere(3)
    cap = np.sqrt(30 / inner.n_vertices * 4)  # cap radius / r: pi rho^2 = (30 / 642) 4 pi r^2
    assert abs(cap - 0.43) < 0.005 and 1.75 < 1 / (1 - cap) < 1.77
    for radius, pieces in ((1.7, 1), (1.75, 2)):
        values = eigenbasis(PointCloud(np.vstack([inner.vertices, radius * inner.vertices])), 3).values
        assert np.sum(np.abs(values) < 1e-8 * values[-1]) == pieces


def test_recap_claims(notebook):
    """The scan is in 4 pieces (4 zero eigenvalues) and has a defect the cotangent Laplacian cannot serve."""
    from lbo_notebooks import eigenbasis
    from lbo_notebooks.operators import cotan_defects

    scan = notebook["scan"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        values = eigenbasis(scan, 6).values
    assert scan.n_components == 4 and np.sum(np.abs(values) < 1e-8) == 4 and cotan_defects(scan)


# --- 04-repair -------------------------------------------------------------------------------------

def test_repair_right_answers(notebook):
    full("04-repair", **answers(solution("04-repair"), "repair"))
    full("04-repair", repair={k: float(v) for k, v in reversed(REPAIR.items())})  # floats, another order
    full("04-repair", repair={**{k: np.int64(v) for k, v in REPAIR.items()}, "faces_flipped": 20})  # an extra count
    full("04-repair", repair={k: str(v) for k, v in REPAIR.items()})
    code = ("from lbo_notebooks.geometry._repair import clean_mesh\n\n"
            "_, report = clean_mesh((v, faces))\n"
            "repair = dict(polygons_split=report.polygons_split, vertices_welded=report.vertices_welded,\n"
            "              degenerate_faces=report.degenerate_faces, duplicate_faces=report.duplicate_faces,\n"
            "              unreferenced_vertices=report.unreferenced_vertices,\n"
            "              non_manifold_edges=report.non_manifold_edges, n_components=report.n_components)")
    full("04-repair", **answers(code, "repair", **context(notebook, "v", "faces")))


@pytest.mark.parametrize("change, hint", [
    ({"unreferenced_vertices": 5}, "holes"),            # only the vertices no face ever used
    ({"unreferenced_vertices": 8}, "holes"),            # the hole centres forgotten
    ({"duplicate_faces": 10}, "one copy"),              # faces involved, not removed
    ({"degenerate_faces": 4}, "one line"),              # the collinear face missed
    ({"non_manifold_edges": 9}, "only the one"),        # every fin edge
    ({"n_components": 3}, "quad included"),
    ({"n_components": 7}, "part of its piece"),         # the fins as pieces
    ({"vertices_welded": 0}, "exact copy"),
    ({"polygons_split": 1.5}, "quads"),
])
def test_repair_wrong_counts(change, hint):
    zero("04-repair", hint, repair={**REPAIR, **change})


def test_repair_incomplete_or_malformed():
    zero("04-repair", "missing", "n_components", repair={k: v for k, v in REPAIR.items() if k != "n_components"})
    zero("04-repair", "dict", repair=list(REPAIR.values()))
    zero("04-repair", "whole number", repair={**REPAIR, "duplicate_faces": "five"})
    zero("04-repair", "every part", repair={**REPAIR, "n_components": ...})
    zero("04-repair", status="not attempted", **answers(placeholder("04-repair"), "repair"))
    zero("04-repair", status="not attempted", repair=...)


# --- 04-operator -----------------------------------------------------------------------------------

def test_operator_right_answers(notebook):
    full("04-operator", **answers(solution("04-operator"), "operator", **context(notebook, "candidates")))
    full("04-operator", operator={"pinched": " Robust", "fins": "ROBUST", "two_pieces": "Cotan ", "holes": "cotan"})
    code = ("operator = {}\nfor name, mesh in candidates.items():\n"
            "    operator[name] = 'robust' if lbo.operators.cotan_defects(mesh) else 'cotan'")
    full("04-operator", **answers(code, "operator", **context(notebook, "candidates")))
    full("04-operator", operator=dict(zip(["holes", "two_pieces", "fins", "pinched"], ["cotan"] * 2 + ["robust"] * 2)))


@pytest.mark.parametrize("change, hint", [
    (dict.fromkeys(OPERATOR, "robust"), "boundary"),                 # every defect-looking mesh robust
    ({"two_pieces": "robust"}, "block-diagonal"),
    ({"fins": "cotan"}, "three opposite angles"),
    ({"pinched": "cotan"}, "pinched"),
    (dict.fromkeys(OPERATOR, "cotan"), "three opposite angles"),
    ({"pinched": "tufted"}, '"cotan" or "robust"'),
    ({"fins": True}, '"cotan" or "robust"'),
])
def test_operator_wrong_answers(change, hint):
    zero("04-operator", hint, operator={**OPERATOR, **change})


def test_operator_incomplete_or_malformed(notebook):
    zero("04-operator", "one entry per mesh", operator={k: v for k, v in OPERATOR.items() if k != "pinched"})
    zero("04-operator", "one entry per mesh", operator={**OPERATOR, "needles": "robust"})
    zero("04-operator", "one entry per mesh", operator={**OPERATOR, 3: "cotan"})   # a non-string key
    zero("04-operator", "dict", operator=list(OPERATOR.values()))
    zero("04-operator", status="not attempted", **answers(placeholder("04-operator"), "operator"))


# --- 04-cloud --------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def cloud_error(notebook) -> float:
    return float(notebook["cloud_spectrum"].values[9] / 12 - 1)


def test_cloud_right_answers(notebook, cloud_error):
    full("04-cloud", **answers(solution("04-cloud"), "relative_error", **context(notebook, "cloud_spectrum")))
    code = "lam = cloud_spectrum.values[9]\ntarget = exact[9]\nrelative_error = (lam - target) / target"
    full("04-cloud", **answers(code, "relative_error", **context(notebook, "cloud_spectrum", "exact")))
    code = "ell = 3\nrelative_error = np.float32(cloud_spectrum.values[ell**2] / (ell * (ell + 1)) - 1)"
    full("04-cloud", **answers(code, "relative_error", **context(notebook, "cloud_spectrum")))
    full("04-cloud", relative_error=float(f"{cloud_error:.4f}"))        # by hand, to 3 significant digits
    full("04-cloud", relative_error=np.array([cloud_error]))


def test_cloud_wrong_answers(notebook, cloud_error):
    lam = float(notebook["cloud_spectrum"].values[9])
    zero("04-cloud", "sign", relative_error=-cloud_error)
    zero("04-cloud", "percentage", relative_error=100 * cloud_error)
    zero("04-cloud", "percentage", relative_error=float(f"{100 * cloud_error:.1f}"))   # -5.9 (%)
    zero("04-cloud", "absolute", relative_error=lam - 12)
    zero("04-cloud", "upside down", relative_error=12 / lam - 1)
    zero("04-cloud", "not ℓ", relative_error=lam / 90 - 1)                  # l = k = 9
    zero("04-cloud", "wrong ℓ", relative_error=lam / 20 - 1)                # l = 4
    zero("04-cloud", "wrong ℓ", relative_error=lam / 6 - 1)                 # l = 2
    zero("04-cloud", "find ℓ", relative_error=0.0)
    zero("04-cloud", "expected", relative_error="about -6%")


def test_cloud_a_coarse_rounding_asks_for_digits(cloud_error):
    message = zero("04-cloud", "more digits", relative_error=float(f"{cloud_error:.3f}"))   # -0.059
    assert "ℓ" not in message and "wrong sign" not in message.lower()


def test_cloud_placeholder():
    zero("04-cloud", status="not attempted", **answers(placeholder("04-cloud"), "relative_error"))


# --- 04-largest ------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def largest_values(notebook) -> np.ndarray:
    from lbo_notebooks import eigenbasis, load_mesh

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return eigenbasis(load_mesh(notebook["scan_path"], clean=True, keep_largest_component=True), 16).values


def test_largest_right_answers(notebook, largest_values):
    names = ("largest_zeros", "largest_worst")
    full("04-largest", **answers(solution("04-largest"), *names, **context(notebook, "scan_path", "exact", "warnings")))
    code = ("with warnings.catch_warnings():\n"
            "    warnings.simplefilter('ignore')\n"
            "    piece = lbo.load_mesh(scan_path, keep_largest_component=True, clean=True)\n"
            "    lam = lbo.eigenbasis(piece, 20).values\n"
            "largest_zeros = np.isclose(lam, 0, atol=1e-8).sum()\n"
            "largest_worst = max(abs(a / b - 1) for a, b in zip(lam[1:16], exact[1:16]))")
    full("04-largest", **answers(code, *names, **context(notebook, "scan_path", "exact", "warnings")))
    worst = float(np.max(np.abs(largest_values[1:] / notebook["exact"][1:] - 1)))
    full("04-largest", largest_zeros=1.0, largest_worst=float(f"{worst:.3f}"))      # by hand: 0.019
    full("04-largest", largest_zeros=np.int64(1), largest_worst=np.float32(worst))


def test_largest_wrong_answers(notebook, largest_values):
    exact = notebook["exact"]
    worst = float(np.max(np.abs(largest_values[1:] / exact[1:] - 1)))
    zero("04-largest", "drops the flakes", largest_zeros=4, largest_worst=worst)     # the flakes kept
    zero("04-largest", "constant", largest_zeros=0, largest_worst=worst)
    zero("04-largest", "percentage", largest_zeros=1, largest_worst=100 * worst)
    shifted = float(np.max(np.abs(largest_values[4:] / exact[1:13] - 1)))          # the 4-zero offset kept
    zero("04-largest", "index for index", largest_zeros=1, largest_worst=shifted)
    mean = float(np.mean(np.abs(largest_values[1:] / exact[1:] - 1)))               # mean, not max
    zero("04-largest", "k = 1, ..., 15", largest_zeros=1, largest_worst=mean)
    zero("04-largest", "got nan", largest_zeros=1, largest_worst=float("nan"))
    zero("04-largest", "every part", largest_zeros=1, largest_worst=...)


def test_largest_a_coarse_rounding_asks_for_digits(notebook, largest_values):
    worst = float(np.max(np.abs(largest_values[1:] / notebook["exact"][1:] - 1)))
    assert f"{worst:.2f}" == "0.02"
    zero("04-largest", "more digits", largest_zeros=1, largest_worst=0.02)


def test_largest_placeholder():
    zero("04-largest", status="not attempted", **answers(placeholder("04-largest"), "largest_zeros", "largest_worst"))


# --- 04-neighbors ----------------------------------------------------------------------------------

def test_neighbors():
    full("04-neighbors", **answers(solution("04-neighbors"), "neighbors_effect"))
    full("04-neighbors", neighbors_effect="Further")
    full("04-neighbors", neighbors_effect="  further ")
    zero("04-neighbors", "compare", neighbors_effect="closer")
    zero("04-neighbors", "operator", neighbors_effect="same")
    zero("04-neighbors", "one of", neighbors_effect="worse")
    zero("04-neighbors", "one of", neighbors_effect=10)
    zero("04-neighbors", status="not attempted", **answers(placeholder("04-neighbors"), "neighbors_effect"))


# --- 04-gap ----------------------------------------------------------------------------------------

def test_gap_right_answers(notebook):
    full("04-gap", **answers(solution("04-gap"), "pieces", **context(notebook, "inner")))
    code = ("pieces = {}\n"
            "for r in [1.5, 1.75, 2]:\n"
            "    both = lbo.PointCloud(np.concatenate([inner.vertices, inner.vertices * r]))\n"
            "    lam = lbo.eigenbasis(both, 4, n_neighbors=30).values\n"
            "    pieces[r] = int((lam < 1e-6).sum())")
    full("04-gap", **answers(code, "pieces", **context(notebook, "inner")))          # the key 2, not 2.0
    full("04-gap", pieces={"1.5": 1, "1.75": 2.0, "2": np.int64(2)})
    full("04-gap", pieces={np.float64(2.0): 2, np.float64(1.75): 2, np.float64(1.5): 1})


def test_gap_wrong_answers():
    zero("04-gap", "reach further", pieces={**PIECES, 1.5: 2})                      # the gap called wide
    zero("04-gap", "wider", pieces={**PIECES, 1.75: 1})
    zero("04-gap", "wider", pieces={1.5: 1, 1.75: 1, 2.0: 1})                       # always fused
    zero("04-gap", "reach further", pieces={1.5: 2, 1.75: 2, 2.0: 2})              # always separate


def test_gap_requires_exactly_the_radii_asked():
    zero("04-gap", "not asked", "1.7", pieces={**PIECES, 1.7: 1})                  # issue 38: called correct before
    zero("04-gap", "missing", "1.5", "1.75", pieces={2.0: 2})
    zero("04-gap", "above 1", pieces={**PIECES, 0.5: 1})
    zero("04-gap", "twice", pieces={**PIECES, "2": 2})


def test_gap_any_key_type_gives_a_wrong_verdict():
    zero("04-gap", "keys are the outer radii", pieces={"far": 2, 1.5: 1, 1.75: 2})   # issue 38: raised ValueError
    zero("04-gap", "keys are the outer radii", pieces={(1.5, 1.75): 1, 2.0: 2})
    zero("04-gap", "keys are the outer radii", pieces={None: 1, **PIECES})
    zero("04-gap", "dict", pieces=[1, 2, 2])
    zero("04-gap", "whole number", pieces={**PIECES, 2.0: "two"})


def test_gap_placeholder():
    zero("04-gap", status="not attempted", **answers(placeholder("04-gap"), "pieces"))
    zero("04-gap", status="not attempted", pieces=...)


# --- 04-recap --------------------------------------------------------------------------------------

def test_recap_right_answers():
    full("04-recap", **answers(solution("04-recap"), "q1", "q2", "q3"))
    full("04-recap", q1=4.0, q2="Robust", q3=" FUSED ")
    full("04-recap", q1=np.int64(4), q2="robust", q3="fused")
    full("04-recap", q1="4", q2="robust ", q3="Fused")


@pytest.mark.parametrize("given, right, hint", [
    ((1, "robust", "fused"), 2, "question 1"),         # one zero whatever the pieces
    ((3, "robust", "fused"), 2, "shape's own constant"),
    ((4, "cotan", "fused"), 2, "question 2"),
    ((4, "robust", "separate"), 2, "question 3"),
    ((0, "cotan", "fused"), 1, "question 2"),
    ((4, ..., ...), 1, "still"),
])
def test_recap_partial_credit(given, right, hint):
    points, status, message = verdict("04-recap", **dict(zip(("q1", "q2", "q3"), given)))
    assert (points, status) == (right, "graded") and hint in message.lower(), message
    assert f"{right} of 3 right" in message and "4" not in message.replace("Question", "").replace(f"{right} of 3", "")


def test_recap_all_wrong_and_placeholders():
    zero("04-recap", "0 of 3", q1=1, q2="cotan", q3="separate")
    zero("04-recap", status="not attempted", **answers(placeholder("04-recap"), "q1", "q2", "q3"))


# --- every exercise ---------------------------------------------------------------------------------

def test_same_answer_same_verdict(cloud_error):
    for exercise, given in [("04-repair", {"repair": {**REPAIR, "n_components": 3}}),
                            ("04-cloud", {"relative_error": cloud_error}),
                            ("04-gap", {"pieces": {**PIECES, 1.75: 1}}),
                            ("04-recap", {"q1": 4, "q2": "cotan", "q3": "fused"})]:
        assert verdict(exercise, **given) == verdict(exercise, **given)


@pytest.mark.parametrize("timed", [False, pytest.param(True, marks=pytest.mark.timing)], ids=["points", "seconds"])
def test_the_real_graded_run(largest_values, notebook, timed):
    """Through the fresh process nbgrader starts: full points, a wrong answer's 0, each well under 10 s."""
    worst = float(np.max(np.abs(largest_values[1:] / notebook["exact"][1:] - 1)))
    start = time.perf_counter()
    assert graded("04-largest", largest_zeros=1, largest_worst=worst) == 2.0
    assert graded("04-gap", pieces={**PIECES, 1.7: 1}) == 0.0
    assert not timed or time.perf_counter() - start < 20  # a wall time: opt-in (LBO_TIMING_TESTS=1, tests/conftest.py)
