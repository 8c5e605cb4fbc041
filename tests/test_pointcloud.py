"""Tests for PointCloud, load_points and the point-cloud Laplacian behind eigenbasis(cloud, k)."""

from __future__ import annotations

import struct
import warnings

import numpy as np
import pytest

import lbo_notebooks as lbo
from .strategies import corrupted_copies
from lbo_notebooks import MeshError, PointCloud, load_points, shapes
from lbo_notebooks.geometry import MeshRepairWarning, save_mesh

L_SPHERE = np.repeat(np.arange(4), 2 * np.arange(4) + 1)
EXACT_SPHERE = (L_SPHERE * (L_SPHERE + 1)).astype(float)  # first 16: 0, 2 x3, 6 x5, 12 x7


def sphere_points(n: int, seed: int = 0) -> np.ndarray:
    x = np.random.default_rng(seed).normal(size=(n, 3))
    return x / np.linalg.norm(x, axis=1, keepdims=True)


# --- the value type -----------------------------------------------------------------------------
def test_point_cloud_copies_is_read_only_and_compares_by_value():
    p = sphere_points(50)
    cloud = PointCloud(p)
    p[0] = 7.0
    assert not np.array_equal(cloud.points[0], p[0])
    with pytest.raises(ValueError):
        cloud.points[0, 0] = 1.0
    with pytest.raises(AttributeError, match="immutable"):
        cloud.points = p
    assert cloud == PointCloud(cloud.points) and hash(cloud) == hash(PointCloud(cloud.points))
    assert cloud != PointCloud(cloud.points[::-1])
    assert len(cloud) == 50 and "n_points=50" in repr(cloud)


@pytest.mark.parametrize(
    "points,words",
    [
        (np.zeros((10, 2)), "shape (n, 3)"),
        (np.eye(3), "at least 5 points"),
        (np.vstack([sphere_points(9), [[np.nan, 0, 0]]]), "non-finite"),
        (np.vstack([sphere_points(9), [[0, 0, np.inf]]]), "non-finite"),
        (np.vstack([sphere_points(9), sphere_points(9)[4:5]]), "repeat an earlier point"),
        ([["a", "b", "c"]] * 6, "convertible to float64"),
    ],
    ids=["2d", "too-few", "nan", "inf", "duplicate", "strings"],
)
def test_bad_points_raise_mesh_error_naming_the_problem(points, words):
    with pytest.raises(MeshError) as info:
        PointCloud(points)
    assert words in str(info.value)


# --- the spectrum -------------------------------------------------------------------------------
def test_random_sphere_points_give_l_times_l_plus_one_within_six_percent():
    s = lbo.eigenbasis(PointCloud(sphere_points(10_000)), 16)
    assert abs(s.values[0]) < 1e-8 * s.values[1]
    np.testing.assert_allclose(s.values[1:], EXACT_SPHERE[1:], rtol=0.06)
    # The mass approximates the area: 4 pi for the unit sphere.
    np.testing.assert_allclose(s.mass.sum(), 4 * np.pi, rtol=0.06)


def test_spectrum_api_on_a_cloud_project_reconstruct_error():
    cloud = PointCloud(sphere_points(3000, seed=1))
    s = lbo.eigenbasis(cloud, 9)
    x = cloud.points[:, 0]  # a degree-1 spherical harmonic: lives in the span of phi_1..phi_3
    total = np.sqrt(x @ (s.mass @ x))
    assert s.error(x, 1) > 0.99 * total  # the constant does not capture it
    assert s.error(x, 4) < 0.05 * total
    coeffs = s.project(x)
    assert coeffs.shape == (9,) and np.abs(coeffs[1:4]).sum() > 0.95 * np.abs(coeffs).sum()
    np.testing.assert_allclose(s.reconstruct(x, 9), s.vectors @ coeffs, rtol=0, atol=1e-12 * np.abs(x).max())


def test_mesh_vertices_as_a_cloud_give_a_spectrum_close_to_the_mesh():
    """Measured (dog, 10k vertices, eigenvalues 1..20): median deviation 1.1%, worst 10% on the legs."""
    mesh = lbo.creature("dog")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ref = lbo.eigenbasis(mesh, 21).values[1:]
    cloud = lbo.eigenbasis(PointCloud(mesh.vertices), 21).values[1:]
    deviation = np.abs(cloud / ref - 1)
    assert np.median(deviation) < 0.03
    assert deviation.max() < 0.15


