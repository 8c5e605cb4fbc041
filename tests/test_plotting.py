import matplotlib
import numpy as np
import pytest

from lbo_notebooks import eigenbasis, plotting, shapes

matplotlib.use("Agg")


@pytest.fixture(scope="module")
def sphere():
    return shapes.icosphere(2)


def test_plot_mesh_draws_all_faces_with_vertex_colours(sphere):
    fig = plotting.plot_mesh(sphere, sphere.vertices[:, 2], symmetric=True, title="z")
    trace = fig.data[0]
    assert trace.type == "mesh3d" and len(trace.i) == sphere.n_faces
    np.testing.assert_allclose(trace.intensity, sphere.vertices[:, 2])
    assert trace.cmin == -trace.cmax


def test_large_meshes_are_decimated_for_display():
    big = shapes.icosphere(5)
    fig = plotting.plot_mesh(big, big.vertices[:, 0], max_faces=2000)
    trace = fig.data[0]
    assert len(trace.i) <= 2000
    # Each displayed vertex carries the value of its nearest original vertex.
    shown = np.column_stack([trace.x, trace.y, trace.z])
    np.testing.assert_allclose(trace.intensity, shown[:, 0], atol=0.1)


def test_plot_meshes_side_by_side(sphere):
    torus = shapes.torus(n_major=16, n_minor=8)
    fig = plotting.plot_meshes([sphere, torus], [sphere.vertices[:, 0], None], ["a", "b"], shared_colour_range=True)
    assert len(fig.data) == 2
    with pytest.raises(ValueError, match="one \\(or None\\) per mesh"):
        plotting.plot_meshes([sphere, torus], [None])


def test_slider_moves_the_figure(sphere):
    basis = eigenbasis(sphere, 10)
    w = plotting.mesh_slider(sphere, lambda i: basis.vectors[:, i], range(10), "index", symmetric=True)
    before = np.array(w.figure.data[0].intensity)
    w.slider.value = 4
    np.testing.assert_allclose(w.figure.data[0].intensity, basis.vectors[:, 4])
    assert not np.allclose(before, w.figure.data[0].intensity)
    moving = plotting.mesh_slider(sphere, lambda t: sphere.vertices * t, [1.0, 2.0], "scale")
    moving.slider.value = 2.0
    np.testing.assert_allclose(moving.figure.data[0].x, 2 * sphere.vertices[:, 0])


def test_static_fallback_and_bad_scalars(sphere):
    ax = plotting.plot_mesh_static(sphere, sphere.vertices[:, 1], title="y")
    assert len(ax.collections) == 1
    with pytest.raises(ValueError, match="one value per vertex"):
        plotting.plot_mesh(sphere, np.ones(3))
    with pytest.raises(ValueError, match="NaN"):
        plotting.plot_mesh(sphere, np.full(sphere.n_vertices, np.nan))
