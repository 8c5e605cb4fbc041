"""What every reader shares: the raw result, the extensions, strict number parsing, count checks.

Numbers are read as C and every mesh tool writes them (Python's ``1_000`` is not a number); a
count a header announces is checked against the file size before anything is allocated. See
:mod:`lbo_notebooks.geometry._formats` for the reasons.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np
from numpy.typing import NDArray

from .._mesh import MeshError
from .._repair import triangulate_polygons

__all__ = [
    "FORMATS", "BINARY_FORMATS", "POINT_FORMATS", "MIN_TEXT_VERTEX_BYTES", "MIN_TEXT_FACE_BYTES",
    "MAX_HEADER_BYTES", "RawMesh", "read_text", "check_ends_with_line_break", "parse_int",
    "parse_float", "clamped", "content_lines", "check_counts", "parse_numbers", "parse_vertex_lines",
    "parse_counted_faces", "numbers_per_line", "UTF8_BOM", "check_no_trailing_lines", "line_locator",
]


#: Supported mesh file extensions (lower case, with the dot).
FORMATS: tuple[str, ...] = (".off", ".obj", ".ply", ".stl")
#: Mesh formats that also have a binary form.
BINARY_FORMATS: tuple[str, ...] = (".ply", ".stl")
#: Extensions :func:`~lbo_notebooks.load_points` reads: the mesh formats (their vertices) and text point lists.
POINT_FORMATS: tuple[str, ...] = FORMATS + (".xyz", ".pts", ".txt", ".csv")

# Smallest number of bytes a record can take in a text file: "0 0 0\n" and "3 0 1 2\n".
MIN_TEXT_VERTEX_BYTES = 6
MIN_TEXT_FACE_BYTES = 8
MAX_HEADER_BYTES = 1 << 16


@dataclass(frozen=True)
class RawMesh:
    """A file's vertices and triangles as read, before any topology check."""

    vertices: NDArray[np.float64]
    triangles: NDArray[np.int64]
    n_file_faces: int  # faces as the file lists them
    n_polygons: int  # faces with more than three corners
    # Where the file writes a face or a vertex (``locate("face", k)`` -> "line 8, 'f 3 1 2'"), for error
    # messages; None for formats without lines to point at. Called only when a message needs it.
    locate: Callable[[str, int], str | None] | None = field(default=None, compare=False, repr=False)



UTF8_BOM = b"\xef\xbb\xbf"  # a UTF-8 byte order mark, as some Windows editors write it: not data
_FIRST_CHUNK = 1 << 16


def read_text(p: Path, kind: str) -> str:
    """The text of ``p`` (latin-1, a UTF-8 byte order mark dropped), after checking its first 64 KiB for NUL bytes.

    The check comes before the rest is read, so that a large binary file given a text extension
    is refused at once instead of being read whole first.
    """
    with open(p, "rb") as fh:
        first = fh.read(_FIRST_CHUNK)
        if b"\x00" in first:
            raise MeshError(
                f"this is binary data, not a text {kind} file (it contains NUL bytes). "
                f"Check that the file really is an {kind} file; re-export it from its source."
            )
        data = first + fh.read()
    if data.startswith(UTF8_BOM):
        data = data[len(UTF8_BOM):]
    return data.decode("latin-1")


def check_ends_with_line_break(text: str, comment: str = "#") -> None:
    """Refuse a text whose last line has data but no line break: it may be cut inside a number.

    A comment on that line shows that its data ended; a PLY body has no comments (``comment`` is
    then a pattern that cannot occur in a line).
    """
    tail = text[max(text.rfind("\n"), text.rfind("\r")) + 1 :]
    if tail.strip() and re.search(comment, tail) is None:
        raise MeshError(
            f"the file does not end with a line break, so its last line {tail[-60:]!r} may have been cut off "
            "(a number cut short still parses, to a wrong value): the file is probably truncated. "
            "Re-export or re-download it; if it is complete, add a line break at its end."
        )


def parse_int(token: str) -> int:
    """``int(token)`` for integers as files write them (Python's ``1_000`` is refused)."""
    if "_" in token:
        raise ValueError(token)
    return int(token)


