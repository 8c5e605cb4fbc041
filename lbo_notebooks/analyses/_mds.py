"""Multidimensional scaling: canonical forms of surfaces from their geodesic distances.

A *canonical form* (Elad & Kimmel 2003) embeds a surface in R^m so that Euclidean distances
between the embedded vertices approximate geodesic distances on the surface. Isometric poses of
the same shape then get (nearly) the same canonical form: for exact isometries the same one up to a
translation and an orthogonal map (a rotation or a reflection); real poses stretch slightly, so
theirs nearly coincide.

* :func:`classical_mds` — the reference: double-centre the n x n squared distances and keep the
  top ``dim`` eigenpairs (a partial Lanczos solve, not a full eigendecomposition). O(n^2) memory.
* :func:`landmark_mds` — de Silva & Tenenbaum (2004): classical MDS of q landmarks, then every
  vertex is placed by distance-based triangulation from its distances to the landmarks.
* :func:`spectral_mds` — Aflalo & Kimmel (2013): every column of the squared-distance matrix is
  fitted in the span of the first ``k`` Laplace–Beltrami eigenfunctions to its values at q
  samples, whose whole distance fields are computed (least squares with a smoothness penalty:
  biharmonic energy as in the paper, or Dirichlet energy), and the scaling is done in a
  (k + q)-dimensional space (k x k in the paper's form, ``sampled="rows"`` or ``"pairs"``).
  O(n (k + q)^2) time, O(n k + q n) memory; never forms an n x n matrix.
* :func:`~lbo_notebooks.analyses.fast_classical_scaling` (:mod:`lbo_notebooks.analyses._fast_classical_scaling`) — the
  columns fitted by a smoothing spline on the surface instead of eigenfunctions.

Accuracy is compared without aligning anything by :func:`~lbo_notebooks.analyses.gram_error`
(the relative Frobenius error of the Gram matrices), and after an optimal rotation by
:func:`~lbo_notebooks.analyses.procrustes_error` (both in :mod:`lbo_notebooks.analyses._embedding_error`). The steps every variant shares (checks,
top eigenpairs, scaling in a span) are in :mod:`lbo_notebooks.analyses._classical_scaling`.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import scipy.linalg
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Indices, Integer, Number, Options, Relation, Satisfies, validated
from .._support.progress import LARGE_MESH, PROGRESS, progress_bar
from ..operators._cotangent import MESH
from ..spectral._solvers import one_blas_thread
from ._geodesics import (
    MEMORY_BUDGET,
    METHOD,
    GeodesicMethod,
    check_connected,
    check_memory,
    distance_matrix_bytes,
    farthest_point_sampling,
    geodesic_solver,
)
from ..spectral._inner_product import fix_signs, is_square_matrix
from ..spectral._mass_products import DiagonalMass, mass_operator
from ..geometry._mesh import Mesh
from ._classical_scaling import (
    DIM,
    check_dim,
    check_samples,
    dim_below,
    sample_count,
    sampling_pair,
    scaling_in_span,
    top_eigenpairs,
)
from ..spectral._spectrum import Spectrum, eigenbasis

__all__ = [
    "classical_mds",
    "landmark_mds",
    "spectral_mds",
    "scale_mu",
    "SMDS_DEFAULTS",
    "SMDS_EIGEN_TOL",
    "ENERGIES",
    "SAMPLED",
]

#: Defaults of :func:`spectral_mds` (``n_samples`` and ``k`` are capped at the number of
#: vertices). The rule: fixed counts, independent of the area and the units (mu is dimensionless,
#: :func:`scale_mu`), with more sampled fields than eigenfunctions (q = 1.5 k). The error depends on
#: the shape's geometry more than on its resolution, but it does grow slowly with n; above about 25k
#: vertices no reference can be computed here (classical MDS needs two n x n matrices), so the 1%
#: bound at 50k rests on that trend. With ``sampled="fields"`` the embedding is not confined to the
#: span of the eigenfunctions, so 200 of them do better on the tuning shapes than 300 with projected
#: rows (the previous default, k = q = 300); with q <= k the interpolation of the columns is
#: underdetermined and depends on mu, with q = 1.5 k it hardly does. Shapes that chose nothing
#: confirm the bound (recorded in ``lbo_notebooks/recorded/mds.json``), and k = 200 also costs less
#: CPU time than the previous defaults.
SMDS_DEFAULTS: dict[str, Any] = {"energy": "biharmonic", "k": 200, "n_samples": 300, "mu": 0.05, "sampled": "fields"}

#: Lanczos tolerance of the eigenbasis :func:`spectral_mds` computes itself. The embedding only
#: needs the span of the eigenfunctions and eigenvalues good to a few digits (they weigh the
#: smoothness term): with 1e-6 the eigenvalues still agree with a 1e-10 basis to 1e-14 and the
#: embedding to 1e-11 (an 8k-vertex dog, k = 200; no further gain in time at 1e-4), and the
#: eigenbasis costs less CPU time than at the default tolerance.
SMDS_EIGEN_TOL = 1e-6

#: How :func:`spectral_mds` uses the samples' squared-distance rows ``F = D2[S, :]`` (q x n):
#: ``"fields"`` uses them as they are, not projected onto the eigenfunctions, and fits only
#: the columns, ``D2 ~ (Phi M F + F.T M.T Phi.T) / 2`` (which does not reproduce the sampled rows
#: exactly), so the embedding lives in the span of the eigenfunctions *and* of the sampled fields;
#: ``"rows"`` also projects the rows onto the eigenfunctions, ``D2 ~ Phi alpha Phi.T`` with
#: ``alpha = M F A Phi`` (the paper's form of the result, ``X = Phi B``); ``"pairs"`` uses only
#: the pairs among the samples ``D2[S, S]`` (q x q), ``alpha = M D2[S, S] M.T`` (the closed form of
#: Aflalo & Kimmel as reimplemented elsewhere).
SAMPLED = ("fields", "rows", "pairs")


def _got(value: Any) -> str:
    """What a message says was passed instead of a matrix: "shape (3, 4)", or "a ragged sequence"."""
    try:
        return f"shape {np.shape(value)}"
    except ValueError:
        return "a ragged sequence"


# --- classical MDS ----------------------------------------------------------------------------
def _mesh_or_square(distances: Any) -> bool:
    return isinstance(distances, Mesh) or is_square_matrix(distances)


def _points(distances: Any) -> int:
    """n: the vertices of a mesh or the rows of a (square) distance matrix."""
    return distances.n_vertices if isinstance(distances, Mesh) else np.shape(distances)[0]


def _too_large(distances: Any, dim: int, **_: Any) -> str:
    points = "vertices" if isinstance(distances, Mesh) else "points"
    return f"dim={dim} must be smaller than the number of {points} ({_points(distances)})."


@validated(
    distances=Satisfies(_mesh_or_square,
                        message=lambda name, value: f"distances must be a square (n, n) matrix, got {_got(value)}."),
    dim=(DIM, Relation(lambda distances, dim, **_: dim < _points(distances), _too_large)),
    memory_budget=MEMORY_BUDGET,
    progress=PROGRESS,
)
def classical_mds(
    distances: ArrayLike | Mesh,
    dim: int = 3,
    *,
    method: GeodesicMethod = "heat",
    memory_budget: float | None = None,
    progress: bool | None = None,
) -> NDArray[np.float64]:
    """Classical (Torgerson) MDS: ``X = U_m Gamma_m^(1/2)`` of ``B = -1/2 J D2 J``.

    ``D2`` holds squared distances and ``J = I - 1 1.T / n`` centres. Only the ``dim`` largest
    eigenpairs of B are computed (Lanczos, ``eigsh(which="LA")``), in O(n^2) per iteration.
    Eigenvalues below zero (non-Euclidean distances) contribute nothing.

    Parameters
    ----------
    distances : (n, n) array or Mesh
        A full distance matrix (symmetrised here), or a mesh, whose all-pairs geodesic distances
        are computed with ``method`` — after the memory check, so an impossible size fails at once.
    dim : int, default 3
        Embedding dimension, ``dim < n``.
    method : {"heat", "exact", "fmm"}
        Geodesic method when ``distances`` is a mesh.
    memory_budget : float, optional
        Bytes this call may use. Classical MDS needs two n x n float64 matrices (the distances and
        B); a size that would not fit raises ``MemoryError`` stating the memory it would need.
        Default: half of the memory available now (psutil).
    progress : bool, optional
        Progress bar for the all-pairs distances (default: on for at least 500 vertices).

    Returns
    -------
    ndarray, shape (n, dim)
        Centred; column signs fixed by :func:`~lbo_notebooks.spectral.fix_signs`.

    Examples
    --------
    >>> from scipy.spatial.distance import cdist
    >>> P = np.random.default_rng(0).normal(size=(30, 3))
    >>> X = classical_mds(cdist(P, P), dim=3)
    >>> bool(np.allclose(cdist(X, X), cdist(P, P)))
    True
    """
    if isinstance(distances, Mesh):
        mesh = distances
        check_connected(mesh, "classical MDS on geodesic distances")
        n = mesh.n_vertices
        check_memory(2 * distance_matrix_bytes(n, n), memory_budget,
                      f"classical MDS on {n} vertices (two {n} x {n} float64 matrices)",
                      "simplify the mesh (fewer vertices)")
        D2 = geodesic_solver(mesh, method).distances(
            np.arange(n), progress=progress, memory_budget=float("inf")
        )
        np.square(D2, out=D2)  # our own buffer: square in place
    else:
        D = np.asarray(distances, dtype=np.float64)
        n = D.shape[0]
        # Inline, on the one float64 copy: the table also takes a Mesh, and D may be large.
        if not np.all(np.isfinite(D)):
            raise ValueError("distances contain NaN or inf (a disconnected mesh?); MDS needs finite distances.")
        if np.any(D < 0):
            raise ValueError("distances must be non-negative.")
        check_memory(2 * distance_matrix_bytes(n, n), memory_budget,
                      f"classical MDS on {n} points (two more {n} x {n} float64 matrices)",
                      "use fewer points")
        D2 = np.square(D)  # a new buffer: the caller's matrix is never modified
    # B = -1/2 J D2 J with D2 symmetrised (heat distances are not exactly symmetric).
    B = np.add(D2, D2.T)
    del D2
    B *= -0.25
    row = B.mean(axis=1)
    B -= row[:, None]
    B -= row[None, :]
    B += row.mean()
    vals, vecs = top_eigenpairs(B, dim)
    del B
    X = vecs * np.sqrt(np.maximum(vals, 0.0))
    return fix_signs(X - X.mean(axis=0))


# --- landmark MDS -----------------------------------------------------------------------------
def _with_mesh(mesh_or_distances: Any, landmarks: Any, **_: Any) -> bool:
    return not (isinstance(mesh_or_distances, Mesh) and landmarks is not None)


def _with_distances(mesh_or_distances: Any, landmarks: Any, **_: Any) -> bool:
    return isinstance(mesh_or_distances, Mesh) or landmarks is not None


@validated(
    dim=DIM,
    mesh_or_distances=Satisfies(
        lambda value: isinstance(value, Mesh) or np.ndim(value) == 2,
        message=lambda name, value: f"distances must be a (q, n) array (landmarks x vertices), got {_got(value)}."),
    landmarks=(
        Relation(_with_mesh, "landmarks= goes with a precomputed (q, n) distance array, not with a mesh."),
        Relation(_with_distances, "with a distance array, pass landmarks= (the vertex index of each row)."),
        Indices(lambda mesh_or_distances, **_: np.shape(mesh_or_distances)[1] - 1,
                length=lambda mesh_or_distances, **_: np.shape(mesh_or_distances)[0], none=True,
                what="{length} integer vertex indices in 0..{high}, one per row of distances",
                hint="landmarks= are the vertices of the {length} rows of distances"),
    ),
    progress=PROGRESS,
)
def landmark_mds(
    mesh_or_distances: Mesh | ArrayLike,
    dim: int = 3,
    n_samples: int = 300,
    *,
    landmarks: ArrayLike | None = None,
    method: GeodesicMethod = "heat",
    progress: bool | None = None,
) -> NDArray[np.float64]:
    """Landmark MDS (de Silva & Tenenbaum 2004).

    1. q landmarks (farthest-point samples, chosen in edge-graph distance) and their geodesic
       distance fields ``Delta`` (q x n);
    2. classical MDS of the q x q block of squared distances: ``L = U_m Gamma_m^(1/2)``;
    3. every vertex a is placed by distance-based triangulation
       ``x_a = -1/2 L^# (delta_a - delta_mean)``, with ``L^# = Gamma_m^(-1/2) U_m.T`` and
       ``delta_mean`` the mean column of the landmarks' squared distances.

    The result is then centred over all vertices. O(n q dim) time, O(n q) memory.

    Parameters
    ----------
    mesh_or_distances : Mesh or (q, n) array
        A connected mesh, or precomputed distances from q landmarks to all n vertices (then
        ``landmarks`` must give each row's vertex).
    dim : int, default 3
        Embedding dimension, ``dim < q``.
    n_samples : int, default 300
        Number of landmarks q for a mesh, ``2 <= q <= n``.
    landmarks : sequence of int, optional
        With a distance array: the vertex of each row (not allowed with a mesh).
    method : {"heat", "exact", "fmm"}
        Geodesic method for a mesh.
    progress : bool, optional
        Progress bar for the sampling.

    Returns
    -------
    ndarray, shape (n, dim)

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> X = landmark_mds(shapes.ellipsoid(subdivisions=3), n_samples=60)
    >>> X.shape
    (642, 3)
    """
    if isinstance(mesh_or_distances, Mesh):
        mesh = mesh_or_distances
        check_connected(mesh, "landmark MDS")
        q = check_samples(n_samples, mesh.n_vertices)
        idx, delta = farthest_point_sampling(mesh, q, method=method, return_distances=True, progress=progress, select="graph")
    else:
        delta = np.asarray(mesh_or_distances, dtype=np.float64)
        idx = landmarks
        # Inline, on the one float64 copy (the table also takes a Mesh).
        if not np.all(np.isfinite(delta)):
            raise ValueError("distances contain NaN or inf (a disconnected mesh?).")
    q = delta.shape[0]
    dim = check_dim(dim, q, "the number of landmarks")
    # (q, n) squared distances: in place when the distances are our own, never in the caller's array
    sq = np.square(delta, out=delta) if isinstance(mesh_or_distances, Mesh) else delta**2
    block = sq[:, idx]
    block = 0.5 * (block + block.T)
    mean_col = block.mean(axis=1)
    Bq = -0.5 * (block - mean_col[:, None] - mean_col[None, :] + mean_col.mean())
    vals, vecs = top_eigenpairs(Bq, dim)
    if np.any(vals <= 1e-12 * max(vals[0], 1e-300)):
        raise ValueError(
            f"the landmarks span fewer than dim={dim} positive directions; use more landmarks or a smaller dim."
        )
    pinv = vecs / np.sqrt(vals)  # (q, dim): columns of L^#.T
    X = -0.5 * (sq.T @ pinv - mean_col @ pinv)  # = -1/2 (sq - mean_col 1.T).T pinv, without a (q, n) copy
    return fix_signs(X - X.mean(axis=0))


# --- spectral MDS -----------------------------------------------------------------------------
#: The interpolation energies of :func:`spectral_mds`: the power of Lam in the regulariser.
ENERGIES: dict[str, int] = {"dirichlet": 1, "biharmonic": 2}


_ENERGY = Options(*ENERGIES, message=f"energy must be one of {sorted(ENERGIES)} (the interpolation's smoothness "
                  "term), got {value!r}.")


def _or_default(name: str, value: int | None, mesh: Mesh) -> int:
    """``k`` or ``n_samples`` as passed, or by default that of :data:`SMDS_DEFAULTS`, at most the vertex count."""
    return min(SMDS_DEFAULTS[name], mesh.n_vertices) if value is None else value


@validated(energy=_ENERGY)
def scale_mu(
    mu: float, phi_s: NDArray[np.float64], eigenvalues: NDArray[np.float64], *, energy: str = "dirichlet"
) -> float:
    """The absolute regulariser ``mu_abs = mu * ||Phi_s.T Phi_s||_2 / lam[k-1]**p`` (docs/maths.md, "Multidimensional scaling").

    ``p = 1`` for the Dirichlet energy ``sum lam_i c_i^2`` and ``p = 2`` for the biharmonic one
    ``sum lam_i^2 c_i^2``. ``Phi_s.T Phi_s`` scales with the number of samples and with 1/area, and
    ``lam`` with 1/length^2; dividing them out makes ``mu`` dimensionless, so one value of ``mu``
    can serve meshes of different sizes, resolutions, units and sample counts.

    Examples
    --------
    >>> phi_s, lam = np.eye(3), np.array([0.0, 1.0, 4.0])
    >>> scale_mu(0.5, phi_s, lam), scale_mu(0.5, phi_s, lam, energy="biharmonic")
    (0.125, 0.03125)
    """
    power = ENERGIES[energy]
    top = float(np.linalg.norm(phi_s, 2)) ** 2
    return float(mu) * top / float(eigenvalues[-1]) ** power


def _scaling_with_fields(
    phi: NDArray[np.float64], m: NDArray[np.float64], fields: NDArray[np.float64], M: NDArray[np.float64], dim: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Classical scaling of ``D2 ~ (Phi M F + F.T M.T Phi.T) / 2`` (``sampled="fields"``), ``(X, G)``.

    ``F`` = ``fields`` (q x n, squared distances), ``m`` the column means of ``Phi``. Then
    ``B = -1/2 J D2 J = C middle C.T`` with ``C = J [Phi, F.T]`` (n x (k + q)) and
    ``middle = -1/4 [[0, M], [M.T, 0]]``, and ``scaling_in_span`` needs only ``C.T C``: built from
    ``[Phi, F.T].T [Phi, F.T]`` minus the rank-one centring term, O(n (k + q)^2), without a copy of
    ``F``. Returns the (uncentred) embedding and the eigenvalues, descending.
    """
    n, k = phi.shape
    q = fields.shape[0]
    f = fields.mean(axis=1)
    gram = np.empty((k + q, k + q))
    gram[:k, :k] = phi.T @ phi
    gram[:k, k:] = phi.T @ fields.T
    gram[k:, :k] = gram[:k, k:].T
    gram[k:, k:] = fields @ fields.T
    # Columns of unit length (before centring, so that the constant eigenfunction, which centring
    # annihilates, stays at round-off and is dropped): eigenfunctions and squared distances have
    # unrelated units.
    unit = 1.0 / np.sqrt(np.diag(gram))
    means = np.concatenate([m, f])
    gram -= n * np.outer(means, means)
    middle = np.zeros((k + q, k + q))
    middle[:k, k:] = -0.25 * M
    middle[k:, :k] = -0.25 * M.T
    y, G = scaling_in_span(gram * np.outer(unit, unit), middle / np.outer(unit, unit), dim)
    y *= unit[:, None]
    return phi @ y[:k] + fields.T @ y[k:], G


def _spectrum_fits(mesh: Mesh, k: int | None, spectrum: Spectrum | None, **_: Any) -> bool:
    return spectrum is None or (spectrum.n_vertices == mesh.n_vertices and spectrum.k >= _or_default("k", k, mesh))


def _spectrum_misfit(mesh: Mesh, k: int | None, spectrum: Spectrum, **_: Any) -> str:
    k, n = _or_default("k", k, mesh), mesh.n_vertices
    return (f"spectrum has {spectrum.k} eigenpairs on {spectrum.n_vertices} vertices; need at least "
            f"k={k} on this mesh's {n} vertices. Compute it with eigenbasis(mesh, {k}).")


@validated(
    mesh=MESH,
    method=METHOD,
    k=Integer(2, lambda mesh, **_: mesh.n_vertices, none=True,
              what="an integer between 2 and the number of vertices ({high})"),
    dim=dim_below(lambda mesh, k, **_: _or_default("k", k, mesh),
                  "k (the embedding lives in the span of the eigenfunctions)"),
    n_samples=sample_count(lambda mesh, **_: mesh.n_vertices, none=True),
    energy=_ENERGY,
    sampled=Options(*SAMPLED, message=(
        "sampled must be 'fields' (the samples' distance fields, unprojected), 'rows' (those fields projected onto "
        "the eigenfunctions) or 'pairs' (the distances among the samples only), got {value!r}.")),
    mu=Number(0, open_low=True, what="a positive number (dimensionless; try 0.05)"),
    spectrum=(Satisfies(lambda spectrum: isinstance(spectrum, Spectrum), none=True,
                        message="spectrum must be a Spectrum (from eigenbasis), got {type}."),
              Relation(_spectrum_fits, _spectrum_misfit)),
    sampling=sampling_pair(lambda mesh, n_samples, **_: _or_default("n_samples", n_samples, mesh), "k"),
    progress=PROGRESS,
)
def spectral_mds(
    mesh: Mesh,
    dim: int = 3,
    *,
    n_samples: int | None = None,
    k: int | None = None,
    mu: float = 0.05,
    method: GeodesicMethod = "heat",
    energy: str = "biharmonic",
    sampled: str = "fields",
    spectrum: Spectrum | None = None,
    sampling: tuple[ArrayLike, ArrayLike] | None = None,
    progress: bool | None = None,
    return_details: bool = False,
) -> NDArray[np.float64] | tuple[NDArray[np.float64], dict[str, Any]]:
    """Spectral MDS (Aflalo & Kimmel 2013): canonical form from q sampled distance rows.

    1. ``Phi`` (n x k), ``Lam``: the first ``k`` LBO eigenpairs; q farthest-point samples S and
       their squared geodesic distance fields ``F = D2[S, :]`` (q x n); ``Phi_s`` the rows of Phi
       at the samples;
    2. ``M = (Phi_s.T Phi_s + mu_abs Lam^p)^-1 Phi_s.T`` (k x q) fits values at the samples in
       the span: least squares plus ``mu_abs`` times the biharmonic energy (``p = 2``, the
       paper's choice, default) or the Dirichlet energy (``p = 1``); as ``mu -> 0`` with
       ``q <= k`` it becomes the smoothest interpolant. Column j of D2 is the distance field of
       vertex j, known at the samples (``F[:, j]``), so ``Phi M F`` fits every column;
    3. the approximate ``D2``, from which ``B = -1/2 J D2 J`` is scaled:

       - ``sampled="fields"`` (default): ``D2 ~ (Phi M F + F.T M.T Phi.T) / 2``. The sampled fields
         enter as they are, not projected onto the eigenfunctions (the approximation does not
         reproduce the sampled rows exactly), so B lives in the span of ``J [Phi, F.T]`` (k + q
         columns) and the embedding is not confined to the span of the eigenfunctions (whose
         projection of the classical embedding is the floor of the other two forms);
       - ``sampled="rows"``: ``D2 ~ Phi alpha Phi.T`` with ``alpha = M F A Phi`` (symmetrised):
         each sampled row is also projected onto the eigenfunctions (its A-inner products). This is
         the paper's form of the result, ``X = Phi B``;
       - ``sampled="pairs"``: ``alpha = M D2[S, S] M.T``, both directions interpolated from the
         q x q block among the samples (the closed form as reimplemented elsewhere); rows need
         about half the samples for the same accuracy;
    4. reduced scaling: with ``C = Q R`` (Q orthonormal; R from the small Gram matrix ``C.T C``,
       see ``scaling_in_span``), ``C = J [Phi, F.T]`` (fields) or ``J Phi`` (rows, pairs),
       eigendecompose the small ``R middle R.T = U G U.T``; ``X = Q U_m G_m^(1/2)``.

    Cost O(n (k + q)^2) plus q geodesic solves and the eigenbasis; memory O(n k + q n)
    (``"pairs"``: O(n k + q^2)). No n x n matrix is formed.

    Parameters
    ----------
    mesh : Mesh
        A connected mesh.
    dim : int, default 3
        Embedding dimension, ``dim < k``.
    n_samples : int, optional
        Number of farthest-point samples q, ``2 <= q <= n``. Default ``min(300, n)``
        (:data:`SMDS_DEFAULTS`).
    k : int, optional
        Number of LBO eigenfunctions k. Default ``min(200, n)``. Accuracy depends on it and on q
        far more than on mu.
    mu : float, default 0.05
        Dimensionless smoothness weight; the absolute weight is given by :func:`scale_mu`.
    method : {"heat", "exact", "fmm"}
        Geodesic method for the sample distances (passed to the geodesic solver).
    energy : {"biharmonic", "dirichlet"}, default "biharmonic"
        Smoothness term of the interpolation: ``sum_i lam_i^2 c_i^2`` (the paper's) or
        ``sum_i lam_i c_i^2``. Each at its best ``mu``, biharmonic was as accurate or
        better, and far less sensitive to ``mu``.
    sampled : {"fields", "rows", "pairs"}, default "fields"
        What is kept of the samples' distance fields (see step 3).
    spectrum : Spectrum, optional
        A precomputed eigenbasis of ``mesh`` with at least ``k`` pairs (its first ``k``
        are used). Lets a parameter sweep pay for the eigenbasis once.
    sampling : (samples, distances), optional
        A precomputed ``farthest_point_sampling(mesh, count, method=..., select="graph", return_distances=True)``
        with ``count >= n_samples``; its first ``n_samples`` are used (sampling is nested).
    progress : bool or None, default None
        A progress bar over the stages (eigenbasis, samples and their distance fields,
        embedding). ``None``: only for meshes of 10,000 vertices or more, and only in a notebook
        or a terminal (never in a log file or under pytest); see :mod:`lbo_notebooks._support.progress`.
    return_details : bool, default False
        Also return a dict with ``samples``, ``eigenvalues`` (the top ``dim + 1`` of the reduced
        problem), ``eigengap`` (``G[dim-1] / G[dim]``), ``mu_abs``, ``sampled``, ``alpha`` (the k x k
        coefficients of ``D2 ~ Phi alpha Phi.T``; ``None`` for ``"fields"``) and ``timings`` (seconds for
        ``eigenbasis``, ``sampling`` (including the distances), ``embedding``, ``total``).

    Returns
    -------
    ndarray, shape (n, dim)
        Centred; column signs fixed. With ``return_details``, ``(X, details)``.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> m = shapes.ellipsoid(subdivisions=3)
    >>> X = spectral_mds(m, n_samples=100, k=40)
    >>> X.shape
    (642, 3)
    """
    t0 = time.perf_counter()
    check_connected(mesh, "spectral MDS")
    n = mesh.n_vertices
    k, q = _or_default("k", k, mesh), _or_default("n_samples", n_samples, mesh)
    power = ENERGIES[energy]

    # One BLAS thread throughout (unless the user chose the count): the eigensolver and the heat
    # method limit themselves anyway, and OpenBLAS threads spinning against another program made
    # the embedding's products many times slower.
    with one_blas_thread(), progress_bar(3, "spectral MDS", progress, long=n >= LARGE_MESH) as bar:
        # 1. eigenbasis
        bar.set_postfix_str("eigenbasis", refresh=True)
        if spectrum is None:
            spectrum = eigenbasis(mesh, k, tol=SMDS_EIGEN_TOL, progress=False)
        phi = spectrum.vectors[:, :k]
        lam = np.maximum(spectrum.values[:k], 0.0)
        t1 = time.perf_counter()
        bar.update()
        bar.set_postfix_str("samples and their distance fields", refresh=True)

        # 2. samples and their squared distances: whole rows (q x n), or only the q x q block among the
        # samples (each field is still solved on the whole mesh)
        if sampling is None and sampled != "pairs":
            samples, ds = farthest_point_sampling(mesh, q, method=method, select="graph", return_distances=True, progress=False)
            np.square(ds, out=ds)
        elif sampling is None:
            samples = farthest_point_sampling(mesh, q, method=method, select="graph")
            ds = geodesic_solver(mesh, method).distances(samples, targets=samples, progress=False) ** 2
        else:
            samples, fields = (np.asarray(a) for a in sampling)
            samples = samples[:q].astype(np.int64)
            ds = fields[:q] ** 2 if sampled != "pairs" else fields[:q][:, samples] ** 2
        t2 = time.perf_counter()
        bar.update()
        bar.set_postfix_str("embedding", refresh=True)

        # 3. the interpolation operator M (k x q), then the coefficients alpha (k x k) of D2 ~ Phi alpha Phi.T
        phi_s = phi[samples]
        mu_abs = scale_mu(mu, phi_s, lam, energy=energy)
        M = scipy.linalg.solve(phi_s.T @ phi_s + mu_abs * np.diag(lam**power), phi_s.T, assume_a="pos")
        m = phi.mean(axis=0)
        if sampled == "fields":
            X, G = _scaling_with_fields(phi, m, ds, M, dim)
            alpha = None
        elif sampled == "rows":
            # Each row's coefficients are its A-inner products with the eigenfunctions; then the other
            # direction is interpolated. ds is this function's own array: a lumped mass scales it in place.
            mass = mass_operator(spectrum.mass)
            if isinstance(mass, DiagonalMass):
                ds *= mass.diagonal
                alpha = M @ (ds @ phi)
            else:
                alpha = M @ (ds @ (mass @ phi))
        else:
            alpha = M @ (0.5 * (ds + ds.T)) @ M.T
        del ds
        if alpha is not None:
            alpha = 0.5 * (alpha + alpha.T)
            # 4. reduced classical scaling in the span of J Phi (J Phi = Phi - 1 m.T, never formed)
            gram = phi.T @ phi - n * np.outer(m, m)
            y, G = scaling_in_span(gram, -0.5 * alpha, dim)
            X = phi @ y
        X = fix_signs(X - X.mean(axis=0))
        t3 = time.perf_counter()
        bar.update()
    if not return_details:
        return X
    details = {
        "samples": samples,
        "eigenvalues": G[: dim + 1].copy(),
        "eigengap": float(G[dim - 1] / G[dim]) if G[dim] > 0 else float("inf"),
        "mu_abs": mu_abs,
        "sampled": sampled,
        "alpha": alpha,
        "timings": {"eigenbasis": t1 - t0, "sampling": t2 - t1, "embedding": t3 - t2, "total": t3 - t0},
    }
    return X, details
