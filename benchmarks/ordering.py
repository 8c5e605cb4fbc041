"""Fill-reducing orderings for SuperLU: METIS nested dissection (ours) against SuperLU's own.

Run from the repository root::

    .venv/bin/python benchmarks/ordering.py            # 10k, 50k and 150k vertices
    .venv/bin/python benchmarks/ordering.py --quick    # 10k and 50k

Every factorisation in the package is ``sparse_factor.symmetric_lu``: an unpivoted SuperLU of
``P M P^T`` with ``P`` a METIS nested-dissection order. This compares it, on the eigensolver's
indefinite ``W - b A`` (``b`` near the 100th eigenvalue), with SuperLU ordering the same matrix
itself by minimum degree on ``A + A^T`` (``MMD_AT_PLUS_A``, what the package used before) and by
COLAMD (SciPy's default), all with one BLAS thread, in one run. Columns: the ordering's own time,
the factorisation's, the fill (entries of L and U), and milliseconds per right-hand side when
solving blocks of 4 (the Lanczos block). Times are the best of 3. The METIS order is passed
explicitly at every size; given no order, ``symmetric_lu`` uses it only from
``NESTED_DISSECTION_MIN`` (20k) unknowns on, where its own cost is repaid.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
import scipy.sparse.linalg as spla
from threadpoolctl import threadpool_limits

import lbo_notebooks as lbo
from lbo_notebooks.spectral._engine.factor import fill_reducing_order, symmetric_lu

from _measure import best_time  # type: ignore[import-not-found]  # benchmarks/ is the script's directory
from mds import deformed_torus  # type: ignore[import-not-found]


def superlu(matrix, spec: str):
    return spla.splu(matrix.tocsc(), permc_spec=spec, diag_pivot_thresh=0.0, options={"SymmetricMode": True})


def rows(n_vertices: int) -> list[tuple]:
    mesh = deformed_torus(n_vertices)
    W, A = lbo.stiffness_matrix(mesh), lbo.mass_matrix(mesh)
    shift = 100 * 4 * np.pi / float(A.sum())  # Weyl: about 100 eigenvalues below it
    M = (W - shift * A).tocsr()
    block = np.random.default_rng(0).standard_normal((M.shape[0], 4))
    out = []
    start = time.perf_counter()
    order = fill_reducing_order(M)
    order_s = time.perf_counter() - start
    nd = symmetric_lu(M, order)
    out.append(("METIS ND (ours)", order_s, best_time(lambda: symmetric_lu(M, order)), nd.nnz, best_time(lambda: nd.solve(block)) / 4))
    for spec in ("MMD_AT_PLUS_A", "COLAMD"):
        lu = superlu(M, spec)
        out.append((f"SuperLU {spec}", 0.0, best_time(lambda: superlu(M, spec)), lu.L.nnz + lu.U.nnz, best_time(lambda: lu.solve(block)) / 4))
    return [(mesh.n_vertices, *r) for r in out]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="10k and 50k vertices only")
    sizes = [10_000, 51_200] if parser.parse_args().quick else [10_000, 51_200, 150_000]
    print(f"{'vertices':>8s} {'ordering':<22s} {'order s':>8s} {'factor s':>9s} {'fill':>11s} {'solve ms/rhs':>13s}")
    with threadpool_limits(1):
        for n in sizes:
            table = rows(n)
            for r in table:
                print(f"{r[0]:8d} {r[1]:<22s} {r[2]:8.3f} {r[3]:9.3f} {r[4]:11d} {r[5] * 1e3:13.2f}")
            ours, mmd = table[0], table[1]
            print(
                f"{'':8s} MMD / ours: factorisation {mmd[3] / ours[3]:.2f}x (with the ordering {mmd[3] / (ours[2] + ours[3]):.2f}x), "
                f"fill {mmd[4] / ours[4]:.2f}x, solve {mmd[5] / ours[5]:.2f}x"
            )


if __name__ == "__main__":
    main()
