"""Sphinx configuration of the site ``./make.sh site`` builds (``scripts/build_site.py``).

Why Sphinx + myst-nb + numpydoc, and not Jupyter Book: it is the stack of the scientific-Python
projects this library is read against (NumPy, SciPy, scikit-learn document their API with autodoc,
autosummary and numpydoc on the PyData theme), and the API reference needs exactly autodoc and
numpydoc. Jupyter Book 1 was a configuration layer over these same Sphinx extensions and is
superseded; Jupyter Book 2 is built on MyST-MD, a Node.js tool without autodoc or numpydoc. myst-nb
renders the notebooks; it does not execute them (``nb_execution_mode = "off"``): the builder has
already run them with the site prelude (``scripts/site_prelude.py``), which myst-nb has no
equivalent for (plotly figures that need only the page's own plotly.js, sliders as plotly frames).

Everything the pages load is in the site (it works offline, from ``file://`` or a static host):

- the PyData theme ships its fonts and scripts; Sphinx's search runs in the page on
  ``searchindex.js``;
- formulas are typeset by MathJax 2 copied into ``_static/mathjax`` from the Python package
  ``jupyter-server-mathjax`` (``LBO_SITE_MATHJAX`` names another local MathJax 2 folder, e.g.
  Debian's ``/usr/share/javascript/mathjax``); Sphinx's default MathJax comes from a CDN;
- plotly figures call ``Plotly.newPlot`` on the one ``_static/plotly.min.js`` copied from the
  installed plotly; ``_static/lazy_plotly.js`` draws each figure only when it comes near the
  viewport and releases the WebGL contexts of 3D figures far from it (a page may hold more 3D
  scenes than the browser keeps contexts for).

The source folder is the one ``scripts/build_site.py`` assembles (the executed notebooks under
``notebooks/``, ``docs/*.md`` under ``docs/``, ``index.md``, ``reference.rst``); this folder is
only the configuration (``sphinx-build -c docs``), its templates and its stylesheet.
"""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

# Document the package of this checkout, whatever else the environment has installed.
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

project = "lbo_notebooks"
author = "lbo_notebooks contributors"
copyright = "the lbo_notebooks contributors (MIT licence)"
html_title = "lbo_notebooks"

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
]
exclude_patterns = ["_clean", ".doctrees", "**/.ipynb_checkpoints"]
# Absolute: autosummary looks templates up relative to the source folder, Sphinx's HTML builder
# relative to this one, and the two differ (``sphinx-build -c docs``).
templates_path = [str(Path(__file__).resolve().parent / "_templates")]
html_static_path = ["_static"]
html_css_files = ["site.css"]
# Not deferred: each figure's inline script calls Plotly.newPlot as the page is parsed, and
# lazy_plotly.js wraps it first, so that only figures near the viewport are drawn (a browser keeps
# only so many WebGL contexts, one per 3D scene; Chromium 16): see the comment at its top.
html_js_files = ["plotly.min.js", "lazy_plotly.js"]
html_theme = "pydata_sphinx_theme"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    # The page's table of contents, not "edit this page" / "show source" links; none beside a
    # notebook (see html_sidebars).
    "secondary_sidebar_items": {"docs/*": ["page-toc"], "docs/lecturers/*": ["page-toc"], "generated/*": ["page-toc"], "reference": ["page-toc"]},
    "footer_start": ["copyright"],
    "footer_end": [],
    "header_links_before_dropdown": 6,
}
# Light unless the reader switches: the figures are drawn on white. (The theme's template needs a
# value: without one its script logs "Got invalid theme mode" as a console error on a first visit.)
html_context = {"default_mode": "light"}
# No sidebars beside a notebook: its 3D figures need the page's width (three scenes side by side
# clip in the theme's reading column); the header, the Previous/Next links and the index navigate.
# The landing page lists the notebooks itself.
html_sidebars = {"index": [], "notebooks/*": []}
html_show_sourcelink = False
html_copy_source = False

# Notebooks: rendered as executed by scripts/build_site.py, never executed again here.
nb_execution_mode = "off"
nb_ipywidgets_js = {}                 # no require.js / widget manager from a CDN (no widget state is kept)
nb_merge_streams = True
# The exercises' feedback carries a machine-readable mime type beside its HTML (the page shows the
# HTML); myst-nb's Sphinx parser renders every type before choosing and warns on ones it cannot.
suppress_warnings = ["mystnb.unknown_mime_type"]
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_dmath_double_inline = True      # $$...$$ inside a paragraph, as Jupyter renders it
myst_heading_anchors = 3

