"""Benchmark: load/save time of a 100k-vertex scan-like mesh in every format.

The mesh is made procedurally (two perforated icospheres and a torus: about 100k vertices, three
components, holes), saved in each format, then loaded with ``load_mesh`` (and with
``clean=True``). open3d's own reader is timed on the same files as the baseline; it does no
validation. Run:

    python benchmarks/io.py
"""

from __future__ import annotations

import tempfile
import time
import warnings
from pathlib import Path

import sys
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _measure import best_time as _best  # noqa: E402

from lbo_notebooks import Mesh, shapes  # noqa: E402
from lbo_notebooks.geometry._files import load_mesh, read_mesh_arrays, save_mesh


def main() -> None:
    import open3d as o3d

    t0 = time.perf_counter()
    mesh = shapes.scan_like()
    print(f"mesh: {mesh.summary()}  (built in {time.perf_counter() - t0:.1f} s)")
    tmp = Path(tempfile.mkdtemp())
    rows = []
    for name, binary in (("off", None), ("obj", None), ("ply", True), ("ply", False), ("stl", True), ("stl", False)):
        path = tmp / f"scan_{'bin' if binary else 'txt'}.{name}"
        t_save = _best(lambda: save_mesh(mesh, path, binary=binary), 1)
        t_read = _best(lambda: read_mesh_arrays(path))
        t_load = _best(lambda: load_mesh(path))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t_clean = _best(lambda: load_mesh(path, clean=True), 1)
        with o3d.utility.VerbosityContextManager(o3d.utility.VerbosityLevel.Error):
            t_o3d = _best(lambda: o3d.io.read_triangle_mesh(str(path)))
        rows.append((path.name, path.stat().st_size / 1e6, t_save, t_read, t_load, t_clean, t_o3d))
    t_mesh = _best(lambda: Mesh(mesh.vertices, mesh.faces))
    print(f"Mesh(vertices, faces) with its topology checks alone: {t_mesh:.2f} s")
    print("read = parse the file (read_mesh_arrays); load = read + Mesh checks; open3d = its reader, no checks")
    print(f"{'file':<14}{'MB':>6}{'save s':>8}{'read s':>8}{'load s':>8}{'clean s':>9}{'open3d s':>10}{'read/o3d':>10}")
    for name, mb, ts, tr, tl, tc, to in rows:
        print(f"{name:<14}{mb:6.1f}{ts:8.2f}{tr:8.2f}{tl:8.2f}{tc:9.2f}{to:10.2f}{tr / to:10.1f}")


if __name__ == "__main__":
    main()
