"""Spectral MDS against classical MDS: accuracy at 3-12k vertices, time and memory up to 50k.

Part 3 compares all four methods (classical, landmark, spectral, fast classical scaling).

Run from the repository root::

    .venv/bin/python benchmarks/mds.py                    # full run (several minutes)
    .venv/bin/python benchmarks/mds.py --quick            # small sizes only, for a smoke test
    .venv/bin/python benchmarks/mds.py --json lbo_notebooks/recorded/mds.json   # also record results
    .venv/bin/python benchmarks/mds.py --validation --json lbo_notebooks/recorded/mds.json   # held-out shapes
    .venv/bin/python benchmarks/mds.py --speed 5fb7d99 --pairs 4 --json lbo_notebooks/recorded/mds.json
    .venv/bin/python benchmarks/mds.py --resolution --json lbo_notebooks/recorded/mds.json   # paper section 5
    .venv/bin/python benchmarks/mds.py --energies         # Dirichlet vs biharmonic over mu (tuning shapes)
    .venv/bin/python benchmarks/mds.py --smds-tuning      # SMDS over k, q, fields/rows/pairs (tuning shapes)
    .venv/bin/python benchmarks/mds.py --fcs-tuning       # fast classical scaling over q and mu (tuning shapes)

Part 1 (accuracy): on several shapes of 3,000-5,000 vertices, SMDS with its *default* parameters
against classical MDS computed from the same (heat-method) geodesic distances; the Gram error
(``embedding_error.gram_error``: ``||Z Z.T - X X.T||_F / ||X X.T||_F`` of the centred embeddings, X classical)
must be under 1%. Landmark MDS with as many samples is shown beside it.

Part 2 (scaling): a family of deformed tori from 2k to 51k vertices. Every measurement runs in a
fresh subprocess so that its peak resident memory (above the process's baseline after imports and
mesh construction) is its own. Classical MDS is computed the efficient way: all-pairs distances
with one factorisation, then Lanczos for the top three eigenpairs of B only. The speed ratio is
classical time / SMDS time from this one run; the machine is shared, so absolute times are noisy
and the ratios are what to read.

Tuning and validation of the SMDS defaults. The defaults (``mds.SMDS_DEFAULTS``: fields, k = 200,
q = 300, mu = 0.05, biharmonic) were chosen on the tuning shapes of :func:`tuning_shapes` (a
sitting horse of 4,500 vertices, a dog with its head turned of 3,600, a walking dog with legs x1.35
and tail x1.4 of 5,000, a bumpy sphere (seed 3) and a thin torus of about 4,000) and nothing else.
They were then checked on the validation family :data:`VALIDATION`, none of whose shapes was looked
at while choosing.

The recorded runs of the tuning, the validation and the speed-ups: ``benchmarks/results/mds-history.md``.
"""

from __future__ import annotations

import os
import sys

# BLAS threads must be fixed before numpy is imported; children inherit the environment. On a
# shared, oversubscribed machine multi-threaded OpenBLAS spins and can be 50x slower than one thread.
if "--blas-threads" in sys.argv:
    _threads = sys.argv[sys.argv.index("--blas-threads") + 1]
    for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ[_var] = _threads

import argparse
import json
import subprocess
import time
from pathlib import Path

import numpy as np

from lbo_notebooks import Mesh, shapes
try:
    from lbo_notebooks.analyses import gram_error, procrustes_error
    from lbo_notebooks.analyses import FCS_DEFAULTS, fast_classical_scaling
except ImportError:  # --speed imports this file beside an older tree, where these lived in mds
    from lbo_notebooks.analyses import FCS_DEFAULTS, fast_classical_scaling, gram_error, procrustes_error
from lbo_notebooks.analyses import SMDS_DEFAULTS, classical_mds, landmark_mds, spectral_mds


# --- shapes ------------------------------------------------------------------------------------
def deformed_torus(n_vertices: int) -> Mesh:
    """A torus whose tube thickness varies around the ring, stretched: no symmetry left.

    The grid has ``n_major ~ 2.5 n_minor`` so that triangles are near-equilateral.
    """
    nv = max(8, int(round(np.sqrt(n_vertices / 2.5))))
    nu = max(8, int(round(n_vertices / nv)))
    base = shapes.torus(1.0, 0.4, nu, nv)
    u = 2 * np.pi * np.repeat(np.arange(nu), nv) / nu
    w = 2 * np.pi * np.tile(np.arange(nv), nu) / nv
    r = 0.4 * (1.0 + 0.35 * np.cos(u) + 0.1 * np.sin(2 * u))
    verts = np.column_stack([(1.0 + r * np.cos(w)) * np.cos(u), (1.0 + r * np.cos(w)) * np.sin(u), r * np.sin(w)])
    return Mesh(verts * [1.3, 1.0, 0.9], base.faces)


def remeshed(mesh: Mesh, n_vertices: int) -> Mesh:
    """``mesh`` remeshed isotropically (gpytoolbox.remesh_botsch) to about ``n_vertices``."""
    import gpytoolbox as gpy

    # An equilateral closed mesh has about 2 faces per vertex of area sqrt(3)/4 h^2 each.
    h = np.sqrt(mesh.area / (2 * n_vertices) * 4 / np.sqrt(3))
    V, F = gpy.remesh_botsch(np.array(mesh.vertices), np.array(mesh.faces), i=10, h=h, project=True)
    return Mesh(V, F)


