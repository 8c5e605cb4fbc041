"""Shape matching with functional maps, and how to measure a correspondence.

:func:`match` is the whole pipeline in one call: both shapes scaled to unit area, eigenbases in
the metric ``|K|^alpha g`` (:func:`~lbo_notebooks.spectral.eigenbasis` with ``alpha``), WKS
descriptors, a ``k x k`` functional map from the quadratic energy of
:func:`~lbo_notebooks.analyses.estimate_map` (descriptors, Laplacian commutativity,
descriptor commutativity and orientation), then ZoomOut to ``k_final`` on 2000 farthest-point
samples of each shape, and one final nearest-neighbour search over every vertex. Nothing uses
vertex indices: the target's vertices may come in any order. On large meshes the eigenbases
take most of the time: ZoomOut on the samples costs a small fraction of ZoomOut on every vertex,
for a somewhat larger mean error.

:func:`matching_error` is the standard score: for every target vertex the geodesic distance *on
the source* between the predicted and the true match, divided by ``sqrt(source area)``;
:func:`error_curve` is the cumulative curve matching papers plot (fraction of vertices with error
below each threshold).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Indices, Integer, Number, Relation, Satisfies, validated
from ..operators._cotangent import MESH
from .._support.progress import LARGE_MESH, PROGRESS, progress_bar
from ..spectral._solvers import one_blas_thread
from ._functional_maps import COMMUTATIVITY_WEIGHT, LAPLACIAN_WEIGHT, ORIENTATION_WEIGHT
from ..geometry._mesh import Mesh
from ..spectral._spectrum import eigenbasis

__all__ = ["match", "matching_error", "error_curve"]


_WEIGHT = Number(0)


def _unit_area(mesh: Mesh) -> Mesh:
    v = mesh.vertices
    return mesh.with_vertices((v - v.mean(axis=0)) / np.sqrt(mesh.area))


#: Default number of farthest-point samples per shape on which ZoomOut iterates (see :func:`match`).
N_SAMPLES = 2000

#: Lanczos tolerance of the eigenbases :func:`match` computes. Point maps come from nearest
#: neighbours among the eigenfunctions' values, which 1e-6 residuals do not move: on the dog
#: pair (target shuffled) the maps were identical to those with the solver's default tolerance,
#: for less CPU time.
EIGEN_TOL = 1e-6


def _count(minimum: Any, hint: Any = None, none: bool = False) -> Integer:
    """An integer >= ``minimum`` (a number or a callable of the arguments), said so even for 1."""
    return Integer(minimum, what="an integer >= {low}", hint=hint, none=none)


# Every argument is checked before anything is computed.
@validated(
    source=MESH,
    target=MESH,
    k=_count(2),
    k_final=(
        _count(2),
        Integer(lambda k, **_: k,
                message="k_final ({value}) must be at least k ({low}); use k_final=k to skip ZoomOut."),
        Integer(high=lambda source, target, **_: min(source.n_vertices, target.n_vertices) - 1,
                what=lambda source, target, **_: "an integer smaller than the vertex count of the smaller shape "
                                                 f"({min(source.n_vertices, target.n_vertices)})"),
    ),
    alpha=Number(0, 1, what="a number in [0, 1] (the exponent of the metric |K|^alpha g)"),
    n_descriptors=_count(1, "it is the number of WKS energies"),
    laplacian_weight=_WEIGHT,
    commutativity_weight=_WEIGHT,
    orientation_weight=_WEIGHT,
    zoomout_step=_count(1, "it is the number of functions ZoomOut adds per iteration"),
    n_samples=_count(
        lambda k_final, **_: 2 * k_final, none=True,
        hint=lambda k_final, **_: f"ZoomOut fits maps of up to k_final={k_final} functions on the samples; "
                                  "use n_samples=None for every vertex",
    ),
    progress=PROGRESS,
)
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
    n_samples: int | None = N_SAMPLES,
    progress: bool | None = None,
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
        Weights of :func:`~lbo_notebooks.analyses.estimate_map`.
    zoomout_step : int, default 2
        Functions added per ZoomOut iteration.
    n_samples : int or None, default 2000
        ZoomOut iterates on this many farthest-point samples of each shape (chosen along the
        edges, :func:`~lbo_notebooks.analyses.farthest_point_sampling` with ``select="graph"``)
        and converts the final map to a point map once, on every vertex: each iteration then
        searches nearest neighbours among the samples instead of among all vertices. Only when
        both shapes have more than ``2.5 * n_samples`` vertices (5,000 by default); on smaller
        shapes, and with ``None``, ZoomOut iterates on every vertex (at 3,000 vertices that was
        as fast as 2,000 samples, and a little more accurate).
    progress : bool or None, default None
        A progress bar over the stages (eigenbases, descriptors, map, samples, ZoomOut).
        ``None``: only for shapes of 10,000 vertices or more, and only in a notebook or a
        terminal (never in a log file or under pytest).

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
    from ._descriptors import wks
    from ._functional_maps import estimate_map, zoomout
    from ._geodesics import farthest_point_sampling

    n_min = min(source.n_vertices, target.n_vertices)

    sampled = n_samples is not None and n_min > 2.5 * n_samples
    long = max(source.n_vertices, target.n_vertices) >= LARGE_MESH
    # One BLAS thread throughout (unless the user chose the count): the nearest-neighbour search
    # runs in its own threads, and the rest gains little from more and loses beside a busy program.
    with one_blas_thread(), progress_bar(5 + sampled, "match", progress, long=long) as bar:
        def stage(name: str) -> None:
            bar.set_postfix_str(name, refresh=True)

        s1, s2 = _unit_area(source), _unit_area(target)
        stage("eigenbasis of the source")
        e1 = eigenbasis(s1, k_final, alpha=alpha, tol=EIGEN_TOL, progress=False)
        bar.update()
        stage("eigenbasis of the target")
        e2 = eigenbasis(s2, k_final, alpha=alpha, tol=EIGEN_TOL, progress=False)
        bar.update()
        stage("descriptors")
        d1 = wks(e1, n_energies=n_descriptors)
        d2 = wks(e2, n_energies=n_descriptors)
        bar.update()
        stage("functional map")
        C = estimate_map(
            s1, s2, e1, e2, d1, d2, k=k,
            laplacian_weight=laplacian_weight,
            commutativity_weight=commutativity_weight,
            orientation_weight=orientation_weight,
        )
        bar.update()
        samples = None
        if sampled:
            stage("samples")
            # "exact" sets nothing up: with select="graph" the samples are chosen along the edges
            # and no geodesic distance is computed.
            samples = tuple(farthest_point_sampling(m, n_samples, method="exact", select="graph") for m in (s1, s2))
            bar.update()
        stage("ZoomOut")
        p2p = zoomout(C, e1, e2, k_final=k_final, step=zoomout_step, samples=samples, progress=False)[1]
        bar.update()
    return p2p


def _source_vertices(what: str) -> Indices:
    """A 1-D integer array of vertex indices of ``source`` (integer dtype: a point map, not floats)."""
    return Indices(lambda source, **_: source.n_vertices - 1, what=what,
                   hint=lambda source, **_: f"the source has {source.n_vertices} vertices")


_P2P = _source_vertices("a 1-D integer array of source vertex indices")


@validated(
    source=MESH,
    p2p=_P2P,
    true_p2p=(_P2P, Relation(lambda p2p, true_p2p, **_: p2p.shape == true_p2p.shape,
                             "p2p {p2p.shape} and true_p2p {true_p2p.shape} must have the same length "
                             "(one entry per target vertex).")),
)
def matching_error(source: Mesh, p2p: ArrayLike, true_p2p: ArrayLike, *, method: str = "heat") -> NDArray[np.float64]:
    """Geodesic error of a correspondence on the source, per target vertex, divided by ``sqrt(area)``.

    Parameters
    ----------
    source : Mesh
        The shape the indices refer to.
    p2p, true_p2p : int arrays, shape (n_target,)
        Predicted and true source vertex of every target vertex.
    method : {"heat", "exact", "fmm"}, default "heat"
        Geodesic distances of :func:`~lbo_notebooks.analyses.geodesic_distances`: the heat method
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
    from ._geodesics import GeodesicSolver

    pred, true = np.asarray(p2p), np.asarray(true_p2p)  # int64 vertex indices, checked by the table
    err = np.zeros(true.size, dtype=np.float64)
    wrong = np.flatnonzero(pred != true)  # exact hits cost nothing
    if wrong.size:
        solver = GeodesicSolver(source, method)
        order = wrong[np.argsort(true[wrong], kind="stable")]
        starts = np.flatnonzero(np.r_[True, np.diff(true[order]) != 0])
        for rows in np.split(order, starts[1:]):
            err[rows] = solver.distance(int(true[rows[0]]))[pred[rows]]
    return err / np.sqrt(source.area)


def _flat(values: ArrayLike) -> NDArray[np.float64]:
    return np.asarray(values, dtype=np.float64).ravel()


@validated(errors=Satisfies(
    lambda e: (a := _flat(e)).size > 0 and bool(np.all(np.isfinite(a))) and bool(np.all(a >= 0)),
    convert=_flat,
    message="errors must be a non-empty array of finite non-negative numbers.",
))
def error_curve(
    errors: ArrayLike, thresholds: ArrayLike | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
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
    e = np.asarray(errors)  # flat float64, checked by the table
    t = np.linspace(0.0, 0.25, 101) if thresholds is None else np.asarray(thresholds, dtype=np.float64).ravel()
    return t, np.searchsorted(np.sort(e), t, side="right") / e.size
