"""What every reader shares: the raw result, the extensions, strict number parsing, count checks.

Numbers are read as C and every mesh tool writes them (Python's ``1_000`` is not a number); a
count a header announces is checked against the file size before anything is allocated. See
:mod:`lbo_notebooks.formats` for the reasons.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..mesh import MeshError
from ..repair import triangulate_polygons

__all__ = [
    "FORMATS", "BINARY_FORMATS", "POINT_FORMATS", "MIN_TEXT_VERTEX_BYTES", "MIN_TEXT_FACE_BYTES",
    "MAX_HEADER_BYTES", "RawMesh", "read_text", "check_ends_with_line_break", "parse_int",
    "parse_float", "clamped", "content_lines", "check_counts", "parse_numbers", "parse_vertex_lines",
    "parse_counted_faces"
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



def read_text(p: Path, kind: str) -> str:
    data = p.read_bytes()
    if b"\x00" in data[: 1 << 16]:
        raise MeshError(
            f"this is binary data, not a text {kind} file (it contains NUL bytes). "
            f"Check that the file really is an {kind} file; re-export it from its source."
        )
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]  # a UTF-8 byte order mark, as some Windows editors write it: not data
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


def content_lines(text: str) -> list[str]:
    out = []
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            out.append(line)
    return out


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


def parse_vertex_lines(lines: list[str], first_line: int) -> NDArray[np.float64]:
    arr = parse_numbers("\n".join(lines), np.float64)
    if arr is not None and arr.size == 3 * len(lines):  # fast path: three numbers per line
        return arr.reshape(-1, 3)
    out = np.empty((len(lines), 3))
    for k, line in enumerate(lines):
        parts = line.split()
        try:
            if len(parts) < 3:
                raise ValueError
            out[k] = [parse_float(x) for x in parts[:3]]
        except ValueError:
            raise MeshError(
                f"vertex {k} ({line[:60]!r}) is not three numbers x y z; the file is corrupt."
            ) from None
    return out


def parse_counted_faces(lines: list[str], nv: int) -> tuple[NDArray[np.int64], int]:
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
        parts = line.split()
        try:
            n = parse_int(parts[0])
            if n < 0 or len(parts) < n + 1:
                raise ValueError
            poly = [parse_int(x) for x in parts[1 : n + 1]]
        except (ValueError, IndexError):
            raise MeshError(
                f"face {k} ({line[:60]!r}) is not 'n i_1 ... i_n' with integer vertex indices (written as integers, e.g. 2 and not 2.0); the file is corrupt."
            ) from None
        if n < 3:
            raise MeshError(f"face {k} has {n} corners; a face needs at least 3. Remove it from the file.")
        outside = [i for i in poly if not 0 <= i < nv]
        if outside:
            raise MeshError(
                f"face {k} ({line[:60]!r}) uses vertex index {outside[0]}, outside 0..{nv - 1} (the file has {nv} "
                "vertices, indices are 0-based); fix the file's faces."
            )
        polygons.append(poly)
    tris, n_poly = triangulate_polygons(polygons)
    return tris, n_poly
