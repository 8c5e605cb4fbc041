"""OFF files: a count header, vertex lines, counted face lines.
"""

from __future__ import annotations

from pathlib import Path

from .._mesh import MeshError, plural
from .common import (
    MIN_TEXT_FACE_BYTES,
    MIN_TEXT_VERTEX_BYTES,
    RawMesh,
    check_counts,
    check_ends_with_line_break,
    check_no_trailing_lines,
    content_lines,
    line_locator,
    parse_counted_faces,
    parse_int,
    parse_vertex_lines,
    read_text,
)

__all__ = ["read_off"]


# How many numbers a vertex line of each OFF variant holds: x y z, then normals (N), then an RGB or RGBA colour (C).
_VERTEX_NUMBERS = {"OFF": (3,), "COFF": (6, 7), "NOFF": (6,), "CNOFF": (9, 10)}
_VERTEX_LAYOUT = {
    "OFF": "x y z; colours or normals after them need the header 'COFF' or 'NOFF'",
    "COFF": "x y z r g b [a]",
    "NOFF": "x y z nx ny nz",
    "CNOFF": "x y z nx ny nz r g b [a]",
}


def read_off(p: Path) -> RawMesh:
    """Read an OFF file: vertex lines hold the numbers their variant's header announces (see ``_VERTEX_NUMBERS``);
    data lines after the announced faces are refused (comments and blank lines are not data)."""
    text = read_text(p, "OFF")
    lines, numbers = content_lines(text)
    if lines:
        check_ends_with_line_break(text)
    if not lines:
        raise MeshError("the file holds only comments or blank lines; no mesh.")
    head = lines[0].split()
    if not head[0].endswith("OFF"):
        raise MeshError(f"not an OFF file: the first line must be 'OFF', got {lines[0][:40]!r}.")
    if head[0] not in _VERTEX_NUMBERS:
        raise MeshError(f"unsupported OFF variant {head[0]!r}; re-export as plain 'OFF'.")
    if len(head) > 1 and head[1].upper() == "BINARY":
        raise MeshError("binary OFF is not supported; re-export as text OFF, PLY or STL.")
    first = 1  # the first vertex record, in ``lines``
    counts = head[1:4] if len(head) >= 4 else (lines[1].split()[:3] if len(lines) > 1 else [])
    if len(head) < 4:
        first = 2
    try:
        nv, nf = parse_int(counts[0]), parse_int(counts[1])
    except (ValueError, IndexError):
        raise MeshError(
            f"the OFF header must give 'n_vertices n_faces n_edges' as integers, got {' '.join(counts)!r}."
        ) from None
    if nv < 0 or nf < 0:
        raise MeshError(f"the OFF header announces negative counts ({nv} vertices, {nf} faces).")
    check_counts(p, nv, nf, nv * MIN_TEXT_VERTEX_BYTES + nf * MIN_TEXT_FACE_BYTES)
    rest = lines[first:]
    if len(rest) < nv + nf:
        raise MeshError(
            f"the header announces {nv} vertices and {nf} faces but the file has only {len(rest)} "
            "data lines: it is truncated. Re-export or re-download it."
        )
    check_no_trailing_lines(rest[nv + nf :], lambda k: numbers[first + nv + nf + k],
                            f"{plural(nv, 'vertex', 'vertices')} and {plural(nf, 'face')}")
    vertices = parse_vertex_lines(rest[:nv], lambda k: numbers[first + k], _VERTEX_NUMBERS[head[0]],
                                  _VERTEX_LAYOUT[head[0]])
    face_lines = rest[nv : nv + nf]
    triangles, n_poly = parse_counted_faces(face_lines, nv, lambda k: numbers[first + nv + k])
    all_lines = text.splitlines()
    locate = line_locator(
        all_lines,
        lambda: [n - 1 for n in numbers[first : first + nv]],
        lambda: [n - 1 for n in numbers[first + nv : first + nv + nf]],
        lambda: [int(line.split()[0]) for line in face_lines],
        n_poly,
    )
    return RawMesh(vertices, triangles, nf, n_poly, locate)
