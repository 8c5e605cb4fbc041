"""Heat-method geodesics: blocks of sources (ours) against one source at a time (ours, potpourri3d).

Run from the repository root::

    .venv/bin/python benchmarks/geodesics.py            # 10k and 50k vertices, 60 sources
    .venv/bin/python benchmarks/geodesics.py --quick    # 10k only

For each mesh (the deformed torus of ``benchmarks/mds.py``): the set-up time (factorisations),
the cost per source of our heat method in blocks and one source at a time, and of potpourri3d's
heat method (geometry-central, one source per call), all in one run, plus the largest difference
between the two implementations relative to the diameter. The ratio to read is potpourri3d's
time per source over ours in blocks.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from lbo_notebooks.analyses import HeatMethod

from mds import deformed_torus  # type: ignore[import-not-found]  # benchmarks/ is the script's directory


def row(n_vertices: int, n_sources: int) -> dict:
    import potpourri3d as pp3d

    mesh = deformed_torus(n_vertices)
    sources = np.linspace(0, mesh.n_vertices - 1, n_sources).astype(np.int64)
    V, F = np.ascontiguousarray(mesh.vertices), np.ascontiguousarray(mesh.faces)

    t0 = time.perf_counter()
    heat = HeatMethod(mesh)
    t1 = time.perf_counter()
    theirs = pp3d.MeshHeatMethodDistanceSolver(V, F)
    t2 = time.perf_counter()
    blocks = heat.distances(sources)
    t3 = time.perf_counter()
    for s in sources:
        heat.distances(np.array([s]))
    t4 = time.perf_counter()
    reference = np.vstack([theirs.compute_distance(int(s)) for s in sources])
    t5 = time.perf_counter()
    return {
        "n": mesh.n_vertices, "block": heat.block_size, "setup_ours": t1 - t0, "setup_pp3d": t2 - t1,
        "ms_blocks": 1e3 * (t3 - t2) / n_sources, "ms_single": 1e3 * (t4 - t3) / n_sources,
        "ms_pp3d": 1e3 * (t5 - t4) / n_sources, "ratio": (t5 - t4) / (t3 - t2),
        "difference": float(np.abs(blocks - reference).max() / reference.max()),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="10k vertices only")
    ap.add_argument("--sources", type=int, default=60)
    args = ap.parse_args()
    sizes = [10_000] if args.quick else [10_000, 50_000]
    print(f"{'vertices':>8} {'block':>5} {'setup ours s':>12} {'setup pp3d s':>12} {'ours blocks ms':>14} "
          f"{'ours single ms':>14} {'pp3d ms':>8} {'pp3d/blocks':>11} {'max diff':>9}")
    for n in sizes:
        r = row(n, args.sources)
        print(f"{r['n']:>8} {r['block']:>5} {r['setup_ours']:>12.2f} {r['setup_pp3d']:>12.2f} {r['ms_blocks']:>14.1f} "
              f"{r['ms_single']:>14.1f} {r['ms_pp3d']:>8.1f} {r['ratio']:>11.2f} {r['difference']:>9.1e}", flush=True)


if __name__ == "__main__":
    main()
