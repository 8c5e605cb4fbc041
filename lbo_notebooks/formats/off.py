"""OFF files: a count header, vertex lines, counted face lines.
"""

from __future__ import annotations

from pathlib import Path

from ..mesh import MeshError
from .common import (
    MIN_TEXT_FACE_BYTES,
    MIN_TEXT_VERTEX_BYTES,
    RawMesh,
    check_counts,
    check_ends_with_line_break,
    content_lines,
    parse_counted_faces,
    parse_int,
    parse_vertex_lines,
    read_text,
)

__all__ = ["read_off"]


def read_off(p: Path) -> RawMesh:
    text = read_text(p, "OFF")
    lines = content_lines(text)
    if lines:
        check_ends_with_line_break(text)
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
        nv, nf = parse_int(counts[0]), parse_int(counts[1])
    except (ValueError, IndexError):
        raise MeshError(
            f"the OFF header must give 'n_vertices n_faces n_edges' as integers, got {' '.join(counts)!r}."
        ) from None
    if nv < 0 or nf < 0:
        raise MeshError(f"the OFF header announces negative counts ({nv} vertices, {nf} faces).")
    check_counts(p, nv, nf, nv * MIN_TEXT_VERTEX_BYTES + nf * MIN_TEXT_FACE_BYTES)
    if len(rest) < nv + nf:
        raise MeshError(
            f"the header announces {nv} vertices and {nf} faces but the file has only {len(rest)} "
            "data lines: it is truncated. Re-export or re-download it."
        )
    vertices = parse_vertex_lines(rest[:nv], 0)
    face_lines = rest[nv : nv + nf]
    triangles, n_poly = parse_counted_faces(face_lines, nv)
    return RawMesh(vertices, triangles, nf, n_poly)
