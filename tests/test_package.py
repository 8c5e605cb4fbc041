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
