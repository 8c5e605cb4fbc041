"""Build the static site: the executed notebooks, the API reference and the docs, with Sphinx.

One command (from the repository root, with the project's environment; ``./make.sh site``)::

    python scripts/build_site.py                   # -> build/site/index.html
    python scripts/build_site.py --out /tmp/site notebooks/03_laplace_beltrami.ipynb

The site is rendered by Sphinx with myst-nb (notebooks and Markdown), autosummary + numpydoc (a
reference page for every name in ``lbo_notebooks.__all__``) and the PyData theme, with Sphinx's
own search; ``docs/conf.py`` says why this stack and how the site stays offline (MathJax and
plotly.js copied into it, no CDN). This script does what Sphinx cannot, then hands over:

1. **The series.** It publishes exactly ``00_start_here`` and the notebooks its map of the series
   lists (``| NN | [name](NN_name.ipynb) | topic |``), in that order. Any other ``.ipynb`` in
   ``notebooks/`` (a scratch notebook, a ``-Copy1``, a student's ``.new.ipynb``) is neither executed
   nor listed; the build names what it skipped. Notebooks given on the command line are built as given.
2. **Execution.** Each notebook runs top to bottom in a fresh kernel (working directory
   ``notebooks/``, like JupyterLab) started with ``scripts/site_prelude.py``: plotly figures become
   HTML that uses the site's one plotly.js, ``mesh_slider`` viewers become plotly figures with a
   plotly slider over precomputed frames, progress bars are off. The kernel talks to the builder
   over IPC sockets (a TCP kernel warns that its traffic is unencrypted). myst-nb then renders the
   executed notebooks as they are (``nb_execution_mode = "off"``).
3. **What the reader sees.** Exercise solutions (nbgrader answer cells) are folded in a
   ``<details>`` block with what they print, their figures staying in view; check cells show the
   check call, not their hidden tests (``### BEGIN HIDDEN TESTS`` ...: run, but the autograder's);
   verification cells (``hide-input``, or collapsed in JupyterLab) are folded by myst-nb; live
   widgets (which need a kernel) are replaced by a note.
4. **The source folder** for Sphinx (``<out>-src``, rebuilt each time, laid out like the
   repository so that links between notebooks and ``docs/`` resolve): ``notebooks/`` (executed),
   ``docs/*.md`` and ``docs/lecturers/*.md`` (the "For lecturers" pages; the slides and the
   solutions booklet built by ``./make.sh slides booklet`` are copied to ``<out>/lecturers/``), ``index.md`` (every notebook with its title, its topic from the series map, a
   link to the clean ``.ipynb`` and its run time), ``notebooks/index.md`` (the series' table of
   contents) and ``reference.rst`` (an autosummary of ``lbo_notebooks.__all__``, read when the site
   is built: names added or moved by the library need no change here).

Exit code 1 if a notebook fails to execute (its page is still written, with the error shown) or
Sphinx fails.
"""

from __future__ import annotations

import argparse
import importlib.util
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

REPO = Path(__file__).resolve().parent.parent
PRELUDE = Path(__file__).resolve().parent / "site_prelude.py"
WIDGET_MIME = "application/vnd.jupyter.widget-view+json"
WIDGET_NOTE = ('<p class="lbo-widget-note"><em>An interactive widget appears here when the notebook runs in '
               'JupyterLab.</em></p>')


@dataclass
class Page:
    source: Path
    title: str
    description: str
    seconds: float
    error: str | None


def series_map(nb: nbformat.NotebookNode) -> dict[str, str]:
    """Topics from a notebook's map of the series: markdown table rows ``| NN | [name](file.ipynb) | topic |``.

    Returns ``{file stem: topic}``; ``00_start_here`` holds the map the index uses.
    """
    topics = {}
    for cell in nb.cells:
        if cell.cell_type != "markdown":
            continue
        for line in cell.source.splitlines():
            cols = [c.strip() for c in line.strip().strip("|").split("|")]
            link = re.search(r"\]\(([^)]+)\.ipynb\)", line)
            if link and len(cols) >= 3 and line.lstrip().startswith("|"):
                topics[Path(link.group(1)).name] = cols[-1]
    return topics


