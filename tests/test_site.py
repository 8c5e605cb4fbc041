"""scripts/build_site.py without executing notebooks: the index text and the offline MathJax copy.

(The pages themselves are built and opened in a real browser, with the network blocked, by
tests/browser/test_jupyterlab.py::test_static_site.)
"""

import importlib.util
import re
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


def test_the_site_is_exactly_the_series(site, tmp_path):
    series, skipped = site.series_notebooks(REPO / "notebooks")
    stems = [p.stem for p in series]
    assert stems[0] == "00_start_here" and stems[1:] == sorted(stems[1:]) and len(stems) >= 10
    assert all(site.SERIES_NAME.match(s) for s in stems)
    # Strays beside the series: a scratch notebook, JupyterLab's copy, a student's new edition,
    # a numbered notebook the map does not list.
    for name in ("00_start_here", "01_shapes"):
        (tmp_path / f"{name}.ipynb").write_bytes((REPO / "notebooks" / f"{name}.ipynb").read_bytes())
    for stray in ("scratch", "01_shapes-Copy1", "01_shapes.new", "42_lecture_draft"):
        nbformat.write(nbformat.v4.new_notebook(), tmp_path / f"{stray}.ipynb")
    series, skipped = site.series_notebooks(tmp_path)
    assert [p.stem for p in series] == ["00_start_here", "01_shapes"]            # the map's others are absent here
    assert sorted(p.stem for p in skipped) == ["01_shapes-Copy1", "01_shapes.new", "42_lecture_draft", "scratch"]
    (tmp_path / "00_start_here.ipynb").unlink()                                    # no map: the NN_name notebooks
    assert [p.stem for p in site.series_notebooks(tmp_path)[0]] == ["01_shapes", "42_lecture_draft"]


def test_build_executes_and_lists_only_the_series(site, tmp_path, monkeypatch, capsys):
    repo = tmp_path / "repo"
    (repo / "notebooks").mkdir(parents=True)
    cell = nbformat.v4.new_markdown_cell
    nbformat.write(nbformat.v4.new_notebook(cells=[cell("# 00 · Start\n\n| 01 | [one](01_one.ipynb) | the first topic |")]),
                   repo / "notebooks" / "00_start_here.ipynb")
    nbformat.write(nbformat.v4.new_notebook(cells=[cell("# 01 · One")]), repo / "notebooks" / "01_one.ipynb")
    nbformat.write(nbformat.v4.new_notebook(cells=[cell("# My scratch")]), repo / "notebooks" / "scratch.ipynb")
    executed = []
    monkeypatch.setattr(site, "REPO", repo)
    monkeypatch.setattr(site, "execute", lambda nb, cwd, timeout: executed.append(nb.cells[0].source.splitlines()[0]))
    out = tmp_path / "site"
    assert site.main(["--out", str(out)]) == 0
    assert executed == ["# 00 · Start", "# 01 · One"]
    index = (out / "index.html").read_text()
    assert "01 · One" in index and "the first topic" in index and "scratch" not in index.lower()
    assert sorted(p.name for p in out.glob("*.html")) == ["00_start_here.html", "01_one.html", "index.html"]
    assert sorted(p.name for p in (out / "notebooks").iterdir()) == ["00_start_here.ipynb", "01_one.ipynb"]
    assert "skipped: scratch.ipynb" in capsys.readouterr().out


def test_pages_show_no_hidden_tests_and_fold_the_solutions(site):
    nb = _read("04_your_own_data")
    answers = [c for c in nb.cells if c.metadata.get("nbgrader", {}).get("solution")]
    checks = [c for c in nb.cells if c.metadata.get("nbgrader", {}).get("grade")]
    assert answers and checks and all("BEGIN HIDDEN TESTS" in c.source for c in checks)
    answers[0].outputs = [nbformat.v4.new_output("stream", name="stdout", text="{'printed': 'by the solution'}\n")]
    site.prepare_for_html(nb)
    page = site.render(nb, "mathjax/MathJax.js?config=TeX-AMS_CHTML-full,Safe", "03")
    assert "HIDDEN TESTS" not in page and "assert feedback.correct" not in page
    assert "BEGIN SOLUTION" not in page and "END SOLUTION" not in page
    assert "check_repair_counts" in page                                       # the check call is shown
    # Every solution, and what it printed, sits inside a <details> block, opened on purpose.
    blocks = re.findall(r'<details class="lbo-solutions">.*?</details>', page, re.S)
    folded, outside = "".join(blocks), re.sub(r'<details class="lbo-solutions">.*?</details>', "", page, flags=re.S)
    assert folded.count("<summary>Solution (click to show)</summary>") == len(answers)
    assert "by the solution" in folded and "by the solution" not in outside
    assert "&quot;polygons_split&quot;: 1" in folded or '"polygons_split": 1' in folded
    assert "unreferenced_vertices&quot;: 10" not in outside and '"unreferenced_vertices": 10' not in outside
