"""Reading, writing and repairing triangle-mesh files (.off, .obj, .ply, .stl).

:func:`load_mesh` returns a validated :class:`~lbo_notebooks.Mesh` whose vertices are exactly
the ones the file lists, in the file's order; :func:`save_mesh` writes one;
:func:`clean_mesh` repairs what can be repaired and reports what it changed.

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

STL stores three separate corners per triangle: corners with exactly equal coordinates are
welded back into shared vertices, numbered in order of first appearance, so a closed surface
stays closed.

Polygons (faces with more than three corners, in OFF, OBJ or PLY) are refused by default with a
:class:`MeshError`; with ``clean=True`` each is split into a fan of triangles from its first
corner (right for convex polygons, which is what exporters write) and the split is reported.

Examples
--------
>>> import tempfile, pathlib
>>> from lbo_notebooks import shapes
>>> sphere = shapes.icosphere(2)
>>> path = pathlib.Path(tempfile.mkdtemp()) / "sphere.ply"
>>> _ = save_mesh(sphere, path)
>>> load_mesh(path) == sphere
True
"""

from __future__ import annotations

import os
import re
import struct
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Sequence, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .mesh import DEGENERATE_AREA_TOL, Mesh, MeshError, validate_topology

__all__ = ["load_mesh", "save_mesh", "clean_mesh", "read_mesh_arrays", "CleanReport", "MeshRepairWarning", "FORMATS"]

PathLike = Union[str, "os.PathLike[str]"]

#: Supported file extensions (lower case, with the dot).
FORMATS: tuple[str, ...] = (".off", ".obj", ".ply", ".stl")
_BINARY_FORMATS = (".ply", ".stl")

# Smallest number of bytes a record can take in a text file: "0 0 0\n" and "3 0 1 2\n".
_MIN_TEXT_VERTEX_BYTES = 6
_MIN_TEXT_FACE_BYTES = 8
_MAX_HEADER_BYTES = 1 << 16


class MeshRepairWarning(UserWarning):
    """Issued by :func:`load_mesh` with ``clean=True`` when it changed the mesh; says what."""


# =============================================================================================
# Raw reading: file -> (vertices, triangles) without any topology check
# =============================================================================================
@dataclass(frozen=True)
class _Raw:
    vertices: NDArray[np.float64]
    triangles: NDArray[np.int64]
    n_file_faces: int  # faces as the file lists them
    n_polygons: int  # faces with more than three corners


def _check_path(path: PathLike) -> Path:
    p = Path(os.fspath(path))
    ext = p.suffix.lower()
    if ext not in FORMATS:
        raise ValueError(
            f"unsupported mesh file extension {p.suffix!r} in {str(p)!r}; supported: {', '.join(FORMATS)}."
        )
    if not p.exists():
        raise FileNotFoundError(f"no such mesh file: {str(p)!r}")
    if not p.is_file():
        raise MeshError(f"{str(p)!r} is not a regular file; pass the path of a mesh file.")
    if p.stat().st_size == 0:
        raise MeshError(f"{str(p)!r} is empty (0 bytes); it holds no mesh. Re-export or re-download it.")
    return p


def read_mesh_arrays(path: PathLike) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Read a mesh file's vertices and triangles without any topology check.

    This is the raw material for :func:`clean_mesh` when :func:`load_mesh` refuses a file.
    Structural problems (truncated or junk files, absurd header counts) still raise. Polygons
    are split into fans of triangles.

    Parameters
    ----------
    path : str or os.PathLike
        A ``.off``, ``.obj``, ``.ply`` or ``.stl`` file.

    Returns
    -------
    vertices : ndarray, shape (n, 3), float64
        As the file lists them (STL: welded corners, in order of first appearance).
    faces : ndarray, shape (m, 3), int64
        0-based triangles; not checked against ``n``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "dup.off"
    >>> _ = path.write_text("OFF\\n3 2 0\\n0 0 0\\n1 0 0\\n0 1 0\\n3 0 1 2\\n3 0 1 2\\n")
    >>> v, f = read_mesh_arrays(path)
    >>> f.tolist()
    [[0, 1, 2], [0, 1, 2]]
    """
    raw = _read_raw(_check_path(path))
    return raw.vertices, raw.triangles


def _read_raw(p: Path) -> _Raw:
    ext = p.suffix.lower()
    reader = {".off": _read_off, ".obj": _read_obj, ".ply": _read_ply, ".stl": _read_stl}[ext]
    try:
        return reader(p)
    except MeshError as exc:
        raise MeshError(f"{str(p)!r}: {exc}") from None


def _read_text(p: Path, kind: str) -> str:
    data = p.read_bytes()
    if b"\x00" in data[: 1 << 16]:
        raise MeshError(
            f"this is binary data, not a text {kind} file (it contains NUL bytes). "
            f"Check that the file really is an {kind} file; re-export it from its source."
        )
    return data.decode("latin-1")


def _content_lines(text: str) -> list[str]:
    out = []
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            out.append(line)
    return out


def _fan(polygons: Sequence[Sequence[int]]) -> tuple[NDArray[np.int64], int]:
    """Triangles from polygons: a fan from each polygon's first corner; also the polygon count."""
    tris: list[tuple[int, int, int]] = []
    n_poly = 0
    for poly in polygons:
        if len(poly) > 3:
            n_poly += 1
        a = poly[0]
        for k in range(1, len(poly) - 1):
            tris.append((a, poly[k], poly[k + 1]))
    return np.array(tris, dtype=np.int64).reshape(-1, 3), n_poly