def accuracy_shapes(quick: bool) -> dict[str, Mesh]:
    n = 1500 if quick else 4000
    out = {
        "bumpy sphere": remeshed(shapes.bumpy_sphere(5), n),
        "ellipsoid 1.6:1:0.6": remeshed(shapes.ellipsoid(1.6, 1.0, 0.6, subdivisions=5), n),
        "deformed torus": deformed_torus(n),
    }
    try:  # the four-legged creatures, where that module exists
        from lbo_notebooks.shapes import creature

        for species in ("dog", "horse"):
            out[species] = creature(species, n_vertices=n)
    except Exception as exc:  # noqa: BLE001 - report and go on with the other shapes
        print(f"(creatures skipped: {type(exc).__name__}: {exc})")
    return out


# --- the validation family: shapes none of which was used to choose the SMDS defaults ------------
def _largest_component(V: np.ndarray, F: np.ndarray) -> Mesh:
    """The largest edge-connected piece of the faces ``F``, its unused vertices dropped."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import connected_components

    n = len(V)
    e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
    _, labels = connected_components(sp.coo_matrix((np.ones(len(e)), (e[:, 0], e[:, 1])), shape=(n, n)), directed=False)
    used = np.zeros(n, dtype=bool)
    used[F.ravel()] = True
    F = F[labels[F[:, 0]] == np.bincount(labels[used]).argmax()]
    used = np.unique(F)
    index = np.full(n, -1)
    index[used] = np.arange(used.size)
    return Mesh(V[used], index[F])


def with_holes(mesh: Mesh, centres: np.ndarray, radius: float) -> Mesh:
    """``mesh`` without the faces within ``radius`` of any of ``centres``: holes, as in a scan."""
    c = mesh.vertices[mesh.faces].mean(axis=1)
    d = np.min(np.linalg.norm(c[:, None, :] - np.asarray(centres)[None], axis=2), axis=1)
    return _largest_component(np.array(mesh.vertices), np.array(mesh.faces)[d > radius])


def double_torus(n_vertices: int) -> Mesh:
    """A genus-2 surface: the zero set of a smooth implicit function, marched and remeshed."""
    import gpytoolbox as gpy
    from skimage.measure import marching_cubes

    g = np.linspace(-1.7, 1.7, 120)
    step = np.array([1.0, 0.7, 0.5]) * (g[1] - g[0])
    x, y, z = np.meshgrid(g, 0.7 * g, 0.5 * g, indexing="ij")
    f = (((x - 0.6) ** 2 + y**2) * ((x + 0.6) ** 2 + y**2) - 0.35) ** 2 + (2.2 * z) ** 2 - 0.06
    V, F, _, _ = marching_cubes(f, 0.0, spacing=tuple(step))
    marched = Mesh(V + g[0] * np.array([1.0, 0.7, 0.5]), F[:, ::-1])
    h = np.sqrt(marched.area / (2 * n_vertices) * 4 / np.sqrt(3))
    V2, F2 = gpy.remesh_botsch(np.array(marched.vertices), np.array(marched.faces), i=10, h=h, project=True)
    return _largest_component(V2, F2)


def wavy_sheet(n_vertices: int) -> Mesh:
    """An open 2 x 1 sheet with one boundary loop, waved and sheared (a height field)."""
    ny = int(round(np.sqrt(n_vertices / 2)))
    nx = int(round(n_vertices / ny))
    r = shapes.rectangle(2.0, 1.0, nx - 1, ny - 1)
    x, y = r.vertices[:, 0], r.vertices[:, 1]
    return Mesh(np.column_stack([x, y, 0.25 * np.sin(2.5 * x) * np.cos(3 * y) + 0.15 * x * y]), r.faces)


def saddle_disk(n_vertices: int) -> Mesh:
    """A disk (one boundary circle) bent into a saddle, with a bump."""
    d = shapes.disk(1.0, int(round(np.sqrt(n_vertices / 3))))
    x, y = d.vertices[:, 0], d.vertices[:, 1]
    z = 0.35 * (x**2 - y**2) + 0.3 * np.exp(-((x - 0.3) ** 2 + y**2) / 0.1)
    return Mesh(np.column_stack([x, y, z]), d.faces)


def holed_horse(n_vertices: int) -> Mesh:
    """A walking horse with three holes (a hoof, the muzzle, the belly): boundaries and thin legs."""
    from lbo_notebooks.shapes import creature

    horse = creature("horse", "walking", n_vertices=n_vertices)
    V = horse.vertices
    return with_holes(horse, [V[np.argmin(V[:, 2])], V[np.argmax(V[:, 0])], V.mean(axis=0) - [0.0, 0.0, 0.12]], 0.08)


def _creature(species: str, pose: str, parts: dict | None = None):
    from lbo_notebooks.shapes import creature

    return lambda n: creature(species, pose, parts, n_vertices=n)


#: The validation family of the SMDS defaults: (builder, description). None of these shapes was
#: used to choose the defaults (the tuning shapes are :func:`tuning_shapes`; poses, parts, sizes
#: and species combinations differ from every tuning creature).
VALIDATION: dict[str, tuple] = {
    "horse galloping": (_creature("horse", "galloping"), 9000, "closed, genus 0, thin legs"),
    "dog tail raised": (_creature("dog", "tail_raised"), 3000, "closed, genus 0, thin tail"),
    "dog sitting, long ears+tail": (_creature("dog", "sitting", {"ears": 1.5, "tail": 1.6}), 7000, "closed, genus 0, thin parts"),
    "horse standing, long neck+legs": (_creature("horse", "standing", {"neck": 1.3, "legs": 1.25}), 5500, "closed, genus 0, thin legs"),
    "dog walking, 12k": (_creature("dog", "walking"), 12000, "closed, genus 0"),
    "horse with 3 holes": (holed_horse, 6000, "3 boundary loops, thin legs"),
    "deformed torus": (deformed_torus, 5000, "closed, genus 1"),
    "double torus": (double_torus, 5000, "closed, genus 2"),
    "wavy sheet": (wavy_sheet, 4000, "1 boundary loop"),
    "saddle disk": (saddle_disk, 4500, "1 boundary loop"),
    "ellipsoid 1.6:1:0.6": (lambda n: remeshed(shapes.ellipsoid(1.6, 1.0, 0.6, subdivisions=5), n), 3500, "closed, genus 0, smooth"),
    "bumpy sphere, seed 0": (lambda n: remeshed(shapes.bumpy_sphere(5), n), 4000, "closed, genus 0"),
}

#: The defaults before the held-out validation (commit 5fb7d99): projected rows, k = q = 300.
OLD_DEFAULTS = {"k": 300, "n_samples": 300, "sampled": "rows"}


def part_validation(quick: bool, names: list[str] | None = None) -> list[dict]:
    """SMDS with today's defaults (and with the previous ones) against classical MDS on the validation family."""
    print(f"\nValidation family: SMDS defaults {SMDS_DEFAULTS} (and the previous {OLD_DEFAULTS}) against classical "
          f"MDS from the same heat-method distances")
    print(f"{'shape':32s} {'n':>6s} {'topology':30s} {'Gram err':>9s} {'previous':>9s} {'gap':>6s}  verdict")
    rows = []
    for name, (build, size, topology) in VALIDATION.items():
        if names and name not in names:
            continue
        mesh = build(int(size * (0.4 if quick else 1.0)))
        X = classical_mds(mesh, progress=False)
        Z, info = spectral_mds(mesh, return_details=True, progress=False)
        old = spectral_mds(mesh, progress=False, **OLD_DEFAULTS)
        row = {"shape": name, "n": mesh.n_vertices, "topology": topology, "euler": mesh.euler_characteristic,
               "boundary_edges": int(len(mesh.boundary_edges)), "gram_error": gram_error(Z, X),
               "previous_gram_error": gram_error(old, X), "eigengap": info["eigengap"]}
        row["pass"] = row["gram_error"] <= 0.01
        rows.append(row)
        print(f"{name:32s} {row['n']:6d} {topology:30s} {row['gram_error']:9.4f} {row['previous_gram_error']:9.4f} "
              f"{row['eigengap']:6.2f}  {'PASS' if row['pass'] else 'FAIL'} (<= 0.01)", flush=True)
    if rows:
        print(f"largest Gram error: {max(r['gram_error'] for r in rows):.4f} (previous defaults: "
              f"{max(r['previous_gram_error'] for r in rows):.4f})")
    return rows


