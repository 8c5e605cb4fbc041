"""Graded tests of notebook 09 (spectral MDS, canonical forms): see :mod:`lbo_notebooks.exercises.grading`.

Two builds: classical MDS (09-classical-mds), judged by the Gram matrix (any rotation or
reflection is right) on distance matrices the notebook does not show, and the k x k step of
spectral MDS (09-scaling), each with the library's scaling routines (and scikit-learn's) made
unavailable.
"""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from .. import canonical_forms
from ..feedback import WRONG, Stop
from ._answers import choice, number, recap_of_choices
from ._registry import Verdict, from_feedback, grader, student_call

# --- 09-memory -----------------------------------------------------------------------------------

@grader("09-memory", kind="compute")
def _memory(classical_gb: Any) -> Verdict:
    # The prompt's n = 50,000 (not the kernel's): two n x n float64 matrices, in GB.
    gigabytes = number(classical_gb, "a number of gigabytes")
    return from_feedback(canonical_forms.check_classical_memory(gigabytes, 50_000, show=False))


# --- 09-landmarks, 09-fmm: predictions -----------------------------------------------------------

@grader("09-landmarks", kind="predict")
def _landmarks(landmark_verdict: Any) -> Verdict:
    return from_feedback(canonical_forms.check_landmark_samples(choice(landmark_verdict), show=False))


@grader("09-fmm", kind="predict")
def _fmm(fmm_verdict: Any) -> Verdict:
    return from_feedback(canonical_forms.check_fmm_gap(choice(fmm_verdict), show=False))


# --- 09-classical-mds: build it yourself --------------------------------------------------------

# What a build of classical MDS must not call: the package's MDS (public, and the routines behind
# it: the top eigenpairs, scaling in a span, the fields' variant; landmark MDS with every point a
# landmark is classical MDS, and so are spectral MDS and fast classical scaling in their limits),
# the visible check's own reference, and scikit-learn's routes to the same embedding (ClassicalMDS;
# KernelPCA of a precomputed B; Isomap, classical MDS of shortest paths; MDS and smacof, which
# minimise the stress and reach the same points on Euclidean distances). NumPy's and SciPy's
# eigensolvers are what the exercise asks for, and stay.
_CLASSICAL = (
    "lbo_notebooks.analyses._mds:classical_mds", "lbo_notebooks.analyses._mds:landmark_mds",
    "lbo_notebooks.analyses._mds:spectral_mds",
    "lbo_notebooks.analyses._mds:_scaling_with_fields",
    "lbo_notebooks.analyses._classical_scaling:top_eigenpairs",
    "lbo_notebooks.analyses._classical_scaling:scaling_in_span",
    "lbo_notebooks.analyses._fast_classical_scaling:fast_classical_scaling",
    "lbo_notebooks.exercises.canonical_forms:mds_slips",
    "lbo_notebooks.exercises.canonical_forms:_double_centred",
    "lbo_notebooks.exercises.canonical_forms:scaling_slips", "lbo_notebooks.exercises.canonical_forms:_top",
    "sklearn.manifold:ClassicalMDS.fit", "sklearn.manifold:ClassicalMDS.fit_transform",
    "sklearn.manifold:MDS.fit", "sklearn.manifold:MDS.fit_transform", "sklearn.manifold:smacof",
    "sklearn.manifold:Isomap.fit", "sklearn.manifold:Isomap.fit_transform",
    "sklearn.decomposition:KernelPCA.fit", "sklearn.decomposition:KernelPCA.fit_transform",
    "sklearn.decomposition:KernelPCA._fit_transform_in_place",
)


def _graph_distances(edges: list[tuple[int, int]], n: int) -> np.ndarray:
    import scipy.sparse as sp
    from scipy.sparse.csgraph import shortest_path

    i, j = np.array(edges).T
    return shortest_path(sp.coo_matrix((np.ones(len(i)), (i, j)), shape=(n, n)), directed=False, unweighted=True)


