"""Fuzz test of every file reader (issue 26): over 1,000 damaged files, no crash, no hang, no nonsense.

Small files of every supported format are made here from the package's own shapes (text and
binary PLY, OFF, OBJ, ASCII and binary STL, and the point lists .xyz, .csv, .pts, .txt), then
damaged with a seeded random generator: bytes flipped, inserted or deleted, the file truncated at a
random offset, a digit changed, a number replaced by NaN, inf, an overflowing or a huge value, an
underscore or a decimal, a count or an index made absurd, lines duplicated or dropped, the text
re-encoded (UTF-16, a byte order mark, CR line ends), and empty or blank files. For every file:

- every loader (``load_mesh``, ``load_mesh(clean=True)``, ``load_points``) either returns or raises
  :class:`MeshError` / ``ValueError`` -- nothing else -- and takes less than 10 s;
- whatever loads gets a finite, A-orthonormal spectrum from ``eigenbasis`` (which may also refuse
  it with a ``MeshError`` or ``ValueError``, e.g. a cloud of fewer points than its neighbourhoods);
- a truncated file never loads as something else than the whole file: formats that announce their
  size (OFF, PLY, STL, .pts) are refused wherever they are cut, and the others (OBJ, .xyz, .csv,
  .txt, which have no count to check) can only lose whole lines, never part of a number.

The meshes have 25 to 42 vertices, so the eigenproblems take the dense path; the whole file runs in
well under a minute on one core.
"""

from __future__ import annotations

import re
import struct
import time
import warnings
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest

from lbo_notebooks import Mesh, MeshError, PointCloud, eigenbasis, shapes
from lbo_notebooks.formats import FORMATS, mesh_text
from lbo_notebooks.io import load_mesh, load_points, save_mesh

SEED = 26
MUTANTS_PER_BASE = 72
SLOW_CALL = 10.0  # seconds


# --- the undamaged files ------------------------------------------------------------------------
def _grid_of_quads(n: int = 4) -> tuple[np.ndarray, list[list[int]]]:
    """An (n+1) x (n+1) grid of vertices and its n*n quads (polygons exercise the fan splitting)."""
    x, y = np.meshgrid(np.arange(n + 1.0), np.arange(n + 1.0), indexing="ij")
    v = np.column_stack([x.ravel(), y.ravel(), 0.1 * np.sin(x.ravel() + y.ravel())]) / n
    quads = [[i * (n + 1) + j, (i + 1) * (n + 1) + j, (i + 1) * (n + 1) + j + 1, i * (n + 1) + j + 1]
             for i in range(n) for j in range(n)]
    return v, quads


def _polygon_text(v: np.ndarray, polygons: list[list[int]], ext: str) -> str:
    xyz = ["%.17g %.17g %.17g" % tuple(row) for row in v.tolist()]
    if ext == ".off":
        return f"OFF\n{len(v)} {len(polygons)} 0\n" + "\n".join(xyz + [f"{len(p)} " + " ".join(map(str, p)) for p in polygons]) + "\n"
    if ext == ".obj":  # slash forms and relative (negative) indices, as exporters write them
        faces = ["f " + " ".join(f"{i + 1}/{i + 1}" if k % 2 else str(i - len(v)) for k, i in enumerate(p)) for p in polygons]
        return "# grid\n" + "\n".join([f"v {row}" for row in xyz] + faces) + "\n"
    header = (f"ply\nformat ascii 1.0\nelement vertex {len(v)}\nproperty double x\nproperty double y\n"
              f"property double z\nelement face {len(polygons)}\nproperty list uchar int vertex_indices\nend_header\n")
    return header + "\n".join(xyz + [f"{len(p)} " + " ".join(map(str, p)) for p in polygons]) + "\n"


def _binary_point_ply(points: np.ndarray) -> bytes:
    header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(points)}\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n").encode()
    return header + points.astype("<f4").tobytes()