def lean_classical_mds(mesh: Mesh, dim: int = 3, block: int = 1024) -> np.ndarray:
    """Classical MDS on all heat-method geodesic distances in ``n^2`` float32 numbers (4 bytes each).

    ``classical_mds`` holds two ``n x n`` float64 matrices (36 GB at 48k vertices); this reference
    keeps only the squared distances, symmetrised, in float32 (9 GB at 48k), and finds the top
    ``dim`` eigenpairs of ``B = -1/2 J D2 J`` by Lanczos on products with it. Rounding ``D2`` to
    float32 changes each entry by at most 6e-8 of itself, and float32 products over ``n`` terms
    err by about ``sqrt(n)`` times that: some 1e-5 at 48k, three orders below the Gram errors
    measured with it. Checked against ``classical_mds`` where both fit (``--growth`` prints the
    Gram error between the two references at the first size).
    """
    import scipy.sparse.linalg as spla

    from lbo_notebooks.analyses._geodesics import geodesic_solver

    n = mesh.n_vertices
    solver = geodesic_solver(mesh, "heat")
    D2 = np.empty((n, n), dtype=np.float32)
    for start in range(0, n, block):
        rows = solver.distances(np.arange(start, min(n, start + block)), progress=False, memory_budget=float("inf"))
        D2[start : start + rows.shape[0]] = np.square(rows)
    for i in range(0, n, block):  # symmetrise in place, tile pair by tile pair
        for j in range(i, n, block):
            tile = 0.5 * (D2[i : i + block, j : j + block] + D2[j : j + block, i : i + block].T)
            D2[i : i + block, j : j + block] = tile
            D2[j : j + block, i : i + block] = tile.T

    def B_times(x: np.ndarray) -> np.ndarray:  # -1/2 J D2 J x, J = I - 11^T / n: centre, multiply, centre
        x = np.asarray(x, dtype=np.float64).reshape(n, -1)
        xc = x - x.mean(axis=0)
        y = (D2 @ xc.astype(np.float32)).astype(np.float64)
        return (-0.5 * (y - y.mean(axis=0))).reshape(-1) if x.shape[1] == 1 else -0.5 * (y - y.mean(axis=0))

    op = spla.LinearOperator((n, n), matvec=B_times, matmat=B_times, dtype=np.float64)
    vals, vecs = spla.eigsh(op, k=dim, which="LA", v0=np.ones(n) + np.arange(n) / n)
    order = np.argsort(vals)[::-1]
    X = vecs[:, order] * np.sqrt(np.maximum(vals[order], 0.0))
    return X - X.mean(axis=0)


