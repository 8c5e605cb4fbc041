"""The spectrum does not depend on the units of the input: scaling a shape by s divides lam by s^2.

Every solver path of :func:`lbo_notebooks.eigenbasis` is run on a shape and on copies scaled by
1e-12 ... 1e12; ``lam * s^2`` must agree to 1e-10 of the largest eigenvalue (docs/maths.md,
"Units"). Before the unit normalisation the ARPACK path lost copies of repeated eigenvalues at
1e-8 and was off by 100% at 1e-12.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.sparse as sp

import lbo_notebooks as lbo
from lbo_notebooks import Mesh, MeshError, PointCloud, shapes

SCALES = (1e-12, 1e-8, 1e-4, 1e4, 1e8, 1e12)


def sphere_points(n: int, seed: int = 0) -> np.ndarray:
    x = np.random.default_rng(seed).normal(size=(n, 3))
    return x / np.linalg.norm(x, axis=1, keepdims=True)


ICO2, ICO3, BUMPY3 = shapes.icosphere(2), shapes.icosphere(3), shapes.bumpy_sphere(3)
POINTS = sphere_points(700)


def scaled(mesh: Mesh, s: float) -> Mesh:
    return Mesh(mesh.vertices * s, mesh.faces)


# name -> (spectrum of the shape scaled by s, power p with lam ~ s^-p)
PATHS = {
    "dense": (lambda s: lbo.eigenbasis(scaled(ICO2, s), 20), 2.0),  # 162 vertices
    "arpack": (lambda s: lbo.eigenbasis(scaled(ICO3, s), 20), 2.0),  # 642 vertices, k < 100
    "arpack-bumpy": (lambda s: lbo.eigenbasis(scaled(BUMPY3, s), 50), 2.0),
    # k = 25 and 36 end on whole clusters of the icosphere; ARPACK alone missed copies at 1e-12 and 1e12.
    "arpack-k25": (lambda s: lbo.eigenbasis(scaled(ICO3, s), 25), 2.0),
    "arpack-k36": (lambda s: lbo.eigenbasis(scaled(ICO3, s), 36), 2.0),
    "slicing": (lambda s: lbo.eigenbasis(scaled(BUMPY3, s), 120), 2.0),  # k >= 100
    "robust": (lambda s: lbo.eigenbasis(scaled(ICO3, s), 20, laplacian="robust"), 2.0),
    "point-cloud": (lambda s: lbo.eigenbasis(PointCloud(POINTS * s), 20), 2.0),
    "metric-alpha-0.5": (lambda s: lbo.eigenbasis(scaled(ICO3, s), 20, alpha=0.5), 1.0),  # s^(-2 (1 - alpha))
    "metric-alpha-1": (lambda s: lbo.eigenbasis(scaled(BUMPY3, s), 20, alpha=1.0), 0.0),
    "operators": (
        lambda s: lbo.eigenbasis((lbo.stiffness_matrix(BUMPY3), lbo.mass_matrix(BUMPY3) * s**2), 20),
        2.0,
    ),
}
_REFERENCE: dict[str, lbo.Spectrum] = {}


def reference(name: str) -> lbo.Spectrum:
    if name not in _REFERENCE:
        _REFERENCE[name] = PATHS[name][0](1.0)
    return _REFERENCE[name]


@pytest.mark.parametrize("s", SCALES)
@pytest.mark.parametrize("name", list(PATHS))
def test_eigenvalues_times_s_squared_do_not_depend_on_the_scale(name, s):
    compute, power = PATHS[name]
    ref = reference(name)
    spectrum = compute(s)
    values = spectrum.values * s**power
    assert np.abs(values - ref.values).max() <= 1e-10 * np.abs(ref.values).max(), (values, ref.values)
    # The eigenvectors are A-orthonormal for the caller's (scaled) mass matrix.
    gram = spectrum.vectors.T @ (spectrum.mass @ spectrum.vectors)
    assert np.abs(gram - np.eye(spectrum.k)).max() < 1e-10


@pytest.mark.parametrize("s", (1e-59, 1e59))
@pytest.mark.parametrize("name", ["arpack", "slicing", "robust", "point-cloud", "metric-alpha-0.5"])
def test_the_ends_of_the_usable_range_give_the_same_spectrum(name, s):
    """The icosphere's bounding-box diagonal is 3.5 s: inside lbo.geometry._rescaling.USABLE_DIAGONAL (1e-60, 1e60)."""
    compute, power = PATHS[name]
    ref = reference(name)
    values = compute(s).values * s**power
    assert np.abs(values - ref.values).max() <= 1e-10 * np.abs(ref.values).max()


@pytest.mark.parametrize("s", (2e-71, 3e69))  # diagonals 6.9e-71 and 1.04e70
def test_just_outside_the_usable_range_is_a_clear_error(s):
    with pytest.raises(MeshError, match="usable range"):
        lbo.eigenbasis(scaled(ICO2, s), 5)
    with pytest.raises(MeshError, match="usable range"):
        PointCloud(POINTS * s)


@pytest.mark.parametrize("s", (1e-12, 1e12))
def test_eigenvectors_scale_as_one_over_s(s):
    """Simple eigenvalues (a bumpy sphere): the same eigenfunctions, divided by s (A-normalised)."""
    ref = reference("arpack-bumpy")
    spectrum = PATHS["arpack-bumpy"][0](s)
    np.testing.assert_allclose(spectrum.vectors * s, ref.vectors, rtol=0, atol=1e-8 * np.abs(ref.vectors).max())


def test_arpack_sets_missing_copies_of_a_repeated_eigenvalue_are_completed(monkeypatch):
    """Whether ARPACK finds every copy depends on round-off; an inertia count catches a short set."""
    import scipy.sparse.linalg as spla

    ref = reference("arpack-k25")
    eigsh = spla.eigsh

    def short(*args, **kwargs):  # one copy of lam = 12 (l = 3) missing, the next eigenvalue instead
        values, vectors = eigsh(*args, **{**kwargs, "k": kwargs["k"] + 1})
        keep = np.ones(values.size, dtype=bool)
        keep[np.argsort(values)[12]] = False
        return values[keep], vectors[:, keep]

    monkeypatch.setattr(spla, "eigsh", short)
    spectrum = lbo.eigenbasis(ICO3, 25)
    assert np.abs(spectrum.values - ref.values).max() <= 1e-10 * ref.values.max()


def test_an_explicit_shift_is_in_the_callers_units():
    s = 1e-9
    ref = reference("arpack")
    spectrum = lbo.eigenbasis(scaled(ICO3, s), 20, shift=0.05 / s**2)
    assert np.abs(spectrum.values * s**2 - ref.values).max() <= 1e-10 * ref.values.max()


# --- coordinates out of a usable range: a clear error, not a crash -------------------------------
@pytest.mark.parametrize("s", (1e78, 1e100))
def test_a_huge_mesh_gets_a_clear_error_not_a_zero_division(s):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # numpy's overflow warnings while measuring
        try:
            mesh = scaled(ICO2, s)
        except MeshError as error:  # the Mesh itself may refuse it; then that is the clear error
            assert "rescale" in str(error).lower() or "range" in str(error).lower(), error
            return
        with pytest.raises(MeshError, match="range") as info:
            lbo.eigenbasis(mesh, 5)
    assert "rescale" in str(info.value).lower()


def test_default_shift_of_a_mass_that_sums_to_zero_is_a_value_error():
    from lbo_notebooks.spectral._engine.policy import default_shift

    with pytest.raises(ValueError, match="mass"):
        default_shift(sp.csr_matrix((4, 4)))
