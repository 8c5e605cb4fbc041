"""Interleaved A/B timing of ``eigenbasis``: the working tree against an earlier commit, on one machine.

Run: ``.venv/bin/python benchmarks/versus.py [REV] [--size 10k] [--k 100] [--pairs 8] [--plain]``
(``REV`` defaults to ``HEAD``: what the uncommitted change does).

These machines drift: the same call can take 20% longer an hour later. Two benchmark runs made
minutes apart therefore cannot show a 10% change. Here each pair runs the old and the new code
back to back, each in a fresh process (a ``git worktree`` of ``REV`` for the old), on a mesh and
with the calls of ``benchmarks/eigen.py``, and the table reports the median of the per-pair
ratios. ``--plain`` adds the peers' one-line ``eigsh(W, k, M=A, sigma=-s)`` to every pair. Each process times one call after a warm-up call
on 2.5k vertices (imports and lazy set-up excluded) and reports the growth of its peak RSS.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from eigen import SIZES  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
# One measurement in a fresh interpreter: the package from the tree given as argv[1], the meshes
# and the two calls from benchmarks/eigen.py (this tree's), so both sides time the same thing.
CHILD = """
import sys, time, resource
sys.path[:0] = [sys.argv[1], sys.argv[2]]
import lbo_notebooks as lbo
from eigen import mesh_for, ours, plain
assert lbo.__file__.startswith(sys.argv[1]), lbo.__file__
call, k = {"ours": ours, "plain": plain}[sys.argv[3]], int(sys.argv[5])
call(mesh_for("warm-up"), 100)
mesh = mesh_for(sys.argv[4])
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
start = time.perf_counter()
lam_k = call(mesh, k)
seconds = time.perf_counter() - start
print(seconds, (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base) / 1024, lam_k)
"""


def run(tree: Path, what: str, size: str, k: int) -> tuple[float, float, float]:
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(tree), str(ROOT / "benchmarks"), what, size, str(k)],
        capture_output=True,
        text=True,
        check=True,
    )
    seconds, mib, lam_k = map(float, out.stdout.split())
    return seconds, mib, lam_k


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rev", nargs="?", default="HEAD", help="the commit to compare against (default HEAD; e.g. HEAD~3)")
    sizes = [size for size in SIZES if size != "warm-up"]
    ap.add_argument("--size", choices=sizes, default="10k", help="a mesh of benchmarks/eigen.py")
    ap.add_argument("--k", type=int, default=100)
    ap.add_argument("--pairs", type=int, default=8)
    ap.add_argument("--plain", action="store_true", help="also time the peers' eigsh call in every pair")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        old_tree = Path(tmp) / "old"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(old_tree), args.rev], check=True, capture_output=True)
        try:
            variants = {"old": (old_tree, "ours"), "new": (ROOT, "ours")}
            if args.plain:
                variants["plain"] = (ROOT, "plain")
            results: dict[str, list[tuple[float, float, float]]] = {name: [] for name in variants}
            for _ in range(args.pairs):
                for name, (tree, what) in variants.items():
                    results[name].append(run(tree, what, args.size, args.k))
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(old_tree)], check=False)
    print(f"{SIZES[args.size][0]} ({args.size}), k = {args.k}, {args.pairs} interleaved pairs (old = {args.rev}, new = working tree)")
    print(f"{'':6}{'median s':>10}{'min s':>8}{'median MiB':>12}{'lam_k':>16}")
    for name, rows in results.items():
        t, mib = np.array([r[0] for r in rows]), np.array([r[1] for r in rows])
        print(f"{name:6}{np.median(t):>10.3f}{t.min():>8.3f}{np.median(mib):>12.0f}{rows[0][2]:>16.10g}")
    ratios = {"old/new": ("old", "new"), "plain/new": ("plain", "new")}
    summary = {}
    for label, (a, b) in ratios.items():
        if a in results:
            per_pair = [x[0] / y[0] for x, y in zip(results[a], results[b])]
            summary[label] = float(np.median(per_pair))
            print(f"{label} per pair: median {np.median(per_pair):.2f}, min {min(per_pair):.2f}")
    print(json.dumps(summary))


if __name__ == "__main__":
    main()