def part_growth(sizes: list[int]) -> list[dict]:
    """The defaults (and the previous ones) on one shape, a walking dog, at growing resolution.

    Where two ``n x n`` float64 matrices do not fit in a third of the memory, the classical
    reference is :func:`lean_classical_mds`; at the first size both are computed and compared.
    """
    from lbo_notebooks.shapes import creature
    from lbo_notebooks.analyses._geodesics import available_memory

    print(f"\nOne shape at growing resolution: walking dog, SMDS defaults {SMDS_DEFAULTS} and the previous {OLD_DEFAULTS}")
    print(f"{'n':>6s} {'Gram err':>9s} {'previous':>9s}  reference")
    rows = []
    for i, size in enumerate(sizes):
        mesh = creature("dog", "walking", n_vertices=size)
        n = mesh.n_vertices
        if 16 * n * n < available_memory() / 3:
            X, reference = classical_mds(mesh, progress=False), "classical_mds"
            if i == 0:
                print(f"   (lean reference against classical_mds at n = {n}: Gram error "
                      f"{gram_error(lean_classical_mds(mesh), X):.1e})", flush=True)
        else:
            X, reference = lean_classical_mds(mesh), "lean (float32 D2)"
        row = {"n": mesh.n_vertices, "gram_error": gram_error(spectral_mds(mesh, progress=False), X),
               "previous_gram_error": gram_error(spectral_mds(mesh, progress=False, **OLD_DEFAULTS), X),
               "reference": reference}
        rows.append(row)
        print(f"{row['n']:6d} {row['gram_error']:9.4f} {row['previous_gram_error']:9.4f}  {reference}", flush=True)
    return rows


# --- paper section 5: higher resolution at the same cost ------------------------------------------
def at_points(mesh: Mesh, values: np.ndarray, points: np.ndarray) -> np.ndarray:
    """``values`` (one row per vertex of ``mesh``) interpolated linearly at the closest points of ``mesh`` to ``points``."""
    import gpytoolbox

    _, face, bary = gpytoolbox.squared_distance(np.asarray(points), np.array(mesh.vertices), np.array(mesh.faces), use_cpp=True)
    return np.einsum("pk,pkc->pc", bary, values[mesh.faces[face]])


def part_resolution(n_ref: int = 12000, n_smds: int = 6000) -> dict:
    """SMDS on a fine mesh against classical MDS on coarser meshes of the same surface, at equal cost.

    The reference is classical MDS on a finer mesh (``n_ref`` vertices) of the walking dog, so that
    neither candidate shares its discretisation. Every embedding is interpolated linearly to the
    reference's vertices (closest point on its own mesh) and compared there by the Gram error.
    Classical MDS runs on isotropic remeshes of the SMDS mesh: at equal memory
    (``2 n_c^2 = n (k + q)`` floats: two n_c x n_c matrices against the n x (k + q) arrays of
    SMDS) and at larger sizes, with their CPU times, so that equal time can be read off too.
    """
    from lbo_notebooks.shapes import creature

    ref = creature("dog", "walking", n_vertices=n_ref)
    cpu = time.process_time()
    X_ref = classical_mds(ref, progress=False)
    print(f"\nResolution at equal cost: reference classical MDS on {ref.n_vertices} vertices "
          f"({time.process_time() - cpu:.1f} s CPU)")
    fine = creature("dog", "walking", n_vertices=n_smds)
    cpu = time.process_time()
    Z = spectral_mds(fine, progress=False)
    smds = {"n": fine.n_vertices, "cpu_seconds": time.process_time() - cpu,
            "gram_error": gram_error(at_points(fine, Z, ref.vertices), X_ref),
            "floats": fine.n_vertices * (SMDS_DEFAULTS["k"] + SMDS_DEFAULTS["n_samples"])}
    print(f"SMDS (defaults) on {smds['n']} vertices: {smds['cpu_seconds']:.1f} s CPU, {smds['floats'] / 1e6:.1f} M floats, "
          f"Gram error {smds['gram_error']:.4f}")
    n_equal = int(round(np.sqrt(smds["floats"] / 2)))
    rows = []
    for factor in (1.0, 1.5, 2.0, 3.0):
        coarse = remeshed(fine, int(factor * n_equal))
        cpu = time.process_time()
        Xc = classical_mds(coarse, progress=False)
        row = {"n": coarse.n_vertices, "cpu_seconds": time.process_time() - cpu, "floats": 2 * coarse.n_vertices**2,
               "gram_error": gram_error(at_points(coarse, Xc, ref.vertices), X_ref)}
        rows.append(row)
        print(f"classical MDS on {row['n']:5d} vertices: {row['cpu_seconds']:6.1f} s CPU, {row['floats'] / 1e6:6.1f} M floats, "
              f"Gram error {row['gram_error']:.4f}", flush=True)
    return {"reference_n": ref.n_vertices, "smds": smds, "classical": rows, "equal_memory_n": n_equal}


# --- end to end at 51k vertices, interleaved against an earlier commit ----------------------------
SPEED_CHILD = """
import sys, time
sys.path[:0] = [sys.argv[1], sys.argv[2]]
import lbo_notebooks as lbo
from lbo_notebooks.analyses import spectral_mds
from mds import deformed_torus
assert lbo.__file__.startswith(sys.argv[1]), lbo.__file__
spectral_mds(lbo.shapes.icosphere(3), k=60, n_samples=60, progress=False)   # warm-up: imports, lazy set-up
mesh = deformed_torus(int(sys.argv[3]))
_ = mesh.edges, mesh.face_areas
cpu, start = time.process_time(), time.perf_counter()
X, info = spectral_mds(mesh, return_details=True, progress=False)
t = info["timings"]
print(time.perf_counter() - start, time.process_time() - cpu, t["eigenbasis"], t["sampling"], t["embedding"])
"""


