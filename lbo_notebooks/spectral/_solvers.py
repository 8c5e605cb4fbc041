"""The solver services the analyses use, over the private engine (``lbo_notebooks.spectral._engine``).

An analysis that factorises or diagonalises a matrix of ``W`` and ``A`` asks here, and nowhere
else, for the one convention of each:

* :func:`symmetric_lu` -- the one sparse factorisation of a symmetric matrix (fill-reducing
  symmetric order, diagonal pivots, so its pivots count eigenvalues);
* :func:`mesh_order_where_it_pays` -- the fill-reducing order of a mesh's edge graph, which every
  operator assembled on its triangles shares, from the size on where METIS pays;
* :func:`use_dense`, :func:`default_shift`, :func:`start_vector` -- dense or sparse, the shift of
  shift-invert (it scales like the eigenvalues), the fixed Lanczos start vector (determinism);
* :func:`one_blas_thread`, :func:`blas_threads_for`, :func:`default_workers` -- the thread policy:
  how many worker threads the package's parallel loops use, and BLAS on one thread meanwhile;
* :func:`slice_eigsh` and :func:`count_below` -- the sliced eigensolver and the Sylvester count
  of eigenvalues below a value, for readers who bring their own matrices.

The engine takes sparse matrices (and an optional order), never a mesh; what depends on a mesh
(its order, cached on it) is decided here.

Examples
--------
>>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
>>> m = shapes.icosphere(3)
>>> factor = symmetric_lu(stiffness_matrix(m) + default_shift(mass_matrix(m)) * mass_matrix(m))
>>> factor.n_negative  # W + s A is positive definite
0
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ._engine.eigensolver import slice_eigsh
from .._support.validation import Number, validated
from ._engine.factor import NESTED_DISSECTION_MIN, SymmetricFactor, fill_reducing_order, symmetric_lu
from ._engine.factor import count_below as _inertia_below
from ._inner_product import check_operators
from ._engine.policy import default_shift, start_vector, use_dense
from ._engine.threads import blas_threads_for, default_workers, one_blas_thread
from ..geometry._mesh import Mesh, per_mesh

__all__ = [
    "SymmetricFactor", "blas_threads_for", "count_below", "default_shift", "default_workers", "mesh_order",
    "mesh_order_where_it_pays", "one_blas_thread", "slice_eigsh", "start_vector", "symmetric_lu", "use_dense",
]


@validated(value=Number(what="a finite number (where to count up to)"))
def count_below(stiffness: sp.spmatrix, mass: sp.spmatrix, value: float) -> int:
    """Number of eigenvalues of ``stiffness phi = lam mass phi`` below ``value`` (Sylvester inertia).

    ``W - value A`` is factorised once (LDL^T-like, by sparse LU) and its negative pivots counted:
    by Sylvester's law of inertia they are the eigenvalues below ``value``. The pair is checked as
    in :func:`~lbo_notebooks.spectral._inner_product.check_operators`.

    Examples
    --------
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> m = shapes.icosphere(3)
    >>> count_below(stiffness_matrix(m), mass_matrix(m), 4.0)  # l = 0, 1: 1 + 3 eigenvalues below 4
    4
    """
    W, A = check_operators(stiffness, mass)
    return _inertia_below(W, A, value)


@per_mesh
def mesh_order(mesh: Mesh) -> NDArray[np.intp]:
    """The fill-reducing (METIS) order of the mesh's edge graph, computed once per mesh.

    Every operator assembled on the mesh's own triangles (``W``, ``A``, ``W - b A``, ``A + t W``,
    the pinned ``W``) has the pattern of the edge graph, so they all share this order: one METIS
    run serves the eigensolver and the heat method's Poisson step. Not the intrinsic Delaunay
    operators of the robust Laplacian: their flipped edges cross this order's separators (much
    more fill on a stretched torus), so they are ordered on their own pattern.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> m = shapes.icosphere(2)
    >>> order = mesh_order(m)
    >>> sorted(order.tolist()) == list(range(m.n_vertices)), mesh_order(m) is order  # cached
    (True, True)
    """
    edges, n = mesh.edges, mesh.n_vertices
    graph = sp.coo_matrix((np.ones(len(edges)), (edges[:, 0], edges[:, 1])), shape=(n, n))
    return fill_reducing_order(graph)


def mesh_order_where_it_pays(mesh: Mesh) -> NDArray[np.intp] | None:
    """:func:`mesh_order` from the size on where METIS pays for its own run, else ``None`` (SuperLU orders).

    The one rule for callers that factorise operators of a mesh (the eigensolver, the heat method).

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> mesh_order_where_it_pays(shapes.icosphere(2)) is None  # 162 vertices: METIS would not pay
    True
    """
    return mesh_order(mesh) if mesh.n_vertices >= NESTED_DISSECTION_MIN else None
