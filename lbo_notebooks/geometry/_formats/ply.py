"""PLY (ASCII, binary little and big endian): the header checked and normalised here, the body read by ``plyfile``
(or by NumPy for the common ASCII layout).
"""

from __future__ import annotations

import re
import struct
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .._mesh import MeshError, plural
from .._repair import triangulate_polygons
from .common import (
    MAX_HEADER_BYTES,
    UTF8_BOM,
    RawMesh,
    check_ends_with_line_break,
    parse_int,
    parse_numbers,
)

__all__ = ["read_ply"]


_PLY_TYPES = {
    "char": 1, "int8": 1, "uchar": 1, "uint8": 1, "short": 2, "int16": 2, "ushort": 2, "uint16": 2,
    "int": 4, "int32": 4, "uint": 4, "uint32": 4, "float": 4, "float32": 4, "double": 8, "float64": 8,
}
_PLY_FORMATS = ("ascii", "binary_little_endian", "binary_big_endian")
_FACE_LISTS = ("vertex_indices", "vertex_index")


@dataclass
class _PlyElement:
    name: str
    count: int
    row_bytes: int = 0  # the smallest size of one row (lists counted empty)
    properties: list[tuple[str, bool]] = field(default_factory=list)  # (name, is a list)


def _ply_header(p: Path) -> tuple[bytes, int, str, list[_PlyElement]]:
    """Check and normalise a PLY header.

    Returns the header rewritten in the form ``plyfile`` reads, the offset of the body, the
    format and the elements.
    """
    with open(p, "rb") as fh:
        head = fh.read(MAX_HEADER_BYTES)
    start = len(UTF8_BOM) if head.startswith(UTF8_BOM) else 0  # a byte order mark, as Windows editors write it
    if not head.startswith(b"ply", start):
        raise MeshError("not a PLY file: it must start with the line 'ply'. Check the file or its extension.")
    end = head.find(b"end_header")
    if end < 0:
        raise MeshError(f"no 'end_header' line within the first {MAX_HEADER_BYTES} bytes: the PLY header is corrupt.")
    newline = head.find(b"\n", end)
    body_start = len(head) if newline < 0 else newline + 1
    try:
        text = head[start:end].decode("ascii")
    except UnicodeDecodeError:
        raise MeshError("the PLY header holds non-ASCII bytes: it is corrupt.") from None
    fmt = None
    out = ["ply"]
    elements: list[_PlyElement] = []
    element_lines: list[int] = []  # where each element's line is in ``out``
    for line in text.splitlines()[1:]:
        parts = re.sub(r"\{[^}]*\}", " ", line).split()  # '{ ambient color }': a comment
        if not parts:
            continue
        if parts[0] in ("comment", "obj_info"):
            out.append(line.strip())
            continue
        try:
            if parts[0] == "format":
                fmt = parts[1]
                if fmt not in _PLY_FORMATS:
                    raise MeshError(f"unknown PLY format {fmt!r}; expected ascii, binary_little_endian or binary_big_endian.")
                out.append(f"format {fmt} {parts[2] if len(parts) > 2 else '1.0'}")
            elif parts[0] == "element":
                count = parse_int(parts[2])
                if count < 0:
                    raise MeshError("the PLY header announces a negative element count; it is corrupt.")
                elements.append(_PlyElement(parts[1], count))
                element_lines.append(len(out))
                out.append(f"element {parts[1]} {count}")
            elif parts[0] == "property" and parts[1] == "list":
                count_type, item_type, name = parts[2], parts[3], parts[4]
                if count_type not in _PLY_TYPES or item_type not in _PLY_TYPES:
                    raise ValueError
                elements[-1].row_bytes += _PLY_TYPES[count_type] if fmt != "ascii" else 2
                elements[-1].properties.append((name, True))
                out.append(f"property list {count_type} {item_type} {name}")
            elif parts[0] == "property":
                kind, name = parts[1], parts[2]
                if kind not in _PLY_TYPES and name in _PLY_TYPES:
                    kind, name = name, kind  # 'property ambient_red uchar', as in the PLY spec's example
                if kind not in _PLY_TYPES:
                    raise ValueError
                elements[-1].row_bytes += _PLY_TYPES[kind] if fmt != "ascii" else 2
                elements[-1].properties.append((name, False))
                out.append(f"property {kind} {name}")
            else:
                raise ValueError
        except (IndexError, ValueError) as exc:
            if isinstance(exc, MeshError):
                raise
            raise MeshError(f"unreadable PLY header line {line[:60]!r}: the header is corrupt.") from None
    if fmt is None:
        raise MeshError("the PLY header has no 'format' line; it is corrupt.")
    for e, at in zip(elements, element_lines):
        if not e.properties:
            # A row without properties holds no data. In ASCII it still takes a line of its own (empty), as
            # plyfile reads it; in binary it takes no bytes, so the element is left out of what plyfile reads
            # (whatever its count: reading it row by row would loop for nothing).
            if fmt == "ascii":
                e.row_bytes = 1
            else:
                out[at] = ""
    out = [line for line in out if line]
    out.append("end_header\n")
    return "\n".join(out).encode("ascii"), body_start, fmt, elements


