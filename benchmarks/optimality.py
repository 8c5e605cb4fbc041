"""Benchmark ``worst_case_ratio``: the sparse path (Lanczos + sparse LU) against the dense one.

Run: ``.venv/bin/python benchmarks/optimality.py``. For meshes from 642 to 20,000 vertices and a
basis of n = 100 functions (the constant plus Legendre polynomials in the coordinates,
:func:`lbo_notebooks.analyses._competitor_bases.polynomial_basis`), prints the wall time of
``worst_case_ratio(..., method="dense")`` and ``method="sparse"`` (each in a fresh process; the
mesh and basis are built before the clock starts), the growth of peak memory, their ratio, and the
relative difference of the two answers. The dense path is skipped above 2,562 vertices (an
O(n_vertices^3) generalized eigensolve of two dense matrices).

On a shared, oversubscribed machine multithreaded OpenBLAS can slow small dense products by 10-30x;
``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/optimality.py`` gives steadier numbers.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _measure import measure  # noqa: E402

import lbo_notebooks as lbo  # noqa: E402
from lbo_notebooks import shapes  # noqa: E402
from lbo_notebooks.analyses import _competitor_bases as bases
from lbo_notebooks.analyses import worst_case_ratio  # noqa: E402

N = 100
DENSE_MAX = 2562
CASES = ["bumpy sphere 642", "bumpy sphere 2562", "bumpy sphere 10242", "torus 20000"]


def mesh_for(name: str) -> lbo.Mesh:
    if name == "torus 20000":
        return shapes.torus(1.0, 0.4, n_major=200, n_minor=100)
    return shapes.bumpy_sphere({"642": 3, "2562": 4, "10242": 5}[name.split()[-1]])


def run(name: str, method: str) -> tuple[float, float]:
    m = mesh_for(name)
    W, A = lbo.stiffness_matrix(m), lbo.mass_matrix(m)
    B = bases.polynomial_basis(m, N)
    start = time.perf_counter()
    value = worst_case_ratio(B, W, A, method=method)
    return time.perf_counter() - start, value


def main() -> None:
    print(f"{'mesh':<20}{'vertices':>9}{'n':>5} | {'dense s':>8}{'MiB':>7} | {'sparse s':>9}{'MiB':>7} | {'dense/sparse':>12}{'rel. diff':>11}{'C(V)':>12}")
    for name in CASES:
        nv = mesh_for(name).n_vertices
        _, _, m2, (t2, v2) = measure(run, name, "sparse")
        if nv <= DENSE_MAX:
            _, _, m1, (t1, v1) = measure(run, name, "dense")
            dense = f"{t1:>8.2f}{m1:>7.0f}"
            ratio, diff = f"{t1 / t2:>12.1f}", f"{abs(v1 / v2 - 1):>11.1e}"
        else:
            dense, ratio, diff = f"{'-':>8}{'-':>7}", f"{'-':>12}", f"{'-':>11}"
        print(f"{name:<20}{nv:>9}{N:>5} | {dense} | {t2:>9.2f}{m2:>7.0f} | {ratio}{diff}{v2:>12.4g}")
    print("seconds: worst_case_ratio only (mesh, operators and basis are built first). MiB = growth of peak RSS")
    print("during the whole child (including the basis). dense/sparse > 1: the sparse path is faster.")


if __name__ == "__main__":
    main()
