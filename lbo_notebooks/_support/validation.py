"""Argument checks: one mechanism for numbers in a range, options, arrays of a shape, vertex indices.

Every public function checks its arguments and raises ``ValueError`` with a message that names the
argument, what it must be, what was passed and, where it helps, what to pass instead. The test of
the value (``True`` is not an integer here, although ``bool`` subclasses ``int``; NumPy integers
and floats are accepted; NaN and infinity are not numbers in a range) is written once, below; the
message is built from the same parts everywhere:

    {name} must be {what}, got {value!r}[; {hint}].

What it must be reads as the bounds state it ("an integer in 2..300", "an integer >= 3", "a
positive integer") or as the caller words it (``what=``), so that messages stay specific: "k must be an integer
between 1 and the number of vertices (642), got 0." The idea is scikit-learn's declared parameter
constraints, kept to the kinds this package needs.

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

The same checks, declared: :func:`validated` takes one constraint per argument (:class:`Integer`,
:class:`Number`, :class:`Options`, :class:`Boolean`, :class:`Array`, :class:`Indices`, :class:`Relation`,
:class:`Satisfies`), binds the arguments once
per call, and hands the normalized values (``int``, ``float``, the option) to the body. A bound or
message may be a callable of the arguments, so it can depend on another one:

>>> @validated(n=Integer(1), k=Integer(1, lambda n, **_: n, what="an integer between 1 and n ({high})"),
...            tol=Number(0, 1, open_low=True, none=True), method=Options("cotan", "robust"))
... def pick(n, k=1, tol=None, method="cotan"):
...     "Pick k of n."
...     return k, tol, method
>>> pick(np.int64(5), np.int32(3), 1)
(3, 1.0, 'cotan')
>>> pick(5, 6)
Traceback (most recent call last):
...
ValueError: k must be an integer between 1 and n (5), got 6.
>>> pick(5, method="fem")
Traceback (most recent call last):
...
ValueError: method must be one of ('cotan', 'robust'), got 'fem'.
"""

from __future__ import annotations

import functools
import inspect
import math
from collections.abc import Callable
from typing import Any, TypeVar

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "is_integer", "is_number", "check_integer", "check_number",
    "validated", "Constraint", "Integer", "Number", "Options", "Boolean", "Satisfies",
    "Array", "Indices", "Relation",
]


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


# --- Declared constraints: one table per public function -------------------------------------------

Bound = Any  # a number, None, or a callable of the function's arguments (``lambda mesh, **_: mesh.n_vertices``)


def _resolve(bound: Bound, arguments: dict[str, Any]) -> Any:
    return bound(**arguments) if callable(bound) else bound


class Constraint:
    """One argument's rule: :meth:`check` returns the normalized value or raises ``ValueError``.

    ``none=True`` lets ``None`` through unchanged. ``what`` (what the value must be) and ``hint``
    (appended after the value) may be strings, formatted with the resolved ``{low}`` and ``{high}``,
    or callables of the function's arguments. ``message`` replaces the whole message; it is
    formatted with ``{name}``, ``{value!r}``, ``{type}`` (the value's type name), ``{low}``, ``{high}``,
    or is a callable ``message(name, value)``. ``error`` is the exception raised (``ValueError``;
    ``TypeError`` where an object of the wrong kind is passed and callers already expect that).
    """

    low: Bound = None
    high: Bound = None

    def __init__(self, *, what: Any = None, hint: Any = None, message: Any = None, none: bool = False,
                 error: type[Exception] = ValueError) -> None:
        self.what, self.hint, self.message, self.none, self.error = what, hint, message, none, error

    def accepts(self, value: Any, low: Any, high: Any) -> bool:  # pragma: no cover - each kind has its own
        raise NotImplementedError

    def normalize(self, value: Any) -> Any:
        return value

    def default_what(self, low: Any, high: Any) -> str:  # pragma: no cover
        raise NotImplementedError

    def check(self, value: Any, name: str, arguments: dict[str, Any]) -> Any:
        if value is None and self.none:
            return None
        low, high = _resolve(self.low, arguments), _resolve(self.high, arguments)
        if self.accepts(value, low, high):
            return self.normalize(value)
        parts = {"low": low, "high": high}
        if callable(self.message):
            raise self.error(self.message(name, value))
        if self.message is not None:
            raise self.error(self.message.format(name=name, value=value, type=type(value).__name__, **parts))
        what = self.default_what(low, high) if self.what is None else self._text(self.what, arguments, parts)
        hint = None if self.hint is None else self._text(self.hint, arguments, parts)
        raise self.error(str(_fail(name, what, value, hint)))

    @staticmethod
    def _text(text: Any, arguments: dict[str, Any], parts: dict[str, Any]) -> str:
        return text(**arguments) if callable(text) else text.format(**parts)


