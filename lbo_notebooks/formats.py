"""The file formats: raw readers and text writers for .off, .obj, .ply, .stl and text point lists.

This layer turns bytes into arrays and arrays into text, with no topology checks; the public
entry points are in :mod:`lbo_notebooks.io` (``load_mesh``, ``save_mesh``, ``load_points``).

How each format is handled, and why
-----------------------------------
Every file is parsed here, with NumPy doing the bulk conversion, and open3d writes the binary
formats (binary PLY at float64, binary STL). Before any data is read, the counts a header
announces (OFF, PLY, binary STL) are checked against the file size, so a corrupt header fails at
once instead of allocating gigabytes. open3d's readers were tried first and rejected because a
broken file must raise :class:`MeshError`, not kill the Python process or Jupyter kernel
(measured with open3d 0.20):

- PLY: a five-line ASCII PLY whose quad has an out-of-range index crashes the interpreter
  (segmentation fault, in its ear-clipping triangulation); randomly corrupted binary PLY files
  did the same; a truncated file or a ``nan`` gives partial, uninitialised arrays and no error.
  PLY is read with the ``plyfile`` library instead, after the header has been checked here:
  scanners write headers ``plyfile`` alone refuses (the Stanford files' ``property ambient_red
  uchar { ambient color }`` puts the name before the type and a comment in braces), so each
  header line is normalised first. Every element is read (ASCII, binary little or big endian);
  only ``vertex`` (x, y, z) and ``face`` (``vertex_indices`` or ``vertex_index``) are used.
- OFF: a file with fewer vertices than its header announces crashes the interpreter; a ``nan``
  coordinate gives uninitialised memory.
- OBJ: open3d renumbers the vertices in order of first use, drops unreferenced ones, splits a
  vertex wherever its texture or normal index changes (cutting the surface open at every seam)
  and skips faces with more than three corners. Here the ``v`` and ``f`` lines are read directly,
  so vertex ``k`` of the mesh is the ``k``-th ``v`` line and ``vt``/``vn`` seams do not exist.
- STL: open3d reads ASCII STL through ASSIMP at single precision, and its binary reader took
  about 4 s for 200k triangles; a binary STL is a header and fixed 50-byte records, read here
  with one ``numpy.fromfile`` call.
- open3d writes text formats with six significant digits, which is lossy; here they are written
  with 17, so that saving and loading gives back the same float64 coordinates.

Numbers are read as C and every mesh tool writes them: Python's ``1_000`` is not a number, and a
vertex index must be written as an integer (``2``, not ``2.0`` or ``2e0``) in every format; an
index too large for a 64-bit integer is reported as written. A truncated file is refused wherever
the format lets us tell: counts announced by a header (OFF, PLY, binary STL) are checked, an ASCII
STL must end with ``endsolid`` after complete facets, a ``.pts`` count line must match its points,
and the last line of a text file must end with a line break unless it ends in a comment, because a
file cut inside its last number (``3 0 1 12`` cut to ``3 0 1 1``) still parses. OBJ and the other
point lists announce no count: one cut exactly at a line break loses whole lines unseen.

STL stores three separate corners per triangle: corners with exactly equal coordinates are
welded back into shared vertices, numbered in order of first appearance, so a closed surface
stays closed.

Polygons (faces with more than three corners, in OFF, OBJ or PLY) are refused by default with a
:class:`MeshError`; with ``clean=True`` each is split into a fan of triangles from its first
corner (right for convex polygons, which is what exporters write) and the split is reported.

Examples
--------
>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "tri.off"
>>> _ = path.write_text(mesh_text([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], ".off"))
>>> raw = read_raw(path)
>>> raw.triangles.tolist(), raw.n_polygons
([[0, 1, 2]], 0)
"""

from __future__ import annotations

import re
import struct
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .mesh import MeshError, unique_rows
from .repair import triangulate_polygons

__all__ = ["FORMATS", "POINT_FORMATS", "BINARY_FORMATS", "RawMesh", "read_raw", "read_point_text", "mesh_text"]

#: Supported mesh file extensions (lower case, with the dot).
FORMATS: tuple[str, ...] = (".off", ".obj", ".ply", ".stl")
#: Mesh formats that also have a binary form.
BINARY_FORMATS: tuple[str, ...] = (".ply", ".stl")
#: Extensions :func:`~lbo_notebooks.load_points` reads: the mesh formats (their vertices) and text point lists.
POINT_FORMATS: tuple[str, ...] = FORMATS + (".xyz", ".pts", ".txt", ".csv")

