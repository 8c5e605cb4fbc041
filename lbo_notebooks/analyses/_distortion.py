"""How far a deformation is from an isometry: two meshes with one triangulation, compared.

A bending of a surface (a creature changing pose) keeps every geodesic distance; a stretch does
not. :func:`pose_distortion` gives global statistics (edge-length change, geodesic-distance
change among farthest-point samples), :func:`vertex_strain` where on the surface it happens.
Both take two meshes with the same faces, e.g. two poses of one creature
(:mod:`lbo_notebooks.shapes._creatures`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .._support.validation import Integer, Relation, validated
from ..operators._cotangent import MESH
from ._geodesics import farthest_point_sampling
from ..geometry._mesh import Mesh

__all__ = ["pose_distortion", "vertex_strain"]

#: ``rest`` and ``posed`` are two poses of one triangulation (on ``posed``, named last).
_SAME_FACES = Relation(
    lambda rest, posed, **_: rest.n_vertices == posed.n_vertices and np.array_equal(rest.faces, posed.faces),
    "rest and posed must share one triangulation (same faces); pass two poses of one creature.",
)


@validated(n_samples=Integer(2, lambda rest, **_: rest.n_vertices), posed=_SAME_FACES)
def pose_distortion(rest: Mesh, posed: Mesh, n_samples: int = 50) -> dict[str, float]:
    """How far ``posed`` is from an isometry of ``rest`` (two meshes with the same faces).

    Returns the median and 99th percentile of the relative edge-length change, and the mean
    relative change of the distances among ``n_samples`` geodesic farthest-point samples of
    ``rest`` (:func:`~lbo_notebooks.analyses.farthest_point_sampling`), measured as shortest
    paths on the edge graph (:func:`scipy.sparse.csgraph.dijkstra`) of both meshes.

    Examples
    --------
    >>> from lbo_notebooks.shapes._creatures import creature_poses
    >>> poses = creature_poses("dog", n_vertices=3000)
    >>> d = pose_distortion(poses["standing"], poses["walking"])
    >>> d["edge_median"] < 0.02 and d["edge_p99"] < 0.10 and d["geodesic_mean"] < 0.03
    True
    """
    import scipy.sparse as sp
    from scipy.sparse.csgraph import dijkstra

    edges, n = rest.edges, rest.n_vertices

    def lengths(mesh: Mesh) -> NDArray[np.float64]:
        return np.linalg.norm(mesh.vertices[edges[:, 0]] - mesh.vertices[edges[:, 1]], axis=1)

    def edge_graph(weights: NDArray[np.float64]) -> sp.csr_matrix:
        return sp.coo_matrix((weights, (edges[:, 0], edges[:, 1])), shape=(n, n)).tocsr()

    rest_lengths, posed_lengths = lengths(rest), lengths(posed)
    samples = farthest_point_sampling(rest, int(n_samples), progress=False)
    rest_d = dijkstra(edge_graph(rest_lengths), directed=False, indices=samples)[:, samples]
    posed_d = dijkstra(edge_graph(posed_lengths), directed=False, indices=samples)[:, samples]
    pairs = np.triu_indices(int(n_samples), 1)
    stretch = np.abs(posed_lengths / rest_lengths - 1.0)
    return {
        "edge_median": float(np.median(stretch)),
        "edge_p99": float(np.percentile(stretch, 99)),
        "geodesic_mean": float(np.mean(np.abs(posed_d[pairs] / rest_d[pairs] - 1.0))),
    }


@validated(rest=MESH, posed=(MESH, _SAME_FACES))
def vertex_strain(rest: Mesh, posed: Mesh) -> NDArray[np.float64]:
    """Per vertex, the largest relative length change ``|l1 / l0 - 1|`` of the edges at it.

    ``rest`` and ``posed`` must share one triangulation (two poses of one creature). Zero for a
    rigid motion; a local picture of where a pose departs from an isometry
    (:func:`pose_distortion` gives the global statistics).

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> m = shapes.icosphere(1)
    >>> float(vertex_strain(m, m.with_vertices(2 * m.vertices)).max().round(12))   # scaling by 2: +100%
    1.0
    """
    e = rest.edges
    l0 = np.linalg.norm(rest.vertices[e[:, 0]] - rest.vertices[e[:, 1]], axis=1)
    l1 = np.linalg.norm(posed.vertices[e[:, 0]] - posed.vertices[e[:, 1]], axis=1)
    rel = np.abs(l1 / l0 - 1.0)
    out = np.zeros(rest.n_vertices)
    np.maximum.at(out, e[:, 0], rel)
    np.maximum.at(out, e[:, 1], rel)
    return out
