"""scripts/build_site.py and docs/conf.py: the series, the index, the reference page and a small
real Sphinx build (a reference page and a notebook page, without executing anything).

(The whole site is built and opened in a real browser, with the network blocked, by
tests/browser/test_jupyterlab.py::test_static_site.)
"""

import importlib.util
import inspect
import re
import sys
from pathlib import Path

import nbformat
import pytest

import lbo_notebooks

REPO = Path(__file__).resolve().parents[1]


def _load(name, path):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module          # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def site():
    yield _load("build_site", REPO / "scripts" / "build_site.py")
    del sys.modules["build_site"]


@pytest.fixture(scope="module")
def conf():
    yield _load("lbo_sphinx_conf", REPO / "docs" / "conf.py")
    del sys.modules["lbo_sphinx_conf"]


def _read(stem):
    return nbformat.read(REPO / "notebooks" / f"{stem}.ipynb", as_version=4)


def test_index_describes_each_notebook_by_its_topic_from_the_series_map(site):
    topics = site.series_map(_read("00_start_here"))
    notebooks = [p.stem for p in site.series_notebooks(REPO / "notebooks")[0] if p.stem != "00_start_here"]
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


def test_the_site_is_exactly_the_series(site, tmp_path):
    series, skipped = site.series_notebooks(REPO / "notebooks")
    stems = [p.stem for p in series]
    assert stems[0] == "00_start_here" and stems[1:] == sorted(stems[1:]) and len(stems) >= 10
    assert all(site.SERIES_NAME.match(s) for s in stems)
    # Strays beside the series: a scratch notebook, JupyterLab's copy, a student's new edition,
    # a numbered notebook the map does not list.
    first = stems[1]
    for name in ("00_start_here", first):
        (tmp_path / f"{name}.ipynb").write_bytes((REPO / "notebooks" / f"{name}.ipynb").read_bytes())
    for stray in ("scratch", f"{first}-Copy1", f"{first}.new", "42_lecture_draft"):
        nbformat.write(nbformat.v4.new_notebook(), tmp_path / f"{stray}.ipynb")
    series, skipped = site.series_notebooks(tmp_path)
    assert [p.stem for p in series] == ["00_start_here", first]            # the map's others are absent here
    assert sorted(p.stem for p in skipped) == sorted([f"{first}-Copy1", f"{first}.new", "42_lecture_draft", "scratch"])
    (tmp_path / "00_start_here.ipynb").unlink()                           # no map: the NN_name notebooks
    assert [p.stem for p in site.series_notebooks(tmp_path)[0]] == sorted([first, "42_lecture_draft"])


def test_the_reference_lists_every_public_name_once(site):
    names = site.public_names()
    assert names == list(lbo_notebooks.__all__) and "eigenbasis" in names
    page = site.reference_page(names)
    listed = re.findall(r"^   (\w+)$", page, re.M)
    assert sorted(listed) == sorted(names)
    objects, modules = page.split("Modules\n-------")
    for name in names:
        is_module = inspect.ismodule(getattr(lbo_notebooks, name))
        assert re.search(rf"^   {name}$", modules if is_module else objects, re.M), name


def test_build_executes_and_lists_only_the_series(site, tmp_path, monkeypatch, capsys):
    repo = tmp_path / "repo"
    (repo / "notebooks").mkdir(parents=True)
    (repo / "docs").mkdir()
    (repo / "docs" / "glossary.md").write_text("# Glossary\n")
    cell = nbformat.v4.new_markdown_cell
    nbformat.write(nbformat.v4.new_notebook(cells=[cell("# 00 · Start\n\n| 01 | [one](01_one.ipynb) | the topic, $\\lambda_n\\,p$ |")]),
                   repo / "notebooks" / "00_start_here.ipynb")
    nbformat.write(nbformat.v4.new_notebook(cells=[cell("# 01 · One")]), repo / "notebooks" / "01_one.ipynb")
    nbformat.write(nbformat.v4.new_notebook(cells=[cell("# My scratch")]), repo / "notebooks" / "scratch.ipynb")
    executed, rendered = [], []
    monkeypatch.setattr(site, "REPO", repo)
    monkeypatch.setattr(site, "execute", lambda nb, cwd, timeout: executed.append(nb.cells[0].source.splitlines()[0]))
    monkeypatch.setattr(site, "public_names", lambda: ["eigenbasis", "shapes"])
    monkeypatch.setattr(site, "run_sphinx", lambda src, out: rendered.append(src) or 0)
    out = tmp_path / "site"
    assert site.main(["--out", str(out)]) == 0
    assert executed == ["# 00 · Start", "# 01 · One"]
    src = rendered[0]
    assert sorted(p.name for p in (src / "notebooks").iterdir()) == ["00_start_here.ipynb", "01_one.ipynb", "index.md"]
    assert sorted(p.name for p in (src / "_clean").iterdir()) == ["00_start_here.ipynb", "01_one.ipynb"]
    assert [p.name for p in (src / "docs").iterdir()] == ["glossary.md"]
    index = (src / "index.md").read_text()
    assert "[**01 · One**](notebooks/01_one.ipynb)" in index and "the topic, $\\lambda_n\\,p$" in index
    assert "{download}`01_one.ipynb <_clean/01_one.ipynb>`" in index
    assert "scratch" not in index.lower() and "\nreference\ndocs/glossary\n" in index
    toc = (src / "notebooks" / "index.md").read_text()
    assert toc.index("00_start_here") < toc.index("01_one")
    assert "   eigenbasis\n" in (src / "reference.rst").read_text()
    assert "skipped: scratch.ipynb" in capsys.readouterr().out
    # A second build replaces the first; a folder that is not a site build is never emptied.
    (out / ".buildinfo").write_text("")
    assert site.main(["--out", str(out), "--no-reference"]) == 0 and not (rendered[1] / "reference.rst").exists()
    with pytest.raises(SystemExit, match="not a previous site build"):
        site.main(["--out", str(repo)])
    # A build interrupted while executing (no index.md yet) does not block the next one.
    (rendered[1] / "index.md").unlink()
    assert site.main(["--out", str(out), "--no-reference"]) == 0