# Smallest number of bytes a record can take in a text file: "0 0 0\n" and "3 0 1 2\n".
_MIN_TEXT_VERTEX_BYTES = 6
_MIN_TEXT_FACE_BYTES = 8
_MAX_HEADER_BYTES = 1 << 16


@dataclass(frozen=True)
class RawMesh:
    """A file's vertices and triangles as read, before any topology check."""

    vertices: NDArray[np.float64]
    triangles: NDArray[np.int64]
    n_file_faces: int  # faces as the file lists them
    n_polygons: int  # faces with more than three corners



def read_raw(p: Path, *, need_faces: bool = True) -> RawMesh:
    """Read the mesh file ``p`` (extension in :data:`FORMATS`, already checked to exist).

    Structural problems raise :class:`MeshError` naming the file; polygons are split into fans.
    With ``need_faces=False`` a file without faces (a point cloud) is not an error.
    """
    ext = p.suffix.lower()
    reader = {".off": _read_off, ".obj": _read_obj, ".ply": _read_ply, ".stl": _read_stl}[ext]
    try:
        return reader(p) if ext in (".off", ".stl") else reader(p, need_faces)
    except MeshError as exc:
        raise MeshError(f"{str(p)!r}: {exc}") from None


def _read_text(p: Path, kind: str) -> str:
    data = p.read_bytes()
    if b"\x00" in data[: 1 << 16]:
        raise MeshError(
            f"this is binary data, not a text {kind} file (it contains NUL bytes). "
            f"Check that the file really is an {kind} file; re-export it from its source."
        )
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]  # a UTF-8 byte order mark, as some Windows editors write it: not data
    return data.decode("latin-1")


def _check_ends_with_line_break(text: str, comment: str = "#") -> None:
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


def _int(token: str) -> int:
    """``int(token)`` for integers as files write them (Python's ``1_000`` is refused)."""
    if "_" in token:
        raise ValueError(token)
    return int(token)


def _float(token: str) -> float:
    """``float(token)`` for numbers as files write them (Python's ``1_000`` is refused)."""
    if "_" in token:
        raise ValueError(token)
    return float(token)


def _clamped(ints: NDArray[np.int64]) -> bool:
    """True if :func:`_numbers` may have clamped an integer too large for int64 (it returns the extreme)."""
    info = np.iinfo(np.int64)
    return bool(ints.size) and (int(ints.max()) == info.max or int(ints.min()) == info.min)


def _content_lines(text: str) -> list[str]:
    out = []
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            out.append(line)
    return out


def _read_off(p: Path) -> RawMesh:
    text = _read_text(p, "OFF")
    lines = _content_lines(text)
    if lines:
        _check_ends_with_line_break(text)
    if not lines:
        raise MeshError("the file holds only comments or blank lines; no mesh.")
    head = lines[0].split()
    if not head[0].endswith("OFF"):
        raise MeshError(f"not an OFF file: the first line must be 'OFF', got {lines[0][:40]!r}.")
    if head[0] not in ("OFF", "COFF", "NOFF", "CNOFF"):
        raise MeshError(f"unsupported OFF variant {head[0]!r}; re-export as plain 'OFF'.")
    if len(head) > 1 and head[1].upper() == "BINARY":
        raise MeshError("binary OFF is not supported; re-export as text OFF, PLY or STL.")
    rest = lines[1:]
    counts = head[1:4] if len(head) >= 4 else (rest[0].split()[:3] if rest else [])
    if len(head) < 4:
        rest = rest[1:]
    try:
        nv, nf = _int(counts[0]), _int(counts[1])
    except (ValueError, IndexError):
        raise MeshError(
            f"the OFF header must give 'n_vertices n_faces n_edges' as integers, got {' '.join(counts)!r}."
        ) from None
    if nv < 0 or nf < 0:
        raise MeshError(f"the OFF header announces negative counts ({nv} vertices, {nf} faces).")
    _check_counts(p, nv, nf, nv * _MIN_TEXT_VERTEX_BYTES + nf * _MIN_TEXT_FACE_BYTES)
    if len(rest) < nv + nf:
        raise MeshError(
            f"the header announces {nv} vertices and {nf} faces but the file has only {len(rest)} "
            "data lines: it is truncated. Re-export or re-download it."
        )
    vertices = _parse_vertex_lines(rest[:nv], 0)
    face_lines = rest[nv : nv + nf]
    triangles, n_poly = _parse_counted_faces(face_lines, nv)
    return RawMesh(vertices, triangles, nf, n_poly)


