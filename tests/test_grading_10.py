"""The graded tests of notebook 10 (spectral MDS at scale) on answers the instructor did not write:
correct ones written differently earn full points, typical wrong ones earn none, placeholders count
as not attempted, and verdicts are deterministic."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from tests.grading_support import answers, assert_full, assert_zero, full_points, graded, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "10_spectral_mds_at_scale.ipynb"


def solution(exercise: str) -> str:
    """The instructor's answer cell of ``exercise`` as a student who wrote it would run it."""
    cells = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
    (cell,) = [c for c in cells if c["metadata"].get("nbgrader", {}).get("grade_id") == f"{exercise}-answer"]
    lines = "".join(cell["source"]).splitlines()
    return "\n".join(line for line in lines if not re.match(r"\s*### (BEGIN|END) SOLUTION", line))


@pytest.fixture(scope="module")
def notebook():
    """The names the notebook's earlier cells define that the answers use (its section 1)."""
    import lbo_notebooks as lbo
    from lbo_notebooks.analyses import gram_error
    from lbo_notebooks.analyses import farthest_point_sampling
    from lbo_notebooks.analyses import SMDS_EIGEN_TOL, classical_mds, spectral_mds

    dog = lbo.creature("dog", "walking", n_vertices=2000)
    spectrum = lbo.eigenbasis(dog, 300, tol=SMDS_EIGEN_TOL)
    sampling = farthest_point_sampling(dog, 600, return_distances=True, select="graph")
    X_classical = classical_mds(dog, progress=False)
    X_smds = spectral_mds(dog, spectrum=spectrum, sampling=sampling)
    return {"dog": dog, "spectrum": spectrum, "sampling": sampling, "X_classical": X_classical, "X_smds": X_smds,
            "spectral_mds": spectral_mds, "classical_mds": classical_mds, "gram_error": gram_error}


full = assert_full
zero = assert_zero


def test_points_follow_the_kinds():
    assert {e: full_points(e) for e in ("10-mu", "10-equal-size", "10-two-d", "10-cost-recap")} == {
        "10-mu": 1, "10-equal-size": 2, "10-two-d": 2, "10-cost-recap": 3}


# --- 10-mu ---------------------------------------------------------------------------------------

def test_mu_prediction():
    full("10-mu", **answers(solution("10-mu"), "mu_verdict"))
    for right in ("Less than half", "  less  than   half ", np.str_("LESS THAN HALF")):
        full("10-mu", mu_verdict=right)
    for wrong, hint in (("about double", "λᵢ²"), ("more than tenfold", "smooth already"), ("less", "one of"),
                        (0.5, "one of")):
        zero("10-mu", hint, mu_verdict=wrong)
    zero("10-mu", mu_verdict=..., status="not attempted")
    zero("10-mu", mu_verdict="", status="not attempted")


# --- 10-equal-size -------------------------------------------------------------------------------

def test_equal_size_right_answers(notebook):
    dog = notebook["dog"]
    full("10-equal-size", **answers(solution("10-equal-size"), "n_c", dog=dog))
    # the old hidden test's claim: the solution is sqrt(n (k + q) / 2) with the library's defaults
    from lbo_notebooks.analyses import SMDS_DEFAULTS

    assert answers(solution("10-equal-size"), "n_c", dog=dog)["n_c"] == pytest.approx(
        np.sqrt(dog.n_vertices * (SMDS_DEFAULTS["k"] + SMDS_DEFAULTS["n_samples"]) / 2), abs=1)
    full("10-equal-size", **answers("floats = dog.n_vertices * (200 + 300)\nn_c = (floats / 2) ** 0.5", "n_c", dog=dog))
    full("10-equal-size", **answers("n_c = round(np.sqrt(len(dog.vertices) * 250))", "n_c", dog=dog))
    full("10-equal-size", **answers("n_c = int(np.sqrt(dog.n_vertices * 500 / 2))", "n_c", dog=dog))   # floored
    full("10-equal-size", n_c=703)                                   # by hand, to the vertex
    full("10-equal-size", n_c=np.array([703.4]))


@pytest.mark.parametrize("code, hint", [
    ("n_c = np.sqrt(dog.n_vertices * 500)", "two"),                  # one matrix
    ("n_c = np.sqrt(dog.n_vertices * 200 / 2)", "sampled fields"),   # Phi only
    ("n_c = np.sqrt(dog.n_vertices * 300 / 2)", "eigenbasis"),       # F only
    ("n_c = dog.n_vertices * 500 / 2", "square root"),
    ("n_c = dog.n_vertices * 500", "solve"),
    ("n_c = np.sqrt(dog.n_vertices * 500 / 2) / 2", "set the floats"),
])
def test_equal_size_wrong_answers(notebook, code, hint):
    zero("10-equal-size", hint, **answers(code, "n_c", dog=notebook["dog"]))


def test_equal_size_not_a_number_and_placeholders():
    zero("10-equal-size", "number of vertices", n_c="many")
    zero("10-equal-size", "number of vertices", n_c=(703, 703))
    zero("10-equal-size", n_c=..., status="not attempted")


# --- 10-two-d ------------------------------------------------------------------------------------

