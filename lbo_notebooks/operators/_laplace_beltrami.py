"""Which ``(W, A)`` for this input: the one owner of the choice of Laplace–Beltrami operators.

:func:`~lbo_notebooks.eigenbasis` is operators + solver; this module is the operators half. For a
:class:`~lbo_notebooks.Mesh` it chooses between the cotangent operator
(:mod:`~lbo_notebooks.operators._cotangent`, with the mass ``mass_kind``), the scale-invariant metric
``|K|^alpha g`` (:func:`~lbo_notebooks.operators.metric_mass_matrix`) and the robust intrinsic
tufted Laplacian (:mod:`~lbo_notebooks.operators._robust`) for meshes the cotangent operator cannot serve;
a :class:`~lbo_notebooks.PointCloud` gets the point-cloud Laplacian. Every option is checked here,
once, and an option that does not apply to the chosen operator is refused with the reason.

Examples
--------
>>> from lbo_notebooks import shapes
>>> mesh = shapes.icosphere(2)
>>> W, A = laplace_beltrami(mesh)  # the cotangent operator and the Voronoi mass
>>> W.shape, bool(abs(A.sum() / mesh.area - 1) < 1e-12)
((162, 162), True)
"""

from __future__ import annotations

from typing import Any

import scipy.sparse as sp

from .._support.validation import Number, Options, Relation, Satisfies, validated
from .._support.warning import warn
from ..geometry._mesh import Mesh, MeshError, check_coordinate_range
from ._cotangent import MASS_KIND, mass_matrix, stiffness_matrix
from ..geometry._pointcloud import PointCloud
from ._robust import (
    LAPLACIANS,
    N_NEIGHBORS,
    LaplacianWarning,
    check_referenced,
    cotan_defects,
    point_cloud_operators,
    robust_operators,
)

__all__ = ["laplace_beltrami", "select_operators"]

_LAPLACIAN = Options(*LAPLACIANS)
_NO_COTAN_FOR_CLOUDS = Relation(
    lambda shape, laplacian, **_: not (isinstance(shape, PointCloud) and laplacian == "cotan"),
    "a point cloud has no triangles for the cotangent Laplacian; use laplacian='auto' or 'robust'.",
)
_SHAPE = Satisfies(lambda shape: isinstance(shape, (Mesh, PointCloud)), message=lambda name, value: (
    f"eigenbasis takes a Mesh or a PointCloud or a (stiffness, mass) tuple, got {type(value).__name__}."))


@validated(laplacian=_LAPLACIAN, mass_kind=MASS_KIND, alpha=Number(0, 1))
def laplace_beltrami(
    shape: Mesh | PointCloud,
    *,
    laplacian: str = "auto",
    mass_kind: str = "voronoi",
    alpha: float = 0.0,
    curvature_floor: float | None = None,
    n_neighbors: int = N_NEIGHBORS,
) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """The operators ``(stiffness, mass)`` of a mesh or point cloud, as :func:`~lbo_notebooks.eigenbasis` builds them.

    The options are :func:`~lbo_notebooks.eigenbasis`'s, with the same meaning: ``laplacian``
    ("auto", "cotan" or "robust"; a point cloud always gets the point-cloud Laplacian),
    ``mass_kind`` (cotangent operator only), ``alpha`` and ``curvature_floor`` (the metric
    ``|K|^alpha g``, cotangent operator only), ``n_neighbors`` (point clouds only).

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes
    >>> W, A = laplace_beltrami(shapes.icosphere(2), mass_kind="barycentric", alpha=1.0)
    >>> bool(abs(A.sum() / (4 * np.pi) - 1) < 1e-4)  # area of |K| g: the total curvature, 4 pi (Gauss-Bonnet)
    True
    """
    if isinstance(shape, Mesh):
        check_coordinate_range(shape.vertices, "mesh")
    robust = select_operators(shape, laplacian, mass_kind=mass_kind, alpha=alpha, n_neighbors=n_neighbors)
    if robust is not None:
        return robust
    W = stiffness_matrix(shape)
    if alpha == 0.0:
        return W, mass_matrix(shape, mass_kind)
    from ._curvature import DEFAULT_FLOOR, metric_mass_matrix

    floor = DEFAULT_FLOOR if curvature_floor is None else curvature_floor
    return W, metric_mass_matrix(shape, alpha, mass_kind=mass_kind, floor=floor)


