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

The recorded runs, the tolerance check and how ``match`` got its speed: ``benchmarks/results/matching-history.md``.
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
