"""The graded tests as a whole (lbo_notebooks.exercises.grading): every exercise has a grader whose
hidden test uses only the prompt's names, the points follow the kinds, and the grade cannot be
changed from the student's kernel. The graders of each notebook are tested in test_grading_NN.py."""

from __future__ import annotations

import ast
import json
import re
from pathlib import Path

import numpy as np
import pytest

import lbo_notebooks
from lbo_notebooks import exercises
from lbo_notebooks.exercises import grading
from lbo_notebooks.exercises.grading import _registry

NOTEBOOKS = sorted((Path(__file__).resolve().parent.parent / "notebooks").glob("*.ipynb"))
PROMPT = re.compile(r"\*\*Exercise (\d\d-[\w-]+)\*\* · \*([^*]+)\*")
HIDDEN = re.compile(r"### BEGIN HIDDEN TESTS\n(.*?)### END HIDDEN TESTS", re.S)
KINDS = {"build it yourself": "build", "recap": "recap", "explain": "choice"}


def _cells():
    for path in NOTEBOOKS:
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            source = "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]
            yield path, cell, source


def _expected_kind(prompt_kind: str) -> str:
    first = prompt_kind.split(",")[0].strip()
    return KINDS.get(prompt_kind, {"predict": "predict", "compute": "compute", "explore": "explore"}.get(first.split()[0], first))


def test_every_exercise_has_a_grader_of_its_kind():
    graders = grading.load_graders()
    prompts = {m.group(1): m.group(2) for _, c, s in _cells() if c["cell_type"] == "markdown"
               for m in [PROMPT.search(s)] if m and not c["metadata"].get("nbgrader")}
    assert len(prompts) >= 75
    assert set(prompts) == set(graders), (sorted(set(prompts) - set(graders)), sorted(set(graders) - set(prompts)))
    wrong_kind = {e: (k, graders[e].kind) for e, k in prompts.items() if graders[e].kind != _expected_kind(k)}
    assert not wrong_kind, wrong_kind


def test_hidden_tests_call_the_grader_with_the_prompts_names_only():
    graders = grading.load_graders()
    seen = set()
    for path, cell, source in _cells():
        meta = cell["metadata"].get("nbgrader", {})
        if not (meta.get("grade") and cell["cell_type"] == "code"):
            continue
        exercise = meta["grade_id"][: -len("-check")]
        hidden = HIDDEN.search(source)
        assert hidden, f"{path.name}: {exercise} has no hidden test"
        tree = ast.parse(hidden.group(1))
        *imports, last = tree.body
        assert [ast.unparse(s) for s in imports] == ["from lbo_notebooks.exercises.grading import grade"], (
            f"{path.name}: {exercise}'s hidden test should only import grade, then call it")
        call = last.value if isinstance(last, ast.Expr) else None
        assert isinstance(call, ast.Call) and ast.unparse(call.func) == "grade", f"{exercise}: end with grade(...)"
        assert [ast.literal_eval(a) for a in call.args] == [exercise], f"{exercise}: grade({exercise!r}, ...)"
        names = [k.arg for k in call.keywords]
        assert names == list(graders[exercise].names), (exercise, names, graders[exercise].names)
        assert all(ast.unparse(k.value) == k.arg for k in call.keywords), f"{exercise}: pass each answer by its own name"
        assert meta["points"] == graders[exercise].points, (exercise, meta["points"], graders[exercise].points)
        seen.add(exercise)
    assert seen == set(graders)


def test_written_answers_are_worth_their_points():
    written = [(p.name, c["metadata"]["nbgrader"]) for p, c, _ in _cells()
               if c["cell_type"] == "markdown" and c["metadata"].get("nbgrader", {}).get("grade")]
    assert len(written) >= 7
    assert all(m["points"] == grading.POINTS["written"] and m["grade_id"].endswith("-explain") for _, m in written)


def test_patching_the_checks_in_the_kernel_changes_no_grade(monkeypatch):
    """An answer cell runs in the kernel that runs the hidden test: what it patches there stays there."""
    monkeypatch.setattr(exercises.Feedback, "correct", property(lambda self: True))
    monkeypatch.setattr(np, "allclose", lambda *a, **k: True)
    monkeypatch.setattr(exercises, "check_stretch_growth", lambda *a, **k: exercises.Feedback("01-stretch", "correct", ""))
    with pytest.raises(AssertionError, match="0 / 1 points"):
        grading.grade("01-stretch", stretch="same")
    assert grading.grade("01-stretch", stretch="double") == 1.0


def test_what_an_answer_prints_stays_out_of_the_cell(capfd):
    """nbgrader gives 0 points to a graded cell with anything on stderr: the graded run keeps the
    answer's output and warnings to itself."""
    def noisy(mesh):
        import sys
        import warnings

        print("debug", file=sys.stderr)
        warnings.warn("a student's warning")
        return np.ones((2, 2))

    with pytest.raises(AssertionError, match="03-stiffness · 0 / 5"):
        grading.grade("03-stiffness", my_stiffness=noisy)
    out, err = capfd.readouterr()
    assert err == "" and "debug" not in out


def test_an_answer_that_never_returns_gets_no_points(monkeypatch):
    monkeypatch.setenv("LBO_GRADE_TIMEOUT", "5")

    def forever(mesh):
        while True:
            pass

    with pytest.raises(AssertionError, match="longer than 5 s"):
        grading.grade("03-stiffness", my_stiffness=forever)


def test_an_answer_that_cannot_be_sent_gets_no_points():
    import threading

    with pytest.raises(AssertionError, match="could not be sent"):
        grading.grade("01-stretch", stretch=threading.Lock())