@validated(laplacian=(_LAPLACIAN, _NO_COTAN_FOR_CLOUDS), shape=_SHAPE)
def select_operators(
    shape: Any,
    laplacian: str,
    *,
    mass_kind: str,
    alpha: float,
    n_neighbors: int = N_NEIGHBORS,
) -> tuple[sp.csr_matrix, sp.csr_matrix] | None:
    """The robust ``(stiffness, mass)`` for ``shape``, or None when the cotangent path applies.

    The dispatch behind ``eigenbasis(..., laplacian=...)``: ``"auto"`` takes the cotangent
    operator unless :func:`cotan_defects` finds a reason not to, and then warns
    (:class:`LaplacianWarning`) naming the reasons; ``"cotan"`` refuses a mesh with defects;
    ``"robust"`` always takes the tufted Laplacian. A :class:`~lbo_notebooks.PointCloud` always
    gets :func:`point_cloud_operators`.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> select_operators(shapes.icosphere(1), "auto", mass_kind="voronoi", alpha=0.0, n_neighbors=30) is None
    True
    >>> W, A = select_operators(shapes.icosphere(1), "robust", mass_kind="voronoi", alpha=0.0, n_neighbors=30)
    >>> W.shape
    (42, 42)
    """
    if isinstance(shape, PointCloud):
        _check_robust_options(mass_kind, alpha)
        return point_cloud_operators(shape, n_neighbors=n_neighbors)
    check_referenced(shape)
    if laplacian == "robust":
        _check_robust_options(mass_kind, alpha)
        return robust_operators(shape)
    reasons = cotan_defects(shape)
    if not reasons:
        return None
    why = "; ".join(reasons)
    if laplacian == "cotan":
        raise MeshError(
            f"the cotangent Laplacian cannot serve this mesh: {why}. Use eigenbasis(mesh, k, laplacian='robust') "
            "(or the default laplacian='auto'), which builds the intrinsic tufted Laplacian of Sharp & Crane 2020."
        )
    _check_robust_options(mass_kind, alpha)
    warn(
        f"eigenbasis used the robust (intrinsic tufted) Laplacian of Sharp & Crane 2020 instead of the cotangent "
        f"one, because the mesh has {why}. Pass laplacian='robust' to choose it explicitly."
        + _component_note(shape.n_components),
        LaplacianWarning,
    )
    return robust_operators(shape)


def _check_robust_options(mass_kind: str, alpha: float) -> None:
    # Inline, not a table's: for a Mesh under "auto" whether the robust operator is taken is
    # cotan_defects' verdict on the mesh, known only here (and after check_referenced).
    if mass_kind not in ("voronoi", "barycentric"):
        raise ValueError(
            f"the robust Laplacian comes with its own lumped (diagonal) mass; mass_kind={mass_kind!r} applies to the "
            "cotangent operator only. Leave mass_kind at its default or pass laplacian='cotan'."
        )
    if alpha != 0.0:
        raise ValueError(
            "alpha (the scale-invariant metric of notebook 08) is built on the cotangent operator, which cannot "
            "serve this shape (a point cloud, laplacian='robust', or a mesh with the defects cotan_defects lists); "
            "use alpha=0, or repair the mesh into an edge-manifold one with well-shaped triangles."
        )


def _component_note(n_components: int) -> str:
    if n_components <= 1:
        return ""
    return (
        f" It has {n_components} connected components, so its first {n_components} eigenvalues are (near) zero, "
        "one constant per component; keep only the largest with load_mesh(path, clean=True, "
        "keep_largest_component=True) if you want one shape."
    )
