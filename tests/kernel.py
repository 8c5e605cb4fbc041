"""Run a cell of code in a fresh Jupyter kernel, as a notebook would (for tests of what a notebook shows)."""

from __future__ import annotations

import pytest


def cell_outputs(code: str, timeout: int = 300) -> list[dict]:
    """The outputs of ``code`` run as the one cell of a notebook in a fresh ``python3`` kernel.

    Skips the test when nbformat or nbclient is not installed.
    """
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(code)])
    nbclient.NotebookClient(nb, timeout=timeout, kernel_name="python3").execute()
    return nb.cells[0].outputs


def is_widget(output: dict) -> bool:
    """Whether a cell output is a Jupyter widget (a tqdm bar in a notebook is one)."""
    return "application/vnd.jupyter.widget-view+json" in output.get("data", {})
