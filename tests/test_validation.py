"""lbo_notebooks._validation: the one argument check, and that the package uses it."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import lbo_notebooks as lbo
from lbo_notebooks._validation import check_integer, check_number, is_integer, is_number


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
