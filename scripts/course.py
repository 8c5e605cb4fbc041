"""Write a ready nbgrader course from the instructor edition: one assignment per notebook.

    python scripts/course.py DIR          # (./make.sh course DIR)

writes

- ``DIR/nbgrader_config.py``: the course's settings (the student edition's stubs, time-outs, kernels);
- ``DIR/source/<stem>/<stem>.ipynb``: each notebook of the series that has exercises, as its own
  assignment (``00_start_here``, ``01_shapes``, ...), releasable alone: no notebook reads a file
  outside its folder, recorded benchmark results ship with the package;
- ``DIR/POINTS.md``: every exercise with its kind and points, per assignment;
- ``DIR/RUBRICS.md``: the written answers (graded by a person in the formgrader), with the model
  answer and the rubric of each.

The standard nbgrader commands then run in ``DIR`` with no edit: ``nbgrader generate_assignment
01_shapes``, ``release_assignment``, ``collect``, ``autograde``, ``generate_feedback``, and the
formgrader (docs/exercises.md, "Running a graded course", walks through a term). An existing
``DIR/source/<stem>`` is never overwritten: a lecturer's edits there are kept (``--force`` replaces).
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "scripts"))

from student_edition import (  # noqa: E402
    CODE_STUB, NOTEBOOKS, copy_for_edition, has_exercises, nbgrader_meta, read, series, source,
)

CONFIG = """\
# nbgrader settings of the lbo_notebooks course, written by `./make.sh course` (scripts/course.py).
import os
import tempfile

c = get_config()  # noqa: F821 - provided by nbgrader
c.CourseDirectory.course_id = "lbo-notebooks"
# A solution region leaves nothing behind (not nbgrader's `raise NotImplementedError()`): the `...`
# before it is the answer cell's one placeholder, the notebook runs top to bottom unanswered and
# every check says "not attempted".
c.ClearSolutions.code_stub = {{"python": {stub!r}}}
c.ClearSolutions.text_stub = "YOUR ANSWER HERE"
# A notebook runs in well under a minute; a cell (a graded run included) may take up to this long.
c.Execute.timeout = 600
c.Autograde.create_student = True
# The grade is decided outside the student's kernel: each hidden test publishes the answers it was
# given, and this preprocessor (right after nbgrader's Execute) judges them in a fresh process and
# writes the cell's outcome, whatever the student's code did to the kernel (docs/exercises.md).
from nbconvert.preprocessors import ClearMetadataPreprocessor  # noqa: E402
from nbgrader.preprocessors import (  # noqa: E402
    AssignLatePenalties, CheckCellMetadata, Execute, IgnorePattern, LimitOutput, SaveAutoGrades,
)

from lbo_notebooks.exercises.grading.autograde import GradeOutsideKernel  # noqa: E402

os.environ["LBO_GRADE_OUTSIDE_KERNEL"] = "1"  # read by the hidden tests' grade(): publish, do not judge
c.Autograde.autograde_preprocessors = [
    Execute, GradeOutsideKernel, IgnorePattern, ClearMetadataPreprocessor, LimitOutput, SaveAutoGrades,
    AssignLatePenalties, CheckCellMetadata,
]
# Kernels on local IPC sockets, not TCP: ipykernel warns at each start that TCP is unencrypted, and
# a warning in a graded cell's output costs the student its points.
c.KernelManager.transport = "ipc"
c.KernelManager.ip = os.path.join(tempfile.mkdtemp(prefix="lbo-course-kernels-"), "kernel")
# Where releases and submissions are exchanged with the students (nbgrader's default below); set it
# to the folder your JupyterHub shares, e.g.
# c.Exchange.root = "/srv/nbgrader/exchange"
"""

KIND = re.compile(r"\*\*Exercise (\d\d-[\w-]+)\*\* · \*([^*]+)\*")
OUTSIDE = re.compile(r"""["'](\.\./[^"']+)["']""")


def exercises_of(path: Path) -> list[dict]:
    """The exercises of one notebook: id, the prompt's kind, the points of its graded cells."""
    nb = read(path)
    found: dict[str, dict] = {}
    for cell in nb["cells"]:
        text = source(cell)
        if cell["cell_type"] == "markdown" and (m := KIND.search(text)) and not nbgrader_meta(cell):
            found.setdefault(m.group(1), {"id": m.group(1), "kind": m.group(2), "auto": 0, "manual": 0})
        meta = nbgrader_meta(cell)
        if meta.get("grade"):
            exercise = meta["grade_id"].rsplit("-", 1)[0]
            entry = found.setdefault(exercise, {"id": exercise, "kind": "?", "auto": 0, "manual": 0})
            entry["manual" if meta.get("solution") else "auto"] += meta.get("points", 0)
    return list(found.values())