class Integer(Constraint):
    """An integer (:func:`is_integer`, so not ``True``) in ``low..high``; the body gets ``int(value)``."""

    def __init__(self, low: Bound = None, high: Bound = None, **options: Any) -> None:
        super().__init__(**options)
        self.low, self.high = low, high

    def accepts(self, value: Any, low: Any, high: Any) -> bool:
        return is_integer(value) and (low is None or value >= low) and (high is None or value <= high)

    def normalize(self, value: Any) -> int:
        return int(value)

    def default_what(self, low: Any, high: Any) -> str:
        return _described(low, high, False, False, True)


class Number(Constraint):
    """A finite real number (:func:`is_number`) in ``[low, high]``; ``open_low``/``open_high`` exclude an end.

    ``infinite=True`` also takes ``inf`` and ``-inf`` (still compared with the bounds; NaN never passes).

    The body gets ``float(value)``.
    """

    def __init__(self, low: Bound = None, high: Bound = None, *, open_low: bool = False, open_high: bool = False,
                 infinite: bool = False, **options: Any) -> None:
        super().__init__(**options)
        self.low, self.high, self.open_low, self.open_high = low, high, open_low, open_high
        self.infinite = infinite

    def accepts(self, value: Any, low: Any, high: Any) -> bool:
        infinite = self.infinite and isinstance(value, (float, np.floating)) and math.isinf(value)
        if not (is_number(value) or infinite):
            return False
        return (low is None or (value > low if self.open_low else value >= low)) and (
            high is None or (value < high if self.open_high else value <= high)
        )

    def normalize(self, value: Any) -> float:
        return float(value)

    def default_what(self, low: Any, high: Any) -> str:
        return _described(low, high, self.open_low, self.open_high, False)


class Options(Constraint):
    """One of the given strings, integers or other scalars; ``True`` never counts as ``1``. Gives the option itself."""

    def __init__(self, *choices: Any, **options: Any) -> None:
        super().__init__(**options)
        self.choices = choices

    def _match(self, value: Any) -> Any:
        if isinstance(value, (str, int, float, np.generic)):
            for choice in self.choices:
                if isinstance(value, (bool, np.bool_)) == isinstance(choice, bool) and value == choice:
                    return choice
        return _NO_MATCH

    def accepts(self, value: Any, low: Any, high: Any) -> bool:
        return self._match(value) is not _NO_MATCH

    def normalize(self, value: Any) -> Any:
        return self._match(value)

    def default_what(self, low: Any, high: Any) -> str:
        return f"one of {self.choices!r}"


_NO_MATCH = object()


class Boolean(Constraint):
    """``True`` or ``False`` (NumPy booleans too, not ``0``/``1``); gives ``bool``."""

    def accepts(self, value: Any, low: Any, high: Any) -> bool:
        return isinstance(value, (bool, np.bool_))

    def normalize(self, value: Any) -> bool:
        return bool(value)

    def default_what(self, low: Any, high: Any) -> str:
        return "True, False or None" if self.none else "True or False"


class Satisfies(Constraint):
    """The rare special case: ``predicate(value)`` is true; ``what`` or ``message`` says what it must be."""

    def __init__(self, predicate: Callable[[Any], bool], what: Any = None, *,
                 convert: Callable[[Any], Any] | None = None, **options: Any) -> None:
        super().__init__(what=what, **options)
        self.predicate, self.convert = predicate, convert

    def accepts(self, value: Any, low: Any, high: Any) -> bool:
        try:
            return bool(self.predicate(value))
        except (TypeError, ValueError):
            return False

    def normalize(self, value: Any) -> Any:
        return value if self.convert is None else self.convert(value)

    def default_what(self, low: Any, high: Any) -> str:
        return "valid"


def _shape_text(ndim: tuple[int, ...], rows: Any, cols: Any, cols_name: str) -> str:
    """The accepted shapes as a reader writes them: "(162,)", "(162, k)", "(162,) or (162, c)"."""
    row = "n" if rows is None else str(rows)
    col = cols_name if cols is None else str(cols)
    forms = {0: "()", 1: f"({row},)", 2: f"({row}, {col})"}
    return " or ".join(forms.get(d, f"{d}-D") for d in ndim)


