"""Build the static site for self-study readers: every notebook executed and rendered to HTML.

One command (from the repository root, with the project's environment)::

    python scripts/build_site.py                   # -> build/site/index.html
    python scripts/build_site.py --out /tmp/site notebooks/03_laplace_beltrami.ipynb

The site publishes exactly the series: ``00_start_here`` and the notebooks its map of the series
lists (``| NN | [name](NN_name.ipynb) | topic |``), in that order. Any other ``.ipynb`` in
``notebooks/`` (a lecturer's scratch notebook, a ``-Copy1`` JupyterLab made, a student's
``.new.ipynb``) is neither executed nor listed; the build names what it skipped. Notebooks given
on the command line are built as given.

Each notebook of the series is executed top to bottom in a fresh kernel (working directory
``notebooks/``, like JupyterLab) and converted with nbconvert's ``HTMLExporter`` (lab template).
The site works offline, from ``file://`` or any static host:

- plotly figures stay interactive: the kernel renders them as HTML that calls ``Plotly.newPlot``,
  and every page loads the one ``plotly.min.js`` copied into the site from the installed plotly;
- ``mesh_slider`` viewers (live widgets need a kernel) become plotly figures with a plotly slider
  over precomputed frames (see ``scripts/site_prelude.py``); other widgets are replaced by a note;
- solutions (cells hidden with ``{"jupyter": {"source_hidden": true}}``, and the answer cells of
  the exercises marked for nbgrader, with what they print) are folded in a ``<details>`` block; the
  check cells show the check call only, not their hidden tests (``### BEGIN HIDDEN TESTS`` ...),
  which are run but are the autograder's, not the reader's;
- formulas are typeset by MathJax 2 copied into the site (``mathjax/``) from the installed Python
  package ``jupyter-server-mathjax`` (a ``[test]`` dependency; ``--mathjax`` names another local
  MathJax 2 folder, e.g. Debian's ``libjs-mathjax``), so no page loads anything from the network;
- progress bars are switched off while executing (a notebook-widget bar would be a dead widget on a
  static page), and the kernel talks to the builder over IPC sockets rather than TCP;
- ``index.html`` lists every notebook with its title line, its topic (its row in the series map of
  ``00_start_here``, else the "What you will learn" sentence), its run time and a link to the clean
  ``.ipynb``.

Exit code 1 if a notebook fails to execute (its page is still written, with the error shown).
"""

from __future__ import annotations

import argparse
import html
import re
import shutil
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import mistune
import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError
from nbconvert import HTMLExporter

REPO = Path(__file__).resolve().parent.parent
PRELUDE = Path(__file__).resolve().parent / "site_prelude.py"
DEBIAN_MATHJAX = Path("/usr/share/javascript/mathjax")
# MathJax 2 options set before MathJax.js loads: typeset with the web fonts shipped in the copy
# (jupyter-server-mathjax ships STIX-Web only), never ask the network for others.
MATHJAX_PRECONFIG = ('<script>window.MathJax = {"HTML-CSS": {availableFonts: [], preferredFont: null, '
                     'webFont: "STIX-Web", imageFont: null}, messageStyle: "none", '
                     'tex2jax: {inlineMath: [["$", "$"], ["\\\\(", "\\\\)"]], processEscapes: true}};</script>')
WIDGET_MIME = "application/vnd.jupyter.widget-view+json"
WIDGET_NOTE = ('<p class="lbo-widget-note"><em>An interactive widget appears here when the notebook runs in '
               'JupyterLab.</em></p>')


@dataclass
class Page:
    source: Path
    html_name: str
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


_MATH = re.compile(r"\$\$.+?\$\$|\$[^$]+\$", re.S)


def markdown_inline(text: str) -> str:
    r"""One line of markdown as HTML, with ``$...$`` formulas passed through untouched for MathJax.

    (Markdown would otherwise eat TeX's backslash escapes: ``\,`` becomes ``,``.)

    >>> markdown_inline(r"the top of $(A X X^\top A - \mu W)\,p = \sigma A p$ and **bold** <b>")
    'the top of $(A X X^\\top A - \\mu W)\\,p = \\sigma A p$ and <strong>bold</strong> &lt;b&gt;'
    """
    formulas: list[str] = []

    def stash(m: re.Match) -> str:
        formulas.append(html.escape(m.group(0), quote=False))
        return f"@@MATH{len(formulas) - 1}@@"  # letters and digits: markdown leaves them alone

    body = mistune.create_markdown(escape=True)(_MATH.sub(stash, text)).strip()
    body = body.removeprefix("<p>").removesuffix("</p>")
    return re.sub(r"@@MATH(\d+)@@", lambda m: formulas[int(m.group(1))], body)


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


