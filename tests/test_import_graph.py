"""scripts/import_graph.py: the package has no import cycle and no cross-module private import."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[1] / "scripts" / "import_graph.py"


def run(package: Path | None = None) -> subprocess.CompletedProcess[str]:
    args = [sys.executable, str(SCRIPT)] + ([str(package)] if package else [])
    return subprocess.run(args, capture_output=True, text=True, timeout=60)


def test_the_package_is_clean():
    result = run()
    assert result.returncode == 0, result.stdout
    assert "0 cycles, 0 bad imports" in result.stdout
    assert re.search(r"^inner_product +-> -$", result.stdout, re.M)  # the algebra depends on nothing else


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