def test_a_blocked_function_raises_only_inside_the_answer():
    from lbo_notebooks import operators, shapes

    mesh = shapes.icosphere(1)
    _registry.block(("lbo_notebooks.operators._cotangent:stiffness_matrix",))
    _registry.block(("lbo_notebooks.operators._cotangent:stiffness_matrix",))   # twice: no second wrapper
    assert operators.stiffness_matrix(mesh).shape == (42, 42)         # the grader itself may use it
    with pytest.raises(_registry.LibraryUsed):
        _registry.student_call(lambda m: operators.stiffness_matrix(m), mesh)

    def hides_it(m):
        try:
            return operators.stiffness_matrix(m)
        except Exception:  # noqa: BLE001 - a student catching everything
            return np.zeros((42, 42))

    with pytest.raises(_registry.LibraryUsed):                        # caught, still seen
        _registry.student_call(hides_it, mesh)
    assert operators.stiffness_matrix(mesh).shape == (42, 42)


def test_a_blocked_function_keeps_its_signature(monkeypatch):
    """Blocking lasts for the process; help() and inspect still see the original's parameters
    (a notebook cell asserts a default through inspect.signature)."""
    import inspect
    import sys

    from lbo_notebooks.spectral import _spectrum as spectrum

    # Unblock at teardown: a later test of this worker (test_grading_03's library calls) expects
    # the 03-stiffness grader to name laplace_beltrami, not an eigenbasis blocked here.
    original = lbo_notebooks.eigenbasis  # bound in the lazy front door now, so restored there too
    for name, module in list(sys.modules.items()):
        if module is not None and name.partition(".")[0] == "lbo_notebooks":
            for key, value in list(vars(module).items()):
                if value is original:
                    monkeypatch.setattr(module, key, original)
    before = inspect.signature(spectrum.eigenbasis)
    _registry.block(("lbo_notebooks.spectral._spectrum:eigenbasis",))
    assert getattr(spectrum.eigenbasis, "__lbo_guard__", False)
    assert inspect.signature(spectrum.eigenbasis) == before
    assert inspect.signature(lbo_notebooks.eigenbasis).parameters["n_neighbors"].default == 30


def test_a_verdict_is_a_fraction():
    with pytest.raises(ValueError, match="fraction"):
        grading.Verdict(1.5, "too much")
    with pytest.raises(ValueError, match="kind"):
        grading.grader("99-x", kind="essay")


def _check_cell(exercise: str, outputs: list) -> "nbformat.NotebookNode":
    import nbformat

    cell = nbformat.v4.new_code_cell("feedback = ...", metadata={"nbgrader": {
        "grade": True, "solution": False, "grade_id": f"{exercise}-check", "points": 1}})
    cell.outputs = [nbformat.from_dict(o) for o in outputs]
    return cell


def _published(exercise: str, **answers) -> dict:
    import base64

    import cloudpickle

    payload = base64.b64encode(cloudpickle.dumps(answers)).decode("ascii")
    return {"output_type": "display_data", "metadata": {}, "data": {grading.ANSWERS_MIME: {"exercise": exercise, "payload": payload}}}


def test_autograde_decides_outside_the_kernel():
    """The course's preprocessor judges the published answers itself: what the kernel claimed (a
    score, an error, a warning on stderr) is replaced, and a cell that published nothing earns 0."""
    pytest.importorskip("nbconvert")
    from lbo_notebooks.exercises.grading.autograde import GradeOutsideKernel

    claimed = {"output_type": "execute_result", "execution_count": 1, "metadata": {}, "data": {"text/plain": "1.0"}}
    warning = {"output_type": "stream", "name": "stderr", "text": "a student's warning\n"}
    import nbformat

    pre = GradeOutsideKernel()
    nb = nbformat.v4.new_notebook(cells=[_check_cell("01-stretch", [claimed])])
    nb, _ = pre(nb, {})                                                  # as nbconvert calls it: enabled
    assert [o.output_type for o in nb.cells[0].outputs] == ["error"]
    right, _ = pre.preprocess_cell(_check_cell("01-stretch", [warning, _published("01-stretch", stretch="double")]), {}, 0)
    kinds = [o.output_type for o in right.outputs]
    assert kinds[-1] == "execute_result" and right.outputs[-1].data["text/plain"] == "1.0" and "error" not in kinds
    assert all(o.get("name") != "stderr" for o in right.outputs)        # nbgrader would score stderr as 0
    wrong, _ = pre.preprocess_cell(_check_cell("01-stretch", [claimed, _published("01-stretch", stretch="same")]), {}, 0)
    assert [o.output_type for o in wrong.outputs] == ["error"] and "0 / 1 points" in wrong.outputs[0].evalue
    faked, _ = pre.preprocess_cell(_check_cell("01-stretch", [claimed]), {}, 0)   # grade() replaced: nothing published
    assert [o.output_type for o in faked.outputs] == ["error"] and "no answers reached" in faked.outputs[0].evalue
    other, _ = pre.preprocess_cell(_check_cell("01-stretch", [_published("01-area", area_factor=2.56)]), {}, 0)
    assert other.outputs[-1].output_type == "error"                     # answers of another exercise


def test_under_the_courses_autograde_grade_only_publishes_and_fails_safe(monkeypatch):
    """With NBGRADER_EXECUTION=autograde and the course's flag, grade() leaves the verdict to the
    preprocessor: in a kernel it publishes the answers and raises, so that a course without the
    preprocessor scores the cell 0, never full marks."""
    published = []
    monkeypatch.setenv("NBGRADER_EXECUTION", "autograde")
    monkeypatch.setenv(grading.OUTSIDE_KERNEL, "1")
    monkeypatch.setattr(grading, "_publish", lambda exercise, payload: published.append(exercise) or True)
    with pytest.raises(AssertionError, match="course's grader"):
        grading.grade("01-stretch", stretch="double")
    assert published == ["01-stretch"]