def part_speed(rev: str, pairs: int, n: int) -> dict:
    """``spectral_mds`` with its defaults on a deformed torus of ``n`` vertices: this tree against ``rev``.

    Each pair runs the old and the new code back to back, each in a fresh process (the old from a
    ``git worktree`` of ``rev``), alternating which goes first; the machine is shared, so only the
    per-pair ratios are compared (their median), not two separate runs.
    """
    import tempfile

    root = Path(__file__).resolve().parents[1]
    results: dict[str, list[list[float]]] = {"old": [], "new": []}
    with tempfile.TemporaryDirectory() as tmp:
        old_tree = Path(tmp) / "old"
        subprocess.run(["git", "-C", str(root), "worktree", "add", "--detach", str(old_tree), rev], check=True, capture_output=True)
        try:
            for i in range(pairs):
                for name in (("old", "new") if i % 2 == 0 else ("new", "old")):
                    tree = old_tree if name == "old" else root
                    out = subprocess.run([sys.executable, "-c", SPEED_CHILD, str(tree), str(root / "benchmarks"), str(n)],
                                         capture_output=True, text=True, check=True)
                    results[name].append([float(v) for v in out.stdout.split()[-5:]])
                    print(f"pair {i + 1} {name}: {results[name][-1][0]:.2f} s wall, {results[name][-1][1]:.2f} s CPU "
                          f"(eigenbasis {results[name][-1][2]:.2f}, sampling {results[name][-1][3]:.2f}, "
                          f"embedding {results[name][-1][4]:.2f})", flush=True)
        finally:
            subprocess.run(["git", "-C", str(root), "worktree", "remove", "--force", str(old_tree)], check=False)
    old, new = np.array(results["old"]), np.array(results["new"])
    ratio = old[:, 0] / new[:, 0]
    cpu_ratio = old[:, 1] / new[:, 1]
    print(f"\nspectral_mds defaults, deformed torus of {n} vertices, {pairs} interleaved pairs (old = {rev}, new = this tree)")
    print(f"{'':5s} {'median s':>9s} {'min s':>7s} {'CPU s':>7s} {'eig s':>7s} {'samp s':>7s} {'emb s':>7s}")
    for name, a in (("old", old), ("new", new)):
        print(f"{name:5s} {np.median(a[:, 0]):9.2f} {a[:, 0].min():7.2f} {np.median(a[:, 1]):7.2f} "
              f"{np.median(a[:, 2]):7.2f} {np.median(a[:, 3]):7.2f} {np.median(a[:, 4]):7.2f}")
    print(f"old/new per pair: wall median {np.median(ratio):.2f} (min {ratio.min():.2f}), CPU median {np.median(cpu_ratio):.2f}")
    return {"rev": rev, "n": n, "pairs": pairs, "old": results["old"], "new": results["new"],
            "ratio_median": float(np.median(ratio)), "cpu_ratio_median": float(np.median(cpu_ratio))}


# --- one measurement in this process -----------------------------------------------------------
def _status_mib(field: str) -> float:
    """A memory field of /proc/self/status (VmRSS, VmHWM) in MiB (Linux)."""
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(field + ":"):
                return int(line.split()[1]) / 1024.0
    raise RuntimeError(f"{field} not found in /proc/self/status")


def _reset_peak() -> None:
    # Writing 5 to clear_refs resets the peak RSS (VmHWM) to the current RSS (Linux >= 4.0).
    # getrusage's ru_maxrss would not do: it survives fork + exec from the parent.
    with open("/proc/self/clear_refs", "w") as fh:
        fh.write("5")


def measure(kind: str, n: int) -> dict:
    mesh = deformed_torus(n)
    _ = mesh.edges, mesh.face_areas  # mesh set-up is not part of either algorithm
    _reset_peak()
    base = _status_mib("VmRSS")
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    out: dict = {"kind": kind, "n": mesh.n_vertices}
    if kind == "smds":
        X, info = spectral_mds(mesh, return_details=True, progress=False)
        out["timings"] = info["timings"]
        out["eigengap"] = info["eigengap"]
    elif kind == "fcs":
        X, info = fast_classical_scaling(mesh, return_details=True, progress=False)
        out["timings"] = info["timings"]
    elif kind == "landmark":
        X = landmark_mds(mesh, n_samples=int(SMDS_DEFAULTS["n_samples"]), progress=False)
    else:
        X = classical_mds(mesh, progress=False)
    out["seconds"] = time.perf_counter() - t0
    # CPU seconds of this process: on a shared machine it estimates the wall time on idle cores.
    out["cpu_seconds"] = time.process_time() - cpu0
    out["peak_mib"] = _status_mib("VmHWM") - base
    np.save(f"/tmp/mds_bench_{kind}_{n}.npy", X)
    return out


def run_child(kind: str, n: int) -> dict:
    res = subprocess.run(
        [sys.executable, __file__, "--measure", kind, str(n)], capture_output=True, text=True, check=False
    )
    if res.returncode != 0:
        return {"kind": kind, "n": n, "error": res.stderr.strip().splitlines()[-1] if res.stderr else "failed"}
    return json.loads(res.stdout.strip().splitlines()[-1])


# --- the two parts ------------------------------------------------------------------------------
def part_accuracy(quick: bool) -> list[dict]:
    print(f"\nPart 1: SMDS defaults {SMDS_DEFAULTS} vs classical MDS, same heat-method distances")
    print(f"{'shape':22s} {'n':>6s} {'Gram err':>9s} {'Procr.':>8s} {'gap':>6s} {'LMDS(300)':>10s} "
          f"{'SMDS s':>7s} {'class. s':>8s}  verdict")
    rows = []
    for name, mesh in accuracy_shapes(quick).items():
        t = time.perf_counter()
        X = classical_mds(mesh, progress=False)
        tc = time.perf_counter() - t
        t = time.perf_counter()
        Z, info = spectral_mds(mesh, return_details=True, progress=False)
        ts = time.perf_counter() - t
        L = landmark_mds(mesh, n_samples=min(300, mesh.n_vertices), progress=False)
        row = {
            "shape": name, "n": mesh.n_vertices, "gram_error": gram_error(Z, X),
            "procrustes_error": procrustes_error(Z, X), "eigengap": info["eigengap"],
            "landmark_gram_error": gram_error(L, X), "smds_seconds": ts, "classical_seconds": tc,
        }
        row["pass"] = row["gram_error"] < 0.01
        rows.append(row)
        print(f"{name:22s} {row['n']:6d} {row['gram_error']:9.4f} {row['procrustes_error']:8.4f} "
              f"{row['eigengap']:6.2f} {row['landmark_gram_error']:10.4f} {ts:7.2f} {tc:8.2f}  "
              f"{'PASS' if row['pass'] else 'FAIL'} (< 0.01)")
    return rows