def _read_off(p: Path) -> _Raw:
    text = _read_text(p, "OFF")
    lines = _content_lines(text)
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
        nv, nf = int(counts[0]), int(counts[1])
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
    return _Raw(vertices, triangles, nf, n_poly)


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
            out[k] = [float(x) for x in parts[:3]]
        except ValueError:
            raise MeshError(
                f"vertex {k} ({line[:60]!r}) is not three numbers x y z; the file is corrupt."
            ) from None
    return out


def _parse_counted_faces(lines: list[str], nv: int) -> tuple[NDArray[np.int64], int]:
    """Faces written as 'k i_1 ... i_k [colour...]' (OFF)."""
    if not lines:
        return np.zeros((0, 3), dtype=np.int64), 0
    arr = _numbers("\n".join(lines), np.int64)
    if arr is not None and arr.size == 4 * len(lines):  # fast path: all triangles, nothing else
        arr = arr.reshape(-1, 4)
        if np.all(arr[:, 0] == 3) and all(len(line.split()) == 4 for line in lines):
            return arr[:, 1:].copy(), 0
    polygons = []
    for k, line in enumerate(lines):
        parts = line.split()
        try:
            n = int(parts[0])
            if n < 0 or len(parts) < n + 1:
                raise ValueError
            poly = [int(x) for x in parts[1 : n + 1]]
        except (ValueError, IndexError, OverflowError):
            raise MeshError(
                f"face {k} ({line[:60]!r}) is not 'n i_1 ... i_n' with integer vertex indices; the file is corrupt."
            ) from None
        if n < 3:
            raise MeshError(f"face {k} has {n} corners; a face needs at least 3. Remove it from the file.")
        polygons.append(poly)
    tris, n_poly = _fan(polygons)
    return tris, n_poly


def _read_obj(p: Path) -> _Raw:
    text = _read_text(p, "OBJ")
    lines = text.splitlines()
    vertex_lines = [line[2:].split("#", 1)[0] for line in lines if line[:2] in ("v ", "v\t")]
    face_lines = [line[2:] for line in lines if line[:2] in ("f ", "f\t")]
    if not vertex_lines:
        raise MeshError("no vertex ('v x y z') lines found; this is not an OBJ mesh.")
    if not face_lines:
        raise MeshError("no face ('f a b c') lines found: the file is a point cloud or line set, not a surface.")
    vertices = _parse_vertex_lines(vertex_lines, 0)
    block = "\n".join(face_lines)
    if "-" not in block and "#" not in block:
        # Fast path: positive indices only; keep the vertex index of each 'v/vt/vn' corner.
        if "/" in block:
            block = re.sub(r"/\S*", "", block)
        idx = _numbers(block, np.int64)
        if idx is not None and idx.size == 3 * len(face_lines) and all(len(x.split()) == 3 for x in block.split("\n")):
            if idx.size and idx.min() == 0:
                raise MeshError("a face uses vertex index 0; OBJ indices are 1-based. Fix the file's 'f' lines.")
            return _Raw(vertices, _obj_check_range(idx.reshape(-1, 3) - 1, len(vertices)), len(face_lines), 0)
    # General path: polygons, negative (relative) indices, comments.
    polygons: list[list[int]] = []
    nv = 0
    for lineno, line in enumerate(lines, start=1):
        if line[:2] in ("v ", "v\t"):
            nv += 1
        elif line[:2] in ("f ", "f\t"):
            poly = []
            try:
                for token in line[2:].split("#", 1)[0].split():
                    i = int(token.split("/", 1)[0])
                    if i == 0:
                        raise ValueError
                    poly.append(i - 1 if i > 0 else nv + i)  # negative: relative to the last vertex
            except ValueError:
                raise MeshError(
                    f"line {lineno} ({line[:60]!r}) is not a face of 1-based vertex indices 'f a b c' "
                    "(or 'a/t/n'); the file is corrupt."
                ) from None
            if len(poly) < 3:
                raise MeshError(f"line {lineno}: a face needs at least 3 corners, got {len(poly)}.")
            polygons.append(poly)
    triangles, n_poly = _fan(polygons)
    return _Raw(vertices, _obj_check_range(triangles, len(vertices)), len(polygons), n_poly)


def _obj_check_range(triangles: NDArray[np.int64], nv: int) -> NDArray[np.int64]:
    bad = np.flatnonzero(((triangles < 0) | (triangles >= nv)).any(axis=1))
    if bad.size:
        raise MeshError(
            f"{bad.size} faces use vertex indices outside 1..{nv} (first: triangle {bad[0]} = "
            f"{(triangles[bad[0]] + 1).tolist()}, 1-based as in the file) but the file has {nv} 'v' lines; "
            "fix the file's 'f' lines."
        )
    return triangles


