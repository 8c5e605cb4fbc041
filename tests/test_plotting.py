import matplotlib
import numpy as np
import pytest

from lbo_notebooks import eigenbasis, plotting, shapes
from lbo_notebooks.shapes import _creatures as creatures

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


# --- layout: panels, colour bars, titles, camera ------------------------------------------------

from lbo_notebooks.plotting._scene import MARGIN as _MARGIN, NOMINAL_WIDTH as _NOMINAL_WIDTH  # noqa: E402  (the layout's stated assumptions)


@pytest.fixture(scope="module")
def dog():
    return creatures.creature("dog", n_vertices=1000)


def _scenes(fig):
    return [fig.layout[f"scene{'' if p == 0 else p + 1}"] for p in range(len(fig.data))]


def _overlap(a, b):
    return min(a[1], b[1]) - max(a[0], b[0]) > 1e-12


def test_panels_do_not_overlap_and_colour_bars_sit_in_their_own_panel(dog):
    meshes = [dog, dog.with_vertices(1.6 * dog.vertices), dog, dog, dog]
    values = [(p + 1) * m.vertices[:, 0] for p, m in enumerate(meshes)]     # five colour ranges
    fig = plotting.plot_meshes(meshes, values, titles=[f"panel {p}" for p in range(5)], cols=3)
    scenes = _scenes(fig)
    boxes = [(s.domain.x, s.domain.y) for s in scenes]
    for p in range(len(boxes)):
        for q in range(p + 1, len(boxes)):
            assert not (_overlap(boxes[p][0], boxes[q][0]) and _overlap(boxes[p][1], boxes[q][1])), (p, q)
    for p, (trace, scene) in enumerate(zip(fig.data, scenes)):
        c = p % 3
        cb = trace.colorbar
        # Right of its own scene, left of the next column's scene, with room for its tick labels.
        next_left = scenes[c + 1].domain.x[0] if c < 2 else 1.0
        assert trace.showscale and scene.domain.x[1] <= cb.x and cb.xanchor == "left"
        assert next_left - cb.x >= 0.8 * 70 / _NOMINAL_WIDTH
        assert scene.domain.y[0] <= cb.y - cb.len / 2 and cb.y + cb.len / 2 <= scene.domain.y[1]


def test_shared_colour_range_has_one_colour_bar_in_the_last_panel(dog, sphere):
    fig = plotting.plot_meshes([dog, sphere], [dog.vertices[:, 0], sphere.vertices[:, 0]], shared_colour_range=True)
    assert [t.showscale for t in fig.data] == [False, True]
    assert fig.data[0].cmin == fig.data[1].cmin and fig.data[0].cmax == fig.data[1].cmax
    assert fig.layout.scene2.domain.x[1] <= fig.data[1].colorbar.x < 1


def test_panels_with_one_colour_scale_share_one_colour_bar_and_no_scene_is_narrowed(dog):
    x = dog.vertices[:, 0]
    width = lambda s: s.domain.x[1] - s.domain.x[0]
    # Groups: the first two panels share a range, the last two another (notebook 12's HKS and phi_8).
    fig = plotting.plot_meshes([dog] * 4, [x, 2 * x, x**2, 3 * x**2], shared_colour_range=["a", "a", "b", "b"])
    assert [t.showscale for t in fig.data] == [False, True, False, True]
    assert (fig.data[0].cmin, fig.data[0].cmax) == (fig.data[1].cmin, fig.data[1].cmax) == (2 * x.min(), 2 * x.max())
    assert (fig.data[2].cmin, fig.data[2].cmax) == ((x**2).min(), 3 * (x**2).max())
    np.testing.assert_allclose([width(s) for s in _scenes(fig)], width(fig.layout.scene), rtol=1e-12)
    # The same cmin and cmax given for every panel: one scale, so one bar (notebook 11).
    fig = plotting.plot_meshes([dog] * 3, [x, 2 * x, 3 * x], cmin=0.0, cmax=1.0)
    assert [t.showscale for t in fig.data] == [False, False, True]
    # Separate ranges: a bar each, and still equal scenes.
    fig = plotting.plot_meshes([dog] * 3, [x, 2 * x, None])
    assert [bool(t.showscale) for t in fig.data] == [True, True, False]
    np.testing.assert_allclose([width(s) for s in _scenes(fig)], width(fig.layout.scene), rtol=1e-12)
    for bad in (["a"], "ab", 3):
        with pytest.raises(ValueError, match="shared_colour_range"):
            plotting.plot_meshes([dog, dog], [x, x], shared_colour_range=bad)