def _check_counts(p: Path, nv: int, nf: int, min_bytes: int) -> None:
    size = p.stat().st_size
    if min_bytes > size:
        raise MeshError(
            f"the header announces {nv} vertices and {nf} faces, which need at least {min_bytes} bytes, "
            f"but the file has {size}: the header is corrupt or the file is truncated. "
            "Re-export or re-download it."
        )


def _numbers(text: str, dtype: Any) -> NDArray[Any] | None:
    """All whitespace-separated numbers of ``text`` (C speed), or None if one is not a number."""
    import warnings as _w

    with _w.catch_warnings():
        _w.simplefilter("ignore")  # numpy < 2 warns (instead of raising) on unparsable text
        try:
            return np.fromstring(text, dtype=dtype, sep=" ")
        except ValueError:
            return None


def _parse_vertex_lines(lines: list[str], first_line: int) -> NDArray[np.float64]:
    arr = _numbers("\n".join(lines), np.float64)
    if arr is not None and arr.size == 3 * len(lines):  # fast path: three numbers per line
        return arr.reshape(-1, 3)
    out = np.empty((len(lines), 3))
    for k, line in enumerate(lines):
        parts = line.split()
        try:
            if len(parts) < 3:
                raise ValueError
            out[k] = [_float(x) for x in parts[:3]]
        except ValueError:
            raise MeshError(
                f"vertex {k} ({line[:60]!r}) is not three numbers x y z; the file is corrupt."
            ) from None
    return out


def _parse_counted_faces(lines: list[str], nv: int) -> tuple[NDArray[np.int64], int]:
    """Faces written as 'k i_1 ... i_k [colour...]' (OFF), with 0-based indices checked against ``nv``."""
    if not lines:
        return np.zeros((0, 3), dtype=np.int64), 0
    arr = _numbers("\n".join(lines), np.int64)
    # Fast path: all triangles, nothing else. NumPy clamps an integer too large for int64 to the
    # extreme value; such a file takes the slow path, which reports the index as written.
    if arr is not None and arr.size == 4 * len(lines) and not _clamped(arr):
        arr = arr.reshape(-1, 4)
        if np.all(arr[:, 0] == 3) and all(len(line.split()) == 4 for line in lines):
            bad = np.flatnonzero(((arr[:, 1:] < 0) | (arr[:, 1:] >= nv)).any(axis=1))
            if bad.size == 0:
                return arr[:, 1:].copy(), 0
    polygons = []
    for k, line in enumerate(lines):
        parts = line.split()
        try:
            n = _int(parts[0])
            if n < 0 or len(parts) < n + 1:
                raise ValueError
            poly = [_int(x) for x in parts[1 : n + 1]]
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


