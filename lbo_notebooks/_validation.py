"""Argument checks: one mechanism for "an integer in a range" and "a number in a range".

Every public function checks its arguments and raises ``ValueError`` with a message that names the
argument, what it must be, what was passed and, where it helps, what to pass instead. The test of
the value (``True`` is not an integer here, although ``bool`` subclasses ``int``; NumPy integers
and floats are accepted; NaN and infinity are not numbers in a range) is written once, below; the
message is built from the same parts everywhere:

    {name} must be {what}, got {value!r}[; {hint}].

What it must be reads as the bounds state it ("an integer in 2..300", "an integer >= 3", "a
positive integer") or as the caller words it (``what=``), so that messages stay specific: "k must be an integer
between 1 and the number of vertices (642), got 0." The idea is scikit-learn's declared parameter
constraints, kept to the two checks this package needs.

Examples
--------
>>> check_integer(5, "k", 1)
5
>>> check_integer(True, "k", 1)
Traceback (most recent call last):
...
ValueError: k must be a positive integer, got True.
>>> check_number(2.0, "tol", 0, 1, what="a number between 0 and 1 (e.g. 1e-10)")
Traceback (most recent call last):
...
ValueError: tol must be a number between 0 and 1 (e.g. 1e-10), got 2.0.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["is_integer", "is_number", "check_integer", "check_number"]


def is_integer(value: Any) -> bool:
    """True for Python and NumPy integers, False for ``bool`` (``True`` is not a count).

    Examples
    --------
    >>> is_integer(3), is_integer(np.int32(3)), is_integer(True), is_integer(3.0)
    (True, True, False, False)
    """
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def is_number(value: Any) -> bool:
    """True for finite real Python and NumPy numbers, not ``bool``.

    Examples
    --------
    >>> is_number(0.5), is_number(np.float32(2)), is_number(float("nan")), is_number(False), is_number("1")
    (True, True, False, False, False)
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        return False
    return math.isfinite(value)


def _described(low: float | None, high: float | None, open_low: bool, open_high: bool, integer: bool) -> str:
    """What the value must be, from its bounds: "a positive integer", "an integer in 2..300", "a number in (0, 1)"."""
    kind = "integer" if integer else "number"
    if high is None and integer and low == 1:
        return "a positive integer"
    if high is None and low == 0:
        return f"a positive {kind}" if open_low else f"a non-negative {kind}"
    article = "an integer" if integer else "a number"
    if low is not None and high is not None:
        if integer:
            return f"{article} in {low}..{high}"
        return f"{article} in {'(' if open_low else '['}{low:g}, {high:g}{')' if open_high else ']'}"
    if low is not None:
        return f"{article} {'>' if open_low else '>='} {low:g}"
    if high is not None:
        return f"{article} {'<' if open_high else '<='} {high:g}"
    return article


def _fail(name: str, what: str, value: Any, hint: str | None) -> ValueError:
    return ValueError(f"{name} must be {what}, got {value!r}{'; ' + hint if hint else ''}.")


def check_integer(
    value: Any, name: str, low: int | None = None, high: int | None = None, *, what: str | None = None, hint: str | None = None
) -> int:
    """``int(value)`` when it is an integer (:func:`is_integer`) with ``low <= value <= high``; else ``ValueError``.

    Either bound may be ``None``. ``what`` says in the message what the value must be (default,
    from the bounds: "a positive integer", "an integer in 2..300", "an integer >= 3"); ``hint``
    is appended after the value.

    Examples
    --------
    >>> check_integer(np.int64(7), "n_rings", 3)
    7
    >>> check_integer(0, "n_samples", 2, 300)
    Traceback (most recent call last):
    ...
    ValueError: n_samples must be an integer in 2..300, got 0.
    >>> check_integer(0, "k", 1, 9, what="an integer between 1 and n - 1 = 9", hint="ask for fewer")
    Traceback (most recent call last):
    ...
    ValueError: k must be an integer between 1 and n - 1 = 9, got 0; ask for fewer.
    """
    if not (is_integer(value) and (low is None or value >= low) and (high is None or value <= high)):
        raise _fail(name, _described(low, high, False, False, True) if what is None else what, value, hint)
    return int(value)


def check_number(
    value: Any,
    name: str,
    low: float | None = None,
    high: float | None = None,
    *,
    open_low: bool = False,
    open_high: bool = False,
    what: str | None = None,
    hint: str | None = None,
) -> float:
    """``float(value)`` when it is a finite number (:func:`is_number`) in the range; else ``ValueError``.

    The range is ``[low, high]``; ``open_low`` / ``open_high`` exclude an end. ``what`` and
    ``hint`` as in :func:`check_integer` (default: "a positive number", "a number in (0, 1)", ...).

    Examples
    --------
    >>> check_number(1e-8, "tol", 0, 1, open_low=True, open_high=True)
    1e-08
    >>> check_number(0.0, "shift", 0, open_low=True)
    Traceback (most recent call last):
    ...
    ValueError: shift must be a positive number, got 0.0.
    """
    inside = is_number(value) and (low is None or (value > low if open_low else value >= low)) and (
        high is None or (value < high if open_high else value <= high)
    )
    if not inside:
        raise _fail(name, _described(low, high, open_low, open_high, False) if what is None else what, value, hint)
    return float(value)