def test_titles_are_wrapped_to_their_panel_and_leave_room_above_the_scene(dog):
    long = "canonical form of the head_turned pose, computed by spectral MDS"
    fig = plotting.plot_meshes([dog] * 6, titles=[long] * 6)
    scenes = _scenes(fig)
    assert len(fig.layout.annotations) == 6
    panel_px = _NOMINAL_WIDTH / 3            # six panels: two rows of three
    for note, scene in zip(fig.layout.annotations, scenes):
        lines = note.text.split("<br>")
        assert " ".join(lines) == long
        assert max(map(len, lines)) * 0.58 * note.font.size <= panel_px
        assert scene.domain.x[0] <= note.x <= scene.domain.x[1]
        # The title hangs from the top of the panel; the scene starts below its last line.
        room = (note.y - scene.domain.y[1]) * fig.layout.height
        assert note.yanchor == "top" and room >= len(lines) * note.font.size


def _project(vertices, scene, width_px, height_px, eye=None):
    """Screen coordinates in [-1, 1]^2 of ``vertices`` under plotly's camera (measured in chromium:
    axis ranges map to [-0.5, 0.5]^3, perspective with a 45 degree vertical field of view)."""
    ranges = np.array([scene.xaxis.range, scene.yaxis.range, scene.zaxis.range])
    ratio = np.array([scene.aspectratio.x, scene.aspectratio.y, scene.aspectratio.z])
    p = ((vertices - ranges[:, 0]) / (ranges[:, 1] - ranges[:, 0]) - 0.5) * ratio
    cam = scene.camera
    e = np.array([cam.eye.x, cam.eye.y, cam.eye.z]) if eye is None else eye
    up = np.array([cam.up.x, cam.up.y, cam.up.z])
    forward = -e / np.linalg.norm(e)
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, forward)
    rel = p - e
    depth = rel @ forward
    t = np.tan(np.pi / 8)
    return (rel @ right) / depth / (t * width_px / height_px), (rel @ true_up) / depth / t


@pytest.mark.parametrize("up", ["auto", "y", "z", "-x", (1.0, 1.0, 0.2)])
def test_the_camera_shows_every_vertex_from_any_direction(dog, up):
    height = 400
    fig = plotting.plot_mesh(dog, dog.vertices[:, 2], up=up, height=height)
    scene = fig.layout.scene
    # Equal scale on all axes, and ranges that contain every vertex with a margin.
    widths = [r[1] - r[0] for r in (scene.xaxis.range, scene.yaxis.range, scene.zaxis.range)]
    np.testing.assert_allclose(widths, widths[0], rtol=1e-12)
    assert scene.aspectratio.x == scene.aspectratio.y == scene.aspectratio.z
    for a, r in enumerate((scene.xaxis.range, scene.yaxis.range, scene.zaxis.range)):
        margin = 0.5 * _MARGIN * widths[0] / 2
        assert r[0] + margin <= dog.vertices[:, a].min() and dog.vertices[:, a].max() <= r[1] - margin
    width_px, height_px = _NOMINAL_WIDTH - 70, height - fig.layout.margin.t
    cam = scene.camera.eye
    distance = np.linalg.norm([cam.x, cam.y, cam.z])
    rng = np.random.default_rng(0)
    for eye in [None, *(distance * d / np.linalg.norm(d) for d in rng.normal(size=(20, 3)))]:
        x, y = _project(dog.vertices, scene, width_px, height_px, eye)
        assert np.abs(x).max() < 1 and np.abs(y).max() < 1
    x, y = _project(dog.vertices, scene, width_px, height_px)
    assert max(np.abs(x).max(), np.abs(y).max()) > 0.4   # ... and the mesh is not a speck


