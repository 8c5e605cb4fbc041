#!/usr/bin/env python3
"""Move the notebooks' verification cells out of the reader's way (idempotent).

Every numeric claim a notebook's prose makes is checked by a code cell of ``assert`` statements
right after it (nbval runs them all). Such a cell is test material, not part of the lesson, so it
carries the cell tag ``hide-input`` (the tag Jupyter Book and myst-nb honour) and its input is
collapsed in JupyterLab (``metadata.jupyter.source_hidden``; the reader sees a "..." bar and can
click it open). Its outputs stay visible. This script

1. tags ``hide-input`` every code cell that only verifies: its statements are ``assert``s, plus
   the simple statements they need (assignments to names, imports, ``pass``, ``del``, and
   ``for`` / ``if`` / ``with`` blocks made of the same), with at least one ``assert``;
2. collapses every code cell tagged ``hide-input`` (``"jupyter": {"source_hidden": true}``) and
   keeps its outputs shown.

A cell that prints, plots, defines a function or changes an object's state is left as it is
(tag it by hand if it should be hidden too), and so are the cells of an exercise marked for
nbgrader (answer cells and their autograded check cells: the reader works with them). Standard library only; a notebook that needs no
change is not rewritten, and a rewritten one keeps the committed layout (sorted keys, one-space
indent, as ``scripts/strip_notebook.py`` writes it).

    python3 scripts/tag_verification_cells.py              # every notebooks/*.ipynb
    python3 scripts/tag_verification_cells.py --check      # list what would change; exit 1 if anything
    python3 scripts/tag_verification_cells.py notebooks/03_laplace_beltrami.ipynb
"""

from __future__ import annotations

import argparse
import ast
import json
import sys
from pathlib import Path

TAG = "hide-input"
ROOT = Path(__file__).resolve().parent.parent


def _source(cell: dict) -> str:
    source = cell.get("source", "")
    return source if isinstance(source, str) else "".join(source)


def _simple_target(node: ast.expr) -> bool:
    if isinstance(node, ast.Name):
        return True
    if isinstance(node, ast.Starred):
        return _simple_target(node.value)
    if isinstance(node, (ast.Tuple, ast.List)):
        return all(_simple_target(e) for e in node.elts)
    return False


def _only_checks(body: list[ast.stmt]) -> bool:
    """Every statement is an assert or a simple statement an assert needs."""
    for node in body:
        if isinstance(node, (ast.Assert, ast.Import, ast.ImportFrom, ast.Pass)):
            continue
        if isinstance(node, ast.Assign) and all(_simple_target(t) for t in node.targets):
            continue
        if isinstance(node, (ast.AnnAssign, ast.AugAssign)) and _simple_target(node.target):
            continue
        if isinstance(node, ast.Delete) and all(isinstance(t, ast.Name) for t in node.targets):
            continue
        if isinstance(node, ast.For) and _simple_target(node.target) and _only_checks(node.body + node.orelse):
            continue
        if isinstance(node, ast.If) and _only_checks(node.body + node.orelse):
            continue
        if isinstance(node, ast.With) and _only_checks(node.body):
            continue
        return False
    return True


def is_verification(cell: dict) -> bool:
    """True for a code cell whose code only checks claims (see the module docstring).

    Examples
    --------
    >>> code = lambda text: {"cell_type": "code", "source": text}
    >>> is_verification(code("worst = max(d.max() for d in devs)\\nassert worst < 0.02  # poses"))
    True
    >>> is_verification(code("for name in names:\\n    assert errors[name] < 0.1, name"))
    True
    >>> is_verification(code("print(x)\\nassert x > 0"))          # shows something to the reader
    False
    >>> is_verification(code("viewer.slider.value = 5\\nassert viewer.slider.value == 5"))   # moves a widget
    False
    >>> is_verification(code("x = 1"))                            # no assert: nothing is verified
    False
    >>> check = dict(code("assert answer == 42"), metadata={"nbgrader": {"grade": True, "locked": True}})
    >>> is_verification(check)                                    # an exercise's check stays in view
    False
    """
    if cell.get("cell_type") != "code":
        return False
    nbgrader = cell.get("metadata", {}).get("nbgrader", {})
    if nbgrader.get("grade") or nbgrader.get("solution"):
        return False  # an exercise's answer or its autograded check: part of the exercise, not of the proof
    text = _source(cell)
    if any(line.lstrip().startswith(("%", "!")) for line in text.splitlines()):
        return False  # IPython magics and shell escapes are not plain Python
    try:
        tree = ast.parse(text)
    except SyntaxError:
        return False
    has_assert = any(isinstance(node, ast.Assert) for node in ast.walk(tree))
    return has_assert and _only_checks(tree.body)


def is_tagged(cell: dict) -> bool:
    return TAG in cell.get("metadata", {}).get("tags", [])


def is_collapsed(cell: dict) -> bool:
    """The cell's input is collapsed in JupyterLab and its outputs are shown."""
    jupyter = cell.get("metadata", {}).get("jupyter", {})
    return jupyter.get("source_hidden") is True and not jupyter.get("outputs_hidden", False)


def tag_and_collapse(nb: dict) -> list[str]:
    """Tag and collapse the verification cells of ``nb`` in place; return what changed, one line per cell."""
    changes = []
    for index, cell in enumerate(nb.get("cells", [])):
        if cell.get("cell_type") != "code":
            continue
        meta = cell.setdefault("metadata", {})
        if not is_tagged(cell) and is_verification(cell):
            meta.setdefault("tags", []).append(TAG)
            changes.append(f"cell {index}: tagged {TAG}")
        if is_tagged(cell) and not is_collapsed(cell):
            jupyter = meta.setdefault("jupyter", {})
            jupyter["source_hidden"] = True
            jupyter.pop("outputs_hidden", None)
            changes.append(f"cell {index}: input collapsed")
    return changes


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("notebooks", nargs="*", type=Path, help="default: notebooks/*.ipynb")
    parser.add_argument("--check", action="store_true", help="only list the changes; exit 1 if there are any")
    args = parser.parse_args(argv)
    paths = args.notebooks or sorted((ROOT / "notebooks").glob("*.ipynb"))
    pending = 0
    for path in paths:
        nb = json.loads(path.read_text(encoding="utf-8"))
        changes = tag_and_collapse(nb)
        for change in changes:
            print(f"{path.name}: {change}")
        pending += len(changes)
        if changes and not args.check:
            text = json.dumps(nb, sort_keys=True, indent=1, ensure_ascii=False) + "\n"
            path.write_text(text, encoding="utf-8")
    if args.check and pending:
        print(f"{pending} change(s) needed: run python3 scripts/tag_verification_cells.py", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