# PLY property type -> numpy type code (sizes follow).
_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
    "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}
_STRUCT = {"i1": "b", "u1": "B", "i2": "h", "u2": "H", "i4": "i", "u4": "I", "f4": "f", "f8": "d"}
_FACE_LISTS = ("vertex_indices", "vertex_index")


@dataclass(frozen=True)
class _PlyProperty:
    name: str
    type: str  # numpy code of the value (of the items, for a list)
    count: str | None = None  # numpy code of a list's length, None for a scalar

    def min_bytes(self, corners: int) -> int:
        size = np.dtype(self.type).itemsize
        return size if self.count is None else np.dtype(self.count).itemsize + corners * size


def _read_ply(p: Path) -> _Raw:
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
        header = head[:end].decode("ascii")
    except UnicodeDecodeError:
        raise MeshError("the PLY header holds non-ASCII bytes: it is corrupt.") from None

    fmt = None
    elements: list[tuple[str, int, list[_PlyProperty]]] = []
    for line in header.splitlines()[1:]:
        parts = line.split()
        if not parts or parts[0] in ("comment", "obj_info"):
            continue
        try:
            if parts[0] == "format":
                fmt = parts[1]
            elif parts[0] == "element":
                elements.append((parts[1], int(parts[2]), []))
            elif parts[0] == "property" and parts[1] == "list":
                elements[-1][2].append(_PlyProperty(parts[4], _PLY_TYPES[parts[3]], _PLY_TYPES[parts[2]]))
            elif parts[0] == "property":
                elements[-1][2].append(_PlyProperty(parts[2], _PLY_TYPES[parts[1]]))
            else:
                raise ValueError
        except (IndexError, ValueError, KeyError):
            raise MeshError(f"unreadable PLY header line {line[:60]!r}: the header is corrupt.") from None
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise MeshError(f"unknown PLY format {fmt!r}; expected ascii, binary_little_endian or binary_big_endian.")
    counts = {name: n for name, n, _ in elements}
    nv, nf = counts.get("vertex", 0), counts.get("face", 0)
    if nv <= 0:
        raise MeshError("the PLY header declares no vertices ('element vertex N'); no mesh.")
    if nf <= 0:
        raise MeshError("the PLY file has no faces ('element face N'): it is a point cloud, not a surface.")
    vprops = {q.name: q for q in elements[[e[0] for e in elements].index("vertex")][2]}
    if not all(c in vprops and vprops[c].count is None for c in "xyz"):
        raise MeshError("the PLY vertex element lacks scalar x, y, z properties; no positions to read.")
    fprops = [q.name for q in elements[[e[0] for e in elements].index("face")][2]]
    if not any(name in fprops for name in _FACE_LISTS):
        raise MeshError("the PLY face element has no 'vertex_indices' list; cannot read the faces.")
    ascii = fmt == "ascii"
    min_bytes = sum(
        n * sum(2 + 6 * (q.count is not None and name == "face") if ascii else q.min_bytes(3 * (name == "face")) for q in props)
        for name, n, props in elements
    )
    if any(n < 0 for _, n, _ in elements):
        raise MeshError("the PLY header announces a negative element count; it is corrupt.")
    _check_counts(p, nv, nf, body_start + min_bytes)

    body = p.read_bytes()[body_start:]
    if ascii:
        vertices, polygons = _ply_ascii(body, elements)
    else:
        vertices, polygons = _ply_binary(body, elements, "<" if fmt == "binary_little_endian" else ">")
    if isinstance(polygons, tuple):
        triangles, n_poly = polygons
    else:
        short = [k for k, poly in enumerate(polygons) if len(poly) < 3]
        if short:
            raise MeshError(f"face {short[0]} has {len(polygons[short[0]])} corners; a face needs at least 3.")
        triangles, n_poly = _fan(polygons)
    return _Raw(vertices, triangles, nf, n_poly)


