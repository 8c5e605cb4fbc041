"""Build the static site for self-study readers: every notebook executed and rendered to HTML.

One command (from the repository root, with the project's environment)::

    python scripts/build_site.py                   # -> build/site/index.html
    python scripts/build_site.py --out /tmp/site notebooks/02_laplace_beltrami.ipynb

Each notebook in ``notebooks/`` is executed top to bottom in a fresh kernel (working directory
``notebooks/``, like JupyterLab) and converted with nbconvert's ``HTMLExporter`` (lab template).
The site works offline, from ``file://`` or any static host:

- plotly figures stay interactive: the kernel renders them as HTML that calls ``Plotly.newPlot``,
  and every page loads the one ``plotly.min.js`` copied into the site from the installed plotly;
- ``mesh_slider`` viewers (live widgets need a kernel) become plotly figures with a plotly slider
  over precomputed frames (see ``scripts/site_prelude.py``); other widgets are replaced by a note;
- solutions (cells hidden with ``{"jupyter": {"source_hidden": true}}``) are folded in a
  ``<details>`` block;
- formulas use MathJax from ``--mathjax`` (a local MathJax 2 folder, copied into the site; by default
  Debian's ``libjs-mathjax`` at /usr/share/javascript/mathjax if installed), else the CDN, in which
  case formulas show as LaTeX source when offline;
- ``index.html`` lists every notebook with its title, its one-line description (the first item of
  "What you will learn" in its first cell), its run time and a link to the clean ``.ipynb``.

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
MATHJAX_CDN = "https://cdnjs.cloudflare.com/ajax/libs/mathjax/2.7.7/latest.js?config=TeX-AMS_CHTML-full,Safe"
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


def title_and_description(nb: nbformat.NotebookNode) -> tuple[str, str]:
    """Title (first ``#`` heading) and a one-line description from the first markdown cell."""
    first = next((c for c in nb.cells if c.cell_type == "markdown"), None)
    if first is None:
        return "Untitled", ""
    lines = [ln.strip() for ln in first.source.splitlines()]
    title = next((ln.lstrip("#").strip() for ln in lines if ln.startswith("# ")), lines[0] if lines else "Untitled")
    description = ""
    for i, ln in enumerate(lines):
        m = re.match(r"\**what you will learn\**\s*:?\**\s*:?\s*(.*)", ln, re.IGNORECASE)
        if m:
            rest = m.group(1).strip()
            if not rest:  # the aims are a list below the label: take the first item
                rest = next((re.sub(r"^[-*]\s+|^\d+\.\s+", "", x) for x in lines[i + 1:] if x), "")
            description = rest
            break
    if not description:  # otherwise the first paragraph that is not a heading
        description = next((ln for ln in lines if ln and not ln.startswith("#")), "")
    description = re.sub(r"[;,:]\s*$", "", description)
    return title, description


def execute(nb: nbformat.NotebookNode, cwd: Path, timeout: int) -> str | None:
    """Run the notebook in place in a fresh kernel started with the site prelude; return the error, if any."""
    client = NotebookClient(nb, timeout=timeout, kernel_name="python3", store_widget_state=False,
                            extra_arguments=[f"--IPKernelApp.exec_files={PRELUDE}"],
                            resources={"metadata": {"path": str(cwd)}})
    try:
        client.execute()
    except CellExecutionError as exc:
        return f"{exc.ename}: {exc.evalue}"
    return None


def prepare_for_html(nb: nbformat.NotebookNode) -> None:
    """Replace widget outputs by a note and fold hidden solution cells into <details>."""
    cells = []
    for cell in nb.cells:
        if cell.cell_type == "code":
            for out in cell.get("outputs", []):
                if out.get("output_type") in ("display_data", "execute_result") and WIDGET_MIME in out.get("data", {}):
                    out["data"] = {"text/html": WIDGET_NOTE}
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


# The parts of MathJax 2 that the TeX-AMS_CHTML-full configuration loads (about 1.3 MB of 54 MB).
MATHJAX_PARTS = ["MathJax.js", "config/TeX-AMS_CHTML-full.js", "jax/input/TeX", "jax/output/CommonHTML",
                 "jax/element", "extensions", "localization/en", "fonts/HTML-CSS/TeX/woff"]


def copy_mathjax(source: Path, target: Path) -> None:
    """Copy the MathJax 2 files the pages need (following symlinks, as Debian's package uses them)."""
    for part in MATHJAX_PARTS:
        src, dst = source / part, target / part
        if not src.exists():
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        if src.is_dir():
            shutil.copytree(src, dst, symlinks=False, dirs_exist_ok=True)
        else:
            shutil.copy2(src, dst)


def mathjax_setting(out: Path, mathjax: str | None) -> str:
    """The MathJax URL for the pages, copying a local MathJax 2 into the site when there is one."""
    source = Path(mathjax) if mathjax and not mathjax.startswith("http") else (DEBIAN_MATHJAX if mathjax is None else None)
    if source is not None and (source / "MathJax.js").exists():
        copy_mathjax(source, out / "mathjax")
        return "mathjax/MathJax.js?config=TeX-AMS_CHTML-full,Safe"
    if mathjax and mathjax.startswith("http"):
        return mathjax
    if mathjax:
        raise SystemExit(f"--mathjax {mathjax}: no MathJax.js there")
    print("note: no local MathJax (apt-get install libjs-mathjax): formulas load MathJax from the CDN", file=sys.stderr)
    return MATHJAX_CDN


def render(nb: nbformat.NotebookNode, mathjax_url: str, title: str) -> str:
    exporter = HTMLExporter(template_name="lab", mathjax_url=mathjax_url)
    exporter.register_preprocessor(_remove_input_preprocessor(), enabled=True)
    body, _ = exporter.from_notebook_node(nb, resources={"metadata": {"name": title}})
    # No require.js from a CDN (nothing needs it: no widget state is embedded); load plotly.js locally.
    body = body.replace(f'<script src="{exporter.require_js_url}"></script>', "")
    nav = ('<nav class="lbo-nav" style="padding:0.5em 1em;font-family:sans-serif">'
           '<a href="index.html">&larr; all notebooks</a></nav>')
    body = body.replace("<head>", '<head>\n<script src="plotly.min.js"></script>', 1)
    return re.sub(r"(<body[^>]*>)", r"\1" + nav, body, count=1)


def _remove_input_preprocessor():
    from nbconvert.preprocessors import TagRemovePreprocessor

    return TagRemovePreprocessor(remove_input_tags={"lbo-remove-input"}, enabled=True)


def index_page(pages: list[Page], mathjax_url: str) -> str:
    md = mistune.create_markdown(escape=True)
    rows = []
    for p in pages:
        status = f' <span class="err">(failed: {html.escape(p.error)})</span>' if p.error else ""
        rows.append(
            f'<li><a href="{p.html_name}"><strong>{html.escape(p.title)}</strong></a>{status}'
            f'<div class="desc">{md(p.description).strip().removeprefix("<p>").removesuffix("</p>")}</div>'
            f'<div class="meta"><a href="notebooks/{p.source.name}" download>{p.source.name}</a> · '
            f'runs in {p.seconds:.0f} s</div></li>')
    built = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>lbo_notebooks: spectral shape analysis with the Laplace–Beltrami operator</title>
<script type="text/x-mathjax-config">MathJax.Hub.Config({{tex2jax: {{inlineMath: [['$','$'], ['\\\\(','\\\\)']], processEscapes: true}}}});</script>
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
    parser.add_argument("notebooks", nargs="*", type=Path, help="notebooks (default: notebooks/*.ipynb)")
    parser.add_argument("--out", type=Path, default=REPO / "build" / "site", help="output folder (default build/site)")
    parser.add_argument("--timeout", type=int, default=600, help="per-cell timeout in seconds")
    parser.add_argument("--mathjax", help="local MathJax 2 folder to copy into the site, or a MathJax URL")
    args = parser.parse_args(argv)

    # The series' entry point first, then the numbered notebooks in order.
    sources = [p.resolve() for p in args.notebooks] or sorted(
        (REPO / "notebooks").glob("*.ipynb"), key=lambda p: (p.stem != "00_start_here", p.name))
    if not sources:
        print("no notebooks found", file=sys.stderr)
        return 1
    out = args.out.resolve()
    (out / "notebooks").mkdir(parents=True, exist_ok=True)
    import plotly.offline

    (out / "plotly.min.js").write_text(plotly.offline.get_plotlyjs(), encoding="utf-8")
    mathjax_url = mathjax_setting(out, args.mathjax)

    pages = []
    for src in sources:
        nb = nbformat.read(src, as_version=4)
        title, description = title_and_description(nb)
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
