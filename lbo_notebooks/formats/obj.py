"""Wavefront OBJ: ``v`` and ``f`` lines read directly, so vertex ``k`` is the ``k``-th ``v`` line and texture seams do not split vertices.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..mesh import MeshError
from ..repair import triangulate_polygons
from .common import (
    RawMesh,
    check_ends_with_line_break,
    clamped,
    parse_int,
    parse_numbers,
    parse_vertex_lines,
    read_text,
)

__all__ = ["read_obj"]


def read_obj(p: Path, need_faces: bool = True) -> RawMesh:
    text = read_text(p, "OBJ")
    check_ends_with_line_break(text)
    lines = [line.lstrip() for line in text.splitlines()]  # an indented 'v' line is still a vertex
    vertex_lines = [line[2:].split("#", 1)[0] for line in lines if line[:2] in ("v ", "v\t")]
    face_lines = [line[2:] for line in lines if line[:2] in ("f ", "f\t")]
    if not vertex_lines:
        raise MeshError("no vertex ('v x y z') lines found; this is not an OBJ mesh.")
    if not face_lines and not need_faces:
        return RawMesh(parse_vertex_lines(vertex_lines, 0), np.zeros((0, 3), np.int64), 0, 0)
    if not face_lines:
        raise MeshError("no face ('f a b c') lines found: the file is a point cloud or line set, not a surface. Read its points with lbo.load_points.")
    vertices = parse_vertex_lines(vertex_lines, 0)
    block = "\n".join(face_lines)
    if "-" not in block and "#" not in block:
        # Fast path: positive indices only; keep the vertex index of each 'v/vt/vn' corner.
        if "/" in block:
            block = re.sub(r"/\S*", "", block)
        idx = parse_numbers(block, np.int64)
        if idx is not None and not clamped(idx) and idx.size == 3 * len(face_lines) and all(len(x.split()) == 3 for x in block.split("\n")):
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
                    i = parse_int(token.split("/", 1)[0])
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
