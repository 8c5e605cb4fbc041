"""Tests for lbo_notebooks.operators._curvature: Gauss–Bonnet, sphere curvature, and the metrics |K|^alpha g."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from hypothesis import given, settings
from hypothesis import strategies as st

from lbo_notebooks import Mesh, eigenbasis, shapes
from lbo_notebooks.shapes import _creatures as creatures
from lbo_notebooks.operators._curvature import (
    DEFAULT_FLOOR,
    angle_defects,
    conformal_factor,
    gaussian_curvature,
    metric_curvature,
    metric_mass_matrix,
)
from lbo_notebooks.operators import MASS_KINDS, mass_matrix, stiffness_matrix

EPS = np.finfo(float).eps

ALPHAS = (0.0, 0.25, 0.4, 0.5, 0.75, 1.0)


@pytest.fixture(scope="module")
def bumpy() -> Mesh:
    return shapes.bumpy_sphere(3)


@pytest.fixture(scope="module")
def curved_shapes(bumpy: Mesh) -> list[Mesh]:
    creature = creatures.creature("dog", n_vertices=2000)
    return [bumpy, shapes.torus(n_major=24, n_minor=10), shapes.ellipsoid(subdivisions=3), creature]


# --- Gaussian curvature ---------------------------------------------------------------------------
@pytest.mark.parametrize(
    "make",
    [
        lambda: shapes.icosphere(3),
        lambda: shapes.bumpy_sphere(3),
        lambda: shapes.torus(n_major=32, n_minor=12),
        lambda: shapes.disk(n_rings=6),
        lambda: shapes.rectangle(2.0, 1.0, 6, 3),
        lambda: shapes.ellipsoid(3.0, 1.0, 0.3, subdivisions=3),
    ],
    ids=["icosphere", "bumpy_sphere", "torus", "disk", "rectangle", "ellipsoid"],
)
def test_gauss_bonnet(make) -> None:
    mesh = make()
    K = gaussian_curvature(mesh)
    a = mass_matrix(mesh, "voronoi").diagonal()
    total = float((K * a).sum())
    assert total == pytest.approx(2 * np.pi * mesh.euler_characteristic, abs=1e-10)
    assert np.allclose(K * a, angle_defects(mesh), rtol=1e-12, atol=64 * EPS * 2 * np.pi)  # a sum of 2 pi - angles


def test_gauss_bonnet_with_a_hole() -> None:
    # An icosphere with one vertex's fan removed: a disk (chi = 1) whose boundary is a curved loop.
    sphere = shapes.icosphere(2)
    keep = ~np.any(sphere.faces == 0, axis=1)
    f = sphere.faces[keep]
    used = np.unique(f)
    remap = np.full(sphere.n_vertices, -1)
    remap[used] = np.arange(used.size)
    mesh = Mesh(sphere.vertices[used], remap[f])
    assert mesh.euler_characteristic == 1
    total = float(angle_defects(mesh).sum())
    assert total == pytest.approx(2 * np.pi, abs=1e-10)


def test_angle_defect_matches_hand_computed_tetrahedron() -> None:
    # Regular tetrahedron: three equilateral angles at each vertex, defect 2 pi - pi = pi.
    v = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], dtype=float)
    f = np.array([[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]])
    mesh = Mesh(v, f)
    assert np.allclose(angle_defects(mesh), np.pi, atol=64 * EPS * np.pi)
    # Right triangle (single face, all vertices on the boundary): defects pi - angle.
    tri = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    assert np.allclose(angle_defects(tri), [np.pi / 2, 3 * np.pi / 4, 3 * np.pi / 4], atol=64 * EPS * np.pi)


def test_angle_defects_match_libigl() -> None:
    igl = pytest.importorskip("igl")
    mesh = shapes.bumpy_sphere(2)
    ref = igl.gaussian_curvature(np.asarray(mesh.vertices), np.asarray(mesh.faces))
    assert np.allclose(angle_defects(mesh), ref, atol=1e-12)


@pytest.mark.parametrize("radius", [0.5, 2.0])
def test_sphere_curvature_is_one_over_r_squared(radius: float) -> None:
    errors = []
    for sub in (2, 3, 4):
        K = gaussian_curvature(shapes.icosphere(sub, radius=radius))
        errors.append(float(np.abs(K * radius**2 - 1).max()))
    # Inscribed polyhedra: error O(h^2), about 4x smaller per subdivision.
    assert errors[1] < 0.01 and errors[2] < 0.003
    assert errors[0] > 3 * errors[1] > 9 * errors[2]


def test_flat_surfaces_have_zero_interior_curvature() -> None:
    for mesh in (shapes.rectangle(1.0, 0.7, 7, 5), shapes.disk(n_rings=5)):
        K = gaussian_curvature(mesh)
        interior = np.setdiff1d(np.arange(mesh.n_vertices), mesh.boundary_vertices)
        assert np.abs(K[interior]).max() < 1e-10 / mesh.mean_edge_length**2


def test_curvature_is_cached_and_read_only(bumpy: Mesh) -> None:
    K = gaussian_curvature(bumpy)
    assert gaussian_curvature(bumpy) is K
    assert metric_curvature(bumpy) is metric_curvature(bumpy, floor=DEFAULT_FLOOR)
    with pytest.raises(ValueError):
        K[0] = 1.0


# --- metric curvature and conformal factor --------------------------------------------------------
def test_metric_curvature_scales_as_inverse_area(bumpy: Mesh) -> None:
    rho = metric_curvature(bumpy)
    big = bumpy.with_vertices(3.0 * bumpy.vertices)
    assert np.allclose(metric_curvature(big) * 9.0, rho, rtol=1e-12)
    # A one-ring average of |K| with a floor: never below the floor, never above max |K|.
    floor = DEFAULT_FLOOR * 4 * np.pi / bumpy.area
    assert rho.min() >= floor
    assert rho.max() <= np.abs(gaussian_curvature(bumpy)).max() * (1 + 1e-12)


def test_metric_curvature_follows_the_one_ring_definition(bumpy: Mesh) -> None:
    d = np.abs(angle_defects(bumpy))
    a = mass_matrix(bumpy).diagonal()
    i = 17
    ring = np.unique(bumpy.edges[np.any(bumpy.edges == i, axis=1)])  # includes i itself
    expected = max(d[ring].sum() / a[ring].sum(), DEFAULT_FLOOR * 4 * np.pi / bumpy.area)
    assert metric_curvature(bumpy)[i] == pytest.approx(expected, rel=1e-12)


def test_conformal_factor(bumpy: Mesh) -> None:
    rho = metric_curvature(bumpy)
    assert np.array_equal(conformal_factor(bumpy, 0.0), np.ones(bumpy.n_vertices))
    assert np.allclose(conformal_factor(bumpy, 0.5), np.sqrt(rho))
    face = conformal_factor(bumpy, 1.0, where="face")
    assert face.shape == (bumpy.n_faces,)
    assert np.allclose(face, rho[bumpy.faces].mean(axis=1))


# --- the metric mass matrix -----------------------------------------------------------------------
@pytest.mark.parametrize("kind", MASS_KINDS)
def test_alpha_zero_is_exactly_the_regular_mass(bumpy: Mesh, kind: str) -> None:
    A0 = metric_mass_matrix(bumpy, 0.0, mass_kind=kind)
    A = mass_matrix(bumpy, kind)
    assert (A0 != A).nnz == 0


def test_alpha_zero_is_exactly_the_regular_eigenbasis() -> None:
    mesh = shapes.bumpy_sphere(4)  # large enough for the sparse (ARPACK) path
    s0 = eigenbasis(mesh, 20, alpha=0.0, curvature_floor=0.5)
    s = eigenbasis(mesh, 20)
    assert np.array_equal(s0.values, s.values)
    assert np.array_equal(s0.vectors, s.vectors)


@pytest.mark.parametrize("kind", MASS_KINDS)
def test_lumped_and_consistent_metric_masses(bumpy: Mesh, kind: str) -> None:
    alpha = 0.6
    A = metric_mass_matrix(bumpy, alpha, mass_kind=kind)
    assert (A != A.T).nnz == 0
    if kind == "consistent":
        # Each triangle's local matrix is scaled by rho_t^alpha: entries sum to sum_t rho_t^a |t|,
        # and the sparsity pattern is that of the regular consistent mass.
        rho_t = conformal_factor(bumpy, alpha, where="face")
        assert float(A.sum()) == pytest.approx(float((rho_t * bumpy.face_areas).sum()), rel=1e-12)
        assert A.nnz == mass_matrix(bumpy, "consistent").nnz
    else:
        expected = mass_matrix(bumpy, kind).diagonal() * metric_curvature(bumpy) ** alpha
        assert np.allclose(A.diagonal(), expected, rtol=1e-14)
        assert A.nnz == bumpy.n_vertices


def _smallest_pivot(A) -> float:
    """Smallest pivot of a symmetric LDL^T-like factorisation: positive iff A is positive definite."""

    lu = spla.splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    assert np.array_equal(lu.perm_r, lu.perm_c), "the factorisation pivoted off the diagonal"
    return float(lu.U.diagonal().min())


def test_smallest_pivot_detects_indefinite_matrices(bumpy: Mesh) -> None:
    # The positive-definiteness oracle below must be able to fail.
    M = mass_matrix(bumpy, "consistent")
    lowest = scipy.linalg.eigvalsh(M.toarray())[0]
    assert _smallest_pivot(M) > 0
    assert _smallest_pivot((M - 1.5 * lowest * sp.identity(M.shape[0])).tocsr()) < 0


@pytest.mark.parametrize("kind", MASS_KINDS)
def test_mass_is_positive_definite_for_every_alpha(curved_shapes: list[Mesh], kind: str) -> None:
    flat = shapes.rectangle(1.0, 0.7, 10, 7)
    for mesh in [*curved_shapes, flat]:
        for alpha in ALPHAS:
            A = metric_mass_matrix(mesh, alpha, mass_kind=kind)
            assert np.all(np.isfinite(A.data))
            if kind == "consistent":
                assert _smallest_pivot(A) > 0
            else:
                assert A.diagonal().min() > 0


@pytest.mark.parametrize("kind", MASS_KINDS)
def test_flat_rectangle_metric_is_a_constant_multiple(kind: str) -> None:
    # K = 0 inside; the boundary turning angles are not Gaussian curvature, so rho is the floor
    # everywhere and the metric is c * g with c = (floor * 4 pi / area)^alpha.
    mesh = shapes.rectangle(1.0, 0.73, 12, 9)
    floor = 0.01
    c = (floor * 4 * np.pi / mesh.area) ** 0.7
    A = metric_mass_matrix(mesh, 0.7, mass_kind=kind, floor=floor)
    assert abs(A - c * mass_matrix(mesh, kind)).max() < 1e-12 * c * mass_matrix(mesh, kind).max()
    s0 = eigenbasis(mesh, 12, mass_kind=kind)
    s = eigenbasis(mesh, 12, mass_kind=kind, alpha=0.7, curvature_floor=floor)
    assert np.allclose(s.values[1:] * c, s0.values[1:], rtol=1e-9)
    # Same eigenfunctions, up to the factor sqrt(c) and a sign (the rectangle's symmetry makes the
    # deterministic sign rule a tie-break between mirror-image peaks).
    v = s.vectors * np.sqrt(c)
    sign = np.sign(np.einsum("ij,ij->j", v, s0.vectors))
    assert np.allclose(v * sign, s0.vectors, atol=1e-8)


# --- invariance -----------------------------------------------------------------------------------
@pytest.mark.parametrize("kind, subdivisions", [("voronoi", 4), ("barycentric", 3), ("consistent", 3)])
def test_alpha_one_spectrum_is_scale_invariant(kind: str, subdivisions: int) -> None:
    mesh = shapes.bumpy_sphere(subdivisions)  # 4: the sparse (ARPACK) path, 3: the dense one
    big = mesh.with_vertices(3.0 * mesh.vertices)
    a = eigenbasis(mesh, 30, alpha=1.0, mass_kind=kind).values
    b = eigenbasis(big, 30, alpha=1.0, mass_kind=kind).values
    assert np.abs(b[1:] / a[1:] - 1).max() < 1e-8
    # The regular spectrum is not: it falls by 1 / 9.
    c = eigenbasis(big, 30, mass_kind=kind).values
    assert np.abs(c[1:] * 9 / eigenbasis(mesh, 30, mass_kind=kind).values[1:] - 1).max() < 1e-8


@settings(max_examples=6, deadline=None)
@given(
    alpha=st.floats(0.0, 1.0),
    scale=st.floats(0.2, 5.0),
    kind=st.sampled_from(MASS_KINDS),
)
def test_eigenvalues_scale_as_s_to_minus_two_one_minus_alpha(alpha: float, scale: float, kind: str) -> None:
    mesh = shapes.bumpy_sphere(2, seed=3)
    scaled = mesh.with_vertices(scale * mesh.vertices)
    a = eigenbasis(mesh, 15, alpha=alpha, mass_kind=kind).values
    b = eigenbasis(scaled, 15, alpha=alpha, mass_kind=kind).values
    assert np.allclose(b[1:], a[1:] * scale ** (-2 * (1 - alpha)), rtol=1e-9)


def test_metric_spectrum_is_rigid_motion_invariant(bumpy: Mesh) -> None:
    rng = np.random.default_rng(0)
    q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    moved = bumpy.with_vertices(bumpy.vertices @ q.T + [1.0, -2.0, 0.5])
    a = eigenbasis(bumpy, 12, alpha=0.5).values
    b = eigenbasis(moved, 12, alpha=0.5).values
    assert np.allclose(a, b, rtol=1e-9, atol=1e-10)


@pytest.mark.parametrize("kind", ["voronoi", "consistent"])
def test_unit_sphere_every_alpha_gives_l_l_plus_one(kind: str) -> None:
    mesh = shapes.icosphere(3)
    ell = np.repeat(np.arange(6), 2 * np.arange(6) + 1)
    for alpha in (0.5, 1.0):
        values = eigenbasis(mesh, 36, alpha=alpha, mass_kind=kind).values
        assert np.abs(values[1:] / (ell * (ell + 1))[1:] - 1).max() < 0.06


def test_stiffness_is_untouched_by_alpha(bumpy: Mesh) -> None:
    s = eigenbasis(bumpy, 5, alpha=1.0)
    assert (s.stiffness != stiffness_matrix(bumpy)).nnz == 0
    assert np.allclose(s.vectors.T @ s.mass @ s.vectors, np.eye(5), atol=1e-10)


# --- bad input ------------------------------------------------------------------------------------
@pytest.mark.parametrize("alpha", [-0.1, 1.5, np.nan, np.inf, "1", None, True, [0.5]])
def test_bad_alpha(bumpy: Mesh, alpha) -> None:
    with pytest.raises(ValueError, match="alpha"):
        metric_mass_matrix(bumpy, alpha)
    with pytest.raises(ValueError, match="alpha"):
        conformal_factor(bumpy, alpha)


@pytest.mark.parametrize("floor", [0.0, -1e-3, np.nan, np.inf, "small", None, True])
def test_bad_floor(bumpy: Mesh, floor) -> None:
    with pytest.raises(ValueError, match="floor"):
        metric_mass_matrix(bumpy, 0.5, floor=floor)
    with pytest.raises(ValueError, match="floor"):
        metric_curvature(bumpy, floor=floor)
    if floor is not None:  # None means "the default" in eigenbasis
        with pytest.raises(ValueError, match="floor"):
            eigenbasis(bumpy, 5, alpha=0.5, curvature_floor=floor)


def test_bad_kind_and_where(bumpy: Mesh) -> None:
    with pytest.raises(ValueError, match="mass_kind must be one of"):
        metric_mass_matrix(bumpy, 0.5, mass_kind="cotan")
    with pytest.raises(ValueError, match="where"):
        conformal_factor(bumpy, 0.5, where="edge")
    with pytest.raises(ValueError, match="Mesh"):
        gaussian_curvature(np.zeros((3, 3)))


# --- jittered torus: an exact surface with an irregular triangulation ------------------------------
def test_jittered_torus_is_the_torus_with_its_exact_curvature():
    from lbo_notebooks.shapes import jittered_torus

    flat, K0 = jittered_torus(12, 0.0)
    assert np.array_equal(flat.vertices, shapes.torus(1.0, 0.4, 30, 12).vertices)
    mesh, K = jittered_torus(30, 0.5, seed=1)
    x, y, z = mesh.vertices.T
    on_surface = (np.hypot(x, y) - 1.0) ** 2 + z**2 - 0.4**2
    assert np.abs(on_surface).max() < 1e-12 * 0.4**2 * 100
    assert not np.allclose(mesh.vertices, jittered_torus(30, 0.0)[0].vertices)
    # the analytic K integrates to 0 (chi = 0), as the angle defects do exactly
    a = mass_matrix(mesh, "voronoi").diagonal()
    assert abs(np.sum(K * a)) < 0.05 * np.sum(np.abs(K) * a)
    # on a regular fine grid the angle-defect curvature matches K where |K| is not small
    fine, Kf = jittered_torus(80, 0.0)
    strong = np.abs(Kf) > 0.5
    assert np.median(np.abs(gaussian_curvature(fine)[strong] / Kf[strong] - 1)) < 0.01


@pytest.mark.parametrize("kwargs, match", [({"n_minor": 2}, "n_minor"), ({"n_minor": 8, "jitter": 1.0}, "jitter"),
                                           ({"n_minor": 8, "minor_radius": 2.0}, "minor_radius")])
def test_jittered_torus_bad_arguments(kwargs, match):
    from lbo_notebooks.shapes import jittered_torus

    with pytest.raises(ValueError, match=match):
        jittered_torus(**kwargs)