def test_up_is_respected_and_auto_finds_the_height_of_an_animal(dog):
    cam = lambda fig: fig.layout.scene.camera
    vec = lambda v: np.array([v.x, v.y, v.z])
    z_up = plotting.plot_mesh(dog)                                      # the creatures are z-up
    np.testing.assert_allclose(vec(cam(z_up).up), [0, 0, 1])
    y_up = dog.with_vertices(dog.vertices[:, [0, 2, 1]] * [1, 1, -1])  # as read from a y-up file
    np.testing.assert_allclose(vec(cam(plotting.plot_mesh(y_up)).up), [0, 1, 0])
    np.testing.assert_allclose(vec(cam(plotting.plot_mesh(y_up, up="z")).up), [0, 0, 1])
    np.testing.assert_allclose(vec(cam(plotting.plot_mesh(dog, up="-y")).up), [0, -1, 0])
    np.testing.assert_allclose(vec(cam(plotting.plot_mesh(dog, up=[0, 3, 4])).up), [0, 0.6, 0.8])
    # A side view, slightly from above: the eye is mostly along the dog's thin axis (y).
    eye = vec(cam(z_up).eye)
    assert np.argmax(np.abs(eye)) == 1 and 0 < eye[2] < np.abs(eye[1])
    for bad in ("w", [0, 0, 0], [1, 2], [np.nan, 0, 1]):
        with pytest.raises(ValueError, match="up"):
            plotting.plot_mesh(dog, up=bad)


def test_same_scale_compares_sizes_across_panels(dog):
    big = dog.with_vertices(2 * dog.vertices)
    same = _scenes(plotting.plot_meshes([dog, big]))
    own = _scenes(plotting.plot_meshes([dog, big], same_scale=False))
    width = lambda s: s.xaxis.range[1] - s.xaxis.range[0]
    assert width(same[0]) == width(same[1])
    np.testing.assert_allclose(width(own[1]), 2 * width(own[0]), rtol=1e-12)


def test_a_constant_function_gets_the_middle_colour_not_an_extreme(sphere):
    c = np.full(sphere.n_vertices, 0.28209479177387814)
    c[::7] += 1e-17                                          # round-off noise on a constant
    for symmetric in (True, False):
        trace = plotting.plot_mesh(sphere, c, symmetric=symmetric).data[0]
        assert trace.cmin < c.min() and c.max() < trace.cmax
        np.testing.assert_allclose((trace.cmin + trace.cmax) / 2, c.mean(), rtol=1e-12)
    zero = plotting.plot_mesh(sphere, np.zeros(sphere.n_vertices), symmetric=True).data[0]
    assert zero.cmin < 0 < zero.cmax
    # A function that varies is still drawn over its own range.
    trace = plotting.plot_mesh(sphere, sphere.vertices[:, 0] + 5).data[0]
    assert (trace.cmin, trace.cmax) == (sphere.vertices[:, 0].min() + 5, sphere.vertices[:, 0].max() + 5)


def test_no_negative_zero_in_titles(sphere):
    assert plotting.tidy_label(f"λ = {-3e-16:.2f}, μ = {-0.004:.3f}, t = {-1e-9:.1e}") == "λ = 0.00, μ = -0.004, t = -1.0e-09"
    assert plotting.tidy_label("-0.0 and x-0.0 and -0.05 and 10-0") == "0.0 and x-0.0 and -0.05 and 10-0"
    assert plotting.tidy_label(None) is None
    with pytest.raises(ValueError, match="text must be a string"):
        plotting.tidy_label(0.5)
    basis = eigenbasis(sphere, 4)
    assert abs(basis.values[0]) < 1e-10 * basis.values[-1]                         # the constant's eigenvalue: zero up to round-off
    w = plotting.mesh_slider(sphere, lambda i: basis.vectors[:, i], range(4), "i", symmetric=True, start=0,
                             title=lambda i: f"λ = {-abs(basis.values[i]):.2f}")
    assert w.figure.layout.title.text == "λ = 0.00"
    fig = plotting.plot_meshes([sphere], titles=[f"{-1e-20:.3f}"])
    assert fig.layout.annotations[0].text == "0.000"


def test_slider_starts_where_asked_and_keeps_moving_vertices_in_view(sphere):
    basis = eigenbasis(sphere, 4)
    w = plotting.mesh_slider(sphere, lambda i: basis.vectors[:, i], range(4), "i", symmetric=True, start=1)
    assert w.slider.value == 1
    np.testing.assert_allclose(w.figure.data[0].intensity, basis.vectors[:, 1])
    with pytest.raises(ValueError, match="start"):
        plotting.mesh_slider(sphere, lambda i: basis.vectors[:, i], range(4), "i", start=7)
    grow = plotting.mesh_slider(sphere, lambda t: sphere.vertices * t, [1.0, 3.0], "scale")
    before = list(grow.figure.layout.scene.xaxis.range)
    grow.slider.value = 3.0
    after = grow.figure.layout.scene.xaxis.range
    assert after[0] < before[0] and after[1] > before[1]
    assert after[0] < 3 * sphere.vertices[:, 0].min() and 3 * sphere.vertices[:, 0].max() < after[1]


