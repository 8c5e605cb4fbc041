"""Shape matching with functional maps, and how to measure a correspondence.

:func:`match` is the whole pipeline in one call: both shapes scaled to unit area, eigenbases in
the metric ``|K|^alpha g`` (:func:`~lbo_notebooks.spectrum.eigenbasis` with ``alpha``), WKS
descriptors, a ``k x k`` functional map from the quadratic energy of
:func:`~lbo_notebooks.functional_maps.estimate_map` (descriptors, Laplacian commutativity,
descriptor commutativity and orientation), then ZoomOut to ``k_final``. Nothing uses vertex
indices: the target's vertices may come in any order.

:func:`matching_error` is the standard score: for every target vertex the geodesic distance *on
the source* between the predicted and the true match, divided by ``sqrt(source area)``;
:func:`error_curve` is the cumulative curve matching papers plot (fraction of vertices with error
below each threshold).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .functional_maps import COMMUTATIVITY_WEIGHT, LAPLACIAN_WEIGHT, ORIENTATION_WEIGHT
from .mesh import Mesh
from .spectrum import eigenbasis

__all__ = ["match", "matching_error", "error_curve"]


def _check_mesh(mesh: Mesh, name: str) -> Mesh:
    if not isinstance(mesh, Mesh):
        raise ValueError(f"{name} must be a Mesh, got {type(mesh).__name__}; build one with lbo_notebooks.Mesh(vertices, faces).")
    return mesh


def _unit_area(mesh: Mesh) -> Mesh:
    v = mesh.vertices
    return mesh.with_vertices((v - v.mean(axis=0)) / np.sqrt(mesh.area))


def match(
    source: Mesh,
    target: Mesh,
    *,
    k: int = 30,
    k_final: int = 80,
    alpha: float = 0.0,
    n_descriptors: int = 100,
    laplacian_weight: float = LAPLACIAN_WEIGHT,
    commutativity_weight: float = COMMUTATIVITY_WEIGHT,
    orientation_weight: float = ORIENTATION_WEIGHT,
    zoomout_step: int = 2,
) -> NDArray[np.int64]:
    """Point-to-point correspondence from ``target`` to ``source`` by functional maps.

    Parameters
    ----------
    source, target : Mesh
        Two connected closed or open surfaces; vertex orders need not agree.
    k : int, default 30
        Size of the functional map estimated from descriptors.
    k_final : int, default 80
        Size reached by ZoomOut refinement (``k_final == k``: no refinement). Eigenbases of
        ``k_final`` functions are computed on both shapes.
    alpha : float in [0, 1], default 0
        Metric ``|K|^alpha g`` of the eigenbases (0: regular LBO; 1: scale invariant).
    n_descriptors : int, default 100
        Number of WKS energies.
    laplacian_weight, commutativity_weight, orientation_weight : float
        Weights of :func:`~lbo_notebooks.functional_maps.estimate_map`.
    zoomout_step : int, default 2
        Functions added per ZoomOut iteration.

    Returns
    -------
    ndarray of int, shape (target.n_vertices,)
        ``p2p[i]`` is the source vertex matched to target vertex ``i``.

    Examples
    --------
    >>> from lbo_notebooks import creature
    >>> a = creature("dog", "standing", n_vertices=2000)
    >>> b = creature("dog", "walking", n_vertices=2000)
    >>> p2p = match(a, b, k=20, k_final=40)
    >>> float(np.mean(p2p == np.arange(b.n_vertices))) > 0.3     # many exact hits
    True
    """
    from .descriptors import wks
    from .functional_maps import estimate_map, zoomout

    source, target = _check_mesh(source, "source"), _check_mesh(target, "target")
    for name, value in (("k", k), ("k_final", k_final)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 2:
            raise ValueError(f"{name} must be an integer >= 2, got {value!r}.")
    if k_final < k:
        raise ValueError(f"k_final ({k_final}) must be at least k ({k}); use k_final=k to skip ZoomOut.")
    n_min = min(source.n_vertices, target.n_vertices)
    if k_final >= n_min:
        raise ValueError(f"k_final ({k_final}) must be smaller than the vertex count of the smaller shape ({n_min}).")
    s1, s2 = _unit_area(source), _unit_area(target)
    e1 = eigenbasis(s1, k_final, alpha=alpha)
    e2 = eigenbasis(s2, k_final, alpha=alpha)
    d1 = wks(e1, n_energies=n_descriptors)
    d2 = wks(e2, n_energies=n_descriptors)
    C = estimate_map(
        s1, s2, e1, e2, d1, d2, k=k,
        laplacian_weight=laplacian_weight,
        commutativity_weight=commutativity_weight,
        orientation_weight=orientation_weight,
    )
    return zoomout(C, e1, e2, k_final=k_final, step=zoomout_step)[1]


def matching_error(source: Mesh, p2p: ArrayLike, true_p2p: ArrayLike, *, method: str = "heat") -> NDArray[np.float64]:
    """Geodesic error of a correspondence on the source, per target vertex, divided by ``sqrt(area)``.

    Parameters
    ----------
    source : Mesh
        The shape the indices refer to.
    p2p, true_p2p : int arrays, shape (n_target,)
        Predicted and true source vertex of every target vertex.
    method : {"heat", "exact", "fmm"}, default "heat"
        Geodesic distances of :func:`~lbo_notebooks.geodesics.geodesic_distances`: the heat method
        (one factorisation, then two back-substitutions per distinct true vertex; an error of
        a few percent of an edge length) or exact polyhedral distances (slow; small meshes).

    Returns
    -------
    ndarray, shape (n_target,)
        Its mean is the usual single score.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> sphere = shapes.icosphere(2)
    >>> err = matching_error(sphere, np.zeros(162, dtype=int), np.arange(162), method="exact")
    >>> bool(abs(err.max() - np.pi / np.sqrt(sphere.area)) < 0.01)   # the antipode of vertex 0
    True
    """
    from .geodesics import GeodesicSolver

    source = _check_mesh(source, "source")
    pred, true = np.asarray(p2p), np.asarray(true_p2p)
    n = source.n_vertices
    for name, arr in (("p2p", pred), ("true_p2p", true)):
        if arr.ndim != 1 or not np.issubdtype(arr.dtype, np.integer):
            raise ValueError(f"{name} must be a 1-D integer array of source vertex indices, got dtype {arr.dtype} and shape {arr.shape}.")
        if arr.size and (arr.min() < 0 or arr.max() >= n):
            raise ValueError(f"{name} holds indices outside 0..{n - 1} (the source has {n} vertices).")
    if pred.shape != true.shape:
        raise ValueError(f"p2p {pred.shape} and true_p2p {true.shape} must have the same length (one entry per target vertex).")
    err = np.zeros(true.size, dtype=np.float64)
    wrong = np.flatnonzero(pred != true)  # exact hits cost nothing
    if wrong.size:
        solver = GeodesicSolver(source, method)
        order = wrong[np.argsort(true[wrong], kind="stable")]
        starts = np.flatnonzero(np.r_[True, np.diff(true[order]) != 0])
        for rows in np.split(order, starts[1:]):
            err[rows] = solver.distance(int(true[rows[0]]))[pred[rows]]
    return err / np.sqrt(source.area)


def error_curve(errors: ArrayLike, thresholds: ArrayLike | None = None) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Cumulative error curve: the fraction of vertices with error at most each threshold.

    Parameters
    ----------
    errors : array, shape (n,)
        Normalised errors from :func:`matching_error`.
    thresholds : array, optional
        Default: 101 values from 0 to 0.25 (a quarter of ``sqrt(area)``).

    Returns
    -------
    thresholds, fractions : ndarray
        ``fractions`` is non-decreasing and reaches 1 at ``max(errors)``.

    Examples
    --------
    >>> t, frac = error_curve([0.0, 0.1, 0.2, 0.3], [0.0, 0.15, 0.3])
    >>> frac.tolist()
    [0.25, 0.5, 1.0]
    """
    e = np.asarray(errors, dtype=np.float64).ravel()
    if e.size == 0 or not np.all(np.isfinite(e)) or np.any(e < 0):
        raise ValueError("errors must be a non-empty array of finite non-negative numbers.")
    t = np.linspace(0.0, 0.25, 101) if thresholds is None else np.asarray(thresholds, dtype=np.float64).ravel()
    return t, np.searchsorted(np.sort(e), t, side="right") / e.size
