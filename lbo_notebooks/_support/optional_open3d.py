"""Import open3d on demand and explain, in words a user can act on, why it failed.

Only the display needs open3d (decimating large meshes for plotting, in
:mod:`lbo_notebooks.plotting`); reading and writing mesh files, binary PLY and STL included, is
done with NumPy and plyfile (:mod:`lbo_notebooks.geometry._formats`), so a machine without open3d's system
libraries (a grading machine, a slim image) still loads and saves meshes.

open3d is a compiled package linked against a few system libraries that a bare Debian/Ubuntu
machine (or a slim Docker image) does not have. Its import then fails deep inside the
extension loader with ``libusb-1.0.so.0: cannot open shared object file``, which says nothing
about how to fix it. :func:`import_open3d` turns that into an :class:`ImportError` that names
the missing library and the ``apt-get`` command that installs it.
"""

from __future__ import annotations

import os
import re
from types import ModuleType

__all__ = ["import_open3d", "SYSTEM_PACKAGES"]

# Shared library (as named in the loader's error) -> Debian/Ubuntu package that provides it.
SYSTEM_PACKAGES: dict[str, str] = {
    "libusb-1.0.so.0": "libusb-1.0-0",
    "libGL.so.1": "libgl1",
    "libEGL.so.1": "libegl1",
    "libgomp.so.1": "libgomp1",
    "libX11.so.6": "libx11-6",
}
_ALL_PACKAGES = "libusb-1.0-0 libgl1 libegl1"
_LIBRARY = re.compile(r"(lib[\w.+-]*\.so[\w.]*)")


def _load() -> ModuleType:
    # Inside a Jupyter kernel open3d's __init__ prints "Jupyter environment detected. Enabling
    # Open3D WebVisualizer." and starts a WebRTC visualiser whose comm JupyterLab cannot open
    # ("Exception opening new comm" in the browser console). We draw with plotly, so switch that
    # hook off through the variable open3d reads, unless the user has set it, and restore it.
    key = "OPEN3D_DISABLE_WEB_VISUALIZER"
    previous = os.environ.get(key)
    if previous is None:
        os.environ[key] = "true"
    try:
        _import_dash_without_its_comm()
        import open3d
    finally:
        if previous is None:
            os.environ.pop(key, None)
    return open3d


def _import_dash_without_its_comm() -> None:
    # open3d imports dash, whose Jupyter helper opens a "dash" comm at import time; JupyterLab has
    # no handler for it and logs "Exception opening new comm". We never run a dash app, so dash's
    # helper is imported with comm creation answered by None, which dash itself treats as "no
    # Jupyter comm available". Nothing changes if dash is absent or was imported already.
    import sys

    if "dash._jupyter" in sys.modules:
        return
    try:
        import comm
    except ImportError:
        return
    create = comm.create_comm
    comm.create_comm = lambda *args, **kwargs: None
    try:
        import dash._jupyter  # noqa: F401
    except ImportError:
        pass
    finally:
        comm.create_comm = create


def import_open3d() -> ModuleType:
    """Return the ``open3d`` module, or raise an ImportError that says how to make it importable.

    Returns
    -------
    module
        The imported ``open3d`` package.

    Raises
    ------
    ImportError
        If open3d is not installed (the message gives the ``pip`` command) or if a system
        library it links against is missing (the message names the library and gives the
        ``apt-get install`` command, e.g. ``libusb-1.0-0`` for ``libusb-1.0.so.0``).

    Examples
    --------
    >>> o3d = import_open3d()
    >>> hasattr(o3d, "io")
    True
    """
    try:
        return _load()
    except ModuleNotFoundError as exc:
        if exc.name not in (None, "open3d"):
            raise _explain(exc) from exc
        raise ImportError(
            "open3d is not installed; it decimates large meshes for display (reading and writing "
            "mesh files do not need it). "
            "Install it with `pip install open3d` (it is a dependency of lbo-notebooks)."
        ) from exc
    except (ImportError, OSError) as exc:
        raise _explain(exc) from exc


def _explain(exc: BaseException) -> ImportError:
    text = str(exc)
    match = _LIBRARY.search(text)
    if match:
        library = match.group(1)
        package = SYSTEM_PACKAGES.get(library)
        if package is None:
            fix = (
                f"install the system package that provides {library} (on Debian/Ubuntu "
                f"`apt-file search {library}` finds it); open3d usually needs "
                f"`sudo apt-get install {_ALL_PACKAGES}`"
            )
        else:
            fix = (
                f"install it with `sudo apt-get install {package}` (open3d needs "
                f"`sudo apt-get install {_ALL_PACKAGES}` on a bare Debian/Ubuntu machine)"
            )
        return ImportError(
            f"open3d cannot be imported because the system library {library} is missing: {fix}. "
            f"Original error: {text}"
        )
    return ImportError(
        f"open3d is installed but failed to import ({type(exc).__name__}: {text}). On a bare "
        f"Debian/Ubuntu machine run `sudo apt-get install {_ALL_PACKAGES}`; otherwise reinstall "
        "it with `pip install --force-reinstall open3d`."
    )