def _ply_ascii(body: bytes, elements: list[tuple[str, int, list[_PlyProperty]]]) -> tuple[NDArray[np.float64], Any]:
    """ASCII PLY body: one line per element row."""
    if b"\x00" in body[: 1 << 16]:
        raise MeshError("the ASCII PLY body holds binary data (NUL bytes): the file is corrupt.")
    lines = [line for line in body.decode("latin-1").splitlines() if line.strip()]
    pos = 0
    vertices = polygons = None
    for name, n, props in elements:
        rows = lines[pos : pos + n]
        pos += n
        if len(rows) < n:
            raise MeshError(f"the header announces {n} {name} rows but the file ends after {len(rows)}: it is truncated.")
        if name == "vertex":
            if any(q.count is not None for q in props):
                raise MeshError("list properties on PLY vertices are not supported; re-export without them.")
            arr = _numbers("\n".join(rows), np.float64)
            if arr is None or arr.size != n * len(props):
                bad = next((k for k, r in enumerate(rows) if len(r.split()) != len(props)), 0)
                raise MeshError(f"vertex {bad} ({rows[bad][:60]!r}) is not {len(props)} numbers; the file is corrupt.")
            cols = [q.name for q in props]
            vertices = arr.reshape(n, len(props))[:, [cols.index(c) for c in "xyz"]].copy()
        elif name == "face":
            if len(props) == 1:
                polygons = _parse_counted_faces(rows, 0)  # (triangles, n_polygons)
                continue
            polygons = []
            for k, row in enumerate(rows):
                tokens, at, poly = row.split(), 0, None
                try:
                    for q in props:
                        if q.count is None:
                            at += 1
                        else:
                            m = int(tokens[at])
                            if m < 0 or at + 1 + m > len(tokens):
                                raise ValueError
                            if q.name in _FACE_LISTS and poly is None:
                                poly = [int(t) for t in tokens[at + 1 : at + 1 + m]]
                            at += 1 + m
                except (ValueError, IndexError):
                    raise MeshError(f"face {k} ({row[:60]!r}) does not match the header's properties; the file is corrupt.") from None
                polygons.append(poly)
    return vertices, polygons


def _ply_binary(body: bytes, elements: list[tuple[str, int, list[_PlyProperty]]], endian: str) -> tuple[NDArray[np.float64], Any]:
    """Binary PLY body: fixed-size rows through numpy; rows with lists walked one by one."""
    off = 0
    vertices = polygons = None
    for name, n, props in elements:
        lists = [q for q in props if q.count is not None]
        if not lists or (len(lists) == 1 and name == "face"):
            # Fixed-size rows (for faces: assume triangles, then check that they are).
            fields = []
            for q in props:
                if q.count is None:
                    fields.append((q.name, endian + q.type))
                else:
                    fields += [("__count", endian + q.count), (q.name, endian + q.type, (3,))]
            dtype = np.dtype(fields)
            if off + n * dtype.itemsize <= len(body):
                rows = np.frombuffer(body, dtype=dtype, count=n, offset=off)
                if not lists or np.all(rows["__count"] == 3):
                    off += n * dtype.itemsize
                    if name == "vertex":
                        vertices = np.column_stack([rows[c].astype(np.float64) for c in "xyz"])
                    elif name == "face":
                        polygons = (rows[lists[0].name].astype(np.int64), 0)
                    continue
            elif not lists:
                raise MeshError(f"the file ends inside the {name} data: it is truncated.")
        if name == "vertex":
            raise MeshError("list properties on PLY vertices are not supported; re-export without them.")
        # General case: walk row by row.
        out: list[list[int]] = []
        for _ in range(n):
            poly = None
            for q in props:
                size = np.dtype(q.type).itemsize
                if q.count is None:
                    off += size
                    continue
                csize = np.dtype(q.count).itemsize
                if off + csize > len(body):
                    raise MeshError(f"the file ends inside the {name} data: it is truncated.")
                m = struct.unpack_from(endian + _STRUCT[q.count], body, off)[0]
                off += csize
                if m < 0 or off + m * size > len(body):
                    raise MeshError(f"a {name} list announces {m} items past the end of the file: it is corrupt.")
                if name == "face" and q.name in _FACE_LISTS and poly is None:
                    poly = [int(i) for i in struct.unpack_from(f"{endian}{m}{_STRUCT[q.type]}", body, off)]
                off += m * size
            if off > len(body):
                raise MeshError(f"the file ends inside the {name} data: it is truncated.")
            out.append(poly)
        if name == "face":
            polygons = out
    return vertices, polygons


def _read_stl(p: Path) -> _Raw:
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
    return _Raw(vertices, triangles, len(triangles), 0)


def _stl_ascii_corners(p: Path) -> NDArray[np.float64]:
    text = _read_text(p, "ASCII STL")
    rows = re.findall(r"^[ \t]*vertex[ \t]+(.*)$", text, flags=re.MULTILINE)
    if not rows:
        raise MeshError("the ASCII STL file holds no 'vertex x y z' lines; no mesh.")
    if len(rows) % 3:
        raise MeshError(f"the ASCII STL file has {len(rows)} vertex lines, not a multiple of 3: it is truncated or corrupt.")
    return _parse_vertex_lines(rows, 0)


