"""scripts/import_graph.py: the package has no import cycle, no wrong-way import between layers, and no
cross-module private import."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[1] / "scripts" / "import_graph.py"
PACKAGE = Path(__file__).resolve().parents[1] / "lbo_notebooks"


def run(package: Path | None = None) -> subprocess.CompletedProcess[str]:
    args = [sys.executable, str(SCRIPT)] + ([str(package)] if package else [])
    return subprocess.run(args, capture_output=True, text=True, timeout=60)


def test_the_package_is_clean():
    result = run()
    assert result.returncode == 0, result.stdout
    assert "0 cycles, 0 bad imports, 0 layer violations" in result.stdout
    levels = int(re.search(r"^longest chain \((\d+) levels", result.stdout, re.M).group(1))
    assert levels <= 8, result.stdout  # issue 27: at most 8 floors
    # The kernels the engine shares with the A-inner-product algebra import nothing from the package;
    # the algebra itself only the argument checks.
    assert re.search(r"^spectral\._mass_products +-> -$", result.stdout, re.M)
    assert re.search(r"^spectral\._inner_product +-> _support\.validation, spectral\._mass_products$", result.stdout, re.M)


def test_a_planted_cycle_and_private_import_are_caught(tmp_path):
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "a.py").write_text("from .b import thing\n")
    (package / "b.py").write_text("def thing():\n    from .a import _helper\n    from .gone import x\n")
    result = run(package)
    assert result.returncode == 1
    assert "CYCLE: a -> b -> a" in result.stdout
    assert "BAD IMPORT: b imports private name _helper from a" in result.stdout
    assert "BAD IMPORT: b imports x from gone, which is not a module of the package" in result.stdout


def _copy_of_the_package(tmp_path: Path) -> Path:
    copy = tmp_path / "lbo_notebooks"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    return copy


def test_a_planted_wrong_way_import_is_caught(tmp_path):
    """The data layer importing a shape (a layer above it) fails the script, naming both layers."""
    copy = _copy_of_the_package(tmp_path)
    assert run(copy).returncode == 0  # the copy itself is clean
    mesh = copy / "geometry" / "_mesh.py"
    mesh.write_text(mesh.read_text() + "\n\ndef _planted():\n    from ..shapes import icosphere\n\n    return icosphere\n")
    result = run(copy)
    assert result.returncode == 1
    assert "LAYER: geometry._mesh (geometry) imports shapes (shapes and pictures), a layer above it" in result.stdout
    assert "1 layer violations" in result.stdout


def test_a_module_in_no_layer_is_caught(tmp_path):
    copy = _copy_of_the_package(tmp_path)
    (copy / "newcomer.py").write_text("from .geometry._mesh import Mesh\n")
    result = run(copy)
    assert result.returncode == 1
    assert "LAYER: newcomer is in no layer: add it to LAYERS in scripts/import_graph.py" in result.stdout


def test_a_chain_of_more_than_eight_levels_fails(tmp_path):
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "__init__.py").write_text("")
    names = [f"m{i}" for i in range(10)]
    for name, below in zip(names, [None] + names):
        (package / f"{name}.py").write_text(f"from .{below} import x\n" if below else "x = 1\n")
    result = run(package)
    assert result.returncode == 1
    assert "TOO HIGH: longest chain (10 levels, at most 8): m9 -> m8" in result.stdout


def test_the_engine_is_private_and_takes_no_mesh():
    """Issue 42: at most three modules outside the engine import it; the engine imports nothing
    from geometry (no Mesh, no PointCloud), although its layer stands above it."""
    result = run()
    edges = {
        line.split("->")[0].strip(): {dep.strip() for dep in line.split("->")[1].split(",")}
        for line in result.stdout.splitlines()
        if " -> " in line and not line.startswith(("longest", "TOO HIGH", "CYCLE"))
    }
    engine = {name for name in edges if name == "spectral._engine" or name.startswith("spectral._engine.")}
    importers = {name for name, deps in edges.items() if name not in engine and deps & engine}
    assert len(importers) <= 3, importers
    assert not any(dep.startswith("geometry") for name in engine for dep in edges[name])
