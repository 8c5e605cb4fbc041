"""Old spellings keep working for one release, warn, name the new spelling, and give the same answer."""

from __future__ import annotations

import inspect
import warnings

import numpy as np
import pytest

import lbo_notebooks as lbo
from lbo_notebooks import bases, geodesics, minmax, mds, optimality, rpca, shapes
from lbo_notebooks._deprecation import moved, renamed


def _same_with_warning(new_call, old_call, new_spelling):
    expected = new_call()
    with pytest.warns(DeprecationWarning, match=new_spelling):
        got = old_call()
    return expected, got


@pytest.fixture(scope="module")
def sphere():
    return shapes.icosphere(2)


# --- the shim helper itself --------------------------------------------------------------------
def test_renamed_maps_warns_and_refuses_both():
    @renamed({"n": "k"}, keyword_only=("scale",), n_positional=2)
    def head(items, k=2, *, scale=1):
        return [scale * x for x in items[:k]]

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert head([1, 2, 3], 1, scale=2) == [2]  # the new spelling never warns
    with pytest.warns(DeprecationWarning, match=r"use head\(k=\.\.\.\)"):
        assert head([1, 2, 3], n=1) == [1]
    with pytest.warns(DeprecationWarning, match="pass scale=... by keyword"):
        assert head([1, 2, 3], 1, 3) == [3]
    with pytest.raises(ValueError, match="pass only k="):
        head([1, 2, 3], n=1, k=2)
    with pytest.raises(TypeError, match="at most 3 arguments"):
        head([1], 1, 2, 3)
    with pytest.raises(TypeError, match="multiple values"):
        head([1], 1, 2, scale=3)
    assert head.__name__ == "head"  # functools.wraps: docs and doctests still see the function


def test_moved_resolves_with_a_warning_and_rejects_unknown_names():
    getattr_ = moved("old", {"dumps": "json:dumps"})
    with pytest.warns(DeprecationWarning, match="use json.dumps instead"):
        assert getattr_("dumps")({"a": 1}) == '{"a": 1}'
    with pytest.raises(AttributeError, match="no attribute 'loads'"):
        getattr_("loads")


# --- every renamed public spelling -------------------------------------------------------------
def test_mass_kind(sphere):
    a, b = _same_with_warning(lambda: lbo.mass_matrix(sphere, mass_kind="barycentric"),
                              lambda: lbo.mass_matrix(sphere, kind="barycentric"), "mass_kind=")
    assert abs(a - b).max() == 0
    a, b = _same_with_warning(lambda: lbo.metric_mass_matrix(sphere, 0.5, mass_kind="consistent"),
                              lambda: lbo.metric_mass_matrix(sphere, 0.5, kind="consistent"), "mass_kind=")
    assert abs(a - b).max() == 0
    a, b = _same_with_warning(lambda: lbo.eigenbasis(sphere, 6, mass_kind="consistent"),
                              lambda: lbo.eigenbasis(sphere, 6, mass="consistent"), "mass_kind=")
    np.testing.assert_array_equal(a.values, b.values)
    a, b = _same_with_warning(lambda: bases.umbrella_basis(sphere, 5, mass_kind="barycentric"),
                              lambda: bases.umbrella_basis(sphere, 5, mass="barycentric"), "mass_kind=")
    np.testing.assert_array_equal(a, b)
    a, b = _same_with_warning(lambda: bases.umbrella_basis(sphere, 5), lambda: bases.umbrella_basis(sphere, n=5), "k=")
    np.testing.assert_array_equal(a, b)
    a, b = _same_with_warning(lambda: bases.random_smooth_functions(sphere, 3),
                              lambda: bases.random_smooth_functions(sphere, count=3), "k=")
    np.testing.assert_array_equal(a, b)