def tuning_shapes(quick: bool) -> dict[str, Mesh]:
    """Shapes the SMDS defaults were chosen on: none of them is reported by notebooks 09 and 10."""
    from lbo_notebooks.shapes import creature

    scale = 0.4 if quick else 1.0
    return {
        "horse, sitting": creature("horse", "sitting", n_vertices=int(4500 * scale)),
        "dog, head turned": creature("dog", "head_turned", n_vertices=int(3600 * scale)),
        "dog, long legs+tail": creature("dog", "walking", parts={"legs": 1.35, "tail": 1.4}, n_vertices=int(5000 * scale)),
        "bumpy sphere, seed 3": remeshed(shapes.bumpy_sphere(5, n_bumps=11, height=0.45, seed=3), int(4200 * scale)),
        "thin torus": remeshed(shapes.torus(1.0, 0.25, 160, 32), int(3800 * scale)),
    }


def part_energies(quick: bool) -> list[dict]:
    """Gram error of the Dirichlet and biharmonic interpolations over mu, at the default k and q."""
    from lbo_notebooks import eigenbasis
    from lbo_notebooks.analyses import farthest_point_sampling

    mus = (0.002, 0.01, 0.05, 0.2, 1.0)
    print(f"\nInterpolation energy: Gram error vs classical MDS at k = {SMDS_DEFAULTS['k']}, "
          f"q = {SMDS_DEFAULTS['n_samples']} (capped at n), tuning shapes")
    print(f"{'shape':22s} {'n':>6s} {'energy':>11s} " + " ".join(f"mu={mu:<6g}" for mu in mus))
    rows = []
    for name, mesh in tuning_shapes(quick).items():
        X = classical_mds(mesh, progress=False)
        k, q = min(SMDS_DEFAULTS["k"], mesh.n_vertices), min(SMDS_DEFAULTS["n_samples"], mesh.n_vertices)
        spectrum = eigenbasis(mesh, k)
        sampling = farthest_point_sampling(mesh, q, return_distances=True, progress=False, select="graph")  # as spectral_mds
        for energy in ("dirichlet", "biharmonic"):
            errs = [gram_error(spectral_mds(mesh, k=k, n_samples=q, mu=mu, energy=energy, spectrum=spectrum,
                                            sampling=sampling), X) for mu in mus]
            rows.append({"shape": name, "n": mesh.n_vertices, "energy": energy, "mu": list(mus), "gram_error": errs})
            print(f"{name:22s} {mesh.n_vertices:6d} {energy:>11s} " + " ".join(f"{e:9.4f}" for e in errs))
    return rows


def part_smds_tuning(quick: bool) -> list[dict]:
    """Gram error of SMDS over (k, q), interpolating whole sampled rows or the pairs among the samples."""
    from lbo_notebooks import eigenbasis
    from lbo_notebooks.analyses import farthest_point_sampling

    grid = [(400, 800), (400, 400), (300, 600), (300, 400), (300, 300), (250, 400), (250, 300), (200, 400), (200, 300),
            (200, 200), (150, 300)]
    print(f"\nSpectral MDS: Gram error vs classical MDS over (k, q), tuning shapes (defaults {SMDS_DEFAULTS})")
    print(f"{'shape':22s} {'n':>6s} {'sampled':>8s} " + " ".join(f"{f'{k}/{q}':>8s}" for k, q in grid))
    rows = []
    for name, mesh in tuning_shapes(quick).items():
        X = classical_mds(mesh, progress=False)
        cap = [(min(k, mesh.n_vertices), min(q, mesh.n_vertices)) for k, q in grid]
        spectrum = eigenbasis(mesh, max(k for k, _ in cap))
        sampling = farthest_point_sampling(mesh, max(q for _, q in cap), return_distances=True, progress=False, select="graph")
        for sampled in ("fields", "rows", "pairs"):
            errs = [gram_error(spectral_mds(mesh, k=k, n_samples=q, sampled=sampled, spectrum=spectrum, sampling=sampling), X)
                    for k, q in cap]
            rows.append({"shape": name, "n": mesh.n_vertices, "sampled": sampled, "k_q": cap, "gram_error": errs})
            print(f"{name:22s} {mesh.n_vertices:6d} {sampled:>8s} " + " ".join(f"{e:8.4f}" for e in errs))
    for sampled in ("fields", "rows", "pairs"):
        worst = np.max([r["gram_error"] for r in rows if r["sampled"] == sampled], axis=0)
        print(f"{'largest':22s} {'':6s} {sampled:>8s} " + " ".join(f"{e:8.4f}" for e in worst))
    return rows


def part_fcs_tuning(quick: bool) -> list[dict]:
    """Gram error of fast classical scaling over the number of samples and mu, on the tuning shapes."""
    from lbo_notebooks.analyses import farthest_point_sampling

    qs, mus = (50, 100, 150, 200), (1e-4, 1e-3, 1e-2, 1e-1)
    print(f"\nFast classical scaling: Gram error vs classical MDS over q and mu, tuning shapes (defaults {FCS_DEFAULTS})")
    print(f"{'shape':22s} {'n':>6s} {'q':>4s} " + " ".join(f"mu={mu:<7g}" for mu in mus))
    rows = []
    for name, mesh in tuning_shapes(quick).items():
        X = classical_mds(mesh, progress=False)
        sampling = farthest_point_sampling(mesh, max(qs), return_distances=True, progress=False, select="graph")
        for q in qs:
            errs = [gram_error(fast_classical_scaling(mesh, n_samples=q, mu=mu, sampling=sampling), X) for mu in mus]
            rows.append({"shape": name, "n": mesh.n_vertices, "q": q, "mu": list(mus), "gram_error": errs})
            print(f"{name:22s} {mesh.n_vertices:6d} {q:4d} " + " ".join(f"{e:10.4f}" for e in errs))
    return rows


