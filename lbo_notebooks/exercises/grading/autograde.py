"""Grading outside the student's kernel: an nbgrader preprocessor for ``nbgrader autograde``.

nbgrader runs a notebook's hidden tests in the student's own kernel, after the student's cells, so
an answer cell can replace anything the hidden test calls (``exercises.grading.grade`` itself).
The course written by ``./make.sh course`` therefore registers :class:`GradeOutsideKernel` right
after nbgrader's ``Execute``: the hidden test only publishes the answers it was given (an output
of type :data:`~lbo_notebooks.exercises.grading.ANSWERS_MIME`), and this preprocessor, in the
grading process, judges them in a fresh Python process and writes the cell's outcome, the points
(nbgrader's partial credit) or an error with the reason, replacing whatever the kernel wrote
there. A check cell whose hidden test published nothing (it raised first, or was replaced) earns 0.
What the kernel can still choose is only which answers it sends, which is answering.

Needs nbconvert (installed with nbgrader); the rest of the package never imports this module.
"""

from __future__ import annotations

import base64
from typing import Any

from nbconvert.preprocessors import Preprocessor
from nbformat.v4 import new_output
from traitlets import Bool

from . import ANSWERS_MIME, graded_run


def _is_check(cell: Any) -> bool:
    meta = cell.get("metadata", {}).get("nbgrader", {})
    return (cell.get("cell_type") == "code" and bool(meta.get("grade")) and not meta.get("solution")
            and str(meta.get("grade_id", "")).endswith("-check"))


class GradeOutsideKernel(Preprocessor):
    """Replace each check cell's outcome by the verdict on the answers its hidden test published."""

    # nbconvert's preprocessors do nothing unless enabled; this one is registered only to run.
    enabled = Bool(True).tag(config=True)

    def preprocess_cell(self, cell: Any, resources: Any, index: int) -> tuple[Any, Any]:
        if not _is_check(cell):
            return cell, resources
        exercise = cell.metadata.nbgrader.grade_id[: -len("-check")]
        published = [o for o in cell.get("outputs", []) if o.get("output_type") == "display_data"
                     and ANSWERS_MIME in o.get("data", {})]
        kept = []
        for output in cell.get("outputs", []):
            kind = output.get("output_type")
            if kind in ("execute_result", "error") or (kind == "display_data" and ANSWERS_MIME in output.get("data", {})):
                continue  # the kernel's own outcome: decided here instead
            if kind == "stream" and output.get("name") == "stderr":
                # a warning from the student's code in the visible check is not a failed test
                output = new_output("stream", name="stdout", text=output.get("text", ""))
            kept.append(output)
        answers = published[-1]["data"][ANSWERS_MIME] if published else None
        if not answers or answers.get("exercise") != exercise:
            points, message = 0.0, (f"{exercise} · 0 points: no answers reached the grader (an error in the "
                                    "cell before the graded test, or a graded test that was replaced).")
        else:
            points, message = graded_run(exercise, base64.b64decode(answers["payload"]))
        if points > 0:
            kept.append(new_output("stream", name="stdout", text=message + "\n"))
            kept.append(new_output("execute_result", data={"text/plain": repr(points)}, execution_count=cell.get("execution_count")))
        else:
            kept.append(new_output("error", ename="AssertionError", evalue=message, traceback=[f"AssertionError: {message}"]))
        cell.outputs = kept
        return cell, resources
