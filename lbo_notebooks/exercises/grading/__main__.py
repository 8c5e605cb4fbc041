"""The graded run of one exercise, in a fresh process: ``python -m lbo_notebooks.exercises.grading
EXERCISE ANSWERS RESULT`` reads the pickled answers from the file ANSWERS and writes the verdict as
JSON to the file RESULT (see :func:`lbo_notebooks.exercises.grading.grade`, which starts it)."""

from __future__ import annotations

import contextlib
import io
import json
import os
import pickle
import sys
import traceback
import warnings


def _verdict(exercise: str, data: bytes) -> dict:
    from ..feedback import NOT_ATTEMPTED, Stop, plain
    from . import _registry, load_graders

    load_graders(exercise)
    found = _registry.GRADERS.get(exercise)
    if found is None:
        return {"error": f"no grader for exercise {exercise!r}"}
    _registry.block(found.replaces)
    try:
        answers = pickle.loads(data)
    except Exception as err:  # noqa: BLE001 - whatever the answer's objects need to rebuild
        return {"fraction": 0.0, "status": "wrong", "points": found.points,
                "message": f"Your answer could not be read back in the graded run ({type(err).__name__}: {err})."}
    if set(answers) != set(found.names):
        return {"error": f"{exercise}: the hidden test passes {sorted(answers)}, the grader takes {list(found.names)}"}
    try:
        # Read as plain data: no method of the answer's own classes runs while the grader reads it.
        answers = {name: plain(value) for name, value in answers.items()}
        verdict = found.judge(**answers)
        fraction, message, status = verdict.fraction, verdict.message, "graded"
    except Stop as stop:
        fraction, message, status = 0.0, stop.message, stop.status
    except _registry.LibraryUsed as used:
        fraction, status = 0.0, "wrong"
        message = (f"This exercise asks you to build it yourself: in the graded run the library's `{used}` is "
                   "not available, and your answer calls it.")
    if status == NOT_ATTEMPTED:
        message = f"Not attempted: {message}"
    return {"fraction": float(fraction), "status": status, "points": found.points, "message": message}


def main(argv: list[str]) -> int:
    exercise, answers_path, result_path = argv
    with open(answers_path, "rb") as handle:
        data = handle.read()
    # What the answer prints is not the verdict: keep it off the result, and warnings out of it.
    sink = io.StringIO()
    with warnings.catch_warnings(), contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
        warnings.simplefilter("ignore")
        try:
            result = _verdict(exercise, data)
        except BaseException:  # noqa: BLE001 - a grader's own bug is reported, with its traceback
            result = {"error": traceback.format_exc(limit=8)}
    with open(result_path, "w", encoding="utf-8") as handle:
        json.dump(result, handle)
    return 0


if __name__ == "__main__":
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    sys.exit(main(sys.argv[1:]))