def part_scaling(quick: bool, classical_max: int, sizes: list[int] | None = None) -> list[dict]:
    if sizes is None:
        sizes = [1000, 2000, 4000] if quick else [2000, 4000, 8000, 16000, 32000, 51200]
    print("\nPart 2: time and peak memory (fresh subprocess per run) on deformed tori")
    print("wall seconds (ratio = classical / SMDS), CPU seconds of the process, peak MiB above baseline")
    print(f"{'n':>6s} {'SMDS s':>7s} {'eig s':>6s} {'samp s':>7s} {'emb s':>6s} {'CPU s':>6s} {'SMDS MiB':>9s} "
          f"{'class. s':>8s} {'CPU s':>7s} {'class. MiB':>10s} {'ratio':>6s} {'CPU ratio':>9s} {'Gram err':>9s}")
    rows = []
    for n in sizes:
        s = run_child("smds", n)
        c = run_child("classical", n) if n <= classical_max else {"skipped": True}
        row = {"n": s.get("n", n), "smds": s, "classical": c}
        ratio = c["seconds"] / s["seconds"] if "seconds" in c and "seconds" in s else float("nan")
        row["ratio"] = ratio
        cpu_ratio = c["cpu_seconds"] / s["cpu_seconds"] if "cpu_seconds" in c and "cpu_seconds" in s else float("nan")
        row["cpu_ratio"] = cpu_ratio
        err = float("nan")
        if "seconds" in c and "seconds" in s:
            err = gram_error(np.load(f"/tmp/mds_bench_smds_{n}.npy"), np.load(f"/tmp/mds_bench_classical_{n}.npy"))
        row["gram_error"] = err
        rows.append(row)
        tm = s.get("timings", {})
        cs = (f"{c['seconds']:8.2f} {c['cpu_seconds']:7.2f} {c['peak_mib']:10.0f}" if "seconds" in c
              else f"{'-':>8s} {'-':>7s} {'-':>10s}")
        print(f"{row['n']:6d} {s.get('seconds', float('nan')):7.2f} {tm.get('eigenbasis', float('nan')):6.2f} "
              f"{tm.get('sampling', float('nan')):7.2f} {tm.get('embedding', float('nan')):6.2f} "
              f"{s.get('cpu_seconds', float('nan')):6.2f} "
              f"{s.get('peak_mib', float('nan')):9.0f} {cs} {ratio:6.1f} {cpu_ratio:9.1f} {err:9.4f}"
              + (f"   ({s['error']})" if "error" in s else "") + (f"   ({c['error']})" if "error" in c else ""))
    big = [r for r in rows if r["n"] >= 50000 and "seconds" in r["smds"]]
    if big:
        b = big[0]["smds"]
        print(f"SMDS end to end at {big[0]['n']} vertices: {b['seconds']:.1f} s wall, {b['cpu_seconds']:.1f} s CPU "
              f"(goal <= 10 s on 2 idle cores)")
    at8k = [r for r in rows if 7000 <= r["n"] <= 9000 and np.isfinite(r["ratio"])]
    if at8k:
        print(f"speed ratio classical / SMDS at {at8k[0]['n']} vertices: {at8k[0]['ratio']:.1f}x wall, "
              f"{at8k[0]['cpu_ratio']:.1f}x CPU (an earlier goal, >= 10x, dates from when classical MDS solved one "
              f"heat source at a time)")
    return rows


def part_four(quick: bool, classical_max: int, sizes: list[int] | None = None) -> list[dict]:
    """Classical, landmark, spectral and fast classical scaling side by side, in one run."""
    if sizes is None:
        sizes = [1000, 2000] if quick else [4000, 8000, 51200]
    kinds = ["classical", "landmark", "smds", "fcs"]
    print("\nPart 3: the four methods on deformed tori (fresh subprocess each; Gram error against classical)")
    print(f"{'n':>6s} " + " ".join(f"{k + ' s':>12s} {'MiB':>6s} {'Gram':>7s}" for k in kinds))
    rows = []
    for n in sizes:
        res = {k: run_child(k, n) for k in kinds if k != "classical" or n <= classical_max}
        cells = []
        for k in kinds:
            r = res.get(k, {})
            err = float("nan")
            if "seconds" in r and "seconds" in res.get("classical", {}):
                err = gram_error(np.load(f"/tmp/mds_bench_{k}_{n}.npy"), np.load(f"/tmp/mds_bench_classical_{n}.npy"))
            r["gram_error"] = err
            cells.append(f"{r.get('seconds', float('nan')):12.2f} {r.get('peak_mib', float('nan')):6.0f} {err:7.4f}")
        rows.append({"n": n, **res})
        print(f"{n:6d} " + " ".join(cells))
    big = [r for r in rows if r["n"] >= 50000 and "seconds" in r.get("fcs", {})]
    if big:
        print(f"fast classical scaling end to end at {big[0]['fcs']['n']} vertices: {big[0]['fcs']['seconds']:.1f} s wall "
              f"(goal <= 5 s on 2 idle cores)")
    compared = [r for r in rows if np.isfinite(r.get("fcs", {}).get("gram_error", float("nan")))]
    if compared:
        worst = max(r["fcs"]["gram_error"] for r in compared)
        print(f"fast classical scaling, largest Gram error against classical MDS: {worst:.4f} (goal <= 0.02)")
    return rows


