"""Lecture slides, one reveal.js deck per notebook, built offline into ``build/slides/`` (``./make.sh slides``).

::

    python scripts/slides.py                                  # every notebook of the series
    python scripts/slides.py notebooks/03_laplace_beltrami.ipynb --out /tmp/slides

The notebooks are never changed (others edit them): each is read, and a copy gets its cells'
``slideshow.slide_type`` from its structure, then goes through nbconvert's reveal.js exporter
(``jupyter nbconvert --to slides``, here its Python class ``SlidesExporter``):

- a markdown cell is first split at its headings (a cell holding ``# Title`` and ``## Section``
  gives two), and an over-long one at its paragraphs;
- a ``#`` or ``##`` heading starts a slide, a ``###`` heading or an exercise prompt
  (``**Exercise NN-name**``) a sub-slide; other markdown continues the slide (``-``), code cells
  are fragments; a slide that would grow past :data:`SLIDE_LINES` lines goes on in a sub-slide;
- skipped: verification cells (tag ``hide-input`` or collapsed in JupyterLab), written model
  answers and rubrics (nbgrader solution cells in Markdown), empty cells;
- answer cells keep their skeleton (the ``...`` placeholder) without the solution, check cells lose
  their hidden tests (``### BEGIN HIDDEN TESTS``): the decks are safe to show to a class;
- a ``slide_type`` the notebook sets itself is kept;
- no outputs (the notebooks are not executed: code cells are shown as code).

Offline, no CDN: reveal.js (the npm package ``reveal.js``, pinned at :data:`REVEAL_VERSION`, the
version nbconvert's template is written for: ``dist/reveal.js``, ``dist/theme/*.css``,
``plugin/notes/notes.js``) and MathJax 2 (the copy the site uses, ``docs/conf.py``) are copied
into ``<out>/_static/``. The template drops what nbconvert's loads from a CDN and this deck does
not need (require.js, jQuery, mermaid) and loads reveal.js with plain script tags.
reveal.js comes from ``build/vendor/`` (``npm pack`` fetches it there once; ``./make.sh slides``
installs npm with apt-get when it is missing).
"""

from __future__ import annotations

import argparse
import copy
import html
import importlib.util
import re
import shutil
import subprocess
import sys
import tarfile
from pathlib import Path

import nbformat

REPO = Path(__file__).resolve().parent.parent
REVEAL_VERSION = "4.0.2"            # nbconvert 7's reveal template: https://unpkg.com/reveal.js@4.0.2
VENDOR = REPO / "build" / "vendor"
SLIDE_LINES = 22                    # lines of text a 960 x 700 slide shows at the template's 20 px
WRAP = 80                           # characters of prose per slide line

_HIDDEN_TESTS = re.compile(r"^[ \t]*#+\s*BEGIN HIDDEN TESTS.*?^[ \t]*#+\s*END HIDDEN TESTS[^\n]*\n?", re.M | re.S)
_SOLUTION = re.compile(r"^([ \t]*)#+\s*BEGIN SOLUTION[^\n]*\n.*?^[ \t]*#+\s*END SOLUTION[^\n]*\n?", re.M | re.S)
_HEADING = re.compile(r"^(#{1,6})\s")
_EXERCISE = re.compile(r"^\*\*Exercise \d\d-[\w-]+\*\*")


# --- the shared offline assets: MathJax 2 (as the site has it) and reveal.js ------------------------