def _read_obj(p: Path, need_faces: bool = True) -> RawMesh:
    text = _read_text(p, "OBJ")
    _check_ends_with_line_break(text)
    lines = [line.lstrip() for line in text.splitlines()]  # an indented 'v' line is still a vertex
    vertex_lines = [line[2:].split("#", 1)[0] for line in lines if line[:2] in ("v ", "v\t")]
    face_lines = [line[2:] for line in lines if line[:2] in ("f ", "f\t")]
    if not vertex_lines:
        raise MeshError("no vertex ('v x y z') lines found; this is not an OBJ mesh.")
    if not face_lines and not need_faces:
        return RawMesh(_parse_vertex_lines(vertex_lines, 0), np.zeros((0, 3), np.int64), 0, 0)
    if not face_lines:
        raise MeshError("no face ('f a b c') lines found: the file is a point cloud or line set, not a surface. Read its points with lbo.load_points.")
    vertices = _parse_vertex_lines(vertex_lines, 0)
    block = "\n".join(face_lines)
    if "-" not in block and "#" not in block:
        # Fast path: positive indices only; keep the vertex index of each 'v/vt/vn' corner.
        if "/" in block:
            block = re.sub(r"/\S*", "", block)
        idx = _numbers(block, np.int64)
        if idx is not None and not _clamped(idx) and idx.size == 3 * len(face_lines) and all(len(x.split()) == 3 for x in block.split("\n")):
            if idx.size and idx.min() == 0:
                raise MeshError("a face uses vertex index 0; OBJ indices are 1-based. Fix the file's 'f' lines.")
            return RawMesh(vertices, _obj_check_range(idx.reshape(-1, 3) - 1, len(vertices)), len(face_lines), 0)
    # General path: polygons, negative (relative) indices, comments.
    polygons: list[list[int]] = []
    nv, n_total = 0, len(vertices)
    for lineno, line in enumerate(lines, start=1):
        if line[:2] in ("v ", "v\t"):
            nv += 1
        elif line[:2] in ("f ", "f\t"):
            poly = []
            try:
                for token in line[2:].split("#", 1)[0].split():
                    i = _int(token.split("/", 1)[0])
                    if i == 0:
                        raise ValueError
                    if not (i <= n_total if i > 0 else nv + i >= 0):
                        raise MeshError(
                            f"line {lineno} ({line[:60]!r}) uses vertex index {i}, outside 1..{n_total} (the file "
                            f"has {n_total} 'v' lines; a negative index counts back from the {nv} 'v' lines above "
                            "it); fix the file's 'f' lines."
                        )
                    poly.append(i - 1 if i > 0 else nv + i)  # negative: relative to the last vertex
            except ValueError as exc:
                if isinstance(exc, MeshError):
                    raise
                raise MeshError(
                    f"line {lineno} ({line[:60]!r}) is not a face of 1-based integer vertex indices 'f a b c' "
                    "(or 'a/t/n'); the file is corrupt."
                ) from None
            if len(poly) < 3:
                raise MeshError(f"line {lineno}: a face needs at least 3 corners, got {len(poly)}.")
            polygons.append(poly)
    triangles, n_poly = triangulate_polygons(polygons)
    return RawMesh(vertices, triangles, len(polygons), n_poly)  # indices checked above, as written


def _obj_check_range(triangles: NDArray[np.int64], nv: int) -> NDArray[np.int64]:
    bad = np.flatnonzero(((triangles < 0) | (triangles >= nv)).any(axis=1))
    if bad.size:
        raise MeshError(
            f"{bad.size} faces use vertex indices outside 1..{nv} (first: triangle {bad[0]} = "
            f"{(triangles[bad[0]] + 1).tolist()}, 1-based as in the file) but the file has {nv} 'v' lines; "
            "fix the file's 'f' lines."
        )
    return triangles


# PLY property types (both spellings of the format's spec) and the smallest size of each.
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
        head = fh.read(_MAX_HEADER_BYTES)
    if not head.startswith(b"ply"):
        raise MeshError("not a PLY file: it must start with the line 'ply'. Check the file or its extension.")
    end = head.find(b"end_header")
    if end < 0:
        raise MeshError(f"no 'end_header' line within the first {_MAX_HEADER_BYTES} bytes: the PLY header is corrupt.")
    newline = head.find(b"\n", end)
    body_start = len(head) if newline < 0 else newline + 1
    try:
        text = head[:end].decode("ascii")
    except UnicodeDecodeError:
        raise MeshError("the PLY header holds non-ASCII bytes: it is corrupt.") from None
    fmt = None
    out = ["ply"]
    elements: list[_PlyElement] = []
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
                count = _int(parts[2])
                if count < 0:
                    raise MeshError("the PLY header announces a negative element count; it is corrupt.")
                elements.append(_PlyElement(parts[1], count))
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
    out.append("end_header\n")
    return "\n".join(out).encode("ascii"), body_start, fmt, elements


