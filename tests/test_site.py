"""scripts/build_site.py without executing notebooks: the index text and the offline MathJax copy.

(The pages themselves are built and opened in a real browser, with the network blocked, by
tests/browser/test_jupyterlab.py::test_static_site.)
"""

import importlib.util
import sys
from pathlib import Path

import nbformat
import pytest

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def site():
    spec = importlib.util.spec_from_file_location("build_site", REPO / "scripts" / "build_site.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules["build_site"] = module          # dataclasses look their module up there
    spec.loader.exec_module(module)
    yield module
    del sys.modules["build_site"]


def _read(stem):
    return nbformat.read(REPO / "notebooks" / f"{stem}.ipynb", as_version=4)


def test_index_describes_each_notebook_by_its_topic_from_the_series_map(site):
    topics = site.series_map(_read("00_start_here"))
    notebooks = sorted(p.stem for p in (REPO / "notebooks").glob("[0-9][0-9]_*.ipynb") if p.stem != "00_start_here")
    # Every notebook of the series has a row in the map (the index's description comes from it).
    assert set(notebooks) <= set(topics), set(notebooks) - set(topics)
    for stem in notebooks:
        nb = _read(stem)
        title, description = site.title_and_description(nb, topics[stem])
        assert title.startswith(stem[:2] + " ·") and description == topics[stem]
        first_bullet = next(ln for ln in nb.cells[0].source.splitlines() if ln.startswith("- "))
        assert description not in first_bullet


def test_a_notebook_outside_the_map_falls_back_to_its_stated_aim_never_to_a_bullet(site):
    inline = nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell(
        "# 00 · Start\n\n**What you will learn**: how to read the series.\n")])
    assert site.title_and_description(inline) == ("00 · Start", "how to read the series")
    listed = nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell(
        "# 11 · Topic\n\n**What you will learn**\n- one detail;\n- another.\n")])
    assert site.title_and_description(listed) == ("11 · Topic", "")


def test_index_markdown_keeps_tex_intact(site):
    topic = r"the top generalized eigenvectors of $(A X X^\top A - \mu W)\,p = \sigma A p$, *fast* & <safe>"
    out = site.markdown_inline(topic)
    assert r"$(A X X^\top A - \mu W)\,p = \sigma A p$" in out          # the `W),p` bug: \, was eaten
    assert "<em>fast</em> &amp; &lt;safe&gt;" in out
    assert site.markdown_inline("$a < b$") == "$a &lt; b$"             # escaped for HTML, MathJax reads it back


def test_mathjax_is_copied_from_an_installed_package(site, tmp_path):
    source = site.installed_mathjax()
    if source is None:
        pytest.fail("jupyter-server-mathjax is a [test] dependency: pip install jupyter-server-mathjax")
    url = site.mathjax_setting(tmp_path, None)
    assert not url.startswith(("http:", "https:", "//"))
    path, config = url.split("?config=")
    assert (tmp_path / path).is_file()
    for name in config.split(","):
        assert (tmp_path / "mathjax" / "config" / f"{name}.js").is_file()
    copied = tmp_path / "mathjax"
    assert (copied / "jax" / "input" / "TeX").is_dir() and (copied / "localization" / "en").is_dir()
    assert not (copied / "jax" / "output" / "SVG").exists()          # never loaded by the pages
    with pytest.raises(SystemExit, match="pip install jupyter-server-mathjax"):
        site.mathjax_setting(tmp_path / "other", str(tmp_path / "no-such-folder"))