@functools.lru_cache(maxsize=1)
def _mds_cases() -> tuple[tuple[np.ndarray, tuple[int, ...], str], ...]:
    """(D, dims, where) that neither the notebook nor the visible check shows: points in ℝ³ (exactly
    embeddable), points on a tilted plane asked for dim 3 (a zero eigenvalue, negative at round-off),
    and three graph distances that are not Euclidean (negative eigenvalues): a 10-cycle (every
    eigenvalue twofold), a 4 × 3 grid graph asked for dim 7 (past its five positive eigenvalues) and
    a star of six leaves (a fivefold eigenvalue). Each dim ends below a gap or among the clipped
    eigenvalues, so the Gram matrix X Xᵀ is determined."""
    from scipy.spatial.distance import cdist

    rng = np.random.default_rng(9091)
    cloud = rng.normal(size=(40, 3)) * [3.0, 1.5, 0.5] + [1.0, -2.0, 4.0]
    tilt = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    plane = np.column_stack([rng.uniform(-1, 1, size=(30, 2)) * [2.0, 1.0], np.zeros(30)]) @ tilt.T
    cycle = _graph_distances([(i, (i + 1) % 10) for i in range(10)], 10)
    grid = _graph_distances([(3 * r + c, 3 * r + c + 1) for r in range(4) for c in range(2)]
                            + [(3 * r + c, 3 * r + c + 3) for r in range(3) for c in range(3)], 12)
    star = _graph_distances([(0, leaf) for leaf in range(1, 7)], 7)
    return ((cdist(cloud, cloud), (3, 2), "40 points in ℝ³"),
            (cdist(plane, plane), (3,), "30 points on a tilted plane in ℝ³"),
            (cycle, (2, 4), "the graph distances of a 10-cycle"),
            (grid, (2, 7), "the graph distances of a 4 × 3 grid"),
            (star, (5,), "the graph distances of a star with six leaves"))


@grader("09-classical-mds", kind="build", replaces=_CLASSICAL)
def _classical_mds(my_classical_mds: Any) -> Verdict:
    cases = [(D, dims, f"{where}, which the notebook does not show") for D, dims, where in _mds_cases()]
    message = canonical_forms.judge_classical_mds(my_classical_mds, cases,
                                                  call=lambda f, D, dim: student_call(f, D, dim))
    return Verdict(1.0, message.replace("Right:", "Right on five distance matrices the notebook does not show (points in "
                                        "ℝ³ and on a plane, three graph distances):", 1))


# --- 09-scaling: build it yourself ---------------------------------------------------------------

# What a build of the k x k step must not call: the package's scaling routines (public and
# private: the small eigenproblem, the top eigenpairs, the fields' variant), every MDS that ends
# in them, the visible check's own reference, and scikit-learn's classical scaling (ClassicalMDS,
# and KernelPCA, which is classical scaling of a precomputed Gram matrix).
_SCALING = (
    "lbo_notebooks.analyses._classical_scaling:scaling_in_span",
    "lbo_notebooks.analyses._classical_scaling:top_eigenpairs",
    "lbo_notebooks.analyses._mds:_scaling_with_fields", "lbo_notebooks.analyses._mds:spectral_mds",
    "lbo_notebooks.analyses._mds:classical_mds", "lbo_notebooks.analyses._mds:landmark_mds",
    "lbo_notebooks.analyses._fast_classical_scaling:fast_classical_scaling",
    "lbo_notebooks.exercises.canonical_forms:scaling_slips", "lbo_notebooks.exercises.canonical_forms:_top",
    "sklearn.manifold:ClassicalMDS.fit", "sklearn.manifold:ClassicalMDS.fit_transform",
    "sklearn.decomposition:KernelPCA.fit", "sklearn.decomposition:KernelPCA.fit_transform",
    "sklearn.decomposition:KernelPCA._fit_transform_in_place",
)


