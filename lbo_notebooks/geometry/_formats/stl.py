"""STL (binary and ASCII): fixed 50-byte records or ``vertex`` lines; equal corners welded back into shared vertices.
"""

from __future__ import annotations

import re
import struct
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from .._mesh import MeshError, unique_rows
from .common import (
    UTF8_BOM,
    RawMesh,
    parse_vertex_lines,
    read_text,
)

__all__ = ["read_stl"]


def read_stl(p: Path) -> RawMesh:
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
    elif head.removeprefix(UTF8_BOM).lstrip().startswith(b"solid"):
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
    text = read_text(p, "ASCII STL")
    first, end = text.find("\n"), len(text.rstrip())
    last_start = text.rfind("\n", 0, end)
    last = text[last_start + 1 : end].strip() if 0 <= first < last_start else ""
    body = text[first + 1 : last_start] if last else ""  # between the 'solid name' and 'endsolid name' lines
    vertex_line = re.compile(r"^[ \t]*vertex[ \t]+(.*)$", flags=re.MULTILINE)
    rows = vertex_line.findall(body)
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

    def line_of(k: int) -> int:  # for an error message only
        match = next(m for j, m in enumerate(vertex_line.finditer(body)) if j == k)
        return text.count("\n", 0, first + 1 + match.start()) + 1

    return parse_vertex_lines(rows, line_of, (3,), "x y z")


def _weld_corners(corners: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Shared vertices from per-triangle corners: exactly equal points become one vertex.

    Vertices are numbered in order of first appearance in the corner list.
    """
    first, inverse = unique_rows(corners)
    order = np.argsort(first, kind="stable")  # groups sorted by first appearance
    rank = np.empty_like(order)
    rank[order] = np.arange(order.size)
    return corners[first[order]].copy(), rank[inverse].reshape(-1, 3).astype(np.int64)
