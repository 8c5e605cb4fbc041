"""Benchmark: the hand-written readers against meshio and trimesh on the fuzz contract (issue 42, item 8).

Every file of ``tests/test_fuzz_files.py`` (its 21 undamaged bases, their 2,016 seeded damaged
copies, and the issue 41 families: a number moved between vertex lines, data after the last
record, a propertyless PLY element with a huge count) is loaded by

- ``lbo``: ``load_mesh`` (after a refusal of polygons, ``load_mesh(clean=True)``, as its message
  says), or ``load_points`` for the point-cloud files;
- ``meshio``: ``meshio.read(path)`` (polygon cells split into fans of triangles here);
- ``trimesh``: ``trimesh.load(path, process=False)``.

Each loader runs in its own worker process, one file at a time with a 10 s limit, so a segfault or
a hang is recorded and the worker restarted. The outcome is classified against what the contract
fixes for that file:

- the bases, a byte order mark alone, CR or CRLF line ends: must load as the undamaged file;
- an empty file, a number moved between OFF/OBJ/ASCII STL vertex lines, data after the records of
  a counted format, a cut counted file, a propertyless element in ASCII PLY, a degree sign inside a
  number: must be refused (loading the intact data all the same is counted as "tolerated");
- a cut OBJ/.xyz/.csv/.txt file: may load the lines before the cut;
- any other damage (flipped bytes, changed digits, replaced numbers or counts, edited lines, two
  mutations ...): the contract fixes no answer, so the loaded arrays are checked for NaN/inf,
  indices out of range and emptiness, and otherwise only compared with ``lbo``'s result.

"Correct" means the same vertices to round-off (1e-12 of the coordinate scale, 2e-7 for float32
files) and the same faces in the same order; STL has no shared vertices, so STL results are compared
as triangle soups (the corners of each face, in file order). A clean error is ``ValueError`` (and
``MeshError``, a subclass) or the library's own read error (``meshio.ReadError``); any other
exception type is "unclean". A format a library does not read at all is "unsupported".

Then the time to load 100k-vertex files written by ``save_mesh`` (``shapes.scan_like``), best of
three, in this process, with the ratio to ``load_mesh``. meshio and trimesh are not dependencies of
the project: install them outside the venv (``.venv/bin/python -m pip install --target /tmp/iolibs
meshio trimesh``) and pass ``--libs /tmp/iolibs``; without them their columns are skipped. Run from
the repository root:

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/io_libraries.py --libs /tmp/iolibs

Options: ``--libs DIR`` (appended to ``sys.path``), ``--sample N`` (every N-th damaged file only),
``--no-timing``, ``--examples K`` (list K examples of each wrong answer). Seeded, no network.
The last recorded run and the decision: ``benchmarks/results/io-libraries.md``.
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import platform
import re
import select
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402

TIMEOUT = 10.0  # seconds per file, as in the contract
LIBRARIES = ("lbo", "meshio", "trimesh")
POINT_EXTS = (".xyz", ".csv", ".pts", ".txt")
MESH_EXTS = (".off", ".obj", ".ply", ".stl")


# --- the worker: one library, one file at a time --------------------------------------------------
def _fan(polygons) -> np.ndarray:
    tris = [[p[0], p[i], p[i + 1]] for p in polygons for i in range(1, len(p) - 1)]
    return np.asarray(tris, dtype=np.int64).reshape(-1, 3)


def _load_lbo(path: Path, role: str):
    from lbo_notebooks import MeshError
    from lbo_notebooks.geometry import load_mesh, load_points

    if role == "points":
        return load_points(path).points, None
    try:
        mesh = load_mesh(path)
    except MeshError as exc:
        if "more than three corners" not in str(exc):
            raise
        mesh = load_mesh(path, clean=True)
    return mesh.vertices, mesh.faces


def _load_meshio(path: Path, role: str):
    import meshio

    m = meshio.read(str(path))
    blocks = []
    for block in m.cells:
        if block.type == "triangle":
            blocks.append(np.asarray(block.data, dtype=np.int64).reshape(-1, 3))
        elif block.type == "quad" or block.type.startswith("polygon"):
            blocks.append(_fan(np.asarray(block.data).tolist()))
    faces = np.vstack(blocks) if blocks else None
    return np.asarray(m.points, dtype=np.float64), faces


def _load_trimesh(path: Path, role: str):
    import trimesh

    out = trimesh.load(str(path), process=False)
    if isinstance(out, trimesh.Scene):
        geoms = list(out.geometry.values())
        if not geoms:
            return np.zeros((0, 3)), None
        out = geoms[0] if len(geoms) == 1 else trimesh.util.concatenate(geoms)
    faces = getattr(out, "faces", None)
    faces = None if faces is None or len(faces) == 0 else np.asarray(faces, dtype=np.int64)
    return np.asarray(out.vertices, dtype=np.float64), faces


def _clean_errors(lib: str) -> tuple[type, ...]:
    if lib == "meshio":
        import meshio

        return (ValueError, meshio.ReadError)
    return (ValueError,)


def worker(lib: str) -> None:
    """Read JSON requests on stdin, answer one JSON line each on the original stdout."""
    out = os.fdopen(os.dup(1), "w")
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)  # whatever a library prints must not corrupt the answers
    os.dup2(devnull, 2)
    load = {"lbo": _load_lbo, "meshio": _load_meshio, "trimesh": _load_trimesh}[lib]
    clean = _clean_errors(lib)
    import logging

    logging.disable(logging.CRITICAL)
    warnings.simplefilter("ignore")
    for line in sys.stdin:
        req = json.loads(line)
        start = time.perf_counter()
        try:
            v, f = load(Path(req["path"]), req["role"])
            np.savez(req["out"], v=v, f=np.zeros((0, 3), np.int64) if f is None else f, has_f=f is not None)
            answer = {"status": "ok"}
        except clean as exc:
            answer = {"status": "error", "type": type(exc).__name__, "msg": str(exc)[:200]}
        except BaseException as exc:  # noqa: BLE001 -- the point of the benchmark
            answer = {"status": "unclean", "type": type(exc).__name__, "msg": str(exc)[:200]}
        answer["seconds"] = time.perf_counter() - start
        out.write(json.dumps(answer) + "\n")
        out.flush()


class Worker:
    """A worker process for one library, restarted after it dies or hangs."""

    def __init__(self, lib: str, libs_dir: str | None):
        self.lib, self.libs_dir, self.proc = lib, libs_dir, None
        self.restarts = 0

    def _start(self) -> None:
        cmd = [sys.executable, str(Path(__file__).resolve()), "--worker", self.lib]
        if self.libs_dir:
            cmd += ["--libs", self.libs_dir]
        self.proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, cwd=ROOT,
                                     env={**os.environ, "OPENBLAS_NUM_THREADS": "1"})

    def ask(self, path: Path, role: str, out: Path) -> dict:
        if self.proc is None or self.proc.poll() is not None:
            self._start()
        self.proc.stdin.write(json.dumps({"path": str(path), "role": role, "out": str(out)}) + "\n")
        self.proc.stdin.flush()
        ready, _, _ = select.select([self.proc.stdout], [], [], TIMEOUT + (30 if self.restarts == 0 else 10))
        line = self.proc.stdout.readline() if ready else ""
        if ready and line:
            answer = json.loads(line)
            if answer["seconds"] > TIMEOUT:
                answer = {"status": "hung", "type": f"took {answer['seconds']:.1f} s", "msg": ""}
            return answer
        if not ready:  # a hang: kill it
            self.proc.kill()
            self.proc.wait()
            self.proc, self.restarts = None, self.restarts + 1
            return {"status": "hung", "type": f"no answer in {TIMEOUT:.0f} s", "msg": ""}
        code = self.proc.wait()
        self.proc, self.restarts = None, self.restarts + 1
        return {"status": "died", "type": f"exit code {code}", "msg": ""}

    def close(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            self.proc.stdin.close()
            self.proc.wait(timeout=30)


# --- the corpus and what the contract expects of each file ---------------------------------------
def _expected_bases():
    """The arrays each undamaged base holds, from the shapes the test writes (not from any reader)."""
    from lbo_notebooks import shapes
    from tests.test_fuzz_files import _grid_of_quads, _mixed_faces

    sphere, disk = shapes.icosphere(1), shapes.disk(n_rings=3)
    grid_v, quads = _grid_of_quads()
    exp = {}
    for name in ("sphere.off", "sphere.obj", "sphere.ply", "sphere.stl", "sphere_binary.ply", "sphere_binary.stl",
                 "sphere_bom.ply", "sphere_bom.stl"):
        exp[name] = ("mesh", sphere.vertices, sphere.faces)
    exp["disk.obj"] = ("mesh", disk.vertices, disk.faces)
    for name in ("quads.off", "quads.obj", "quads.ply"):
        exp[name] = ("mesh", grid_v, _fan(quads))
    for name in ("quads_binary_le.ply", "quads_binary_be.ply"):
        exp[name] = ("mesh", grid_v, _fan(_mixed_faces(quads)))
    for name in ("cloud.csv", "cloud.pts", "cloud.txt", "cloud.xyz", "cloud_binary.ply", "cloud_face0.ply"):
        exp[name] = ("points", sphere.vertices, None)
    exp["cloud_eu.csv"] = ("points", np.vstack([[0.5, 1.5, 2.5], sphere.vertices]), None)
    return exp


def _expectation(base: str, data: bytes, label: str, damaged: bytes, truncated: bool) -> str:
    """'whole', 'refuse', 'prefix' (an uncounted file cut at a line end) or 'open' (the contract fixes nothing)."""
    from tests.test_fuzz_files import BOM, SHIFT_BASES, UNCOUNTED

    ext = Path(base).suffix
    binary = b"format binary" in data[:60] or base == "sphere_binary.stl"
    first = re.match(r"[a-z_]+?(?=\d)", label).group()
    if "+" in label:
        return "open"
    if truncated:
        if ext in UNCOUNTED:
            return "prefix" if damaged.endswith((b"\n", b"\r")) or not damaged.strip() else "open"
        return "refuse"
    if first == "empty":
        return "refuse"
    if (first == "bom" or (first == "reencode" and damaged == BOM + data)) and data.startswith(BOM):
        return "open"  # two byte order marks: the contract says nothing
    if first == "bom" or (first == "reencode" and damaged == BOM + data):
        return "refuse" if base == "sphere_binary.stl" else "whole"
    if first == "reencode":
        if damaged in (data.replace(b"\n", b"\r\n"), data.replace(b"\n", b"\r")):
            return "whole"
        if "\u00b0".encode() in damaged and "\u00b0".encode() not in data:
            return "refuse"
        return "open"  # UTF-16
    if first == "shift_number" and base in SHIFT_BASES:
        return "refuse"
    if first == "trailing_data" and (ext in (".off", ".ply", ".pts") or base == "sphere_binary.stl"):
        return "refuse"
    if first == "propertyless_element" and ext == ".ply":
        return "whole" if binary else "refuse"
    return "open"


def corpus(folder: Path):
    """(file name, base, expectation) for every file, written into ``folder``."""
    from tests import test_fuzz_files as fz

    (folder / "_bases").mkdir()
    bases = fz.base_files(folder / "_bases")
    assert sorted(bases) == fz.BASE_NAMES
    files = []
    for index, name in enumerate(fz.BASE_NAMES):
        data = bases[name]
        (folder / name).write_bytes(data)
        files.append((name, name, "whole", "base"))
        for mutant, damaged, truncated in fz.mutants(name, data, index):
            (folder / mutant).write_bytes(damaged)
            files.append((mutant, name, _expectation(name, data, mutant[: -len(name) - 1], damaged, truncated), "fuzz"))
    families = (  # issue 41 (b) and (c): (prefix, bases, stream, copies per base, damage)
        ("shift", fz.SHIFT_BASES, 2, fz.SHIFTS_PER_BASE, fz._shift_a_number),
        ("trailing", fz.TRAILING_BASES, 3, fz.TRAILERS_PER_BASE, fz._append_trailing_data),
    )
    for prefix, family, stream, copies, damage in families:
        for base in family:
            rng = np.random.default_rng([fz.SEED, 41, stream, family.index(base)])
            for k in range(copies):
                name = f"{prefix}{k}_{base}"
                (folder / name).write_bytes(damage(bases[base], base, rng)[0])
                files.append((name, base, "refuse", "issue 41"))
    for base in fz.PLY_BASES:  # issue 41 (a)
        rng = np.random.default_rng([fz.SEED, 41, 1, fz.PLY_BASES.index(base)])
        binary = b"format binary" in bases[base][:60]
        for k in range(6):
            name = f"junk{k}_{base}"
            (folder / name).write_bytes(fz._insert_propertyless_element(bases[base], rng)[0])
            files.append((name, base, "whole" if binary else "refuse", "issue 41"))
    return files


# --- classification -------------------------------------------------------------------------------
def _canonical_faces(f: np.ndarray) -> np.ndarray:
    """Each face rotated to start at its smallest index, rows sorted: the face set, order-free."""
    if len(f) == 0:
        return f
    rolled = np.array([np.roll(row, -int(np.argmin(row))) for row in f])
    return rolled[np.lexsort(rolled.T[::-1])]


def _same(got, want, stl: bool, tol: float) -> str:
    """'same', 'reordered' (same face set, other order), 'prefix' or 'different'."""
    (v, f), (wv, wf) = got, want
    atol = tol * max(1.0, float(np.abs(wv).max()) if len(wv) else 1.0)
    if wf is None:  # points
        if v.shape == wv.shape and np.allclose(v, wv, rtol=0, atol=atol):
            return "same"
        if 0 < len(v) < len(wv) and np.allclose(v, wv[: len(v)], rtol=0, atol=atol):
            return "prefix"
        return "different"
    if f is None:
        return "different"
    if stl:  # a triangle soup
        s, ws = v[f], wv[wf]
        if s.shape == ws.shape and np.allclose(s, ws, rtol=0, atol=atol):
            return "same"
        if 0 < len(s) < len(ws) and np.allclose(s, ws[: len(s)], rtol=0, atol=atol):
            return "prefix"
        return "different"
    if v.shape == wv.shape and np.allclose(v, wv, rtol=0, atol=atol):
        if f.shape == wf.shape and np.array_equal(f, wf):
            return "same"
        if f.shape == wf.shape and np.array_equal(_canonical_faces(f), _canonical_faces(wf)):
            return "reordered"
        return "different"
    n = len(v)
    if 0 < n < len(wv) and np.allclose(v, wv[:n], rtol=0, atol=atol):
        return "prefix"
    return "different"


OUTCOMES = ("correct", "faces reordered", "clean error", "tolerated", "refused valid", "wrong answer",
            "unclean exception", "died or hung", "unsupported")
OPEN_OUTCOMES = ("agrees with lbo", "loads, lbo refuses", "refuses, lbo loads", "differs from lbo",
                 "wrong answer", "unclean exception", "died or hung", "unsupported")


def _sanity(v: np.ndarray, f: np.ndarray | None, role: str) -> str | None:
    """Why a loaded result is wrong whatever the file held: NaN/inf, bad indices, nothing at all."""
    if len(v) == 0:
        return "empty"
    if v.ndim != 2 or v.shape[1] != 3:
        return "not 3D"
    if not np.all(np.isfinite(v)):
        return "NaN/inf"
    if f is not None and len(f) and (f.min() < 0 or f.max() >= len(v)):
        return "index out of range"
    if role == "mesh" and f is None:
        return "faces dropped"
    return None


def classify(answer: dict, got, expect: str, want, stl: bool, tol: float, role: str, lbo_got) -> tuple[str, str]:
    """(outcome, detail) of one library on one file."""
    status = answer["status"]
    if status == "unsupported":
        return "unsupported", ""
    if status in ("died", "hung"):
        return "died or hung", answer["type"]
    if status == "unclean":
        return "unclean exception", answer["type"]
    if expect == "open":
        if status == "error":
            return ("agrees with lbo" if lbo_got is None else "refuses, lbo loads"), answer["type"]
        bad = _sanity(*got, role)
        if bad:
            return "wrong answer", bad
        if lbo_got is None:
            return "loads, lbo refuses", ""
        same = _same(got, lbo_got, stl, tol)
        return ("agrees with lbo" if same == "same" else "differs from lbo"), same
    if status == "error":
        return ("refused valid" if expect == "whole" else "clean error"), answer["type"]
    bad = _sanity(*got, role)
    if bad:
        return "wrong answer", bad
    same = _same(got, want, stl, tol)
    if expect == "refuse":
        return ("tolerated", "intact data") if same == "same" else ("wrong answer", f"loaded damage ({same})")
    if same == "same":
        return "correct", ""
    if same == "reordered":
        return "faces reordered", ""
    if expect == "prefix" and same == "prefix":
        return "correct", "lines before the cut"
    return "wrong answer", same


# --- timing ---------------------------------------------------------------------------------------
def timing(libs: list[str]) -> list[str]:
    from _measure import best_time

    from lbo_notebooks import shapes
    from lbo_notebooks.geometry import save_mesh

    mesh = shapes.scan_like()
    folder = Path(tempfile.mkdtemp())
    loaders = {"lbo": _load_lbo, "meshio": _load_meshio, "trimesh": _load_trimesh}
    lines = [f"Load time of a {mesh.n_vertices:,}-vertex, {mesh.n_faces:,}-triangle mesh (`shapes.scan_like()`, "
             "written by `save_mesh`), best of 3, seconds (ratio to `lbo`; `!` = result not correct):", "",
             "| file | MB | " + " | ".join(libs) + " |", "|---|---:|" + "---:|" * len(libs)]
    want = (mesh.vertices, mesh.faces)
    for name, binary in (("ply", True), ("ply", False), ("obj", None), ("off", None), ("stl", True), ("stl", False)):
        path = save_mesh(mesh, folder / f"scan_{'bin' if binary else 'txt'}.{name}", binary=binary)
        cells, t_lbo = [], None
        for lib in libs:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                try:
                    got = loaders[lib](path, "mesh")
                    ok = _same(got, want, name == "stl", 2e-7 if name == "stl" and binary else 1e-12) == "same"
                    t = best_time(lambda: loaders[lib](path, "mesh"), 3)
                except Exception as exc:  # noqa: BLE001
                    cells.append(f"{type(exc).__name__}")
                    continue
            t_lbo = t if lib == "lbo" else t_lbo
            ratio = "" if lib == "lbo" or t_lbo is None else f" ({t / t_lbo:.1f}x)"
            cells.append(f"{t:.3f}{ratio}{'' if ok else ' !'}")
        lines.append(f"| {path.name} | {path.stat().st_size / 1e6:.1f} | " + " | ".join(cells) + " |")
    return lines


# --- main -----------------------------------------------------------------------------------------
def _versions(libs: list[str]) -> str:
    from importlib.metadata import version

    names = ["numpy", "plyfile"] + [lib for lib in libs if lib != "lbo"]
    return ", ".join(f"{n} {version(n)}" for n in names)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--libs", help="a folder with meshio and trimesh, appended to sys.path")
    parser.add_argument("--worker", help=argparse.SUPPRESS)
    parser.add_argument("--sample", type=int, default=1, help="every N-th damaged file only")
    parser.add_argument("--no-timing", action="store_true")
    parser.add_argument("--examples", type=int, default=3)
    args = parser.parse_args()
    if args.libs:
        sys.path.append(args.libs)  # appended: the venv's numpy stays first
    if args.worker:
        return worker(args.worker)

    libs = ["lbo"]
    for lib in ("meshio", "trimesh"):
        try:
            __import__(lib)
            libs.append(lib)
        except ImportError:
            print(f"{lib} is not installed (not a dependency of the project): its columns are skipped; "
                  f"install it with `.venv/bin/python -m pip install --target /tmp/iolibs {lib}` and pass --libs /tmp/iolibs")
    supported = {"lbo": MESH_EXTS + POINT_EXTS}
    if "meshio" in libs:
        supported["meshio"] = MESH_EXTS  # meshio has no reader for .xyz/.csv/.pts/.txt point lists
    if "trimesh" in libs:
        import trimesh

        supported["trimesh"] = tuple(e for e in MESH_EXTS + POINT_EXTS if e[1:] in trimesh.available_formats())

    t0 = time.perf_counter()
    folder = Path(tempfile.mkdtemp(prefix="io_libraries_"))
    files = corpus(folder)
    if args.sample > 1:
        files = [f for k, f in enumerate(files) if f[3] != "fuzz" or k % args.sample == 0]
    expected = _expected_bases()
    workers = {lib: Worker(lib, args.libs) for lib in libs}
    decided = {lib: collections.Counter() for lib in libs}
    opened = {lib: collections.Counter() for lib in libs}
    details = {lib: collections.defaultdict(list) for lib in libs}
    by_expect = collections.Counter(f[2] for f in files)
    try:
        for name, base, expect, family in files:
            path = folder / name
            role, wv, wf = expected[base]
            ext = Path(base).suffix
            stl = ext == ".stl"
            tol = 2e-7 if base in ("sphere_binary.stl", "cloud_binary.ply") else 1e-12
            results = {}
            for lib in libs:
                if ext not in supported[lib]:
                    results[lib] = ({"status": "unsupported"}, None)
                    continue
                out = folder / f"_out_{lib}.npz"
                answer = workers[lib].ask(path, role, out)
                got = None
                if answer["status"] == "ok":
                    z = np.load(out)
                    got = (z["v"], z["f"] if bool(z["has_f"]) else None)
                results[lib] = (answer, got)
            lbo_answer, lbo_got = results["lbo"]
            for lib in libs:
                answer, got = results[lib]
                outcome, detail = classify(answer, got, expect, (wv, wf), stl, tol, role,
                                           lbo_got if lbo_answer["status"] == "ok" else None)
                (opened if expect == "open" else decided)[lib][outcome] += 1
                key = outcome if outcome not in ("correct", "agrees with lbo", "clean error", "unsupported") else None
                if key:
                    details[lib][key].append(f"{name} [{expect}]: {detail} {answer.get('msg', '')[:90]}".strip())
    finally:
        for w in workers.values():
            w.close()
    elapsed = time.perf_counter() - t0

    print(f"# meshio and trimesh against the hand-written readers\n")
    print(f"{time.strftime('%Y-%m-%d')}, {platform.node() or 'machine'}: {os.cpu_count()} cores, Python "
          f"{platform.python_version()}, {_versions(libs)}; {len(files)} files"
          f"{f' (every {args.sample}-th damaged file)' if args.sample > 1 else ''}, classified in {elapsed:.0f} s.\n")
    n_decided = sum(v for k, v in by_expect.items() if k != "open")
    print(f"## Files whose answer the contract fixes ({n_decided}: {by_expect['whole']} must load as the undamaged "
          f"file, {by_expect['refuse']} must be refused, {by_expect['prefix']} may lose whole lines)\n")
    print("| library | " + " | ".join(OUTCOMES) + " |")
    print("|---|" + "---:|" * len(OUTCOMES))
    for lib in libs:
        print(f"| {lib} | " + " | ".join(str(decided[lib][o]) for o in OUTCOMES) + " |")
    print(f"\n## Damage the contract fixes no answer for ({by_expect['open']} files): compared with `lbo`\n")
    print("| library | " + " | ".join(OPEN_OUTCOMES) + " |")
    print("|---|" + "---:|" * len(OPEN_OUTCOMES))
    for lib in libs:
        print(f"| {lib} | " + " | ".join(str(opened[lib][o]) for o in OPEN_OUTCOMES) + " |")
    print("\n## Details (counts by kind, then examples)\n")
    for lib in libs:
        for key, items in sorted(details[lib].items()):
            kinds = collections.Counter(re.sub(r"^\S+ \[\w+\]: ", "", s).split(" ")[0] or "-" for s in items)
            print(f"- {lib}, {key} ({len(items)}): " + ", ".join(f"{k} {n}" for k, n in kinds.most_common(6)))
            for s in items[: args.examples]:
                print(f"  - `{s}`")
    if not args.no_timing:
        print()
        print("\n".join(timing(libs)))


if __name__ == "__main__":
    main()
