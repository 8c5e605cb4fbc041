"""Real-browser test of the student edition: a student runs it, answers, and reads the feedback.

Skipped unless ``LBO_BROWSER_TESTS=1``; run with ``./make.sh browser`` (or
``LBO_BROWSER_TESTS=1 .venv/bin/python -m pytest -p no:dash tests/browser/test_student_edition.py -v``).
It reuses the machinery of ``test_jupyterlab.py`` (the JupyterLab server, the offline headless
Chromium, Run All Cells from the menu bar) and needs nbgrader (the ``[test]`` extra), which
makes the edition.

What happens: the student edition is built with ``scripts/student_edition.py`` into a temporary
copy of the repository's layout (``<tmp>/repo/build/student``; the repository's own
``build/student/``, where a student may be working, is never touched), JupyterLab is started on it,
every notebook of the series is run unanswered (no error, every check "not attempted"), and for
each of notebooks 01, 03 and 04 a fresh page

1. runs every cell (*Run > Run All Cells*), unanswered: no cell errors, every check cell shows
   exactly one feedback line and each says "not attempted";
2. answers one exercise wrong, as a student would: clicks into its answer cell, replaces the
   ``...`` placeholder by typed code, runs it and its check (Shift+Enter twice); the
   page must show "wrong" with the hint aimed at that mistake, and no solution;
3. answers another exercise right the same way: the page must show "✔ correct";
4. in 03, asks for a solution on purpose (``exercises.solution(...)`` in a new cell): the
   instructor's solution is shown.

Screenshots of each check's feedback go to ``artifacts/browser/student/<notebook>/``.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

if os.environ.get("LBO_BROWSER_TESTS") != "1":
    pytest.skip("browser tests are opt-in: set LBO_BROWSER_TESTS=1", allow_module_level=True)

from tests.browser.test_jupyterlab import (  # noqa: E402  (the same server, browser and page machinery)
    ARTIFACTS, REPO, RUN_TIMEOUT, Lab, Offline, Page, _kernel_ready, _open, _run_all, _wait_until_done, browser,
    check_glossary_opens, offline,
)

__all__ = ["browser", "offline"]  # fixtures used here, imported from test_jupyterlab.py

# Per notebook: one exercise answered wrong (the words its hint must contain) and one answered right.
# Answers are one line each: typed text goes in as it is (no bracket auto-closing, see _type_answer).
STUDENT_ANSWERS = {
    "01_shapes": {
        "wrong": ("01-edges", "n_edges = 3 * dog.n_faces", ["factor of two"]),
        "right": ("01-area", "area_factor = 1.6 ** 2"),
    },
    "03_laplace_beltrami": {
        "wrong": ("03-convergence", "error_drop = 2", ["first order"]),
        "right": ("03-scaling", "eigenvalue_factor = 1 / 4"),
    },
    "04_your_own_data": {
        "wrong": ("04-cloud", "relative_error = cloud_spectrum.values[9] / (9 * 10) - 1", ["is not ℓ", "2ℓ+1"]),
        "right": ("04-operator", 'operator = {"holes": "cotan", "two_pieces": "cotan", "fins": "robust", "pinched": "robust"}'),
    },
}
REVEAL = ("04_your_own_data", "04-repair", "unreferenced_vertices")   # notebook, exercise, a word of its solution
FEEDBACK = ".jp-OutputArea-output .lbo-feedback"


@pytest.fixture(scope="module")
def student_lab(tmp_path_factory):
    """JupyterLab on a freshly built student edition, ``<tmp>/repo/build/student``."""
    mirror = tmp_path_factory.mktemp("student") / "repo"
    mirror.mkdir()
    for entry in REPO.iterdir():   # the rest of the repository, for paths relative to the edition
        if entry.name not in {"build", ".git", "artifacts"}:
            (mirror / entry.name).symlink_to(entry)
    edition = mirror / "build" / "student"
    build = subprocess.run([sys.executable, str(REPO / "scripts" / "student_edition.py"), "--out", str(edition)],
                           capture_output=True, text=True, timeout=900)
    assert build.returncode == 0, f"student_edition.py failed:\n{build.stdout}\n{build.stderr}"
    server = Lab(edition, default_url="/lab/tree/00_start_here.ipynb")  # as ./make.sh student lab
    yield server
    server.stop()


@pytest.fixture
def student_page(offline: Offline, student_lab: Lab):
    yield offline.page
    student_lab.shutdown_kernels()


def _code_cells(page: Page):
    return page.locator(".jp-Notebook .jp-Cell.jp-CodeCell")


def _index_of_cell(page: Page, text: str) -> int:
    """The index (among code cells) of the cell whose source contains ``text``."""
    index = _code_cells(page).evaluate_all(
        "(cells, text) => cells.findIndex(c => { const e = c.querySelector('.cm-content');"
        " return e !== null && e.innerText.includes(text); })", text)
    assert index >= 0, f"no code cell contains {text!r}"
    return index


def _feedback(cell) -> list[dict]:
    return cell.locator(FEEDBACK).evaluate_all(
        "els => els.map(e => ({exercise: e.dataset.exercise, status: e.dataset.status, text: e.innerText}))")


def _type_answer(page: Page, cell, answer: str) -> None:
    """Click into the cell's editor, select everything, type the answer in its place."""
    editor = cell.locator(".cm-content")
    editor.scroll_into_view_if_needed()
    editor.click()
    page.keyboard.press("Control+A")
    # One insertion (not key by key): CodeMirror does not auto-close brackets or quotes then.
    page.keyboard.insert_text(answer)
    typed = editor.inner_text()
    assert typed.strip() == answer, f"the editor holds {typed!r}, not the typed answer {answer!r}"


