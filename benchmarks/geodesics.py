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

from lbo_notebooks.heat_method import HeatMethod

from mds import deformed_torus  # type: ignore[import-not-found]  # benchmarks/ is the script's directory


def _seconds(fn) -> float:
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def row(n_vertices: int, n_sources: int) -> dict:
    import potpourri3d as pp3d

    mesh = deformed_torus(n_vertices)
    sources = np.linspace(0, mesh.n_vertices - 1, n_sources).astype(np.int64)
    setup_ours = _seconds(lambda: HeatMethod(mesh))
    heat = HeatMethod(mesh)
    V, F = np.ascontiguousarray(mesh.vertices), np.ascontiguousarray(mesh.faces)
    start = time.perf_counter()
    theirs = pp3d.MeshHeatMethodDistanceSolver(V, F)
    setup_theirs = time.perf_counter() - start

    blocks = [None]
    per_block = _seconds(lambda: blocks.__setitem__(0, heat.distances(sources))) / n_sources
    per_single = _seconds(lambda: [heat.distances(sources[i : i + 1]) for i in range(n_sources)]) / n_sources
    reference = [None]
    per_theirs = _seconds(lambda: reference.__setitem__(0, np.vstack([theirs.compute_distance(int(s)) for s in sources]))) / n_sources
    difference = float(np.abs(blocks[0] - reference[0]).max() / reference[0].max())
    return {
        "n": mesh.n_vertices, "block": heat.block_size, "setup_ours": setup_ours, "setup_pp3d": setup_theirs,
        "ms_blocks": 1e3 * per_block, "ms_single": 1e3 * per_single, "ms_pp3d": 1e3 * per_theirs,
        "ratio": per_theirs / per_block, "difference": difference,
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
