"""open3d is imported without its Jupyter WebVisualizer hook (noise in every notebook's output)."""

import os
import subprocess
import sys

# A kernel-like interpreter: open3d's __init__ recognises Jupyter by get_ipython()'s class name.
_SCRIPT = """
import builtins, os
class ZMQInteractiveShell: pass
builtins.get_ipython = lambda: ZMQInteractiveShell()
{setup}
from lbo_notebooks._support.optional_open3d import import_open3d
o3d = import_open3d()
print("env after:", os.environ.get("OPEN3D_DISABLE_WEB_VISUALIZER"))
"""


def _run(setup: str = "") -> str:
    env = {k: v for k, v in os.environ.items() if k != "OPEN3D_DISABLE_WEB_VISUALIZER"}
    done = subprocess.run([sys.executable, "-c", _SCRIPT.format(setup=setup)], env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_no_web_visualizer_banner_in_a_kernel_and_environment_restored():
    out = _run()
    assert "WebVisualizer" not in out
    assert "env after: None" in out


def test_the_hook_itself_is_what_we_switch_off():
    # Control: importing open3d directly in the same fake kernel does print the banner, so the
    # test above would fail if import_open3d stopped switching it off.
    out = _run("import open3d")
    assert "Jupyter environment detected" in out


def test_a_users_own_setting_is_kept():
    out = _run("os.environ['OPEN3D_DISABLE_WEB_VISUALIZER'] = 'false'")
    assert "env after: false" in out


def test_dash_opens_no_comm_when_open3d_is_imported():
    # open3d imports dash, whose Jupyter helper opens a "dash" comm that JupyterLab cannot answer
    # ("Exception opening new comm"). Fresh interpreter, comm creation recorded.
    code = (
        "import comm\n"
        "opened = []\n"
        "comm.create_comm = lambda *a, **k: opened.append(k.get('target_name')) or object()\n"
        "from lbo_notebooks._support.optional_open3d import import_open3d\n"
        "import_open3d()\n"
        "import dash._jupyter\n"
        "assert 'dash' not in opened, opened\n"
        "assert dash._jupyter._dash_comm is None\n"
        "print('ok')\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0 and "ok" in result.stdout, result.stderr[-2000:]
