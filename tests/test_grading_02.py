"""The graded tests of notebook 02 (lbo_notebooks/exercises/grading/nb02.py), on answers written as
students write them: the instructor's, correct ones written differently, typical wrong ones and
placeholders."""

from __future__ import annotations

import ast
import json
import re
from pathlib import Path

import numpy as np
import pytest

from lbo_notebooks.exercises.grading import load_graders

from .grading_support import answers, full_points, graded, verdict

NOTEBOOK = Path(__file__).resolve().parent.parent / "notebooks" / "02_graph_laplacian.ipynb"
_REGION = re.compile(r"### BEGIN SOLUTION\n(.*?)### END SOLUTION", re.S)


def _cells() -> list[dict]:
    cells = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
    for cell in cells:
        cell["source"] = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
    return cells


def solution(exercise: str) -> str:
    (cell,) = [c for c in _cells() if c["metadata"].get("nbgrader", {}).get("grade_id") == f"{exercise}-answer"]
    return _REGION.search(cell["source"]).group(1)


@pytest.fixture(scope="module")
def graph_laplacian():
    """The notebook's own `graph_laplacian`, taken from its cell (the function alone)."""
    (cell,) = [c for c in _cells() if c["cell_type"] == "code" and "def graph_laplacian" in c["source"]]
    (function,) = [n for n in ast.parse(cell["source"]).body if isinstance(n, ast.FunctionDef)]
    namespace: dict = {}
    exec("import numpy as np\nimport scipy.sparse as sp\n" + ast.unparse(function), namespace)
    return namespace["graph_laplacian"]


def test_kinds_and_points():
    graders = load_graders("02-edge-energy")
    assert {e: (g.kind, g.points) for e, g in graders.items() if e.startswith("02-")} == {
        "02-edge-energy": ("compute", 2), "02-cycle-pair": ("predict", 1), "02-step-decay": ("predict", 1),
        "02-graph-recap": ("recap", 3)}


def _right(exercise: str, names: tuple[str, ...], codes: list[str], **context) -> None:
    points = full_points(exercise)
    assert verdict(exercise, **answers(solution(exercise), *names, **context))[0] == points, "the solution"
    for code in codes:
        got = verdict(exercise, **answers(code, *names, **context))
        assert got[0] == points, (code, got)


def _wrong(exercise: str, names: tuple[str, ...], code: str, hint: str, **context) -> str:
    points, status, message = verdict(exercise, **answers(code, *names, **context))
    assert (points, status) == (0, "wrong") and hint in message, (code, message)
    return message


# --- 02-edge-energy ----------------------------------------------------------------------------

EDGE_RIGHT = [
    "g = [0, 1, 4, 9, 16]\npath_energy = sum((g[i] - g[i + 1]) ** 2 for i in range(4))",
    "path_energy = float(np.sum(np.diff(np.array([0, 1, 4, 9, 16.0])) ** 2))",
    "path_energy = np.int64(84)",
    "path_energy = 84.0",
]
EDGE_WRONG = [
    ("g = [0, 1, 4, 9, 16]\npath_energy = sum((g[i] - g[j]) ** 2 for i in range(5) for j in (i - 1, i + 1) if 0 <= j < 5)",
     "Twice"),
    ("path_energy = 1 + 3 + 5 + 7", "Square each difference"),
    ("path_energy = sum(x * x for x in [0, 1, 4, 9, 16])", "‖f‖²"),
    ("path_energy = -84", "never negative"),
    ("path_energy = 1**2 + 3**2 + 5**2", "4 edges"),
    ("path_energy = 'eighty-four'", "a number"),
    ("path_energy = {84: 'energy'}", "a number"),
]


def test_edge_energy_right():
    _right("02-edge-energy", ("path_energy",), EDGE_RIGHT)


@pytest.mark.parametrize("code, hint", EDGE_WRONG)
def test_edge_energy_wrong(code, hint):
    assert "84" not in _wrong("02-edge-energy", ("path_energy",), code, hint)


def test_edge_energy_placeholder():
    assert verdict("02-edge-energy", path_energy=...)[:2] == (0, "not attempted")


def test_the_notebooks_graph_laplacian_gives_the_edge_sum(graph_laplacian):
    """The old hidden test's claim, as a test of the notebook's function: fᵀ L f on the path is the
    sum over its edges (so a value computed with graph_laplacian, which the prompt does not ask
    for, is right too)."""
    g = np.array([0, 1, 4, 9, 16.0])
    energy = g @ graph_laplacian(5, [(k, k + 1) for k in range(4)]) @ g
    assert np.isclose(energy, np.sum(np.diff(g) ** 2), rtol=1e-12)
    assert verdict("02-edge-energy", path_energy=energy)[0] == full_points("02-edge-energy")


# --- 02-cycle-pair -----------------------------------------------------------------------------

CYCLE_RIGHT = [
    "multiplicity = 2.0",
    "k = np.arange(12)\nmultiplicity = int(np.sum(np.isclose(2 - 2 * np.cos(2 * np.pi * k / 12), 2)))",
    "eye = np.eye(12)\nL = 2 * eye - np.roll(eye, 1, axis=1) - np.roll(eye, -1, axis=1)\n"
    "multiplicity = np.sum(np.abs(np.linalg.eigvalsh(L) - 2) < 1e-9)",
]
CYCLE_WRONG = [
    ("multiplicity = 1", "sine"),
    ("multiplicity = 0", "there are solutions"),
    ("multiplicity = 4", "Too many"),
    ("multiplicity = 12", "Too many"),
    ("multiplicity = 2.5", "whole number"),
    ("multiplicity = 'two'", "whole number"),
]