def test_n_neighbors_is_checked_and_changes_the_operator():
    cloud = PointCloud(sphere_points(400))
    a = lbo.eigenbasis(cloud, 4, n_neighbors=10).values
    b = lbo.eigenbasis(cloud, 4, n_neighbors=30).values
    assert not np.allclose(a, b)
    for bad in (2, 400, 12.5, True):
        with pytest.raises(ValueError, match="n_neighbors"):
            lbo.eigenbasis(cloud, 4, n_neighbors=bad)
    with pytest.raises(ValueError, match="no triangles"):
        lbo.eigenbasis(cloud, 4, laplacian="cotan")


# --- load_points --------------------------------------------------------------------------------
SQ = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1], [0.5, 0.25, 0.125]])


@pytest.mark.parametrize(
    "name,text",
    [
        ("a.xyz", "".join(f"{x} {y} {z} 0 0 1\n" for x, y, z in SQ)),  # with normals
        ("a.pts", f"{len(SQ)}\n" + "".join(f"{x} {y} {z} 17 200 100 50\n" for x, y, z in SQ)),  # count, intensity, rgb
        ("a.txt", "# exported\n" + "".join(f"{x},{y},{z}\n" for x, y, z in SQ)),
        ("a.csv", "x,y,z,red\n" + "".join(f"{x}, {y}, {z}, 3\n" for x, y, z in SQ)),
        ("a.txt", "".join(f"{x}\t{y}\t{z}  // note\n\n" for x, y, z in SQ)),
    ],
    ids=["xyz-normals", "pts-count", "txt-commas-comment", "csv-header", "txt-tabs"],
)
def test_text_point_files(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    np.testing.assert_array_equal(load_points(path).points, SQ)


@pytest.mark.parametrize("binary", [True, False])
def test_vertex_only_ply(tmp_path, binary):
    head = (
        f"ply\nformat {'binary_little_endian' if binary else 'ascii'} 1.0\nelement vertex {len(SQ)}\n"
        "property double x\nproperty double y\nproperty double z\nproperty uchar red\nend_header\n"
    ).encode()
    body = b"".join(struct.pack("<3dB", *p, 9) for p in SQ) if binary else "".join(f"{x} {y} {z} 9\n" for x, y, z in SQ).encode()
    path = tmp_path / "cloud.ply"
    path.write_bytes(head + body)
    np.testing.assert_array_equal(load_points(path).points, SQ)


@pytest.mark.parametrize("ext", [".off", ".obj", ".ply", ".stl"])
def test_a_mesh_files_vertices(tmp_path, ext):
    mesh = shapes.icosphere(1)
    cloud = load_points(save_mesh(mesh, tmp_path / f"m{ext}"))
    if ext == ".stl":  # float32, welded in order of first appearance
        assert cloud.n_points == mesh.n_vertices
        np.testing.assert_allclose(np.sort(cloud.points, axis=0), np.sort(mesh.vertices, axis=0), atol=1e-6)
    else:
        np.testing.assert_array_equal(cloud.points, mesh.vertices)


def test_an_obj_point_cloud_loads_as_points(tmp_path):
    path = tmp_path / "pc.obj"
    path.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in SQ))
    np.testing.assert_array_equal(load_points(path).points, SQ)


def test_load_points_clean_drops_duplicates_and_non_finite_rows(tmp_path):
    path = tmp_path / "dup.xyz"
    rows = np.vstack([SQ, SQ[2:3], [[np.nan, 0, 0]]])
    path.write_text("".join(f"{x} {y} {z}\n" for x, y, z in rows))
    with pytest.raises(MeshError, match="non-finite") as info:
        load_points(path)
    assert "dup.xyz" in str(info.value)
    with pytest.warns(MeshRepairWarning, match="1 non-finite and 1 repeated points dropped"):
        cloud = load_points(path, clean=True)
    np.testing.assert_array_equal(cloud.points, SQ)


@pytest.mark.parametrize(
    "name,content,words",
    [
        ("e.xyz", "", "empty"),
        ("c.xyz", "# only a comment\n", "only comments"),
        ("b.xyz", "0 0 0\n1 0\n", "three numbers"),
        ("j.txt", bytes(range(256)) * 4, "binary data"),
        ("few.xyz", "0 0 0\n1 0 0\n", "at least 5"),
    ],
)
def test_broken_point_files_raise_mesh_error_naming_the_file(tmp_path, name, content, words):
    path = tmp_path / name
    path.write_bytes(content if isinstance(content, bytes) else content.encode())
    with pytest.raises(MeshError) as info:
        load_points(path)
    assert words in str(info.value) and name in str(info.value)