def parse_float(token: str) -> float:
    """``float(token)`` for numbers as files write them (Python's ``1_000`` is refused)."""
    if "_" in token:
        raise ValueError(token)
    return float(token)


def clamped(ints: NDArray[np.int64]) -> bool:
    """True if :func:`parse_numbers` may have clamped an integer too large for int64 (it returns the extreme)."""
    info = np.iinfo(np.int64)
    return bool(ints.size) and (int(ints.max()) == info.max or int(ints.min()) == info.min)


def content_lines(text: str) -> tuple[list[str], list[int]]:
    """The lines of ``text`` that hold data (comments after ``#`` and blank lines dropped), and their 1-based line numbers."""
    out, numbers = [], []
    for number, line in enumerate(text.splitlines(), start=1):
        line = line.split("#", 1)[0].strip()
        if line:
            out.append(line)
            numbers.append(number)
    return out, numbers


def check_counts(p: Path, nv: int, nf: int, min_bytes: int) -> None:
    size = p.stat().st_size
    if min_bytes > size:
        raise MeshError(
            f"the header announces {nv} vertices and {nf} faces, which need at least {min_bytes} bytes, "
            f"but the file has {size}: the header is corrupt or the file is truncated. "
            "Re-export or re-download it."
        )


def parse_numbers(text: str, dtype: Any) -> NDArray[Any] | None:
    """All whitespace-separated numbers of ``text`` (C speed), or None if one is not a number."""
    import warnings as _w

    with _w.catch_warnings():
        _w.simplefilter("ignore")  # numpy < 2 warns (instead of raising) on unparsable text
        try:
            return np.fromstring(text, dtype=dtype, sep=" ")
        except ValueError:
            return None


def numbers_per_line(joined: str) -> NDArray[np.int64]:
    """How many whitespace-separated tokens each line of ``joined`` (lines joined by ``\\n``) holds, vectorised.

    A token starts wherever a byte above the space character follows a space, a control
    character or the start; the starts are counted between consecutive line breaks.
    """
    b = np.frombuffer(joined.encode("latin-1"), np.uint8)
    if b.size == 0:
        return np.zeros(1, np.int64)
    space = b <= 32
    starts = np.flatnonzero(~space & np.concatenate(([True], space[:-1])))
    bounds = np.concatenate(([0], np.flatnonzero(b == 10) + 1, [b.size]))
    return np.diff(np.searchsorted(starts, bounds)).astype(np.int64)


def parse_vertex_lines(
    lines: list[str], line_of: Callable[[int], int], allowed: tuple[int, ...] = (3,), layout: str = "x y z",
) -> NDArray[np.float64]:
    """The first three numbers of each vertex line, after checking that every line holds an allowed count of numbers.

    ``line_of(k)`` is the file's line number (from 1) of ``lines[k]``, computed only for an
    error message; ``allowed`` are the counts of numbers a vertex line may hold (the first three
    are x y z) and ``layout`` says what they are, for the message. The fast path parses
    everything in one NumPy call and counts the numbers of each line with a vectorised scan, so
    that ``0 0`` followed by ``0 1 0 0`` (the right total, spread wrongly) is not read as two
    vertices.
    """
    joined = "\n".join(lines)
    arr = parse_numbers(joined, np.float64)
    if arr is not None and lines:
        counts = numbers_per_line(joined)
        if len(counts) == len(lines) and int(counts.sum()) == arr.size:  # the scan and NumPy agree on the tokens
            if arr.size == 3 * len(lines) and np.all(counts == 3):
                return arr.reshape(-1, 3)
            if np.all(np.isin(counts, allowed)):
                starts = np.cumsum(counts) - counts
                return arr[starts[:, None] + np.arange(3)]
    out = np.empty((len(lines), 3))
    need = " or ".join(str(n) for n in allowed)
    for k, line in enumerate(lines):
        parts = line.split()
        values = []
        for token in parts:
            try:
                values.append(parse_float(token))
            except ValueError:
                raise MeshError(
                    f"line {line_of(k)} ({line.strip()[:60]!r}) holds {token[:30]!r}, which is not a number; a vertex "
                    f"line holds {need} numbers ({layout}). The file is corrupt."
                ) from None
        if len(values) not in allowed:
            raise MeshError(
                f"line {line_of(k)} ({line.strip()[:60]!r}) holds {len(values)} numbers where a vertex line needs "
                f"{need} numbers ({layout}): the file is corrupt (a number lost, or moved onto another line)."
            )
        out[k] = values[:3]
    return out


