"""Cells of one exercise, marked the nbgrader way (see docs/exercises.md).

An exercise is three cells, in this order, where the idea is taught:

1. ``prompt``: a Markdown cell, ``**Exercise NN-name** · *kind*`` and the question;
2. ``answer``: the code cell the student edits, an nbgrader *solution* cell with grade id
   ``NN-name-answer``. It starts with a placeholder line (``x = ...``) that the student edition
   keeps, then the instructor's solution between ``### BEGIN SOLUTION`` and ``### END SOLUTION``,
   which the student edition replaces by a stub;
3. ``check``: a locked nbgrader *grade* cell (grade id ``NN-name-check``, 1 point) that calls the
   check from ``lbo_notebooks.exercises``; its hidden tests (``### BEGIN HIDDEN TESTS`` ...) assert
   that the answer is correct and any claim that needs the solution. The student edition drops
   them, the instructor edition (nbval) and the autograder run them.

Use from a notebook-editing script::

    import sys; sys.path.insert(0, "scripts")
    from exercise_cells import exercise
    nb.cells[i:i] = exercise("05-projection", "build it yourself", "Write ...", answer_src, "exercises.check_...(...)")
"""

from __future__ import annotations

import nbformat

SCHEMA_VERSION = 3


def _nbgrader(grade_id: str, *, solution: bool, grade: bool, points: int | None = None) -> dict:
    meta = {"grade": grade, "grade_id": grade_id, "locked": grade and not solution, "schema_version": SCHEMA_VERSION,
            "solution": solution, "task": False}
    if grade:
        meta["points"] = points
    return meta


def prompt(exercise: str, kind: str, text: str) -> nbformat.NotebookNode:
    """The question: ``kind`` is compute, predict, explain, explore or build it yourself."""
    return nbformat.v4.new_markdown_cell(f"**Exercise {exercise}** · *{kind}*. {text}")


def answer(exercise: str, placeholder: str, solution: str, *, after: str = "") -> nbformat.NotebookNode:
    """The student's cell: ``placeholder`` (kept), the solution region, then ``after`` (kept)."""
    def indent_of(text: str) -> str:
        first = next((line for line in text.splitlines() if line.strip()), "")
        return first[: len(first) - len(first.lstrip())]

    pad = indent_of(solution)
    body = f"{placeholder.rstrip()}\n{pad}### BEGIN SOLUTION\n{solution.rstrip()}\n{pad}### END SOLUTION"
    if after:
        body += "\n" + after.rstrip()
    cell = nbformat.v4.new_code_cell(body.lstrip("\n"))
    cell.metadata["nbgrader"] = _nbgrader(f"{exercise}-answer", solution=True, grade=False)
    return cell


def check(exercise: str, call: str, hidden: str = "", *, points: int = 1) -> nbformat.NotebookNode:
    """The locked check cell: ``feedback = <call>``, then hidden tests (correct answer + ``hidden``)."""
    tests = "assert feedback.correct, feedback.message"
    if hidden:
        tests += "\n" + hidden.rstrip()
    cell = nbformat.v4.new_code_cell(f"feedback = {call}\n### BEGIN HIDDEN TESTS\n{tests}\n### END HIDDEN TESTS")
    cell.metadata["nbgrader"] = _nbgrader(f"{exercise}-check", solution=False, grade=True, points=points)
    return cell


def exercise(exercise_id: str, kind: str, text: str, placeholder: str, solution: str, call: str,
             hidden: str = "", *, after: str = "", points: int = 1) -> list[nbformat.NotebookNode]:
    """The three cells of one exercise: prompt, answer, check."""
    return [prompt(exercise_id, kind, text), answer(exercise_id, placeholder, solution, after=after),
            check(exercise_id, call, hidden, points=points)]