SERIES_NAME = re.compile(r"^\d\d_\w+$")   # NN_name: 00_start_here, 01_shapes, ...
START_HERE = "00_start_here"


def series_notebooks(folder: Path) -> tuple[list[Path], list[Path]]:
    """The series in ``folder``, in order, and the other notebooks there (skipped by the site).

    The series is ``00_start_here`` and the ``NN_name`` notebooks its map (:func:`series_map`)
    links to, in the map's order; without ``00_start_here``, every ``NN_name.ipynb``. Scratch
    notebooks, ``-Copy1`` files and ``.new.ipynb`` editions are never part of it.
    """
    everything = sorted(folder.glob("*.ipynb"))
    start = folder / f"{START_HERE}.ipynb"
    if start.exists():
        listed = [folder / f"{stem}.ipynb" for stem in series_map(nbformat.read(start, as_version=4))]
        series = [start] + [p for p in listed if p.exists() and SERIES_NAME.match(p.stem) and p != start]
    else:
        series = [p for p in everything if SERIES_NAME.match(p.stem)]
    return series, [p for p in everything if p not in series]


def title_and_description(nb: nbformat.NotebookNode, topic: str | None = None) -> tuple[str, str]:
    """The title line (first ``#`` heading) and a one-line description.

    The description is ``topic`` when the series map gives one, else the "What you will learn"
    text when it is a sentence on the label's line, else empty (a list of aims is not a topic).
    """
    first = next((c for c in nb.cells if c.cell_type == "markdown"), None)
    if first is None:
        return "Untitled", topic or ""
    lines = [ln.strip() for ln in first.source.splitlines()]
    title = next((ln.lstrip("#").strip() for ln in lines if ln.startswith("# ")), lines[0] if lines else "Untitled")
    if topic:
        return title, topic
    for ln in lines:
        m = re.match(r"\**what you will learn\**\s*:?\**\s*:?\s*(.*)", ln, re.IGNORECASE)
        if m:
            return title, re.sub(r"[;,:.]\s*$", "", m.group(1).strip())
    return title, ""


def execute(nb: nbformat.NotebookNode, cwd: Path, timeout: int) -> str | None:
    """Run the notebook in place in a fresh kernel started with the site prelude; return the error, if any.

    The kernel listens on IPC (unix) sockets: a TCP kernel warns that its traffic is unencrypted.
    """
    import tempfile

    from jupyter_client.manager import KernelManager

    with tempfile.TemporaryDirectory(prefix="lbo-kernel-") as sockets:
        # An absolute socket path: the kernel runs in ``cwd``, the builder wherever it was started.
        km = KernelManager(kernel_name="python3", transport="ipc", ip=str(Path(sockets) / "kernel"))
        client = NotebookClient(nb, km=km, timeout=timeout, kernel_name="python3", store_widget_state=False,
                                extra_arguments=[f"--IPKernelApp.exec_files={PRELUDE}"],
                                resources={"metadata": {"path": str(cwd)}})
        try:
            client.execute()
        except CellExecutionError as exc:
            return f"{exc.ename}: {exc.evalue}"
        finally:
            if km.has_kernel:  # nbclient shuts down only kernel managers it created itself
                km.shutdown_kernel()
    return None


def _tag(cell: nbformat.NotebookNode, tag: str) -> None:
    tags = cell.metadata.setdefault("tags", [])
    if tag not in tags:
        tags.append(tag)


def prepare_for_html(nb: nbformat.NotebookNode) -> None:
    """Make an executed notebook ready for myst-nb: widget outputs become a note, answer cells are
    folded, check cells lose their hidden tests, cells collapsed in JupyterLab are folded."""
    cells = []
    for cell in nb.cells:
        if cell.cell_type == "markdown" and "**Rubric" in cell.source:
            # a written answer's model answer and rubric: folded, like the code solutions
            cell.source = f"<details><summary>Model answer and rubric</summary>\n\n{cell.source}\n\n</details>"
        if cell.cell_type == "code":
            for out in cell.get("outputs", []):
                if out.get("output_type") in ("display_data", "execute_result") and WIDGET_MIME in out.get("data", {}):
                    out["data"] = {"text/html": WIDGET_NOTE}
            grader = cell.metadata.get("nbgrader", {})
            if grader.get("grade") and not grader.get("solution"):
                cell.source = without_hidden_tests(cell.source)
            if grader.get("solution") and "BEGIN SOLUTION" in cell.source:
                cells.append(folded_solution(cell))
            elif cell.metadata.get("jupyter", {}).get("source_hidden"):
                _tag(cell, "hide-input")          # myst-nb folds the input ("Show code cell source")
        cells.append(cell)
    nb.cells = cells
    nb.metadata.pop("widgets", None)