def test_static_fallback_turns_the_mesh_upright(dog):
    from lbo_notebooks.plotting._meshes import _view_rotation
    from lbo_notebooks.plotting._scene import View as _View

    y_up = dog.vertices[:, [0, 2, 1]] * [1, 1, -1]
    for vertices, up in ((dog.vertices, "auto"), (y_up, "auto"), (y_up, "y"), (dog.vertices, [1.0, 0.0, 1.0])):
        view = _View(vertices, up)
        rotation = _view_rotation(view)
        np.testing.assert_allclose(rotation @ rotation.T, np.eye(3), atol=1e-12)
        assert np.linalg.det(rotation) > 0
        np.testing.assert_allclose(rotation @ view.up, [0, 0, 1], atol=1e-12)   # up is drawn up
    ax = plotting.plot_mesh_static(dog.with_vertices(y_up), y_up[:, 0], title=f"{-1e-9:.2f}")
    r = ax.get_xlim()[1]
    assert ax.get_xlim() == ax.get_ylim() == ax.get_zlim() == (-r, r)
    assert r >= np.linalg.norm(y_up - (y_up.min(0) + y_up.max(0)) / 2, axis=1).max()
    assert ax.get_title() == "0.00"


def test_same_scale_draws_equal_sizes_equally_large_even_beside_a_colour_bar(dog):
    fig = plotting.plot_meshes([dog, dog, dog], [dog.vertices[:, 0], dog.vertices[:, 1], None])
    scenes = _scenes(fig)
    eyes = [np.linalg.norm([s.camera.eye.x, s.camera.eye.y, s.camera.eye.z]) for s in scenes]
    sizes = [(s.domain.x[1] - s.domain.x[0], s.domain.y[1] - s.domain.y[0]) for s in scenes]
    np.testing.assert_allclose(eyes, eyes[0], rtol=1e-12)      # same distance and same scene size:
    np.testing.assert_allclose(sizes, [sizes[0]] * 3, rtol=1e-12)  # the same size on screen


# --- issue 26, item 11: point clouds are plotted like meshes -----------------------------------------
@pytest.fixture(scope="module")
def cloud():
    from lbo_notebooks import PointCloud

    return PointCloud(shapes.icosphere(2).vertices)


def test_plot_mesh_draws_a_point_cloud_as_points_coloured_by_the_function(cloud):
    f = cloud.points[:, 2]
    fig = plotting.plot_mesh(cloud, f, symmetric=True, title="z")
    trace = fig.data[0]
    assert trace.type == "scatter3d" and trace.mode == "markers"
    np.testing.assert_array_equal(np.column_stack([trace.x, trace.y, trace.z]), cloud.points)
    np.testing.assert_allclose(trace.marker.color, f)
    assert trace.marker.cmin == -trace.marker.cmax and trace.marker.showscale
    assert plotting.plot_mesh(cloud).data[0].type == "scatter3d"  # no function: one colour
    with pytest.raises(ValueError, match=f"one value per point, shape \\({cloud.n_points},\\)"):
        plotting.plot_mesh(cloud, f[:-1])


def test_large_clouds_are_thinned_for_display_with_the_values_of_the_points_shown():
    from lbo_notebooks import PointCloud

    big = PointCloud(shapes.icosphere(5).vertices)
    fig = plotting.plot_mesh(big, big.points[:, 0], max_faces=2000)
    trace = fig.data[0]
    shown = np.column_stack([trace.x, trace.y, trace.z])
    assert len(shown) <= 2000
    np.testing.assert_array_equal(trace.marker.color, shown[:, 0])


def test_plot_meshes_static_and_slider_accept_point_clouds(cloud, sphere):
    basis = eigenbasis(cloud, 6)
    fig = plotting.plot_meshes([sphere, cloud], [sphere.vertices[:, 0], basis.vectors[:, 1]], ["mesh", "cloud"])
    assert [t.type for t in fig.data] == ["mesh3d", "scatter3d"]
    ax = plotting.plot_mesh_static(cloud, basis.vectors[:, 1], up="z")
    assert len(ax.collections) == 1 and len(ax.collections[0].get_offsets()) == cloud.n_points
    w = plotting.mesh_slider(cloud, lambda i: basis.vectors[:, i], range(6), "index", symmetric=True, start=1)
    w.slider.value = 4
    np.testing.assert_allclose(w.figure.data[0].marker.color, basis.vectors[:, 4])
    moving = plotting.mesh_slider(cloud, lambda t: cloud.points * t, [1.0, 2.0], "scale")
    moving.slider.value = 2.0
    np.testing.assert_allclose(moving.figure.data[0].x, 2 * cloud.points[:, 0])
    vertices, faces, index = plotting.display_mesh(cloud)
    assert faces is None and index is None and len(vertices) == cloud.n_points