def prepare_for_html(nb: nbformat.NotebookNode) -> None:
    """Replace widget outputs by a note, fold hidden solution cells and answer cells into <details>,
    and drop the hidden tests from check cells."""
    cells = []
    for cell in nb.cells:
        if cell.cell_type == "code":
            for out in cell.get("outputs", []):
                if out.get("output_type") in ("display_data", "execute_result") and WIDGET_MIME in out.get("data", {}):
                    out["data"] = {"text/html": WIDGET_NOTE}
            grader = cell.metadata.get("nbgrader", {})
            if grader.get("grade") and not grader.get("solution"):
                cell.source = without_hidden_tests(cell.source)
            if grader.get("solution"):
                cells.append(folded_solution(cell))
                cells.append(cell)
                continue
            if cell.metadata.get("jupyter", {}).get("source_hidden"):
                code = html.escape(cell.source)
                summary = "Solutions" if cell.source.lstrip().lower().startswith("# solution") else "Hidden code"
                cells.append(nbformat.v4.new_markdown_cell(
                    f'<details class="lbo-solutions"><summary>{summary} (click to show)</summary>\n'
                    f'<pre><code class="language-python">{code}</code></pre>\n</details>'))
                cell.metadata.setdefault("tags", []).append("lbo-remove-input")
        cells.append(cell)
    nb.cells = cells
    nb.metadata.pop("widgets", None)


_HIDDEN_TESTS = re.compile(r"^[ \t]*#+\s*BEGIN HIDDEN TESTS.*?^[ \t]*#+\s*END HIDDEN TESTS[^\n]*\n?", re.M | re.S)


_SOLUTION_MARKER = re.compile(r"^[ \t]*#+\s*(BEGIN|END) SOLUTION[^\n]*\n?", re.M)


def without_hidden_tests(source: str) -> str:
    r"""A check cell's source without its nbgrader hidden tests (the autograder's, not the reader's).

    >>> without_hidden_tests("feedback = check(x)\n### BEGIN HIDDEN TESTS\nassert feedback.correct\n### END HIDDEN TESTS")
    'feedback = check(x)'
    """
    return _HIDDEN_TESTS.sub("", source).rstrip()


