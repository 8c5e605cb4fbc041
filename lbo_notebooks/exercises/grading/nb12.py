"""Graded tests of notebook 12 (the spectral toolbox): see :mod:`lbo_notebooks.exercises.grading`.

The builds (12-hks, 12-fmap, 12-zoomout-step) are judged on spectra, times, point maps, maps and
sizes the notebook never shows (no dog: small spheres, tori, an ellipsoid, a disk; shapes of
different vertex counts for the maps), with the library's HKS, functional map and ZoomOut (and
pyFM's) unavailable. 12-bound is judged against the standing dog's eigenbasis rebuilt from the
notebook's definitions (3,000 vertices, 60 eigenpairs: a few seconds on one core), not the student's
``ref``.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from ..feedback import WRONG, Stop, pick
from ..toolbox import (
    RECAP_TOOLBOX,
    fmap_hint,
    hks_hint,
    zoomout_step_hint,
    check_alpha_choice,
    check_mirror_maps,
    check_truncation_bound,
    check_zoomout,
)
from ._registry import Verdict, from_feedback, grader, recap_verdict, student_call

N, K = 3000, 60  # the notebook's first cell

# What a build of the HKS must not call: the library's and pyFM's (by its own module and by the
# names its package re-exports).
_HKS = (
    "lbo_notebooks.analyses._descriptors:hks",
    "pyFM.signatures.HKS_functions:HKS",
    "pyFM.signatures.HKS_functions:lm_HKS",
    "pyFM.signatures.HKS_functions:auto_HKS",
    "pyFM.signatures.HKS_functions:mesh_HKS",
    "pyFM.signatures:HKS",
    "pyFM.signatures:lm_HKS",
    "pyFM.signatures:auto_HKS",
    "pyFM.signatures:mesh_HKS",
)

# What a build of the functional map must not call: the library's map (and the A-projection
# methods of a Spectrum, Φᵀ A f in one call), pyFM's conversions.
_FMAP = (
    "lbo_notebooks.analyses._functional_maps:map_from_points",
    "lbo_notebooks.spectral._spectrum:Spectrum.project",
    "lbo_notebooks.spectral._spectrum:Spectrum.reconstruct",
    "pyFM.spectral.convert:p2p_to_FM",
    "pyFM.spectral.convert:mesh_p2p_to_FM",
    "pyFM.spectral:p2p_to_FM",
    "pyFM.spectral:mesh_p2p_to_FM",
)

# What a build of one ZoomOut iteration must not call: the library's ZoomOut and both its conversions
# (and the nearest-row search they share, the A-projection of a Spectrum), pyFM's.
_ZOOMOUT_STEP = (
    "lbo_notebooks.analyses._functional_maps:zoomout",
    "lbo_notebooks.analyses._functional_maps:points_from_map",
    "lbo_notebooks.analyses._functional_maps:map_from_points",
    "lbo_notebooks.analyses._functional_maps:_nearest_rows",
    "lbo_notebooks.spectral._spectrum:Spectrum.project",
    "lbo_notebooks.spectral._spectrum:Spectrum.reconstruct",
    "pyFM.spectral.convert:FM_to_p2p",
    "pyFM.spectral.convert:mesh_FM_to_p2p",
    "pyFM.spectral.convert:mesh_FM_to_p2p_precise",
    "pyFM.spectral.convert:p2p_to_FM",
    "pyFM.spectral.convert:mesh_p2p_to_FM",
    "pyFM.spectral:FM_to_p2p",
    "pyFM.spectral:p2p_to_FM",
    "pyFM.refine.zoomout:zoomout_iteration",
    "pyFM.refine.zoomout:zoomout_refine",
    "pyFM.refine.zoomout:mesh_zoomout_refine",
    "pyFM.refine.zoomout:mesh_zoomout_refine_p2p",
    "pyFM.refine:zoomout_refine",
    "pyFM.refine:mesh_zoomout_refine",
)


def _fresh(spectrum: Any) -> Any:
    """A copy of a spectrum for the student's function (nothing of ours reachable from it)."""
    from ...spectral._spectrum import Spectrum

    return Spectrum(spectrum.values.copy(), spectrum.vectors.copy(), spectrum.stiffness.copy(), spectrum.mass.copy())


@functools.lru_cache(maxsize=1)
def _unseen_spectra() -> tuple[tuple[str, Any], ...]:
    """Spectra no notebook cell and no visible check uses, of different sizes."""
    from ... import shapes
    from ...spectral._spectrum import eigenbasis

    rng = np.random.default_rng(1212)
    ring = shapes.torus(n_major=30, n_minor=12)
    bumpy = ring.with_vertices(ring.vertices * rng.uniform(0.92, 1.08, size=(ring.n_vertices, 1)))
    return (("a bumpy torus", eigenbasis(bumpy, 20)),
            ("an ellipsoid", eigenbasis(shapes.ellipsoid(1.0, 0.6, 0.4, subdivisions=2), 12)),
            ("a disk (with a boundary)", eigenbasis(shapes.disk(n_rings=6), 9)),
            ("a sphere", eigenbasis(shapes.icosphere(3), 16)))


@grader("12-hks", kind="build", replaces=_HKS)
def _hks(my_hks: Any) -> Verdict:
    from ...analyses._descriptors import hks

    spectra = _unseen_spectra()
    for (what, spectrum), scales in zip(spectra, ([0.3, 2.0], [0.05, 0.4, 1.5, 4.0, 9.0], [0.7], [0.01, 1.0, 3.0])):
        times = np.asarray(scales) / spectrum.values[1]  # from the first frequency to below the last
        ref = hks(spectrum, times)
        with np.errstate(over="ignore", invalid="ignore"):
            value = student_call(my_hks, _fresh(spectrum), times.copy())
        hint = hks_hint(value, spectrum, times, ref)
        if hint is not None:
            raise Stop(WRONG, f"{hint} (Graded on {what}, {spectrum.k} eigenpairs and {times.size} times the "
                              "notebook does not show.)")
    return Verdict(1.0, "Right on four spectra and sets of times the notebook does not show "
                        "(a torus, an ellipsoid, a disk, a sphere).")


