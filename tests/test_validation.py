"""lbo_notebooks._support.validation: the one argument check, and that the package uses it."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import lbo_notebooks as lbo
from lbo_notebooks._support.validation import check_integer, check_number, is_integer, is_number


def test_integers():
    assert check_integer(np.int16(4), "k", 1, 4) == 4 and type(check_integer(np.int16(4), "k")) is int
    for bad in (True, np.bool_(True), 2.0, "2", None, np.array(2)):
        assert not is_integer(bad)
        with pytest.raises(ValueError, match=r"^k must be an integer, got "):
            check_integer(bad, "k")
    with pytest.raises(ValueError, match=r"^k must be a positive integer, got 0\.$"):
        check_integer(0, "k", 1)
    with pytest.raises(ValueError, match=r"^k must be a non-negative integer, got -1\.$"):
        check_integer(-1, "k", 0)
    with pytest.raises(ValueError, match=r"^n must be an integer >= 3, got 2\.$"):
        check_integer(2, "n", 3)
    with pytest.raises(ValueError, match=r"^n must be an integer in 2\.\.5, got 6; fewer, please\.$"):
        check_integer(6, "n", 2, 5, hint="fewer, please")


def test_numbers():
    assert check_number(1, "x") == 1.0 and check_number(np.float32(0.5), "x", 0, 1) == 0.5
    for bad in (np.nan, np.inf, True, "1", None, 1j):
        assert not is_number(bad)
        with pytest.raises(ValueError, match=r"^x must be a number, got "):
            check_number(bad, "x")
    with pytest.raises(ValueError, match=r"^x must be a positive number, got 0\.0\.$"):
        check_number(0.0, "x", 0, open_low=True)
    assert check_number(0.0, "x", 0) == 0.0
    with pytest.raises(ValueError, match=r"^tol must be a number in \(0, 1\), got 1\.$"):
        check_number(1, "tol", 0, 1, open_low=True, open_high=True)




def test_no_hand_written_bool_checks_are_left():
    """Issue 27, item 6: ``isinstance(x, bool) or not isinstance(x, ...)`` is written once, in _validation."""
    root = Path(lbo.__file__).parent
    pattern = re.compile(r"isinstance\([^)]*, bool\) or not isinstance|not isinstance\([^)]*, bool\) and isinstance")
    left = [
        str(path.relative_to(root))
        for path in root.rglob("*.py")
        if path.name != "_validation.py" and "exercises" not in path.parts and pattern.search(path.read_text())
    ]
    assert not left, left


# --- the declared constraints (issue 42, item 7) --------------------------------------------------

import inspect as _inspect

from lbo_notebooks._support.validation import Boolean, Integer, Number, Options, Satisfies, validated


@validated(
    n=Integer(1),
    k=Integer(1, lambda n, **_: n, what="an integer between 1 and n ({high})"),
    tol=Number(0, 1, open_low=True, none=True),
    method=Options("cotan", "robust", 3),
    flag=Boolean(),
    name=Satisfies(lambda s: isinstance(s, str) and s.isidentifier(),
                   message="{name} must be an identifier, got {value!r}."),
)
def _pick(n: int, k: int = 1, *, tol: float | None = None, method: str = "cotan", flag: bool = False, name: str = "x"):
    """Pick k of n."""
    return n, k, tol, method, flag, name


def test_dependent_bounds():
    assert _pick(5, 5)[1] == 5
    with pytest.raises(ValueError, match=r"^k must be an integer between 1 and n \(5\), got 6\.$"):
        _pick(5, 6)


def test_none_allowed_and_values_normalized():
    n, k, tol, _, flag, _ = _pick(np.int64(4), np.int16(2), tol=np.float32(0.5), flag=np.bool_(True))
    assert (type(n), type(k), type(tol), type(flag)) == (int, int, float, bool)
    assert _pick(3)[2] is None
    with pytest.raises(ValueError, match=r"^tol must be a number in \(0, 1\], got 0\.$"):
        _pick(3, tol=0)


def test_options_and_booleans():
    assert _pick(3, method="robust")[3] == "robust" and _pick(3, method=np.int64(3))[3] == 3
    with pytest.raises(ValueError, match=r"^method must be one of \('cotan', 'robust', 3\), got 'fem'\.$"):
        _pick(3, method="fem")
    with pytest.raises(ValueError, match=r"^flag must be True or False, got 1\.$"):
        _pick(3, flag=1)
    with pytest.raises(ValueError, match=r"^name must be an identifier, got '1x'\.$"):
        _pick(3, name="1x")


def test_bool_is_not_an_integer_and_nan_is_not_a_number():
    with pytest.raises(ValueError, match=r"^n must be a positive integer, got True\.$"):
        _pick(True)
    with pytest.raises(ValueError, match=r"^method must be one of .*, got True\.$"):
        _pick(3, method=True)  # True == 1 == 3 - 2 must not slip through an integer option
    with pytest.raises(ValueError, match=r"^tol must be a number in \(0, 1\], got nan\.$"):
        _pick(3, tol=float("nan"))


def test_signature_and_docstring_preserved():
    assert _pick.__name__ == "_pick" and _pick.__doc__ == "Pick k of n." and _pick.__wrapped__ is not None
    assert str(_inspect.signature(_pick)) == str(_inspect.signature(_pick.__wrapped__))
    assert lbo.shapes.icosphere.__wrapped__ and "icosahedron" in lbo.shapes.icosphere.__doc__
    with pytest.raises(TypeError, match="no parameter"):
        validated(nope=Integer())(_pick.__wrapped__)


# --- arrays, vertex indices, relations ---------------------------------------------------------

from lbo_notebooks._support.validation import Array, Indices, Relation


@validated(
    n=Integer(1),
    f=Array((1, 2), rows=lambda n, **_: n, meaning="one value per vertex", hint="replace them first"),
    Y=Array((1, 2), rows=lambda n, **_: n, column=True, none=True, nonempty=True),
    sources=Indices(lambda n, **_: n - 1, scalar=True, integral=True, nonempty=True, none=True),
    mu=Number(0, none=True),
    beta=(Number(0, none=True), Relation(lambda mu, beta, **_: (mu is None) != (beta is None),
                                         "give exactly one of mu and beta, got mu={mu} and beta={beta}")),
)
def _field(n, f, Y=None, sources=None, mu=None, beta=1.0):
    """Hand back what the body receives."""
    return f, Y, sources, mu, beta


def test_arrays_arrive_as_float64_of_the_declared_shape():
    f, Y, sources, _, _ = _field(3, [1, 2, 3], Y=[4, 5, 6], sources=np.float32(2))
    assert f.dtype == np.float64 and f.shape == (3,) and Y.shape == (3, 1) and sources.tolist() == [2]
    assert sources.dtype == np.int64
    assert _field(2, np.ones((2, 4)))[0].shape == (2, 4)


def test_array_shape_messages_name_the_expected_and_the_actual_shape():
    with pytest.raises(ValueError, match=r"^f must have shape \(3,\) or \(3, c\): one value per vertex; got \(4,\)\.$"):
        _field(3, np.zeros(4))
    with pytest.raises(ValueError, match=r"^f must have shape .*; got \(3, 1, 1\)\.$"):
        _field(3, np.zeros((3, 1, 1)))
    with pytest.raises(ValueError, match=r"^f must .*; got a value that is not an array of numbers\.$"):
        _field(2, [[1, 2], [3]])  # ragged
    with pytest.raises(ValueError, match=r"^f must .*; got a value that is not an array of numbers\.$"):
        _field(2, ["a", "b"])
    with pytest.raises(ValueError, match=r"^Y is empty \(shape \(3, 0\)\); pass at least one value\.$"):
        _field(3, np.zeros(3), Y=np.zeros((3, 0)))


def test_non_finite_values_are_refused_with_the_fix():
    for bad in (np.nan, np.inf, -np.inf):
        with pytest.raises(ValueError, match=r"^f must be finite, got NaN or inf; replace them first\.$"):
            _field(3, [0.0, bad, 1.0])


def test_the_callers_array_is_not_modified():
    f = np.array([3, 2, 1])
    out, Y, sources, _, _ = _field(3, f, Y=f, sources=f - 1)
    assert f.dtype == np.int64 and f.tolist() == [3, 2, 1] and out.dtype == np.float64
    assert Y.shape == (3, 1) and f.shape == (3,) and sources.tolist() == [2, 1, 0]


def test_indices_refuse_booleans_fractions_and_out_of_range():
    with pytest.raises(ValueError, match=r"^sources must be an array of vertex indices; got dtype bool"):
        _field(3, np.zeros(3), sources=[True, False])
    with pytest.raises(ValueError, match=r"^sources must be .*; got dtype float64 and shape \(1,\)\.$"):
        _field(3, np.zeros(3), sources=[1.5])
    with pytest.raises(ValueError, match=r"^sources must be .*; got dtype float64 and shape \(1,\)\.$"):
        _field(3, np.zeros(3), sources=[np.nan])
    for single in (2.5, True, np.nan):  # one value is shown as itself, not as "shape (1,)"
        with pytest.raises(ValueError, match=rf"^sources must be .*; got {single!r}\.$"):
            _field(3, np.zeros(3), sources=single)
    for empty in (np.array([], dtype=np.int64), []):
        with pytest.raises(ValueError, match=r"^sources is empty; pass at least one vertex index\.$"):
            _field(3, np.zeros(3), sources=empty)
    with pytest.raises(ValueError, match=r"^sources must be .*shape \(1, 1\)\.$"):
        _field(3, np.zeros(3), sources=[[1]])
    for bad in (3, -1):
        with pytest.raises(ValueError, match=rf"^sources holds vertex index {bad} outside 0\.\.2\.$"):
            _field(3, np.zeros(3), sources=[0, bad])


def test_relations_between_arguments():
    assert _field(3, np.zeros(3), mu=0.5, beta=None)[3:] == (0.5, None)
    with pytest.raises(ValueError, match=r"^give exactly one of mu and beta, got mu=0.5 and beta=1.0\.$"):
        _field(3, np.zeros(3), mu=0.5)
    with pytest.raises(ValueError, match=r"^give exactly one of mu and beta, got mu=None and beta=None\.$"):
        _field(3, np.zeros(3), beta=None)


@pytest.mark.timing
def test_per_call_overhead_is_small():
    import timeit

    seconds = min(timeit.repeat(lambda: _pick(5, 2, tol=0.5), number=2000, repeat=3)) / 2000
    assert seconds < 1e-4, seconds


def test_infinite_numbers_only_where_declared():
    budget = Number(0, open_low=True, infinite=True)
    assert budget.check(float("inf"), "memory_budget", {}) == float("inf")
    for bad in (float("-inf"), float("nan"), 0.0):
        with pytest.raises(ValueError, match=r"^memory_budget must be a positive number, got"):
            budget.check(bad, "memory_budget", {})
    with pytest.raises(ValueError, match=r"^tol must be a number in \(0, 1\], got inf\.$"):
        _pick(3, tol=float("inf"))


def test_out_of_range_message_as_the_caller_words_it():
    rule = Indices(lambda n, **_: n - 1, out_of_range="{name} vertex {index} is out of range: {count} vertices")
    with pytest.raises(ValueError, match=r"^target vertex 7 is out of range: 3 vertices$"):
        rule.check([0, 7], "target", {"n": 3})


def test_a_rule_may_raise_the_error_callers_already_expect():
    rule = Satisfies(lambda mesh: isinstance(mesh, lbo.Mesh), error=TypeError, message="needs a Mesh, got {type}.")
    with pytest.raises(TypeError, match=r"^needs a Mesh, got ndarray\.$"):
        rule.check(np.eye(3), "mesh", {})
    with pytest.raises(TypeError, match=r"^k must be a positive integer, got 0\.$"):
        Integer(1, error=TypeError).check(0, "k", {})