def folded_solution(cell: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """An exercise's answer cell folded: the code and what it printed, in a <details> block.

    The cell itself keeps its rich outputs (figures) but loses its input and printed text, so that
    a reader sees the question, then the check's verdict, and opens the solution on purpose.
    """
    printed = "".join(o.get("text", "") for o in cell.get("outputs", []) if o.get("output_type") == "stream")
    cell.outputs = [o for o in cell.get("outputs", []) if o.get("output_type") != "stream"]
    cell.metadata.setdefault("tags", []).append("lbo-remove-input")
    code = _SOLUTION_MARKER.sub("", cell.source).strip("\n")
    shown = f'<pre><code class="language-python">{html.escape(code)}</code></pre>'
    if printed.strip():
        shown += f"\n<pre class=\"lbo-output\">{html.escape(printed.rstrip())}</pre>"
    return nbformat.v4.new_markdown_cell(
        f'<details class="lbo-solutions"><summary>Solution (click to show)</summary>\n{shown}\n</details>')


# MathJax 2 configurations, best first: CommonHTML output where the copy has it, else HTML-CSS.
MATHJAX_CONFIGS = ["TeX-AMS_CHTML-full", "TeX-AMS-MML_HTMLorMML-full"]


def installed_mathjax() -> Path | None:
    """MathJax 2 shipped by the ``jupyter-server-mathjax`` package, if installed."""
    try:
        import jupyter_server_mathjax
    except ImportError:
        return None
    return Path(jupyter_server_mathjax.__file__).parent / "static"


def copy_mathjax(source: Path, target: Path) -> None:
    """Copy MathJax 2 without what the pages never load: other languages, SVG output, unpacked sources."""

    def skip(folder: str, names: list[str]) -> list[str]:
        rel = Path(folder).relative_to(source).as_posix()
        if rel == "localization":
            return [n for n in names if n != "en"]
        if rel == "jax/output":
            return [n for n in names if n == "SVG"]
        return [n for n in names if n in ("unpacked", "test", "docs")]

    shutil.copytree(source, target, ignore=skip, symlinks=False, dirs_exist_ok=True)


def mathjax_setting(out: Path, mathjax: str | None) -> str:
    """Copy MathJax 2 into ``out/mathjax`` and return the pages' relative URL for it.

    ``mathjax`` is a local MathJax 2 folder; by default the ``jupyter-server-mathjax`` package's
    copy (or Debian's ``libjs-mathjax``). A site that loaded MathJax from the network would show
    raw LaTeX offline, so there is no network fallback.
    """
    candidates = [Path(mathjax)] if mathjax else [p for p in (installed_mathjax(), DEBIAN_MATHJAX) if p is not None]
    source = next((p for p in candidates if (p / "MathJax.js").exists()), None)
    if source is None:
        where = f"--mathjax {mathjax}: no MathJax.js there" if mathjax else "no MathJax 2 installed"
        raise SystemExit(f"{where}. Install it with: pip install jupyter-server-mathjax "
                         "(part of the [test] extra, which ./make.sh site installs).")
    config = next((c for c in MATHJAX_CONFIGS if (source / "config" / f"{c}.js").exists()), None)
    if config is None:
        raise SystemExit(f"{source}: none of the MathJax configurations {MATHJAX_CONFIGS} is there.")
    copy_mathjax(source, out / "mathjax")
    return f"mathjax/MathJax.js?config={config},Safe"


def render(nb: nbformat.NotebookNode, mathjax_url: str, title: str) -> str:
    exporter = HTMLExporter(template_name="lab", mathjax_url=mathjax_url)
    exporter.register_preprocessor(_remove_input_preprocessor(), enabled=True)
    body, _ = exporter.from_notebook_node(nb, resources={"metadata": {"name": title}})
    # No require.js from a CDN (nothing needs it: no widget state is embedded); load plotly.js locally.
    body = body.replace(f'<script src="{exporter.require_js_url}"></script>', "")
    body = body.replace(f'<script src="{mathjax_url}">', MATHJAX_PRECONFIG + f'\n<script src="{mathjax_url}">', 1)
    nav = ('<nav class="lbo-nav" style="padding:0.5em 1em;font-family:sans-serif">'
           '<a href="index.html">&larr; all notebooks</a></nav>')
    body = body.replace("<head>", '<head>\n<script src="plotly.min.js"></script>', 1)
    return re.sub(r"(<body[^>]*>)", r"\1" + nav, body, count=1)


def _remove_input_preprocessor():
    from nbconvert.preprocessors import TagRemovePreprocessor

    return TagRemovePreprocessor(remove_input_tags={"lbo-remove-input"}, enabled=True)


def index_page(pages: list[Page], mathjax_url: str) -> str:
    rows = []
    for p in pages:
        status = f' <span class="err">(failed: {html.escape(p.error)})</span>' if p.error else ""
        rows.append(
            f'<li><a href="{p.html_name}"><strong>{html.escape(p.title)}</strong></a>{status}'
            f'<div class="desc">{markdown_inline(p.description)}</div>'
            f'<div class="meta"><a href="notebooks/{p.source.name}" download>{p.source.name}</a> · '
            f'runs in {p.seconds:.0f} s</div></li>')
    built = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>lbo_notebooks: spectral shape analysis with the Laplace–Beltrami operator</title>
{MATHJAX_PRECONFIG}
<script src="{mathjax_url}"></script>
<style>
body {{ font-family: system-ui, sans-serif; max-width: 52em; margin: 2em auto; padding: 0 1em; line-height: 1.5; color: #222; }}
li {{ margin: 0 0 1.2em 0; }} .desc {{ margin-top: 0.2em; }} .meta {{ color: #666; font-size: 0.9em; }} .err {{ color: #b00; }}
</style></head>
<body>
<h1>Spectral shape analysis with the Laplace–Beltrami operator</h1>
<p>The notebooks of <code>lbo_notebooks</code>, executed and rendered for reading. 3D figures can be rotated and
zoomed; sliders step through precomputed frames. To change the code, download a notebook (or clone the
repository) and run it in JupyterLab: <code>./make.sh lab</code>.</p>
<ol>
{chr(10).join(rows)}
</ol>
<p class="meta">Built {built}.</p>
</body></html>
"""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path,
                        help="notebooks (default: the series, 00_start_here and the notebooks its map lists)")
    parser.add_argument("--out", type=Path, default=REPO / "build" / "site", help="output folder (default build/site)")
    parser.add_argument("--timeout", type=int, default=600, help="per-cell timeout in seconds")
    parser.add_argument("--mathjax", help="local MathJax 2 folder to copy into the site "
                        "(default: the jupyter-server-mathjax package's)")
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
    (out / "notebooks").mkdir(parents=True, exist_ok=True)
    import plotly.offline

    (out / "plotly.min.js").write_text(plotly.offline.get_plotlyjs(), encoding="utf-8")
    mathjax_url = mathjax_setting(out, args.mathjax)

    start_here = REPO / "notebooks" / "00_start_here.ipynb"
    topics = series_map(nbformat.read(start_here, as_version=4)) if start_here.exists() else {}
    pages = []
    for src in sources:
        nb = nbformat.read(src, as_version=4)
        title, description = title_and_description(nb, topics.get(src.stem))
        start = time.perf_counter()
        error = execute(nb, src.parent, args.timeout)
        seconds = time.perf_counter() - start
        prepare_for_html(nb)
        page = Page(src, src.stem + ".html", title, description, seconds, error)
        (out / page.html_name).write_text(render(nb, mathjax_url, title), encoding="utf-8")
        shutil.copy2(src, out / "notebooks" / src.name)
        pages.append(page)
        print(f"{src.name:<34} {seconds:6.1f} s  {'FAILED: ' + error if error else 'ok'}", flush=True)
    (out / "index.html").write_text(index_page(pages, mathjax_url), encoding="utf-8")
    print(f"wrote {out / 'index.html'} ({len(pages)} notebooks)")
    return 1 if any(p.error for p in pages) else 0


if __name__ == "__main__":
    sys.exit(main())
