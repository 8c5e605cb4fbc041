"""Tests for the procedural creatures: topology, triangle quality, correspondence, isometry,
part scaling, determinism and input validation."""

from __future__ import annotations

import numpy as np
import pytest

from lbo_notebooks import Mesh
from lbo_notebooks.shapes import _creatures as C
from lbo_notebooks.analyses import _distortion as D
from lbo_notebooks.operators import corner_angles

N = 3000  # small meshes keep the file fast; one test uses 10,000


@pytest.fixture(scope="module", params=["dog", "horse"])
def family(request: pytest.FixtureRequest) -> tuple[str, dict[str, Mesh]]:
    return request.param, C.creature_poses(request.param, n_vertices=N)


def _min_angles(mesh: Mesh) -> np.ndarray:
    """Smallest angle of each triangle, in degrees."""
    return np.degrees(corner_angles(mesh)).min(axis=1)


def _signed_volume(mesh: Mesh) -> float:
    p = mesh.vertices[mesh.faces]
    return float(np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum() / 6.0)


def test_tables() -> None:
    assert set(C.SPECIES) >= {"dog", "horse"}
    assert len(C.POSES) >= 6


def test_topology_and_orientation(family: tuple[str, dict[str, Mesh]]) -> None:
    _, poses = family
    for name, m in poses.items():
        assert m.is_closed, name
        assert m.n_components == 1, name
        assert m.euler_characteristic == 2, name
        assert np.all(m.edge_face_counts == 2), name  # edge-manifold (Mesh also checks > 2)
        assert _signed_volume(m) > 0, f"{name}: normals point inward"
        # Mesh(check=True) re-validates consistent orientation and manifoldness.
        Mesh(m.vertices, m.faces)


def test_outward_normals_point_away_from_body(family: tuple[str, dict[str, Mesh]]) -> None:
    # A point a little outside along each face normal has winding number ~0, inside ~1.
    igl = pytest.importorskip("igl")

    _, poses = family
    m = poses["standing"]
    eps = 0.2 * m.mean_edge_length
    centres = m.vertices[m.faces].mean(axis=1)[::7]
    normals = m.face_normals[::7]
    outside = igl.winding_number(m.vertices, m.faces, centres + eps * normals)
    inside = igl.winding_number(m.vertices, m.faces, centres - eps * normals)
    assert np.median(np.abs(outside)) < 0.05 and np.median(inside) > 0.95


def test_triangle_quality(family: tuple[str, dict[str, Mesh]]) -> None:
    _, poses = family
    for name, m in poses.items():
        a = _min_angles(m)
        assert a.min() >= 5.0, name
        assert np.mean(a >= 25.0) >= 0.9, name


def test_poses_share_triangulation(family: tuple[str, dict[str, Mesh]]) -> None:
    _, poses = family
    faces = poses["standing"].faces
    assert {"standing", "walking", "galloping", "sitting", "head_turned", "tail_raised"} <= set(poses)
    for name, m in poses.items():
        assert np.array_equal(m.faces, faces), name
        if name != "standing":
            assert not np.allclose(m.vertices, poses["standing"].vertices), f"{name} did not move"


def test_poses_nearly_isometric(family: tuple[str, dict[str, Mesh]]) -> None:
    # pose_distortion itself is checked against exact oracles in test_pose_distortion_oracles.
    _, poses = family
    for name, m in poses.items():
        d = D.pose_distortion(poses["standing"], m, n_samples=50)
        assert d["edge_median"] < 0.02, name
        assert d["edge_p99"] < 0.10, name
        assert d["geodesic_mean"] < 0.03, name


def test_no_interpenetration(family: tuple[str, dict[str, Mesh]]) -> None:
    # Self-intersection would put some surface points inside another part: just outside the
    # surface the winding number of the whole mesh would then be ~1 instead of ~0.
    igl = pytest.importorskip("igl")

    _, poses = family
    for name, m in poses.items():
        eps = 0.3 * m.mean_edge_length
        centres = m.vertices[m.faces].mean(axis=1)
        w = igl.winding_number(m.vertices, m.faces, centres + eps * m.face_normals)
        assert np.max(w) < 0.5, f"{name}: {np.sum(w >= 0.5)} faces lie inside another part"


