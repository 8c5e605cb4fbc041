"""Cells of one exercise, marked the nbgrader way (see docs/exercises.md).

An exercise is three cells, in this order, where the idea is taught:

1. ``prompt``: a Markdown cell, ``**Exercise NN-name** · *kind*`` and the question;
2. ``answer``: the code cell the student edits, an nbgrader *solution* cell with grade id
   ``NN-name-answer``. It starts with the placeholder the student edition keeps (``x = ...``, or
   a ``def`` line, its docstring and ``...`` as its body), then the instructor's solution between
   ``### BEGIN SOLUTION`` and ``### END SOLUTION``, which the student edition removes;
3. ``check``: a locked nbgrader *grade* cell (grade id ``NN-name-check``, the points of the
   exercise's kind, ``lbo_notebooks.exercises.grading.POINTS``) that calls the check from
   ``lbo_notebooks.exercises``; its hidden test passes the answers, by the prompt's names, to the
   exercise's grader (``grade("NN-name", x=x)``, registered in ``exercises/grading/nbNN.py``). The
   student edition drops it, the instructor edition (nbval) and the autograder run it;
4. optionally ``written``: a manually graded Markdown cell (``NN-name-explain``) with the model
   answer and the rubric.

Use from a notebook-editing script::

    import sys; sys.path.insert(0, "scripts")
    from exercise_cells import exercise
    nb.cells[i:i] = exercise("05-projection", "build it yourself", "Write ...", placeholder, solution,
                             "exercises.check_projection(my_project, spectrum)", ("my_project",))
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


def check(exercise: str, call: str, names: tuple[str, ...], *, points: int) -> nbformat.NotebookNode:
    """The locked check cell: ``feedback = <call>``, then the hidden test ``grade(exercise, name=name, ...)``."""
    arguments = "".join(f", {name}={name}" for name in names)
    tests = f"from lbo_notebooks.exercises.grading import grade\n\ngrade({exercise!r}{arguments})".replace("'", '"')
    cell = nbformat.v4.new_code_cell(f"feedback = {call}\n### BEGIN HIDDEN TESTS\n{tests}\n### END HIDDEN TESTS")
    cell.metadata["nbgrader"] = _nbgrader(f"{exercise}-check", solution=False, grade=True, points=points)
    return cell


def written(exercise: str, model_answer: str, rubric: str, *, points: int = 2) -> nbformat.NotebookNode:
    """A written answer graded by a person: the model answer and the rubric (the student edition
    shows *YOUR ANSWER HERE* instead)."""
    cell = nbformat.v4.new_markdown_cell(f"**Model answer.** {model_answer.strip()}\n\n**Rubric ({points} points).** {rubric.strip()}")
    cell.metadata["nbgrader"] = _nbgrader(f"{exercise}-explain", solution=True, grade=True, points=points)
    return cell


def exercise(exercise_id: str, kind: str, text: str, placeholder: str, solution: str, call: str,
             names: tuple[str, ...], *, after: str = "", points: int | None = None) -> list[nbformat.NotebookNode]:
    """The three cells of one exercise: prompt, answer, check (``points``: the kind's, by default)."""
    if points is None:
        from lbo_notebooks.exercises.grading import POINTS

        first = kind.split(",")[0].split()[0]
        points = POINTS[{"build": "build", "explain": "choice"}.get(first, first)]
    return [prompt(exercise_id, kind, text), answer(exercise_id, placeholder, solution, after=after),
            check(exercise_id, call, names, points=points)]
