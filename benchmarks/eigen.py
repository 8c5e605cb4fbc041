"""Benchmark ``lbo_notebooks.eigenbasis`` against the plain SciPy call peer libraries use.

Run: ``.venv/bin/python benchmarks/eigen.py``. Prints, for 10k vertices / k=100 and 50k vertices
/ k=300, the wall time and peak memory of ``eigenbasis(mesh, k)`` and of
``scipy.sparse.linalg.eigsh(W, k, M=A, sigma=-0.01)`` on the same operators, measured in the
same run (each in a fresh process), and their ratio.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import scipy.sparse.linalg as spla

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _measure import measure  # noqa: E402

import lbo_notebooks as lbo  # noqa: E402
from lbo_notebooks import shapes  # noqa: E402

# (name, k): a 10,242-vertex bumpy sphere with k=100 and a 50,000-vertex torus with k=300.
CASES = [("bumpy sphere", 100), ("torus", 300)]


def mesh_for(name: str) -> lbo.Mesh:
    if name == "torus":
        return shapes.torus(1.0, 0.4, n_major=400, n_minor=125)
    return shapes.bumpy_sphere(5)


def ours(name: str, k: int) -> float:
    spec = lbo.eigenbasis(mesh_for(name), k)
    return float(spec.values[-1])


def plain(name: str, k: int) -> float:
    m = mesh_for(name)
    W, A = lbo.stiffness_matrix(m), lbo.mass_matrix(m)
    values = spla.eigsh(W, k=k, M=A, sigma=-0.01, which="LM")[0]
    return float(np.sort(values)[-1])


def main() -> None:
    print(f"{'mesh':<14}{'vertices':>9}{'k':>5} | {'eigenbasis s':>12}{'MiB':>7} | {'plain eigsh s':>13}{'MiB':>7} | {'time ratio':>10}{'lam_k agree':>12}")
    for name, k in CASES:
        n = mesh_for(name).n_vertices
        t1, _, m1, v1 = measure(ours, name, k)
        t2, _, m2, v2 = measure(plain, name, k)
        print(f"{name:<14}{n:>9}{k:>5} | {t1:>12.2f}{m1:>7.0f} | {t2:>13.2f}{m2:>7.0f} | {t1 / t2:>10.2f}{abs(v1 / v2 - 1):>12.1e}")
    print("time ratio = eigenbasis / plain eigsh (< 1: ours is faster). MiB = growth of peak RSS during the call.")


if __name__ == "__main__":
    main()