# --- issue 29: figures that teach ------------------------------------------------------------------
from lbo_notebooks.shapes import creature, creature_poses  # noqa: E402


def _screen_up(scene, centre, up, width_px, height_px):
    """The screen direction (x right, y up) of the segment from ``centre`` along ``up``."""
    pts = np.array([centre, centre + 0.1 * up])
    x, y = _project(pts, scene, width_px, height_px)
    d = np.array([x[1] - x[0], y[1] - y[0]])
    return d / np.linalg.norm(d)


@pytest.mark.parametrize("species", ["dog", "horse"])
def test_every_pose_of_every_creature_is_drawn_upright(species):
    """The creatures are z-up in every pose (the sitting dog is taller than it is long, which the
    old "axis of middle extent" rule turned into a dog lying on its side); as read from a y-up file
    (centred or standing on y = 0) they are y-up."""
    poses = creature_poses(species, n_vertices=1000)
    scaled = creature(species, "sitting", parts={"head": 1.5, "legs": 0.85}, n_vertices=1000)
    for name, mesh in {**poses, "big head, sitting": scaled}.items():
        v = mesh.vertices
        y_up = v[:, [0, 2, 1]] * [1, 1, -1]
        centred = y_up - (y_up.min(axis=0) + y_up.max(axis=0)) / 2
        for vertices, axis in ((v, 2), (y_up, 1), (centred, 1)):
            fig = plotting.plot_mesh(mesh.with_vertices(vertices), height=400)
            cam = fig.layout.scene.camera
            np.testing.assert_allclose([cam.up.x, cam.up.y, cam.up.z], np.eye(3)[axis], err_msg=name)
            # On screen: the shape's up axis points straight up, and the eye is not above it.
            centre = (vertices.min(axis=0) + vertices.max(axis=0)) / 2
            d = _screen_up(fig.layout.scene, centre, np.eye(3)[axis], _NOMINAL_WIDTH, 400 - fig.layout.margin.t)
            assert d[1] > 0.99, (name, axis, d)
            eye = np.array([cam.eye.x, cam.eye.y, cam.eye.z])
            assert np.degrees(np.arcsin(eye[axis] / np.linalg.norm(eye))) < 30, (name, axis)
            # Lit from above, whichever the file's convention.
            light = fig.data[0].lightposition
            light = np.array([light.x, light.y, light.z])
            assert light[axis] / np.linalg.norm(light) > 0.75, (name, axis)


def test_auto_up_for_the_other_built_in_shapes_and_a_flat_scan():
    from lbo_notebooks.plotting._scene import auto_up as _auto_up

    np.testing.assert_array_equal(_auto_up(shapes.icosphere(2).vertices), [0, 0, 1])     # a tie: z
    np.testing.assert_array_equal(_auto_up(shapes.torus().vertices), [0, 1, 0])          # flat in xy: face on
    np.testing.assert_array_equal(_auto_up(shapes.rectangle().vertices), [0, 1, 0])
    # A wide, low object standing on its floor: the floor decides, not the extents.
    box = np.array([[x, y, z] for x in (0, 4) for y in (0, 1.4) for z in (-0.9, 0.9)], dtype=float)
    np.testing.assert_array_equal(_auto_up(box), [0, 1, 0])
    np.testing.assert_array_equal(_auto_up(box[:, [0, 2, 1]]), [0, 0, 1])


