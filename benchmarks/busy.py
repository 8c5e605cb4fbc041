"""Benchmark: each heavy public call quiet and beside one CPU-bound process (issue 30, item 4).

On Binder a container sees all the host's cores under a small CPU quota, and on a laptop other
programs run; a call that fills every core with BLAS threads then competes with them. This runs
each heavy call in a fresh process, once on a quiet machine and once beside a child process that
spins (``while True: pass``), interleaved, and prints the slowdown (busy / quiet wall time).

The BLAS thread variables (``OPENBLAS_NUM_THREADS`` and the others of
:data:`lbo_notebooks.spectral._engine.threads.ENVIRONMENT`) are *removed* from the children's environment,
as on a user's machine: OpenBLAS then starts one thread per core.

With ``--baseline REV`` the same calls also run from ``git archive REV`` (a copy of that commit in
a temporary directory), interleaved with this tree, so the quiet times of the two are compared in
the same run (new / old) and both slowdowns are shown.

Run::

    python benchmarks/busy.py [--calls rpca smds match eigenbasis distances] [--repeats 2] [--baseline HEAD]

Calls and sizes (``--n`` scales the meshes):

* ``rpca``: :class:`~lbo_notebooks.analyses._rpca.RegularizedPCA` of two poses (6 columns) of a 25k-vertex
  torus, ``solve(100, beta=0.5)``;
* ``smds``: :func:`~lbo_notebooks.analyses._mds.spectral_mds` with its defaults, deformed torus of 25k;
* ``match``: :func:`~lbo_notebooks.match` with its defaults, dog standing -> walking, 12k, target shuffled;
* ``eigenbasis``: ``eigenbasis(mesh, 100)`` on the 25k dog;
* ``distances``: ``geodesic_distances`` from every vertex of a 4k dog (a 4k x 4k matrix).

The recorded run (also in ``lbo_notebooks/recorded/busy.json``) and the fix it led to:
``benchmarks/results/busy-history.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
BLAS_VARIABLES = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")
CALLS = ("rpca", "smds", "match", "eigenbasis", "distances")
SIZES = {"rpca": 25000, "smds": 25000, "match": 12000, "eigenbasis": 25000, "distances": 4000}


def _setup(call: str, n: int):
    """Inputs of ``call`` (not timed) and the timed function."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import lbo_notebooks as lbo

    if call == "rpca":
        from rpca import two_poses

        from lbo_notebooks.analyses import RegularizedPCA

        mesh, X = two_poses(n)
        W, A = lbo.stiffness_matrix(mesh), lbo.mass_matrix(mesh)
        return lambda: RegularizedPCA(X, W, A, center=True).solve(100, beta=0.5)
    if call == "smds":
        from mds import deformed_torus

        mesh = deformed_torus(n)
        _ = mesh.edges, mesh.face_areas
        return lambda: lbo.spectral_mds(mesh, progress=False)
    if call == "match":
        a = lbo.creature("dog", "standing", n_vertices=n)
        b = lbo.creature("dog", "walking", n_vertices=n)
        perm = np.random.default_rng(0).permutation(b.n_vertices)
        b = lbo.Mesh(b.vertices[perm], np.argsort(perm)[b.faces])
        return lambda: lbo.match(a, b, progress=False)
    if call == "eigenbasis":
        mesh = lbo.creature("dog", "standing", n_vertices=n)
        _ = mesh.edges, mesh.face_areas
        return lambda: lbo.eigenbasis(mesh, 100)
    if call == "distances":
        mesh = lbo.creature("dog", "standing", n_vertices=n)
        return lambda: lbo.geodesic_distances(mesh, np.arange(mesh.n_vertices), progress=False)
    raise ValueError(call)


def child(call: str, n: int) -> None:
    fn = _setup(call, n)
    c0, t0 = time.process_time(), time.perf_counter()
    fn()
    print(json.dumps({"wall": time.perf_counter() - t0, "cpu": time.process_time() - c0}))


