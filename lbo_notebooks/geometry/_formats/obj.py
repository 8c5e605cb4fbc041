"""Wavefront OBJ: ``v`` and ``f`` lines read directly, so vertex ``k`` is the ``k``-th ``v`` line and texture seams do not split vertices.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Callable

import numpy as np
from numpy.typing import NDArray

from .._mesh import MeshError
from .._repair import triangulate_polygons
from .common import (
    RawMesh,
    check_ends_with_line_break,
    clamped,
    line_locator,
    parse_int,
    parse_numbers,
    parse_vertex_lines,
    read_text,
)

__all__ = ["read_obj"]


# A 'v' line holds x y z, optionally followed by a weight w (x y z w) or by a colour (x y z r g b, a common
# extension); the first three numbers are the position. Any other count is a damaged line.
_V_NUMBERS = (3, 4, 6)
_V_LAYOUT = "x y z, or x y z w, or x y z r g b"


def _is_vertex(line: str) -> bool:
    return line[:2] in ("v ", "v\t")


def _is_face(line: str) -> bool:
    return line[:2] in ("f ", "f\t")


def read_obj(p: Path, need_faces: bool = True) -> RawMesh:
    text = read_text(p, "OBJ")
    check_ends_with_line_break(text)
    lines = [line.lstrip() for line in text.splitlines()]  # an indented 'v' line is still a vertex
    vertex_lines = [line[2:].split("#", 1)[0] for line in lines if _is_vertex(line)]
    face_lines = [line[2:] for line in lines if _is_face(line)]

    def vertex_rows() -> list[int]:
        return [i for i, line in enumerate(lines) if _is_vertex(line)]

    def face_rows() -> list[int]:
        return [i for i, line in enumerate(lines) if _is_face(line)]

    def line_of_vertex(k: int) -> int:
        return vertex_rows()[k] + 1

    if not vertex_lines:
        raise MeshError("no vertex ('v x y z') lines found; this is not an OBJ mesh.")
    if not face_lines and not need_faces:
        return RawMesh(parse_vertex_lines(vertex_lines, line_of_vertex, _V_NUMBERS, _V_LAYOUT),
                       np.zeros((0, 3), np.int64), 0, 0)
    if not face_lines:
        raise MeshError("no face ('f a b c') lines found: the file is a point cloud or line set, not a surface. Read its points with lbo.load_points.")
    vertices = parse_vertex_lines(vertex_lines, line_of_vertex, _V_NUMBERS, _V_LAYOUT)
    block = "\n".join(face_lines)
    if "-" not in block and "#" not in block:
        # Fast path: positive indices only; keep the vertex index of each 'v/vt/vn' corner.
        if "/" in block:
            block = re.sub(r"/\S*", "", block)
        idx = parse_numbers(block, np.int64)
        if idx is not None and not clamped(idx) and idx.size == 3 * len(face_lines) and all(len(x.split()) == 3 for x in block.split("\n")):
            if idx.size and idx.min() == 0:
                k = int(np.flatnonzero((idx.reshape(-1, 3) == 0).any(axis=1))[0])
                raise MeshError(f"line {face_rows()[k] + 1} ({lines[face_rows()[k]][:60]!r}) uses vertex index 0; OBJ "
                                "indices are 1-based. Fix the file's 'f' lines.")
            triangles = _obj_check_range(idx.reshape(-1, 3) - 1, len(vertices), lambda k: face_rows()[k] + 1)
            locate = line_locator(lines, vertex_rows, face_rows, None, 0)
            return RawMesh(vertices, triangles, len(face_lines), 0, locate)
    # General path: polygons, negative (relative) indices, comments.
    polygons: list[list[int]] = []
    nv, n_total = 0, len(vertices)
    for lineno, line in enumerate(lines, start=1):
        if _is_vertex(line):
            nv += 1
        elif _is_face(line):
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
    locate = line_locator(lines, vertex_rows, face_rows, lambda: [len(poly) for poly in polygons], n_poly)
    return RawMesh(vertices, triangles, len(polygons), n_poly, locate)  # indices checked above, as written


def _obj_check_range(triangles: NDArray[np.int64], nv: int, line_of: Callable[[int], int]) -> NDArray[np.int64]:
    bad = np.flatnonzero(((triangles < 0) | (triangles >= nv)).any(axis=1))
    if bad.size:
        raise MeshError(
            f"{bad.size} faces use vertex indices outside 1..{nv} (first: triangle {bad[0]} = "
            f"{(triangles[bad[0]] + 1).tolist()}, on line {line_of(int(bad[0]))}; triangles counted from 0, vertex "
            f"indices from 1 as in the file) but the file has {nv} 'v' lines; fix the file's 'f' lines."
        )
    return triangles
