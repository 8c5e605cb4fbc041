"""The student edition of the series, made by nbgrader from the instructor edition ``notebooks/``.

    python scripts/student_edition.py                 # write build/student/ (the series)
    python scripts/student_edition.py --check         # ... then check both editions (CI)

(``./make.sh student [--check]`` runs it in the project's environment; ``./make.sh student lab``
opens JupyterLab on the edition for self-study.)

The build runs ``nbgrader generate_assignment`` on a throw-away course directory whose source is
the series in ``notebooks/`` (``00_start_here`` and the notebooks its map lists, as on the static
site; stray notebooks are left out): solution regions (``### BEGIN SOLUTION`` ... ``### END SOLUTION``) disappear,
leaving the ``...`` placeholder before them,
hidden tests (``### BEGIN HIDDEN TESTS`` ...) disappear, check cells are locked, outputs are
cleared. Notebooks without exercises pass through unchanged apart from that. Files a notebook
reads by a relative path outside its folder (``../benchmarks/...``) are copied to the same place
relative to the edition, so it runs where it is written; the glossary (and the formulas page it
links) is copied beside the notebooks, whose link to it then points there. A notebook in ``build/student/`` that
changed since it was written (a student's answers) is never overwritten: the new edition of it
is written beside it as ``NN_name.new.ipynb``.

``--check`` then verifies, for the notebooks that have exercises (nbgrader grade cells):

(a) the student edition runs top to bottom without an error, unanswered, and every check in it
    reports "not attempted" (read from the feedback's own MIME type in the outputs);
(b) with the instructor's answers put back into the student edition's answer cells (matched by
    grade id), ``nbgrader autograde`` gives full marks on every autograded check (written answers
    wait for the lecturer's manual grade).

Both run at once (a subprocess each way), so the check costs about one execution of those
notebooks in wall time on two cores. See docs/exercises.md.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOKS = ROOT / "notebooks"
ASSIGNMENT = "series"
STUDENT = "self-check"
MIME_TYPE = "application/vnd.lbo-notebooks.feedback+json"  # lbo_notebooks.exercises.MIME_TYPE
# Nothing in place of a solution: the `...` before it (a value, or a function's body) is the one
# placeholder a student replaces, and the edition runs unanswered (nbgrader's default stub raises).
CODE_STUB = ""
MANIFEST = ".edition.json"  # digests of the notebooks as written, to tell a student's changes
RELATIVE_FILE = re.compile(r"""\.\./[\w./-]+""")

CONFIG = """\
c = get_config()
c.CourseDirectory.root = {root!r}
c.CourseDirectory.db_url = {db_url!r}
c.ClearSolutions.code_stub = {{"python": {stub!r}}}
c.ClearSolutions.text_stub = "YOUR ANSWER HERE"
c.Execute.timeout = 600
c.Autograde.create_student = True
# Kernels on local IPC sockets, not TCP: ipykernel warns at each start that TCP is unencrypted.
c.KernelManager.transport = "ipc"
c.KernelManager.ip = {sockets!r}
"""


def log(message: str) -> None:
    print(f"[student edition] {message}", file=sys.stderr, flush=True)


def read(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


def source(cell: dict) -> str:
    return "".join(cell["source"]) if isinstance(cell["source"], list) else cell["source"]


def nbgrader_meta(cell: dict) -> dict:
    return cell.get("metadata", {}).get("nbgrader", {})


def has_exercises(path: Path) -> bool:
    return any(nbgrader_meta(c).get("grade") for c in read(path)["cells"])


def nbgrader(root: Path, *args: str) -> subprocess.Popen:
    # nbgrader runs the `alembic` command of its environment: put that environment's bin/ first on PATH
    # (it is not there when the venv's python is called by its path).
    env = dict(os.environ, PATH=os.pathsep.join([str(Path(sys.executable).parent), os.environ.get("PATH", "")]))
    # nbgrader's gradebook code warns (SAWarning) at every autograde under SQLAlchemy 2; nothing to act on.
    env["PYTHONWARNINGS"] = ",".join(filter(None, [os.environ.get("PYTHONWARNINGS"), "ignore:::nbgrader.api"]))
    return subprocess.Popen([sys.executable, "-m", "nbgrader", *args], cwd=root, env=env)


SERIES_NAME = re.compile(r"^\d\d_\w+$")
MAP_LINK = re.compile(r"^\s*\|.*\]\((\d\d_\w+)\.ipynb\)", re.MULTILINE)


def series(folder: Path) -> list[Path]:
    """The notebooks of the series in ``folder``: ``00_start_here`` and the ``NN_name`` notebooks its
    map of the series links to (as the static site, scripts/build_site.py); without ``00_start_here``,
    every ``NN_name.ipynb``. A lecturer's scratch notebook, a ``-Copy1`` or a ``.new.ipynb`` never
    goes into the student edition."""
    start = folder / "00_start_here.ipynb"
    if not start.exists():
        return sorted(p for p in folder.glob("*.ipynb") if SERIES_NAME.match(p.stem))
    text = "\n".join(source(c) for c in read(start)["cells"] if c["cell_type"] == "markdown")
    listed = [folder / f"{stem}.ipynb" for stem in MAP_LINK.findall(text)]
    return [start] + [p for p in listed if p.exists() and p != start]


#: The docs pages an edition carries beside its notebooks: the glossary every notebook links, and
#: the formulas page the glossary links (``](maths.md)``, beside it as in docs/).
PAGES_BESIDE = ("glossary.md", "maths.md")
GLOSSARY_LINK = "](../docs/glossary.md)"


def copy_for_edition(nb: Path, target: Path) -> None:
    """Copy notebook ``nb`` to ``target`` with its glossary link pointing beside it, and put the
    glossary (and the page it links) beside it. An edition's folder is served or handed out alone
    (JupyterLab's root, an nbgrader assignment), where ``../docs/`` does not exist."""
    text = nb.read_text(encoding="utf-8")
    target.write_text(text.replace(GLOSSARY_LINK, "](glossary.md)"), encoding="utf-8")
    shutil.copystat(nb, target)
    copy_pages_beside(target.parent)


def copy_pages_beside(folder: Path) -> None:
    for name in PAGES_BESIDE:
        shutil.copy2(ROOT / "docs" / name, folder / name)


def course(root: Path) -> Path:
    """A course directory whose assignment's source is a copy of the series in notebooks/."""
    source_dir = root / "source" / ASSIGNMENT
    source_dir.mkdir(parents=True)
    for nb in series(NOTEBOOKS):
        copy_for_edition(nb, source_dir / nb.name)
    (root / "nbgrader_config.py").write_text(CONFIG.format(root=str(root), db_url=f"sqlite:///{root / 'gradebook.db'}",
                                                           stub=CODE_STUB, sockets=str(root / "kernel")), encoding="utf-8")
    return source_dir


def copy_relative_files(folder: Path) -> None:
    """Copy the files the notebooks in ``folder`` read by a path outside it (``../benchmarks/...``)."""
    for nb in sorted(folder.glob("*.ipynb")):
        for rel in sorted(set(RELATIVE_FILE.findall("\n".join(source(c) for c in read(nb)["cells"])))):
            rel = rel.rstrip(".\\")
            if (NOTEBOOKS / rel).is_file():
                target = (folder / rel).resolve()
                target.parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(NOTEBOOKS / rel, target)


def build(root: Path) -> Path:
    """Make the student edition of every notebook with nbgrader; return the folder it is in."""
    course(root)
    if nbgrader(root, "generate_assignment", ASSIGNMENT, "--force", "--log-level=WARN").wait() != 0:
        raise SystemExit("nbgrader generate_assignment failed (its messages are above)")
    release = root / "release" / ASSIGNMENT
    leaked = [p.name for p in release.glob("*.ipynb") if "BEGIN SOLUTION" in p.read_text(encoding="utf-8")]
    if leaked:
        raise SystemExit(f"solution markers left in the student edition of {leaked}")
    copy_relative_files(release)
    return release


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def publish(release: Path, out: Path) -> None:
    """Copy the edition to ``out``. A notebook there that changed since it was written (a student's
    answers, or outputs saved by JupyterLab) is kept, never overwritten: its new version goes beside it."""
    out.mkdir(parents=True, exist_ok=True)
    manifest_path = out / MANIFEST
    manifest = json.loads(manifest_path.read_text()) if manifest_path.exists() else {}
    for nb in sorted(release.glob("*.ipynb")):
        target = out / nb.name
        if target.exists() and manifest_path.exists() and manifest.get(nb.name) != digest(target):
            target = out / f"{nb.stem}.new.ipynb"
            log(f"kept {nb.name}, which changed since it was written (your work); the new edition is {target.name}")
        else:
            manifest[nb.name] = digest(nb)
        shutil.copy2(nb, target)
    manifest_path.write_text(json.dumps(manifest, indent=1) + "\n", encoding="utf-8")
    copy_relative_files(out)
    copy_pages_beside(out)
    shown = out.relative_to(ROOT) if out.is_relative_to(ROOT) else out
    log(f"wrote the student edition of {len(manifest)} notebooks to {shown}/")


def answered(student: Path, instructor: Path) -> dict:
    """The student edition with the instructor's answer cells put back (matched by grade id)."""
    answers = {nbgrader_meta(c)["grade_id"]: source(c) for c in read(instructor)["cells"] if nbgrader_meta(c).get("solution")}
    nb = read(student)
    for cell in nb["cells"]:
        meta = nbgrader_meta(cell)
        if meta.get("solution"):
            cell["source"] = answers[meta["grade_id"]]
    return nb


def execute_unanswered(paths: list[Path], results: Path) -> subprocess.Popen:
    """Run the unanswered notebooks in a subprocess (nbclient); it writes the executed copies to ``results``."""
    code = (
        "import sys, nbformat\n"
        "from nbclient import NotebookClient\n"
        "from traitlets.config import Config\n"
        "# Kernels on local IPC sockets (no TCP: no 'unencrypted' warning), started and shut down by the client.\n"
        "ipc = Config({'KernelManager': {'transport': 'ipc', 'ip': sys.argv[1]}})\n"
        "for path, target in zip(sys.argv[2::2], sys.argv[3::2]):\n"
        "    nb = nbformat.read(path, as_version=4)\n"
        "    NotebookClient(nb, config=ipc, timeout=600, kernel_name='python3', resources={'metadata': {'path': str(__import__('pathlib').Path(path).parent)}}).execute()\n"
        "    nbformat.write(nb, target)\n"
    )
    results.mkdir(parents=True, exist_ok=True)
    args = [str(results / "kernel")] + [a for p in paths for a in (str(p), str(results / p.name))]
    return subprocess.Popen([sys.executable, "-c", code, *args])


def feedback_statuses(nb: dict) -> list[tuple[str, str]]:
    found = []
    for cell in nb["cells"]:
        for output in cell.get("outputs", []):
            data = output.get("data", {}).get(MIME_TYPE)
            if data:
                found.append((data["exercise"], data["status"]))
    return found


def check(release: Path, root: Path) -> bool:
    """(a) unanswered run: clean, every check "not attempted"; (b) autograde of the instructor's answers: full marks."""
    graded = [p for p in sorted(release.glob("*.ipynb")) if has_exercises(p)]
    if not graded:
        log("no notebook has exercises yet: nothing to check")
        return True
    names = [p.name for p in graded]
    log(f"checking {', '.join(names)}: unanswered run and autograde, side by side")
    submitted = root / "submitted" / STUDENT / ASSIGNMENT
    submitted.mkdir(parents=True)
    for p in graded:
        (submitted / p.name).write_text(json.dumps(answered(p, NOTEBOOKS / p.name), indent=1), encoding="utf-8")
    start = time.monotonic()
    grader = nbgrader(root, "autograde", ASSIGNMENT, "--force", f"--student={STUDENT}", "--log-level=ERROR")
    runner = execute_unanswered(graded, root / "executed")
    ok = True
    if runner.wait() != 0:
        log("(a) FAILED: the unanswered student edition raised an error (the traceback is above)")
        ok = False
    else:
        for p in graded:
            nb = read(root / "executed" / p.name)
            statuses = feedback_statuses(nb)
            n_checks = sum(1 for c in nb["cells"] if nbgrader_meta(c).get("grade") and "exercises.check_" in source(c))
            bad = [(e, s) for e, s in statuses if s != "not attempted"]
            if len(statuses) != n_checks or bad or not statuses:
                log(f"(a) FAILED in {p.name}: {n_checks} check cells, feedback {statuses}")
                ok = False
            else:
                log(f"(a) {p.name}: ran clean unanswered; all {n_checks} checks report 'not attempted'")
    if grader.wait() != 0:
        log("(b) FAILED: nbgrader autograde exited with an error")
        return False
    from nbgrader.api import Gradebook

    with Gradebook(f"sqlite:///{root / 'gradebook.db'}") as gb:
        submission = gb.find_submission(ASSIGNMENT, STUDENT)
        for nb in submission.notebooks:
            if nb.name + ".ipynb" not in names:
                continue
            # Written answers (NN-name-explain) wait for the lecturer's grade: not the autograder's to give.
            written = [g for g in nb.grades if g.needs_manual_grade]
            auto = [g for g in nb.grades if not g.needs_manual_grade]
            failed = [g.name for g in auto if g.score != g.max_score]
            failed += [g.name for g in written if not g.name.endswith("-explain")]  # a code check left to a human
            auto_max = sum(g.max_score for g in auto)
            full = auto_max > 0 and not failed
            waiting = f"; {sum(g.max_score for g in written):g} points of written answers await a manual grade" if written else ""
            log(f"(b) {nb.name}: autograde {sum(g.score for g in auto):g} / {auto_max:g} points{waiting}"
                + ("" if full else f"; lost in {failed}"))
            ok &= full
    log(f"checks done in {time.monotonic() - start:.0f} s")
    return ok


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=ROOT / "build" / "student", help="where to write the edition")
    parser.add_argument("--check", action="store_true", help="also run (a) unanswered and (b) autograded, see above")
    parser.add_argument("--keep", action="store_true", help="keep the nbgrader course directory (printed)")
    args = parser.parse_args()
    root = Path(tempfile.mkdtemp(prefix="lbo-course-"))
    try:
        release = build(root)
        publish(release, args.out.resolve())
        ok = check(release, root) if args.check else True
    finally:
        if args.keep:
            log(f"course directory kept: {root}")
        else:
            shutil.rmtree(root, ignore_errors=True)
    if args.check:
        print("student edition: " + ("1 passed, 0 failed" if ok else "0 passed, 1 failed"))
    return 0 if ok else 1


if __name__ == "__main__":
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    os.environ.setdefault("MKL_NUM_THREADS", "1")
    sys.exit(main())