def run(tree: Path, call: str, n: int, busy: bool) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in BLAS_VARIABLES}
    env["PYTHONPATH"] = str(tree)
    spinner = subprocess.Popen([sys.executable, "-c", "while True: pass"]) if busy else None
    try:
        if spinner is not None:
            time.sleep(0.2)
        out = subprocess.run([sys.executable, __file__, "--child", call, str(n)], env=env,
                             capture_output=True, text=True, check=False)
    finally:
        if spinner is not None:
            spinner.kill()
            spinner.wait()
    if out.returncode != 0:
        raise RuntimeError(f"{call} in {tree} failed:\n{out.stderr}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", nargs="+", choices=CALLS, default=list(CALLS))
    parser.add_argument("--repeats", type=int, default=1)
    parser.add_argument("--scale", type=float, default=1.0, help="multiply every mesh size")
    parser.add_argument("--baseline", help="a git revision to compare with (run from git archive)")
    parser.add_argument("--record", action="store_true", help="also write the table to lbo_notebooks/recorded/busy.json")
    parser.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(args.child[0], int(args.child[1]))
        return
    trees = {"new": ROOT}
    with tempfile.TemporaryDirectory() as tmp:
        if args.baseline:
            old = Path(tmp) / "old"
            old.mkdir()
            archive = subprocess.run(["git", "-C", str(ROOT), "archive", args.baseline, "lbo_notebooks"],
                                     capture_output=True, check=True).stdout
            subprocess.run(["tar", "-x", "-C", str(old)], input=archive, check=True)
            trees = {"old": old, "new": ROOT}
        times: dict = {}
        for r in range(args.repeats):
            for call in args.calls:
                n = int(SIZES[call] * args.scale)
                order = [(name, busy) for name in trees for busy in (False, True)]
                if r % 2:
                    order.reverse()
                for name, busy in order:
                    t = run(trees[name], call, n, busy)
                    times.setdefault((call, name, busy), []).append(t)
                    print(f"{call:10s} {name:3s} {'busy ' if busy else 'quiet'} wall {t['wall']:7.2f} s  cpu {t['cpu']:7.2f} s",
                          flush=True)
    print(f"\nload average at the end: {os.getloadavg()[0]:.2f}; medians over {args.repeats} round(s)")
    print(f"{'call':10s} {'code':4s} {'quiet s':>8s} {'busy s':>8s} {'busy/quiet':>10s} {'quiet cpu':>9s} {'busy cpu':>8s}"
          + ("  quiet new/old" if len(trees) > 1 else ""))
    rows = []
    for call in args.calls:
        for name in trees:
            quiet = np.median([t["wall"] for t in times[(call, name, False)]])
            busy = np.median([t["wall"] for t in times[(call, name, True)]])
            cpu = np.median([t["cpu"] for t in times[(call, name, False)]])
            busy_cpu = np.median([t["cpu"] for t in times[(call, name, True)]])
            extra = ""
            if len(trees) > 1 and name == "new":
                ratios = [a["wall"] / b["wall"] for a, b in zip(times[(call, "new", False)], times[(call, "old", False)])]
                extra = f"  {np.median(ratios):13.2f}"
            print(f"{call:10s} {name:4s} {quiet:8.2f} {busy:8.2f} {busy / quiet:10.2f} {cpu:9.2f} {busy_cpu:8.2f}{extra}")
            rows.append({"call": call, "code": name, "n": int(SIZES[call] * args.scale), "quiet_s": float(quiet),
                         "busy_s": float(busy), "slowdown": float(busy / quiet), "quiet_cpu_s": float(cpu),
                         "busy_cpu_s": float(busy_cpu), "runs": {("busy" if b else "quiet"): times[(call, name, b)] for b in (False, True)}})
    if args.record:
        out = ROOT / "lbo_notebooks" / "recorded" / "busy.json"
        out.write_text(json.dumps({"command": " ".join(["python benchmarks/busy.py"] + sys.argv[1:]),
                                   "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
                                   "baseline": args.baseline, "load_at_end": os.getloadavg()[0],
                                   "cores": os.cpu_count(), "rows": rows}, indent=1) + "\n")
        print(f"written to {out}")


if __name__ == "__main__":
    main()
