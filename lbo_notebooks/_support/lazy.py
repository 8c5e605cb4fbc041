"""Front doors that load on first use: a package's public names, imported when first asked for."""

from __future__ import annotations

import importlib
from typing import Any, Callable, Iterable

__all__ = ["front_door"]


def front_door(
    package: str, exports: dict[str, tuple[str, ...]], modules: Iterable[str] = ()
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """``__getattr__`` and ``__dir__`` for ``package``, whose public names live in its modules.

    ``exports`` maps a module of the package (``"_mesh"``) to the names it holds; ``modules`` are
    subpackages handed out themselves (the top level's ``geometry``, ``shapes``, ...). A name is
    imported on first access and then kept in the package's namespace, so that importing one
    subpackage never imports the rest, and a lower layer may import a module of a package whose
    other modules stand above it.

    Examples
    --------
    >>> __getattr__, __dir__ = front_door("lbo_notebooks.geometry", {"_mesh": ("Mesh",)})
    >>> __getattr__("Mesh").__name__
    'Mesh'
    """
    where = {name: module for module, names in exports.items() for name in names}
    modules = frozenset(modules)
    namespace = importlib.import_module(package).__dict__

    def __getattr__(name: str) -> Any:
        if name in modules:
            return importlib.import_module(f".{name}", package)  # binds itself on the package
        if name not in where:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f".{where[name]}", package), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(where) | modules)

    return __getattr__, __dir__