def _weld_corners(corners: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Shared vertices from per-triangle corners: exactly equal points become one vertex.

    Vertices are numbered in order of first appearance in the corner list.
    """
    first, inverse = _unique_rows(corners)
    order = np.argsort(first, kind="stable")  # groups sorted by first appearance
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    return corners[first[order]].copy(), rank[inverse].reshape(-1, 3).astype(np.int64)


def _unique_rows(a: NDArray[Any]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Group equal rows of a 2-D array.

    Returns ``first`` (index of the first row of each group, groups in sorted order) and
    ``inverse`` (group of each row). A stable lexicographic sort: much faster than
    ``np.unique(a, axis=0)``, which sorts opaque row records.
    """
    if len(a) == 0:
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    order = np.lexsort(a.T[::-1])
    s = a[order]
    new = np.ones(len(a), dtype=bool)
    new[1:] = np.any(s[1:] != s[:-1], axis=1)
    inverse = np.empty(len(a), dtype=np.int64)
    inverse[order] = np.cumsum(new) - 1
    return order[new].astype(np.int64), inverse


def _open3d() -> Any:
    from ._open3d import import_open3d

    return import_open3d()


# =============================================================================================
# Public API
# =============================================================================================
def load_mesh(path: PathLike, clean: bool = False, *, keep_largest_component: bool = False) -> Mesh:
    """Read a triangle mesh from an ``.off``, ``.obj``, ``.ply`` or ``.stl`` file.

    The vertices come back exactly as the file lists them (same count, same order); STL corners
    are welded into shared vertices in order of first appearance. See the module docstring for
    how each format is read.

    Parameters
    ----------
    path : str or os.PathLike
        The file. The extension (case-insensitive) selects the format.
    clean : bool, default False
        Repair what can be repaired (see :func:`clean_mesh`) and issue a
        :class:`MeshRepairWarning` saying what changed. Without it, any defect raises.
    keep_largest_component : bool, default False
        With ``clean=True``, keep only the connected component with the most faces.

    Returns
    -------
    Mesh
        A validated mesh. Several connected components and boundaries are legal.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    ValueError
        If the extension is not one of :data:`FORMATS`.
    MeshError
        If the file is unreadable, empty, truncated or junk, announces absurd counts, or holds
        a defect: non-finite coordinates, indices out of range, polygons, degenerate or
        duplicate faces, unreferenced vertices (all repaired by ``clean=True``), non-manifold
        edges or a non-orientable surface (never repaired). The message names the file, the
        defect and the fix.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "quad.obj"
    >>> _ = path.write_text("v 0 0 0\\nv 1 0 0\\nv 1 1 0\\nv 0 1 0\\nf 1 2 3 4\\n")
    >>> load_mesh(path)
    Traceback (most recent call last):
    ...
    lbo_notebooks.mesh.MeshError: ...1 of its 1 faces have more than three corners...
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     load_mesh(path, clean=True).faces.tolist()
    [[0, 1, 2], [0, 2, 3]]
    """
    if keep_largest_component and not clean:
        raise ValueError("keep_largest_component=True only applies when cleaning; pass clean=True as well.")
    p = _check_path(path)
    raw = _read_raw(p)
    if clean:
        try:
            mesh, report = _clean(raw.vertices, raw.triangles, keep_largest_component, raw.n_polygons)
        except MeshError as exc:
            raise MeshError(f"{str(p)!r}: cannot be repaired: {exc}") from None
        if report.changed:
            warnings.warn(f"{str(p)!r} was repaired: {report}", MeshRepairWarning, stacklevel=2)
        return mesh
    if raw.n_polygons:
        raise MeshError(
            f"{str(p)!r}: {raw.n_polygons} of its {raw.n_file_faces} faces have more than three corners; the LBO "
            "needs triangles. Load with clean=True, which splits each polygon into a fan of triangles, or "
            "triangulate it in a mesh editor."
        )
    try:
        return Mesh(raw.vertices, raw.triangles)
    except MeshError as exc:
        raise MeshError(f"{str(p)!r}: {exc}") from None


def save_mesh(mesh: Mesh, path: PathLike, *, binary: bool | None = None) -> Path:
    """Write ``mesh`` to an ``.off``, ``.obj``, ``.ply`` or ``.stl`` file.

    Parameters
    ----------
    mesh : Mesh
        The mesh to write.
    path : str or os.PathLike
        Destination; the extension selects the format. An existing file is overwritten.
    binary : bool or None, default None
        PLY and STL: binary (default) or ASCII. OFF and OBJ are text only (``binary=True``
        raises). Binary PLY and text files store float64 exactly (text at 17 significant
        digits); STL stores float32 by definition of the format.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    TypeError
        If ``mesh`` is not a :class:`Mesh`.
    ValueError
        For an unsupported extension or ``binary=True`` with a text-only format.
    OSError
        If the file cannot be written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from lbo_notebooks import shapes
    >>> path = save_mesh(shapes.icosphere(1), pathlib.Path(tempfile.mkdtemp()) / "s.off")
    >>> path.read_text().splitlines()[1]
    '42 80 0'
    """
    if not isinstance(mesh, Mesh):
        raise TypeError(f"save_mesh needs a Mesh, got {type(mesh).__name__}; build one with Mesh(vertices, faces).")
    p = Path(os.fspath(path))
    ext = p.suffix.lower()
    if ext not in FORMATS:
        raise ValueError(f"unsupported mesh file extension {p.suffix!r}; supported: {', '.join(FORMATS)}.")
    if binary is None:
        binary = ext in _BINARY_FORMATS
    if binary and ext not in _BINARY_FORMATS:
        raise ValueError(f"{ext} files are text only; pass binary=False (or None), or save as .ply or .stl.")
    v, f = mesh.vertices, mesh.faces
    if binary:
        o3d = _open3d()
        tm = o3d.geometry.TriangleMesh(
            o3d.utility.Vector3dVector(np.array(v, dtype=np.float64)),
            o3d.utility.Vector3iVector(np.array(f, dtype=np.int32)),
        )
        if ext == ".stl":
            tm.compute_triangle_normals()
        with o3d.utility.VerbosityContextManager(o3d.utility.VerbosityLevel.Error):
            ok = o3d.io.write_triangle_mesh(str(p), tm, write_ascii=False, write_vertex_normals=False,
                                            write_vertex_colors=False, write_triangle_uvs=False)
        if not ok:
            raise OSError(f"open3d could not write {str(p)!r}; check that the folder exists and is writable.")
        return p
    writer = {".off": _off_text, ".obj": _obj_text, ".ply": _ply_text, ".stl": _stl_text}[ext]
    with open(p, "w", encoding="ascii", newline="\n") as fh:
        fh.write(writer(v, f))
    return p


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


# =============================================================================================
# Cleaning
# =============================================================================================
@dataclass(frozen=True)
class CleanReport:
    """What :func:`clean_mesh` changed. ``str(report)`` is a one-line summary.

    Attributes
    ----------
    n_vertices_in, n_faces_in, n_vertices_out, n_faces_out : int
        Sizes before (triangles, after splitting polygons) and after cleaning.
    polygons_split : int
        Faces with more than three corners split into triangles.
    vertices_welded : int
        Vertices merged into an earlier vertex with exactly the same coordinates.
    degenerate_faces : int
        Zero-area faces removed (repeated corners, or area below the :class:`Mesh` tolerance).
    duplicate_faces : int
        Faces removed because an earlier face has the same three vertices.
    unreferenced_vertices : int
        Vertices removed because no face uses them (also those orphaned by removed faces).
    faces_flipped : int
        Faces whose orientation was reversed to agree with their neighbours.
    components_removed : int
        Components dropped by ``keep_largest_component``.
    vertex_map : ndarray, shape (n_vertices_in,)
        New index of each input vertex, or -1 if it was removed.
    """

    n_vertices_in: int
    n_faces_in: int
    n_vertices_out: int
    n_faces_out: int
    polygons_split: int = 0
    vertices_welded: int = 0
    degenerate_faces: int = 0
    duplicate_faces: int = 0
    unreferenced_vertices: int = 0
    faces_flipped: int = 0
    components_removed: int = 0
    vertex_map: NDArray[np.int64] = field(default_factory=lambda: np.zeros(0, np.int64), repr=False, compare=False)

    @property
    def changed(self) -> bool:
        """True when cleaning changed anything."""
        return bool(
            self.polygons_split or self.vertices_welded or self.degenerate_faces or self.duplicate_faces
            or self.unreferenced_vertices or self.faces_flipped or self.components_removed
        )

    def __str__(self) -> str:
        items = [
            (self.polygons_split, "polygons split into triangles"),
            (self.vertices_welded, "duplicate vertices welded"),
            (self.degenerate_faces, "degenerate faces removed"),
            (self.duplicate_faces, "duplicate faces removed"),
            (self.unreferenced_vertices, "unreferenced vertices removed"),
            (self.faces_flipped, "faces flipped to a consistent orientation"),
            (self.components_removed, "smaller components removed"),
        ]
        parts = [f"{n} {what}" for n, what in items if n]
        done = "; ".join(parts) if parts else "nothing to repair"
        return (
            f"{done} ({self.n_vertices_in} -> {self.n_vertices_out} vertices, "
            f"{self.n_faces_in} -> {self.n_faces_out} faces)"
        )


MeshLike = Union[Mesh, tuple[ArrayLike, Any]]


def clean_mesh(mesh: MeshLike, keep_largest_component: bool = False) -> tuple[Mesh, CleanReport]:
    """Repair a mesh or raw ``(vertices, faces)`` arrays; return the clean mesh and a report.

    Repairs, in this order: split polygons into fans of triangles; weld vertices with exactly
    equal coordinates (the first keeps its place); remove degenerate faces (repeated corners or
    zero area, same tolerance as :class:`Mesh`), then duplicate faces (same three vertices in
    any order; the first is kept); re-orient each connected component consistently (breadth
    first over faces that share an edge, flipping as few faces as possible); optionally keep the
    component with the most faces; finally drop unreferenced vertices, keeping the others'
    order. Boundaries and several components are legal and left alone.

    Parameters
    ----------
    mesh : Mesh or (vertices, faces)
        A :class:`Mesh` (e.g. built with ``check=False``) or raw arrays: ``vertices`` (n, 3) and
        ``faces`` as an (m, 3) integer array or a sequence of polygons (index sequences with at
        least three corners). The caller's arrays are never modified.
    keep_largest_component : bool, default False
        Keep only the vertex-connected component with the most faces.

    Returns
    -------
    mesh : Mesh
        The repaired, validated mesh.
    report : CleanReport
        What changed (``str(report)`` summarises it; ``report.vertex_map`` maps old vertex
        indices to new ones).

    Raises
    ------
    MeshError
        For what cannot be repaired: wrong shapes, indices out of range, non-finite coordinates
        on a used vertex, edges shared by more than two faces, a non-orientable component.

    Examples
    --------
    >>> v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0], [5, 5, 5]]
    >>> f = [[0, 1, 2], [2, 3, 4], [0, 1, 2]]     # vertex 4 repeats vertex 1, 5 is unused
    >>> m, report = clean_mesh((v, f))
    >>> m.faces.tolist()
    [[0, 1, 2], [2, 1, 3]]
    >>> print(report)
    1 duplicate vertices welded; 1 duplicate faces removed; 1 unreferenced vertices removed; 1 faces flipped to a consistent orientation (6 -> 4 vertices, 3 -> 2 faces)
    """
    if isinstance(mesh, Mesh):
        vertices, faces = mesh.vertices, mesh.faces
    else:
        try:
            vertices, faces = mesh
        except (TypeError, ValueError):
            raise TypeError("clean_mesh needs a Mesh or a (vertices, faces) pair.") from None
    v = np.array(vertices, dtype=np.float64, copy=True)
    if v.ndim != 2 or v.shape[1] != 3:
        raise MeshError(f"vertices must have shape (n, 3), got {v.shape}.")
    n_poly = 0
    try:
        f = np.array(faces, dtype=np.int64, copy=True)
        if f.ndim == 2 and f.shape[1] == 3:
            pass
        elif f.ndim == 2 and f.shape[1] > 3 or f.ndim == 1 and f.size == 0:
            raise ValueError
        else:
            raise MeshError(f"faces must have shape (m, 3) or be a list of polygons, got shape {f.shape}.")
    except (ValueError, TypeError):
        polygons = [list(map(int, poly)) for poly in faces]
        short = [k for k, poly in enumerate(polygons) if len(poly) < 3]
        if short:
            raise MeshError(f"{len(short)} faces have fewer than 3 corners (first: face {short[0]}).") from None
        f, n_poly = _fan(polygons)
    return _clean(v, f, keep_largest_component, n_poly)


def _clean(v: NDArray[np.float64], f: NDArray[np.int64], keep_largest: bool, n_poly: int) -> tuple[Mesh, CleanReport]:
    n_in, m_in = len(v), len(f)
    if m_in == 0:
        raise MeshError("the mesh has no faces; nothing to clean.")
    if f.min() < 0 or f.max() >= n_in:
        bad = np.flatnonzero(((f < 0) | (f >= n_in)).any(axis=1))
        raise MeshError(
            f"{bad.size} faces use vertex indices outside 0..{n_in - 1} (first: face {bad[0]} = {f[bad[0]].tolist()}); "
            "fix the file: indices must refer to existing vertices."
        )
    used = np.zeros(n_in, dtype=bool)
    used[f.ravel()] = True
    finite = np.isfinite(v).all(axis=1)
    if np.any(used & ~finite):
        bad = np.flatnonzero(used & ~finite)
        raise MeshError(
            f"{bad.size} vertices used by faces have non-finite (NaN or inf) coordinates (first: vertex {bad[0]}); "
            "fix them in the source."
        )

    # Weld used vertices with exactly equal coordinates onto the first of them.
    rep = np.arange(n_in)
    idx = np.flatnonzero(used)
    first, inverse = _unique_rows(v[idx])
    rep[idx] = idx[first[inverse]]
    welded = int(np.count_nonzero(rep[idx] != idx))
    f = rep[f]

    # Degenerate faces: repeated corners or (near-)zero area, with the Mesh tolerance.
    repeated = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])
    cross = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    area = 0.5 * np.linalg.norm(cross, axis=1)
    ref = v[np.unique(f)]
    diagonal = float(np.linalg.norm(ref.max(axis=0) - ref.min(axis=0)))
    degenerate = repeated | (area <= DEGENERATE_AREA_TOL * max(diagonal, np.finfo(float).tiny) ** 2)
    f = f[~degenerate]
    n_degenerate = int(degenerate.sum())
    if len(f) == 0:
        raise MeshError("every face is degenerate (zero area); there is no surface left.")

    # Duplicate faces: same vertex set; keep the first occurrence.
    first_face, _ = _unique_rows(np.sort(f, axis=1))
    keep = np.zeros(len(f), dtype=bool)
    keep[first_face] = True
    n_duplicate = int(len(f) - keep.sum())
    f = f[keep]

    # Edge-manifoldness cannot be repaired: let the Mesh checks name the defect.
    v_c, f_c, vmap = _compact(v, f)
    def nonmanifold() -> None:
        validate_topology(Mesh(v_c, f_c, check=False))  # names the non-manifold edges
        raise MeshError("some edges are shared by more than two faces; the mesh is not edge-manifold.")

    f_c, flipped = _orient(f_c, nonmanifold)

    removed_components = 0
    if keep_largest:
        labels = _vertex_components(f_c, len(v_c))[f_c[:, 0]]
        sizes = np.bincount(labels)
        removed_components = int(np.count_nonzero(sizes)) - 1
        f_c = f_c[labels == int(np.argmax(sizes))]
    v_out, f_out, vmap2 = _compact(v_c, f_c)

    # Compose: input vertex -> its weld representative -> compacted index -> final index.
    mid = vmap[rep]
    vertex_map = np.where(mid >= 0, vmap2[np.maximum(mid, 0)], -1)
    unreferenced = n_in - welded - len(v_out)
    mesh = Mesh(v_out, f_out)
    report = CleanReport(
        n_vertices_in=n_in, n_faces_in=m_in, n_vertices_out=mesh.n_vertices, n_faces_out=mesh.n_faces,
        polygons_split=n_poly, vertices_welded=welded, degenerate_faces=n_degenerate,
        duplicate_faces=n_duplicate, unreferenced_vertices=unreferenced, faces_flipped=flipped,
        components_removed=removed_components, vertex_map=vertex_map,
    )
    return mesh, report