def test_two_d_right_answers(notebook):
    full("10-two-d", **answers(solution("10-two-d"), "e2", **notebook))
    code = """
Z = spectral_mds(dog, 2)                          # without reusing the eigenbasis and the samples
X2 = classical_mds(dog, dim=2, progress=False)    # the 2-D classical embedding itself
e2 = float(gram_error(Z, X2))
"""
    full("10-two-d", **answers(code, "e2", **notebook))
    code = """
two = spectral_mds(dog, dim=2, spectrum=spectrum, sampling=sampling)
G, H = two @ two.T, X_classical[:, :2] @ X_classical[:, :2].T
e2 = np.linalg.norm(G - H) / np.linalg.norm(H)    # the Gram error by its definition
"""
    full("10-two-d", **answers(code, "e2", **notebook))
    value = answers(solution("10-two-d"), "e2", **notebook)["e2"]
    full("10-two-d", e2=float(f"{value:.3g}"))        # copied to three digits
    full("10-two-d", e2=np.float32(value))


def test_two_d_old_hidden_claims(notebook):
    """What the hidden test used to assert: 2-D spectral MDS of the dog is within 2% of 2-D classical
    MDS with a clear eigengap, and a 2-D embedding is the first two columns of the 3-D one (classical
    MDS, and spectral MDS, which the grader relies on)."""
    from scipy.spatial.distance import cdist

    from lbo_notebooks.analyses import gram_error
    from lbo_notebooks.analyses import classical_mds, spectral_mds

    dog, X_classical = notebook["dog"], notebook["X_classical"]
    X2, info2 = spectral_mds(dog, dim=2, spectrum=notebook["spectrum"], sampling=notebook["sampling"],
                             return_details=True)
    assert gram_error(X2, X_classical[:, :2]) < 0.02 and info2["eigengap"] > 1
    assert gram_error(X2, notebook["X_smds"][:, :2]) < 1e-10
    P = np.random.default_rng(0).normal(size=(40, 3)) * [3.0, 2.0, 1.0]
    assert gram_error(classical_mds(cdist(P, P), dim=2), classical_mds(cdist(P, P), dim=3)[:, :2]) < 1e-10


@pytest.mark.parametrize("code, hint", [
    ("e2 = gram_error(X_smds, X_classical)", "3-D"),                                          # not 2-D
    ("e2 = gram_error(spectral_mds(dog, dim=2, spectrum=spectrum, sampling=sampling), X_classical)",
     "3-D classical"),
    (("from lbo_notebooks.analyses._embedding_error import procrustes_error\n"
      "e2 = procrustes_error(spectral_mds(dog, dim=2, spectrum=spectrum, sampling=sampling), X_classical[:, :2])"),
     "Procrustes"),
    ("e2 = 100 * gram_error(spectral_mds(dog, dim=2, spectrum=spectrum, sampling=sampling), X_classical[:, :2])",
     "percentage"),
    (("e2 = gram_error(spectral_mds(dog, dim=2, sampled='rows', spectrum=spectrum, sampling=sampling),"
      " X_classical[:, :2])"), "gram_error(Z, X)"),                                             # the paper's form
])
def test_two_d_wrong_answers(notebook, code, hint):
    zero("10-two-d", hint, **answers(code, "e2", **notebook))


def test_two_d_precision_and_placeholders(notebook):
    value = answers(solution("10-two-d"), "e2", **notebook)["e2"]
    assert 0.002 < value < 0.01
    zero("10-two-d", "a Gram error", e2="small")
    zero("10-two-d", "a Gram error", e2=[value, value])
    zero("10-two-d", e2=..., status="not attempted")
    assert verdict("10-two-d", e2=value) == verdict("10-two-d", e2=value)          # deterministic
    assert graded("10-two-d", e2=value) == 2.0                                     # the real, fresh process


# --- 10-cost-recap -------------------------------------------------------------------------------

def test_recap_right_answers():
    full("10-cost-recap", **answers(solution("10-cost-recap"), "q1", "q2", "q3"))
    full("10-cost-recap", q1="No", q2=2.0, q3="Spectral ")
    full("10-cost-recap", **answers("q1 = 'NO'\nq2 = np.int64(2)\nq3 = 'spectral'", "q1", "q2", "q3"))
    full("10-cost-recap", q1="no", q2="2", q3=np.str_("spectral"))


@pytest.mark.parametrize("given, expected, words", [
    (("yes", 2, "spectral"), 2.0, ["question 1", "dashed"]),
    (("no", 1, "spectral"), 2.0, ["question 2", "spectral mds's memory"]),
    (("no", 3, "spectral"), 2.0, ["question 2", "entries"]),
    (("no", 2, "classical"), 2.0, ["question 3", "coarser mesh"]),
    (("yes", 1, "spectral"), 1.0, ["question 1", "question 2"]),
    (("yes", "two", "classical"), 0.0, ["0 of 3"]),
    ((..., 2, ...), 1.0, ["question 1", "not answered", "question 3"]),
])
def test_recap_partial_credit(given, expected, words):
    points, _, message = verdict("10-cost-recap", **dict(zip(("q1", "q2", "q3"), given)))
    assert points == expected, (given, message)
    for word in words:
        assert word in message.lower(), (word, message)
    for answer, right in zip(given, ("no", "2", "spectral")):
        if str(answer) != right and right != "2":                # hints never give the right choices
            assert f'"{right}"' not in message.lower(), (right, message)


def test_recap_placeholders():
    zero("10-cost-recap", q1=..., q2=..., q3=..., status="not attempted")
    zero("10-cost-recap", **answers("q1 = ...\nq2 = ...\nq3 = ...", "q1", "q2", "q3"), status="not attempted")