@functools.lru_cache(maxsize=1)
def _unseen_pairs() -> tuple[tuple[str, np.ndarray, Any, Any, int], ...]:
    """(what, p2p, source, target, k): a permutation between two poses of one torus, a many-to-one
    map onto a smaller target, a map onto a larger target."""
    from ... import shapes
    from ...spectral._spectrum import eigenbasis

    rng = np.random.default_rng(2112)
    big = eigenbasis(shapes.bumpy_sphere(3, seed=4), 16)                     # 642 vertices
    small = eigenbasis(shapes.ellipsoid(1.0, 0.7, 0.5, subdivisions=2), 14)  # 162 vertices
    ring = shapes.torus(n_major=24, n_minor=10)
    stretched = ring.with_vertices(ring.vertices * [1.0, 1.25, 0.85])
    one, two = eigenbasis(ring, 13), eigenbasis(stretched, 13)
    shuffle = rng.permutation(one.n_vertices)  # first: where a map used the wrong way round shows
    onto_small = rng.integers(0, big.n_vertices, small.n_vertices)
    onto_big = rng.integers(0, small.n_vertices, big.n_vertices)
    return (("two poses of a torus, vertices shuffled", shuffle, one, two, 11),
            ("a sphere mapped onto a smaller ellipsoid", onto_small, big, small, 9),
            ("an ellipsoid mapped onto a larger sphere", onto_big, small, big, 12))


@grader("12-fmap", kind="build", replaces=_FMAP)
def _fmap(my_functional_map: Any) -> Verdict:
    from ...analyses._functional_maps import map_from_points

    for what, p2p, source, target, k in _unseen_pairs():
        ref = map_from_points(p2p, source, target, k_source=k, k_target=k)
        value = student_call(my_functional_map, p2p.copy(), _fresh(source), _fresh(target), k)
        hint = fmap_hint(value, p2p, source, target, ref)
        if hint is not None:
            raise Stop(WRONG, f"{hint} (Graded on {what}, k = {k}: {source.n_vertices} source and "
                              f"{target.n_vertices} target vertices, inputs the notebook does not show.)")
    return Verdict(1.0, "Right on three point maps the notebook does not show (a shuffled permutation, onto a "
                        "smaller shape, onto a larger shape).")


@functools.lru_cache(maxsize=1)
def _unseen_steps() -> tuple[tuple[str, np.ndarray, Any, Any], ...]:
    """(what, C, source, target): the shape pairs of 12-fmap, each with a seeded k x k map, a signed
    identity plus noise (not orthogonal, so that C^T and C^-1 differ and a transposed C shows)."""
    rng = np.random.default_rng(2019)  # Melzi et al.
    steps = []
    for what, _, source, target, k in _unseen_pairs():
        C = np.diag(rng.choice([-1.0, 1.0], k)) + 0.15 * rng.standard_normal((k, k))
        steps.append((what.replace(", vertices shuffled", ""), C, source, target))
    return tuple(steps)


@grader("12-zoomout-step", kind="build", replaces=_ZOOMOUT_STEP)
def _zoomout_step(my_zoomout_step: Any) -> Verdict:
    for what, C, source, target in _unseen_steps():
        value = student_call(my_zoomout_step, C.copy(), _fresh(source), _fresh(target))
        hint = zoomout_step_hint(value, C, source, target)
        if hint is not None:
            raise Stop(WRONG, f"{hint} (Graded on {what}, k = {C.shape[0]}: {source.n_vertices} source and "
                              f"{target.n_vertices} target vertices, inputs the notebook does not show.)")
    return Verdict(1.0, "Right on three maps the notebook does not show (between two poses of a torus, onto a "
                        "smaller shape, onto a larger shape).")


@grader("12-alpha", kind="predict")
def _alpha(best_alpha: Any) -> Verdict:
    return from_feedback(check_alpha_choice(best_alpha, show=False))


@functools.lru_cache(maxsize=1)
def _standing() -> tuple[Any, np.ndarray]:
    """``ref = spectra["standing"]`` and ``f_z`` of section 5, from the notebook's definitions."""
    from ...shapes import _creatures as creatures
    from ...spectral._spectrum import eigenbasis

    dog = creatures.creature("dog", "standing", n_vertices=N)  # = poses["standing"] = source
    z = dog.vertices[:, 2]
    return eigenbasis(dog, K), z - z.mean()


@grader("12-bound", kind="compute")
def _bound(bound_z: Any) -> Verdict:
    ref, f_z = _standing()
    from_feedback(check_truncation_bound(bound_z, ref, f_z, 30, show=False))
    return Verdict(1.0, "Right: ‖∇f_z‖²/λ_30 as a fraction of ‖f_z‖²_A (the standing dog's eigenbasis rebuilt "
                        "from the notebook's definitions).")


@grader("12-mirror", kind="predict")
def _mirror(with_orientation: Any, without_orientation: Any) -> Verdict:
    return from_feedback(check_mirror_maps(with_orientation, without_orientation, show=False))


@grader("12-zoomout", kind="predict")
def _zoomout(without_zoomout: Any) -> Verdict:
    return from_feedback(check_zoomout(without_zoomout, show=False))


@grader("12-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict([q1, q2, q3], [pick(q) for q in RECAP_TOOLBOX])
