"""Every notebook is saved clean and follows the series' shape (reads the .ipynb JSON only; fast).

Checked for each ``notebooks/*.ipynb``: valid nbformat; no outputs, execution counts or saved
widget state; the first cell is a markdown title ``# NN · ...`` (NN = the file's number) followed
by "What you will learn" and "What you need"; the last section is "Exercises"; the solutions come
after it in code cells hidden with ``{"jupyter": {"source_hidden": true}}``, or, in a notebook marked
for nbgrader (docs/exercises.md), every exercise is an answer cell whose solution lies between
``### BEGIN SOLUTION`` and ``### END SOLUTION`` followed by its locked check cell, with at least
two exercises inside the body and at least one in the Exercises section; cells that display a
slider widget carry the cell tag ``nbval-ignore-output`` (a widget's repr changes from run to run;
nbval's tags keep such markers out of the reader's code);
verification cells (only ``assert``s and what they need) are tagged ``hide-input`` and every cell so
tagged is collapsed (``scripts/tag_verification_cells.py`` does both).
"""

from __future__ import annotations

import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

NOTEBOOKS = sorted((Path(__file__).resolve().parent.parent / "notebooks").glob("*.ipynb"))
HEADING = re.compile(r"^(#{1,2})\s+(.*)$", re.MULTILINE)
WIDGET_FACTORIES = ("mesh_slider(", "widgets.", "interactive(", "interact(")


def _load_script(name: str):
    path = Path(__file__).resolve().parent.parent / "scripts" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


tagging = _load_script("tag_verification_cells")


def _source(cell) -> str:
    return cell.source if isinstance(cell.source, str) else "".join(cell.source)


