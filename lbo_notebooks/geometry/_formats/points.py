"""Text point lists (.xyz, .pts, .txt, .csv): the first three columns.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from .._mesh import MeshError
from .common import (
    check_ends_with_line_break,
    parse_float,
    parse_int,
    read_text,
)

__all__ = ["read_point_text"]


_DECIMAL_COMMA = re.compile(r"[-+]?\d*,\d+(?:[eE][-+]?\d+)?")


def _is_number(token: str) -> bool:
    try:
        parse_float(token)
        return True
    except ValueError:
        return False


def read_point_text(p: Path) -> NDArray[np.float64]:
    """The first three columns of a text point list (.xyz, .pts, .txt, .csv), shape (n, 3).

    Columns are separated by spaces, tabs or commas; ``#`` and ``//`` start comments. A file whose
    columns are separated by semicolons (as spreadsheets in countries writing ``0,5`` export CSV)
    may write its numbers with a decimal comma: ``0,5;1,5;2,5`` is the point (0.5, 1.5, 2.5). A
    file without semicolons whose rows are numbers like ``0,5`` separated by spaces or tabs is
    ambiguous (decimal commas, or commas between columns?) and is refused.

    A first line holding one integer is a count (``.pts``) and must equal the number of points. A
    first line starting with a word is a header and is skipped (``x,y,z``, ``Points: 5``) unless it
    looks like data (three or more columns, some of them numbers: ``abc,1,2``), which is an error
    naming the line, as is any other row that does not start with three numbers.
    """
    text = read_text(p, "point")
    check_ends_with_line_break(text, comment="#|//")
    numbered = []
    for number, line in enumerate(text.splitlines(), start=1):
        line = re.split(r"#|//", line, maxsplit=1)[0].strip()
        if line:
            numbered.append((number, line))
    if not numbered:
        raise MeshError("the file holds only comments or blank lines; no points.")
    semicolons = any(";" in line for _, line in numbered)
    if semicolons:
        def split(line: str) -> list[str]:
            fields = [f.strip() for f in line.split(";")]
            while len(fields) > 1 and not fields[-1]:
                fields.pop()  # a trailing ';', as spreadsheets write it
            return [f.replace(",", ".") if _DECIMAL_COMMA.fullmatch(f) else f for f in fields]
    else:
        for number, line in numbered:
            tokens = line.split()
            if len(tokens) > 1 and all(_DECIMAL_COMMA.fullmatch(t) for t in tokens):
                raise MeshError(
                    f"line {number} ({line[:60]!r}) is ambiguous: numbers written with a decimal comma (0,5) and "
                    "separated by spaces or tabs, or columns separated by commas? Export the file with decimal "
                    "points (0.5), or with columns separated by ';' (then 0,5 is read as 0.5)."
                )

        def split(line: str) -> list[str]:
            return re.split(r"[\s,]+", line)

    rows = [(number, split(line), line) for number, line in numbered]
    first_number, first, first_line = rows[0]
    if len(first) == 1 and len(rows) > 1 and _is_number(first[0]):  # a count line (.pts)
        try:
            count = parse_int(first[0])
        except ValueError:
            raise MeshError(f"the first line {first_line[:40]!r} is one number but not a point count (an integer).") from None
        if count != len(rows) - 1:
            raise MeshError(
                f"the count line announces {count} points but the file holds {len(rows) - 1}: it is truncated "
                "or corrupt. Re-export or re-download it."
            )
        rows = rows[1:]
    elif not _is_number(first[0]) and re.search("[A-Za-z]", first[0]):
        # A header such as 'x,y,z' or 'Points: 5'; but 'abc,1,2' is a data row with a damaged first column,
        # and '1_0 2 3' (no letter) a corrupt row: both are refused below, naming the line.
        if len(first) < 3 or not any(_is_number(t) for t in first):
            rows = rows[1:]
    if not rows:
        raise MeshError("the file holds a header but no points.")
    out = np.empty((len(rows), 3))
    for k, (number, row, line) in enumerate(rows):
        try:
            if len(row) < 3:
                raise ValueError
            out[k] = [parse_float(x) for x in row[:3]]
        except ValueError:
            raise MeshError(
                f"line {number} ({line[:60]!r}) does not start with three numbers x y z; the file is corrupt."
            ) from None
    return out
