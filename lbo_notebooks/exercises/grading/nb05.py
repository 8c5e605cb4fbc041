"""Graded tests of notebook 05 (the optimality theorem): see :mod:`lbo_notebooks.exercises.grading`."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import theory
from ..feedback import WRONG, Stop
from ._registry import Verdict, from_feedback, grader, recap_verdict, student_call

# What a build of the projection P_n f must not call: the spectrum's own projection (`project`
# gives the coefficients, `reconstruct` the projection, `error` goes through it), the optimality
# module's error (through `error`), and the other helpers that project onto an A-orthonormal basis
# (`inner_product.reconstruct`, which keeps the centroid: P_n f itself when φ_0 is in the basis, and
# the Krylov solver's `_project_out`). `a_orthonormalize` stays allowed: re-orthonormalising the
# eigenvectors first is a legitimate (if unneeded) step, not the projection.
_PROJECTION = ("lbo_notebooks.spectral._spectrum:Spectrum.project", "lbo_notebooks.spectral._spectrum:Spectrum.reconstruct",
               "lbo_notebooks.spectral._spectrum:Spectrum.error",
               "lbo_notebooks.analyses._optimality:representation_error",
               "lbo_notebooks.spectral._inner_product:reconstruct", "lbo_notebooks.spectral._engine.krylov:_project_out")


def notebook_dog() -> Any:
    """The notebook's dog (``creatures.creature("dog", n_vertices=2000)``), rebuilt: never the kernel's."""
    from ...shapes._creatures import creature

    return creature("dog", n_vertices=2000)


def _unseen_spectra() -> list[tuple[str, Any, list[tuple[np.ndarray, int]]]]:
    """Spectra no notebook cell and no visible check uses, with functions and n: a bumpy torus
    (genus 1, 16 eigenpairs) and an open wavy sheet with boundary (12 eigenpairs), n from 1 (the
    constant alone) to all of them. Rebuilt at every call."""
    from ... import shapes
    from ...spectral._spectrum import eigenbasis

    rng = np.random.default_rng(5051)
    ring = shapes.torus(1.0, 0.35, 24, 10)
    bumpy = ring.with_vertices(ring.vertices * rng.uniform(0.92, 1.08, size=(ring.n_vertices, 1)))
    sheet = shapes.rectangle(1.4, 1.0, 9, 7)
    v = sheet.vertices.copy()
    v[:, :2] += rng.uniform(-0.03, 0.03, size=(len(v), 2))
    v[:, 2] = 0.25 * np.sin(2.5 * v[:, 0]) * np.cos(2 * v[:, 1])
    cases = []
    for name, mesh, k, ns in (("a bumpy torus", bumpy, 16, (1, 6, 11, 16)), ("an open sheet", sheet.with_vertices(v), 12, (3, 8, 12))):
        spectrum = eigenbasis(mesh, k)
        x, y, z = mesh.vertices.T
        smooth = x * y + z**2 + 0.3 * x
        functions = [(rng.normal(size=mesh.n_vertices) if i % 2 else smooth, n) for i, n in enumerate(ns)]
        cases.append((name, spectrum, functions))
    return cases


def _fresh(spectrum: Any) -> Any:
    """A copy of ``spectrum`` for the student's function: what it does to it reaches no reference."""
    from ...spectral._spectrum import Spectrum

    return Spectrum(np.array(spectrum.values), np.array(spectrum.vectors), spectrum.stiffness.copy(), spectrum.mass.copy())


@grader("05-projection", kind="build", replaces=_PROJECTION)
def _projection(my_project: Any) -> Verdict:
    for name, spectrum, functions in _unseen_spectra():
        phi = np.asarray(spectrum.vectors)
        for f, n in functions:
            where = f"(Graded on {name}, {spectrum.n_vertices} vertices, with n = {n}: a spectrum the notebook does not show.)"
            try:
                p = student_call(my_project, _fresh(spectrum), f.copy(), int(n))
            except Stop as stop:
                stop = theory.projection_call_stop(stop)
                raise Stop(stop.status, f"{stop.message} {where}" if stop.status == WRONG else stop.message) from None
            hint = theory.projection_slip(p, phi, spectrum.mass, f, n)
            if hint is not None:
                raise Stop(WRONG, f"{hint} {where}")
    return Verdict(1.0, "Right on two spectra the notebook does not show (a torus, an open sheet), for n from 1 "
                        "to all the eigenpairs.")


@grader("05-bound", kind="compute")
def _bound(bound_y: Any) -> Verdict:
    from ...spectral._spectrum import eigenbasis

    dog = notebook_dog()
    return from_feedback(theory.check_energy_bound(bound_y, eigenbasis(dog, 101), dog.vertices[:, 1], 20, show=False))


@grader("05-extra", kind="predict")
def _extra(extra_verdict: Any) -> Verdict:
    return from_feedback(theory.check_extra_function(extra_verdict, show=False))


@grader("05-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    return recap_verdict((q1, q2, q3), theory.RECAP_OPTIMALITY)