def _ply_elements(p: Path, header: bytes, body_start: int, fmt: str) -> tuple[NDArray[Any], NDArray[Any] | None]:
    """The ``vertex`` and ``face`` rows, read by plyfile.

    Binary files are memory-mapped (plyfile reads list rows one by one in Python otherwise:
    about 120x slower on a 200k-triangle scan, see ``benchmarks/ply.py``), first assuming
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
            attempts = [{"face": {k: n for k in _FACE_LISTS}} for n in (3, 4)] if fmt != "ascii" else []
            for known in attempts + [{}]:
                stream.seek(0)
                try:
                    vertex, face = read(stream, known)
                    break
                except plyfile.PlyElementParseError as exc:
                    if not known or "list length" not in str(exc):
                        raise
        except (plyfile.PlyParseError, ValueError, TypeError, OverflowError, EOFError, struct.error, KeyError) as exc:
            raise MeshError(
                f"the PLY data does not match its header ({str(exc)[:120]}): the file is truncated or corrupt."
            ) from None
        finally:
            if not same:
                stream.close()
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
    _check_ends_with_line_break(body, comment="\n")  # no comments in a PLY body
    lines = [line for line in body.splitlines() if line.strip()]
    if "_" in body:
        k = next(k for k, line in enumerate(lines) if "_" in line)
        raise MeshError(f"data line {k} ({lines[k][:60]!r}) holds '_', which is not part of a number; the file is corrupt.")
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

    plyfile parses ASCII row by row in Python (about 8x slower on a 100k-vertex scan,
    ``benchmarks/ply.py``); this
    covers what most files hold, with one row per line as plyfile demands. Anything else (polygons, lists outside the faces, a count that does not match the header)
    goes to plyfile, which reads it or names the problem.
    """
    widths = []
    for e in elements:
        lists = [name for name, is_list in e.properties if is_list]
        if lists and (e.name != "face" or len(lists) > 1 or lists[0] not in _FACE_LISTS):
            return None
        widths.append(len(e.properties) + 3 * len(lists))  # a triangle list is 4 numbers
    numbers = _numbers(body, np.float64)
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
        elif e.name == "face":
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


def _read_ply(p: Path, need_faces: bool = True) -> RawMesh:
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
    _check_counts(p, nv, nf, body_start + min_bytes)
    if fmt == "ascii":
        fast = _ply_ascii_fast(*_ply_ascii_body(p, body_start, elements), elements)
        if fast is not None:
            return fast
    vertex, face = _ply_elements(p, header, body_start, fmt)
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


def _read_stl(p: Path) -> RawMesh:
    size = p.stat().st_size
    with open(p, "rb") as fh:
        head = fh.read(84)
    n_binary = struct.unpack("<I", head[80:84])[0] if len(head) == 84 else -1
    if n_binary >= 0 and 84 + 50 * n_binary == size:
        if n_binary == 0:
            raise MeshError("the binary STL file holds 0 triangles; no mesh.")
        # 50-byte records: normal (3 float32), three corners (9 float32), attribute (uint16).
        record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
        data = np.fromfile(p, dtype=record, count=n_binary, offset=84)
        corners = data["corners"].reshape(-1, 3).astype(np.float64)
    elif head.lstrip().startswith(b"solid"):
        corners = _stl_ascii_corners(p)
    else:
        announced = f"{n_binary} triangles = {84 + 50 * n_binary} bytes" if n_binary >= 0 else "nothing"
        raise MeshError(
            f"neither a binary STL (its header announces {announced}, but the file has {size} bytes) "
            "nor an ASCII STL (which starts with 'solid'): the file is truncated or not an STL file."
        )
    if not np.all(np.isfinite(corners)):
        bad = int(np.flatnonzero(~np.isfinite(corners).all(axis=1))[0]) // 3
        raise MeshError(
            f"triangle {bad} has non-finite (NaN or inf) corner coordinates; fix or remove it in the source."
        )
    vertices, triangles = _weld_corners(corners)
    return RawMesh(vertices, triangles, len(triangles), 0)


def _stl_ascii_corners(p: Path) -> NDArray[np.float64]:
    """The corners of an ASCII STL, after checking that its facets are complete and ``endsolid`` ends it.

    A file cut anywhere, even inside a number of its last facet, lacks its final ``endsolid``
    line; a facet damaged inside lacks one of its keywords, so the keyword counts disagree.
    """
    text = _read_text(p, "ASCII STL")
    first, end = text.find("\n"), len(text.rstrip())
    last_start = text.rfind("\n", 0, end)
    last = text[last_start + 1 : end].strip() if 0 <= first < last_start else ""
    body = text[first + 1 : last_start] if last else ""  # between the 'solid name' and 'endsolid name' lines
    rows = re.findall(r"^[ \t]*vertex[ \t]+(.*)$", body, flags=re.MULTILINE)
    if not last.startswith("endsolid"):
        raise MeshError(
            f"the ASCII STL file does not end with an 'endsolid' line (it ends with {last[-40:]!r}): it is "
            f"truncated, cut off after about {len(rows) // 3} facets. Re-export or re-download it."
        )
    n_end = body.count("endfacet")
    counts = {"facet": body.count("facet") - n_end, "outer loop": body.count("outer"),
              "vertex": len(rows), "endloop": body.count("endloop"), "endfacet": n_end}
    if counts["facet"] == 0:
        raise MeshError("the ASCII STL file holds no facets; no mesh.")
    m = counts["facet"]
    if any(n != m for word, n in counts.items() if word != "vertex") or counts["vertex"] != 3 * m:
        found = ", ".join(f"{n} '{word}'" for word, n in counts.items())
        raise MeshError(
            f"the ASCII STL file's facets are incomplete ({found}; each facet is 'facet normal nx ny nz', "
            "'outer loop', three 'vertex x y z', 'endloop', 'endfacet'): it is truncated or corrupt. "
            "Re-export or re-download it."
        )
    return _parse_vertex_lines(rows, 0)


