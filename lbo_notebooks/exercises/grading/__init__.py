"""The graded tests of the exercises: what ``nbgrader autograde`` scores, apart from the visible checks.

Each exercise's check cell ends in a hidden test (removed from the student edition, restored by
``nbgrader autograde``)::

    feedback = exercises.check_stiffness(my_stiffness)      # the visible, formative check
    ### BEGIN HIDDEN TESTS
    from lbo_notebooks.exercises.grading import grade
    grade("03-stiffness", my_stiffness=my_stiffness)        # the grade
    ### END HIDDEN TESTS

:func:`grade` sends the answers, by the names the prompt defines, to a fresh Python process, where
the exercise's grader (``grading/nbNN.py``) judges them: values against the exact result rebuilt
from the prompt's definitions (not from the notebook's variables), functions on inputs the notebook
never shows, and for a *build it yourself* exercise with the library function it replaces made
unavailable. Patching the checks, :class:`~lbo_notebooks.exercises.Feedback`, NumPy or the library
from an answer cell therefore changes nothing, and the same answers get the same points every time.
Under ``nbgrader autograde`` of a course written by ``./make.sh course``, the verdict is reached
outside the student's kernel altogether (:mod:`~lbo_notebooks.exercises.grading.autograde`).

The points of an exercise follow its kind (:data:`POINTS`; docs/exercises.md, "Points").

Examples
--------
>>> grade("01-stretch", stretch="double")
1.0
>>> grade("01-stretch", stretch="same")
Traceback (most recent call last):
...
AssertionError: 01-stretch · 0 / 1 points: The stretch rθ/L depends on the angle θ: a larger bend over the same band stretches more.
"""

from __future__ import annotations

import importlib
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

from ._registry import GRADERS, POINTS, Grader, LibraryUsed, Verdict, from_feedback, grader, student_call

__all__ = ["grade", "graded_run", "ANSWERS_MIME", "POINTS", "GRADERS", "Grader", "Verdict", "grader", "student_call", "from_feedback",
           "LibraryUsed", "load_graders"]

TIMEOUT = 300.0
"""Seconds one graded run may take (``LBO_GRADE_TIMEOUT`` overrides): an answer that loops forever
gets no points instead of stopping the autograder."""


def load_graders(exercise: str | None = None) -> dict[str, Grader]:
    """Import the graders of one exercise's notebook (``"03-mass"`` -> ``grading/nb03.py``), or of all."""
    here = Path(__file__).parent
    numbers = [exercise.split("-", 1)[0]] if exercise else sorted(p.stem[2:] for p in here.glob("nb[0-9][0-9].py"))
    for number in numbers:
        if (here / f"nb{number}.py").exists():
            importlib.import_module(f"{__name__}.nb{number}")
    return GRADERS


def _environment() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()}
    for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        env.setdefault(name, "1")
    return env


ANSWERS_MIME = "application/vnd.lbo-notebooks.graded-answers+json"
"""MIME type of the output in which :func:`grade` publishes the answers it sends (base64 of the
pickle): ``nbgrader autograde`` with the course's preprocessor
(:class:`~lbo_notebooks.exercises.grading.autograde.GradeOutsideKernel`) grades that output outside
the student's kernel, whatever the kernel did."""


