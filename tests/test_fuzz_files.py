"""Fuzz test of every file reader (issues 26 and 41): over 2,000 damaged files, no crash, no hang, no nonsense.

Small files of every supported format are made here from the package's own shapes (text and
binary PLY, OFF, OBJ, ASCII and binary STL, and the point lists .xyz, .csv, .pts, .txt), among them
the valid files issue 41 found refused or misread (binary PLY mixing triangles and quads in both
byte orders, a PLY point cloud with ``element face 0``, ASCII STL and PLY after a UTF-8 byte order
mark, a ``;``-separated decimal-comma CSV), then damaged with a seeded random generator: bytes
flipped, inserted or deleted, the file truncated at a random offset, a digit changed, a number
replaced by NaN, inf, an overflowing or a huge value, an underscore or a decimal, a count or an
index made absurd, lines duplicated or dropped, the text re-encoded (UTF-16, a byte order mark, CR
line ends), empty or blank files, and issue 41's defects: a PLY element with no properties and a
huge count, a number moved from one vertex line to the next, data after the last record, a byte
order mark in front. For every file:

- every loader (``load_mesh``, ``load_mesh(clean=True)``, ``load_points``) either returns or raises
  :class:`MeshError` / ``ValueError`` -- nothing else -- and takes less than 10 s;
- whatever loads gets a finite, A-orthonormal spectrum from ``eigenbasis`` (which may also refuse
  it with a ``MeshError`` or ``ValueError``, e.g. a cloud of fewer points than its neighbourhoods);
- a truncated file never loads as something else than the whole file: formats that announce their
  size (OFF, PLY, STL, .pts) are refused wherever they are cut, and the others (OBJ, .xyz, .csv,
  .txt, which have no count to check) can only lose whole lines, never part of a number;
- a byte order mark alone in front of a text file (or a binary PLY) changes nothing.

Issue 41's families are also checked one by one, each for its specific outcome (the unit tests
are in ``tests/test_io.py``): the new bases load with the right counts; a propertyless element with
a count of 2e9 and more is refused at once in ASCII PLY and ignored in binary PLY (which stores no
bytes for it), under 2 s and 32 MiB each; a number moved between two OFF, OBJ or ASCII STL vertex
lines is refused, naming one of the two lines; an extra OFF, PLY or .pts line, or bytes after a
binary PLY or STL, are refused (blank lines and comments are not data and still load); and every
file and 12 of its damaged copies load, or are refused, exactly as without a byte order mark.

The meshes have 25 to 42 vertices, so the eigenproblems take the dense path; the whole file runs in
well under a minute on one core.
"""

from __future__ import annotations

import os
import re
import struct
import time
import warnings
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest

from lbo_notebooks import Mesh, MeshError, PointCloud, eigenbasis, shapes
from lbo_notebooks.geometry._formats import FORMATS, mesh_text
from lbo_notebooks.geometry import MeshRepairWarning, load_mesh, load_points, save_mesh