def _weld_corners(corners: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Shared vertices from per-triangle corners: exactly equal points become one vertex.

    Vertices are numbered in order of first appearance in the corner list.
    """
    first, inverse = unique_rows(corners)
    order = np.argsort(first, kind="stable")  # groups sorted by first appearance
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    return corners[first[order]].copy(), rank[inverse].reshape(-1, 3).astype(np.int64)




def mesh_text(vertices: ArrayLike, faces: ArrayLike, ext: str) -> str:
    """The text of a mesh file in format ``ext`` (".off", ".obj", ".ply" ASCII, ".stl" ASCII).

    Coordinates at 17 significant digits, so that reading gives back the same float64 values.
    """
    v, f = np.asarray(vertices, dtype=np.float64), np.asarray(faces, dtype=np.int64)
    writer = {".off": _off_text, ".obj": _obj_text, ".ply": _ply_text, ".stl": _stl_text}[ext]
    return writer(v, f)


def _rows(a: NDArray[Any], fmt: str) -> str:
    if len(a) == 0:
        return ""
    return "\n".join(fmt % tuple(row) for row in a.tolist()) + "\n"


_XYZ = "%.17g %.17g %.17g"


def _off_text(v: NDArray[np.float64], f: NDArray[np.int64]) -> str:
    return f"OFF\n{len(v)} {len(f)} 0\n" + _rows(v, _XYZ) + _rows(f, "3 %d %d %d")


def _obj_text(v: NDArray[np.float64], f: NDArray[np.int64]) -> str:
    return "# written by lbo_notebooks\n" + _rows(v, "v " + _XYZ) + _rows(f + 1, "f %d %d %d")


def _ply_text(v: NDArray[np.float64], f: NDArray[np.int64]) -> str:
    header = (
        "ply\nformat ascii 1.0\ncomment written by lbo_notebooks\n"
        f"element vertex {len(v)}\nproperty double x\nproperty double y\nproperty double z\n"
        f"element face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    return header + _rows(v, _XYZ) + _rows(f, "3 %d %d %d")


def _stl_text(v: NDArray[np.float64], f: NDArray[np.int64]) -> str:
    p = v[f]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), np.finfo(float).tiny)
    facet = (
        "facet normal %.9g %.9g %.9g\n outer loop\n  vertex " + _XYZ + "\n  vertex " + _XYZ
        + "\n  vertex " + _XYZ + "\n endloop\nendfacet"
    )
    rows = np.concatenate([n, p.reshape(-1, 9)], axis=1)
    return "solid lbo_notebooks\n" + _rows(rows, facet) + "endsolid lbo_notebooks\n"




def read_point_text(p: Path) -> NDArray[np.float64]:
    """The first three columns of a text point list (.xyz, .pts, .txt, .csv), shape (n, 3).

    Numbers are separated by spaces, tabs, commas or semicolons; ``#`` and ``//`` start comments.
    A first line holding one integer is a count (``.pts``) and must equal the number of points; a
    first line starting with a word (such as ``x,y,z``) is a header and is skipped.
    """
    text = _read_text(p, "point")
    _check_ends_with_line_break(text, comment="#|//")
    lines = [re.split(r"#|//", line, maxsplit=1)[0].strip() for line in text.splitlines()]
    lines = [line for line in lines if line]
    if not lines:
        raise MeshError("the file holds only comments or blank lines; no points.")
    rows = [re.split(r"[\s,;]+", line) for line in lines]

    def is_number(token: str) -> bool:
        try:
            _float(token)
            return True
        except ValueError:
            return False

    if len(rows[0]) == 1 and len(rows) > 1 and is_number(rows[0][0]):  # a count line (.pts)
        try:
            count = _int(rows[0][0])
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
            out[k] = [_float(x) for x in row[:3]]
        except ValueError:
            raise MeshError(f"point {k} ({' '.join(row)[:60]!r}) does not start with three numbers x y z; the file is corrupt.") from None
    return out

