import importlib
import subprocess
import sys

import pytest

import lbo_notebooks as lbo


def test_import_is_light():
    code = (
        "import sys, lbo_notebooks as lbo, lbo_notebooks.spectrum;"
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
        if module.startswith("_engine"):
            continue  # private: its names are public only through lbo_notebooks.solvers
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
                for name in ast.literal_eval(node.value):
                    homes.setdefault(name, []).append(module)
    return homes


def test_no_public_name_has_two_homes():
    """Issue 27: one ``__all__`` per public name.

    A subpackage's ``__init__`` presenting the names of its own modules (``plotting``,
    ``exercises``) is its front door, not a second home; the top-level ``lbo_notebooks``
    front door is lazy (``_EXPORTS``) and checked by test_every_public_name_resolves.
    """

    def front_door(modules: list[str]) -> bool:
        packages = [m for m in modules if m.endswith(".__init__") and m != "__init__"]
        return len(modules) == 2 and len(packages) == 1 and all(m.startswith(packages[0][: -len("__init__")]) for m in modules)

    twice = {name: modules for name, modules in _declared_names().items() if len(modules) > 1 and not front_door(modules)}
    assert not twice, twice


def test_no_module_is_over_600_lines():
    """Issue 27: one concept per module, at most 600 lines each."""
    from pathlib import Path

    root = Path(lbo.__file__).parent
    sizes = {str(p.relative_to(root)): len(p.read_text().splitlines()) for p in root.rglob("*.py")}
    over = {name: n for name, n in sizes.items() if n > 600}
    assert not over, f"split these by concept: {over}"


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