class Array(Constraint):
    """An array of numbers of a declared shape; the body gets ``np.asarray(value, dtype)`` (a copy only if needed).

    ``ndim`` is the accepted rank or ranks (``(1, 2)``: one function or a column per function);
    ``rows`` and ``cols`` are the lengths of the first two axes (a number, ``None`` for any, or a
    callable of the arguments: ``rows=lambda mesh, **_: mesh.n_vertices``); ``cols_name`` names a
    free second axis in the message. ``column=True`` hands a 1-D value to the body as one column.
    ``finite=True`` refuses NaN and infinity, ``nonempty=True`` a size-0 array. The messages:

        {name} must have shape {shapes}[: {meaning}]; got {shape}.
        {name} is empty (shape {shape}); pass at least one value.
        {name} must be finite, got NaN or inf[; {hint}].

    Examples
    --------
    >>> f = Array((1, 2), rows=3, meaning="one value per vertex", hint="replace them first")
    >>> f.check([1, 2, 3], "f", {}).dtype
    dtype('float64')
    >>> f.check(np.ones((4, 2)), "f", {})
    Traceback (most recent call last):
    ...
    ValueError: f must have shape (3,) or (3, c): one value per vertex; got (4, 2).
    >>> f.check([1.0, np.nan, 0.0], "f", {})
    Traceback (most recent call last):
    ...
    ValueError: f must be finite, got NaN or inf; replace them first.
    """

    def __init__(self, ndim: int | tuple[int, ...] = (1, 2), *, rows: Bound = None, cols: Bound = None,
                 cols_name: str = "c", dtype: Any = np.float64, finite: bool = True, nonempty: bool = False,
                 column: bool = False, meaning: str | None = None, **options: Any) -> None:
        super().__init__(**options)
        self.ndim = (ndim,) if isinstance(ndim, int) else tuple(ndim)
        self.rows, self.cols, self.cols_name, self.dtype = rows, cols, cols_name, dtype
        self.finite, self.nonempty, self.column, self.meaning = finite, nonempty, column, meaning

    def check(self, value: Any, name: str, arguments: dict[str, Any]) -> Any:
        if value is None and self.none:
            return None
        rows, cols = _resolve(self.rows, arguments), _resolve(self.cols, arguments)
        parts = {"rows": rows, "cols": cols}
        shapes = _shape_text(self.ndim, rows, cols, self.cols_name)
        try:
            arr = np.asarray(value, dtype=self.dtype)
        except (TypeError, ValueError):
            arr = None
        got = "a value that is not an array of numbers" if arr is None else str(arr.shape)
        fits = arr is not None and arr.ndim in self.ndim and (
            arr.ndim == 0 or rows is None or arr.shape[0] == rows) and (
            arr.ndim < 2 or cols is None or arr.shape[1] == cols)
        if fits and self.nonempty and arr.size == 0:
            raise ValueError(f"{name} is empty (shape {arr.shape}); pass at least one value.")
        if not fits:
            if self.message is not None:
                raise ValueError(self.message(name, value) if callable(self.message)
                                 else self.message.format(name=name, shape=got, shapes=shapes, **parts))
            what = self._text(self.what, arguments, parts) if self.what is not None else (
                f"have shape {shapes}" + (f": {self.meaning}" if self.meaning else ""))
            raise ValueError(f"{name} must {what}; got {got}.")
        if self.finite and not np.all(np.isfinite(arr)):
            hint = None if self.hint is None else self._text(self.hint, arguments, parts)
            raise ValueError(f"{name} must be finite, got NaN or inf{'; ' + hint if hint else ''}.")
        return arr[:, None] if self.column and arr.ndim == 1 else arr