@functools.lru_cache(maxsize=1)
def _scaling_cases() -> tuple[tuple[str, np.ndarray, np.ndarray, tuple[int, ...]], ...]:
    """(label, phi, alpha, dims) that neither the notebook (a 2,000-vertex dog, dims 3 and 2) nor the
    visible check shows: the paper's form (``sampled="rows"``) of spectral MDS on an ellipsoid and a
    thin torus, with other k and q, and a plain random case (phi neither orthonormal nor with a
    constant column). Each dim is taken where the eigenvalues G[dim-1] > G[dim] are well apart."""
    from ... import shapes
    from ...analyses._mds import spectral_mds
    from ...spectral._spectrum import eigenbasis

    cases = []
    for label, mesh, k, q, dims in (
        ("an ellipsoid of 642 vertices", shapes.ellipsoid(1.0, 0.6, 0.45, subdivisions=3), 40, 60, (3, 1)),
        ("a torus of 560 vertices", shapes.torus(1.0, 0.35, 40, 14), 30, 45, (2,)),
    ):
        spectrum = eigenbasis(mesh, k)
        _, details = spectral_mds(mesh, dim=2, k=k, n_samples=q, sampled="rows", spectrum=spectrum, return_details=True)
        cases.append((label, np.array(spectrum.vectors[:, :k]), np.array(details["alpha"]), dims))
    rng = np.random.default_rng(7)
    phi = rng.normal(size=(120, 10)) * np.geomspace(1.0, 0.2, 10) + 0.3
    a = rng.normal(size=(10, 10))
    cases.append(("a random 120 × 10 basis", phi, -(a @ a.T), (4,)))
    return tuple(cases)


def _embedding(X: Any, n: int, k: int, dim: int) -> np.ndarray:
    """The returned embedding as an n x dim array, or Stop with what is wrong with its form."""
    try:
        X = np.asarray(X, dtype=np.float64)
    except Exception:  # noqa: BLE001 - whatever the answer returned
        raise Stop(WRONG, f"Return an array, one row per vertex (n × dim); got {type(X).__name__}.") from None
    if dim == 1 and X.shape == (n,):
        X = X[:, None]
    if X.shape == (dim, n) and dim != n:
        raise Stop(WRONG, f"Transposed: return one row per vertex, shape ({n}, {dim}), not ({dim}, {n}).")
    if X.shape == (k, dim):
        raise Stop(WRONG, "That is a k × dim matrix of coefficients (C = U_m G_m^½); the embedding is Q C, one row per vertex.")
    if X.ndim == 2 and X.shape[0] == n and X.shape[1] != dim:
        raise Stop(WRONG, f"Asked for dim = {dim}, you returned {X.shape[1]} columns: use the `dim` argument, not a fixed number.")
    if X.shape != (n, dim):
        raise Stop(WRONG, f"Return one row per vertex and one column per dimension, shape ({n}, {dim}); got {X.shape}.")
    if not np.all(np.isfinite(X)):
        raise Stop(WRONG, "NaN or infinity in your embedding: a square root of a negative eigenvalue? `np.linalg.eigh` "
                          "sorts ascending, and the small matrix has negative eigenvalues at the bottom; keep the largest.")
    if not np.any(X):
        raise Stop(WRONG, "Your embedding is all zeros.")
    return X


@grader("09-scaling", kind="build", replaces=_SCALING)
def _scaling(my_scaling: Any) -> Verdict:
    from ...analyses._embedding_error import gram_error

    for label, phi, alpha, dims in _scaling_cases():
        n, k = phi.shape
        for dim in dims:
            got = _embedding(student_call(my_scaling, phi.copy(), alpha.copy(), dim), n, k, dim)
            ref, slips = canonical_forms.scaling_slips(phi, alpha, dim)
            if gram_error(got, ref) <= 1e-6:
                continue
            where = f" (graded on {label}, dim = {dim}, which the notebook does not show.)"
            for slip, hint in slips:
                if gram_error(got, slip) <= 1e-6:
                    raise Stop(WRONG, hint + where)
            raise Stop(WRONG, "Not the embedding of the k × k route (Gram error above 1e-6). The steps: J Φ = Q R, "
                              "B̃ = −½ R α Rᵀ, the top eigenpairs B̃ = U G Uᵀ, then X = Q U_m G_m^½." + where)
    return Verdict(1.0, "Right on inputs the notebook does not show (an ellipsoid, a torus, a random basis; "
                        "dim = 1 to 4), without the library's scaling.")


# --- 09-recap ------------------------------------------------------------------------------------

@grader("09-recap", kind="recap")
def _recap(q1: Any, q2: Any, q3: Any) -> Verdict:
    # The prompt's defaults, k = 200 and q = 300 (tests/test_grading_09.py: they are the library's).
    return recap_of_choices([q1, q2, q3], canonical_forms.recap_canonical_forms_judges(200, 300))
