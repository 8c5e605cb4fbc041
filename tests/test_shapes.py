import numpy as np
import pytest

from lbo_notebooks import shapes


@pytest.mark.parametrize("s, n", [(0, 12), (1, 42), (3, 642), (5, 10242)])
def test_icosphere_vertex_counts_and_radius(s, n):
    m = shapes.icosphere(s, radius=2.5)
    assert m.n_vertices == n and m.euler_characteristic == 2 and m.is_closed
    np.testing.assert_allclose(np.linalg.norm(m.vertices, axis=1), 2.5)


def test_outward_orientation_of_closed_shapes():
    for m in (shapes.icosphere(2), shapes.ellipsoid(), shapes.torus(), shapes.bumpy_sphere(3)):
        # Signed volume (divergence theorem) is positive for outward-facing triangles.
        v = m.vertices[m.faces]
        volume = np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6
        assert volume > 0


def test_torus_and_disk_and_rectangle_geometry():
    t = shapes.torus(2.0, 0.5, n_major=200, n_minor=60)
    assert t.area == pytest.approx(4 * np.pi**2 * 2.0 * 0.5, rel=2e-3)
    assert t.euler_characteristic == 0
    d = shapes.disk(2.0, n_rings=30)
    assert d.area == pytest.approx(np.pi * 4, rel=5e-3) and d.euler_characteristic == 1
    r = shapes.rectangle(3.0, 2.0, 6, 4)
    assert (r.n_vertices, r.n_faces) == (35, 48) and r.area == pytest.approx(6.0)
    assert np.all(r.face_normals[:, 2] > 0) and np.all(d.face_normals[:, 2] > 0)


def test_ellipsoid_axes_and_bumpy_determinism():
    e = shapes.ellipsoid(3, 2, 1, subdivisions=3)
    np.testing.assert_allclose(np.abs(e.vertices).max(axis=0), [3, 2, 1])
    a, b = shapes.bumpy_sphere(3, seed=4), shapes.bumpy_sphere(3, seed=4)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    assert not np.array_equal(a.vertices, shapes.bumpy_sphere(3, seed=5).vertices)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: shapes.icosphere(-1), "subdivisions"),
        (lambda: shapes.icosphere(2, radius=0), "radius"),
        (lambda: shapes.torus(1.0, 2.0), "smaller"),
        (lambda: shapes.rectangle(1, 1, 0, 3), "nx"),
        (lambda: shapes.disk(n_rings=0), "n_rings"),
        (lambda: shapes.ellipsoid(1, -1, 1), "b must"),
        (lambda: shapes.bumpy_sphere(3, height=np.nan), "height"),
    ],
)
def test_bad_arguments(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_scan_like_has_three_pieces_holes_and_no_stray_vertices():
    m = shapes.scan_like(3, n_holes=4, seed=1)
    assert m.n_components == 3 and len(m.boundary_edges) > 0          # pieces and holes, as in a raw scan
    used = np.zeros(m.n_vertices, dtype=bool)
    used[m.faces.ravel()] = True
    assert used.all()                                                 # vertices inside the holes dropped
    closed = shapes.scan_like(3, n_holes=0)
    assert len(closed.boundary_edges) == 0 and closed.euler_characteristic == 2 + 2 + 0
    again = shapes.scan_like(3, n_holes=4, seed=1)
    assert np.array_equal(m.vertices, again.vertices) and np.array_equal(m.faces, again.faces)
    with pytest.raises(ValueError, match="subdivisions"):
        shapes.scan_like(-1)
