"""The graded course on the standard nbgrader workflow, with a simulated class (issue 38).

Opt-in (``LBO_COURSE_TESTS=1``; it executes the series once per student): ``./make.sh course --check``.

``scripts/course.py`` writes the course; ``nbgrader generate_assignment`` makes each notebook's
release; one student goes through the real exchange (``release_assignment``, ``fetch_assignment``,
``submit``, ``collect``); then submissions that nobody who wrote the graders wrote
(tests/simulated_class.py) are autograded, each assignment on its own:

- **blank**: the release as handed out: every autograded cell 0 points, no error outside the graded
  cells, every visible check says "not attempted";
- **instructor**: the instructor's answers: full marks;
- **alternative**: a correct answer to every exercise written differently from the solution: full marks;
- **wrong**: a typical wrong answer to every exercise (some with an attempt to patch the checks): 0;
- **library**: the library call in every *build it yourself* exercise: 0 there.

The same submission autograded again gets the same points; ``generate_feedback`` writes the
students' feedback.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

if os.environ.get("LBO_COURSE_TESTS") != "1":
    pytest.skip("the course tests are opt-in: set LBO_COURSE_TESTS=1 (./make.sh course --check)", allow_module_level=True)

from tests import simulated_class  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MIME_TYPE = "application/vnd.lbo-notebooks.feedback+json"
STUDENTS = ("blank", "instructor", "alternative", "wrong", "library")
EXCHANGE_STUDENT = "exchange"


def _env() -> dict[str, str]:
    bin_dir = str(Path(sys.executable).parent)
    env = dict(os.environ, PATH=os.pathsep.join([bin_dir, os.environ.get("PATH", "")]))
    env["PYTHONWARNINGS"] = ",".join(filter(None, [os.environ.get("PYTHONWARNINGS"), "ignore:::nbgrader.api"]))
    for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        env.setdefault(name, "1")
    env.pop("LBO_NOTEBOOKS_SOLUTIONS", None)
    return env


def nbgrader(cwd: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    run = subprocess.run([sys.executable, "-m", "nbgrader", *args, "--log-level=WARN"], cwd=cwd, env=_env(),
                         capture_output=True, text=True)
    if check and run.returncode != 0:
        raise AssertionError(f"nbgrader {' '.join(args)} failed:\n{run.stdout[-3000:]}\n{run.stderr[-3000:]}")
    return run


def _read(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


def _meta(cell: dict) -> dict:
    return cell.get("metadata", {}).get("nbgrader", {})


def _source(cell: dict) -> str:
    return "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]


def instructor_answers() -> dict[str, str]:
    """The instructor's answer cells, code and written (the model answers), by grade id."""
    answers = {}
    for path in sorted((ROOT / "notebooks").glob("*.ipynb")):
        for cell in _read(path)["cells"]:
            if _meta(cell).get("solution"):
                answers[_meta(cell)["grade_id"]] = _source(cell)
    return answers


ANSWERS = {"blank": {}, "instructor": None, "alternative": simulated_class.ALTERNATIVE,
           "wrong": simulated_class.WRONG, "library": simulated_class.LIBRARY}


def submission(release: Path, answers: dict[str, str]) -> dict:
    """The released notebook with the answer cells in ``answers`` (by grade id) filled in."""
    nb = _read(release)
    for cell in nb["cells"]:
        grade_id = _meta(cell).get("grade_id")
        if _meta(cell).get("solution") and grade_id in answers:
            cell["source"] = answers[grade_id]
    return nb


