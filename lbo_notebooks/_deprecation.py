"""Deprecation shims: old spellings keep working for one release and say what to write instead.

Two tools, used by every module that renamed something:

* :func:`renamed` — a decorator for renamed keyword arguments and for arguments that became
  keyword-only (passing them by position still works, with a warning);
* :func:`moved` — a module ``__getattr__`` for public names that moved to another module.

Each emits a ``DeprecationWarning`` whose message names the new spelling.

Every warning the package emits goes through :func:`warn`, which points it at the user's line:
the first frame outside the package, however many of the package's own frames (a deprecation
wrapper, a dispatcher) lie in between. A fixed ``stacklevel`` counts frames by hand and goes
stale as soon as a decorator is added (the robust-Laplacian warning pointed at this module).
"""

from __future__ import annotations

import functools
import importlib
import os
import sys
import warnings
from typing import Any, Callable, Mapping, Sequence, TypeVar

F = TypeVar("F", bound=Callable[..., Any])

__all__ = ["renamed", "moved", "warn"]


_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def _in_package(filename: str) -> bool:
    return os.path.abspath(filename).startswith(_PACKAGE)


def warn(message: str, category: type[Warning] = DeprecationWarning) -> None:
    """Emit a warning attributed to the first caller outside the package (the user's line).

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     warn("careful", UserWarning)
    >>> caught[0].filename.endswith(".py"), caught[0].category.__name__
    (False, 'UserWarning')
    """
    frame = sys._getframe(1)  # the package function that called warn
    level = 2  # warnings.warn's stacklevel of that frame
    while frame.f_back is not None and _in_package(frame.f_code.co_filename):
        frame = frame.f_back
        level += 1
    warnings.warn(message, category, stacklevel=level)


def renamed(
    arguments: Mapping[str, str] | None = None, *, keyword_only: Sequence[str] = (), n_positional: int | None = None
) -> Callable[[F], F]:
    """Decorator: accept old argument spellings with a ``DeprecationWarning``.

    Parameters
    ----------
    arguments : mapping old name -> new name
        Renamed keyword arguments. Passing both spellings raises ``ValueError``.
    keyword_only : sequence of str
        New names of the arguments that used to be positional, in their old order, after the
        first ``n_positional`` arguments. Extra positional values are mapped onto them.
    n_positional : int, optional
        How many arguments are still positional (required with ``keyword_only``).

    Examples
    --------
    >>> import warnings
    >>> @renamed({"n": "k"})
    ... def head(items, k=2):
    ...     return items[:k]
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     head([1, 2, 3], n=1)
    [1]
    >>> print(caught[0].category.__name__, caught[0].message)
    DeprecationWarning head(n=...) is deprecated: use head(k=...) instead.
    """
    old_to_new = dict(arguments or {})
    if keyword_only and n_positional is None:
        raise ValueError("renamed(keyword_only=...) needs n_positional, the number of arguments still positional.")

    def decorate(func: F) -> F:
        name = func.__name__

        @functools.wraps(func)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            if keyword_only and len(args) > n_positional:  # type: ignore[operator]
                extra = args[n_positional:]
                if len(extra) > len(keyword_only):
                    raise TypeError(f"{name}() takes at most {n_positional + len(keyword_only)} arguments, got {len(args)}.")
                args = args[:n_positional]
                for new, value in zip(keyword_only, extra):
                    if new in kwargs:
                        raise TypeError(f"{name}() got multiple values for argument {new!r}.")
                    kwargs[new] = value
                spelled = ", ".join(f"{new}=..." for new in keyword_only[: len(extra)])
                warn(f"passing {spelled} to {name}() by position is deprecated: pass {spelled} by keyword.")
            for old, new in old_to_new.items():
                if old in kwargs:
                    if new in kwargs:
                        raise ValueError(f"{name}() got both {old}= (old spelling) and {new}=; pass only {new}=.")
                    warn(f"{name}({old}=...) is deprecated: use {name}({new}=...) instead.")
                    kwargs[new] = kwargs.pop(old)
            return func(*args, **kwargs)

        return wrapper  # type: ignore[return-value]

    return decorate


def moved(module: str, names: Mapping[str, str]) -> Callable[[str], Any]:
    """A module ``__getattr__`` resolving names that moved elsewhere, with a warning.

    ``names`` maps an old name of ``module`` to ``"package.module:new_name"``.

    Examples
    --------
    >>> import warnings
    >>> getattr_ = moved("old_place", {"dumps": "json:dumps"})
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     getattr_("dumps")([1])
    '[1]'
    """

    def __getattr__(name: str) -> Any:
        if name not in names:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        where, new = names[name].split(":")
        warn(f"{module}.{name} has moved: use {where}.{new} instead.")
        return getattr(importlib.import_module(where), new)

    return __getattr__