def test_vertex_count_is_honoured() -> None:
    for n in (2_000, 10_000):
        m = C.creature("dog", n_vertices=n)
        assert abs(m.n_vertices - n) <= 0.1 * n, (n, m.n_vertices)


def test_deterministic() -> None:
    a = C.creature("dog", "walking", {"head": 1.3}, n_vertices=N)
    C.rig.template_for.cache_clear()
    b = C.creature("dog", "walking", {"head": 1.3}, n_vertices=N)
    assert C.rig.template_for.cache_info().misses == 1  # b was meshed again from scratch
    assert np.array_equal(a.vertices, b.vertices) and np.array_equal(a.faces, b.faces)


def test_returned_meshes_are_immutable() -> None:
    m = C.creature("dog", n_vertices=N)
    with pytest.raises(ValueError):
        m.vertices[0, 0] = 1.0
    with pytest.raises(AttributeError):
        m.vertices = np.zeros((3, 3))  # type: ignore[misc]
    assert C.creature("dog", n_vertices=N) == m


@pytest.mark.parametrize("part, factor", [("head", 1.6), ("legs", 1.3), ("tail", 0.7)])
def test_part_scaling(part: str, factor: float) -> None:
    rest = C.creature("dog", n_vertices=N)
    big = C.creature("dog", parts={part: factor}, n_vertices=N)
    assert np.array_equal(big.faces, rest.faces)
    masks = C.creature_parts("dog", n_vertices=N)
    groups = {"head": ["head"], "legs": ["front_legs", "hind_legs"], "tail": ["tail"]}[part]
    in_part = np.any([masks[g] for g in groups], axis=0)
    face_in = in_part[rest.faces].all(axis=1)
    face_out = (~in_part)[rest.faces].all(axis=1)
    ratio_in = big.face_areas[face_in].sum() / rest.face_areas[face_in].sum()
    ratio_out = big.face_areas[face_out].sum() / rest.face_areas[face_out].sum()
    assert abs(ratio_in / factor**2 - 1.0) < 0.12, ratio_in
    assert abs(ratio_out - 1.0) < 0.05, ratio_out
    # Smooth blending: triangles stay well shaped, the surface stays closed and embedded.
    a = _min_angles(big)
    assert a.min() >= 5.0 and np.mean(a >= 25.0) >= 0.9
    assert _signed_volume(big) > _signed_volume(rest) * (1.0 if factor > 1 else 0.5)


def test_dict_pose() -> None:
    rest = C.creature("dog", n_vertices=N)
    same = C.creature("dog", {"tail_base": 0.0}, n_vertices=N)
    assert np.array_equal(same.vertices, rest.vertices)
    up = C.creature("dog", {"tail_base": -30.0, "tail_mid": (-20.0, 0.0, 0.0)}, n_vertices=N)
    tail = C.creature_parts("dog", n_vertices=N)["tail"]
    assert up.vertices[tail, 2].max() > rest.vertices[tail, 2].max() + 0.05
    # Only the tail (and its blending band) moves.
    moved = np.linalg.norm(up.vertices - rest.vertices, axis=1) > 1e-9
    assert moved[tail].mean() > 0.9 and moved[~tail].mean() < 0.1


def test_head_turn_turns_left() -> None:
    rest = C.creature("dog", n_vertices=N)
    turned = C.creature("dog", {"neck": (0.0, 20.0, 0.0)}, n_vertices=N)
    head = C.creature_parts("dog", n_vertices=N)["head"]
    assert turned.vertices[head, 1].mean() > rest.vertices[head, 1].mean() + 0.03


