"""Benchmark: load/save time of a 100k-vertex scan-like mesh in every format.

The mesh is made procedurally (two perforated icospheres and a torus: about 100k vertices, three
components, holes), saved in each format, then loaded with ``load_mesh`` (and with
``clean=True``). open3d's own reader is timed on the same files as the baseline; it does no
validation, so the ratio is the price of the checks. Run:

    python benchmarks/io.py
"""

from __future__ import annotations

import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from lbo_notebooks import Mesh, shapes
from lbo_notebooks.io import clean_mesh, load_mesh, save_mesh


def scan_like_mesh(seed: int = 0) -> Mesh:
    """About 100k vertices: two icospheres(6) with holes punched out, plus a torus; 3 components."""
    rng = np.random.default_rng(seed)
    parts = []
    offset = 0
    for shift in ([0.0, 0.0, 0.0], [3.0, 0.0, 0.0]):
        s = shapes.icosphere(6)
        centres = rng.normal(size=(12, 3))
        centres /= np.linalg.norm(centres, axis=1, keepdims=True)
        c = s.vertices[s.faces].mean(axis=1)
        hole = (np.linalg.norm(c[:, None, :] - centres[None], axis=2) < 0.12).any(axis=1)
        parts.append((s.vertices + shift, s.faces[~hole]))
    t = shapes.torus(1.0, 0.3, n_major=160, n_minor=128)
    parts.append((t.vertices + [0.0, 3.0, 0.0], t.faces))
    vs, fs = [], []
    for v, f in parts:
        fs.append(f + offset)
        vs.append(v)
        offset += len(v)
    mesh, _ = clean_mesh((np.concatenate(vs), np.concatenate(fs)))  # drops the vertices inside the holes
    return mesh


def _best(fn, repeat: int = 3) -> float:
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    import open3d as o3d

    t0 = time.perf_counter()
    mesh = scan_like_mesh()
    print(f"mesh: {mesh.summary()}  (built in {time.perf_counter() - t0:.1f} s)")
    tmp = Path(tempfile.mkdtemp())
    rows = []
    for name, binary in (("off", None), ("obj", None), ("ply", True), ("ply", False), ("stl", True), ("stl", False)):
        path = tmp / f"scan_{'bin' if binary else 'txt'}.{name}"
        t_save = _best(lambda: save_mesh(mesh, path, binary=binary), 1)
        t_load = _best(lambda: load_mesh(path))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t_clean = _best(lambda: load_mesh(path, clean=True))
        with o3d.utility.VerbosityContextManager(o3d.utility.VerbosityLevel.Error):
            t_o3d = _best(lambda: o3d.io.read_triangle_mesh(str(path)))
        rows.append((path.name, path.stat().st_size / 1e6, t_save, t_load, t_clean, t_o3d))
    print(f"{'file':<16}{'MB':>7}{'save s':>9}{'load s':>9}{'clean s':>9}{'open3d s':>10}{'load/o3d':>10}")
    for name, mb, ts, tl, tc, to in rows:
        print(f"{name:<16}{mb:7.1f}{ts:9.2f}{tl:9.2f}{tc:9.2f}{to:10.2f}{tl / to:10.1f}")


if __name__ == "__main__":
    main()