_HIDDEN_TESTS = re.compile(r"^[ \t]*#+\s*BEGIN HIDDEN TESTS.*?^[ \t]*#+\s*END HIDDEN TESTS[^\n]*\n?", re.M | re.S)
_SOLUTION_MARKER = re.compile(r"^[ \t]*#+\s*(BEGIN|END) SOLUTION[^\n]*\n?", re.M)


_SOLUTION_REGION = re.compile(r"^([ \t]*)#+\s*BEGIN SOLUTION[^\n]*\n.*?^[ \t]*#+\s*END SOLUTION[^\n]*\n?", re.M | re.S)


def without_solutions(nb: nbformat.NotebookNode) -> None:
    r"""Take the instructor's answers out of an executed notebook, for a site students may read during a
    graded course (``--without-solutions``): answer cells keep their placeholder and lose their outputs,
    check cells lose their verdicts and hidden tests, written answers (manually graded Markdown cells)
    say only where the answer goes. The lesson's own cells and figures stay.

    >>> nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
    ...     "x = ...\n### BEGIN SOLUTION\nx = 2\n### END SOLUTION", metadata={"nbgrader": {"solution": True}})])
    >>> without_solutions(nb); nb.cells[0].source
    'x = ...'
    """
    for cell in nb.cells:
        grader = cell.metadata.get("nbgrader", {})
        if grader.get("solution") and cell.cell_type == "markdown":
            cell.source = "*Your written answer goes here (graded by your lecturer).*"
        elif grader.get("solution"):
            cell.source = _SOLUTION_REGION.sub("", cell.source).rstrip()
            cell.outputs = []
        elif grader.get("grade") and cell.cell_type == "code":
            cell.source = without_hidden_tests(cell.source)
            cell.outputs = []


def without_hidden_tests(source: str) -> str:
    r"""A check cell's source without its nbgrader hidden tests (the autograder's, not the reader's).

    >>> without_hidden_tests("feedback = check(x)\n### BEGIN HIDDEN TESTS\nassert feedback.correct\n### END HIDDEN TESTS")
    'feedback = check(x)'
    """
    return _HIDDEN_TESTS.sub("", source).rstrip()