class Indices(Constraint):
    """Vertex indices: integers (integer dtype; ``integral=True`` also takes floats such as ``3.0``) in ``0..high``.

    ``high`` is usually a callable of the arguments (``lambda mesh, **_: mesh.n_vertices - 1``).
    ``ndim`` as in :class:`Array`; ``scalar=True`` also takes one index and gives it as a 1-D array.
    ``length`` fixes the number of indices; ``nonempty=True`` refuses none. The body gets an
    ``int64`` array. The messages:

        {name} is empty; pass at least one vertex index.
        {name} must be {what}; got dtype {dtype} and shape {shape}.   (a single value: got {value!r}.)
        {name} holds vertex index {index} outside 0..{high}[; {hint}].

    ``out_of_range`` replaces the second, formatted with ``{name}``, ``{index}``, ``{high}`` and
    ``{count}`` (``high + 1``, the number of vertices).

    Examples
    --------
    >>> rule = Indices(high=9, nonempty=True, what="a non-empty 1-D array of vertex indices")
    >>> rule.check([0, 3, 9], "samples", {}).tolist()
    [0, 3, 9]
    >>> rule.check([1.5], "samples", {})
    Traceback (most recent call last):
    ...
    ValueError: samples must be a non-empty 1-D array of vertex indices; got dtype float64 and shape (1,).
    >>> rule.check([10], "samples", {})
    Traceback (most recent call last):
    ...
    ValueError: samples holds vertex index 10 outside 0..9.
    """

    def __init__(self, high: Bound = None, *, ndim: int = 1, length: Bound = None, scalar: bool = False,
                 integral: bool = False, nonempty: bool = False, out_of_range: str | None = None,
                 **options: Any) -> None:
        super().__init__(**options)
        self.high, self.ndim, self.length, self.scalar = high, ndim, length, scalar
        self.integral, self.nonempty, self.out_of_range = integral, nonempty, out_of_range

    def _integers(self, arr: NDArray[Any]) -> bool:
        if arr.dtype == bool:
            return False
        if np.issubdtype(arr.dtype, np.integer):
            return True
        return bool(self.integral and np.issubdtype(arr.dtype, np.floating) and np.all(np.isfinite(arr))
                    and np.all(arr == np.round(arr)))

    def check(self, value: Any, name: str, arguments: dict[str, Any]) -> Any:
        if value is None and self.none:
            return None
        high, length = _resolve(self.high, arguments), _resolve(self.length, arguments)
        parts = {"low": 0, "high": high, "length": length}
        try:
            arr = np.asarray(value)
        except (TypeError, ValueError):
            arr = np.asarray(None)
        one = arr.ndim == 0
        if self.scalar and one:
            arr = arr.reshape(1)
        if self.nonempty and arr.ndim == self.ndim and arr.size == 0:
            raise ValueError(f"{name} is empty; pass at least one vertex index.")
        fits = arr.ndim == self.ndim and self._integers(arr) and (length is None or arr.shape[0] == length)
        if not fits:
            if self.message is not None:
                raise ValueError(self.message(name, value) if callable(self.message) else self.message.format(
                    name=name, dtype=arr.dtype, shape=arr.shape, **parts))
            what = self._text(self.what, arguments, parts) if self.what is not None else (
                f"an integer array of shape ({length},)" if length is not None else "an array of vertex indices")
            got = repr(value) if one else f"dtype {arr.dtype} and shape {arr.shape}"
            raise ValueError(f"{name} must be {what}; got {got}.")
        arr = arr.astype(np.int64)
        bad = (arr < 0) | (arr > high) if high is not None else arr < 0
        if bad.any():
            index = int(arr[bad].flat[0])
            if self.out_of_range is not None:
                raise ValueError(self.out_of_range.format(
                    name=name, index=index, high=high, count=None if high is None else high + 1))
            hint = None if self.hint is None else self._text(self.hint, arguments, parts)
            raise ValueError(f"{name} holds vertex index {index} outside 0..{high}{'; ' + hint if hint else ''}.")
        return arr


class Relation(Constraint):
    """A rule between arguments: ``holds(**arguments)`` is true, else ``ValueError(message)``.

    ``message`` is a string formatted with the arguments, or a callable of them. Put it on the
    argument named last in the relation, so the others are checked first; it passes the value on
    unchanged.

    Examples
    --------
    >>> one = Relation(lambda mu, beta, **_: (mu is None) != (beta is None), "give exactly one of mu and beta")
    >>> one.check(None, "beta", {"mu": 0.1, "beta": None})
    >>> one.check(2.0, "beta", {"mu": 0.1, "beta": 2.0})
    Traceback (most recent call last):
    ...
    ValueError: give exactly one of mu and beta.
    """

    def __init__(self, holds: Callable[..., bool], message: Any) -> None:
        super().__init__(message=message)
        self.holds = holds

    def check(self, value: Any, name: str, arguments: dict[str, Any]) -> Any:
        if self.holds(**arguments):
            return value
        text = self.message(**arguments) if callable(self.message) else self.message.format(**arguments)
        raise ValueError(text if text.endswith(".") else text + ".")


F = TypeVar("F", bound=Callable[..., Any])


def validated(**constraints: Constraint | tuple[Constraint, ...]) -> Callable[[F], F]:
    """Check the named arguments against their constraints, in the order given, before the call.

    An argument may have a tuple of constraints, checked in turn (a range, then a relation to
    another argument). The arguments are bound with the function's signature (defaults applied), each checked value
    is replaced by its normalized form (``int``, ``float``, the option), and the function is called
    with them. A bound or message may depend on arguments named earlier in the table, which are
    then already checked. The wrapper keeps the name, docstring, signature and ``__wrapped__``; its
    table is ``wrapper.__constraints__``.
    """

    def decorate(function: F) -> F:
        signature = inspect.signature(function)
        unknown = sorted(set(constraints) - set(signature.parameters))
        if unknown:
            raise TypeError(f"{function.__qualname__} has no parameter(s) {', '.join(unknown)} to validate.")
        table = tuple((name, rule if isinstance(rule, tuple) else (rule,)) for name, rule in constraints.items())

        @functools.wraps(function)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            bound = signature.bind(*args, **kwargs)
            bound.apply_defaults()
            arguments = bound.arguments
            for name, rules in table:
                for rule in rules:
                    arguments[name] = rule.check(arguments[name], name, arguments)
            return function(*bound.args, **bound.kwargs)

        wrapper.__constraints__ = dict(constraints)  # type: ignore[attr-defined]
        return wrapper  # type: ignore[return-value]

    return decorate
