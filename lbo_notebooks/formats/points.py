"""Text point lists (.xyz, .pts, .txt, .csv): the first three columns.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..mesh import MeshError
from .common import (
    check_ends_with_line_break,
    parse_float,
    parse_int,
    read_text,
)

__all__ = ["read_point_text"]


def read_point_text(p: Path) -> NDArray[np.float64]:
    """The first three columns of a text point list (.xyz, .pts, .txt, .csv), shape (n, 3).

    Numbers are separated by spaces, tabs, commas or semicolons; ``#`` and ``//`` start comments.
    A first line holding one integer is a count (``.pts``) and must equal the number of points; a
    first line starting with a word (such as ``x,y,z``) is a header and is skipped.
    """
    text = read_text(p, "point")
    check_ends_with_line_break(text, comment="#|//")
    lines = [re.split(r"#|//", line, maxsplit=1)[0].strip() for line in text.splitlines()]
    lines = [line for line in lines if line]
    if not lines:
        raise MeshError("the file holds only comments or blank lines; no points.")
    rows = [re.split(r"[\s,;]+", line) for line in lines]

    def is_number(token: str) -> bool:
        try:
            parse_float(token)
            return True
        except ValueError:
            return False

    if len(rows[0]) == 1 and len(rows) > 1 and is_number(rows[0][0]):  # a count line (.pts)
        try:
            count = parse_int(rows[0][0])
        except ValueError:
            raise MeshError(f"the first line {lines[0][:40]!r} is one number but not a point count (an integer).") from None
        if count != len(rows) - 1:
            raise MeshError(
                f"the count line announces {count} points but the file holds {len(rows) - 1}: it is truncated "
                "or corrupt. Re-export or re-download it."
            )
        rows = rows[1:]
    elif not is_number(rows[0][0]) and re.search("[A-Za-z]", rows[0][0]):
        rows = rows[1:]  # a header line such as 'x,y,z' (but '1_0 2 3' is a corrupt row, not a header)
    if not rows:
        raise MeshError("the file holds a header but no points.")
    out = np.empty((len(rows), 3))
    for k, row in enumerate(rows):
        try:
            if len(row) < 3:
                raise ValueError
            out[k] = [parse_float(x) for x in row[:3]]
        except ValueError:
            raise MeshError(f"point {k} ({' '.join(row)[:60]!r}) does not start with three numbers x y z; the file is corrupt.") from None
    return out
