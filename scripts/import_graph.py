#!/usr/bin/env python
"""Print the import graph of the lbo_notebooks package; fail on cycles, wrong-way and private imports.

Reads the source with ``ast`` (nothing is imported, so it runs anywhere in milliseconds). Every
relative import counts, at module level or inside a function (a lazy import is still a
dependency). The rules:

* no cycle between modules (``a`` imports ``b`` imports ... ``a``);
* every module sits in one of the :data:`LAYERS` below, and imports only from its own layer or
  from layers under it (a module that is in no layer is a violation too: place it);
* no private name (``_x``) imported from another module; private *modules* such as
  ``_open3d`` are allowed, they exist to be imported inside the package;
* every relative import resolves to a module of the package (a moved module is caught here).

It also prints the number of *levels*: the longest chain of imports, counted in modules (a module
that imports nothing from the package is on level 1, a module importing it on level 2, ...), and
fails when there are more than :data:`MAX_LEVELS`.

Usage: ``python scripts/import_graph.py [package_dir]``. Exit status 1 on a violation.
"""

from __future__ import annotations

import ast
import fnmatch
import sys
from functools import lru_cache
from pathlib import Path

#: The house, bottom to top: (layer, what it holds, module patterns). A module may import from its
#: own layer and from the layers under it, never from a layer above.
LAYERS: list[tuple[str, str, tuple[str, ...]]] = [
    ("support", "tools every layer uses: warnings, argument checks, optional open3d, progress bars",
     ("_support", "_support.*")),
    ("geometry", "the mesh and point cloud, files in and out, repair", ("geometry", "geometry.*")),
    ("operators", "which (W, A) for an input: cotangent, robust (tufted, point cloud), curvature metric |K|^alpha",
     ("operators", "operators.*")),
    ("inner products", "the A-inner-product algebra (the first floor of the spectral folder: its engine uses it)",
     ("spectral._mass_products", "spectral._inner_product")),
    ("engine", "the private eigensolver: factorisations, Krylov, the sliced solver, the thread policy; "
     "sparse matrices in, never a mesh", ("spectral._engine", "spectral._engine.*")),
    ("spectral", "the solver services over the engine, the Spectrum and eigenbasis",
     ("spectral", "spectral.*")),
    ("analyses", "what the course computes with a spectrum or a mesh", ("analyses", "analyses.*")),
    ("shapes and pictures", "procedural test shapes, the creatures, plotting",
     ("shapes", "shapes.*", "plotting", "plotting.*")),
    ("lessons", "the exercises of the notebooks; the package's lazy front door", ("exercises", "exercises.*", "__init__")),
]

#: Goal for the number of levels (the longest import chain, in modules).
MAX_LEVELS = 8


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


def layer_of(module: str) -> int | None:
    """Index of the layer holding ``module`` (None when no layer lists it)."""
    for index, (_, _, patterns) in enumerate(LAYERS):
        if any(fnmatch.fnmatchcase(module, pattern) for pattern in patterns):
            return index
    return None


def wrong_way(edges: dict[str, set[str]]) -> list[str]:
    """Imports that go up the layers, and modules in no layer."""
    bad = [f"{name} is in no layer: add it to LAYERS in scripts/import_graph.py" for name in sorted(edges)
           if layer_of(name) is None]
    for name in sorted(edges):
        here = layer_of(name)
        for dep in sorted(edges[name]):
            there = layer_of(dep)
            if here is not None and there is not None and there > here:
                bad.append(f"{name} ({LAYERS[here][0]}) imports {dep} ({LAYERS[there][0]}), a layer above it")
    return bad


def levels(edges: dict[str, set[str]]) -> tuple[int, list[str]]:
    """Length in modules of the longest import chain, and one such chain (top first); needs no cycle."""

    @lru_cache(maxsize=None)
    def chain(node: str) -> tuple[str, ...]:
        below = [chain(dep) for dep in sorted(edges.get(node, ()))]
        return (node,) + max(below, key=len, default=())

    longest = max((chain(name) for name in sorted(edges)), key=len, default=())
    return len(longest), list(longest)


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
    against = wrong_way(edges)
    for line in against:
        print("LAYER: " + line)
    too_high = False
    if not found:
        depth, longest = levels(edges)
        too_high = depth > MAX_LEVELS
        print(f"{'TOO HIGH: ' if too_high else ''}longest chain ({depth} levels, at most {MAX_LEVELS}): {' -> '.join(longest)}")
    print(f"{len(edges)} modules, {sum(map(len, edges.values()))} imports, {len(found)} cycles, {len(private)} bad imports, "
          f"{len(against)} layer violations")
    return 1 if found or private or against or too_high else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