@pytest.fixture(params=NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def notebook(request):
    return request.param, nbformat.read(request.param, as_version=4)


def test_there_are_notebooks():
    assert NOTEBOOKS, "no notebooks found in notebooks/"


def test_valid_nbformat(notebook):
    path, nb = notebook
    nbformat.validate(nb)
    assert nb.metadata.get("kernelspec", {}).get("name") == "python3", (
        f"{path.name}: set the kernelspec to python3 so it runs in the project's kernel")


def test_saved_without_outputs(notebook):
    path, nb = notebook
    dirty = [i for i, c in enumerate(nb.cells)
             if c.cell_type == "code" and (c.outputs or c.execution_count is not None)]
    assert not dirty, f"{path.name}: cells {dirty} have outputs or execution counts; clear them before saving"
    assert "widgets" not in nb.metadata, f"{path.name}: saved widget state in the metadata; clear it before saving"


def test_opens_with_what_you_will_learn_and_need(notebook):
    path, nb = notebook
    first = nb.cells[0]
    assert first.cell_type == "markdown", f"{path.name}: the first cell must be markdown (title and aims)"
    text = _source(first)
    title = text.lstrip().splitlines()[0]
    number = path.name.split("_", 1)[0]
    assert re.match(rf"#\s+{re.escape(number)}\b", title), (
        f"{path.name}: the first line should be a title '# {number} · ...', found {title!r}")
    lower = text.lower()
    assert "what you will learn" in lower, f"{path.name}: the first cell must say what you will learn"
    assert "what you need" in lower, f"{path.name}: the first cell must say what you need"


def test_ends_with_exercises_and_hidden_solutions(notebook):
    path, nb = notebook
    headings = [(i, m.group(2)) for i, c in enumerate(nb.cells) if c.cell_type == "markdown"
                for m in HEADING.finditer(_source(c)) if not m.group(2).startswith("#")]
    assert headings, f"{path.name}: no section headings"
    last_index, last_heading = headings[-1]
    assert "exercise" in last_heading.lower(), (
        f"{path.name}: the last section should be 'Exercises', found {last_heading!r}")
    after = nb.cells[last_index + 1:]
    if any("nbgrader" in c.metadata for c in nb.cells):  # the course edition's marking (docs/exercises.md)
        _check_marked_exercises(path, nb, last_index)
        return
    code_after = [c for c in after if c.cell_type == "code"]
    solution_link = re.search(r"\]\(([^)]*solution[^)]*)\)", _source(nb.cells[last_index]), re.IGNORECASE)
    if solution_link:  # solutions in a separate file: it must exist
        assert (path.parent / solution_link.group(1)).exists(), f"{path.name}: {solution_link.group(1)} is missing"
    else:
        assert code_after, f"{path.name}: add the solutions after the exercises (a hidden code cell)"
    shown = [nb.cells.index(c) for c in code_after if not c.metadata.get("jupyter", {}).get("source_hidden")]
    assert not shown, (f"{path.name}: solution cells {shown} are not collapsed; set their metadata to "
                       '{"jupyter": {"source_hidden": true}}')


def _check_marked_exercises(path, nb, exercises_index):
    answers = {i: c.metadata.nbgrader.grade_id for i, c in enumerate(nb.cells)
               if c.metadata.get("nbgrader", {}).get("solution")}
    checks = {c.metadata.nbgrader.grade_id for c in nb.cells if c.metadata.get("nbgrader", {}).get("grade")}
    for i, grade_id in list(answers.items()):
        text = _source(nb.cells[i])
        if grade_id.endswith("-explain"):  # a written answer, graded by a person (docs/exercises.md)
            meta = nb.cells[i].metadata.nbgrader
            assert nb.cells[i].cell_type == "markdown" and meta.get("grade") and meta.get("points", 0) > 0, (
                f"{path.name}: {grade_id} should be a manually graded Markdown answer cell with points")
            assert "**Rubric" in text and grade_id[:-len("explain")] + "check" in checks, (
                f"{path.name}: {grade_id} needs the model answer and a **Rubric** line, after its exercise's check")
            del answers[i]
            continue
        assert "BEGIN SOLUTION" in text and "END SOLUTION" in text, (
            f"{path.name}: answer cell {grade_id} has no ### BEGIN SOLUTION / ### END SOLUTION region")
        assert grade_id.endswith("-answer") and grade_id[:-len("answer")] + "check" in checks, (
            f"{path.name}: answer cell {grade_id} needs a check cell with grade id ...-check")
    inside = sum(i < exercises_index for i in answers)
    assert inside >= 2, f"{path.name}: {inside} marked exercises inside the body; put at least two where the ideas are taught"
    assert len(answers) > inside, f"{path.name}: the Exercises section has no marked exercise"


def test_widget_cells_ignore_their_output(notebook):
    path, nb = notebook
    bad = []
    for i, c in enumerate(nb.cells):
        if c.cell_type != "code":
            continue
        text = _source(c)
        lines = [ln for ln in text.strip().splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
        displays_a_widget = (any(f in text for f in WIDGET_FACTORIES) and lines
                             and re.fullmatch(r"[A-Za-z_][A-Za-z_0-9.]*", lines[-1].strip()))
        if displays_a_widget and "nbval-ignore-output" not in c.metadata.get("tags", []):
            bad.append(i)
    assert not bad, f"{path.name}: cells {bad} display a widget; give them the cell tag 'nbval-ignore-output'"


def test_no_test_markers_in_the_readers_code(notebook):
    path, nb = notebook
    marked = [i for i, c in enumerate(nb.cells) if c.cell_type == "code" and "NBVAL_" in _source(c)]
    assert not marked, f"{path.name}: cells {marked} show an NBVAL_ comment; use nbval's cell tags instead"


def test_verification_cells_are_tagged_and_collapsed(notebook):
    """Cells that only check the text's claims are out of the reader's way: tagged ``hide-input``
    (Jupyter Book, myst-nb) and collapsed in JupyterLab, with their outputs shown."""
    path, nb = notebook
    cells = [dict(c) for c in nb.cells]
    untagged = [i for i, c in enumerate(cells) if tagging.is_verification(c) and not tagging.is_tagged(c)]
    open_ = [i for i, c in enumerate(cells) if c["cell_type"] == "code" and tagging.is_tagged(c)
             and not tagging.is_collapsed(c)]
    fix = f"run: python3 scripts/tag_verification_cells.py notebooks/{path.name}"
    assert not untagged, f"{path.name}: cells {untagged} only verify claims but are not tagged 'hide-input'; {fix}"
    assert not open_, f"{path.name}: cells {open_} are tagged 'hide-input' but not collapsed; {fix}"


def test_the_tagging_script_is_idempotent_and_keeps_outputs_visible():
    import copy

    verification = {"cell_type": "code", "metadata": {"jupyter": {"outputs_hidden": True}}, "outputs": [],
                    "execution_count": None, "source": ["x = 2\n", "assert x > 1  # the claim\n"]}
    lesson = {"cell_type": "code", "metadata": {}, "outputs": [], "execution_count": None,
              "source": "print(x)\nassert x > 1"}
    tagged = {"cell_type": "code", "metadata": {"tags": ["hide-input"]}, "outputs": [], "execution_count": None,
              "source": "plot(x)"}
    nb = {"cells": [verification, lesson, tagged, {"cell_type": "markdown", "metadata": {}, "source": "assert"}]}
    before = copy.deepcopy(nb)
    changes = tagging.tag_and_collapse(nb)
    assert changes == ["cell 0: tagged hide-input", "cell 0: input collapsed", "cell 2: input collapsed"]
    assert nb["cells"][0]["metadata"] == {"tags": ["hide-input"], "jupyter": {"source_hidden": True}}
    assert nb["cells"][1] == before["cells"][1] and nb["cells"][3] == before["cells"][3]
    assert nb["cells"][2]["metadata"]["jupyter"] == {"source_hidden": True}
    again = copy.deepcopy(nb)
    assert tagging.tag_and_collapse(again) == [] and again == nb
    # The git clean filter keeps the collapsed state (it is part of the course, not of a run).
    strip = _load_script("strip_notebook")
    assert strip.strip(nb)["cells"][0]["metadata"] == {"tags": ["hide-input"], "jupyter": {"source_hidden": True}}


# --- a notebook is one class session (issue 29) ---------------------------------------------------

PROSE_WORD_LIMIT = 1600  # about what a 75–90-minute session can read, discuss and run
TIME_ESTIMATE = re.compile(r"^\*Time: about (\d+) minutes in class[^*]*\*", re.MULTILINE)
FORMULA = re.compile(r"\$\$.+?\$\$|\$[^$\n]+\$", re.DOTALL)
TIME_LINE = re.compile(r"^\*Time: [^*\n]*\*", re.MULTILINE)  # the header's times: read at a glance, not prose
SELF_STUDY = re.compile(r"^\*Time: about \d+ minutes in class[^*,]*, about (\d+) on your own\*", re.MULTILINE)


def prose_words(nb) -> int:
    """Words of the markdown cells a student reads, each ``$…$`` or ``$$…$$`` formula counted as one
    word (a written answer's model answer and rubric are the lecturer's: the student edition has
    *YOUR ANSWER HERE* in their place)."""
    return sum(len(FORMULA.sub("formula", TIME_LINE.sub("", _source(c))).split()) for c in nb.cells
               if c.cell_type == "markdown" and not c.metadata.get("nbgrader", {}).get("solution"))


def test_prose_words_counts_a_formula_as_one_word():
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell("The bound $a \\le b / c$ holds: $$x + y$$"),
                                         nbformat.v4.new_code_cell("not prose at all")])
    assert prose_words(nb) == 5
    written = nbformat.v4.new_markdown_cell("**Model answer.** Lecturer only.", metadata={"nbgrader": {"solution": True}})
    nb.cells.append(written)
    assert prose_words(nb) == 5