def test_parts_partition_vertices() -> None:
    masks = C.creature_parts("dog", n_vertices=N)
    total = np.sum([m.astype(int) for m in masks.values()], axis=0)
    assert np.all(total == 1)
    assert set(masks) == {"torso", "neck", "head", "tail", "front_legs", "hind_legs"}


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(species="cat"), "species"),
        (dict(pose="flying"), "pose"),
        (dict(pose={"wing": 10.0}), "joint"),
        (dict(pose={"neck": (1.0, 2.0)}), "pitch"),
        (dict(pose={"neck": 120.0}), "90"),
        (dict(pose={"neck": float("nan")}), "finite"),
        (dict(parts={"wings": 2.0}), "part"),
        (dict(parts={"head": -1.0}), "factor"),
        (dict(parts=[("head", 2.0)]), "dict"),
        (dict(n_vertices=100), "n_vertices"),
        (dict(n_vertices=3000.5), "n_vertices"),
    ],
)
def test_bad_input_raises(kwargs: dict, match: str) -> None:
    args = dict(n_vertices=N) | kwargs
    with pytest.raises(ValueError, match=match):
        C.creature(**args)


def test_pose_distortion_oracles() -> None:
    rest = C.creature("dog", n_vertices=N)
    zero = D.pose_distortion(rest, rest)
    assert zero == {"edge_median": 0.0, "edge_p99": 0.0, "geodesic_mean": 0.0}
    # A uniform scaling by 1.1 changes every length, hence every geodesic, by exactly 10%.
    grown = D.pose_distortion(rest, rest.with_vertices(1.1 * rest.vertices))
    for value in grown.values():
        assert value == pytest.approx(0.1, rel=1e-9)
    with pytest.raises(ValueError, match="triangulation"):
        D.pose_distortion(rest, C.creature("horse", n_vertices=N))
    with pytest.raises(ValueError, match="n_samples"):
        D.pose_distortion(rest, rest, n_samples=1)


def test_isometry_at_10k() -> None:
    poses = C.creature_poses("dog", n_vertices=10_000)
    for name, m in poses.items():
        d = D.pose_distortion(poses["standing"], m)
        assert d["edge_median"] < 0.02 and d["edge_p99"] < 0.10 and d["geodesic_mean"] < 0.03, (name, d)


def test_body_key_turns_rigidly() -> None:
    rest = C.creature("dog", n_vertices=N)
    turned = C.creature("dog", {"body": (0.0, 90.0, 0.0)}, n_vertices=N)
    assert D.pose_distortion(rest, turned, n_samples=5)["edge_p99"] < 1e-12
    # Facing +y now: the long axis of the bounding box swapped from x to y.
    extent = np.ptp(turned.vertices, axis=0)
    assert extent[1] > 2 * extent[0]


def test_poses_are_read_only() -> None:
    with pytest.raises(TypeError):
        C.POSES["new"] = {}  # type: ignore[index]
    with pytest.raises(TypeError):
        C.POSES["walking"]["neck"] = (0.0, 0.0, 0.0)  # type: ignore[index]


def test_vertex_strain_oracles_and_rigid_bones(family: tuple[str, dict[str, Mesh]]) -> None:
    species, poses = family
    rest = poses["standing"]
    # Oracles: a rigid motion gives zero, a uniform scaling by 1.1 gives exactly 10% everywhere.
    R = np.linalg.qr(np.random.default_rng(0).normal(size=(3, 3)))[0]
    assert D.vertex_strain(rest, rest.with_vertices(rest.vertices @ R.T + 1.0)).max() < 1e-12
    assert np.allclose(D.vertex_strain(rest, rest.with_vertices(1.1 * rest.vertices)), 0.1, rtol=1e-9)
    # Outside the joint bands (and their one-ring) every pose moves the body rigidly.
    bands = C.joint_bands(species, n_vertices=N)
    e = rest.edges
    near = bands.copy()
    near[e[bands[e[:, 0]] | bands[e[:, 1]]].ravel()] = True
    assert 0 < (~near).sum() and bands.any()
    for name, m in poses.items():
        strain = D.vertex_strain(rest, m)
        assert strain[~near].max() < 1e-10, name
        if name != "standing":
            assert strain[bands].max() > 1e-3, name  # the bands are where the pose bends
    with pytest.raises(ValueError, match="triangulation"):
        D.vertex_strain(rest, C.creature("horse" if species == "dog" else "dog", n_vertices=N))
    with pytest.raises(ValueError, match="Mesh"):
        D.vertex_strain(rest, rest.vertices)  # type: ignore[arg-type]
