"""Helpers for the tests of the graded tests (tests/test_grading_*.py).

An answer is written as a student writes it, as the source of an answer cell, and run in a fresh
namespace that stands for the notebook's kernel (``__main__``, so that its functions are pickled
by value, helpers and all, as from a real notebook). :func:`verdict` then judges it exactly as the
graded run does (pickled, the replaced library blocked), in this process for speed; :func:`graded`
goes through the real fresh process, as nbgrader does.
"""

from __future__ import annotations

import json
import re
import textwrap
from pathlib import Path
from typing import Any

import cloudpickle

PRELUDE = """\
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla
import lbo_notebooks as lbo
from lbo_notebooks import shapes
"""


def cell(code: str, **context: Any) -> dict[str, Any]:
    """Run ``code`` (dedented) after the usual imports in a fresh ``__main__``-like namespace, with
    ``context`` (names the notebook's earlier cells define) in it; return the namespace."""
    namespace: dict[str, Any] = {"__name__": "__main__", **context}
    exec(compile(PRELUDE + textwrap.dedent(code), "<answer cell>", "exec"), namespace)
    return namespace


def answers(code: str, *names: str, **context: Any) -> dict[str, Any]:
    """The values of ``names`` after running the answer cell ``code``."""
    namespace = cell(code, **context)
    return {name: namespace[name] for name in names}


def verdict(exercise: str, **given: Any) -> tuple[float, str, str]:
    """(points, status, message) of the answers, judged in this process as the graded run judges them."""
    from lbo_notebooks.exercises.grading.__main__ import _verdict

    result = _verdict(exercise, cloudpickle.dumps(given))
    assert "error" not in result, result["error"]
    return round(result["fraction"] * result["points"], 2), result["status"], result["message"]


def points(exercise: str, **given: Any) -> float:
    return verdict(exercise, **given)[0]


def full_points(exercise: str) -> float:
    from lbo_notebooks.exercises.grading import load_graders

    return float(load_graders(exercise)[exercise].points)


def graded(exercise: str, **given: Any) -> float:
    """The points through the real graded run (a fresh process); 0.0 where ``grade`` raises."""
    from lbo_notebooks.exercises.grading import grade

    try:
        return grade(exercise, **given)
    except AssertionError:
        return 0.0


def assert_full(exercise: str, **given: Any) -> str:
    """Assert the answers earn the exercise's full points; return the message."""
    earned, status, message = verdict(exercise, **given)
    assert earned == full_points(exercise), (given, status, message)
    return message


def assert_zero(exercise: str, *words: str, status: str = "wrong", **given: Any) -> str:
    """Assert the answers earn nothing, with ``status`` and a message holding each of ``words``
    (case-insensitive); return the message."""
    earned, got, message = verdict(exercise, **given)
    assert earned == 0 and got == status, (given, got, message)
    for word in words:
        assert word.lower() in message.lower(), (word, message)
    return message


_MARKERS = re.compile(r"^[ \t]*### (BEGIN|END) SOLUTION[^\n]*\n?", re.MULTILINE)
_REGION = re.compile(r"(?ms)^([ \t]*)### BEGIN SOLUTION.*?### END SOLUTION[^\n]*")


def answer_cell(notebook: Path, exercise: str) -> str:
    """The source of ``exercise``'s answer cell (grade id ``<exercise>-answer``) in ``notebook``."""
    cells = json.loads(notebook.read_text(encoding="utf-8"))["cells"]
    (cell,) = [c for c in cells if c["metadata"].get("nbgrader", {}).get("grade_id") == f"{exercise}-answer"]
    return "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]


def solution_of(notebook: Path, exercise: str) -> str:
    """The instructor's answer cell as a student who wrote it would run it (markers stripped)."""
    return _MARKERS.sub("", answer_cell(notebook, exercise))


def stub_of(notebook: Path, exercise: str) -> str:
    """The answer cell as the student edition hands it out (the solution replaced by the stub)."""
    return _REGION.sub("", answer_cell(notebook, exercise))
