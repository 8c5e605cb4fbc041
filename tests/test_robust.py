"""Tests for lbo_notebooks.operators._robust and the laplacian= dispatch of eigenbasis: the tufted Laplacian."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.sparse as sp

import lbo_notebooks as lbo
from lbo_notebooks import Mesh, MeshError, shapes
from lbo_notebooks.operators import mass_matrix, stiffness_matrix
from lbo_notebooks.operators import (
    LaplacianWarning,
    cotan_defects,
    non_manifold_vertices,
    robust_operators,
)

from .test_io import BROKEN, write

L_SPHERE = np.repeat(np.arange(5), 2 * np.arange(5) + 1)  # l of the first 25 sphere eigenvalues
EXACT_SPHERE = (L_SPHERE * (L_SPHERE + 1)).astype(float)


def grid(n: int = 6) -> Mesh:
    """A regular right-triangle grid of the unit square: every edge is (intrinsic) Delaunay."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    v = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    i = np.arange(n - 1)
    a = (i[:, None] * n + i[None, :]).ravel()
    f = np.concatenate([np.column_stack([a, a + 1, a + n + 1]), np.column_stack([a, a + n + 1, a + n])])
    return Mesh(v, f)


def fins_and_pieces(n_pieces: int = 4) -> Mesh:
    """``n_pieces`` icospheres, each with an extra fin on one edge (a non-manifold edge)."""
    ball = shapes.icosphere(2)
    vs, fs, offset = [], [], 0
    for k in range(n_pieces):
        a, b = ball.faces[0, 0], ball.faces[0, 1]
        tip = 1.6 * (ball.vertices[a] + ball.vertices[b]) / 2
        v = np.concatenate([ball.vertices, tip[None]]) + [3.0 * k, 0, 0]
        f = np.concatenate([ball.faces, [[a, b, ball.n_vertices]]])
        vs.append(v)
        fs.append(f + offset)
        offset += len(v)
    return Mesh(np.concatenate(vs), np.concatenate(fs), check=False)


def rel_max(a: sp.spmatrix, b: sp.spmatrix) -> float:
    return float(abs(a - b).max() / abs(b).max())


# --- equals the cotangent operator where the mesh is intrinsic Delaunay ---------------------------
@pytest.mark.parametrize("mesh", [shapes.icosphere(3), grid()], ids=["icosphere", "grid"])
def test_robust_operator_is_the_cotangent_pair_on_an_intrinsic_delaunay_mesh(mesh):
    W, A = robust_operators(mesh)
    eps = np.finfo(float).eps
    assert rel_max(W, stiffness_matrix(mesh)) < 100 * eps * np.sqrt(mesh.n_vertices)
    assert rel_max(A, mass_matrix(mesh, "barycentric")) < 100 * eps * np.sqrt(mesh.n_vertices)


def test_robust_operator_flips_a_non_delaunay_mesh_to_non_negative_weights():
    # Squash the grid's diagonal direction: many cotangent weights turn negative, the intrinsic
    # Delaunay ones never are (the defining property of the intrinsic Delaunay triangulation).
    m = grid(8)
    squashed = m.with_vertices(m.vertices @ np.array([[1, 0, 0], [0.9, 0.2, 0], [0, 0, 1]]))
    W_cot = stiffness_matrix(squashed)
    W_rob, A_rob = robust_operators(squashed)
    off = lambda W: (W - sp.diags(W.diagonal())).tocoo().data  # noqa: E731
    assert off(W_cot).max() > 0.1 * abs(W_cot).max()  # positive off-diagonal = negative edge weight
    assert off(W_rob).max() <= 1e-12 * abs(W_rob).max()
    # Same surface, same area and the same constant kernel.
    np.testing.assert_allclose(A_rob.sum(), squashed.area, rtol=1e-12)
    assert abs(W_rob @ np.ones(squashed.n_vertices)).max() < 1e-12 * abs(W_rob).max()


def test_robust_spectrum_converges_on_the_sphere():
    errors = []
    for level in (2, 3, 4):
        s = lbo.eigenbasis(shapes.icosphere(level), 25, laplacian="robust")
        errors.append(np.abs(s.values[1:] / EXACT_SPHERE[1:] - 1).max())
    assert errors[0] > errors[1] > errors[2]
    assert errors[1] / errors[2] > 3.0  # O(h^2): about 4 per halving of h
    assert errors[2] < 0.01


# --- defects -----------------------------------------------------------------------------------
def test_non_manifold_vertex_detection():
    bowtie = Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [-1, 0, 0], [-1, -1, 0]], [[0, 1, 2], [0, 3, 4]])
    assert non_manifold_vertices(bowtie).tolist() == [0]
    assert non_manifold_vertices(shapes.disk(n_rings=3)).size == 0  # boundary vertices are manifold
    assert non_manifold_vertices(shapes.icosphere(2)).size == 0
    assert "1 non-manifold vertex" in cotan_defects(bowtie)[0]


