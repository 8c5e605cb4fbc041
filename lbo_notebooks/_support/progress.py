"""Progress bars for long calls: shown where someone watches, silent in logs and tests.

One rule for every long public call that takes a ``progress`` argument:

* ``progress=True``: always show a bar (tqdm's, on stderr, or a widget in a notebook);
* ``progress=False``: never;
* ``progress=None`` (the default): show one only if the call is long (the caller decides, e.g.
  from the problem size) *and* someone is watching: in a Jupyter kernel, or in a terminal
  (stderr is a TTY). Output redirected to a log file, CI, and pytest (which captures stderr) get
  nothing.

``tqdm.auto`` picks the widget bar inside a Jupyter kernel (``ipykernel`` imported and ipywidgets
installed) and the text bar elsewhere; the text bar's ``disable=None`` is tqdm's own "only on a
TTY" rule, and the widget bar always shows, which is what a notebook wants. tqdm is imported only
when a bar is asked for, so ``import lbo_notebooks`` stays fast.
"""

from __future__ import annotations

from typing import Any

from .validation import Satisfies

#: Calls on meshes of this many vertices or more are long enough for a bar by default.
LARGE_MESH = 10_000


#: The ``progress`` argument's constraint, for a function's ``@validated`` table: a Python ``bool`` or None.
PROGRESS = Satisfies(lambda progress: isinstance(progress, bool), none=True, message=(
    "{name} must be True (always show a progress bar), False (never) or None (only for long "
    "calls in a notebook or a terminal), got {value!r}."))


def progress_bar(total: int, desc: str, progress: bool | None, *, long: bool = True) -> Any:
    """A tqdm bar of ``total`` steps (``update``, ``set_postfix_str``, ``close``; a context manager).

    Parameters
    ----------
    total : int
        Number of steps.
    desc : str
        Label shown before the bar.
    progress : bool or None
        ``True``: show; ``False``: a silent bar (every method is a no-op); ``None``: show only if
        ``long`` and someone watches (a Jupyter kernel, or stderr on a TTY).
    long : bool, default True
        Whether the call is long enough to deserve a bar by default (only read with ``None``).
    """
    from tqdm.auto import tqdm

    if progress is None:
        disable = None if long else True  # None: tqdm shows a text bar only on a TTY
    else:
        disable = not progress
    return tqdm(total=total, desc=desc, disable=disable, leave=False)