def test_sizes_are_k(sphere):
    s = lbo.eigenbasis(sphere, 12)
    f = sphere.vertices[:, 2] ** 2
    for method in ("project", "reconstruct", "error"):
        a, b = _same_with_warning(lambda: getattr(s, method)(f, k=5), lambda: getattr(s, method)(f, n=5), "k=")
        np.testing.assert_array_equal(a, b)
    for function in (optimality.representation_error, optimality.error_bound):
        a, b = _same_with_warning(lambda: function(s, f, k=5), lambda: function(s, f, n=5), "k=")
        assert a == b
    a, b = _same_with_warning(lambda: minmax.optimal_subspace(s, k=3), lambda: minmax.optimal_subspace(s, n=3), "k=")
    np.testing.assert_array_equal(a, b)
    a, b = _same_with_warning(lambda: minmax.random_subspace(50, k=3), lambda: minmax.random_subspace(50, codim=3), "k=")
    np.testing.assert_array_equal(a, b)


def test_return_vector(sphere):
    s = lbo.eigenbasis(sphere, 12)
    (c1, f1), (c2, f2) = _same_with_warning(
        lambda: optimality.worst_case_ratio(s.vectors[:, :4], s.stiffness, s.mass, return_vector=True),
        lambda: optimality.worst_case_ratio(s.vectors[:, :4], s.stiffness, s.mass, return_function=True),
        "return_vector=",
    )
    assert c1 == c2
    np.testing.assert_array_equal(f1, f2)


def test_rpca_sizes(sphere):
    W, A = lbo.stiffness_matrix(sphere), lbo.mass_matrix(sphere)
    X = sphere.vertices
    a, b = _same_with_warning(lambda: rpca.regularized_pca(X, W, A, k=6, mu=1e-3),
                              lambda: rpca.regularized_pca(X, W, A, m=6, mu=1e-3), "k=")
    np.testing.assert_array_equal(a, b)
    a, b = _same_with_warning(lambda: rpca.mu_from_beta(0.5, X, A, k=6), lambda: rpca.mu_from_beta(0.5, X, A, m=6), "k=")
    assert a == b
    result = rpca.RegularizedPCA(X, W, A).solve(4, beta=0.5)
    with pytest.warns(DeprecationWarning, match="RPCAResult.k"):
        assert result.m == result.k == 4


def test_geodesic_and_mds_options_are_keyword_only(sphere):
    a, b = _same_with_warning(lambda: geodesics.farthest_point_sampling(sphere, k=4, start=7),
                              lambda: geodesics.farthest_point_sampling(sphere, 4, 7), "start=... by keyword")
    np.testing.assert_array_equal(a, b)
    with pytest.warns(DeprecationWarning, match="k="):
        c = geodesics.farthest_point_sampling(sphere, count=4, start=7)
    np.testing.assert_array_equal(a, c)
    a, b = _same_with_warning(lambda: mds.spectral_mds(sphere, 3, n_samples=30, k=20),
                              lambda: mds.spectral_mds(sphere, 3, 30, 20), "n_samples=..., k=... by keyword")
    np.testing.assert_array_equal(a, b)
    with pytest.warns(DeprecationWarning, match="k="):
        c = mds.spectral_mds(sphere, 3, n_samples=30, n_eigs=20)
    np.testing.assert_array_equal(a, c)


def test_moved_names():
    from lbo_notebooks import plotting

    for name in ("rayleigh_sphere_figure", "plane_slider", "PlaneSlider"):
        with pytest.warns(DeprecationWarning, match=f"lbo_notebooks.plotting.{name}"):
            assert getattr(minmax, name) is getattr(plotting, name)
    # principal_angles lives in inner_product; rpca still imports it (not in rpca.__all__)
    assert rpca.principal_angles is lbo.inner_product.principal_angles