def test_cycle_pair_right():
    _right("02-cycle-pair", ("multiplicity",), CYCLE_RIGHT)


@pytest.mark.parametrize("code, hint", CYCLE_WRONG)
def test_cycle_pair_wrong(code, hint):
    _wrong("02-cycle-pair", ("multiplicity",), code, hint)


def test_cycle_pair_placeholder():
    assert verdict("02-cycle-pair", multiplicity=...)[:2] == (0, "not attempted")


# --- 02-step-decay -----------------------------------------------------------------------------

STEP_RIGHT = [
    "error_drop = 2.0",
    "error_drop = 40 / 20  # the tail of 1/k² beyond n is about 1/n",
    "error_drop = np.float32(2.05)",
    # measured, as the notebook's next cell does, on the prompt's step
    "N = 200\nx = (np.arange(N) + 0.5) / N\n"
    "Phi = np.cos(np.pi * np.outer(np.arange(N) + 0.5, np.arange(N)) / N)\nPhi /= np.linalg.norm(Phi, axis=0)\n"
    "c = Phi.T @ (x > 0.4)\nerror_drop = np.sum(c[20:] ** 2) / np.sum(c[40:] ** 2)",
]
STEP_WRONG = [
    ("error_drop = 4", "kink"),
    ("error_drop = 0.5", "above 1"),
    ("error_drop = 1000", "smooth"),
    ("error_drop = 3", "tail"),
    ("error_drop = 'half'", "a number"),
]


def test_step_decay_right():
    _right("02-step-decay", ("error_drop",), STEP_RIGHT)


@pytest.mark.parametrize("code, hint", STEP_WRONG)
def test_step_decay_wrong(code, hint):
    _wrong("02-step-decay", ("error_drop",), code, hint)


def test_step_decay_placeholder():
    assert verdict("02-step-decay", error_drop=...)[:2] == (0, "not attempted")


# --- 02-graph-recap (partial credit) ------------------------------------------------------------

RECAP = ("q1", "q2", "q3")
RECAP_RIGHT = [
    "q1 = 2.0\nq2 = np.float64(4)\nq3 = 'LAM_N'",
    "q1, q2, q3 = [2, 2 - 2 * np.cos(np.pi), ' lam_n ']",
    "q3 = 'lam_n'\nq2 = 4\nq1 = np.int64(2)",
]


def test_recap_right():
    _right("02-graph-recap", RECAP, RECAP_RIGHT)


@pytest.mark.parametrize("code, points, hints", [
    ("q1, q2, q3 = 4, 4, 'lam_n'", 2, ["Question 1", "linear"]),                     # quadratic in the weights
    ("q1, q2, q3 = 2, 2, 'lam_n'", 2, ["Question 2", "largest"]),
    ("q1, q2, q3 = 2, 4, 'lam_n+1'", 2, ["Question 3", "0-based"]),
    ("q1, q2, q3 = 2, 4, 'lam_n - 1'", 2, ["Question 3", "left out"]),               # spaces do not matter
    ("q1, q2, q3 = 1, 0, 'lam_n'", 1, ["Question 1", "Question 2"]),
    ("q1, q2, q3 = 0.5, 2, 'lam_n+1'", 0, ["Question 1", "Question 2", "Question 3"]),
    ("q1, q2, q3 = 2, ..., 'lam_n'", 2, ["Question 2", "still `...`"]),
    ("q1, q2, q3 = 2, 4, {'lam_n': 1}", 2, ["Question 3", "one of"]),
])
def test_recap_partial_credit_with_the_hints_of_the_wrong_ones_only(code, points, hints):
    got, status, message = verdict("02-graph-recap", **answers(code, *RECAP))
    assert got == points and all(h in message for h in hints), (code, got, message)
    assert status == ("wrong" if points == 0 else "graded")
    assert message.startswith(f"{points} of 3 right")
    named = {k for k in range(1, 4) if f"Question {k}" in message}
    assert len(named) == 3 - points                                  # hints of the wrong ones only
    if "one of" not in message:                                      # the options listed, else never the answer
        assert "lam_n" not in message.replace("lam_n+1", "").replace("lam_n-1", "") and "4" not in message


def test_recap_placeholders():
    assert verdict("02-graph-recap", q1=..., q2=..., q3=...)[:2] == (0, "not attempted")


# --- every exercise ----------------------------------------------------------------------------

def test_same_answers_same_verdicts():
    cases = [("02-edge-energy", {"path_energy": 80}), ("02-cycle-pair", {"multiplicity": 2}),
             ("02-step-decay", {"error_drop": 3}), ("02-graph-recap", {"q1": 2, "q2": 3, "q3": "lam_n"})]
    for exercise, given in cases:
        assert verdict(exercise, **given) == verdict(exercise, **given), exercise


def test_the_real_graded_run():
    assert graded("02-graph-recap", q1=2, q2=4, q3="lam_n") == 3.0
    assert graded("02-graph-recap", q1=4, q2=4, q3="lam_n") == 2.0
    assert graded("02-edge-energy", path_energy=168) == 0.0
