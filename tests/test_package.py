import importlib
import subprocess
import sys

import pytest

import lbo_notebooks as lbo


def test_import_is_light():
    code = (
        "import sys, lbo_notebooks as lbo, lbo_notebooks.spectral;"
        "heavy = [m for m in ('open3d', 'plotly', 'ipywidgets', 'skimage', 'gpytoolbox', 'potpourri3d', 'igl', 'matplotlib', 'tqdm') if m in sys.modules];"
        "print(','.join(heavy))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "", f"import lbo_notebooks pulled in {out}"


@pytest.mark.parametrize("name", lbo.__all__)
def test_every_public_name_resolves(name):
    value = getattr(lbo, name)
    if name in lbo._SUBMODULES:
        assert value is importlib.import_module(f"lbo_notebooks.{name}")
    else:  # the very object of the module that _EXPORTS names, documented there
        module = importlib.import_module(f"lbo_notebooks.{lbo._WHERE[name]}")
        assert value is getattr(module, name) and name in module.__all__


def test_unknown_attribute():
    with pytest.raises(AttributeError, match="no attribute"):
        lbo.not_a_function  # noqa: B018
    with pytest.raises(AttributeError):
        lbo.shapes.not_a_shape  # noqa: B018


def _declared_names() -> dict[str, list[str]]:
    """Public name -> the modules whose ``__all__`` lists it (read with ast, nothing imported)."""
    import ast
    from pathlib import Path

    root = Path(lbo.__file__).parent
    homes: dict[str, list[str]] = {}
    for path in sorted(root.rglob("*.py")):
        if path == root / "__init__.py":
            continue  # the lazy front door: its __all__ is computed from _EXPORTS
        module = ".".join(path.relative_to(root).with_suffix("").parts)
        if module.startswith("spectral._engine"):
            continue  # private: its names are public only through lbo_notebooks.spectral
        for node in ast.parse(path.read_text()).body:
            targets = [t.id for t in getattr(node, "targets", [getattr(node, "target", None)]) if isinstance(t, ast.Name)]
            if "__all__" in targets and isinstance(node.value, (ast.List, ast.Tuple)):
                names = ast.literal_eval(node.value)
            elif "_EXPORTS" in targets:  # a lazy front door: module -> names
                names = [name for group in ast.literal_eval(node.value).values() for name in group]
            else:
                continue
            for name in names:
                homes.setdefault(name, []).append(module)
    return homes


def test_no_public_name_has_two_homes():
    """Issue 27: one ``__all__`` per public name.

    A subpackage's ``__init__`` presenting the names of its own modules (``analyses``,
    ``geometry._formats``) is its front door, not a second home; the top-level ``lbo_notebooks``
    front door is lazy (``_EXPORTS``) and checked by test_every_public_name_resolves.
    """

    def front_door(modules: list[str]) -> bool:
        """One home (the deepest module) and, above it, only the front doors of its own packages."""
        home = max(modules, key=lambda m: (m.count("."), not m.endswith(".__init__")))
        doors = [m for m in modules if m != home]
        return all(m.endswith(".__init__") and home.startswith(m[: -len("__init__")]) for m in doors)

    twice = {name: modules for name, modules in _declared_names().items() if len(modules) > 1 and not front_door(modules)}
    assert not twice, twice


def test_no_module_is_over_600_lines():
    """Issue 27: one concept per module, at most 600 lines each."""
    from pathlib import Path

    root = Path(lbo.__file__).parent
    sizes = {str(p.relative_to(root)): len(p.read_text().splitlines()) for p in root.rglob("*.py")}
    over = {name: n for name, n in sizes.items() if n > 600}
    assert not over, f"split these by concept: {over}"


def test_the_library_points_into_benchmarks_at_most_five_times():
    """Issue 42, item 5: measurements live in benchmarks/, the library text points there at most 5 times."""
    from pathlib import Path

    root = Path(lbo.__file__).parent
    pointers = [f"{p.relative_to(root)}:{i}" for p in root.rglob("*.py")
                for i, line in enumerate(p.read_text().splitlines(), 1) if "benchmarks/" in line]
    assert len(pointers) <= 5, pointers


def test_every_public_docstring_parses_as_numpydoc():
    """A malformed docstring (a section twice, a section inside another) drops the name from the
    site's reference table; numpydoc's parser says so here, without building the site."""
    import inspect

    docscrape = pytest.importorskip("numpydoc.docscrape")
    import lbo_notebooks as lbo

    for name in lbo.__all__:
        value = getattr(lbo, name)
        if inspect.ismodule(value):
            continue
        parse = docscrape.ClassDoc if inspect.isclass(value) else docscrape.FunctionDoc
        parse(value)  # raises ValueError on a repeated or misplaced section