# API reference: autosummary writes a page per public name (reference.rst), numpydoc renders the
# docstrings' Parameters / Returns / Examples sections.
autosummary_generate = True
autodoc_typehints = "none"            # the numpydoc sections say the types, in words
numpydoc_show_class_members = False   # the class template documents them (autodoc :members:)
numpydoc_class_members_toctree = False
numpydoc_validation_checks: set[str] = set()

# MathJax 2, local. myst-parser's MathJax override targets MathJax 3/4 configurations: off.
MATHJAX_CONFIGS = ["TeX-AMS_CHTML-full", "TeX-AMS-MML_HTMLorMML-full"]   # best first
DEBIAN_MATHJAX = Path("/usr/share/javascript/mathjax")
myst_update_mathjax = False
mathjax2_config = {
    # Typeset with the web fonts shipped in the copy (jupyter-server-mathjax ships STIX-Web only),
    # never ask the network for others.
    "HTML-CSS": {"availableFonts": [], "preferredFont": None, "webFont": "STIX-Web", "imageFont": None},
    "messageStyle": "none",
    "tex2jax": {"inlineMath": [["\\(", "\\)"]], "displayMath": [["\\[", "\\]"]], "processEscapes": True},
}


def installed_mathjax() -> Path | None:
    """MathJax 2 shipped by the ``jupyter-server-mathjax`` package, if installed."""
    try:
        import jupyter_server_mathjax
    except ImportError:
        return None
    return Path(jupyter_server_mathjax.__file__).parent / "static"


def mathjax_source(folder: str | None = None) -> tuple[Path, str]:
    """The local MathJax 2 folder and the configuration to load from it.

    ``folder`` (or ``LBO_SITE_MATHJAX``) names one; by default the ``jupyter-server-mathjax``
    package's copy, else Debian's ``libjs-mathjax``. A site that loaded MathJax from the network
    would show raw LaTeX offline, so there is no network fallback: no MathJax is an error.
    """
    folder = folder or os.environ.get("LBO_SITE_MATHJAX")
    candidates = [Path(folder)] if folder else [p for p in (installed_mathjax(), DEBIAN_MATHJAX) if p is not None]
    source = next((p for p in candidates if (p / "MathJax.js").exists()), None)
    if source is None:
        where = f"{folder}: no MathJax.js there" if folder else "no MathJax 2 installed"
        raise RuntimeError(f"{where}. Install it with: pip install jupyter-server-mathjax "
                           "(part of the [docs] extra, which ./make.sh site installs).")
    config = next((c for c in MATHJAX_CONFIGS if (source / "config" / f"{c}.js").exists()), None)
    if config is None:
        raise RuntimeError(f"{source}: none of the MathJax configurations {MATHJAX_CONFIGS} is there.")
    return source, config


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


_MATHJAX, _MATHJAX_CONFIG = mathjax_source()
mathjax_path = f"mathjax/MathJax.js?config={_MATHJAX_CONFIG},Safe"   # relative to _static


def _copy_assets(app) -> None:
    """plotly.js and MathJax into the site's ``_static`` (before any page refers to them)."""
    if app.builder.format != "html":
        return
    import plotly.offline

    static = Path(app.outdir) / "_static"
    static.mkdir(parents=True, exist_ok=True)
    (static / "plotly.min.js").write_text(plotly.offline.get_plotlyjs(), encoding="utf-8")
    copy_mathjax(_MATHJAX, static / "mathjax")


def _top_level() -> set[str]:
    import lbo_notebooks

    return {name for name in lbo_notebooks.__all__ if name not in lbo_notebooks._SUBMODULES}


def _skip_top_level_names(app, what, name, obj, skip, options):
    """A folder's page does not document again what has a page of its own at the top level, so that
    a search finds one entry (``lbo_notebooks.spectral_mds``), not two."""
    return True if what == "module" and name in _top_level() else None


def _link_top_level_names(app, what, name, obj, options, lines):
    """...and links those names instead, after the folder's docstring."""
    if what != "module" or not name.startswith("lbo_notebooks.") or name.count(".") != 1:
        return
    here = [n for n in getattr(obj, "__all__", ()) if n in _top_level()]
    if here:
        lines += ["", "Also in this folder, each on its own page: "
                  + ", ".join(f":obj:`~lbo_notebooks.{n}`" for n in here) + ".", ""]


def setup(app):
    app.connect("builder-inited", _copy_assets)
    app.connect("autodoc-skip-member", _skip_top_level_names)
    app.connect("autodoc-process-docstring", _link_top_level_names)
    return {"parallel_read_safe": True}
