"""Interleaved A/B timing of ``eigenbasis``: the working tree against an earlier commit, on one machine.

Run: ``.venv/bin/python benchmarks/versus.py [REV] [--mesh bumpy10k] [--k 100] [--pairs 8] [--plain]``
(``REV`` defaults to ``HEAD``: what the uncommitted change does).

These machines drift: the same call can take 20% longer an hour later. Two benchmark runs made
minutes apart therefore cannot show a 10% change. Here each pair runs the old and the new code
back to back, each in a fresh process (a ``git worktree`` of ``REV`` for the old), and the table
reports the median of the per-pair ratios. ``--plain`` adds the peers' one-line
``eigsh(W, k, M=A, sigma=-s)`` to every pair. Each process times one call after a warm-up call
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

ROOT = Path(__file__).resolve().parents[1]
MESHES = {
    "bumpy10k": "shapes.bumpy_sphere(5)",
    "ico10k": "shapes.icosphere(5)",
    "torus10k": "shapes.torus(1.0, 0.4, n_major=160, n_minor=64)",
    "rect10k": "shapes.rectangle(2.0, 1.0, nx=140, ny=72)",
    "torus50k": "shapes.torus(1.0, 0.4, n_major=400, n_minor=125)",
}
# One measurement in a fresh interpreter; the package is imported from the tree given as argv[1].
CHILD = """
import sys, time, resource
sys.path.insert(0, sys.argv[1])
import numpy as np, scipy.sparse.linalg as spla
import lbo_notebooks as lbo
from lbo_notebooks import shapes
assert lbo.__file__.startswith(sys.argv[1]), lbo.__file__
what, k = sys.argv[2], int(sys.argv[4])
def call(mesh):
    if what == "plain":
        W, A = lbo.stiffness_matrix(mesh), lbo.mass_matrix(mesh)
        s = 1e-2 * 4.0 * np.pi / float(A.sum())
        return float(np.max(spla.eigsh(W, k=k, M=A, sigma=-s, which="LM")[0]))
    return float(lbo.eigenbasis(mesh, k).values[-1])
call(shapes.bumpy_sphere(4))
mesh = eval(sys.argv[3])
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
start = time.perf_counter()
lam_k = call(mesh)
seconds = time.perf_counter() - start
print(seconds, (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - base) / 1024, lam_k)
"""


def run(tree: Path, what: str, mesh: str, k: int) -> tuple[float, float, float]:
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(tree), what, MESHES[mesh], str(k)], capture_output=True, text=True, check=True
    )
    seconds, mib, lam_k = map(float, out.stdout.split())
    return seconds, mib, lam_k


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rev", nargs="?", default="HEAD", help="the commit to compare against (default HEAD; e.g. HEAD~3)")
    ap.add_argument("--mesh", choices=sorted(MESHES), default="bumpy10k")
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
                    results[name].append(run(tree, what, args.mesh, args.k))
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(old_tree)], check=False)
    print(f"{args.mesh}, k = {args.k}, {args.pairs} interleaved pairs (old = {args.rev}, new = working tree)")
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