def base_files(folder: Path) -> dict[str, bytes]:
    """The undamaged files, by name (the extension selects the format)."""
    sphere = shapes.icosphere(1)
    v, f = sphere.vertices, sphere.faces
    files = {f"sphere{ext}": mesh_text(v, f, ext).encode() for ext in FORMATS}  # text PLY and ASCII STL
    for ext in (".ply", ".stl"):
        files[f"sphere_binary{ext}"] = save_mesh(sphere, folder / f"binary{ext}", binary=True).read_bytes()
    disk = shapes.disk(n_rings=3)
    files["disk.obj"] = mesh_text(disk.vertices, disk.faces, ".obj").encode()
    grid_v, quads = _grid_of_quads()
    for ext in (".off", ".obj", ".ply"):
        files[f"quads{ext}"] = _polygon_text(grid_v, quads, ext).encode()
    rows = v.tolist()
    files["cloud.xyz"] = "".join("%r %r %r %r %r %r\n" % (*p, *p) for p in rows).encode()  # with normals
    files["cloud.csv"] = ("x,y,z\n" + "".join("%r,%r,%r\n" % tuple(p) for p in rows)).encode()
    files["cloud.pts"] = (f"{len(rows)}\n" + "".join("%r %r %r 0 200 200 200\n" % tuple(p) for p in rows)).encode()
    files["cloud.txt"] = ("# x y z\n" + "".join("%r\t%r\t%r\n" % tuple(p) for p in rows)).encode()
    files["cloud_binary.ply"] = _binary_point_ply(v)
    return files