def test_load_points_argument_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="no such point file"):
        load_points(tmp_path / "none.xyz")
    (tmp_path / "a.las").write_text("x")
    with pytest.raises(ValueError, match=r"\.xyz") as info:
        load_points(tmp_path / "a.las")
    assert not isinstance(info.value, MeshError)


@pytest.mark.parametrize("ext,binary", [(".xyz", None), (".ply", True), (".ply", False)])
def test_randomly_corrupted_point_files_load_or_raise_mesh_error(tmp_path, ext, binary):
    """Truncated, overwritten or padded bytes: a valid cloud or a MeshError, never another exception."""
    mesh = shapes.icosphere(1)
    if ext == ".xyz":
        source = "".join(f"{x!r} {y!r} {z!r} 0 0 1\n" for x, y, z in mesh.vertices).encode()
    else:
        source = save_mesh(mesh, tmp_path / f"src{ext}", binary=binary).read_bytes()
    rng = np.random.default_rng(11 + bool(binary))
    for k, data in corrupted_copies(source, rng):
        path = tmp_path / f"c{k}{ext}"
        path.write_bytes(data)
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                cloud = load_points(path, clean=bool(k % 2))
        except MeshError as exc:
            assert path.name in str(exc)
            continue
        assert np.all(np.isfinite(cloud.points)) and cloud.n_points >= 5


# --- every cloud the constructor accepts gets a spectrum, or a clear error up front ------------------
@pytest.mark.parametrize("n", [5, 6, 10, 30, 31])
def test_small_clouds_work_with_the_default_arguments(n):
    """PointCloud accepts 5 points; the default n_neighbors (30) means n_points - 1 on small clouds."""
    cloud = PointCloud(sphere_points(n, seed=n))
    s = lbo.eigenbasis(cloud, min(n, 4))
    assert np.all(np.isfinite(s.values)) and abs(s.values[0]) < 1e-8 * max(s.values[-1], 1.0)
    np.testing.assert_allclose(s.vectors.T @ (s.mass @ s.vectors), np.eye(s.k), atol=1e-10)
    W, _ = lbo.operators.point_cloud_operators(cloud)  # the same default there
    assert W.shape == (n, n)
    with pytest.raises(ValueError, match="n_neighbors"):  # any other value is still checked
        lbo.eigenbasis(cloud, 3, n_neighbors=n + 1)


@pytest.mark.parametrize(
    "points",
    [
        np.c_[np.linspace(0, 1, 50), np.zeros(50), np.zeros(50)],
        np.outer(np.linspace(-1, 1, 40), [1.0, 2.0, 3.0]) + 5.0,
        np.c_[np.linspace(0, 1, 50), 1e-12 * np.random.default_rng(1).normal(size=(50, 2))],  # a hair's width
    ],
    ids=["x-axis", "diagonal", "nearly"],
)
def test_collinear_points_are_a_mesh_error_not_a_library_crash(points):
    with pytest.raises(MeshError, match="line") as info:
        lbo.eigenbasis(PointCloud(points), 5)
    assert "surface" in str(info.value)


@pytest.mark.parametrize("s", [1e-300, 1e-100, 1e100, 1e160])
def test_coordinates_out_of_range_are_named_as_such(s):
    """Not "coincident points", not a GC_SAFETY_ASSERT: the scale, and how to rescale."""
    with pytest.raises(MeshError) as info:
        lbo.eigenbasis(PointCloud(sphere_points(100) * s), 5)
    message = str(info.value)
    assert "usable range" in message and "Rescale" in message and "coincide" not in message


@pytest.mark.parametrize("s", [1e-59, 1e59])
def test_the_whole_usable_range_gives_the_same_spectrum(s):
    """robust-laplacian sees the points divided by a power of two near their size, so the far ends of
    the usable range (lbo.geometry._rescaling.USABLE_DIAGONAL) give lam * s^2 of a unit-size cloud."""
    p = sphere_points(300)
    ref = lbo.eigenbasis(PointCloud(p), 10).values
    values = lbo.eigenbasis(PointCloud(p * s), 10).values * s**2
    assert np.abs(values - ref).max() <= 1e-10 * ref.max()
