"""pytest set-up shared by the unit tests, the doctests and the notebooks that nbval runs.

Notebooks (``--nbval`` / ``--nbval-lax``) get two rules on top of nbval's, because nbval checks only
that a cell does not raise (``--nbval-lax``) and never looks at its stderr (issue 43, item 3):

* every cell that writes to stderr fails, with the lines it wrote: a warning a student would see
  (``DeprecationWarning``, ``UserWarning``, ...), or anything else, except the lines listed in
  :data:`HARMLESS_STDERR`, each with the reason it may stay;
* the kernel runs with ``PYTHONWARNINGS`` = :data:`KERNEL_WARNINGS`, so that a DeprecationWarning
  shows whatever module triggers it. Python hides them outside ``__main__`` (IPython shows those a
  cell's own code triggers), so without it a library call deprecated under the student's feet
  would pass the test and warn on the next release of the dependency.

tests/test_notebook_warnings.py runs small notebooks through these rules.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Iterator
from typing import Any

import pytest

# One BLAS thread for every test worker and every notebook kernel (kernels inherit this
# environment), as ./make.sh sets it, also when pytest is started directly: the problems are small
# and oversubscribed OpenBLAS makes them several times slower (README, "Threads"). A value the
# caller set is kept, so `OPENBLAS_NUM_THREADS=2 pytest ...` still tests two threads.
for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_name, "1")

#: Warning filters of every notebook kernel nbval starts (``PYTHONWARNINGS`` syntax). A value the
#: caller set in ``PYTHONWARNINGS`` is appended after it, so it takes precedence.
KERNEL_WARNINGS = "default::DeprecationWarning"

#: stderr lines a notebook cell may write without failing: pattern (``re.search`` on one line) ->
#: why it is harmless. Empty: no cell of the series writes anything a student should ignore. Add a
#: line only with its reason, never a pattern that matches "Warning".
HARMLESS_STDERR: dict[str, str] = {}


def stderr_problems(outputs: Iterable[Any], harmless: dict[str, str] | None = None) -> list[str]:
    """The lines of a cell's outputs written to stderr, except blank and known-harmless ones.

    Parameters
    ----------
    outputs : iterable of dict
        A cell's outputs as nbformat (or nbval's ``test_outputs``) holds them: stream outputs
        have ``output_type == "stream"``, ``name`` and ``text``.
    harmless : dict, optional
        Patterns to let through (default :data:`HARMLESS_STDERR`).

    Examples
    --------
    >>> out = [{"output_type": "stream", "name": "stdout", "text": "fine\\n"},
    ...        {"output_type": "stream", "name": "stderr", "text": "x.py:3: DeprecationWarning: old\\n\\n"}]
    >>> stderr_problems(out)
    ['x.py:3: DeprecationWarning: old']
    >>> stderr_problems(out, {"^x.py:3: ": "an example"})
    []
    """
    patterns = [re.compile(p) for p in (HARMLESS_STDERR if harmless is None else harmless)]
    return [line for out in outputs
            if out.get("output_type") == "stream" and out.get("name") == "stderr"
            for line in out.get("text", "").splitlines()
            if line.strip() and not any(p.search(line) for p in patterns)]


def _is_notebook_cell(item: pytest.Item) -> bool:
    try:
        from nbval.plugin import IPyNbCell
    except ImportError:  # nbval not installed: no notebook is collected
        return False
    return isinstance(item, IPyNbCell)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_setup(item: pytest.Item) -> Iterator[None]:
    """A notebook's kernel starts while its first cell is set up: with :data:`KERNEL_WARNINGS`."""
    if not _is_notebook_cell(item):
        return (yield)
    previous = os.environ.get("PYTHONWARNINGS")
    os.environ["PYTHONWARNINGS"] = KERNEL_WARNINGS + (f",{previous}" if previous else "")
    try:
        return (yield)
    finally:  # the unit tests' subprocesses keep the caller's environment
        if previous is None:
            del os.environ["PYTHONWARNINGS"]
        else:
            os.environ["PYTHONWARNINGS"] = previous


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item: pytest.Item) -> Iterator[None]:
    """A notebook cell that ran without error still fails if it wrote to stderr."""
    result = yield
    if _is_notebook_cell(item):
        problems = stderr_problems(getattr(item, "test_outputs", None) or [])
        if problems:
            item.raise_cell_error(
                "Cell wrote to stderr, which a student would see (a warning?); fix its cause, or "
                "catch an expected warning in the cell; list a harmless line in "
                "conftest.HARMLESS_STDERR with its reason",
                "\n".join(problems))
    return result