def test_prose_fits_one_class_session(notebook):
    path, nb = notebook
    words = prose_words(nb)
    assert words <= PROSE_WORD_LIMIT, (
        f"{path.name}: {words} words of prose, more than one session's {PROSE_WORD_LIMIT}; split the notebook "
        "or move reference material to docs/maths.md")


def test_header_gives_a_time_estimate(notebook):
    path, nb = notebook
    found = TIME_ESTIMATE.search(_source(nb.cells[0]))
    assert found, f"{path.name}: put '*Time: about N minutes in class*' under the title"
    minutes = int(found.group(1))
    assert 30 <= minutes <= 180, f"{path.name}: a notebook should fit one or two 90-minute sessions"
    if minutes > 90:
        assert "(two sessions)" in _source(nb.cells[0]), f"{path.name}: {minutes} minutes: say '(two sessions)'"


def test_stated_time_is_at_least_the_estimate(notebook):
    """Issue 39: a header's minutes are at least the lower-bound estimate of scripts/session_minutes.py
    (prose at 120 words/min, code at 20 lines/min, a fixed time per exercise by kind)."""
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "scripts"))
    from session_minutes import estimate

    path, nb = notebook
    stated, est = int(TIME_ESTIMATE.search(_source(nb.cells[0])).group(1)), estimate(nb)
    assert stated >= est["minutes"], (f"{path.name}: states {stated} minutes, the estimate is {est['minutes']} "
                                      f"({est['words']} words, {est['lines']} code lines, {est['exercises']}); "
                                      "state at least that, or split the notebook")