def folded_solution(cell: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """An exercise's answer cell folded: the code and what it printed, in a <details> block.

    The cell itself keeps its rich outputs (figures) but loses its input (myst-nb's
    ``remove-input`` tag) and printed text, so that a reader sees the question, then the check's
    verdict, and opens the solution on purpose. (myst-nb's ``hide-cell`` would fold the figures too.)
    """
    import html

    printed = "".join(o.get("text", "") for o in cell.get("outputs", []) if o.get("output_type") == "stream")
    cell.outputs = [o for o in cell.get("outputs", []) if o.get("output_type") != "stream"]
    _tag(cell, "remove-input")
    code = _SOLUTION_MARKER.sub("", cell.source).strip("\n")
    shown = f'<pre><code class="language-python">{html.escape(code)}</code></pre>'
    if printed.strip():
        shown += f"\n<pre class=\"lbo-output\">{html.escape(printed.rstrip())}</pre>"
    return nbformat.v4.new_markdown_cell(
        f'<details class="lbo-solutions"><summary>Solution (click to show)</summary>\n{shown}\n</details>')


def public_names() -> list[str]:
    """``lbo_notebooks.__all__``, read from the package being documented."""
    import lbo_notebooks

    return list(lbo_notebooks.__all__)


def reference_page(names: list[str]) -> str:
    """``reference.rst``: an autosummary table (and a page each) for the public functions and classes,
    then for the public submodules (a page each with their members)."""
    modules = [n for n in names if importlib.util.find_spec(f"lbo_notebooks.{n}") is not None]
    objects = [n for n in names if n not in modules]

    def table(entries: list[str]) -> str:
        return ".. autosummary::\n   :toctree: generated\n   :nosignatures:\n\n" + "".join(f"   {n}\n" for n in entries)

    parts = ["API reference\n=============\n\n.. currentmodule:: lbo_notebooks\n\n"
             "Every public name of ``lbo_notebooks`` (its ``__all__``), importable from the top level "
             "(``import lbo_notebooks as lbo; lbo.eigenbasis(...)``), with its documentation.\n\n"]
    if objects:
        parts.append("Functions and classes\n---------------------\n\n" + table(objects) + "\n")
    if modules:
        parts.append("Modules\n-------\n\n" + table(modules))
    return "".join(parts)


def index_page(pages: list[Page], with_reference: bool = True) -> str:
    """``index.md``: the series, each notebook with its title, topic, clean download and run time."""
    rows = []
    for i, p in enumerate(pages, 1):
        status = f" **(failed: {p.error})**" if p.error else ""
        rows.append(f"{i}. [**{p.title}**](notebooks/{p.source.name}){status}\\\n"
                    f"   {p.description}\\\n"
                    f"   {{download}}`{p.source.name} <_clean/{p.source.name}>` · runs in {p.seconds:.0f} s\n")
    docs = "".join(f"docs/{d.stem}\n" for d in sorted((REPO / "docs").glob("*.md")))
    if (REPO / "docs" / "lecturers" / "index.md").exists():
        docs += "docs/lecturers/index\n"      # "For lecturers": plan, project, exam, slides, booklet
    reference = "reference\n" if with_reference else ""
    built = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    return f"""# Spectral shape analysis with the Laplace–Beltrami operator

The notebooks of `lbo_notebooks`, executed and rendered for reading. 3D figures can be rotated and
zoomed; sliders step through precomputed frames. To change the code, download a notebook (or clone the
repository) and run it in JupyterLab: `./make.sh lab`.{" The [API reference](reference) documents every public name of the library; the search box finds any of them." if with_reference else ""}

{chr(10).join(rows)}
```{{toctree}}
:hidden:

notebooks/index
{reference}{docs}```

<p class="lbo-built">Built {built}.</p>
"""


def notebooks_page(pages: list[Page]) -> str:
    """``notebooks/index.md``: the series as a table of contents (the section the notebooks live in)."""
    entries = "".join(f"{p.source.stem}\n" for p in pages)
    return f"# Notebooks\n\nThe series, in reading order.\n\n```{{toctree}}\n:maxdepth: 1\n\n{entries}```\n"


def sphinx_sources(src: Path, pages: list[Page], names: list[str]) -> None:
    """Everything but the executed notebooks: ``docs/*.md``, the index pages and ``reference.rst``."""
    (src / "docs").mkdir(parents=True, exist_ok=True)
    for doc in sorted((REPO / "docs").glob("*.md")):
        shutil.copy2(doc, src / "docs" / doc.name)
    lecturers = sorted((REPO / "docs" / "lecturers").glob("*.md"))
    if lecturers:
        (src / "docs" / "lecturers").mkdir(exist_ok=True)
        for doc in lecturers:
            shutil.copy2(doc, src / "docs" / "lecturers" / doc.name)
    (src / "index.md").write_text(index_page(pages, bool(names)), encoding="utf-8")
    (src / "notebooks" / "index.md").write_text(notebooks_page(pages), encoding="utf-8")
    if names:
        (src / "reference.rst").write_text(reference_page(names), encoding="utf-8")


def lecturer_pack(out: Path) -> list[str]:
    """Copy the built slides and solutions booklet (``./make.sh slides booklet``) into ``<out>/lecturers/``.

    The "For lecturers" page (``docs/lecturers/index.md``) links them there. Returns what was
    missing (not built yet), by name.
    """
    missing = []
    for name in ("slides", "booklet"):
        built = REPO / "build" / name
        if (built / "index.html").exists():
            shutil.copytree(built, out / "lecturers" / name, dirs_exist_ok=True)
        else:
            missing.append(name)
    return missing


def run_sphinx(src: Path, out: Path) -> int:
    """``sphinx-build -b html -c docs <src> <out>`` (doctrees kept in the source folder)."""
    command = [sys.executable, "-m", "sphinx", "-b", "html", "-q", "-c", str(REPO / "docs"),
               "-d", str(src / ".doctrees"), str(src), str(out)]
    return subprocess.run(command, cwd=REPO).returncode


#: Written first into the Sphinx source folder, so that a build interrupted before ``index.md``
#: exists is still recognised as ours (and replaced) by the next run.
SOURCE_MARKER = ".lbo-site-source"


def _fresh(folder: Path, *markers: str) -> None:
    """Empty ``folder`` (a previous build of ours, recognised by one of ``markers``), or create it."""
    if folder.exists() and any(folder.iterdir()):
        if not any((folder / marker).exists() for marker in markers):
            raise SystemExit(f"{folder} is not empty and is not a previous site build: choose another --out")
        shutil.rmtree(folder)
    folder.mkdir(parents=True, exist_ok=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path,
                        help="notebooks (default: the series, 00_start_here and the notebooks its map lists)")
    parser.add_argument("--out", type=Path, default=REPO / "build" / "site", help="output folder (default build/site)")
    parser.add_argument("--timeout", type=int, default=600, help="per-cell timeout in seconds")
    parser.add_argument("--no-reference", action="store_true", help="leave the API reference out (quicker)")
    parser.add_argument("--without-solutions", action="store_true",
                        help="a site for students of a graded course: no instructor answers (docs/exercises.md)")
    args = parser.parse_args(argv)

    # Exactly the series (its entry point first, then the notebooks its map lists), unless named.
    sources = [p.resolve() for p in args.notebooks]
    if not sources:
        sources, skipped = series_notebooks(REPO / "notebooks")
        if skipped:
            print("not part of the series (not in the map of 00_start_here), skipped: "
                  + ", ".join(p.name for p in skipped), flush=True)
    if not sources:
        print("no notebooks found", file=sys.stderr)
        return 1
    out = args.out.resolve()
    src = out.with_name(out.name + "-src")
    _fresh(out, ".buildinfo", "plotly.min.js")   # Sphinx's build, or the site before Sphinx
    _fresh(src, SOURCE_MARKER, "index.md")
    (src / SOURCE_MARKER).write_text("a source folder written by scripts/build_site.py; rebuilt on each run\n")
    (src / "notebooks").mkdir()
    (src / "_clean").mkdir()

    start_here = REPO / "notebooks" / f"{START_HERE}.ipynb"
    topics = series_map(nbformat.read(start_here, as_version=4)) if start_here.exists() else {}
    pages = []
    started = time.perf_counter()
    for path in sources:
        nb = nbformat.read(path, as_version=4)
        title, description = title_and_description(nb, topics.get(path.stem))
        start = time.perf_counter()
        error = execute(nb, path.parent, args.timeout)
        seconds = time.perf_counter() - start
        clean = nbformat.read(path, as_version=4)
        if args.without_solutions:
            without_solutions(nb)
            without_solutions(clean)
        prepare_for_html(nb)
        nbformat.write(nb, src / "notebooks" / path.name)
        nbformat.write(clean, src / "_clean" / path.name)
        pages.append(Page(path, title, description, seconds, error))
        print(f"{path.name:<34} {seconds:6.1f} s  {'FAILED: ' + error if error else 'ok'}", flush=True)
    sphinx_sources(src, pages, [] if args.no_reference else public_names())
    print(f"executed {len(pages)} notebooks in {time.perf_counter() - started:.0f} s; rendering with Sphinx", flush=True)
    start = time.perf_counter()
    status = run_sphinx(src, out)
    html_pages = sum(1 for _ in out.rglob("*.html"))
    print(f"Sphinx: {html_pages} pages in {time.perf_counter() - start:.0f} s; wrote {out / 'index.html'}", flush=True)
    if (REPO / "docs" / "lecturers" / "index.md").exists():
        missing = lecturer_pack(out)
        if missing:
            print(f"not built, so not in the site's lecturer pages: {', '.join(missing)} "
                  "(run ./make.sh slides booklet first)", flush=True)
    return 1 if status or any(p.error for p in pages) else 0


if __name__ == "__main__":
    sys.exit(main())