def grade(exercise: str, /, **answers: Any) -> float:
    """The points the answers earn, judged in a fresh process; raises AssertionError with the reason
    when they earn none.

    Parameters
    ----------
    exercise : str
        The exercise id, e.g. ``"03-stiffness"``.
    **answers
        The answers by the names the exercise's prompt defines (values, or the student's functions,
        sent with cloudpickle together with the helpers they use).

    Returns
    -------
    float
        The points earned, more than 0; as a cell's last value nbgrader takes it as the score
        (partial credit). Under the course's ``nbgrader autograde`` (``NBGRADER_EXECUTION=autograde``
        and :data:`OUTSIDE_KERNEL` set) it only publishes the answers as an output of the cell
        (:data:`ANSWERS_MIME`) and raises: the course's preprocessor grades them outside the
        kernel and replaces the error by its verdict, so that nothing an answer cell patched
        decides the points (and a course without that preprocessor scores 0, not full marks).

    Raises
    ------
    AssertionError
        When the answers earn no points (wrong, not attempted, a library call where a build is
        asked for, too slow), with the grader's message.
    """
    import cloudpickle

    try:
        payload = cloudpickle.dumps(answers)
    except Exception as err:  # noqa: BLE001 - anything an answer can hold
        raise AssertionError(f"{exercise} · 0 points: your answer could not be sent to the grader "
                             f"({type(err).__name__}: {err}).") from None
    if _graded_outside() and _publish(exercise, payload):
        # Fail-safe: without the course's preprocessor, which replaces this error by its verdict,
        # the cell scores 0, never full marks.
        raise AssertionError(f"{exercise}: the answers went to the course's grader, whose verdict replaces this line.")
    points, text = graded_run(exercise, payload)
    if points <= 0:
        raise AssertionError(text)
    if points < POINTS_OF.get(exercise, points + 1):
        print(text)
    return points


POINTS_OF: dict[str, float] = {}
"""The full points of the exercises graded in this process (so that a partial score is explained)."""


OUTSIDE_KERNEL = "LBO_GRADE_OUTSIDE_KERNEL"
"""Set to 1 by the course's ``nbgrader_config.py``, which registers the preprocessor that grades
the published answers outside the kernel; the kernels nbgrader starts inherit it."""


def _graded_outside() -> bool:
    return os.environ.get("NBGRADER_EXECUTION") == "autograde" and os.environ.get(OUTSIDE_KERNEL) == "1"


def _publish(exercise: str, payload: bytes) -> bool:
    """Publish the answers as an output of the running cell, for the course's preprocessor; False
    outside IPython."""
    try:
        from IPython import get_ipython
        from IPython.display import display
    except ImportError:  # pragma: no cover - IPython comes with every kernel
        return False
    if get_ipython() is None:
        return False
    import base64

    display({ANSWERS_MIME: {"exercise": exercise, "payload": base64.b64encode(payload).decode("ascii")}}, raw=True)
    return True


def graded_run(exercise: str, payload: bytes) -> tuple[float, str]:
    """Judge pickled answers in a fresh process: (points, message). Never raises; a run that fails,
    hangs or stops without a verdict earns 0 with a message that says so."""
    timeout = float(os.environ.get("LBO_GRADE_TIMEOUT", TIMEOUT))
    with tempfile.TemporaryDirectory(prefix="lbo-grade-") as tmp:
        answers_path, result_path = Path(tmp, "answers.pickle"), Path(tmp, "result.json")
        answers_path.write_bytes(payload)
        # -E: the kernel's PYTHONPATH (which an answer cell could point at a stand-in package) is ignored;
        # the working directory is an empty folder, so nothing there shadows the package either.
        command = [sys.executable, "-E", "-m", "lbo_notebooks.exercises.grading", exercise,
                   str(answers_path), str(result_path)]
        try:
            run = subprocess.run(command, cwd=tmp, env=_environment(), capture_output=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return 0.0, f"{exercise} · 0 points: the graded run of your answer took longer than {timeout:g} s."
        if not result_path.exists():  # os._exit in an answer, memory exhausted, a crash in a library
            tail = " ".join(run.stderr.decode(errors="replace").strip().splitlines()[-3:])
            return 0.0, (f"{exercise} · 0 points: the graded run stopped before a verdict (exit status "
                         f"{run.returncode}). Does your answer end the process or use too much memory? {tail}").rstrip()
        result = json.loads(result_path.read_text(encoding="utf-8"))
    if "error" in result:
        return 0.0, f"{exercise}: the grader failed; tell your lecturer.\n{result['error']}"
    POINTS_OF[exercise] = result["points"]
    points = round(result["fraction"] * result["points"], 2)
    return float(points), f"{exercise} · {points:g} / {result['points']} points: {result['message']}"