def test_header_gives_a_self_study_time(notebook):
    """Issue 43: a reader alone learns how long a notebook takes them: at least the model's
    self-study time (scripts/session_minutes.self_study_minutes), never less than the class time."""
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "scripts"))
    from session_minutes import self_study_minutes

    path, nb = notebook
    found = SELF_STUDY.search(_source(nb.cells[0]))
    assert found, f"{path.name}: say '*Time: about N minutes in class, about M on your own*' under the title"
    alone, in_class = int(found.group(1)), int(TIME_ESTIMATE.search(_source(nb.cells[0])).group(1))
    assert alone >= max(self_study_minutes(nb), in_class), (
        f"{path.name}: states {alone} minutes on one's own; the model gives {self_study_minutes(nb)}")


def test_readme_states_the_series_self_study_total():
    notebooks = sorted((Path(__file__).resolve().parent.parent / "notebooks").glob("[01][0-9]_*.ipynb"))
    total = sum(int(SELF_STUDY.search(_source(nbformat.read(p, as_version=4).cells[0])).group(1)) for p in notebooks)
    readme = (Path(__file__).resolve().parent.parent / "README.md").read_text(encoding="utf-8")
    stated = re.search(r"studied alone: about (\d+) hours", readme)
    assert stated and int(stated.group(1)) == round(total / 60), f"README: the series alone is {total / 60:.1f} hours"


# --- code cells read without horizontal scrolling (issue 29) --------------------------------------

CODE_LINE_LIMIT = 100  # fits a 1400-pixel JupyterLab window with the file browser open


def test_code_lines_fit_the_window(notebook):
    path, nb = notebook
    long = [(i, len(line)) for i, c in enumerate(nb.cells) if c.cell_type == "code"
            for line in _source(c).splitlines() if len(line) > CODE_LINE_LIMIT]
    assert not long, (f"{path.name}: (cell, length) of lines over {CODE_LINE_LIMIT} characters: {long}; "
                      "run `ruff format notebooks` and split long strings and comments")


def test_code_cells_are_formatted_by_ruff():
    ruff = shutil.which("ruff") or str(Path(sys.executable).with_name("ruff"))
    if not Path(ruff).exists():
        pytest.skip("ruff is not installed (it is in the [test] extra)")
    root = Path(__file__).resolve().parent.parent
    result = subprocess.run([ruff, "format", "--check", "--diff", "notebooks"], cwd=root, capture_output=True, text=True)
    assert result.returncode == 0, f"code cells not formatted; run `ruff format notebooks`:\n{result.stdout[-3000:]}"


def test_header_links_the_glossary(notebook):
    path, nb = notebook
    assert "](../docs/glossary.md)" in _source(nb.cells[0]), (
        f"{path.name}: link the glossary from the first cell: [glossary](../docs/glossary.md)")


def test_eigenfunctions_are_written_as_the_paper_writes_them(notebook):
    """The paper writes the eigenfunctions \\phi_i; a series that mixes \\phi and \\varphi (issue 40)
    makes a reader wonder whether they are two things."""
    path, nb = notebook
    assert not [i for i, c in enumerate(nb.cells) if "\\varphi" in _source(c)], f"{path.name}: write \\phi, not \\varphi"


def test_ends_with_a_three_question_recap(notebook):
    path, nb = notebook
    if path.name.startswith("00_"):
        pytest.skip("00 is the map of the series, not a lesson")
    recaps = [c for c in nb.cells if "recap" in c.metadata.get("nbgrader", {}).get("grade_id", "")]
    assert recaps, f"{path.name}: end with a self-checked recap (exercises.recap, docs/exercises.md)"