def site_conf():
    """``docs/conf.py`` as a module: its local MathJax 2 (``mathjax_source``, ``copy_mathjax``)."""
    if "lbo_site_conf" not in sys.modules:
        spec = importlib.util.spec_from_file_location("lbo_site_conf", REPO / "docs" / "conf.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules["lbo_site_conf"] = module
        spec.loader.exec_module(module)
    return sys.modules["lbo_site_conf"]


def copy_mathjax(static: Path) -> str:
    """Copy MathJax 2 into ``static/mathjax``; return the ``<script>`` tags that configure and load it.

    Inline ``$...$`` / ``\\(...\\)`` and display ``$$...$$`` / ``\\[...\\]``, typeset with the web
    font the copy ships (``HTML-CSS``, STIX-Web); MathJax asks the network for nothing.
    """
    conf = site_conf()
    source, config = conf.mathjax_source()
    if not (static / "mathjax" / "MathJax.js").exists():
        conf.copy_mathjax(source, static / "mathjax")
    return MATHJAX_TAGS.replace("{config}", config)


MATHJAX_TAGS = """<script type="text/x-mathjax-config">
MathJax.Hub.Config({
  tex2jax: {inlineMath: [["$", "$"], ["\\\\(", "\\\\)"]], displayMath: [["$$", "$$"], ["\\\\[", "\\\\]"]],
            processEscapes: true, processEnvironments: true},
  "HTML-CSS": {availableFonts: [], preferredFont: null, webFont: "STIX-Web", imageFont: null},
  messageStyle: "none"
});
</script>
<script src="{prefix}mathjax/MathJax.js?config={config},Safe"></script>"""


def reveal_source(vendor: Path = VENDOR, fetch: bool = True) -> Path:
    """The unpacked npm package ``reveal.js@REVEAL_VERSION`` in ``vendor``, fetched with ``npm pack`` if missing.

    Raises
    ------
    RuntimeError
        When it is missing and cannot be fetched (no npm, or ``fetch=False``), naming the fix.
    """
    folder = vendor / f"reveal.js-{REVEAL_VERSION}"
    needed = ["dist/reveal.js", "dist/reveal.css", "dist/theme/white.css", "plugin/notes/notes.js"]
    if all((folder / n).is_file() for n in needed):
        return folder
    npm = shutil.which("npm")
    if not fetch or npm is None:
        raise RuntimeError(f"reveal.js {REVEAL_VERSION} is not in {folder} and npm is not available: "
                           "install npm (sudo apt-get install -y npm) or run ./make.sh slides, which does.")
    vendor.mkdir(parents=True, exist_ok=True)
    done = subprocess.run([npm, "pack", f"reveal.js@{REVEAL_VERSION}", "--pack-destination", str(vendor)],
                          capture_output=True, text=True)
    tarball = vendor / f"reveal.js-{REVEAL_VERSION}.tgz"
    if done.returncode or not tarball.exists():
        raise RuntimeError(f"npm pack reveal.js@{REVEAL_VERSION} failed: {done.stderr.strip()[-500:]}")
    partial = vendor / f".reveal.js-{REVEAL_VERSION}.partial"
    shutil.rmtree(partial, ignore_errors=True)
    with tarfile.open(tarball) as archive:
        archive.extractall(partial, filter="data")
    shutil.rmtree(folder, ignore_errors=True)
    (partial / "package").rename(folder)
    shutil.rmtree(partial)
    tarball.unlink()
    missing = [n for n in needed if not (folder / n).is_file()]
    if missing:
        raise RuntimeError(f"the reveal.js package in {folder} lacks {missing}: nbconvert's template needs them")
    return folder


def copy_reveal(static: Path, vendor: Path = VENDOR) -> None:
    """reveal.js's ``dist/`` and its notes plugin into ``static/reveal.js`` (what the template loads)."""
    source = reveal_source(vendor)
    target = static / "reveal.js"
    if (target / "dist" / "reveal.js").exists():
        return
    shutil.copytree(source / "dist", target / "dist", ignore=shutil.ignore_patterns("*.map", "*.esm.js"))
    shutil.copytree(source / "plugin" / "notes", target / "plugin" / "notes", ignore=shutil.ignore_patterns("*.esm.js"))
    shutil.copy2(source / "LICENSE", target / "LICENSE")


# --- slide types from the notebook's structure -------------------------------------------------------

def _hidden(cell) -> bool:
    return "hide-input" in cell.metadata.get("tags", []) or bool(cell.metadata.get("jupyter", {}).get("source_hidden"))


def _grader(cell) -> dict:
    return cell.metadata.get("nbgrader", {})


def _lines(cell) -> int:
    """Rough height of a cell on a slide, in lines."""
    if cell.cell_type == "code":
        return len(cell.source.splitlines()) + 1
    return sum(max(1, -(-len(line) // WRAP)) for line in cell.source.splitlines() if line.strip()) + 1


def split_markdown(source: str) -> list[str]:
    """A markdown cell's text in pieces: one per heading, and an over-long piece at its paragraphs.

    Headings inside code fences or ``$$`` blocks are not headings; a paragraph is never cut.

    >>> split_markdown("# T\\n\\ntext\\n## S\\nmore")
    ['# T\\n\\ntext', '## S\\nmore']
    """
    pieces, current, fence, math = [], [], False, False
    for line in source.splitlines():
        stripped = line.strip()
        if not fence and not math and _HEADING.match(line) and any(s.strip() for s in current):
            pieces.append(current)
            current = []
        current.append(line)
        if stripped.startswith("```"):
            fence = not fence
        elif stripped.count("$$") % 2 == 1:
            math = not math
    pieces.append(current)
    out = []
    for piece in pieces:
        text = "\n".join(piece).strip("\n")
        if not text.strip():
            continue
        if _lines(nbformat.v4.new_markdown_cell(text)) <= SLIDE_LINES or "```" in text or "$$" in text:
            out.append(text)
            continue
        chunk: list[str] = []
        for para in re.split(r"\n\s*\n", text):
            candidate = "\n\n".join(chunk + [para])
            if chunk and _lines(nbformat.v4.new_markdown_cell(candidate)) > SLIDE_LINES:
                out.append("\n\n".join(chunk))
                chunk = [para]
            else:
                chunk.append(para)
        out.append("\n\n".join(chunk))
    return out


def slide_cells(nb: nbformat.NotebookNode) -> nbformat.NotebookNode:
    """A copy of ``nb`` ready for the reveal exporter: cells split, shown or skipped, each with a slide type.

    ``nb`` itself is not changed.
    """
    nb = copy.deepcopy(nb)
    nb.metadata.pop("widgets", None)
    cells = []
    for cell in nb.cells:
        grader = _grader(cell)
        if cell.cell_type == "code":
            cell.outputs, cell.execution_count = [], None
            if grader.get("solution"):
                cell.source = _SOLUTION.sub("", cell.source).rstrip()
            elif grader.get("grade"):
                cell.source = _HIDDEN_TESTS.sub("", cell.source).rstrip()
            cells.append(cell)
        elif cell.cell_type == "markdown" and not grader.get("solution"):
            explicit = cell.metadata.get("slideshow")
            for i, text in enumerate(split_markdown(cell.source)):
                piece = nbformat.v4.new_markdown_cell(text)
                if explicit and i == 0:
                    piece.metadata["slideshow"] = dict(explicit)
                cells.append(piece)
        elif cell.cell_type == "markdown":           # a written model answer and its rubric
            cell.metadata.setdefault("slideshow", {"slide_type": "skip"})
            cells.append(cell)
    height = 0
    for cell in cells:
        explicit = cell.metadata.get("slideshow", {}).get("slide_type")
        kind = explicit or _derived_type(cell, height)
        cell.metadata["slideshow"] = {"slide_type": kind}
        if kind in ("slide", "subslide"):
            height = _lines(cell)
        elif kind not in ("skip", "notes"):
            height += _lines(cell)
    # the first shown cell opens the deck
    shown = [c for c in cells if c.metadata["slideshow"]["slide_type"] not in ("skip", "notes")]
    if shown and shown[0].metadata["slideshow"]["slide_type"] in ("-", "fragment", "subslide"):
        shown[0].metadata["slideshow"]["slide_type"] = "slide"
    nb.cells = cells
    return nb


def _derived_type(cell, height: int) -> str:
    if not cell.source.strip() or (cell.cell_type == "code" and _hidden(cell)):
        return "skip"
    if cell.cell_type == "markdown":
        heading = _HEADING.match(cell.source.lstrip())
        if heading and len(heading.group(1)) <= 2:
            return "slide"
        if (heading and len(heading.group(1)) == 3) or _EXERCISE.match(cell.source.lstrip()):
            return "subslide"
    if height and height + _lines(cell) > SLIDE_LINES:
        return "subslide"
    return "fragment" if cell.cell_type == "code" else "-"


# --- the template and the export --------------------------------------------------------------------

TEMPLATE = r"""{%- extends 'index.html.j2' -%}
{#- nbconvert's reveal template, minus what it loads from a CDN: require.js, jQuery, mermaid. -#}
{%- block html_head_js -%}{%- endblock html_head_js -%}
{%- block html_head_js_mathjax -%}
LBO_MATHJAX
{%- endblock html_head_js_mathjax -%}
{%- block jupyter_widgets -%}{%- endblock jupyter_widgets -%}
{%- block notebook_css -%}
{{ super() }}
<style type="text/css">
.reveal .slides section { text-align: left; }
.reveal .jp-InputPrompt { display: none; }   /* no "In [ ]:" beside code that was never run */
/* after the theme's own rules (it comes later in the page): higher specificity */
.reveal .slides h1, .reveal .slides h2, .reveal .slides h3 { text-transform: none; }
.reveal .slides h1 { font-size: 1.7em; } .reveal .slides h2 { font-size: 1.35em; } .reveal .slides h3 { font-size: 1.15em; }
:root { --jp-code-font-size: 16px; }
.reveal .slides .highlight pre { white-space: pre-wrap; overflow-wrap: anywhere; }   /* long lines wrap, never cut */
.lbo-deck-nav { position: fixed; left: 1em; bottom: 0.6em; font-size: 14px; z-index: 30; }
</style>
{%- endblock notebook_css -%}
{% block body_footer %}
</div>
</div>
</main>
<a class="lbo-deck-nav" href="index.html">all decks</a>
</body>
{% endblock body_footer %}
{%- block footer_js -%}
<script src="{{ reveal_url_prefix }}/dist/reveal.js"></script>
<script src="{{ reveal_url_prefix }}/plugin/notes/notes.js"></script>
<script>
Reveal.initialize({
  controls: true, progress: true, history: true, slideNumber: "c/t",
  transition: "{{ reveal_transition }}", width: {{ reveal_width }}, height: {{ reveal_height }},
  plugins: [RevealNotes]
});
// A slide taller than the screen scrolls (nbconvert's own script does this with jQuery).
function lboScroll() {
  var limit = document.querySelector(".reveal").offsetHeight * 0.95;
  document.querySelectorAll("section.present > section, .slides > section.present").forEach(function (s) {
    if (s.scrollHeight > limit) { s.style.height = "95vh"; s.style.overflowY = "auto"; }
  });
}
function lboTypeset() {
  if (window.MathJax && MathJax.Hub) { MathJax.Hub.Queue(["Rerender", MathJax.Hub, Reveal.getCurrentSlide()]); }
}
Reveal.on("ready", lboScroll);
Reveal.on("slidechanged", function () { lboScroll(); lboTypeset(); });
</script>
{%- endblock footer_js -%}
"""


def exporter(mathjax_tags: str):
    """nbconvert's ``SlidesExporter`` with the offline template, reveal.js at ``_static/reveal.js``."""
    from jinja2 import DictLoader
    from nbconvert import SlidesExporter

    template = TEMPLATE.replace("LBO_MATHJAX", mathjax_tags.replace("{prefix}", "_static/"))
    return SlidesExporter(extra_loaders=[DictLoader({"lbo_slides.html.j2": template})],
                          template_file="lbo_slides.html.j2", reveal_url_prefix="_static/reveal.js",
                          reveal_theme="white", reveal_transition="none", exclude_input_prompt=True)


def title_of(nb: nbformat.NotebookNode, fallback: str) -> str:
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    return fallback


def index_html(decks: list[tuple[str, str, int]]) -> str:
    rows = "\n".join(f'<li><a href="{html.escape(f)}">{html.escape(t)}</a> <span>({n} slides)</span></li>'
                     for f, t, n in decks)
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>lbo_notebooks: lecture slides</title>
<style>body {{ font-family: sans-serif; max-width: 46em; margin: 2em auto; line-height: 1.5; }}
li span {{ color: #666; }}</style></head>
<body><h1>Lecture slides</h1>
<p>One reveal.js deck per notebook, built by <code>./make.sh slides</code> (scripts/slides.py): arrows or space
to move, <kbd>s</kbd> for the speaker view, <kbd>Esc</kbd> for the overview. Everything is local (works offline).
Exercise solutions and hidden tests are not in the decks; the solutions booklet has them.</p>
<ol>
{rows}
</ol></body></html>
"""


def default_notebooks() -> list[Path]:
    """The series, in order: ``00_start_here`` and the notebooks its map lists (as the site has it)."""
    if "lbo_build_site" not in sys.modules:
        spec = importlib.util.spec_from_file_location("lbo_build_site", REPO / "scripts" / "build_site.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules["lbo_build_site"] = module     # dataclasses look their module up there
        spec.loader.exec_module(module)
    return sys.modules["lbo_build_site"].series_notebooks(REPO / "notebooks")[0]


def build(notebooks: list[Path], out: Path, vendor: Path = VENDOR) -> list[Path]:
    """Write ``<out>/<stem>.slides.html`` for each notebook, ``<out>/index.html`` and ``<out>/_static``."""
    out.mkdir(parents=True, exist_ok=True)
    static = out / "_static"
    copy_reveal(static, vendor)
    slides = exporter(copy_mathjax(static))
    written, decks = [], []
    for path in notebooks:
        nb = slide_cells(nbformat.read(path, as_version=4))
        body, _ = slides.from_notebook_node(nb, resources={"metadata": {"name": path.stem}})
        target = out / f"{path.stem}.slides.html"
        target.write_text(body, encoding="utf-8")
        count = sum(c.metadata["slideshow"]["slide_type"] in ("slide", "subslide") for c in nb.cells)
        decks.append((target.name, title_of(nb, path.stem), count))
        written.append(target)
        print(f"{target.relative_to(out.parent) if out.parent in target.parents else target}: {count} slides", flush=True)
    (out / "index.html").write_text(index_html(decks), encoding="utf-8")
    return written


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path, help="notebooks (default: the series)")
    parser.add_argument("--out", type=Path, default=REPO / "build" / "slides", help="output folder (default build/slides)")
    args = parser.parse_args(argv)
    notebooks = [p.resolve() for p in args.notebooks] or default_notebooks()
    try:
        build(notebooks, args.out.resolve())
    except RuntimeError as exc:
        print(f"slides: {exc}", file=sys.stderr)
        return 1
    print(f"wrote {args.out / 'index.html'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