@pytest.fixture(scope="module")
def course(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("course")
    run = subprocess.run([sys.executable, str(ROOT / "scripts" / "course.py"), str(root)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    for folder in sorted((root / "source").iterdir()):
        nbgrader(root, "generate_assignment", folder.name)
        released = root / "release" / folder.name / f"{folder.name}.ipynb"
        text = released.read_text(encoding="utf-8")
        assert "BEGIN SOLUTION" not in text and "BEGIN HIDDEN TESTS" not in text and "**Rubric" not in text, folder.name
    return root


@pytest.fixture(scope="module")
def graded(course, tmp_path_factory) -> dict[str, dict]:
    """Autograde every student (a copy of the course each, two at a time): {student: {grade id: (score, max)}}."""
    assignments = sorted(p.name for p in (course / "source").iterdir())
    answers = dict(ANSWERS, instructor=instructor_answers())

    def one(student: str) -> dict:
        root = tmp_path_factory.mktemp(f"course-{student}")
        shutil.copytree(course, root, dirs_exist_ok=True)
        mine = assignments
        if student == "library":  # only the notebooks with builds: the others would be a blank submission again
            mine = [a for a in assignments if any(g.startswith(a[:2] + "-") for g in answers[student])]
        for assignment in mine:
            release = root / "release" / assignment / f"{assignment}.ipynb"
            target = root / "submitted" / student / assignment
            target.mkdir(parents=True)
            (target / release.name).write_text(json.dumps(submission(release, answers[student])), encoding="utf-8")
        scores = {}
        for assignment in mine:
            nbgrader(root, "autograde", assignment, f"--student={student}")
        from nbgrader.api import Gradebook

        with Gradebook(f"sqlite:///{root / 'gradebook.db'}") as gb:
            for assignment in mine:
                for nb in gb.find_submission(assignment, student).notebooks:
                    for g in nb.grades:
                        scores[g.name] = (g.score, g.max_score, g.auto_score is None and g.manual_score is None)
        return {"root": root, "scores": scores}

    with ThreadPoolExecutor(max_workers=2) as pool:
        return dict(zip(STUDENTS, pool.map(one, STUDENTS)))


def _check_ids(scores: dict, answered: dict[str, str]) -> list[str]:
    return [g[: -len("answer")] + "check" for g in answered if g[: -len("answer")] + "check" in scores]


def test_every_assignment_generates_and_releases_alone(course):
    assignments = sorted(p.name for p in (course / "source").iterdir())
    assert len(assignments) == 13 and all((course / "release" / a / f"{a}.ipynb").exists() for a in assignments)
    # Each assignment carries the glossary its notebook links (beside it: ../docs/ is not handed out).
    assert all((course / "release" / a / "glossary.md").is_file() for a in assignments)
    assert all("](glossary.md)" in (course / "release" / a / f"{a}.ipynb").read_text() for a in assignments)
    assert (course / "POINTS.md").exists() and (course / "RUBRICS.md").read_text().count("**Rubric") >= 7


def test_blank_submissions_score_zero_without_an_error(graded):
    scores, root = graded["blank"]["scores"], graded["blank"]["root"]
    assert scores and all(score == 0 for score, _, _ in scores.values())
    for path in sorted((root / "autograded" / "blank").rglob("*.ipynb")):
        nb = _read(path)
        errors = [i for i, c in enumerate(nb["cells"]) if c["cell_type"] == "code" and not _meta(c).get("grade")
                  for o in c.get("outputs", []) if o["output_type"] == "error"]
        assert not errors, f"{path.name}: cells {errors} raised in the unanswered notebook"
        statuses = [o["data"][MIME_TYPE]["status"] for c in nb["cells"] for o in c.get("outputs", [])
                    if MIME_TYPE in o.get("data", {})]
        assert statuses and set(statuses) == {"not attempted"}, f"{path.name}: {statuses}"


def test_the_instructor_earns_full_marks(graded):
    scores = graded["instructor"]["scores"]
    lost = {g: s for g, s in scores.items() if g.endswith("-check") and s[0] != s[1]}
    assert not lost, lost


def test_correct_answers_written_otherwise_earn_full_marks(graded):
    scores = graded["alternative"]["scores"]
    checks = _check_ids(scores, simulated_class.ALTERNATIVE)
    assert len(checks) >= 70
    lost = {g: scores[g][:2] for g in checks if scores[g][0] != scores[g][1]}
    assert not lost, lost


def test_wrong_answers_and_cheats_earn_nothing(graded):
    """A wrong answer earns 0; a recap with some questions wrong earns a point per right one, never full marks."""
    scores = graded["wrong"]["scores"]
    checks = _check_ids(scores, simulated_class.WRONG)
    assert len(checks) >= 70
    earned = {g: scores[g][:2] for g in checks if scores[g][0] != 0 and ("recap" not in g or scores[g][0] >= scores[g][1])}
    assert not earned, earned


def test_library_calls_in_build_exercises_earn_nothing(graded):
    scores = graded["library"]["scores"]
    checks = _check_ids(scores, simulated_class.LIBRARY)
    assert len(checks) >= 5
    earned = {g: scores[g][:2] for g in checks if scores[g][0] != 0}
    assert not earned, earned


def test_written_answers_wait_for_the_lecturer(graded):
    """Written answers: graded by a person when answered, 0 automatically when left blank."""
    written = [g for g in graded["instructor"]["scores"] if g.endswith("-explain")]
    assert len(written) >= 7
    assert all(graded["instructor"]["scores"][g][2] for g in written)   # needs a manual grade
    assert all(graded["blank"]["scores"][g][0] == 0 for g in written)


def test_the_same_submission_gets_the_same_points(graded):
    root, before = graded["alternative"]["root"], graded["alternative"]["scores"]
    nbgrader(root, "autograde", "03_laplace_beltrami", "--student=alternative", "--force")
    from nbgrader.api import Gradebook

    with Gradebook(f"sqlite:///{root / 'gradebook.db'}") as gb:
        nb = gb.find_submission("03_laplace_beltrami", "alternative").notebooks[0]
        again = {g.name: g.score for g in nb.grades}
    assert again == {g: before[g][0] for g in again}


def test_feedback_is_generated(graded):
    root = graded["wrong"]["root"]
    nbgrader(root, "generate_feedback", "01_shapes", "--student=wrong")
    html = next((root / "feedback" / "wrong" / "01_shapes").glob("*.html")).read_text(encoding="utf-8")
    assert "01-stretch" in html


def test_the_exchange_round_trip(course, tmp_path):
    """release_assignment -> fetch_assignment -> submit -> collect -> autograde, for one assignment."""
    exchange, home = tmp_path / "exchange", tmp_path / "home"
    exchange.mkdir()
    home.mkdir()
    exchange.chmod(0o777)
    flags = [f"--Exchange.root={exchange}", "--CourseDirectory.course_id=lbo-notebooks"]
    nbgrader(course, "release_assignment", "00_start_here", *flags)
    nbgrader(home, "fetch_assignment", "00_start_here", *flags)
    assert (home / "00_start_here" / "00_start_here.ipynb").exists()
    nbgrader(home, "submit", "00_start_here", *flags)
    nbgrader(course, "collect", "00_start_here", *flags)
    collected = [p.name for p in (course / "submitted").iterdir()]
    assert collected, "nothing collected"
    nbgrader(course, "autograde", "00_start_here", f"--student={collected[0]}")
