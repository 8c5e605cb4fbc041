"""The solutions booklet for lecturers: every exercise with its points, question, solution and rubric (``./make.sh booklet``).

::

    python scripts/booklet.py                                 # every notebook -> build/booklet/index.html
    python scripts/booklet.py notebooks/05_optimality_theorem.ipynb --out /tmp/booklet
    python scripts/booklet.py --sync-plan                     # docs/lecturers/plan.md's minutes from the notebooks

One HTML page per notebook and an index, read from the instructor edition in ``notebooks/`` (never
changed). An exercise is an nbgrader answer cell ``NN-name-answer``; its written part, if any, the
Markdown cell ``NN-name-explain``. For each the booklet gives

- its id, its kind (the grader's, ``lbo_notebooks/exercises/grading``; ``written`` for an
  explanation) and its points (the nbgrader metadata of its check cell / written cell);
- the question: the prompt ``**Exercise NN-name** ...`` above the answer cell;
- the instructor's solution: the code between ``### BEGIN SOLUTION`` and ``### END SOLUTION``, with
  comments that a formatter wrapped mid-sentence joined again (:func:`reflow_comments`), and the
  visible check it is run through (hidden tests left out);
- for a written exercise, the model answer and the rubric.

Formulas are typeset by MathJax 2, copied into ``<out>/_static/mathjax`` (the site's copy,
``docs/conf.py``); the pages load nothing from the network.
"""

from __future__ import annotations

import argparse
import html
import re
import sys
import textwrap
from dataclasses import dataclass
from pathlib import Path

import nbformat

sys.path.insert(0, str(Path(__file__).resolve().parent))
import slides  # noqa: E402  (scripts/slides.py: the shared MathJax copy and the series' order)

REPO = slides.REPO
PLAN = REPO / "docs" / "lecturers" / "plan.md"

_SOLUTION = re.compile(r"^[ \t]*#+\s*BEGIN SOLUTION[^\n]*\n(.*?)^[ \t]*#+\s*END SOLUTION", re.M | re.S)
_HIDDEN_TESTS = re.compile(r"^[ \t]*#+\s*BEGIN HIDDEN TESTS.*?^[ \t]*#+\s*END HIDDEN TESTS[^\n]*\n?", re.M | re.S)
_MINUTES = re.compile(r"\*Time: about (\d+) minutes")


@dataclass
class Exercise:
    id: str           # "03-kernel" (the written part: "03-kernel-explain")
    kind: str
    points: int | None
    question: str     # markdown
    solution: str     # code, or the model answer (markdown) of a written exercise
    check: str = ""   # the visible check call
    rubric: str = ""  # markdown, written exercises only
    skeleton: str = ""  # what the student edition shows in the answer cell


def reflow_comments(code: str) -> str:
    """Join comment lines that a code formatter wrapped in the middle of a sentence.

    A full-line comment continues the one above it (same indentation, also a full-line comment)
    when that one does not end a sentence (``.``, ``!``, ``?``) and it does not start with a capital.

    >>> print(reflow_comments("x = 1\\n# the outer side stretches by r theta / L, for a\\n# fixed\\n# tube radius.\\n# New one."))
    x = 1
    # the outer side stretches by r theta / L, for a fixed tube radius.
    # New one.
    >>> print(reflow_comments("# Step 1\\n# Step 2"))
    # Step 1
    # Step 2
    """
    out: list[str] = []
    for line in code.splitlines():
        match = re.match(r"^([ \t]*)#\s?(.*?)\s*$", line)
        if match and out:
            previous = re.match(r"^([ \t]*)#\s?(.*?)\s*$", out[-1])
            text = match.group(2)
            if (previous and previous.group(1) == match.group(1) and previous.group(2)
                    and not previous.group(2).endswith((".", "!", "?")) and text and not text[0].isupper()):
                out[-1] = f"{previous.group(1)}# {previous.group(2)} {text}"
                continue
        out.append(line.rstrip())
    return "\n".join(out)


def _grader(cell) -> dict:
    return cell.metadata.get("nbgrader", {})


def _kinds() -> dict[str, str]:
    from lbo_notebooks.exercises.grading import load_graders

    return {exercise: g.kind for exercise, g in load_graders().items()}


