"""Benchmark ``lbo_notebooks.eigenbasis`` (spectrum slicing) against the eigensolver calls peers make.

Run: ``.venv/bin/python benchmarks/eigen.py [--quick]``. For each mesh size and ``k`` it prints the
wall time and the growth of peak memory (RSS, each call in a fresh process, all in the same run) of

- ``ours``: ``eigenbasis(mesh, k)`` (operators + solver + sign fixing; ``solver="auto"`` slices from k = 100 on);
- ``plain``: operators + ``eigsh(W, k, M=A, sigma=-s, which="LM")``, the call LaPy, pyFM, geomfum and
  robust-laplacian users make (also ``eigenbasis(..., solver="arpack")``);
- ``lapy``: ``lapy.Solver(TriaMesh(v, f), lump=True).eigs(k)``;
- ``robust``: ``robust_laplacian.mesh_laplacian(v, f)`` + the same ``eigsh`` call;

and the ratios ``plain / ours`` (> 1: ours is faster) and ``|lam_k(ours) / lam_k(plain) - 1|``.
``--quick`` runs only 10k / k=100 and 50k / k=300 (the issue's two targets).
``--held-out`` runs the same on ``HELD_OUT``, shapes that chose no default.
``--family`` runs k=100 on six different 10k-vertex shapes (closed, with boundary, genus 1, thin
parts, elongated, scan-like: holes, noise, two pieces) and checks plain/ours >= 1.5 on each
(issue 30, item 5); ours and plain alternate, best of three fresh processes each.

``--family`` in the user's default environment (no thread variable set: the peer's BLAS uses both
cores, ours limits itself to one per worker), quiet 2-core machine. ``--interpreters`` runs every
call in a new Python process instead of a forked one (best of 5): slower, and the check that the
forked measurement is fair. 2026-11-26, quiet 2-core machine::

    env -u OPENBLAS_NUM_THREADS python benchmarks/eigen.py --family [--interpreters]

                      20:15 UTC (aa57219:    14:28 UTC           14:37 UTC (a slower hour:
                      centred windows)                           the peer took 7-16% longer)
                      forked  interpr.       forked  interpr.    forked  interpr.     plain/ours
          bumpy sphere  1.86    1.87           1.56    1.65        1.52    1.61
       disk (boundary)  1.74    1.79           1.53    1.73        1.44    1.67
       torus (genus 1)  2.54    2.67           2.08    2.07        1.97    2.12
       dog (thin legs)  2.31    2.37           2.00    2.19        2.00    1.98
        thin ellipsoid  1.75    1.95           1.58    1.48        1.45    1.59
            scan proxy  1.79    1.95           1.54    1.75        1.53    1.54

Since aa57219 the goal (>= 1.5 on each) is met with a margin: 1.74-2.67. Before, it was met in most
runs and missed by up to 0.06 in some, at the noise of this machine. What changed (each a commit
with its own measurements): every Lanczos window is centred on its shift (``slicing.REACH``; the
top window had reached 464 below its shift and 300 above on the disk, and Lanczos converges last at
the edge farthest from the shift), each lower shift is aimed at the middle of its window
(``slicing.centred_target``), the Krylov runs look at their Ritz values from 2 basis vectors per
pair on (nev + 8 for small sets) and with numpy's divide-and-conquer ``eigh``, and
``fix_signs_in_place`` works in row blocks. In-process, best of 5, two rounds interleaved with the
commit before (2a4cc9f): 0.83-0.94 of the time on the six shapes. The same run on seven 10k-ish
shapes that were not used to choose anything (``HELD_OUT``: two horses, a sitting dog, an
icosphere, a rectangle, a jittered torus, all 9-10.3k vertices, and a 15.5k dog; forked, best of
3): plain/ours 2.01-2.34 at 20:05 UTC, against 1.72-2.13 for 2a4cc9f in the same hour;
``--held-out`` at 20:30 UTC (aa57219): horse 2.22, galloping horse 2.12, sitting dog 2.29,
icosphere 1.98, rectangle 2.10, jittered torus 2.43, 15.5k dog 2.26. ``--quick`` at 50k vertices,
k = 300: 7.60 s against 8.29 s, 4.27x the peer, peak 381 MiB against 377 MiB.

After the fix for windows next to big clusters (7e82835), 21:01 UTC, forked, a slower hour (the peer
took 0.75-1.08 s): family 1.88, 1.90, 2.55, 2.46, 1.97, 1.87 (table order); ``--held-out`` horse
2.35, galloping horse 2.26, sitting dog 2.01, icosphere 1.99, rectangle 2.21, jittered torus 2.42,
15.5k dog 2.27.

Earlier (14:28 and 14:37 above; again at 17:12 UTC on eab22c4, forked / new interpreters: bumpy
sphere 1.61 / 1.64, disk 1.66 / 1.63, torus 2.19 / 2.28, dog 2.12 / 2.16, ellipsoid 1.51 / 1.59,
scan proxy 1.60 / 1.72) the two weakest were the subdivided icosahedra (bumpy sphere, ellipsoid),
on which SuperLU's minimum degree is slowest (47-56 ms for the first factorisation against
21-36 ms on the others) and leaves 27% more fill than METIS. At 11:27 UTC, before the two
changes below, the forked run gave 1.46, 1.32, 1.79, 1.59, 1.36, 1.25. The two changes:

- The measurement. OpenBLAS drops its thread pool across ``fork`` and builds it again at the
  child's first change of its thread count; the new threads then spin for about 0.1 s (0.2 s of
  CPU over a 0.1 s sleep on two cores: numpy's and SciPy's OpenBLAS each have one). Ours limits
  BLAS to one thread per worker and paid that spin inside the timed call; the peer changes
  nothing and did not. On the scan proxy ours took 0.54-0.64 s forked against 0.44-0.49 s in new
  interpreters. ``lbo_notebooks.cost.measure_in_fresh_process`` now rebuilds the pools and waits
  until they are idle before it starts the clock; forked and new-interpreter times then agree to
  the noise (table above). Every benchmark that measures in forked processes gains the fix.
- The ordering. Below ``NESTED_DISSECTION_MIN`` (20k) vertices ``eigenbasis`` no longer runs METIS
  (31-47 ms at 10k, before the first set could start): SuperLU's minimum degree orders the top
  shift's matrix and that order serves the others. In new interpreters, best of 5, interleaved
  with the tree before: time 0.88, 0.80, 0.87 of before on the disk, dog and scan proxy, 0.97-1.02
  on the bumpy sphere, torus and ellipsoid (whose minimum-degree fill is 21-27% above METIS's),
  and 0.83, 0.94, 0.97 at 15.5k (k = 100, 300) and 19.4k vertices (k = 300); lam_k agrees to 3e-15.
  The price is memory on those three closed shapes: peak RSS growth ours/plain 1.08 and 1.19 on
  the bumpy sphere and ellipsoid against 0.98 and 1.11 with METIS (3-5 MiB more; 0.94-1.01 on the
  other four). ``--quick`` (10k bumpy sphere, k = 100) reports 1.08 against its goal of <= 1.

Measured before those two changes: with ``OPENBLAS_NUM_THREADS=1`` for both, plain/ours was
1.98-2.71 on all six (the peer gains 1.5x from a second BLAS thread, ours does not). Why ours
does not gain from the second core at this size, measured on the scan proxy (one BLAS thread,
in-process unless said):

- SciPy's (1.17) ``SuperLU.solve`` does not run side by side with another. It releases the GIL,
  but a supernodal solve on a surface mesh is thousands of tiny ``dtrsm``/``dgemm`` calls, and
  such calls into SciPy's OpenBLAS do not run in parallel from two threads (measured without
  Python in ``benchmarks/superlu_threads.py``; this docstring said "holds the GIL" until
  2026-11-26). Fifty 4-column solves with the 10.9k factor in
  each of two threads take as long as the hundred in one (0.169 s against 0.167 s: 1.01x), while
  the Krylov projections (BLAS-3) scale 1.92x and the factorisations 1.5x. So the two Lanczos sets
  of ``eigenbasis(mesh, 100)``, 0.23 s and 0.17 s alone, take 0.46 s side by side: 0.89x of
  running them one after the other. In a fresh process the timeline is: operators and METIS
  75 ms, the top shift's factorisation and count 64 ms, the top set 142-499 ms, meanwhile the
  count above lam_k and the lower shift (in the calling thread), the lower set 241-513 ms.
- A GIL-free triangular solve (a prototype in numba, ``nogil``, same speed as SuperLU's one
  thread) brings the two sets to 1.52x side by side, but ``eigenbasis`` end to end only 5-8%
  (fresh processes, best of 3: scan proxy 0.556 -> 0.517 s, disk 0.537 -> 0.509 s, ellipsoid
  0.575 -> 0.533 s) and 1-4% at 50k vertices, k = 300 (7.36/7.02 -> 7.05/6.94 s). Not adopted: a
  compiler dependency (numba and llvmlite, about 50 MB, a JIT at the first call) for that.
  SciPy's module-level ``_superlu.gstrs`` (private API) also releases the GIL, given the factors
  in SuperLU's own layout (the diagonal of ``U`` in ``L``'s columns): the same results to
  1e-14 and about the same gain (-4 to -11% on five shapes, +7% on the scan proxy; one run beside
  a browser test, so noisy).
- METIS beside the first factorisation (the first ordered by minimum degree, METIS's order for
  every later one; METIS called through ctypes, since pymetis holds the GIL throughout): new /
  old 0.93, 0.99, 0.99, 1.01, 0.97, 1.09 on the six shapes, then 0.98, 0.98, 1.035 on the
  bumpy sphere, dog and scan proxy (new interpreters, best of 5 and 7), and no less peak memory
  (one run each: 48.2 against 48.6 MiB on the bumpy sphere, 49.8 against 47.4 on the
  ellipsoid). Not kept.
- Reverse Cuthill-McKee before minimum degree: 13% less fill and half the first factorisation's
  time on subdivided icosahedra, but 13-17% more fill on the tori and 1-6% more on the disk,
  rectangle and scan proxy (fill decides by the vertex order's tie-breaking, not by the shape).
  Not kept.
- Four sets for k = 100 instead of two (``slice_size`` 34 or 25) take 1.4-3.1x as long. Blocks
  of 6 and 8 with both sets running: 2-33% slower than 4 (in-process, best of 4).
- ``sys.setswitchinterval`` of 0.5 or 0.1 ms instead of 5: no change (the GIL is not the limit).
- One worker with two BLAS threads (one set of 100, or two sets in turn) is slower: 0.65-0.98 s.
  Blocks of 2, 3, 5, 6 or 8 vectors instead of 4 are 2-50% slower (both sets, one thread);
  ``tol=1e-8`` instead of 1e-10 saves 5-10% of the sets, but the default accuracy stays.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import scipy.sparse.linalg as spla

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _measure import measure  # noqa: E402

import lbo_notebooks as lbo  # noqa: E402
from lbo_notebooks import shapes  # noqa: E402

SIZES = {
    "10k": ("bumpy sphere", 5),
    "10k ico": ("icosphere", 5),
    "50k": ("torus", (400, 125)),
    "150k": ("torus", (750, 200)),
    "warm-up": ("bumpy sphere", 4),
}
# The icosphere's exactly repeated eigenvalues (5-fold ones among them) are the hard case for a
# block method: a block of 4 misses copies, which the inertia counts expose and slicing completes.
CASES = [("10k", 100), ("10k", 300), ("10k ico", 100), ("50k", 100), ("50k", 300), ("150k", 100), ("150k", 300)]
QUICK = [("10k", 100), ("50k", 300)]


def mesh_for(size: str) -> lbo.Mesh:
    name, arg = SIZES[size]
    if name == "torus":
        return shapes.torus(1.0, 0.4, n_major=arg[0], n_minor=arg[1])
    if name == "icosphere":
        return shapes.icosphere(arg)
    return shapes.bumpy_sphere(arg)


def scan_proxy(n_vertices: int = 10_000, seed: int = 0) -> lbo.Mesh:
    """A 10k-vertex stand-in for a raw scan: a dog with 16 holes cut, vertices moved off the surface
    by up to a quarter of the mean edge length, and a disjoint holed copy of a small sphere (two pieces)."""
    rng = np.random.default_rng(seed)
    dog = lbo.creature("dog", n_vertices=int(n_vertices * 0.9))
    centres = dog.vertices[rng.choice(dog.n_vertices, 16, replace=False)]
    h = dog.mean_edge_length
    tri_centres = dog.vertices[dog.faces].mean(axis=1)
    near = np.min(np.linalg.norm(tri_centres[:, None] - centres[None], axis=2), axis=1) < 2.5 * h
    ball = shapes.icosphere(4)
    ball_v = ball.vertices * 0.15 + dog.vertices.max(axis=0) + 0.3
    ball_keep = ball.faces[ball.vertices[ball.faces].mean(axis=1)[:, 2] < 0.7]
    v = np.vstack([dog.vertices + rng.uniform(-0.25, 0.25, dog.vertices.shape) * h / np.sqrt(3), ball_v])
    f = np.vstack([dog.faces[~near], ball_keep + dog.n_vertices])
    used = np.unique(f)
    remap = np.full(len(v), -1)
    remap[used] = np.arange(len(used))
    return lbo.Mesh(v[used], remap[f])


FAMILY = {
    "bumpy sphere": lambda: shapes.bumpy_sphere(5),
    "disk (boundary)": lambda: shapes.disk(n_rings=58),
    "torus (genus 1)": lambda: shapes.torus(1.0, 0.4, n_major=160, n_minor=64),
    "dog (thin legs)": lambda: lbo.creature("dog", n_vertices=10_000),
    "thin ellipsoid": lambda: shapes.ellipsoid(1.0, 0.3, 0.1, subdivisions=5),
    "scan proxy": scan_proxy,
}


# Shapes no default was chosen on: the check that what was tuned on FAMILY carries over.
HELD_OUT = {
    "horse": lambda: lbo.creature("horse", n_vertices=10_000),
    "horse galloping": lambda: lbo.creature("horse", pose="galloping", n_vertices=10_000),
    "dog sitting": lambda: lbo.creature("dog", pose="sitting", n_vertices=10_000),
    "icosphere": lambda: shapes.icosphere(5),
    "rectangle": lambda: shapes.rectangle(2.0, 1.0, 140, 70),
    "jittered torus": lambda: shapes.jittered_torus(60, 0.3)[0],
    "dog 15.5k": lambda: lbo.creature("dog", n_vertices=15_000),
}


def _in_new_interpreter(shape: str, solver: str, k: int) -> float:
    """Wall time of ``solver`` on FAMILY[shape] or HELD_OUT[shape] in a new Python process (after a warm-up call on 2.5k vertices)."""
    script = (
        "import sys, time; sys.path.insert(0, 'benchmarks'); import eigen as b; "
        f"fn = getattr(b, {solver!r}); fn(b.mesh_for('warm-up'), {k}); m = {{**b.FAMILY, **b.HELD_OUT}}[{shape!r}](); time.sleep(0.25); "
        f"t = time.perf_counter(); fn(m, {k}); print(time.perf_counter() - t)"
    )
    root = Path(__file__).resolve().parents[1]
    out = subprocess.run([sys.executable, "-c", script], cwd=root, capture_output=True, text=True, check=True)
    return float(out.stdout.split()[-1])


def family(k: int = 100, goal: float = 1.5, *, interpreters: bool = False, repeats: int = 3) -> None:
    """plain / ours on the six 10k-vertex shapes of FAMILY, interleaved, best of ``repeats`` each.

    Each call runs in a forked child (:func:`_measure.measure`), or with ``interpreters`` in a new
    Python process: slower to run, and free of anything a fork leaves behind.
    """
    for fn in (ours, plain):
        fn(mesh_for("warm-up"), k)
    print(f"{'shape':>18}{'vertices':>9}{'pieces':>7}{'boundary':>9}{'ours s':>8}{'plain s':>8}{'plain/ours':>11}  goal")
    worst = np.inf
    for name, make in FAMILY.items():
        mesh = make()
        times = {"ours": [], "plain": []}
        for _ in range(repeats):
            for solver, fn in (("ours", ours), ("plain", plain)):
                times[solver].append(_in_new_interpreter(name, solver, k) if interpreters else measure(fn, mesh, k)[0])
        t_ours, t_plain = min(times["ours"]), min(times["plain"])
        worst = min(worst, t_plain / t_ours)
        print(
            f"{name:>18}{mesh.n_vertices:>9}{mesh.n_components:>7}{len(mesh.boundary_edges):>9}"
            f"{t_ours:>8.2f}{t_plain:>8.2f}{t_plain / t_ours:>11.2f}  {'met' if t_plain / t_ours >= goal else 'MISSED'}"
        )
    where = "new interpreters" if interpreters else "forked processes"
    print(f"k = {k}; wall time of operators + eigensolver, best of {repeats} {where}, ours and plain alternating.")
    print(f"smallest plain/ours over the family: {worst:.2f} (goal >= {goal})")


def _shift(A) -> float:
    return 1e-2 * 4.0 * np.pi / float(A.sum())  # the scale-aware shift eigenbasis uses


def ours(m: lbo.Mesh, k: int) -> float:
    return float(lbo.eigenbasis(m, k).values[-1])


def plain(m: lbo.Mesh, k: int) -> float:
    W, A = lbo.stiffness_matrix(m), lbo.mass_matrix(m)
    return float(np.max(spla.eigsh(W, k=k, M=A, sigma=-_shift(A), which="LM")[0]))


def lapy(m: lbo.Mesh, k: int) -> float:
    from lapy import Solver, TriaMesh

    solver = Solver(TriaMesh(m.vertices, m.faces), lump=True)
    return float(np.max(solver.eigs(k=k)[0]))


def robust(m: lbo.Mesh, k: int) -> float:
    import robust_laplacian

    L, M = robust_laplacian.mesh_laplacian(np.asarray(m.vertices), np.asarray(m.faces))
    return float(np.max(spla.eigsh(L, k=k, M=M, sigma=-_shift(M), which="LM")[0]))


def main() -> None:
    if "--family" in sys.argv or "--held-out" in sys.argv:
        if "--held-out" in sys.argv:
            FAMILY.clear()
            FAMILY.update(HELD_OUT)
        family(interpreters="--interpreters" in sys.argv, repeats=5 if "--interpreters" in sys.argv else 3)
        return
    cases = QUICK if "--quick" in sys.argv else CASES
    solvers = {"ours": ours, "plain": plain, "lapy": lapy, "robust": robust}
    # Every solver runs once here, on 2.5k vertices, before any measurement: the measured
    # children are forked from this process, so none of them pays for importing its modules
    # (ours imports its solver lazily, 0.05 s; SciPy's ARPACK is imported above).
    for fn in solvers.values():
        fn(mesh_for("warm-up"), 100)
    head = "".join(f"{name + ' s':>10}{'MiB':>6}" for name in solvers)
    print(f"{'mesh':>13}{'vertices':>9}{'k':>5} |{head} | {'plain/ours':>10}{'lapy/ours':>10}{'robust/ours':>12}{'lam_k agree':>12}")
    goals = {("10k", 100): 1.5, ("50k", 300): 3.0}
    summary = []
    for size, k in cases:
        # The mesh is built here, untouched (nothing is cached on it), and each forked child
        # starts from it: what is timed is operators + eigensolver, as printed below.
        mesh = mesh_for(size)
        n = mesh.n_vertices
        # Small cases take under a second and jitter: the best of three fresh runs each.
        repeat = 3 if n < 20_000 else 1
        results = {name: min((measure(fn, mesh, k) for _ in range(repeat)), key=lambda r: r[0]) for name, fn in solvers.items()}
        cells = "".join(f"{t:>10.2f}{dm:>6.0f}" for t, _, dm, _ in results.values())
        t = {name: r[0] for name, r in results.items()}
        agree = abs(results["ours"][3] / results["plain"][3] - 1)
        print(
            f"{SIZES[size][0]:>13}{n:>9}{k:>5} |{cells} | {t['plain'] / t['ours']:>10.2f}{t['lapy'] / t['ours']:>10.2f}"
            f"{t['robust'] / t['ours']:>12.2f}{agree:>12.1e}"
        )
        if (size, k) in goals:
            summary.append(
                f"{n} vertices, k={k}: plain/ours = {t['plain'] / t['ours']:.2f} (goal >= {goals[size, k]}), "
                f"peak memory ours/plain = {results['ours'][2] / results['plain'][2]:.2f} (goal <= 1)"
            )
    print("s = wall time of operators + eigensolver; MiB = growth of peak RSS during the call (fresh process each).")
    print("lapy uses its own lumped mass and robust its own Laplacian: their lam_k differ by discretisation, not error.")
    print("cases under 20k vertices: best of 3 runs. Each solver ran once before (2.5k vertices), so no child imports modules.")
    for line in summary:
        print(line)


if __name__ == "__main__":
    main()
