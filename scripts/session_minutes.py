"""A lower bound on the class time a notebook needs, from what a student reads, runs and answers.

The estimate adds reading the prose at 120 words a minute, reading and running the visible code at
20 lines a minute, and a fixed time per exercise by kind: a build 25 minutes, an explore 10, a
compute 8, a recap 5, a prediction or a choice 3, a written explanation 5. A notebook's header
must state at least this many minutes (``tests/test_notebooks_format.py``); the lecturers' term plan
takes its minutes from the headers (``scripts/booklet.py --sync-plan``).

A reader studying alone has no lecturer to unblock an exercise or explain a figure: the header's
self-study time (``about M on your own``) allows half as long again as the estimate, rounded up
to five minutes, and never less than the class time the header states (``self_study_minutes``).
The factor is an assumption of the model, not a measurement; the header must state at least it.

Usage::

    python scripts/session_minutes.py            # the table: stated, estimated, and its parts

Examples
--------
>>> import nbformat
>>> nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell(" ".join(["word"] * 240)),
...                                      nbformat.v4.new_code_cell("x = 1\\ny = 2")])
>>> estimate(nb)["minutes"]
2.1
>>> self_study_minutes(nb)
5
"""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))
from booklet import stated_minutes  # noqa: E402  (the header's class time, parsed once for all)
WORDS_PER_MINUTE = 120
LINES_PER_MINUTE = 20
SELF_STUDY_FACTOR = 1.5  # alone: no one to ask (an assumption of the model, see above)
MINUTES_PER_EXERCISE = {"build": 25, "explore": 10, "compute": 8, "recap": 5, "predict": 3, "choice": 3, "written": 5}
_FORMULA = re.compile(r"\$\$.+?\$\$|\$[^$\n]+\$", re.DOTALL)
_HIDDEN = re.compile(r"^[ \t]*#+\s*BEGIN (?:HIDDEN TESTS|SOLUTION).*?^[ \t]*#+\s*END (?:HIDDEN TESTS|SOLUTION)[^\n]*\n?",
                     re.MULTILINE | re.DOTALL)


def _grader(cell: nbformat.NotebookNode) -> dict:
    return cell.metadata.get("nbgrader", {})


def _hidden(cell: nbformat.NotebookNode) -> bool:
    return "hide-input" in cell.metadata.get("tags", []) or cell.metadata.get("jupyter", {}).get("source_hidden", False)


def exercise_kinds(nb: nbformat.NotebookNode) -> list[str]:
    """The kind of every exercise of ``nb``: from its grader (``NN-name-check`` cells) or
    ``written`` (``NN-name-explain`` cells)."""
    sys.path.insert(0, str(ROOT))
    from lbo_notebooks.exercises.grading import _registry, load_graders

    kinds = []
    for cell in nb.cells:
        grade_id = _grader(cell).get("grade_id", "")
        if grade_id.endswith("-explain"):
            kinds.append("written")
        elif grade_id.endswith("-check"):
            exercise = grade_id[: -len("-check")]
            load_graders(exercise)
            kinds.append(_registry.GRADERS[exercise].kind)
    return kinds


def estimate(nb: nbformat.NotebookNode) -> dict:
    """The estimate's parts and total (minutes, one decimal): ``{"words", "lines", "exercises",
    "minutes"}``. Prose excludes a written answer's model answer; code excludes hidden
    verification cells, solutions and hidden tests."""
    words = sum(len(_FORMULA.sub("formula", c.source).split()) for c in nb.cells
                if c.cell_type == "markdown" and not _grader(c).get("solution"))
    lines = sum(1 for c in nb.cells if c.cell_type == "code" and not _hidden(c)
                for line in _HIDDEN.sub("", c.source).splitlines() if line.strip())
    kinds = exercise_kinds(nb)
    minutes = words / WORDS_PER_MINUTE + lines / LINES_PER_MINUTE + sum(MINUTES_PER_EXERCISE[k] for k in kinds)
    return {"words": words, "lines": lines, "exercises": kinds, "minutes": round(minutes, 1)}


def self_study_minutes(nb: nbformat.NotebookNode) -> int:
    """The self-study time the model gives ``nb``: the estimate times ``SELF_STUDY_FACTOR``, rounded
    up to a multiple of five minutes, or the class time its header states if that is longer."""
    try:
        in_class = stated_minutes(nb)
    except ValueError:  # no header yet
        in_class = 0
    return max(5 * math.ceil(SELF_STUDY_FACTOR * estimate(nb)["minutes"] / 5), in_class)


def main() -> None:
    print("| notebook | stated | estimate | on your own | words | code lines | exercises |\n"
          "| --- | ---: | ---: | ---: | ---: | ---: | --- |")
    for path in sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb")):
        nb = nbformat.read(path, as_version=4)
        est = estimate(nb)
        counts = {k: est["exercises"].count(k) for k in MINUTES_PER_EXERCISE if k in est["exercises"]}
        print(f"| {path.stem} | {stated_minutes(nb)} | {est['minutes']} | {self_study_minutes(nb)} | {est['words']} | {est['lines']} | "
              + ", ".join(f"{n} {k}" for k, n in counts.items()) + " |")


if __name__ == "__main__":
    main()