def exercises_of(nb: nbformat.NotebookNode, kinds: dict[str, str] | None = None) -> list[Exercise]:
    """The exercises of an instructor-edition notebook, in order (answer cells, then their written part)."""
    kinds = _kinds() if kinds is None else kinds
    cells = nb.cells
    found: list[Exercise] = []
    for i, cell in enumerate(cells):
        grade_id = _grader(cell).get("grade_id", "")
        if grade_id.endswith("-answer") and _grader(cell).get("solution"):
            exercise = grade_id[: -len("-answer")]
            check = next((c for c in cells if _grader(c).get("grade_id") == f"{exercise}-check"), None)
            match = _SOLUTION.search(cell.source)
            solution = textwrap.dedent(match.group(1)).strip("\n") if match else cell.source
            skeleton = _SOLUTION.sub("", cell.source) if match else ""
            skeleton = re.sub(r"^[ \t]*#+\s*END SOLUTION[^\n]*\n?", "", skeleton, flags=re.M).strip("\n")
            found.append(Exercise(
                id=exercise, kind=kinds.get(exercise, "?"),
                points=check.metadata["nbgrader"].get("points") if check is not None else None,
                question=prompt_of(cells, i, exercise), solution=reflow_comments(solution),
                check=_HIDDEN_TESTS.sub("", check.source).strip() if check is not None else "",
                skeleton=skeleton))
        elif grade_id.endswith("-explain") and cell.cell_type == "markdown":
            exercise = grade_id[: -len("-explain")]
            model, _, rubric = cell.source.partition("**Rubric")
            found.append(Exercise(
                id=grade_id, kind="written", points=_grader(cell).get("points"),
                question=prompt_of(cells, i, exercise), solution=model.strip(),
                rubric=("**Rubric" + rubric).strip() if rubric else ""))
    return found


def prompt_of(cells, index: int, exercise: str) -> str:
    """The prompt above cell ``index``: the markdown cell headed ``**Exercise <exercise>**``, else the nearest one."""
    above = [c for c in cells[:index] if c.cell_type == "markdown" and not _grader(c).get("solution")]
    for cell in reversed(above):
        if re.match(rf"\s*\*\*Exercise {re.escape(exercise)}\*\*", cell.source):
            return cell.source
    return above[-1].source if above else ""


def stated_minutes(nb: nbformat.NotebookNode) -> int:
    """The class time a notebook's header states: ``*Time: about N minutes ...*``.

    Raises
    ------
    ValueError
        When the first cell states none (the header's second line should).
    """
    match = _MINUTES.search(nb.cells[0].source) if nb.cells else None
    if match is None:
        raise ValueError("the notebook's first cell states no '*Time: about N minutes in class*': add it to its header.")
    return int(match.group(1))


# --- docs/lecturers/plan.md: its minutes follow the notebooks' headers -------------------------------

_PLAN_ROW = re.compile(r"^\| (?P<nb>\d\d) \|(?P<mid>.*?)\| (?P<min>\d+) \|(?P<rest>[^\n]*)$", re.M)


def plan_minutes(text: str) -> dict[str, int]:
    """``{"03": 85, ...}`` from the term-plan table (rows ``| NN | ... | minutes | ...``)."""
    return {m.group("nb"): int(m.group("min")) for m in _PLAN_ROW.finditer(text.split("## Weekly schedule")[0])}


def sync_plan(text: str, minutes: dict[str, int]) -> str:
    """``plan.md`` with its minutes from ``minutes``: the term-plan rows, the totals and each week's sum.

    The term plan's rows are ``| NN | ... | minutes | ...``; the weekly schedule's rows
    ``| week | NN, NN | minutes | ...`` (a week's minutes are the sum of its notebooks'); the
    lines marked ``<!-- total -->`` / ``<!-- core total -->`` carry the sums.
    """
    plan, sep, rest = text.partition("## Weekly schedule")

    def row(m: re.Match) -> str:
        return f"| {m.group('nb')} |{m.group('mid')}| {minutes[m.group('nb')]} |{m.group('rest')}"

    plan = _PLAN_ROW.sub(row, plan)
    core = [m.group("nb") for m in _PLAN_ROW.finditer(plan) if "| core |" in m.group(0)]

    def week(m: re.Match) -> str:
        listed = re.findall(r"\b(\d\d)\b", m.group("nbs"))
        return f"| {m.group('week')} | {m.group('nbs')} | {sum(minutes[n] for n in listed)} |{m.group('rest')}"

    rest = re.sub(r"^\| (?P<week>\d+) \| (?P<nbs>[\d, ]+?) \| \d+ \|(?P<rest>[^\n]*)$", week, rest, flags=re.M)
    text = plan + sep + rest
    total = sum(minutes[n] for n in plan_minutes(plan))
    text = re.sub(r"\*\*\d+ minutes\*\*(.*)<!-- total -->", lambda m: f"**{total} minutes**{m.group(1)}<!-- total -->", text)
    core_total = sum(minutes[n] for n in core)
    text = re.sub(r"\*\*\d+ minutes\*\*(.*)<!-- core total -->",
                  lambda m: f"**{core_total} minutes**{m.group(1)}<!-- core total -->", text)
    return text


