"""The one way the package emits a warning: attributed to the user's line.

Every warning the package emits goes through :func:`warn`, which points it at the first frame
outside the package, however many of the package's own frames (a wrapper, a dispatcher) lie in
between. A fixed ``stacklevel`` counts frames by hand and goes stale as soon as a wrapper is
added (the robust-Laplacian warning once pointed inside the package).
"""

from __future__ import annotations

import os
import sys
import warnings

__all__ = ["warn"]


_PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep  # lbo_notebooks/


def _in_package(filename: str) -> bool:
    return os.path.abspath(filename).startswith(_PACKAGE)


def warn(message: str, category: type[Warning]) -> None:
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
