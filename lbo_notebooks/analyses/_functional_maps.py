"""Functional maps: a correspondence between two shapes as a small matrix in the spectral domain.

A point map ``p2p`` sending every target vertex ``i`` to a source vertex ``p2p[i]`` pulls functions
back from source to target, ``(Pi f)[i] = f[p2p[i]]``. In A-orthonormal eigenbases (``Phi_1`` on
the source, ``Phi_2`` on the target) it becomes the ``k_2 x k_1`` matrix

    C = Phi_2.T A_2 Pi Phi_1                    (:func:`map_from_points`),

which takes source coefficients to target coefficients (Ovsjanikov et al. 2012). For an isometry
``C`` is nearly diagonal: eigenfunctions go to eigenfunctions, up to sign and to mixing inside
clusters of nearly equal eigenvalues.

Estimating ``C`` from descriptors (:func:`estimate_map`) minimises the quadratic energy

    ||C D_1 - D_2||^2                                   descriptors preserved
    + w_lap ||C Lam_1 - Lam_2 C||^2                     commutes with the Laplacian (isometry)
    + w_comm sum_f ||C Omega_1^f - Omega_2^f C||^2      commutes with multiplication by descriptors
    + w_orient sum_f ||C O_1^f - O_2^f C||^2            preserves orientation (Ren et al. 2018)

with ``D = Phi.T A F`` the descriptor coefficients, ``Omega^f = Phi.T A diag(f) Phi`` and
``O^f[i, j] = int phi_i (n x grad f) . grad phi_j dA`` (:func:`orientation_operators`). The last
term separates a shape from its mirror image, which every intrinsic descriptor confuses. The
energy is quadratic in ``C``, so it is minimised exactly by one dense linear solve of size
``k_1 k_2`` (no iterative optimiser, no initial guess).

A point map is recovered from ``C`` by nearest neighbours (:func:`points_from_map`), and ZoomOut
(Melzi et al. 2019, :func:`zoomout`) alternates the two conversions while growing ``k``, on every
vertex or, as its authors suggest for large meshes, on farthest-point samples with one final
conversion on every vertex.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Array, Indices, Integer, Number, Relation, Satisfies, validated
from .._support.progress import LARGE_MESH, PROGRESS, progress_bar
from ..spectral._inner_product import a_norms
from ..geometry._mesh import Mesh
from ..spectral._spectrum import Spectrum
from ..spectral._solvers import default_workers, one_blas_thread

__all__ = [
    "map_from_points",
    "points_from_map",
    "estimate_map",
    "zoomout",
    "face_gradients",
    "orientation_operators",
    "multiplication_operators",
]


_SPECTRUM = Satisfies(lambda s: isinstance(s, Spectrum),
                      message="{name} must be a Spectrum (from lbo_notebooks.eigenbasis), got {type}.")
_WEIGHT = Number(0)


def _eigenpairs(computed: Any, none: bool = False) -> Integer:
    """A number of basis functions, 1..``computed(**arguments)`` (the eigenpairs of a spectrum)."""
    return Integer(1, computed, none=none, what="an integer between 1 and the number of eigenpairs computed ({high})",
                   hint="compute more eigenpairs with eigenbasis(mesh, k)")


#: A point map from the target to the source: one source vertex per target vertex.
_P2P = Indices(
    lambda source, **_: source.n_vertices - 1,
    length=lambda target, **_: target.n_vertices,
    what="an integer array of shape ({length},): one source vertex per target vertex",
    hint=lambda source, **_: f"the source has {source.n_vertices} vertices",
)


def _map_shape(source: Spectrum, target: Spectrum, **_: Any) -> str:
    return f"be a finite (k_target, k_source) matrix with k_target <= {target.k} and k_source <= {source.k}"


#: A functional map no larger than the two bases (the Relation reads the checked ``C``).
_MAP = (
    Array(2, nonempty=True, what=_map_shape),
    Relation(lambda C, source, target, **_: C.shape[0] <= target.k and C.shape[1] <= source.k,
             lambda C, source, target, **_: f"C must {_map_shape(source, target)}; got {C.shape}"),
)


@validated(
    source=_SPECTRUM,
    target=_SPECTRUM,
    k_source=_eigenpairs(lambda source, **_: source.k, none=True),
    k_target=_eigenpairs(lambda target, **_: target.k, none=True),
    p2p=_P2P,
)
def map_from_points(
    p2p: ArrayLike, source: Spectrum, target: Spectrum, *, k_source: int | None = None, k_target: int | None = None
) -> NDArray[np.float64]:
    """The functional map ``C = Phi_2.T A_2 Pi Phi_1`` of a point map, shape (k_target, k_source).

    Parameters
    ----------
    p2p : int array, shape (n_target,)
        ``p2p[i]`` is the source vertex matched to target vertex ``i``.
    source, target : Spectrum
    k_source, k_target : int, optional
        Number of basis functions on each side (default: all computed).

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.ellipsoid(subdivisions=3), 6)
    >>> C = map_from_points(np.arange(s.n_vertices), s, s)
    >>> bool(np.allclose(C, np.eye(6), atol=1e-10))      # identity map -> identity matrix
    True
    """
    k1 = source.k if k_source is None else k_source
    k2 = target.k if k_target is None else k_target
    p = np.asarray(p2p)  # int64 source vertices, checked by the table
    return target.vectors[:, :k2].T @ (target.mass @ source.vectors[p, :k1])


def _nearest_rows(
    queries: NDArray[np.float64], points: NDArray[np.float64], *, dtype: type = np.float64, workers: int | None = None
) -> NDArray[np.int64]:
    """Index of the nearest row of ``points`` (Euclidean) for every row of ``queries``; exact.

    ``|q - p|^2 = |q|^2 - 2 q.p + |p|^2``, so the nearest ``p`` maximises ``q.p - |p|^2 / 2``:
    with ``-|p|^2 / 2`` appended to every point and ``1`` to every query, that is a matrix
    product and an argmax along its rows, done on tiles of 1024 queries x 2048 points (faster
    than full rows of points, whose products leave the cache before the argmax reads them). A
    k-d tree, the textbook answer, degrades to a near-exhaustive search in the 30-80 dimensions of a
    spectral embedding, and there its scalar distance loops lose clearly to the matrix product.
    ``dtype=np.float32`` is faster (half the memory traffic); the scores it compares differ by
    ``|p - p'|^2 / 2`` between neighbouring points, far above its rounding, so only near-ties can
    change.

    The blocks of 1024 queries are shared among ``workers`` threads (default: the usable cores,
    at most 2), each running BLAS on one thread (:mod:`lbo_notebooks.spectral._engine.threads`): the argmax
    runs in parallel too, and no BLAS thread spins waiting for a core that another program holds.
    Every block is computed alone, so the result does not depend on
    ``workers``.
    """
    n_points, dim = points.shape
    augmented = np.empty((dim + 1, n_points), dtype=dtype)
    augmented[:-1] = points.T
    augmented[-1] = -0.5 * np.einsum("ij,ij->i", points, points)
    rows = np.empty((len(queries), dim + 1), dtype=dtype)
    rows[:, :-1] = queries
    rows[:, -1] = 1.0
    out = np.empty(len(queries), dtype=np.int64)

    def search(start: int) -> None:
        block = rows[start : start + 1024]
        best = np.full(len(block), -np.inf, dtype=dtype)
        at = out[start : start + 1024]
        for first in range(0, n_points, 2048):
            scores = block @ augmented[:, first : first + 2048]
            arg = scores.argmax(axis=1)
            value = scores[np.arange(len(block)), arg]
            better = value > best  # ties keep the lower index, as one argmax over all points would
            best[better] = value[better]
            at[better] = arg[better] + first

    starts = range(0, len(queries), 1024)
    workers = min(default_workers() if workers is None else workers, len(starts))
    if workers <= 1:
        for start in starts:
            search(start)
        return out
    with one_blas_thread(), ThreadPoolExecutor(max_workers=workers) as pool:
        list(pool.map(search, starts))
    return out


@validated(source=_SPECTRUM, target=_SPECTRUM, C=_MAP)
def points_from_map(C: ArrayLike, source: Spectrum, target: Spectrum) -> NDArray[np.int64]:
    """Point map of a functional map: nearest neighbours in the spectral embedding.

    A delta at source vertex ``j`` has coefficients ``Phi_1[j]``; ``C`` carries them to
    ``C Phi_1[j]``, and target vertex ``i`` is matched to the source vertex whose image is nearest
    to its own coefficients ``Phi_2[i]`` (rows of ``Phi_2`` against rows of ``Phi_1 C.T``). The
    search is exhaustive, by blocks of matrix products in single precision (a few seconds for
    50,000 vertices on each side, ``k = 80``).

    Returns
    -------
    ndarray of int, shape (n_target,)
        ``p2p[i]``, the source vertex of target vertex ``i``.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.bumpy_sphere(2), 10)
    >>> bool((points_from_map(np.eye(10), s, s) == np.arange(s.n_vertices)).all())  # identity
    True
    """
    C = np.asarray(C)  # float64, checked by the table
    k2, k1 = C.shape
    return _nearest_rows(target.vectors[:, :k2], source.vectors[:, :k1] @ C.T, dtype=np.float32)


def _check_samples(samples: Any, source: Spectrum, target: Spectrum) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    try:
        s1, s2 = (np.asarray(s) for s in samples)
    except (TypeError, ValueError):
        raise ValueError(
            "samples must be a pair (source vertex indices, target vertex indices), e.g. from "
            "farthest_point_sampling on each shape."
        ) from None
    for name, arr, n in (("source", s1, source.n_vertices), ("target", s2, target.n_vertices)):
        if arr.ndim != 1 or arr.size == 0 or not np.issubdtype(arr.dtype, np.integer):
            raise ValueError(f"the {name} samples must be a non-empty 1-D array of vertex indices, "
                             f"got dtype {arr.dtype} and shape {arr.shape}.")
        if arr.min() < 0 or arr.max() >= n:
            raise ValueError(
                f"the {name} samples hold vertex indices outside 0..{n - 1} (the {name} has {n} vertices).")
    return s1.astype(np.int64), s2.astype(np.int64)


@validated(
    source=_SPECTRUM,
    target=_SPECTRUM,
    k_final=_eigenpairs(lambda source, target, **_: min(source.k, target.k), none=True),
    step=Integer(1),
    C=(*_MAP, Relation(lambda C, k_final, **_: k_final is None or min(C.shape) <= k_final,
                       "C is already {C.shape}, larger than k_final={k_final}.")),
    progress=PROGRESS,
)
def zoomout(
    C: ArrayLike,
    source: Spectrum,
    target: Spectrum,
    *,
    k_final: int | None = None,
    step: int = 1,
    samples: tuple[ArrayLike, ArrayLike] | None = None,
    progress: bool | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """ZoomOut refinement (Melzi et al. 2019): grow ``C`` from (k, k) to (k_final, k_final).

    Each iteration converts ``C`` to a point map and the point map back to a functional map
    ``step`` sizes larger. The high frequencies this adds are what makes the point map precise.

    Parameters
    ----------
    C : array, shape (k, k)
        The initial map (e.g. :func:`estimate_map`).
    source, target : Spectrum
        At least ``k_final`` eigenpairs each.
    k_final : int, optional
        Final size (default: all computed eigenpairs of the smaller spectrum).
    step : int, default 1
        Functions added per iteration.
    samples : (source indices, target indices), optional
        Iterate on these vertices only, then convert the final map once on all vertices (the
        sampled variant of the ZoomOut paper): the point maps of the iterations go from target
        samples to source samples, and each new map is the least-squares fit
        ``Phi_2[S_2] C ~ Phi_1[p2p]`` on the samples, which needs many more samples than
        ``k_final`` and samples that cover the shapes evenly (farthest-point samples weigh every
        part of the surface alike). Default: every vertex, the map from :func:`map_from_points`.
    progress : bool or None, default None
        A progress bar over the iterations. ``None``: only for meshes of 10,000 vertices or
        more, and only in a notebook or a terminal (never in a log file or under pytest).

    Returns
    -------
    C : ndarray, shape (k_final, k_final)
    p2p : ndarray of int, shape (n_target,)
        The point map of the final ``C``, on all vertices.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.bumpy_sphere(2), 12)
    >>> C, p2p = zoomout(np.eye(6), s, s, k_final=12)
    >>> C.shape, bool((p2p == np.arange(s.n_vertices)).all())
    ((12, 12), True)
    """
    C = np.asarray(C)  # float64, checked by the table
    k_final = min(source.k, target.k) if k_final is None else k_final
    picked = None if samples is None else _check_samples(samples, source, target)
    if picked is not None and picked[1].size < k_final:
        raise ValueError(
            f"ZoomOut on samples fits maps of k_final={k_final} functions by least squares on the target samples, "
            f"so it needs at least {k_final} of them (many more for a good fit), got {picked[1].size}."
        )
    k = min(C.shape)
    long = max(source.n_vertices, target.n_vertices) >= LARGE_MESH
    with progress_bar(-(-(k_final - k) // step) + 1, "ZoomOut", progress, long=long) as bar:
        if picked is None:
            while True:
                p2p = points_from_map(C, source, target)
                bar.update()
                if k >= k_final:
                    return C, p2p
                k = min(k + step, k_final)
                C = map_from_points(p2p, source, target, k_source=k, k_target=k)
        phi1, phi2 = source.vectors[picked[0], :k_final], target.vectors[picked[1], :k_final]
        while k < k_final:
            k2, k1 = C.shape
            matched = _nearest_rows(phi2[:, :k2], phi1[:, :k1] @ C.T)  # rows of phi1
            k = min(k + step, k_final)
            C = np.linalg.lstsq(phi2[:, :k], phi1[matched, :k], rcond=None)[0]
            bar.update()
        p2p = points_from_map(C, source, target)
        bar.update()
    return C, p2p


@validated(f=Array((1, 2), rows=lambda mesh, **_: mesh.n_vertices, finite=False, meaning="one value per vertex"))
def face_gradients(mesh: Mesh, f: ArrayLike) -> NDArray[np.float64]:
    """Gradient of piecewise-linear vertex functions on every face, shape (m, 3) or (m, 3, c).

    ``grad f = sum_i f_i (n x e_i) / (2 area)`` with ``e_i`` the edge opposite corner ``i``,
    traversed counter-clockwise.
    """
    F = mesh.faces
    arr = np.asarray(f)  # float64, checked by the table
    V = mesh.vertices
    n = mesh.face_normals
    scale = 1.0 / (2.0 * mesh.face_areas)
    grad = 0.0
    for i in range(3):
        e = V[F[:, (i + 2) % 3]] - V[F[:, (i + 1) % 3]]
        rot = np.cross(n, e) * scale[:, None]  # (m, 3)
        fi = arr[F[:, i]]
        grad = grad + (rot[:, :, None] * fi[:, None, :] if arr.ndim == 2 else rot * fi[:, None])
    return np.asarray(grad)


@validated(
    spectrum=_SPECTRUM,
    k=_eigenpairs(lambda spectrum, **_: spectrum.k),
    descriptors=Array(2, rows=lambda mesh, **_: mesh.n_vertices, cols_name="p", finite=False,
                      meaning="one column per descriptor"),
)
def orientation_operators(mesh: Mesh, spectrum: Spectrum, descriptors: ArrayLike, k: int) -> NDArray[np.float64]:
    """``O^f[i, j] = int phi_i (n x grad f) . grad phi_j dA`` for every descriptor column, (p, k, k).

    ``(n x grad f) . grad g = n . (grad f x grad g)`` is the signed area form ``df ^ dg``: it
    changes sign under a reflection and is conformally invariant, so the operator is the same in
    every metric ``|K|^alpha g`` (only ``phi`` changes). Face values are spread to the three
    corners with weight ``area / 3``, the lumped mass.
    """
    D = np.asarray(descriptors)  # float64, checked by the table
    Phi = spectrum.vectors[:, :k]
    grad_phi = face_gradients(mesh, Phi)  # (m, 3, k)
    rotated = np.cross(mesh.face_normals[:, :, None], face_gradients(mesh, D), axis=1)  # (m, 3, p)
    corner_sum = Phi[mesh.faces].sum(axis=1) * (mesh.face_areas / 3.0)[:, None]  # (m, k)
    m, p = rotated.shape[0], rotated.shape[2]
    out = np.zeros((k, p * k))
    for start in range(0, m, 4096):  # (faces, p, k) in chunks: 480 MB at once for 100k faces
        chunk = slice(start, start + 4096)
        field = np.matmul(rotated[chunk].transpose(0, 2, 1), grad_phi[chunk])  # (n x grad f) . grad phi_j
        out += corner_sum[chunk].T @ field.reshape(-1, p * k)
    return out.reshape(k, p, k).transpose(1, 0, 2)


@validated(spectrum=_SPECTRUM, k=_eigenpairs(lambda spectrum, **_: spectrum.k))
def multiplication_operators(spectrum: Spectrum, descriptors: ArrayLike, k: int) -> NDArray[np.float64]:
    """``Omega^f = Phi.T A diag(f) Phi`` for every descriptor column, shape (p, k, k)."""
    D = np.asarray(descriptors, dtype=np.float64)
    Phi = spectrum.vectors[:, :k]
    APhi = np.asarray(spectrum.mass @ Phi)
    return np.stack([(APhi * D[:, [c]]).T @ Phi for c in range(D.shape[1])])


def _commutator_normal(X: NDArray[np.float64], Y: NDArray[np.float64], sign: float = -1.0) -> NDArray[np.float64]:
    """Normal matrix of ``sum_p ||C X_p + sign * Y_p C||^2`` in column-major ``vec(C)``.

    With ``vec(C X) = (X.T kron I) vec C`` and ``vec(Y C) = (I kron Y) vec C``:
    ``L.T L = X X.T kron I + I kron Y.T Y + sign (X kron Y + X.T kron Y.T)``.
    """
    p, k1, _ = X.shape
    k2 = Y.shape[1]
    XX = np.einsum("pab,pcb->ac", X, X)
    YY = np.einsum("pba,pbc->ac", Y, Y)
    cross = np.einsum("pab,pce->acbe", X, Y) + np.einsum("pba,pec->acbe", X, Y)
    H = np.kron(XX, np.eye(k2)) + np.kron(np.eye(k1), YY) + sign * cross.reshape(k1 * k2, k1 * k2)
    return H


#: Default weights of the energy terms of :func:`estimate_map` (also :func:`~lbo_notebooks.match`'s).
LAPLACIAN_WEIGHT, COMMUTATIVITY_WEIGHT, ORIENTATION_WEIGHT = 1e-2, 1e-1, 1e-1


def _unit_columns(D: NDArray[np.float64], mass: sp.spmatrix) -> NDArray[np.float64]:
    norms = a_norms(D, mass)
    return D / np.where(norms > 0, norms, 1.0)


@validated(
    source=_SPECTRUM,
    target=_SPECTRUM,
    k=(_eigenpairs(lambda source, **_: source.k), _eigenpairs(lambda target, **_: target.k)),
    laplacian_weight=_WEIGHT,
    commutativity_weight=_WEIGHT,
    orientation_weight=_WEIGHT,
    n_operators=Integer(1),
    source_descriptors=Array(2, rows=lambda source, **_: source.n_vertices, cols_name="p",
                             meaning="one row per source vertex, one column per descriptor"),
    target_descriptors=Array(2, rows=lambda target, **_: target.n_vertices,
                             cols=lambda source_descriptors, **_: source_descriptors.shape[1],
                             meaning="one row per target vertex and the same number of columns as source_descriptors"),
)
def estimate_map(
    source_mesh: Mesh,
    target_mesh: Mesh,
    source: Spectrum,
    target: Spectrum,
    source_descriptors: ArrayLike,
    target_descriptors: ArrayLike,
    *,
    k: int = 30,
    laplacian_weight: float = LAPLACIAN_WEIGHT,
    commutativity_weight: float = COMMUTATIVITY_WEIGHT,
    orientation_weight: float = ORIENTATION_WEIGHT,
    n_operators: int = 20,
) -> NDArray[np.float64]:
    """Functional map ``C`` (k x k) minimising the quadratic energy of the module docstring.

    Parameters
    ----------
    source_mesh, target_mesh : Mesh
        The shapes (the orientation term needs their normals and face gradients).
    source, target : Spectrum
        Their eigenbases (any metric; at least ``k`` eigenpairs).
    source_descriptors, target_descriptors : array, shape (n_source, p) and (n_target, p)
        Corresponding descriptor columns (e.g. :func:`~lbo_notebooks.analyses.wks`). Each
        column is scaled to unit A-norm on its shape.
    k : int, default 30
    laplacian_weight : float, default 1e-2
        Weight of the Laplacian commutativity term; the eigenvalue differences are normalised
        to unit Frobenius norm, so the weight does not depend on the shapes' size.
    commutativity_weight, orientation_weight : float, default 0.1
        Weights of the descriptor-commutativity and orientation-preserving terms, computed for
        ``n_operators`` descriptor columns evenly spread over ``p``. ``0`` switches a term off.

    Returns
    -------
    ndarray, shape (k, k)
        Takes source coefficients to target coefficients.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis, wks
    >>> m = shapes.bumpy_sphere(3)              # no symmetry, so the self-map is unique
    >>> s = eigenbasis(m, 20)
    >>> C = estimate_map(m, m, s, s, wks(s), wks(s), k=10)
    >>> bool(np.abs(C - np.eye(10)).max() < 1e-6)
    True
    """
    # float64 (n, p) arrays with one row per vertex and the same p, checked by the table
    D1 = _unit_columns(np.asarray(source_descriptors), source.mass)
    D2 = _unit_columns(np.asarray(target_descriptors), target.mass)
    A = source.project(D1, k)  # (k, p)
    B = target.project(D2, k)

    H = np.kron(A @ A.T, np.eye(k))
    rhs = (B @ A.T).ravel(order="F")
    lam_diff = (source.values[None, :k] - target.values[:k, None]) ** 2  # [i, j] = (lam1_j - lam2_i)^2
    lam_diff /= np.linalg.norm(lam_diff)
    H += laplacian_weight * np.diag(lam_diff.ravel(order="F"))

    pick = np.unique(np.linspace(0, D1.shape[1] - 1, min(n_operators, D1.shape[1])).round().astype(int))
    if commutativity_weight > 0:
        X = multiplication_operators(source, D1[:, pick], k)
        Y = multiplication_operators(target, D2[:, pick], k)
        H += commutativity_weight * _commutator_normal(X, Y)
    if orientation_weight > 0:
        X = orientation_operators(source_mesh, source, D1[:, pick], k)
        Y = orientation_operators(target_mesh, target, D2[:, pick], k)
        H += orientation_weight * _commutator_normal(X, Y)
    vec = np.linalg.solve(H, rhs)
    return vec.reshape(k, k, order="F")