def _fans_by_brute_force(mesh: Mesh) -> list[int]:
    """Vertices whose faces split into more than one group joined by shared edges, face pair by face pair."""
    from scipy.sparse.csgraph import connected_components

    f = mesh.faces
    out = []
    for v in range(mesh.n_vertices):
        around = f[(f == v).any(axis=1)]
        shared = np.array([[len(set(a) & set(b)) >= 2 for b in around] for a in around])
        if around.shape[0] > 1 and connected_components(sp.csr_matrix(shared), directed=False)[0] > 1:
            out.append(v)
    return out


def _glued(a: Mesh, b: Mesh, vertex_a: int, vertex_b: int) -> Mesh:
    """``a`` and a moved copy of ``b`` sharing one vertex and nothing else."""
    index = np.arange(b.n_vertices) + a.n_vertices - (np.arange(b.n_vertices) > vertex_b)
    index[vertex_b] = vertex_a
    v = np.vstack([a.vertices, np.delete(b.vertices + 3.0, vertex_b, axis=0)])
    return Mesh(v, np.vstack([a.faces, index[b.faces]]), check=False)


def test_non_manifold_vertices_agree_with_a_face_by_face_count():
    # Two closed fans (two spheres touching), a closed and an open one, two open ones, and random
    # pieces of a sphere (bowties wherever a fan breaks): each vertex's faces, grouped directly.
    ball, disk = shapes.icosphere(1), shapes.disk(n_rings=3)
    meshes = [_glued(ball, ball, 0, 5), _glued(disk, ball, 0, 3), _glued(disk, disk, 7, 7)]
    rng = np.random.default_rng(3)
    for _ in range(8):
        faces = shapes.icosphere(2).faces[rng.random(320) < 0.6]
        used, faces = np.unique(faces, return_inverse=True)
        meshes.append(Mesh(shapes.icosphere(2).vertices[used], faces.reshape(-1, 3), check=False))
    for mesh in meshes:
        expected = _fans_by_brute_force(mesh)
        assert expected and non_manifold_vertices(mesh).tolist() == expected


def test_needle_triangle_is_a_defect():
    v = [[0, 0, 0], [1, 0, 0], [0.5, 1e-6, 0], [0.5, -1, 0]]
    mesh = Mesh(v, [[0, 1, 2], [1, 0, 3]])
    assert any("needle" in r for r in cotan_defects(mesh))
    with pytest.warns(LaplacianWarning, match="needle"):
        lbo.eigenbasis(mesh, 3)


def test_auto_uses_robust_with_a_warning_and_one_zero_eigenvalue_per_component():
    mesh = fins_and_pieces(4)
    assert mesh.n_components == 4
    with pytest.warns(LaplacianWarning) as record:
        s = lbo.eigenbasis(mesh, 8)
    message = str(record[0].message)
    assert "4 non-manifold edges" in message and "4 connected components" in message
    scale = s.values[4]
    assert np.all(np.abs(s.values[:4]) < 1e-8 * scale)  # one constant per component
    assert s.values[4] > 0.1  # then real shape: ~2 for a unit sphere
    explicit = lbo.eigenbasis(mesh, 8, laplacian="robust")
    np.testing.assert_allclose(explicit.values, s.values, rtol=0, atol=1e-10 * scale)
    # The Spectrum API works with the robust mass: A-orthonormal vectors, exact reconstruction.
    gram = s.vectors.T @ (s.mass @ s.vectors)
    np.testing.assert_allclose(gram, np.eye(8), atol=1e-10)
    f = s.vectors @ np.arange(1.0, 9.0)
    assert s.error(f) < 1e-10 * np.sqrt(f @ (s.mass @ f))


def test_cotan_on_a_non_manifold_mesh_is_refused_with_the_fix():
    with pytest.raises(MeshError, match="laplacian='robust'"):
        lbo.eigenbasis(fins_and_pieces(1), 4, laplacian="cotan")