SEED = 26
MUTANTS_PER_BASE = 96  # six rounds of the sixteen mutations
# A call slower than this is a failure: a wall time, so only with LBO_TIMING_TESTS=1 (tests/conftest.py;
# the checks sit in the helpers every test here shares, so they are switched, not marked).
SLOW_CALL = 10.0 if os.environ.get("LBO_TIMING_TESTS") == "1" else float("inf")  # seconds
BOM = b"\xef\xbb\xbf"  # UTF-8 byte order mark


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
    # Issue 41's valid files, which were refused or misread: binary PLY mixing triangles and quads (both
    # byte orders), a PLY point cloud with 'element face 0', a UTF-8 byte order mark before ASCII STL and
    # PLY, and a ';'-separated decimal-comma CSV.
    for endian, tag in (("<", "le"), (">", "be")):
        files[f"quads_binary_{tag}.ply"] = _mixed_binary_ply(grid_v, quads, endian)
    files["cloud_face0.ply"] = (f"ply\nformat ascii 1.0\nelement vertex {len(rows)}\nproperty double x\n"
                                "property double y\nproperty double z\nelement face 0\n"
                                "property list uchar int vertex_indices\nend_header\n"
                                + "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in rows)).encode()
    files["sphere_bom.stl"] = BOM + files["sphere.stl"]
    files["sphere_bom.ply"] = BOM + files["sphere.ply"]
    files["cloud_eu.csv"] = ("0,5;1,5;2,5\n" + "".join(";".join(repr(x).replace(".", ",") for x in p) + "\n"
                                                       for p in rows)).encode()
    return files


def _mixed_faces(quads: list[list[int]]) -> list[list[int]]:
    """Every other quad of the grid split into the two triangles of its fan: triangles and quads mixed."""
    out: list[list[int]] = []
    for k, (a, b, c, d) in enumerate(quads):
        out += [[a, b, c, d]] if k % 2 == 0 else [[a, b, c], [a, c, d]]
    return out


def _mixed_binary_ply(v: np.ndarray, quads: list[list[int]], endian: str) -> bytes:
    faces = _mixed_faces(quads)
    fmt = {"<": "binary_little_endian", ">": "binary_big_endian"}[endian]
    header = (f"ply\nformat {fmt} 1.0\nelement vertex {len(v)}\nproperty double x\nproperty double y\n"
              f"property double z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    body = v.astype(endian + "f8").tobytes() + b"".join(struct.pack(f"{endian}B{len(f)}i", len(f), *f) for f in faces)
    return header.encode() + body


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


def _kind(data: bytes) -> str:
    """The format of an (undamaged) base file, from its content: the families below need it."""
    head = data.removeprefix(BOM)[:80]
    if head.startswith(b"ply"):
        return "ply"
    if head.startswith(b"OFF"):
        return "off"
    if head.startswith(b"solid"):
        return "stl"
    return "obj" if re.search(rb"^v ", data, flags=re.MULTILINE) else "other"


def _propertyless_element(data: bytes, rng: np.random.Generator) -> bytes:
    """Issue 41 (a): 'element junk 2000000000' (no properties) in a PLY header; elsewhere a byte flipped."""
    if _kind(data) != "ply" or b"end_header" not in data:
        return _flip_bytes(data, rng)
    return _insert_propertyless_element(data, rng)[0]


def _shift_number(data: bytes, rng: np.random.Generator) -> bytes:
    """Issue 41 (b): a number moved between consecutive OFF / OBJ / ASCII STL vertex lines."""
    kind = _kind(data)
    try:  # a file damaged by a first mutation may have no vertex lines left to shift between
        return _shift_a_number(data, "x." + kind, rng)[0] if kind in ("off", "obj", "stl") else _edit_lines(data, rng)
    except (ValueError, IndexError, AttributeError):
        return _edit_lines(data, rng)


def _trailing_data(data: bytes, rng: np.random.Generator) -> bytes:
    """Issue 41 (c): bytes or a copied line after the last record."""
    if rng.random() < 0.5:
        return data + bytes(rng.integers(0, 256, int(rng.integers(1, 64)), dtype=np.uint8))
    lines = [line for line in data.split(b"\n") if line.strip()] or [b"0 0 0"]
    return data + lines[int(rng.integers(len(lines)))] + b"\n"


def _bom(data: bytes, rng: np.random.Generator) -> bytes:
    """Issue 41 (d): a UTF-8 byte order mark in front."""
    return BOM + data


# Truncation twice: a file cut short is the commonest damage and the one that can pass unseen.
MUTATIONS: list[Mutation] = [_flip_bytes, _flip_bits, _truncate, _insert_bytes, _delete_span, _change_digit,
                             _truncate, _replace_number, _change_count, _edit_lines, _reencode, _empty,
                             _propertyless_element, _shift_number, _trailing_data, _bom]


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
        label = f"{mutation.__name__[1:]}{k}"
        if twice:
            second = MUTATIONS[int(rng.integers(len(MUTATIONS)))]
            damaged = second(damaged, rng)
            label += f"+{second.__name__[1:]}"
        out.append((f"{label}_{name}", damaged, mutation is _truncate and not twice))
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


BASE_NAMES = ["cloud.csv", "cloud.pts", "cloud.txt", "cloud.xyz", "cloud_binary.ply", "cloud_eu.csv",
              "cloud_face0.ply", "disk.obj", "quads.obj", "quads.off", "quads.ply", "quads_binary_be.ply",
              "quads_binary_le.ply", "sphere.obj", "sphere.off", "sphere.ply", "sphere.stl", "sphere_binary.ply",
              "sphere_binary.stl", "sphere_bom.ply", "sphere_bom.stl"]


def test_the_fuzz_covers_every_format_with_over_a_thousand_files(bases):
    assert sorted(bases) == BASE_NAMES
    extensions = {Path(name).suffix for name in bases}
    assert extensions == {".off", ".obj", ".ply", ".stl", ".xyz", ".csv", ".pts", ".txt"}
    assert len(bases) * MUTANTS_PER_BASE >= 2000
    # Both PLY encodings, both STL encodings, polygons and clouds are among the bases.
    assert bases["sphere_binary.ply"].startswith(b"ply\nformat binary") and b"ascii" in bases["sphere.ply"][:40]
    assert bases["sphere.stl"].startswith(b"solid") and not bases["sphere_binary.stl"].startswith(b"solid")
    # Issue 41's valid files: mixed binary polygons in both byte orders, 'element face 0', BOMs, decimal commas.
    assert b"binary_big_endian" in bases["quads_binary_be.ply"][:40] and b"binary_little" in bases["quads_binary_le.ply"][:40]
    assert b"element face 0\n" in bases["cloud_face0.ply"] and bases["cloud_eu.csv"].startswith(b"0,5;1,5;2,5\n")
    assert all(bases[n] == BOM + bases[n.replace("_bom", "")] for n in ("sphere_bom.stl", "sphere_bom.ply"))
    # Every mutation is used on every base, the issue 41 ones included.
    assert MUTANTS_PER_BASE % len(MUTATIONS) == 0 and len(set(MUTATIONS)) == len(MUTATIONS) - 1


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
            bom_alone = re.match(r"bom\d+_", mutant) and name != "sphere_binary.stl" and not data.startswith(BOM)
            if bom_alone and what in whole and shape != whole[what]:
                failures.append(f"{mutant}: {what}: a byte order mark in front gives {shape!r}, not {whole[what]!r}")
            if shape is None:
                continue
            key = (type(shape).__name__, hash(shape))
            if key not in seen:  # many mutants load to the same thing; one spectrum each
                seen.add(key)
                _check_spectrum(f"{mutant}: {what}", shape, failures)
    assert n_truncated >= 5 and not failures, "\n".join(failures)


# --- issue 41's families: valid files that must load, and damage that must be refused -------------
def _outcome(path: Path, what: str, failures: list[str]) -> Any:
    """What ``what`` gives for ``path`` (None when refused with MeshError/ValueError); a crash or slow call fails."""
    load = {"load_points": lambda: load_points(path), "load_mesh": lambda: load_mesh(path),
            "load_mesh(clean=True)": lambda: load_mesh(path, clean=True)}[what]
    return _call(f"{path.name}: {what}", load, failures)


def _loaders(name: str) -> list[str]:
    return ["load_points"] + (["load_mesh", "load_mesh(clean=True)"] if Path(name).suffix in FORMATS else [])


def _refusal(path: Path, what: str, failures: list[str]) -> str | None:
    """The MeshError/ValueError message of ``what`` on ``path``; None (and a failure) if it loads or crashes."""
    load = {"load_points": load_points, "load_mesh": load_mesh,
            "load_mesh(clean=True)": lambda p: load_mesh(p, clean=True)}[what]
    start = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            shape = load(path)
        failures.append(f"{path.name}: {what} loaded {shape!r}; it must be refused")
    except ValueError as exc:
        return str(exc)
    except Exception as exc:  # noqa: BLE001
        failures.append(f"{path.name}: {what}: {type(exc).__name__}: {str(exc)[:200]}")
    finally:
        if time.perf_counter() - start > SLOW_CALL:
            failures.append(f"{path.name}: {what}: took {time.perf_counter() - start:.1f} s")
    return None


def _says(name: str, what: str, message: str | None, words: str) -> bool:
    """Whether a refusal holds ``words``; load_mesh refuses a point cloud's file for that first, whatever else."""
    return message is None or words in message or (name.startswith("cloud") and what != "load_points"
                                                    and "point cloud" in message)


def test_the_issue_41_bases_are_valid_and_load_with_the_right_counts(tmp_path, bases):
    def write(name: str, data: bytes | None = None) -> Path:
        path = tmp_path / name
        path.write_bytes(bases[name] if data is None else data)
        return path

    sphere, grid_v = shapes.icosphere(1), _grid_of_quads()[0]
    # The same mixed faces as text PLY: the binary files must load as it does.
    text = _polygon_text(grid_v, _mixed_faces(_grid_of_quads()[1]), ".ply").encode()
    with pytest.warns(MeshRepairWarning, match="8 polygons split"):
        reference = load_mesh(write("mixed_text.ply", text), clean=True)
    assert (reference.n_vertices, reference.n_faces) == (25, 32)
    for name in ("quads_binary_le.ply", "quads_binary_be.ply"):
        path = write(name)
        with pytest.raises(MeshError, match="8 of its 24 faces have more than three corners"):
            load_mesh(path)
        with pytest.warns(MeshRepairWarning, match="8 polygons split"):
            mesh = load_mesh(path, clean=True)
        assert mesh == reference and (mesh.n_vertices, mesh.n_faces) == (25, 32)
        np.testing.assert_array_equal(load_points(path).points, grid_v)
    path = write("cloud_face0.ply")
    np.testing.assert_array_equal(load_points(path).points, sphere.vertices)
    with pytest.raises(MeshError, match="point cloud"):
        load_mesh(path)
    for name in ("sphere_bom.stl", "sphere_bom.ply"):
        mesh = load_mesh(write(name))
        assert (mesh.n_vertices, mesh.n_faces) == (42, 80)
        assert mesh == load_mesh(write(name.replace("_bom", ""))) and mesh == load_mesh(write(name), clean=True)
    cloud = load_points(write("cloud_eu.csv"))
    np.testing.assert_array_equal(cloud.points, np.vstack([[0.5, 1.5, 2.5], sphere.vertices]))


# (a) A header element with no properties and a huge count. An ASCII row of it is a line of its own, so the
# count is checked against the file's size and refused at once; a binary row takes no bytes, so the file
# loads as without the element (tests/test_io.py, test_a_propertyless_element_*). Either way: fast, and
# without allocating anything proportional to the count.
HUGE_COUNTS = [2_000_000_000, 2**31 - 1, 2**32, 10**12, 2**62]
PLY_BASES = [n for n in BASE_NAMES if n.endswith(".ply")]
PEAK_BYTES = 32 << 20


def _insert_propertyless_element(data: bytes, rng: np.random.Generator) -> tuple[bytes, int]:
    end = data.index(b"end_header")
    places = [m.start() for m in re.finditer(rb"^element ", data[:end], flags=re.MULTILINE)] + [end]
    at = places[int(rng.integers(len(places)))]
    count = HUGE_COUNTS[int(rng.integers(len(HUGE_COUNTS)))]
    return data[:at] + f"element junk {count}\n".encode() + data[at:], count


@pytest.mark.parametrize("timed", [False, pytest.param(True, marks=pytest.mark.timing)], ids=["memory", "seconds"])
@pytest.mark.parametrize("name", PLY_BASES)
def test_a_propertyless_element_with_a_huge_count_is_refused_fast_in_ascii_and_ignored_in_binary(tmp_path, bases, name, timed):
    import tracemalloc

    data, failures = bases[name], []
    binary = b"format binary" in data[:60]
    (tmp_path / name).write_bytes(data)
    whole = {what: _outcome(tmp_path / name, what, failures) for what in _loaders(name)}
    rng = np.random.default_rng([SEED, 41, 1, PLY_BASES.index(name)])
    for k in range(6):
        damaged, count = _insert_propertyless_element(data, rng)
        path = tmp_path / f"junk{k}_{name}"
        path.write_bytes(damaged)
        for what in _loaders(name):
            tracemalloc.start()
            start = time.perf_counter()
            try:
                if binary:
                    shape = _outcome(path, what, failures)
                    if shape != whole[what]:
                        failures.append(f"{path.name}: {what}: {shape!r}, not {whole[what]!r} as without the element")
                else:
                    message = _refusal(path, what, failures)
                    if not (_says(name, what, message, str(count)) and _says(name, what, message, "junk")):
                        failures.append(f"{path.name}: {what}: the refusal names neither 'junk' nor {count}: {message}")
            finally:
                elapsed = time.perf_counter() - start
                peak = tracemalloc.get_traced_memory()[1]
                tracemalloc.stop()
            if (timed and elapsed > 2.0) or peak > PEAK_BYTES:  # the wall time: opt-in (tests/conftest.py)
                failures.append(f"{path.name}: {what}: {elapsed:.2f} s, peak {peak / 2**20:.1f} MiB")
    assert not failures, "\n".join(failures)


# (b) One number moved from a vertex line to the next (or back): the total count of numbers is unchanged, so
# only a per-line check sees it; one line then has two numbers, which is never a vertex.
SHIFT_BASES = ["disk.obj", "quads.obj", "quads.off", "sphere.obj", "sphere.off", "sphere.stl", "sphere_bom.stl"]
SHIFTS_PER_BASE = 8


def _vertex_line_indices(data: bytes, name: str) -> list[int]:
    lines = data.split(b"\n")
    if name.endswith(".off"):
        nv = int(lines[1].split()[0])
        return list(range(2, min(2 + nv, len(lines))))  # (capped: a damaged count may be absurd)
    keyword = rb"v" if name.endswith(".obj") else rb"vertex"
    return [k for k, line in enumerate(lines) if re.match(rb"(\xef\xbb\xbf)?\s*" + keyword + rb"\s", line)]


def _shift_a_number(data: bytes, name: str, rng: np.random.Generator) -> tuple[bytes, tuple[int, int]]:
    """A number moved between consecutive vertex lines; the damaged file and the two lines (numbered from 1)."""
    lines = data.split(b"\n")
    vertex_lines = _vertex_line_indices(data, name)
    k = int(rng.integers(len(vertex_lines) - 1))
    a, b = vertex_lines[k], vertex_lines[k + 1]
    split = [re.match(rb"((?:\xef\xbb\xbf)?\s*(?:(?:vertex|v)\s+)?)(.*)$", lines[i]).groups() for i in (a, b)]
    (pa, na), (pb, nb) = [(prefix, rest.split()) for prefix, rest in split]
    if rng.random() < 0.5:
        nb.insert(0, na.pop())  # line a keeps two numbers
    else:
        na.append(nb.pop(0))  # line b keeps two numbers (line a has four: an OBJ weight, an error elsewhere)
    lines[a], lines[b] = pa + b" ".join(na), pb + b" ".join(nb)
    return b"\n".join(lines), (a + 1, b + 1)


@pytest.mark.parametrize("name", SHIFT_BASES)
def test_a_number_moved_between_vertex_lines_is_refused_naming_the_line(tmp_path, bases, name):
    data, failures = bases[name], []
    rng = np.random.default_rng([SEED, 41, 2, SHIFT_BASES.index(name)])
    assert len(_vertex_line_indices(data, name)) >= 25
    for k in range(SHIFTS_PER_BASE):
        damaged, (a, b) = _shift_a_number(data, name, rng)
        assert len(_NUMBER.findall(damaged)) == len(_NUMBER.findall(data)) and damaged != data
        path = tmp_path / f"shift{k}_{name}"
        path.write_bytes(damaged)
        for what in _loaders(name):
            message = _refusal(path, what, failures)
            if message is not None and not re.search(rf"\bline ({a}|{b})\b", message):
                failures.append(f"{path.name}: {what}: the refusal names neither line {a} nor line {b}: {message[:300]}")
    assert not failures, "\n".join(failures)


# (c) Data after the records a file announces: an extra OFF face or vertex line, an extra PLY data line, bytes
# after a binary PLY or STL, an extra .pts point. A file whose counts disagree with its data is corrupt.
# (Blank lines and comments after the records are not data: those still load, as the control below checks.)
TRAILING_BASES = ["cloud.pts", "cloud_binary.ply", "cloud_face0.ply", "quads.off", "quads.ply", "quads_binary_be.ply",
                  "quads_binary_le.ply", "sphere.off", "sphere.ply", "sphere_binary.ply", "sphere_binary.stl",
                  "sphere_bom.ply"]
TRAILERS_PER_BASE = 6


def _append_trailing_data(data: bytes, name: str, rng: np.random.Generator) -> tuple[bytes, str]:
    """The file with data after its records, and the words its refusal must hold."""
    if b"format binary" in data[:60] or name.endswith(".stl"):
        n = int(rng.integers(1, 64))
        if rng.random() < 0.3:  # a whole record more: a triangle (PLY), a facet (STL)
            record = struct.pack("<B3i", 3, 0, 1, 2) if name.endswith(".ply") else bytes(50)
            n, trailer = len(record), record
        else:
            trailer = bytes(rng.integers(0, 256, n, dtype=np.uint8))
        return data + trailer, (f"{n} byte" if name.endswith(".ply") else "neither a binary STL")
    lines = [line for line in data.split(b"\n") if line.strip()]
    body = lines[int(data[: data.find(b"end_header")].count(b"\n")) + 1:] if name.endswith(".ply") else lines[2:]
    if name.endswith(".off") and rng.random() < 0.5:
        extra = b"3 0 1 2"  # a new face
    else:
        extra = body[int(rng.integers(len(body)))]  # a copy of a vertex or face line
    words = {".pts": "count line announces", ".off": "after", ".ply": "after"}[Path(name).suffix]
    return data + extra + b"\n", words


@pytest.mark.parametrize("name", TRAILING_BASES)
def test_data_after_the_announced_records_is_refused(tmp_path, bases, name):
    data, failures = bases[name], []
    rng = np.random.default_rng([SEED, 41, 3, TRAILING_BASES.index(name)])
    for k in range(TRAILERS_PER_BASE):
        damaged, words = _append_trailing_data(data, name, rng)
        path = tmp_path / f"trailing{k}_{name}"
        path.write_bytes(damaged)
        for what in _loaders(name):
            message = _refusal(path, what, failures)
            if not _says(name, what, message, words):
                failures.append(f"{path.name}: {what}: the refusal does not say {words!r}: {message[:300]}")
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("name", ["cloud_face0.ply", "quads.off", "quads.ply", "sphere.off", "sphere.ply"])
def test_blank_lines_and_comments_after_the_records_still_load(tmp_path, bases, name):
    data, failures = bases[name], []
    path = tmp_path / name
    path.write_bytes(data)
    whole = {what: _outcome(path, what, failures) for what in _loaders(name)}
    trailer = b"\n  \n# written by hand\n\n" if name.endswith(".off") else b"\n  \n\n"
    path = tmp_path / f"blank_{name}"
    path.write_bytes(data + trailer)
    for what in _loaders(name):
        if _outcome(path, what, failures) != whole[what]:
            failures.append(f"{path.name}: {what}: does not load as without the blank lines")
    assert any(shape is not None for shape in whole.values()) and not failures, "\n".join(failures)


# (d) A UTF-8 byte order mark before a text file (and before a binary PLY, whose header is text) is not data:
# the file, and each of its damaged copies, loads or is refused exactly as without it.
BOM_BASES = [n for n in BASE_NAMES if n != "sphere_binary.stl" and "_bom" not in n]
BOM_MUTANTS_PER_BASE = 12


@pytest.mark.parametrize("name", BOM_BASES)
def test_a_byte_order_mark_changes_nothing(tmp_path, bases, name):
    data, failures = bases[name], []
    rng_seed = BASE_NAMES.index(name)
    variants = [("whole", data)] + [(m, d) for m, d, _ in mutants(name, data, rng_seed)[:BOM_MUTANTS_PER_BASE]
                                    if not d.startswith((BOM, b"\xff\xfe", b"\xfe\xff"))]
    n_loaded = 0
    for label, variant in variants:
        plain, marked = tmp_path / f"{label}_{name}", tmp_path / f"{label}_bom_{name}"
        plain.write_bytes(variant)
        marked.write_bytes(BOM + variant)
        for what in _loaders(name):
            without, with_bom = _outcome(plain, what, failures), _outcome(marked, what, failures)
            n_loaded += without is not None
            if label == "whole" and what == "load_points" and without is None:
                failures.append(f"{name}: the undamaged file does not load")
            if (without is None) != (with_bom is None) or with_bom != without:
                failures.append(f"{marked.name}: {what}: {with_bom!r} with the BOM, {without!r} without")
    assert len(variants) >= 10 and n_loaded >= 1 and not failures, "\n".join(failures)