def _compact(v: NDArray[np.float64], f: NDArray[np.int64]) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64]]:
    """Drop unreferenced vertices keeping order; also return old -> new index (-1 if dropped)."""
    used = np.zeros(len(v), dtype=bool)
    used[f.ravel()] = True
    new = np.full(len(v), -1, dtype=np.int64)
    new[used] = np.arange(int(used.sum()))
    return v[used], new[f], new


def _vertex_components(f: NDArray[np.int64], n: int) -> NDArray[np.int64]:
    """Connected-component label of each vertex (vertices joined by face edges)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    rows = np.concatenate([f[:, 0], f[:, 1]])
    cols = np.concatenate([f[:, 1], f[:, 2]])
    graph = coo_matrix((np.ones(rows.size), (rows, cols)), shape=(n, n))
    return connected_components(graph, directed=False)[1]


def _orient(f: NDArray[np.int64], on_nonmanifold: Any) -> tuple[NDArray[np.int64], int]:
    """Flip faces so that every interior edge is traversed in opposite directions by its faces.

    Breadth-first over the faces of each edge-connected component (all components at once,
    level by level); per component the orientation needing fewer flips wins. Calls
    ``on_nonmanifold()`` (which must raise) if an edge has more than two faces. Raises
    MeshError for a non-orientable component.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    m = len(f)
    half = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    face_of = np.tile(np.arange(m), 3)
    _, edge_id = _unique_rows(np.sort(half, axis=1))
    if np.any(np.bincount(edge_id) > 2):
        on_nonmanifold()
    order = np.argsort(edge_id, kind="stable")
    e_sorted = edge_id[order]
    pair = np.flatnonzero(e_sorted[1:] == e_sorted[:-1])  # interior edges: two consecutive half-edges
    h1, h2 = order[pair], order[pair + 1]
    if h1.size == 0:
        return f.copy(), 0
    a, b = face_of[h1], face_of[h2]
    # Same direction along the shared edge -> the two faces need opposite flip states.
    need = (half[h1, 0] == half[h2, 0]).astype(np.int8)

    graph = coo_matrix((np.ones(a.size), (a, b)), shape=(m, m)).tocsr()
    graph = graph + graph.T
    n_comp, labels = connected_components(graph, directed=False)
    # Adjacency with the 'need' bit, both directions, in CSR form.
    src = np.concatenate([a, b])
    dst = np.concatenate([b, a])
    bit = np.concatenate([need, need])
    srt = np.argsort(src, kind="stable")
    src, dst, bit = src[srt], dst[srt], bit[srt]
    indptr = np.searchsorted(src, np.arange(m + 1))

    state = np.full(m, -1, dtype=np.int8)
    _, roots = np.unique(labels, return_index=True)
    state[roots] = 0
    frontier = roots
    while frontier.size:
        starts, stops = indptr[frontier], indptr[frontier + 1]
        lengths = stops - starts
        if lengths.sum() == 0:
            break
        pos = np.repeat(starts - np.cumsum(lengths) + lengths, lengths) + np.arange(lengths.sum())
        owners = np.repeat(frontier, lengths)
        nb = dst[pos]
        fresh = state[nb] < 0
        nb, owners, pos = nb[fresh], owners[fresh], pos[fresh]
        nb_unique, first = np.unique(nb, return_index=True)
        state[nb_unique] = state[owners[first]] ^ bit[pos[first]]
        frontier = nb_unique

    conflict = (state[a] ^ state[b]) != need
    if np.any(conflict):
        comps = np.unique(labels[a[conflict]])
        face = int(a[conflict][0])
        raise MeshError(
            f"{comps.size} connected component(s) are non-orientable (like a Moebius strip; first conflict at "
            f"face {face} = {f[face].tolist()}): no choice of face orientations makes neighbours agree. "
            "Cut the component open or remove it."
        )
    flips_per_comp = np.bincount(labels, weights=state, minlength=n_comp)
    size_per_comp = np.bincount(labels, minlength=n_comp)
    invert = flips_per_comp > size_per_comp / 2
    flip = state.astype(bool) ^ invert[labels]
    out = f.copy()
    out[flip] = out[flip][:, [0, 2, 1]]
    return out, int(flip.sum())