def _record(path: Path | None, key: str, value: object, header: dict) -> None:
    """Store ``value`` under ``key`` (with this run's date, load and defaults) in the JSON file, keeping the rest."""
    if path is None:
        return
    old = json.loads(path.read_text()) if path.exists() else {}
    old[key] = {"date": header["date"], "load_average": max(header["load_average"], os.getloadavg()[0]),
                "cores": header["cores"], "blas_threads": header["blas_threads"], "defaults": SMDS_DEFAULTS, "rows": value}
    path.write_text(json.dumps(old, indent=1, default=float))
    print(f"{key} written to {path}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="small sizes only")
    ap.add_argument("--json", type=Path, help="write the results to this JSON file")
    ap.add_argument("--classical-max", type=int, default=8000, help="largest n for classical MDS")
    ap.add_argument("--skip-accuracy", action="store_true")
    ap.add_argument("--accuracy-only", action="store_true",
                    help="run part 1 only; with --json, keep the scaling rows (and their date and defaults) of the file")
    ap.add_argument("--energies", action="store_true",
                    help="only the table of Gram errors of both interpolation energies over mu (tuning shapes)")
    ap.add_argument("--smds-tuning", action="store_true",
                    help="only the table of SMDS Gram errors over k and q, rows against pairs (tuning shapes)")
    ap.add_argument("--fcs-tuning", action="store_true",
                    help="only the table of fast classical scaling's Gram errors over q and mu (tuning shapes)")
    ap.add_argument("--validation", nargs="*", metavar="SHAPE",
                    help="only the validation-family table (all shapes, or the ones named)")
    ap.add_argument("--growth", type=int, nargs="+", metavar="N",
                    help="only the defaults on a walking dog of these sizes (accuracy against resolution)")
    ap.add_argument("--resolution", action="store_true",
                    help="only SMDS on a fine mesh against classical MDS on coarser ones, against a finer reference")
    ap.add_argument("--speed", metavar="REV", help="only the interleaved end-to-end timing against commit REV")
    ap.add_argument("--pairs", type=int, default=5, help="interleaved pairs of --speed")
    ap.add_argument("--speed-n", type=int, default=51200, help="vertices of the --speed torus")
    ap.add_argument("--sizes", type=int, nargs="+", help="vertex counts of the scaling part")
    ap.add_argument("--merge", action="store_true",
                    help="merge the scaling rows into the existing --json file (same n replaced)")
    ap.add_argument("--blas-threads", type=int, help="BLAS/OpenMP threads for this run and its children")
    ap.add_argument("--measure", nargs=2, metavar=("KIND", "N"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.measure:
        print(json.dumps(measure(args.measure[0], int(args.measure[1]))))
        return
    import platform

    threads = os.environ.get("OPENBLAS_NUM_THREADS", "default")
    print(f"lbo_notebooks MDS benchmark on {platform.node()} ({os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.1f}, BLAS threads {threads}); "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")
    result: dict = {"load_average": os.getloadavg()[0], "cores": os.cpu_count(), "blas_threads": threads,
                    "defaults": SMDS_DEFAULTS, "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}
    if args.validation is not None:
        rows = part_validation(args.quick, args.validation or None)
        _record(args.json, "validation", rows, result)
        return
    if args.growth:
        _record(args.json, "growth", part_growth(args.growth), result)
        return
    if args.resolution:
        _record(args.json, "resolution", part_resolution(), result)
        return
    if args.speed:
        _record(args.json, "speed", part_speed(args.speed, args.pairs, args.speed_n), result)
        return
    if args.energies:
        part_energies(args.quick)
        return
    if args.fcs_tuning:
        part_fcs_tuning(args.quick)
        return
    if args.smds_tuning:
        part_smds_tuning(args.quick)
        return
    if not args.skip_accuracy:
        result["accuracy"] = part_accuracy(args.quick)
    elif args.json and args.json.exists():  # keep the accuracy table of an earlier run
        old = json.loads(args.json.read_text())
        if "accuracy" in old:
            result["accuracy"] = old["accuracy"]
            result["accuracy_recorded"] = old.get("date")
    if args.accuracy_only:
        if args.json and args.json.exists():
            old = json.loads(args.json.read_text())
            for key in ("scaling", "scaling_recorded", "scaling_defaults", "scaling_load_average"):
                if key in old:
                    result[key] = old[key]
            if "scaling" in old and "scaling_recorded" not in old:
                result["scaling_recorded"] = old.get("date")
                result["scaling_defaults"] = old.get("defaults")
                result["scaling_load_average"] = old.get("load_average")
            args.json.write_text(json.dumps(result, indent=1, default=float))
            print(f"results written to {args.json}")
        return
    result["scaling"] = part_scaling(args.quick, args.classical_max, args.sizes)
    result["four_methods"] = part_four(args.quick, args.classical_max, args.sizes)
    result["scaling_recorded"] = result["date"]
    result["scaling_defaults"] = SMDS_DEFAULTS
    result["fcs_defaults"] = FCS_DEFAULTS
    result["scaling_load_average"] = max(result["load_average"], os.getloadavg()[0])
    if args.merge and args.json and args.json.exists():
        old = json.loads(args.json.read_text())
        new_n = {r["n"] for r in result["scaling"]}
        rows = [r for r in old.get("scaling", []) if r["n"] not in new_n] + result["scaling"]
        result["scaling"] = sorted(rows, key=lambda r: r["n"])
        for key in ("date", "load_average"):
            result[key] = f"{old[key]}; {result[key]}" if key == "date" else max(old[key], result[key])
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(result, indent=1, default=float))
        print(f"results written to {args.json}")


if __name__ == "__main__":
    main()
