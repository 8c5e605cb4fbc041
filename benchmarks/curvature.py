"""Benchmark: cost of the metrics |K|^alpha g against the regular LBO.

Two questions, on procedural shapes of about 2.5k, 4k (a creature, when available) and 10k vertices:

1. The metric mass matrix: the first alpha pays for the angle defects, Voronoi areas and the
   regularised |K| (cached on the mesh); every further alpha only rescales. Baseline: the regular
   ``mass_matrix`` on a fresh mesh.
2. The eigen-solve: 300 eigenpairs for alpha = 0, 0.4, 1 (notebook 08's budget). Baseline:
   alpha = 0. The metric makes the mass matrix less uniform, which changes how fast ARPACK
   converges, not the size of the problem.

Times are the best of a few runs; the machine is shared, so read the ratios. Run:

    python benchmarks/curvature.py
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

import sys
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _measure import best_time as _best  # noqa: E402

from lbo_notebooks import Mesh, creature, eigenbasis, shapes  # noqa: E402
from lbo_notebooks.operators import metric_mass_matrix
from lbo_notebooks.operators import mass_matrix




def _fresh(mesh: Mesh) -> Mesh:
    # Same geometry, empty cache.
    return Mesh(mesh.vertices, mesh.faces, check=False)


def _meshes() -> list[tuple[str, Mesh]]:
    out = [("bumpy_sphere(4)", shapes.bumpy_sphere(4))]
    try:
        out.append(("creature('horse', 4000)", creature("horse", n_vertices=4000)))
    except (AttributeError, ImportError):
        pass
    out.append(("bumpy_sphere(5)", shapes.bumpy_sphere(5)))
    return out


def main() -> None:
    print("1. mass matrix (ms; ratio against the regular mass_matrix on a fresh mesh)")
    print(f"{'mesh':>26} {'n':>6} {'regular':>9} {'1st alpha':>10} {'ratio':>6} {'next alpha':>11} {'ratio':>6}")
    for name, mesh in _meshes():
        base = _best(lambda: mass_matrix(_fresh(mesh)))

        def first() -> None:
            metric_mass_matrix(_fresh(mesh), 0.5)

        warm = _fresh(mesh)
        metric_mass_matrix(warm, 0.5)
        first_t = _best(first)
        next_t = _best(lambda: metric_mass_matrix(warm, 0.7))
        print(f"{name:>26} {mesh.n_vertices:>6} {1e3 * base:>9.2f} {1e3 * first_t:>10.2f} {first_t / base:>6.1f} "
              f"{1e3 * next_t:>11.2f} {next_t / base:>6.1f}")

    print("\n2. eigenbasis(mesh, 300, alpha=...) (s; ratio against alpha = 0)")
    print(f"{'mesh':>26} {'n':>6} {'alpha=0':>8} {'alpha=0.4':>10} {'ratio':>6} {'alpha=1':>8} {'ratio':>6}")
    for name, mesh in _meshes()[:2]:
        t = {a: _best(lambda a=a: eigenbasis(mesh, 300, alpha=a), repeat=2) for a in (0.0, 0.4, 1.0)}
        print(f"{name:>26} {mesh.n_vertices:>6} {t[0.0]:>8.2f} {t[0.4]:>10.2f} {t[0.4] / t[0.0]:>6.2f} "
              f"{t[1.0]:>8.2f} {t[1.0] / t[0.0]:>6.2f}")


if __name__ == "__main__":
    main()