def test_mathjax_is_found_locally_and_copied_without_what_pages_never_load(conf, tmp_path):
    source, config = conf.mathjax_source()
    assert (source / "MathJax.js").is_file() and (source / "config" / f"{config}.js").is_file()
    assert conf.mathjax_path == f"mathjax/MathJax.js?config={config},Safe"
    conf.copy_mathjax(source, tmp_path / "mathjax")
    copied = tmp_path / "mathjax"
    assert (copied / "jax" / "input" / "TeX").is_dir() and (copied / "localization" / "en").is_dir()
    assert not (copied / "jax" / "output" / "SVG").exists()          # never loaded by the pages
    with pytest.raises(RuntimeError, match="pip install jupyter-server-mathjax"):
        conf.mathjax_source(str(tmp_path / "no-such-folder"))


@pytest.fixture(scope="module")
def small_site(site, tmp_path_factory):
    """Sphinx run on a reference for two names and notebook 03 as stored (answer cells, checks
    with hidden tests; nothing executed), with a printed output planted in its first answer."""
    src = tmp_path_factory.mktemp("src")
    out = src.parent / "site"
    nb = _read("04_your_own_data")
    answers = [c for c in nb.cells if c.metadata.get("nbgrader", {}).get("solution") and c.cell_type == "code"]
    checks = [c for c in nb.cells if c.metadata.get("nbgrader", {}).get("grade") and c.cell_type == "code"]
    assert answers and checks and all("BEGIN HIDDEN TESTS" in c.source for c in checks)
    answers[0].outputs = [nbformat.v4.new_output("stream", name="stdout", text="{'printed': 'by the solution'}\n")]
    site.prepare_for_html(nb)
    (src / "notebooks").mkdir()
    nbformat.write(nb, src / "notebooks" / "04_your_own_data.ipynb")
    (src / "reference.rst").write_text(site.reference_page(["eigenbasis", "Spectrum", "shapes"]))
    (src / "index.md").write_text("# Test\n\n```{toctree}\nreference\nnotebooks/04_your_own_data\n```\n")
    assert site.run_sphinx(src, out) == 0
    return out, len(answers)


def test_a_reference_page_shows_the_docstring_sections(small_site):
    out, _ = small_site
    page = (out / "generated" / "lbo_notebooks.eigenbasis.html").read_text()
    text = re.sub(r"<[^>]+>", " ", page)
    assert "Parameters" in text and "Returns" in text and "Examples" in text
    for name in inspect.signature(lbo_notebooks.eigenbasis).parameters:
        assert re.search(rf"\b{name}\b", text), name
    # A module's page documents its members; a class's page its methods and properties.
    shapes_page = (out / "generated" / "lbo_notebooks.shapes.html").read_text()
    assert 'id="lbo_notebooks.shapes.icosphere"' in shapes_page
    # ...but not again what has a top-level page (one search hit per name): it is linked instead.
    assert 'id="lbo_notebooks.shapes.creature"' not in shapes_page and "creature_poses" in shapes_page
    assert 'id="lbo_notebooks.Spectrum.project"' in (out / "generated" / "lbo_notebooks.Spectrum.html").read_text()
    assert "lbo_notebooks.eigenbasis" in (out / "searchindex.js").read_text()    # the search finds it


def test_pages_load_nothing_from_the_network(small_site):
    out, _ = small_site
    assert (out / "_static" / "plotly.min.js").is_file() and (out / "_static" / "mathjax" / "MathJax.js").is_file()
    for page in [out / "index.html", out / "search.html", *out.glob("*/*.html")]:
        loads = re.findall(r'<(?:script|link|img)\b[^>]*?\b(?:src|href)="([^"]+)"', page.read_text())
        assert loads and not [u for u in loads if re.match(r"(https?:)?//", u)], (page, loads)


def test_pages_show_no_hidden_tests_and_fold_the_solutions(small_site):
    out, n_answers = small_site
    page = (out / "notebooks" / "04_your_own_data.html").read_text()
    assert "HIDDEN TESTS" not in page and "assert feedback.correct" not in page
    assert "BEGIN SOLUTION" not in page and "END SOLUTION" not in page
    assert "check_repair_counts" in page                                       # the check call is shown
    # Every solution, and what it printed, sits inside a <details> block, opened on purpose.
    blocks = re.findall(r'<details class="lbo-solutions">.*?</details>', page, re.S)
    folded, outside = "".join(blocks), re.sub(r'<details class="lbo-solutions">.*?</details>', "", page, flags=re.S)
    assert folded.count("<summary>Solution (click to show)</summary>") == n_answers
    assert "by the solution" in folded and "by the solution" not in outside
    # The written answers' model answers and rubrics are folded too (04 has two).
    written = re.findall(r"<details><summary>Model answer and rubric</summary>.*?</details>", page, re.S)
    assert len(written) == 2 and all("Rubric" in w for w in written)
    assert "Rubric (2 points)" not in re.sub(r"<details>.*?</details>", "", outside, flags=re.S)
    assert "&quot;polygons_split&quot;: 1" in folded or '"polygons_split": 1' in folded
    assert "unreferenced_vertices&quot;: 10" not in outside and '"unreferenced_vertices": 10' not in outside
    # Cells collapsed in JupyterLab (the verification cells) are folded by myst-nb.
    assert "hide-input" in page and "Show code cell source" in page