def _ply_elements(p: Path, header: bytes, body_start: int, fmt: str, elements: list[_PlyElement]) -> tuple[NDArray[Any], NDArray[Any] | None]:
    """The ``vertex`` and ``face`` rows, read by plyfile.

    Binary files are memory-mapped (plyfile otherwise reads list rows one by one in Python, far
    slower on a large scan), first assuming
    triangles and then quads; plyfile needs a real file for that,
    so a normalised header goes with a copy of the body into a temporary file.
    """
    import tempfile

    import plyfile

    def read(stream: Any, known: dict[str, Any]) -> Any:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ply = plyfile.PlyData.read(stream, known_list_len=known)
        names = [e.name for e in ply.elements]
        vertex = np.array(ply["vertex"].data) if "vertex" in names else None
        face = np.array(ply["face"].data) if "face" in names else None
        return vertex, face

    with open(p, "rb") as original:
        same = original.read(body_start) == header
        stream = original if same else tempfile.TemporaryFile()
        try:
            if not same:
                original.seek(body_start)
                stream.write(header)
                stream.write(original.read())
            # Fixed-length attempts fail on mixed triangles and quads ("unexpected list length", or "early
            # end-of-file" when the fixed rows overrun the file); the general reader then reads any lists.
            attempts = [{"face": {k: n for k in _FACE_LISTS}} for n in (3, 4)] if fmt != "ascii" else []
            for known in attempts + [{}]:
                stream.seek(0)
                try:
                    vertex, face = read(stream, known)
                    break
                except plyfile.PlyElementParseError as exc:
                    if not known or ("list length" not in str(exc) and "end-of-file" not in str(exc)):
                        raise
            trailing = 0  # ASCII: checked in _ply_ascii_body (plyfile reads it through a text wrapper)
            if fmt != "ascii":
                end_of_data = stream.tell()
                trailing = stream.seek(0, 2) - end_of_data
        except (plyfile.PlyParseError, ValueError, TypeError, OverflowError, EOFError, struct.error, KeyError) as exc:
            raise MeshError(
                f"the PLY data does not match its header ({str(exc)[:120]}): the file is truncated or corrupt."
            ) from None
        finally:
            if not same:
                stream.close()
    if trailing:
        raise MeshError(
            f"{plural(trailing, 'byte')} after the {_rows(elements)} the header announces: the header's counts "
            "are wrong or the file is corrupt. Re-export it."
        )
    if vertex is None:
        raise MeshError("the PLY header declares no vertices ('element vertex N'); no mesh.")
    return vertex, face


def _ply_ascii_body(p: Path, body_start: int, elements: list[_PlyElement]) -> tuple[str, list[str]]:
    """The body of an ASCII PLY and its non-blank lines, after the checks plyfile does not make.

    plyfile reads numbers with Python's ``float`` (``1_000`` passes) and loads a file cut inside
    its last number; and a face index written ``2.0`` must be refused here as plyfile refuses it.
    """
    with open(p, "rb") as fh:
        fh.seek(body_start)
        body = fh.read().decode("latin-1")
    check_ends_with_line_break(body, comment="\n")  # no comments in a PLY body
    lines = [line for line in body.splitlines() if line.strip()]
    if "_" in body:
        k = next(k for k, line in enumerate(lines) if "_" in line)
        raise MeshError(f"data line {k} ({lines[k][:60]!r}) holds '_', which is not part of a number; the file is corrupt.")
    data_rows = sum(e.count for e in elements if e.properties)  # each a line of its own, never blank
    if len(lines) > data_rows:
        with open(p, "rb") as fh:
            header_lines = fh.read(body_start).count(b"\n")
        seen = 0
        for number, line in enumerate(body.splitlines(), start=header_lines + 1):
            seen += bool(line.strip())
            if seen > data_rows:
                break
        raise MeshError(
            f"{plural(len(lines) - data_rows, 'data line')} after the {_rows(elements)} the header announces "
            f"(first: line {number}, {line.strip()[:60]!r}): the header's counts are wrong or the file is corrupt. "
            "Fix the counts, or remove the extra lines."
        )
    at = 0
    for e in elements:
        if e.name == "face" and [is_list for _, is_list in e.properties] == [True]:
            for k, line in enumerate(lines[at : at + e.count]):
                if re.search(r"[^0-9\s+-]", line):
                    raise MeshError(
                        f"face {k} ({line[:60]!r}) is not 'n i_1 ... i_n' with integer vertex indices (written as "
                        "integers, e.g. 2 and not 2.0); the file is corrupt."
                    )
        at += e.count
    return body, lines