def notebook_minutes(folder: Path = REPO / "notebooks") -> dict[str, int]:
    """``{"00": 60, ...}``: the stated minutes of every ``NN_name.ipynb`` in ``folder``."""
    return {p.name[:2]: stated_minutes(nbformat.read(p, as_version=4))
            for p in sorted(folder.glob("[0-9][0-9]_*.ipynb"))}


# --- HTML -------------------------------------------------------------------------------------------

def markdown(text: str) -> str:
    """Markdown to HTML, formulas left for MathJax (nbconvert's renderer, which protects ``$...$``)."""
    from nbconvert.filters.markdown_mistune import markdown2html_mistune

    # Links between notebooks point at the booklet's own pages.
    text = re.sub(r"\]\((?:\.\./notebooks/|\./)?(\d\d_\w+)\.ipynb\)", r"](\1.html)", text)
    return markdown2html_mistune(text)


def code(source: str) -> str:
    from pygments import highlight
    from pygments.formatters import HtmlFormatter
    from pygments.lexers import PythonLexer

    return highlight(source, PythonLexer(), HtmlFormatter(cssclass="highlight", nowrap=False))


def _css() -> str:
    from pygments.formatters import HtmlFormatter

    return CSS + HtmlFormatter(style="default").get_style_defs(".highlight")


CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; max-width: 52em; margin: 2em auto;
       padding: 0 1em; line-height: 1.55; color: #222; }