# --- the damage ---------------------------------------------------------------------------------
Mutation = Callable[[bytes, np.random.Generator], bytes]
_NUMBER = re.compile(rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
_REPLACEMENTS = [b"nan", b"inf", b"-inf", b"1e308", b"-1e308", b"1e400", b"1e-320", b"0", b"-1", b"2.5", b"1_0",
                 b"3.0", b"99999999999", b"9223372036854775808", b"18446744073709551621", b"-9223372036854775809",
                 b"4294967295", b"0x10", b"", b"1e", b"--1", b"1..2"]


def _flip_bytes(data: bytes, rng: np.random.Generator) -> bytes:
    out = bytearray(data)
    for _ in range(int(rng.integers(1, 9))):
        out[int(rng.integers(len(out)))] = int(rng.integers(256))
    return bytes(out)


def _flip_bits(data: bytes, rng: np.random.Generator) -> bytes:
    out = bytearray(data)
    for _ in range(int(rng.integers(1, 4))):
        out[int(rng.integers(len(out)))] ^= 1 << int(rng.integers(8))
    return bytes(out)


def _truncate(data: bytes, rng: np.random.Generator) -> bytes:
    return data[: int(rng.integers(len(data)))]


def _insert_bytes(data: bytes, rng: np.random.Generator) -> bytes:
    at = int(rng.integers(len(data) + 1))
    return data[:at] + bytes(rng.integers(0, 256, int(rng.integers(1, 24)), dtype=np.uint8)) + data[at:]


def _delete_span(data: bytes, rng: np.random.Generator) -> bytes:
    at = int(rng.integers(len(data)))
    return data[:at] + data[at + int(rng.integers(1, 40)) :]


def _numbers(data: bytes) -> list[re.Match[bytes]]:
    return [m for m in _NUMBER.finditer(data) if not data[max(m.start() - 1, 0) : m.start()].isalpha()]


def _change_digit(data: bytes, rng: np.random.Generator) -> bytes:
    digits = [i for i, c in enumerate(data) if 48 <= c <= 57]
    if not digits:
        return _flip_bytes(data, rng)
    out = bytearray(data)
    out[digits[int(rng.integers(len(digits)))]] = int(rng.integers(48, 58))
    return bytes(out)


def _replace_number(data: bytes, rng: np.random.Generator) -> bytes:
    found = _numbers(data)
    if not found:
        return _flip_bytes(data, rng)
    m = found[int(rng.integers(len(found)))]
    return data[: m.start()] + _REPLACEMENTS[int(rng.integers(len(_REPLACEMENTS)))] + data[m.end() :]


def _change_count(data: bytes, rng: np.random.Generator) -> bytes:
    """A header count (the first numbers of the file: OFF, PLY, .pts) made absurd or off by one."""
    found = _numbers(data[:400]) if not data.startswith(b"ply") else [
        m for m in _NUMBER.finditer(data[: data.find(b"end_header") + 1]) if m.start() > 10]
    if not found:
        return _replace_number(data, rng)
    m = found[int(rng.integers(min(len(found), 3)))]
    value = int(float(m.group())) if m.group().replace(b".", b"").isdigit() else 1
    new = [value + 1, value - 1, 0, 10**9, 2**31, 2**63, -5][int(rng.integers(7))]
    return data[: m.start()] + str(new).encode() + data[m.end() :]


def _edit_lines(data: bytes, rng: np.random.Generator) -> bytes:
    lines = data.split(b"\n")
    k = int(rng.integers(len(lines)))
    action = int(rng.integers(3))
    if action == 0:
        del lines[k]
    elif action == 1:
        lines.insert(k, lines[int(rng.integers(len(lines)))])
    else:
        j = int(rng.integers(len(lines)))
        lines[k], lines[j] = lines[j], lines[k]
    return b"\n".join(lines)


def _reencode(data: bytes, rng: np.random.Generator) -> bytes:
    text = data.decode("latin-1")
    choice = int(rng.integers(5))
    if choice == 0:
        return text.encode("utf-16")
    if choice == 1:
        return b"\xef\xbb\xbf" + data
    if choice == 2:
        return data.replace(b"\n", b"\r\n")
    if choice == 3:
        return data.replace(b"\n", b"\r")
    return text.replace("0", "\u00b0", 1).encode("utf-8")  # a non-ASCII character inside a number


def _empty(data: bytes, rng: np.random.Generator) -> bytes:
    return [b"", b"\n", b"   \n\n", b"\x00" * 8, data[:1]][int(rng.integers(5))]


# Truncation twice: a file cut short is the commonest damage and the one that can pass unseen.
MUTATIONS: list[Mutation] = [_flip_bytes, _flip_bits, _truncate, _insert_bytes, _delete_span, _change_digit,
                             _truncate, _replace_number, _change_count, _edit_lines, _reencode, _empty]


def mutants(name: str, data: bytes, seed: int) -> list[tuple[str, bytes, bool]]:
    """``MUTANTS_PER_BASE`` damaged copies of one file: each mutation in turn, a second one now and then.

    Each comes with its name and whether it is only a truncation (a prefix of the file).
    """
    rng = np.random.default_rng([SEED, seed])
    out = []
    for k in range(MUTANTS_PER_BASE):
        mutation = MUTATIONS[k % len(MUTATIONS)]
        damaged = mutation(data, rng)
        twice = bool(damaged) and rng.random() < 0.25
        if twice:
            damaged = MUTATIONS[int(rng.integers(len(MUTATIONS)))](damaged, rng)
        out.append((f"{mutation.__name__[1:]}{k}_{name}", damaged, mutation is _truncate and not twice))
    return out


# Formats without a count to check: a cut at a line boundary loses whole lines, which cannot be seen.
UNCOUNTED = (".obj", ".xyz", ".csv", ".txt")


# --- the contract -------------------------------------------------------------------------------
def _call(what: str, load: Callable[[], Any], failures: list[str]) -> Any:
    """``load()``; None if it raised MeshError/ValueError; anything else, or a slow call, is a failure."""
    start = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return load()
    except ValueError:  # MeshError is a ValueError
        return None
    except Exception as exc:  # noqa: BLE001 -- the point of the test
        failures.append(f"{what}: {type(exc).__name__}: {str(exc)[:200]}")
        return None
    finally:
        elapsed = time.perf_counter() - start
        if elapsed > SLOW_CALL:
            failures.append(f"{what}: took {elapsed:.1f} s")


def _check_spectrum(what: str, shape: Mesh | PointCloud, failures: list[str]) -> None:
    n = shape.n_vertices if isinstance(shape, Mesh) else shape.n_points
    spectrum = _call(f"{what}: eigenbasis", lambda: eigenbasis(shape, min(4, n)), failures)
    if spectrum is None:
        return
    V, A = spectrum.vectors, spectrum.mass
    if not (np.all(np.isfinite(spectrum.values)) and np.all(np.isfinite(V))):
        failures.append(f"{what}: non-finite eigenpairs {spectrum.values}")
        return
    gram = V.T @ (A @ V)
    if np.abs(gram - np.eye(V.shape[1])).max() > 1e-8:
        failures.append(f"{what}: eigenvectors not A-orthonormal, |V'AV - I| = {np.abs(gram - np.eye(V.shape[1])).max():.2e}")


@pytest.fixture(scope="module")
def bases(tmp_path_factory) -> dict[str, bytes]:
    return base_files(tmp_path_factory.mktemp("bases"))


BASE_NAMES = ["cloud.csv", "cloud.pts", "cloud.txt", "cloud.xyz", "cloud_binary.ply", "disk.obj", "quads.obj",
              "quads.off", "quads.ply", "sphere.obj", "sphere.off", "sphere.ply", "sphere.stl", "sphere_binary.ply",
              "sphere_binary.stl"]


def test_the_fuzz_covers_every_format_with_over_a_thousand_files(bases):
    assert sorted(bases) == BASE_NAMES
    extensions = {Path(name).suffix for name in bases}
    assert extensions == {".off", ".obj", ".ply", ".stl", ".xyz", ".csv", ".pts", ".txt"}
    assert len(bases) * MUTANTS_PER_BASE >= 1000
    # Both PLY encodings, both STL encodings, polygons and clouds are among the bases.
    assert bases["sphere_binary.ply"].startswith(b"ply\nformat binary") and b"ascii" in bases["sphere.ply"][:40]
    assert bases["sphere.stl"].startswith(b"solid") and not bases["sphere_binary.stl"].startswith(b"solid")


@pytest.mark.parametrize("index,name", list(enumerate(BASE_NAMES)))
def test_damaged_files_load_or_raise_a_clear_error_and_what_loads_has_a_spectrum(tmp_path, bases, index, name):
    data = bases[name]
    failures: list[str] = []
    # The undamaged file loads (so the damage, not the base, decides what happens below).
    path = tmp_path / name
    path.write_bytes(data)
    whole = {"load_points": _call(name, lambda: load_points(path), failures)}
    if path.suffix in FORMATS and not name.startswith("cloud"):
        whole["load_mesh(clean=True)"] = _call(name, lambda: load_mesh(path, clean=True), failures)
        whole["load_mesh"] = _call(name, lambda: load_mesh(path), failures) if not name.startswith("quads") else None
    assert whole["load_points"] is not None and not failures, failures
    seen: set[tuple[str, int]] = set()
    n_truncated = 0
    for mutant, damaged, truncated in mutants(name, data, index):
        n_truncated += truncated
        path = tmp_path / mutant
        path.write_bytes(damaged)
        loaders: list[tuple[str, Callable[[], Any]]] = [("load_points", lambda: load_points(path))]
        if path.suffix in FORMATS:
            loaders += [("load_mesh", lambda: load_mesh(path)), ("load_mesh(clean=True)", lambda: load_mesh(path, clean=True))]
        for what, load in loaders:
            shape = _call(f"{mutant}: {what}", load, failures)
            if truncated:
                lines_lost = path.suffix in UNCOUNTED and damaged.endswith((b"\n", b"\r"))
                if shape is not None and shape != whole.get(what) and not lines_lost:
                    failures.append(f"{mutant}: {what}: the file cut after {len(damaged)} of {len(data)} bytes loads "
                                    f"as {shape!r}, not as the whole file")
            if shape is None:
                continue
            key = (type(shape).__name__, hash(shape))
            if key not in seen:  # many mutants load to the same thing; one spectrum each
                seen.add(key)
                _check_spectrum(f"{mutant}: {what}", shape, failures)
    assert n_truncated >= 5 and not failures, "\n".join(failures)