def parse_counted_faces(
    lines: list[str], nv: int, line_of: Callable[[int], int] | None = None
) -> tuple[NDArray[np.int64], int]:
    """Faces written as 'k i_1 ... i_k [colour...]' (OFF), with 0-based indices checked against ``nv``."""
    if not lines:
        return np.zeros((0, 3), dtype=np.int64), 0
    arr = parse_numbers("\n".join(lines), np.int64)
    # Fast path: all triangles, nothing else. NumPy clamps an integer too large for int64 to the
    # extreme value; such a file takes the slow path, which reports the index as written.
    if arr is not None and arr.size == 4 * len(lines) and not clamped(arr):
        arr = arr.reshape(-1, 4)
        if np.all(arr[:, 0] == 3) and all(len(line.split()) == 4 for line in lines):
            bad = np.flatnonzero(((arr[:, 1:] < 0) | (arr[:, 1:] >= nv)).any(axis=1))
            if bad.size == 0:
                return arr[:, 1:].copy(), 0
    polygons = []
    for k, line in enumerate(lines):
        where = f"face {k}" + ("" if line_of is None else f" (line {line_of(k)})")  # faces counted from 0
        parts = line.split()
        try:
            n = parse_int(parts[0])
            if n < 0 or len(parts) < n + 1:
                raise ValueError
            poly = [parse_int(x) for x in parts[1 : n + 1]]
        except (ValueError, IndexError):
            raise MeshError(
                f"{where}, {line[:60]!r}, is not 'n i_1 ... i_n' with integer vertex indices (written as integers, "
                "e.g. 2 and not 2.0); the file is corrupt."
            ) from None
        if n < 3:
            raise MeshError(f"{where} has {n} corners; a face needs at least 3. Remove it from the file.")
        outside = [i for i in poly if not 0 <= i < nv]
        if outside:
            raise MeshError(
                f"{where}, {line[:60]!r}, uses vertex index {outside[0]}, outside 0..{nv - 1} (the file has {nv} "
                "vertices, indices are 0-based); fix the file's faces."
            )
        polygons.append(poly)
    tris, n_poly = triangulate_polygons(polygons)
    return tris, n_poly



def check_no_trailing_lines(extra: list[str], line_of: Callable[[int], int], announced: str) -> None:
    """Refuse data lines after the records a header announces (comments and blank lines were dropped before)."""
    if extra:
        raise MeshError(
            f"{len(extra)} data line{'s' if len(extra) > 1 else ''} after the {announced} the header announces "
            f"(first: line {line_of(0)}, {extra[0][:60]!r}): the header's counts are wrong or the file holds more "
            "than one mesh. Fix the counts in the header, or remove the extra lines."
        )


def line_locator(
    lines: list[str], vertex_numbers: Callable[[], list[int]], face_numbers: Callable[[], list[int]],
    face_corners: Callable[[], list[int]] | None, n_polygons: int,
) -> Callable[[str, int], str | None]:
    """``locate(kind, k)`` for :class:`RawMesh`: the line of vertex ``k`` or of the file face behind triangle ``k``.

    ``lines`` are the file's lines; ``vertex_numbers()`` and ``face_numbers()`` give the 0-based
    positions in ``lines`` of the vertex and face records, and ``face_corners()`` the corner
    count of each face (needed only when polygons were split into fans, which shifts triangle
    numbers against face numbers). Everything is computed on the first call, for a message.
    """

    def locate(kind: str, k: int) -> str | None:
        if kind == "vertex":
            numbers = vertex_numbers()
        else:
            numbers = face_numbers()
            if n_polygons and face_corners is not None:
                ends = np.cumsum(np.asarray(face_corners(), dtype=np.int64) - 2)  # a fan has corners - 2 triangles
                k = int(np.searchsorted(ends, k, side="right"))
        if not 0 <= k < len(numbers):
            return None
        return f"line {numbers[k] + 1}, {lines[numbers[k]].strip()[:60]!r}"

    return locate