h1 { font-size: 1.7em; } h2 { margin-top: 2.2em; border-top: 1px solid #ddd; padding-top: 1em; font-size: 1.25em; }
.meta { color: #555; font-size: 0.95em; }
.kind { display: inline-block; padding: 0 0.5em; border-radius: 0.6em; background: #eef3fb; color: #1d4e89; }
.points { display: inline-block; padding: 0 0.5em; border-radius: 0.6em; background: #f4efe3; color: #6b4b00; }
.question { border-left: 4px solid #9bb7de; padding: 0.1em 1em; background: #f8fafd; }
.written { border-left: 4px solid #d8b86a; padding: 0.1em 1em; background: #fdfbf5; }
h3 { font-size: 1em; margin: 1.2em 0 0.3em; color: #444; }
pre, .highlight pre { white-space: pre-wrap; word-wrap: break-word; background: #f6f6f6; padding: 0.7em 0.9em;
       border-radius: 4px; line-height: 1.45; }
pre, code { font-family: ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 0.9rem; }
table { border-collapse: collapse; } td, th { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; }
nav { margin-bottom: 1.5em; font-size: 0.95em; } nav a { margin-right: 1em; }
"""


def page(title: str, body: str, mathjax: str, nav: str = "") -> str:
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(title)}</title>
<style>{_css()}</style>
{mathjax}
</head><body>
<nav>{nav}</nav>
{body}
</body></html>
"""


def exercise_html(ex: Exercise) -> str:
    points = f'<span class="points">{ex.points} point{"s" if ex.points != 1 else ""}</span>' if ex.points is not None else ""
    parts = [f'<h2 id="{html.escape(ex.id)}">{html.escape(ex.id)}</h2>',
             f'<p class="meta"><span class="kind">{html.escape(ex.kind)}</span> {points}</p>',
             f'<h3>Question</h3><div class="question">{markdown(ex.question)}</div>']
    if ex.kind == "written":
        parts.append(f'<h3>Model answer</h3><div class="written">{markdown(ex.solution)}</div>')
        if ex.rubric:
            parts.append(f'<h3>Rubric</h3><div class="written">{markdown(ex.rubric)}</div>')
    else:
        if ex.skeleton.strip():
            parts.append(f"<h3>The answer cell students get</h3>{code(ex.skeleton)}")
        parts.append(f'<h3>Solution</h3><div class="solution">{code(ex.solution)}</div>')
        if ex.check:
            parts.append(f"<h3>Checked by</h3>{code(ex.check)}")
    return "\n".join(parts)


def build(notebooks: list[Path], out: Path) -> dict[str, list[Exercise]]:
    """Write ``<out>/<stem>.html`` per notebook and ``<out>/index.html``; return the exercises by notebook."""
    out.mkdir(parents=True, exist_ok=True)
    mathjax = slides.copy_mathjax(out / "_static").replace("{prefix}", "_static/")
    kinds = _kinds()
    by_notebook: dict[str, list[Exercise]] = {}
    titles = {}
    for path in notebooks:
        nb = nbformat.read(path, as_version=4)
        title = slides.title_of(nb, path.stem)
        exercises = exercises_of(nb, kinds)
        by_notebook[path.stem], titles[path.stem] = exercises, title
        total = sum(e.points or 0 for e in exercises)
        contents = " · ".join(f'<a href="#{html.escape(e.id)}">{html.escape(e.id)}</a>' for e in exercises)
        body = (f"<h1>{html.escape(title)}</h1>\n<p class=\"meta\">Solutions booklet: {len(exercises)} graded parts, "
                f"{total} points. {contents}</p>\n" + "\n".join(exercise_html(e) for e in exercises))
        nav = '<a href="index.html">← all notebooks</a>'
        (out / f"{path.stem}.html").write_text(page(f"{title}: solutions", body, mathjax, nav), encoding="utf-8")
        print(f"{path.stem}: {len(exercises)} graded parts, {total} points", flush=True)
    rows = []
    for stem, exercises in by_notebook.items():
        for e in exercises:
            rows.append(f'<tr><td><a href="{stem}.html#{html.escape(e.id)}">{html.escape(e.id)}</a></td>'
                        f"<td>{html.escape(e.kind)}</td><td>{e.points if e.points is not None else '?'}</td>"
                        f'<td><a href="{stem}.html">{html.escape(titles[stem])}</a></td></tr>')
    grand = sum(e.points or 0 for ex in by_notebook.values() for e in ex)
    count = sum(len(ex) for ex in by_notebook.values())
    body = f"""<h1>Solutions booklet</h1>
<p>For lecturers: every graded part of the notebooks ({count}, {grand} points in all) with its question, the
instructor's solution and, for written answers, the model answer and rubric. Built from the instructor edition by
<code>./make.sh booklet</code> (scripts/booklet.py). Points by kind: build 5, compute and explore 2, predict and
choice 1, recap 3 (a point a question), written 2 (graded by a person with the rubric).</p>
<table><thead><tr><th>Exercise</th><th>Kind</th><th>Points</th><th>Notebook</th></tr></thead><tbody>
{chr(10).join(rows)}
</tbody></table>"""
    (out / "index.html").write_text(page("Solutions booklet", body, mathjax), encoding="utf-8")
    return by_notebook


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path, help="notebooks (default: the series)")
    parser.add_argument("--out", type=Path, default=REPO / "build" / "booklet", help="output folder (default build/booklet)")
    parser.add_argument("--sync-plan", action="store_true",
                        help="rewrite the minutes of docs/lecturers/plan.md from the notebooks' headers, and stop")
    args = parser.parse_args(argv)
    if args.sync_plan:
        before = PLAN.read_text(encoding="utf-8")
        after = sync_plan(before, notebook_minutes())
        PLAN.write_text(after, encoding="utf-8")
        print(f"{PLAN.relative_to(REPO)}: {'updated' if after != before else 'already up to date'}")
        return 0
    notebooks = [p.resolve() for p in args.notebooks] or slides.default_notebooks()
    try:
        build(notebooks, args.out.resolve())
    except RuntimeError as exc:
        print(f"booklet: {exc}", file=sys.stderr)
        return 1
    print(f"wrote {args.out / 'index.html'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