@pytest.mark.parametrize("n, bars", [(1, "none"), (2, "each"), (3, "shared"), (4, "each"), (4, "none"), (6, "each")])
def test_every_shape_fills_at_least_half_of_its_panel(dog, n, bars):
    """Projected through each scene's camera (for the nominal figure width), every shape spans at
    least half of its scene's width or height (notebook 12 drew 100-pixel dogs in 450-pixel panels)."""
    meshes = [dog, dog.with_vertices(dog.vertices[:, [0, 2, 1]] * [1, 1, -1]), creature_poses("dog", n_vertices=1000)["sitting"]]
    meshes = (meshes * n)[:n]
    values = None if bars == "none" else [m.vertices[:, 0] for m in meshes]
    fig = plotting.plot_meshes(meshes, values, titles=[f"panel {p}" for p in range(n)],
                               shared_colour_range=bars == "shared")
    for mesh, scene in zip(meshes, _scenes(fig)):
        width_px = (scene.domain.x[1] - scene.domain.x[0]) * _NOMINAL_WIDTH
        height_px = (scene.domain.y[1] - scene.domain.y[0]) * fig.layout.height
        x, y = _project(mesh.vertices, scene, width_px, height_px)
        assert np.abs(x).max() < 1 and np.abs(y).max() < 1                    # inside the scene ...
        assert max(np.ptp(x), np.ptp(y)) / 2 >= 0.5, (n, bars, np.ptp(x), np.ptp(y))   # ... and filling it
        assert n == 1 or 0.6 <= width_px / height_px <= 1.7                    # panels: about square


def test_greek_subscripts_are_typeset_in_labels(sphere):
    tidy = plotting.tidy_label
    assert tidy("dog: phi_6") == "dog: φ₆" and tidy("φ_8, walking") == "φ₈, walking"
    assert tidy("lam_2 = 6, lambda_{i}, λ_n+1, mu_k") == "λ₂ = 6, λᵢ, λₙ₊₁, μₖ"
    for kept in ("head_turned", "alpha_slider", "my_scan.ply", "phi_x1.6", "x_1", "graphi_2"):
        assert tidy(kept) == kept
    fig = plotting.plot_meshes([sphere, sphere], titles=["phi_6", "α = 1: φ_5"])
    assert [a.text for a in fig.layout.annotations] == ["φ₆", "α = 1: φ₅"]
    assert plotting.plot_mesh(sphere, title="lam_1 = -0.00").layout.title.text == "λ₁ = 0.00"


def test_lesson_figures_label_in_unicode():
    w = plotting.plane_slider(np.diag([1.0, 2.0, 4.0]))
    w.slider.value = 90
    title = w.figure.layout.title.text
    assert "≤ λ₁ = 2.000" in title and "<=" not in title and "lam" not in title and "°" in title
    assert w.minimum <= 2.0 + 1e-12 and f"{w.minimum:.3f}" in title
    fig = plotting.rayleigh_sphere_figure(np.diag([1.0, 2.0, 4.0]))
    assert fig.data[0].colorbar.title.text == "xᵀMx"


def test_a_slider_starts_on_a_function_worth_looking_at(sphere):
    """Eigenfunction 0 is the constant, a blank surface: by default the slider starts on 1. A frame
    that moves the vertices, or an explicit start, is taken as it is."""
    basis = eigenbasis(sphere, 6)
    calls = []

    def frame(i):
        calls.append(i)
        return basis.vectors[:, i]

    w = plotting.mesh_slider(sphere, frame, range(6), "index", symmetric=True)
    assert w.slider.value == 1 and calls[:2] == [0, 1]
    np.testing.assert_allclose(w.figure.data[0].intensity, basis.vectors[:, 1])
    assert plotting.mesh_slider(sphere, frame, range(6), "index", start=0).slider.value == 0
    rebuild = plotting.mesh_slider(sphere, lambda n: basis.reconstruct(sphere.vertices[:, 2], n), [1, 2, 3], "n")
    assert rebuild.slider.value == 2                   # from phi_0 alone: a constant
    moving = plotting.mesh_slider(sphere, lambda t: sphere.vertices * t, [1.0, 2.0], "scale")
    assert moving.slider.value == 1.0
    flat = plotting.mesh_slider(sphere, lambda i: np.full(sphere.n_vertices, float(i)), range(5), "c")
    assert flat.slider.value == 0                      # nothing better among the first values


def test_max_faces_must_leave_something_to_draw():
    """max_faces=0 used to give an empty picture without a word (issue 42, item 7: every call checks)."""
    mesh = shapes.icosphere(2)
    for call in (lambda bad: plotting.display_mesh(mesh, bad), lambda bad: plotting.plot_mesh(mesh, max_faces=bad),
                 lambda bad: plotting.plot_meshes([mesh], max_faces=bad)):
        for bad in (0, -1, 2.5, None):
            with pytest.raises(ValueError, match=r"^max_faces must be a positive integer"):
                call(bad)
    assert plotting.display_mesh(mesh, 10)[1].shape == (10, 3)