def written_answers(path: Path) -> list[tuple[str, str]]:
    """(grade id, model answer and rubric) of the manually graded Markdown cells."""
    return [(nbgrader_meta(c)["grade_id"], source(c).strip()) for c in read(path)["cells"]
            if c["cell_type"] == "markdown" and nbgrader_meta(c).get("grade") and nbgrader_meta(c).get("solution")]


def reads_outside(path: Path) -> list[str]:
    """Paths outside its own folder that a notebook's code reads (an assignment must not)."""
    return sorted({m for c in read(path)["cells"] if c["cell_type"] == "code" for m in OUTSIDE.findall(source(c))})


def write(course: Path, force: bool = False, only: list[str] | None = None) -> list[Path]:
    """Write the course into ``course`` (or only the assignments named in ``only``); return the
    assignments' source notebooks."""
    course.mkdir(parents=True, exist_ok=True)
    notebooks = [p for p in series(NOTEBOOKS) if has_exercises(p) and (not only or p.stem in only)]
    if only and len(notebooks) != len(set(only)):
        raise SystemExit(f"no such notebooks with exercises: {sorted(set(only) - {p.stem for p in notebooks})}")
    outside = {p.name: reads_outside(p) for p in notebooks if reads_outside(p)}
    if outside:
        raise SystemExit(f"these notebooks read files outside their folder and cannot be released alone: {outside}")
    written = []
    for nb in notebooks:
        folder = course / "source" / nb.stem
        if folder.exists() and not force:
            print(f"kept {folder.relative_to(course)} (exists; --force replaces it)", file=sys.stderr)
        else:
            shutil.rmtree(folder, ignore_errors=True)
            folder.mkdir(parents=True)
            copy_for_edition(nb, folder / nb.name)  # with the glossary beside it
        written.append(folder / nb.name)
    (course / "nbgrader_config.py").write_text(CONFIG.format(stub=CODE_STUB), encoding="utf-8")

    lines = ["# Points of the lbo_notebooks course", "",
             "Written by `./make.sh course`. *auto*: autograded by the hidden tests; *manual*: a written answer",
             "you grade in the formgrader (rubrics in RUBRICS.md). Points follow the kind of exercise",
             "(docs/exercises.md, \"Points\").", ""]
    rubrics = ["# Written answers: model answers and rubrics", "",
               "Each is a Markdown answer cell the formgrader shows for manual grading; the students' edition",
               "has *YOUR ANSWER HERE* in its place.", ""]
    total_auto = total_manual = 0
    for nb in notebooks:
        rows = exercises_of(nb)
        auto, manual = sum(r["auto"] for r in rows), sum(r["manual"] for r in rows)
        total_auto, total_manual = total_auto + auto, total_manual + manual
        lines += [f"## {nb.stem}: {auto:g} autograded + {manual:g} manual points", "",
                  "| exercise | kind | auto | manual |", "| --- | --- | ---: | ---: |"]
        lines += [f"| {r['id']} | {r['kind']} | {r['auto']:g} | {r['manual'] or ''} |" for r in rows]
        lines.append("")
        for grade_id, text in written_answers(nb):
            rubrics += [f"## {grade_id} ({nb.stem})", "", text, ""]
    lines += [f"**Whole course: {total_auto:g} autograded + {total_manual:g} manual points.**", ""]
    (course / "POINTS.md").write_text("\n".join(lines), encoding="utf-8")
    (course / "RUBRICS.md").write_text("\n".join(rubrics), encoding="utf-8")
    return written


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("course", type=Path, help="the course directory to write (created if missing)")
    parser.add_argument("assignments", nargs="*", help="only these notebooks (stems, e.g. 03_laplace_beltrami)")
    parser.add_argument("--force", action="store_true", help="replace assignments already in DIR/source")
    args = parser.parse_args()
    written = write(args.course.resolve(), args.force, args.assignments)
    print(f"wrote a course of {len(written)} assignments to {args.course}/ (source/, nbgrader_config.py, "
          "POINTS.md, RUBRICS.md); next: cd there and `nbgrader generate_assignment 00_start_here` "
          "(docs/exercises.md, \"Running a graded course\")", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
