"""conftest.py's notebook rule (issue 43, item 3): a cell that writes to stderr fails its nbval test.

Two tiny notebooks run through ``pytest --nbval-lax`` in a fresh process, with the repository's
conftest.py copied beside them (the very hooks ``./make.sh test`` uses): one warns in three ways a
student would see, one does not.
"""

from __future__ import annotations

import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parent.parent
KERNEL = {"kernelspec": {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"},
          "language_info": {"name": "python"}}

# A library module whose DeprecationWarning points into itself (stacklevel 1): Python hides it
# unless the kernel's filters show DeprecationWarnings from every module (conftest.KERNEL_WARNINGS).
OLD_LIBRARY = '''
import warnings


def old_call():
    warnings.warn("old_call is deprecated", DeprecationWarning, stacklevel=1)
    return 1
'''

WARNS = [
    "import warnings\n\nwarnings.warn('old', DeprecationWarning)",  # from the cell (__main__)
    "import old_library\n\nold_library.old_call()",  # from a library module
    "import sys\n\nprint('something went wrong', file=sys.stderr)",  # stderr without a warning
    "print('all is well')",  # stdout only: passes
]
CLEAN = [
    "import warnings\n\nwith warnings.catch_warnings(record=True) as caught:\n"
    "    warnings.simplefilter('always')\n    warnings.warn('expected', UserWarning)\n"
    "print(len(caught), 'warning caught and read')",
    "import old_library\n\nwith warnings.catch_warnings():\n"
    "    warnings.simplefilter('ignore', DeprecationWarning)\n    old_library.old_call()",
]


def _notebook(path: Path, sources: list[str]) -> None:
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(s) for s in sources], metadata=KERNEL)
    nbformat.validate(nb)
    nbformat.write(nb, path)


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory) -> dict[tuple[str, int], str]:
    folder = tmp_path_factory.mktemp("nbval_warnings")
    shutil.copy(ROOT / "conftest.py", folder / "conftest.py")
    (folder / "old_library.py").write_text(OLD_LIBRARY)
    _notebook(folder / "warns.ipynb", WARNS)
    _notebook(folder / "clean.ipynb", CLEAN)
    run = subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:dash", "-p", "no:cacheprovider", "--nbval-lax", "-v",
         "-rf", "warns.ipynb", "clean.ipynb"],
        cwd=folder, capture_output=True, text=True, timeout=300,
    )
    # -v lines, "warns.ipynb::Cell 0 FAILED" (nbval 0.11 prints "warns::ipynb::Cell 0 FAILED")
    found = {(f"{stem}.ipynb", int(cell)): result for stem, cell, result in
             re.findall(r"^(\w+)(?:\.|::)ipynb::Cell (\d+) (PASSED|FAILED|ERROR)", run.stdout, re.MULTILINE)}
    assert len(found) == len(WARNS) + len(CLEAN), run.stdout[-3000:] + run.stderr[-3000:]
    return {**found, "output": run.stdout}


def test_a_warning_from_the_cell_fails(outcomes):
    assert outcomes["warns.ipynb", 0] == "FAILED"
    assert "Cell wrote to stderr" in outcomes["output"] and "DeprecationWarning: old" in outcomes["output"]


def test_a_deprecation_inside_a_library_is_shown_and_fails(outcomes):
    assert outcomes["warns.ipynb", 1] == "FAILED"
    assert "old_call is deprecated" in outcomes["output"]


def test_any_stderr_output_fails(outcomes):
    assert outcomes["warns.ipynb", 2] == "FAILED" and "something went wrong" in outcomes["output"]


def test_cells_without_stderr_pass(outcomes):
    assert outcomes["warns.ipynb", 3] == "PASSED"
    assert outcomes["clean.ipynb", 0] == "PASSED" and outcomes["clean.ipynb", 1] == "PASSED"


def _conftest():
    spec = importlib.util.spec_from_file_location("repository_conftest", ROOT / "conftest.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_harmless_lines_are_listed_with_a_reason():
    conftest = _conftest()
    assert all(isinstance(reason, str) and reason.strip() for reason in conftest.HARMLESS_STDERR.values())
    assert not any(re.search(p, "x.py:1: DeprecationWarning: old") for p in conftest.HARMLESS_STDERR)
    out = [{"output_type": "stream", "name": "stderr", "text": "harmless note\nreal problem\n\n"},
           {"output_type": "stream", "name": "stdout", "text": "not stderr\n"},
           {"output_type": "display_data", "data": {"text/plain": "Warning in a figure title"}}]
    assert conftest.stderr_problems(out, {r"^harmless note$": "a test"}) == ["real problem"]
    assert conftest.stderr_problems(out, {}) == ["harmless note", "real problem"]
