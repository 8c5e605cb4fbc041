"""Benchmark: the procedural creatures — size accuracy, build time, triangle quality, isometry.

Three tables:

1. Template size and cost for 2k..50k vertices (dog and horse): vertices obtained against the
   request, CPU and wall time of a cold build (marching cubes + remeshing + skinning weights),
   and triangle quality (smallest angle, share of triangles with all angles >= 25 degrees).
2. The issue's speed target: a cold 10,000-vertex family of the 6 named poses (template
   included) against the template alone (baseline, same run): posing should add little.
3. Isometry of every named pose against standing at 10,000 vertices: median and 99th
   percentile of the relative edge-length change, mean relative change of the geodesic
   distances among 50 farthest-point samples.

The machine is shared: read the CPU column and the ratios. Run:

    python benchmarks/creatures.py [--quick]
"""

from __future__ import annotations

import sys
import time

import numpy as np

from lbo_notebooks import Mesh
from lbo_notebooks.operators import corner_angles
from lbo_notebooks.shapes import _creatures as C


def _min_angles(mesh: Mesh) -> np.ndarray:
    """Smallest angle of each triangle, in degrees."""
    return np.degrees(corner_angles(mesh)).min(axis=1)


def _timed(fn):  # type: ignore[no-untyped-def]
    c0, w0 = time.process_time(), time.perf_counter()
    out = fn()
    return out, time.process_time() - c0, time.perf_counter() - w0


def main(quick: bool = False) -> None:
    C.creature("dog", n_vertices=2000)  # import the heavy libraries once, outside the timings
    sizes = (2_000, 5_000, 10_000) if quick else (2_000, 5_000, 10_000, 20_000, 50_000)
    print("1. template size, cold build time and triangle quality")
    print(f"{'species':8s} {'asked':>7s} {'got':>7s} {'error':>7s} {'cpu s':>7s} {'wall s':>7s} {'min angle':>9s} {'>=25 deg':>9s}")
    for species in C.SPECIES:
        for n in sizes:
            C.rig.template_for.cache_clear()
            mesh, cpu, wall = _timed(lambda: C.creature(species, n_vertices=n))
            a = _min_angles(mesh)
            print(f"{species:8s} {n:7d} {mesh.n_vertices:7d} {100 * (mesh.n_vertices / n - 1):+6.1f}% {cpu:7.2f} {wall:7.2f} "
                  f"{a.min():8.1f}° {100 * np.mean(a >= 25):8.2f}%")

    print("\n2. cold 10,000-vertex family of poses against the template alone (baseline)")
    print(f"{'species':8s} {'template cpu':>12s} {'family cpu':>11s} {'family wall':>12s} {'ratio':>6s}")
    for species in C.SPECIES:
        C.rig.template_for.cache_clear()
        _, t_cpu, _ = _timed(lambda: C.creature(species, n_vertices=10_000))
        C.rig.template_for.cache_clear()
        poses, f_cpu, f_wall = _timed(lambda: C.creature_poses(species, n_vertices=10_000))
        print(f"{species:8s} {t_cpu:12.2f} {f_cpu:11.2f} {f_wall:12.2f} {f_cpu / t_cpu:6.2f}   ({len(poses)} poses)")

    print("\n3. isometry against standing, 10,000 vertices")
    print(f"{'species':8s} {'pose':12s} {'median edge':>11s} {'99% edge':>9s} {'geodesic':>9s} {'min angle':>9s}")
    for species in C.SPECIES:
        poses = C.creature_poses(species, n_vertices=10_000)
        for name, m in poses.items():
            if name == "standing":
                continue
            d = C.pose_distortion(poses["standing"], m)
            print(f"{species:8s} {name:12s} {100 * d['edge_median']:10.2f}% {100 * d['edge_p99']:8.2f}% "
                  f"{100 * d['geodesic_mean']:8.2f}% {_min_angles(m).min():8.1f}°")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