def _ply_ascii_fast(body: str, lines: list[str], elements: list[_PlyElement]) -> RawMesh | None:
    """ASCII PLY of scalar rows and triangle faces, parsed in one NumPy call; None if not that case.

    plyfile parses ASCII row by row in Python, much slower on a large scan; this
    covers what most files hold, with one row per line as plyfile demands. Anything else (polygons, lists outside the faces, a count that does not match the header)
    goes to plyfile, which reads it or names the problem.
    """
    widths = []
    for e in elements:
        lists = [name for name, is_list in e.properties if is_list]
        if lists and (e.name != "face" or len(lists) > 1 or lists[0] not in _FACE_LISTS):
            return None
        widths.append(len(e.properties) + 3 * len(lists))  # a triangle list is 4 numbers
    numbers = parse_numbers(body, np.float64)
    if numbers is None or numbers.size != sum(e.count * w for e, w in zip(elements, widths)):
        return None
    # One row per line, as plyfile requires (the same numbers spread differently are not this file).
    per_line = np.array([len(line.split()) for line in lines])
    if not np.array_equal(per_line, np.repeat(widths, [e.count for e in elements])):
        return None
    vertices = triangles = None
    at = 0
    for e, w in zip(elements, widths):
        rows = numbers[at : at + e.count * w].reshape(e.count, w)
        at += e.count * w
        names = [name for name, _ in e.properties]
        if e.name == "vertex":
            if not all(c in names for c in "xyz"):
                return None
            vertices = rows[:, [names.index(c) for c in "xyz"]].copy()
        elif e.name == "face" and e.count:
            key = next(name for name in names if name in _FACE_LISTS)
            col = names.index(key)  # scalars before the list take one column each
            block = rows[:, col : col + 4]
            if not (np.all(block[:, 0] == 3) and np.all(np.isfinite(block)) and np.all(block == np.round(block))):
                return None
            if np.abs(block).max() >= 2**62:
                return None
            triangles = block[:, 1:].astype(np.int64)
    if vertices is None:
        return None
    if triangles is None:
        triangles = np.zeros((0, 3), np.int64)
    return RawMesh(vertices, triangles, len(triangles), 0)


def _rows(elements: list[_PlyElement]) -> str:
    """The rows a header announces, for messages: "3 'vertex' rows and 1 'face' row"."""
    parts = [plural(e.count, f"{e.name!r} row") for e in elements]
    return parts[0] if len(parts) == 1 else ", ".join(parts[:-1]) + " and " + parts[-1]


def read_ply(p: Path, need_faces: bool = True) -> RawMesh:
    header, body_start, fmt, elements = _ply_header(p)
    counts = {e.name: e.count for e in elements}
    nv, nf = counts.get("vertex", 0), counts.get("face", 0)
    if nv <= 0:
        raise MeshError("the PLY header declares no vertices ('element vertex N'); no mesh.")
    if nf <= 0 and need_faces:
        raise MeshError("the PLY file has no faces ('element face N'): it is a point cloud, not a surface. "
                        "Read it with lbo.load_points.")
    # Before reading: the rows the header announces must fit in the file (a face holds >= 3 indices).
    min_bytes = sum(e.count * (e.row_bytes + (3 * (1 if fmt != "ascii" else 2) if e.name == "face" else 0)) for e in elements)
    size = p.stat().st_size
    if body_start + min_bytes > size:
        raise MeshError(
            f"the header announces {_rows(elements)}, which need at least {body_start + min_bytes} bytes "
            f"({'a line per row' if fmt == 'ascii' else 'their smallest binary size'}), but the file has {size}: "
            "the header is corrupt or the file is truncated. Re-export or re-download it."
        )
    if fmt == "ascii":
        fast = _ply_ascii_fast(*_ply_ascii_body(p, body_start, elements), elements)
        if fast is not None:
            return fast
    vertex, face = _ply_elements(p, header, body_start, fmt, elements)
    names = vertex.dtype.names or ()
    if not all(c in names and vertex.dtype[c].shape == () and vertex.dtype[c] != object for c in "xyz"):
        raise MeshError("the PLY vertex element lacks scalar x, y, z properties; no positions to read.")
    vertices = np.column_stack([vertex[c].astype(np.float64) for c in "xyz"])
    if nf <= 0:
        return RawMesh(vertices, np.zeros((0, 3), np.int64), 0, 0)
    key = next((name for name in _FACE_LISTS if name in (face.dtype.names or ())), None)
    if key is None:
        raise MeshError("the PLY face element has no 'vertex_indices' list; cannot read the faces.")
    lists = face[key]
    if lists.dtype != object:  # fixed-length lists (memory-mapped): one (m, corners) block
        polygons = lists.astype(np.int64).reshape(len(lists), -1)
        if polygons.shape[1] == 3:
            return RawMesh(vertices, polygons, nf, 0)
    else:
        lengths = np.fromiter((len(x) for x in lists), dtype=np.int64, count=len(lists))
        if lengths.min() < 3:
            k = int(np.argmin(lengths))
            raise MeshError(f"face {k} has {lengths[k]} corners; a face needs at least 3.")
        if np.all(lengths == 3):
            return RawMesh(vertices, np.stack(lists).astype(np.int64).reshape(-1, 3), nf, 0)
        polygons = [x.astype(np.int64).tolist() for x in lists]
    triangles, n_poly = triangulate_polygons(polygons)
    return RawMesh(vertices, triangles, nf, n_poly)
