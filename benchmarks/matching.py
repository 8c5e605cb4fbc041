"""Benchmark: ``lbo_notebooks.match`` against pyFM's default pipeline, same pairs, one run.

Pairs are procedural creatures sharing a triangulation, so the true map is known; every target is
shuffled (random vertex order) before matching, so neither method can use vertex indices. Both
methods get the same meshes (pyFM's ``TriMesh`` with its own cotangent Laplacian and spectrum).

pyFM (PyPI ``pyfmaps``) default pipeline, as in its README: WKS
(100 energies, every 5th kept), 35 x 35 map fitted with w_descr=1, w_lap=1e-2, w_dcomm=1e-1,
w_orient=1e-1 (L-BFGS), nearest-neighbour point map; then, as a second row, its ZoomOut
(nit=10, step=1, its default). Ours: ``match`` with its defaults (30 x 30 map solved in closed
form, ZoomOut to 80).

A second table matches pairs with a rescaled part using eigenbases of the metric |K|^alpha g
(alpha = 0, 0.4, 1), everything else in ``match`` unchanged (notebook 12).

Error: mean geodesic error on the source / sqrt(area) (heat-method distances). Times are wall
times of the whole pipeline including eigenbases, on a shared machine: read the ratios.
Run:

    python benchmarks/matching.py            # the 4k tables
    python benchmarks/matching.py --record   # the semi-local scaling table only, also written to lbo_notebooks/recorded/matching.json

``--record`` stores the semi-local scaling table with its date, machine load and BLAS threads;
notebook 12 quotes those numbers as recorded and asserts its prose against the file.

Real sizes (``--sizes``): one dog standing -> walking pair per size, target shuffled, ``match``
with its defaults and pyFM's default pipeline run in turn ``--repeats`` times; medians of wall
and CPU seconds, and the median of the per-round ratios of wall times. The error is the mean
over 2000 random target vertices (a wrong vertex costs a geodesic field on the source).
2-core machine shared with other jobs (load 7-9), OPENBLAS_NUM_THREADS=1, PYTHONPATH=. :

    OPENBLAS_NUM_THREADS=1 python benchmarks/matching.py --sizes 25000 50000 --repeats 2

         n method                    error  wall (s)  cpu (s)  pyFM wall / ours
     24705 lbo.match                0.0023     11.98     8.12              4.90
     24705 pyFM default             0.0094     48.51    23.17
     49124 lbo.match                0.0018     41.38    20.55              4.41
     49124 pyFM default             0.0100    150.35    60.53

A second run of the same command 15 minutes later (load 5-6), final code:

     24705 lbo.match                0.0023     20.50     8.31              2.63
     24705 pyFM default             0.0094     51.50    24.86
     49124 lbo.match                0.0018     29.41    20.11              2.87
     49124 pyFM default             0.0101     83.58    57.91

With the eigenbases at Lanczos tolerance 1e-6 (``matching.EIGEN_TOL``; identical point maps at 25k
and 50k, 11-15% less CPU), one BLAS thread in ``match`` and the nearest-neighbour search in its own
two worker threads (issue 30, item 4), in the user's default environment (no thread variable
set, so pyFM's BLAS uses both cores), load 1.2-2.2, one round:

    env -u OPENBLAS_NUM_THREADS -u OMP_NUM_THREADS -u MKL_NUM_THREADS python benchmarks/matching.py --sizes 25000 50000 --repeats 1

         n method                    error  wall (s)  cpu (s)  pyFM wall / ours
     24705 lbo.match                0.0023      6.17     6.68              2.23
     24705 pyFM default             0.0094     13.78    26.19
     49124 lbo.match                0.0018     15.00    16.76              2.54
     49124 pyFM default             0.0100     38.12    66.30

The same command a few minutes earlier with ``OPENBLAS_NUM_THREADS=1`` (before the tolerance
change, load 3.4-3.9): 25k 6.46 s (6.92 CPU) against pyFM 21.30 s, 3.30x; 50k 31.27 s (18.37 CPU)
against 64.84 s, 2.07x. Profile at 50k (cProfile, load about 3, 17.5 s): eigenbases 11.1 s (ARPACK's
reorthogonalisation 4.0 s, sparse solves 4.3 s), ZoomOut 3.1 s (the final search over every vertex
2.7 s), ``estimate_map`` 1.9 s, farthest-point samples 1.3 s. Computing the two eigenbases in two
threads was slower (ARPACK holds the GIL): 50k, two interleaved rounds, 15.6 s against 12.7 s.

On the loaded machine of the two earlier runs the wall times are 1.5-2.5x the CPU times; the eigensolver runs in two
threads, so on a quiet machine ``match`` takes less wall time than CPU time. Where the time of
``match`` goes at 50k vertices (same pair, load about 6, wall / CPU seconds): eigenbases
7.7 / 6.2 and 6.5 / 6.0, WKS 0.1, ``estimate_map`` 3.7 / 3.0, farthest-point samples 1.1 / 1.1,
ZoomOut on the samples with the final search over every vertex 4.1 / 3.8.

The same command with two rounds, quiet machine (load 1.4, nothing else running),
2026-11-26 12:09 UTC (medians; ratio: median of the per-round ratios)::

    env -u OPENBLAS_NUM_THREADS -u OMP_NUM_THREADS -u MKL_NUM_THREADS python benchmarks/matching.py --sizes 25000 50000 --repeats 2

         n method                    error  wall (s)  cpu (s)  pyFM wall / ours
     24705 lbo.match                0.0023      5.96     6.43              2.17
     24705 pyFM default             0.0094     12.95    24.78
     49124 lbo.match                0.0018     15.17    16.90              2.29
     49124 pyFM default             0.0100     34.72    66.73

(A run of it 10 minutes earlier beside a browser test, load about 3, gave ratios of 6.97 and 4.62:
pyFM's two BLAS threads suffer far more from a busy machine than ``match``'s one.)

``matching.EIGEN_TOL`` on pairs that played no part in choosing it (other species, poses, part
scalings, sizes and metrics; quiet machine but beside other jobs, so the times are rough),
2026-11-26 11:40 UTC::

    env -u OPENBLAS_NUM_THREADS python benchmarks/matching.py --tolerance-check

    pair                                              n alpha  same map  err tol  err dflt  s tol  s dflt
    horse standing -> galloping                   12063   0.0    1.0000   0.0040    0.0040    4.6     3.7
    horse sitting -> tail_raised {'neck': 1.3}    19574   0.0    1.0000   0.0133    0.0133    7.5     8.3
    dog sitting -> head_turned                    15777   0.4    1.0000   0.0050    0.0050    8.1     7.3
    horse walking -> head_turned {'head': 1.6}     8795   1.0    1.0000   0.0661    0.0661    3.2     3.2
    dog galloping -> tail_raised {'legs': 1.3}    29637   0.0    1.0000   0.0258    0.0258   10.7    20.4

The point maps are identical on all five ("same map": the share of target vertices mapped alike).
(The larger errors come with a rescaled part, which is no isometry; they are the same at the
default tolerance, so they are not the tolerance's doing.)

How ``match`` got there (issue 30; before: 135 s at 25k vertices, 129 s of it in the 26
k-d-tree queries of ZoomOut's point maps). CPU seconds, one thread, dog pair at 25k vertices
unless said otherwise; the machine was loaded, so CPU rather than wall time:

* Nearest neighbours for one point map (25k x 25k rows, k = 80). ``cKDTree``: 34.5 s wall, one
  query (in 80 dimensions a k-d tree visits nearly every point, with scalar loops). Matrix
  products ``q.p - |p|^2/2`` in blocks of queries and an argmax: 1.97 s in double precision,
  0.96 s in single (same points up to near-ties). Tiles of 1024 queries x 2048 points instead
  of whole rows: 3.9 s instead of 6.6 s at 50k x 50k (random data, 80 dimensions).
* Exact pruning by the triangle inequality (points grouped in balls around 500-1000 samples,
  a ball skipped when ``|q - c| - r`` exceeds the best distance so far): only 1.3-4% of the
  products are left, but the bookkeeping makes it 0.65-1.0 s, no better than the plain single
  precision search. Grouping by the samples' cells on the mesh instead leaves 48-99% of the
  products: in the 80-dimensional embedding a mesh edge is 0.9 long (median) against a nearest-
  neighbour distance of 2.2 (median; 5.4 at the 90th percentile), so the balls are not small.
  Not kept.
* An approximate nearest-neighbour library: none is among the dependencies, and the exact
  search is now about a tenth of the pipeline at 25k vertices, so it could save at most that.
  Not tried.
* ZoomOut (30 -> 80, step 2) on farthest-point samples of both shapes, then one search over
  every vertex, against ZoomOut on every vertex (54.4 s, error 0.00047 on the dog pair):

      samples   CPU s (sampling included)   error, dog   error, horse standing -> sitting
        500           1.9                     0.0059        0.0111
       1000           1.9                     0.0035        0.0076
       2000           2.0                     0.0018        0.0051
       4000           3.2                     0.0009        0.0050

  2000 is the default (``match(n_samples=...)``). One more iteration on every vertex after the
  sampled ones: 0.0018 -> 0.0014 for 1.2 s more; not kept.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

import numpy as np

from lbo_notebooks import Mesh, creature, match, matching_error

PAIRS = [
    ("dog", "standing", "walking", None),
    ("horse", "standing", "sitting", None),
    ("dog", "standing", "walking", {"head": 1.6}),
]
N_VERTICES = 4000
SCALING_PAIRS = [("horse", 3000, {"head": 1.6}), ("horse", 2000, {"head": 1.6}), ("dog", 3000, {"legs": 1.4})]


def shuffled(mesh: Mesh, seed: int) -> tuple[Mesh, np.ndarray]:
    perm = np.random.default_rng(seed).permutation(mesh.n_vertices)
    return Mesh(mesh.vertices[perm], np.argsort(perm)[mesh.faces]), perm


def pyfm(source: Mesh, target: Mesh, zoomout: bool) -> np.ndarray:
    from pyFM.functional import FunctionalMapping
    from pyFM.mesh import TriMesh

    model = FunctionalMapping(TriMesh(source.vertices, source.faces), TriMesh(target.vertices, target.faces))
    model.preprocess(n_descr=100, descr_type="WKS", subsample_step=5, verbose=False)
    model.fit(K=(35, 35), w_descr=1e0, w_lap=1e-2, w_dcomm=1e-1, w_orient=1e-1, verbose=False)
    if zoomout:
        model.zoomout_refine(nit=10, step=1, verbose=False)
    return np.asarray(model.get_p2p(n_jobs=1))


def scaling_table() -> list[dict]:
    """Match standing -> walking with a rescaled part for alpha = 0, 0.4, 1; one row per pair."""
    print("\nsemi-local scaling, standing -> walking with a rescaled part; mean error / sqrt(area) by alpha")
    print(f"{'species':8s} {'n':>5s} {'parts':18s} {'alpha=0':>8s} {'alpha=0.4':>10s} {'alpha=1':>8s}")
    rows = []
    for i, (species, n, parts) in enumerate(SCALING_PAIRS):
        source = creature(species, "standing", n_vertices=n)
        target, perm = shuffled(creature(species, "walking", parts, n_vertices=n), seed=i)
        errs = [float(matching_error(source, match(source, target, alpha=a), perm).mean()) for a in (0.0, 0.4, 1.0)]
        print(f"{species:8s} {source.n_vertices:5d} {str(parts):18s} {errs[0]:8.4f} {errs[1]:10.4f} {errs[2]:8.4f}", flush=True)
        rows.append({"species": species, "n_vertices_requested": n, "n_vertices": source.n_vertices, "parts": parts,
                     "error": {"0": errs[0], "0.4": errs[1], "1": errs[2]}})
    return rows


def record() -> None:
    """Run the scaling table and write it, with when and where it ran, to lbo_notebooks/recorded/matching.json."""
    load = os.getloadavg()[0]
    rows = scaling_table()
    out = {
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "cores": os.cpu_count(),
        "load_average": max(load, os.getloadavg()[0]),
        "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS", "default"),
        "error": "mean geodesic error on the source / sqrt(area), all vertices, targets shuffled",
        "scaling": rows,
    }
    path = Path(__file__).resolve().parents[1] / "lbo_notebooks" / "recorded" / "matching.json"
    path.write_text(json.dumps(out, indent=1) + "\n")
    print(f"written {path}")


def large_pairs(sizes: list[int], repeats: int) -> None:
    """Real sizes: ``match`` and pyFM's default pipeline, interleaved, on one pair per size."""
    print("dog standing -> walking, target shuffled; wall and CPU seconds of the whole pipeline; runs interleaved")
    print(f"{'n':>6s} {'method':22s} {'error':>8s} {'wall (s)':>9s} {'cpu (s)':>8s} {'pyFM wall / ours':>17s}")
    for n in sizes:
        source = creature("dog", "standing", n_vertices=n)
        target, perm = shuffled(creature("dog", "walking", n_vertices=n), seed=n)
        runs: dict[str, list[tuple[float, float]]] = {"lbo.match": [], "pyFM default": []}
        errors: dict[str, float] = {}
        # The mean error over 2000 random target vertices: each wrong vertex costs a geodesic
        # field on the source, 50,000 of them would take longer than the matching.
        scored = np.random.default_rng(0).choice(target.n_vertices, 2000, replace=False)
        for _ in range(repeats):
            for label, fn in (("lbo.match", lambda: match(source, target, progress=False)), ("pyFM default", lambda: pyfm(source, target, False))):
                wall, cpu = time.perf_counter(), time.process_time()
                p2p = fn()
                runs[label].append((time.perf_counter() - wall, time.process_time() - cpu))
                errors.setdefault(label, matching_error(source, p2p[scored], perm[scored]).mean())
        ratio = np.median([b[0] / a[0] for a, b in zip(runs["lbo.match"], runs["pyFM default"])])
        for label, times in runs.items():
            wall, cpu = np.median(np.array(times), axis=0)
            extra = f"{ratio:17.2f}" if label == "lbo.match" else ""
            print(f"{source.n_vertices:6d} {label:22s} {errors[label]:8.4f} {wall:9.2f} {cpu:8.2f} {extra}", flush=True)