def _answer_and_check(page: Page, exercise: str, answer: str, out: Path) -> dict:
    """Type ``answer`` into the exercise's answer cell, run it and its check; return the feedback shown."""
    cells = _code_cells(page)
    answer_index = _answer_cell(page, exercise)
    _type_answer(page, cells.nth(answer_index), answer)
    page.keyboard.press("Shift+Enter")          # runs the answer cell, selects the check cell
    page.keyboard.press("Shift+Enter")          # runs the check cell
    _wait_until_done(page, 300)
    check_cell = cells.nth(answer_index + 1)
    check_cell.scroll_into_view_if_needed()
    page.wait_for_timeout(300)
    cells.nth(answer_index).screenshot(path=str(out / f"{exercise}_answer.png"))
    check_cell.screenshot(path=str(out / f"{exercise}_feedback.png"))
    shown = _feedback(check_cell)
    assert len(shown) == 1 and shown[0]["exercise"] == exercise, f"{exercise}: feedback shown {shown}"
    errors = [t for t in cells.nth(answer_index).locator(".jp-OutputArea-output").all_inner_texts() + [check_cell.inner_text()]
              if "Traceback" in t or re.search(r"^\w*Error\b", t, re.M)]
    assert not errors, f"{exercise}: an error instead of feedback:\n" + "\n".join(errors)
    return shown[0]


def _answer_cell(page: Page, exercise: str) -> int:
    """The answer cell of an exercise: the code cell before the one that runs its check."""
    checks = {"01-edges": "check_edge_count(", "01-area": "check_area_factor(", "03-convergence": "check_convergence_factor(",
              "03-scaling": "check_eigenvalue_scaling(", "04-cloud": "check_cloud_eigenvalue(",
              "04-operator": "check_operator_choice(", "04-repair": "check_repair_counts("}
    return _index_of_cell(page, f"feedback = exercises.{checks[exercise]}") - 1


def _run_unanswered(page: Page, lab: Lab, stem: str, out: Path) -> None:
    """Run All on an unanswered notebook of the edition: every cell runs, no error, every check "not attempted"."""
    _open(page, lab, f"{stem}.ipynb")
    _kernel_ready(page, lab, 180)
    _run_all(page)
    prompts = _wait_until_done(page, RUN_TIMEOUT)
    page.wait_for_timeout(1000)
    page.screenshot(path=str(out / "unanswered.png"))
    builds = page.locator(".jp-CodeCell .jp-InputArea", has_text="def my_")
    if builds.count():  # issue 43: a build cell hands out its def line, docstring and `...` only
        builds.first.scroll_into_view_if_needed()
        builds.first.screenshot(path=str(out / "build_placeholder.png"))
        assert "YOUR CODE HERE" not in builds.first.inner_text()
    not_run = [i for i, p in enumerate(prompts) if not re.search(r"\[\d+\]", p)]
    assert not not_run, f"{stem}: code cells {not_run} did not run (prompts {prompts})"
    tracebacks = [t[:800] for t in page.locator(".jp-OutputArea-output").all_inner_texts() if "Traceback" in t]
    assert not tracebacks, f"{stem}: errors in the unanswered edition:\n" + "\n---\n".join(tracebacks)
    n_checks = _code_cells(page).evaluate_all(
        "cells => cells.filter(c => /feedback = exercises\\.check_/.test((c.querySelector('.cm-content') || {}).innerText || '')).length")
    shown = page.locator(FEEDBACK).evaluate_all("els => els.map(e => [e.dataset.exercise, e.dataset.status])")
    assert n_checks >= 4 and len(shown) == n_checks, f"{stem}: {n_checks} check cells, feedback shown {shown}"
    assert all(status == "not attempted" for _, status in shown), f"{stem}: unanswered checks say {shown}"
    assert "BEGIN SOLUTION" not in page.inner_text(".jp-Notebook")