def test_a_clean_mesh_keeps_the_cotangent_path_without_warning():
    mesh = shapes.icosphere(2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        auto = lbo.eigenbasis(mesh, 9)
    cotan = lbo.eigenbasis(mesh, 9, laplacian="cotan")
    np.testing.assert_array_equal(auto.values, cotan.values)


@pytest.mark.parametrize(
    "kwargs,words",
    [
        ({"laplacian": "tufted"}, "laplacian must be one of"),
        ({"laplacian": "robust", "mass_kind": "consistent"}, "own lumped"),
        ({"laplacian": "robust", "alpha": 0.5}, "alpha"),
    ],
)
def test_bad_laplacian_arguments(kwargs, words):
    with pytest.raises(ValueError, match=words):
        lbo.eigenbasis(shapes.icosphere(1), 4, **kwargs)


def test_operators_tuple_with_laplacian_is_refused_and_unreferenced_vertices_named():
    m = shapes.icosphere(1)
    with pytest.raises(ValueError, match="tuple"):
        lbo.eigenbasis((stiffness_matrix(m), mass_matrix(m)), 4, laplacian="robust")
    loose = Mesh(np.concatenate([m.vertices, [[5, 5, 5]]]), m.faces, check=False)
    with pytest.raises(MeshError, match="clean_mesh"):
        lbo.eigenbasis(loose, 4, laplacian="robust")


def test_robust_operators_do_not_touch_the_mesh_and_return_fresh_copies():
    m = shapes.icosphere(1)
    W1, _ = robust_operators(m)
    W1.data[:] = 0.0
    W2, _ = robust_operators(m)
    assert abs(W2).max() > 0


# --- the broken-file corpus through the one documented line ---------------------------------------
@pytest.mark.parametrize("name,content", [c[1:3] for c in BROKEN], ids=[c[0] for c in BROKEN])
def test_every_broken_file_gets_a_spectrum_or_a_mesh_error(tmp_path, name, content):
    path = write(tmp_path / name, content)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mesh = lbo.load_mesh(path, clean=True)
            s = lbo.eigenbasis(mesh, min(3, mesh.n_vertices))
    except MeshError as exc:
        assert name in str(exc)
        return
    assert np.all(np.isfinite(s.values)) and np.all(np.diff(s.values) >= 0)
    top = abs(s.stiffness).max() / s.mass.diagonal().min()  # the scale of the spectrum
    zeros = int(np.sum(np.abs(s.values) <= 1e-9 * top))
    assert zeros == min(mesh.n_components, s.k)


def test_the_non_manifold_and_moebius_files_now_load_through_the_documented_line(tmp_path):
    for case in ("off-non-manifold", "off-moebius"):
        _, name, content, _ = next(c for c in BROKEN if c[0] == case)
        path = write(tmp_path / name, content)
        with pytest.raises(MeshError):
            lbo.load_mesh(path)  # without clean=True: refused, as before
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            s = lbo.eigenbasis(lbo.load_mesh(path, clean=True), 3)
        assert abs(s.values[0]) < 1e-10 * s.values[-1] and s.values[1] > 0


@pytest.mark.parametrize("laplacian", ["cotan", "robust"])
def test_forty_pieces_give_forty_zero_eigenvalues_through_the_sparse_solver(laplacian):
    """A scan in many pieces: shift-invert Lanczos must find the whole zero cluster, not part of it."""
    ball = shapes.icosphere(1)
    sizes = np.random.default_rng(0).uniform(0.5, 2.0, 40)
    v = np.vstack([ball.vertices * r + [3.0 * k, 0, 0] for k, r in enumerate(sizes)])
    f = np.vstack([ball.faces + k * ball.n_vertices for k in range(40)])
    mesh = Mesh(v, f)
    assert mesh.n_vertices > 600  # above the dense solver's limit
    s = lbo.eigenbasis(mesh, 43, laplacian=laplacian)
    scale = abs(s.stiffness).max() / s.mass.diagonal().min()
    assert int(np.sum(np.abs(s.values) < 1e-9 * scale)) == 40
    # Then the largest ball's first nonzero eigenvalue, 2 / r^2, three times.
    np.testing.assert_allclose(s.values[40:], 2 / sizes.max() ** 2, rtol=0.06)


def test_one_owner_chooses_the_operators_and_names_mass_kind():
    """Issue 27: laplacians owns "which (W, A) for this input"; eigenbasis is those operators + the solver."""
    import lbo_notebooks as lbo
    from lbo_notebooks.operators import laplace_beltrami

    sphere = lbo.shapes.icosphere(2)
    for options in ({}, {"mass_kind": "consistent"}, {"alpha": 0.5}, {"laplacian": "robust"}):
        W, A = laplace_beltrami(sphere, **options)
        s = lbo.eigenbasis(sphere, 5, **options)
        assert (s.stiffness != W).nnz == 0 and (s.mass != A).nnz == 0
    with pytest.raises(ValueError, match=r"mass_kind='consistent' applies to the cotangent operator only\. Leave mass_kind"):
        laplace_beltrami(sphere, laplacian="robust", mass_kind="consistent")
    with pytest.raises(ValueError, match=r"mass_kind must be one of"):
        lbo.eigenbasis(sphere, 5, mass_kind="lumped")
    with pytest.raises(ValueError, match=r"alpha must be a number in \[0, 1\]"):
        lbo.eigenbasis(sphere, 5, alpha=2.0)
