#!/usr/bin/env python
"""Print the import graph of the lbo_notebooks package; fail on cycles and on private imports.

Reads the source with ``ast`` (nothing is imported, so it runs anywhere in milliseconds). Every
relative import counts, at module level or inside a function (a lazy import is still a
dependency). Two rules:

* no cycle between modules (``a`` imports ``b`` imports ... ``a``);
* no private name (``_x``) imported from another module; private *modules* such as
  ``_open3d`` are allowed, they exist to be imported inside the package;
* every relative import resolves to a module of the package (a moved module is caught here).

Usage: ``python scripts/import_graph.py [package_dir]``. Exit status 1 on a violation.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path


def module_name(path: Path, root: Path) -> str:
    parts = path.relative_to(root).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts) or "__init__"


def resolve(current: str, is_package: bool, level: int, target: str | None) -> str:
    base = current.split(".") if current != "__init__" else []
    if not is_package:
        base = base[:-1]
    if level > 1:
        base = base[: len(base) - (level - 1)]
    return ".".join(base + ([target] if target else [])) or "__init__"


def graph(root: Path) -> tuple[dict[str, set[str]], list[str]]:
    """Edges module -> imported modules (inside the package) and the bad imports (private or unresolved)."""
    files = {module_name(p, root): p for p in sorted(root.rglob("*.py"))}
    edges: dict[str, set[str]] = {name: set() for name in files}
    private: list[str] = []
    for name, path in files.items():
        is_package = path.name == "__init__.py"
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if not isinstance(node, ast.ImportFrom) or node.level == 0:
                continue
            target = resolve(name, is_package, node.level, node.module)
            for alias in node.names:
                sub = f"{target}.{alias.name}" if target != "__init__" else alias.name
                dep = sub if sub in files else target  # "from . import x" imports module x
                if dep in files and dep != name:
                    edges[name].add(dep)
                elif dep not in files:
                    private.append(f"{name} imports {alias.name} from {target}, which is not a module of the package")
                if dep == target and alias.name.startswith("_") and not alias.name.startswith("__"):
                    private.append(f"{name} imports private name {alias.name} from {target}")
    return edges, private


def cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Elementary cycles found by depth-first search (each reported once, from its smallest node)."""
    found: list[list[str]] = []

    def visit(start: str, node: str, path: list[str]) -> None:
        for nxt in sorted(edges.get(node, ())):
            if nxt == start:
                found.append(path + [start])
            elif nxt > start and nxt not in path:
                visit(start, nxt, path + [nxt])

    for start in sorted(edges):
        visit(start, start, [start])
    return found


def main(argv: list[str]) -> int:
    root = Path(argv[1]) if len(argv) > 1 else Path(__file__).resolve().parents[1] / "lbo_notebooks"
    edges, private = graph(root)
    width = max(map(len, edges))
    for name in sorted(edges):
        print(f"{name:<{width}} -> {', '.join(sorted(edges[name])) or '-'}")
    found = cycles(edges)
    for cycle in found:
        print("CYCLE: " + " -> ".join(cycle))
    for line in private:
        print("BAD IMPORT: " + line)
    print(f"{len(edges)} modules, {sum(map(len, edges.values()))} imports, {len(found)} cycles, {len(private)} bad imports")
    return 1 if found or private else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