def test_the_glossary_opens_from_every_notebook_of_the_edition(student_page: Page, student_lab: Lab, offline: Offline) -> None:
    """The edition's folder is JupyterLab's root: the glossary lies beside the notebooks, which link it there."""
    stems = sorted(p.stem for p in student_lab.root.glob("[0-9][0-9]_*.ipynb"))
    assert len(stems) == len(list((REPO / "notebooks").glob("[0-9][0-9]_*.ipynb"))), stems
    check_glossary_opens(student_page, student_lab, stems, ARTIFACTS / "student" / "glossary")
    assert not [f for f in offline.failed if "glossary" in f], offline.failed
    offline.check("the edition's glossary")


#: The notebooks of the series that test_student_attempts_and_reads_the_feedback does not open.
OTHER_NOTEBOOKS = sorted(p.stem for p in (REPO / "notebooks").glob("[0-9][0-9]_*.ipynb") if p.stem not in STUDENT_ANSWERS)


@pytest.mark.parametrize("stem", OTHER_NOTEBOOKS)
def test_every_other_notebook_runs_unanswered(student_page: Page, student_lab: Lab, offline: Offline, stem: str) -> None:
    out = ARTIFACTS / "student" / stem
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    _run_unanswered(student_page, student_lab, stem, out)
    assert not student_page.locator(".jp-Dialog").all_inner_texts(), f"{stem}: unexpected dialog"
    offline.check(f"student edition {stem}")


@pytest.mark.parametrize("stem", list(STUDENT_ANSWERS))
def test_student_attempts_and_reads_the_feedback(student_page: Page, student_lab: Lab, offline: Offline, stem: str) -> None:
    page = student_page
    out = ARTIFACTS / "student" / stem
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)

    # 1. The whole notebook, unanswered: it runs, and every check says "not attempted".
    _run_unanswered(page, student_lab, stem, out)

    # 2. One exercise answered wrong: "wrong", with the hint aimed at that mistake.
    exercise, answer, hint_words = STUDENT_ANSWERS[stem]["wrong"]
    wrong = _answer_and_check(page, exercise, answer, out)
    assert wrong["status"] == "wrong" and "✘ wrong" in wrong["text"], f"{exercise}: {wrong}"
    for word in hint_words:
        assert word in wrong["text"], f"{exercise}: the hint lacks {word!r}: {wrong['text']}"
    assert f'exercises.solution("{exercise}")' in wrong["text"]       # the way to a solution, on purpose

    # 3. Another one answered right: "correct".
    exercise, answer = STUDENT_ANSWERS[stem]["right"]
    right = _answer_and_check(page, exercise, answer, out)
    assert right["status"] == "correct" and "✔ correct" in right["text"], f"{exercise}: {right}"

    # 4. A solution, revealed on purpose, in a new cell below the last one run.
    if stem == REVEAL[0]:
        page.keyboard.press("Escape")
        page.keyboard.press("b")                     # a new code cell below, in edit mode
        page.keyboard.press("Enter")
        page.keyboard.insert_text(f'exercises.solution("{REVEAL[1]}")')
        page.keyboard.press("Shift+Enter")
        _wait_until_done(page, 120)
        revealed = page.locator(".jp-OutputArea-output", has_text=f"Solution of exercise {REVEAL[1]}")
        revealed.first.wait_for(state="visible", timeout=30_000)
        revealed.first.screenshot(path=str(out / "solution_revealed.png"))
        assert REVEAL[2] in revealed.first.inner_text()

    assert not page.locator(".jp-Dialog").all_inner_texts(), f"{stem}: unexpected dialog"
    offline.check(f"student edition {stem}")
