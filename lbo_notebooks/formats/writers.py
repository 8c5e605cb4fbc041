"""Text for the mesh formats, with 17 significant digits, so that saving and loading gives back the same float64 coordinates.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["mesh_text"]


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
