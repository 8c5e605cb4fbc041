"""The git clean filter (scripts/strip_notebook.py) that keeps run notebooks out of git."""

import doctest
import importlib.util
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent
SCRIPT = REPO / "scripts" / "strip_notebook.py"
NOTEBOOKS = sorted((REPO / "notebooks").glob("*.ipynb"))


def _filter(data: bytes) -> bytes:
    return subprocess.run([sys.executable, str(SCRIPT)], input=data, capture_output=True, check=True).stdout


def _as_if_run(path: Path) -> bytes:
    """The notebook as JupyterLab saves it after a run: outputs, counts, widget state, versions."""
    nb = json.loads(path.read_text(encoding="utf-8"))
    for i, cell in enumerate(nb["cells"]):
        if cell["cell_type"] == "code":
            cell["execution_count"] = i + 1
            cell["outputs"] = [{"output_type": "stream", "name": "stdout", "text": ["λ = 2.0\n"]}]
            cell["metadata"]["scrolled"] = True
            cell["metadata"]["execution"] = {"iopub.status.busy": "2026-01-01T00:00:00"}
    nb["metadata"]["language_info"] = {"name": "python", "version": "3.11.7", "mimetype": "text/x-python"}
    nb["metadata"]["widgets"] = {"application/vnd.jupyter.widget-state+json": {"state": {}}}
    return json.dumps(nb, indent=1, ensure_ascii=False).encode("utf-8")  # unsorted keys, no newline


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.name for p in NOTEBOOKS])
def test_committed_notebooks_pass_unchanged_and_run_ones_come_back_to_them(path):
    committed = path.read_bytes()
    assert _filter(committed) == committed
    run = _as_if_run(path)
    assert run != committed and _filter(run) == committed


def test_text_that_is_not_json_passes_through():
    conflict = b"<<<<<<< HEAD\n{}\n=======\n{}\n>>>>>>> theirs\n"
    assert _filter(conflict) == conflict


@pytest.mark.skipif(shutil.which("git") is None, reason="needs git")
def test_git_status_stays_clean_after_a_run(tmp_path):
    def git(*args):
        return subprocess.run(["git", "-C", str(tmp_path), *args], capture_output=True, text=True, check=True).stdout

    git("init", "-q")
    git("config", "user.email", "t@example.org")
    git("config", "user.name", "t")
    git("config", "filter.strip-notebook.clean", f"{sys.executable} {SCRIPT}")
    shutil.copy(REPO / ".gitattributes", tmp_path)
    shutil.copy(NOTEBOOKS[0], tmp_path / "n.ipynb")
    git("add", ".")
    git("commit", "-qm", "clean notebook")
    (tmp_path / "n.ipynb").write_bytes(_as_if_run(NOTEBOOKS[0]))
    assert git("diff", "--stat") == ""  # git sees no change in content...
    # ...but `git status` trusts the file size and says "M" until the entry is refreshed by
    # `git add`, which stores nothing new; then a `git pull` can update the notebook.
    git("add", "n.ipynb")
    assert git("status", "--porcelain") == ""
    assert git("show", ":n.ipynb").encode("utf-8") == NOTEBOOKS[0].read_bytes()
    assert b'"output_type": "stream"' in (tmp_path / "n.ipynb").read_bytes()  # the outputs stay on disk


def test_docstring_examples():
    spec = importlib.util.spec_from_file_location("strip_notebook", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    result = doctest.testmod(module)
    assert result.attempted > 0 and result.failed == 0
