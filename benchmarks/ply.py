"""Benchmark: reading PLY, plyfile's plain reader against the paths ``load_mesh`` takes.

``read_mesh_arrays`` hands binary PLY to plyfile with fixed-length face lists (memory-mapped)
and parses ASCII PLY of scalar rows and triangles in one NumPy call; plyfile's plain reader walks
list rows one by one in Python. Same ~100k-vertex scan as ``benchmarks/io.py``. Run:

    python benchmarks/ply.py
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _measure import best_time  # noqa: E402

from lbo_notebooks import shapes  # noqa: E402
from lbo_notebooks.geometry._files import read_mesh_arrays, save_mesh  # noqa: E402


def main() -> None:
    import plyfile

    mesh = shapes.scan_like()
    folder = Path(tempfile.mkdtemp())
    print(f"mesh: {mesh.n_vertices} vertices, {mesh.n_faces} triangles")
    print(f"{'file':<12}{'MB':>6}{'plyfile plain s':>17}{'read_mesh_arrays s':>20}{'ratio':>8}")
    for binary in (True, False):
        path = save_mesh(mesh, folder / f"scan_{'bin' if binary else 'txt'}.ply", binary=binary)
        t_plain = best_time(lambda: plyfile.PlyData.read(str(path)), 1)
        t_ours = best_time(lambda: read_mesh_arrays(path))
        print(f"{path.name:<12}{path.stat().st_size / 1e6:6.1f}{t_plain:17.2f}{t_ours:20.3f}{t_plain / t_ours:8.0f}")


if __name__ == "__main__":
    main()