@pytest.mark.parametrize(
    "old_module, name, new_module",
    [
        ("shapes", "creature", "creatures"),
        ("shapes", "creature_poses", "creatures"),
        ("shapes", "POSES", "creatures"),
        ("shapes", "pose_distortion", "distortion"),
        ("creatures", "pose_distortion", "distortion"),
        ("creatures", "vertex_strain", "distortion"),
        ("curvature", "jittered_torus", "shapes"),
        ("units", "check_coordinate_range", "mesh"),
        ("optimality", "complement_ratio", "minmax"),
        ("io", "CleanReport", "repair"),
        ("io", "clean_mesh", "repair"),
        ("spectrum", "fix_signs", "inner_product"),
        ("inner_product", "default_shift", "solver_policy"),
        ("inner_product", "start_vector", "solver_policy"),
        ("inner_product", "use_dense", "solver_policy"),
        ("inner_product", "DENSE_LIMIT", "solver_policy"),
        ("minmax", "plane_normal", "teaching"),
        ("minmax", "plane_circle", "teaching"),
        ("eigensolver", "count_below", "sparse_factor"),
        ("robust", "select_operators", "laplacians"),
    ],
)
def test_names_moved_to_their_layer(old_module, name, new_module):
    """Definitions moved to the layer scripts/import_graph.py gives them; the old spelling warns and is the same object."""
    import importlib

    old, new = (importlib.import_module(f"lbo_notebooks.{m}") for m in (old_module, new_module))
    with pytest.warns(DeprecationWarning, match=f"use lbo_notebooks.{new_module}.{name} instead"):
        assert getattr(old, name) is getattr(new, name)
    assert name not in old.__all__ and name in new.__all__


def test_eigen_basis_is_now_lbo_basis(sphere):
    a, b = _same_with_warning(lambda: bases.lbo_basis(sphere, 5), lambda: bases.eigen_basis(sphere, 5), "bases.lbo_basis")
    np.testing.assert_array_equal(a, b)



# --- every warning points at the caller's line ---------------------------------------------------
def _warned_here(record, category):
    """The warnings of ``category`` in ``record``, with the file and line they point at."""
    return [(w.filename, w.lineno) for w in record if issubclass(w.category, category)]


def test_the_robust_laplacian_warning_points_at_the_callers_line():
    from lbo_notebooks.robust import LaplacianWarning

    v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [1, 1, 1]]
    fin = lbo.Mesh(v, [[0, 1, 2], [1, 0, 3], [0, 1, 4], [1, 2, 5]], check=False)  # three fins on edge 0-1
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1
        lbo.eigenbasis(fin, 3)
    assert _warned_here(record, LaplacianWarning) == [(__file__, line)]


def test_deprecation_warnings_point_at_the_callers_line(sphere):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1
        lbo.eigenbasis(sphere, 4, mass="voronoi")
    assert _warned_here(record, DeprecationWarning) == [(__file__, line)]


def test_a_fallback_warning_points_at_the_callers_line(sphere, monkeypatch):
    import lbo_notebooks.eigensolver as eigensolver

    def no_slices(*args, **kwargs):
        raise RuntimeError("slicing failed (test).")

    monkeypatch.setattr(eigensolver, "slice_eigsh", no_slices)
    monkeypatch.setattr(eigensolver, "SLICE_SIZE", 10)  # slice from k = 10 on
    import lbo_notebooks.solver_policy as solver_policy

    monkeypatch.setattr(solver_policy, "DENSE_LIMIT", 10)  # the sparse path for 162 vertices
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        line = inspect.currentframe().f_lineno + 1
        lbo.eigenbasis(sphere, 20)
    assert _warned_here(record, RuntimeWarning) == [(__file__, line)]


def test_every_warning_in_the_package_goes_through_the_one_helper():
    """A fixed stacklevel goes stale when a wrapper is added; _deprecation.warn walks out of the package."""
    import pathlib
    import re

    root = pathlib.Path(lbo.__file__).parent
    direct = {
        str(path.relative_to(root))
        for path in root.rglob("*.py")
        if path.name != "_deprecation.py" and re.search(r"warnings\.warn\(", path.read_text())
    }
    assert not direct, direct