# Pairs that played no part in choosing matching.EIGEN_TOL (chosen on dog standing -> walking at
# 25k and 50k and on three 4k pairs): other species, poses, part scalings, sizes and metrics.
TOLERANCE_PAIRS = [
    ("horse", "standing", "galloping", None, 12000, 0.0),
    ("horse", "sitting", "tail_raised", {"neck": 1.3}, 20000, 0.0),
    ("dog", "sitting", "head_turned", None, 16000, 0.4),
    ("horse", "walking", "head_turned", {"head": 1.6}, 9000, 1.0),
    ("dog", "galloping", "tail_raised", {"legs": 1.3}, 30000, 0.0),
]


def tolerance_check() -> None:
    """``match`` with its eigenbases at ``EIGEN_TOL`` against the solver's default tolerance, on unseen pairs.

    Prints, per pair, the share of target vertices mapped to the same source vertex and the mean
    errors (over 2000 random target vertices) of both, with both runs' wall times.
    """
    import lbo_notebooks.analyses._matching as matching

    print(f"match with eigenbases at EIGEN_TOL = {matching.EIGEN_TOL:g} against the default tolerance; unseen pairs, targets shuffled")
    print(f"{'pair':52s} {'n':>6s} {'alpha':>5s} {'same map':>9s} {'err tol':>8s} {'err dflt':>9s} {'s tol':>6s} {'s dflt':>7s}")
    chosen = matching.EIGEN_TOL
    for i, (species, pose_a, pose_b, parts, n, alpha) in enumerate(TOLERANCE_PAIRS):
        source = creature(species, pose_a, n_vertices=n)
        target, perm = shuffled(creature(species, pose_b, parts, n_vertices=n), seed=100 + i)
        maps, seconds = {}, {}
        for label, tol in (("tol", chosen), ("default", None)):
            matching.EIGEN_TOL = tol
            start = time.perf_counter()
            maps[label] = match(source, target, alpha=alpha, progress=False)
            seconds[label] = time.perf_counter() - start
        matching.EIGEN_TOL = chosen
        scored = np.random.default_rng(0).choice(target.n_vertices, min(2000, target.n_vertices), replace=False)
        errs = {label: float(matching_error(source, p2p[scored], perm[scored]).mean()) for label, p2p in maps.items()}
        same = float(np.mean(maps["tol"] == maps["default"]))
        name = f"{species} {pose_a} -> {pose_b}" + (f" {parts}" if parts else "")
        print(f"{name:52s} {source.n_vertices:6d} {alpha:5.1f} {same:9.4f} {errs['tol']:8.4f} {errs['default']:9.4f} "
              f"{seconds['tol']:6.1f} {seconds['default']:7.1f}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sizes", type=int, nargs="*", help="vertex counts of the real-size table (e.g. 25000 50000); without it, the 4k tables")
    parser.add_argument("--repeats", type=int, default=2, help="interleaved runs of each method per size (median reported)")
    parser.add_argument("--record", action="store_true", help="only the semi-local scaling table, also written to lbo_notebooks/recorded/matching.json")
    parser.add_argument("--tolerance-check", action="store_true", help="EIGEN_TOL against the default tolerance on pairs not used to choose it")
    args = parser.parse_args()
    if args.tolerance_check:
        tolerance_check()
        return
    if args.record:
        record()
        return
    if args.sizes:
        large_pairs(args.sizes, args.repeats)
        return
    methods = {
        "lbo.match (defaults)": lambda s, t: match(s, t),
        "pyFM default": lambda s, t: pyfm(s, t, zoomout=False),
        "pyFM default + ZoomOut": lambda s, t: pyfm(s, t, zoomout=True),
    }
    print(f"creatures of ~{N_VERTICES} vertices, targets shuffled; error = mean geodesic error / sqrt(area)")
    print(f"{'pair':42s} {'method':24s} {'error':>8s} {'time (s)':>9s} {'time / ours':>12s}")
    for i, (species, pose_a, pose_b, parts) in enumerate(PAIRS):
        source = creature(species, pose_a, n_vertices=N_VERTICES)
        target, perm = shuffled(creature(species, pose_b, parts, n_vertices=N_VERTICES), seed=i)
        name = f"{species} {pose_a} -> {pose_b}" + (f" {parts}" if parts else "")
        base = None
        for label, fn in methods.items():
            start = time.perf_counter()
            p2p = fn(source, target)
            seconds = time.perf_counter() - start
            base = seconds if base is None else base
            err = matching_error(source, p2p, perm).mean()
            print(f"{name:42s} {label:24s} {err:8.4f} {seconds:9.2f} {seconds / base:12.2f}", flush=True)

    scaling_table()


if __name__ == "__main__":
    main()
