"""Competitor bases for the optimality theorem: everything the eigenbasis is compared against.

Every function takes a mesh and a size ``k`` and returns an array of shape ``(n_vertices, k)``
whose columns are **A-orthonormal** (``B.T @ A @ B = I`` for the mesh's mass matrix of the given
kind) with **the constant function first** (so :func:`~lbo_notebooks.analyses.worst_case_ratio`
is finite). Columns are ordered, so the first ``m`` columns are that basis with ``m`` functions:
one call at the largest ``k`` serves a whole curve over ``k``.

The competitors:

* :func:`lbo_basis` — the Laplace–Beltrami eigenbasis itself (the optimum), as an array (a
  :class:`~lbo_notebooks.Spectrum` is :func:`~lbo_notebooks.eigenbasis`);
* :func:`random_smooth_basis` — heat-smoothed random noise;
* :func:`pca_basis` — principal components of a set of sample functions;
* :func:`umbrella_basis` — eigenvectors of the combinatorial (umbrella) graph Laplacian;
* :func:`identity_mass_basis` — eigenvectors of ``W`` with the identity as mass (no areas);
* :func:`polynomial_basis` — low-degree polynomials in the embedding coordinates;
* :func:`metric_basis` — the eigenbasis of a *different* metric (pluggable).

:func:`competitor_bases` builds all of them at once.
"""

from __future__ import annotations

from typing import Callable, Union

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from .._support.validation import Array, Integer, Number, Relation, validated
from ..spectral._inner_product import a_orthonormalize, check_operators
from ..geometry._mesh import Mesh
from ..operators._cotangent import MASS_KIND, MESH, MassKind, mass_matrix, stiffness_matrix
from ..spectral._solvers import symmetric_lu
from ..spectral._spectrum import eigenbasis

__all__ = [
    "lbo_basis",
    "random_smooth_basis",
    "random_smooth_functions",
    "sample_functions",
    "pca_basis",
    "umbrella_basis",
    "identity_mass_basis",
    "polynomial_basis",
    "metric_basis",
    "competitor_bases",
    "Metric",
]

# A metric for metric_basis: a new mass matrix, a new (W, A) pair, or a function of the mesh
# returning either (e.g. ``lambda m: curvature.metric_mass_matrix(m, 0.5)``).
Metric = Union[sp.spmatrix, tuple, Callable[[Mesh], Union[sp.spmatrix, tuple]]]



#: The table of every basis builder: a mesh, a mass kind and a size ``k`` in 1..n_vertices - 1.
_BASIS = dict(
    mesh=MESH,
    mass_kind=MASS_KIND,
    k=Integer(1, lambda mesh, **_: mesh.n_vertices - 1, what="an integer between 1 and n_vertices - 1 = {high}"),
)


def _constant_first(mesh: Mesh, A: sp.csr_matrix, functions: NDArray[np.float64], k: int) -> NDArray[np.float64]:
    """Constant, then ``functions`` A-orthonormalised in order; the first k columns."""
    Q = a_orthonormalize(functions[:, : k - 1], A, prepend=np.ones(mesh.n_vertices))
    return Q[:, :k]


def _identity_mass_eigenbasis(
    mesh: Mesh, k: int, mass_kind: MassKind, operator: Callable[[Mesh], sp.spmatrix]
) -> NDArray[np.float64]:
    """Eigenvectors of ``operator(mesh) x = mu x`` (no area weights), then A-orthonormalised."""
    A = mass_matrix(mesh, mass_kind)
    identity = sp.identity(mesh.n_vertices, format="csr")
    return _constant_first(mesh, A, _smallest_eigenvectors(operator(mesh), identity, k), k)


def _smallest_eigenvectors(W: sp.spmatrix, M: sp.spmatrix, k: int) -> NDArray[np.float64]:
    """Eigenvectors 1..k-1 of ``W x = mu M x`` (the constant, eigenvector 0, is dropped)."""
    return np.asarray(eigenbasis((W, M), k).vectors[:, 1:])


@validated(**_BASIS)
def lbo_basis(mesh: Mesh, k: int, *, mass_kind: MassKind = "voronoi") -> NDArray[np.float64]:
    """The first k Laplace–Beltrami eigenvectors (already A-orthonormal, the constant first).

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> lbo_basis(shapes.icosphere(2), 9).shape
    (162, 9)
    """
    return np.array(eigenbasis(mesh, k, mass_kind=mass_kind).vectors)


@validated(mesh=MESH, k=Integer(0), width=Number(0, open_low=True, what="a positive fraction of sqrt(area)"))
def random_smooth_functions(mesh: Mesh, k: int, *, seed: int = 0, width: float = 0.15) -> NDArray[np.float64]:
    """Random smooth functions: white noise smoothed twice by an implicit heat step.

    Each noise column ``g`` becomes ``(A + t W)^{-1} A (A + t W)^{-1} A g`` with
    ``t = (width * sqrt(area))^2``, so the smoothing length is a fixed fraction of the surface's
    size and does not depend on units. Uses the Voronoi mass.

    Returns
    -------
    ndarray (n_vertices, k)

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> random_smooth_functions(shapes.icosphere(2), 3, seed=1).shape
    (162, 3)
    """
    W, A = stiffness_matrix(mesh), mass_matrix(mesh)
    t = (width * np.sqrt(mesh.area)) ** 2
    lu = symmetric_lu(A + t * W)
    g = np.random.default_rng(seed).normal(size=(mesh.n_vertices, k))
    return lu.solve(np.asarray(A @ lu.solve(np.asarray(A @ g)))) if k else g


@validated(mesh=MESH, heat_time=Number(0, open_low=True, what="a positive fraction of the area"))
def sample_functions(mesh: Mesh, *, seed: int = 0, heat_time: float = 0.005) -> tuple[NDArray[np.float64], list[str]]:
    """Eight functions to test the representation bound on: smooth, kinked and random.

    Columns: the coordinates ``x, y, z``; a heat kernel (four implicit heat steps
    ``(A + t W) u_{k+1} = A u_k`` with ``t = heat_time * area`` from a unit spike at the vertex of
    largest ``x``: not a finite combination of eigenfunctions); the geodesic distance from that
    vertex (heat method; Lipschitz, with a kink at the source); and three
    :func:`random_smooth_functions`. Voronoi mass.

    Returns
    -------
    F : ndarray (n_vertices, 8)
    labels : list of str
        ``["x", "y", "z", "heat kernel", "geodesic distance", "random 1", "random 2", "random 3"]``

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> F, labels = sample_functions(shapes.icosphere(2), seed=1)
    >>> F.shape, labels[3]
    ((162, 8), 'heat kernel')
    """
    from ._geodesics import geodesic_distances

    W, A = stiffness_matrix(mesh), mass_matrix(mesh)
    source = int(np.argmax(mesh.vertices[:, 0]))
    heat = np.zeros(mesh.n_vertices)
    heat[source] = 1.0
    step = symmetric_lu(A + heat_time * mesh.area * W)
    for _ in range(4):
        heat = step.solve(np.asarray(A @ heat))
    distance = geodesic_distances(mesh, [source])[0]
    F = np.column_stack([mesh.vertices, heat, distance, random_smooth_functions(mesh, 3, seed=seed)])
    return F, ["x", "y", "z", "heat kernel", "geodesic distance", "random 1", "random 2", "random 3"]


@validated(**_BASIS)
def random_smooth_basis(
    mesh: Mesh, k: int, *, mass_kind: MassKind = "voronoi", seed: int = 0, width: float = 0.15
) -> NDArray[np.float64]:
    """The constant and ``k - 1`` :func:`random_smooth_functions`, A-orthonormalised.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, mass_matrix
    >>> m = shapes.bumpy_sphere(2)
    >>> B = random_smooth_basis(m, 6, seed=3)
    >>> bool(np.allclose(B.T @ mass_matrix(m) @ B, np.eye(6)) and np.ptp(B[:, 0]) < 1e-12 * B[0, 0])
    True
    """
    A = mass_matrix(mesh, mass_kind)
    return _constant_first(mesh, A, random_smooth_functions(mesh, k - 1, seed=seed, width=width), k)


def _gaussian_bumps(mesh: Mesh, count: int, seed: int) -> NDArray[np.float64]:
    """``count`` Gaussian bumps of the Euclidean distance at random vertices, random widths."""
    rng = np.random.default_rng(seed)
    centres = mesh.vertices[rng.choice(mesh.n_vertices, size=count, replace=count > mesh.n_vertices)]
    widths = rng.uniform(0.1, 0.4, size=count) * np.sqrt(mesh.area)
    out = np.empty((mesh.n_vertices, count))
    for j in range(count):
        d2 = ((mesh.vertices - centres[j]) ** 2).sum(axis=1)
        out[:, j] = np.exp(-d2 / (2.0 * widths[j] ** 2))
    return out


def _enough_samples(k: int, samples: NDArray[np.float64] | None, **_: object) -> bool:
    return samples is None or samples.shape[1] >= k - 1


@validated(**_BASIS, samples=(
    Array(2, rows=lambda mesh, **_: mesh.n_vertices, none=True,
          message="{name} must be a finite array of shape ({rows}, m), got {shape}."),
    Relation(_enough_samples, lambda k, samples, **_: (
        f"pca_basis needs at least k - 1 = {k - 1} independent samples; got {samples.shape[1]} columns.")),
))
def pca_basis(
    mesh: Mesh,
    k: int,
    *,
    mass_kind: MassKind = "voronoi",
    samples: ArrayLike | None = None,
    seed: int = 0,
) -> NDArray[np.float64]:
    """Principal components (in the A inner product) of a set of sample functions.

    The constant part of every sample is removed (the constant is the basis's first column), then
    the leading ``k - 1`` eigenvectors of the A-weighted second-moment operator ``X X.T A`` are
    taken: with ``K = X.T A X = U S U.T`` they are ``X U / sqrt(S)``.

    Parameters
    ----------
    samples : array (n_vertices, m), optional
        The sample functions, ``m >= k - 1`` of rank at least ``k - 1``. Default: ``4 k`` Gaussian
        bumps (of the Euclidean distance, widths 0.1–0.4 sqrt(area)) centred at random vertices.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, mass_matrix
    >>> m = shapes.icosphere(2)
    >>> B = pca_basis(m, 5, samples=m.vertices)  # 3 samples: not enough for 4 components
    Traceback (most recent call last):
    ...
    ValueError: pca_basis needs at least k - 1 = 4 independent samples; got 3 columns.
    >>> bool(np.allclose(pca_basis(m, 4, samples=m.vertices).T @ mass_matrix(m) @ pca_basis(m, 4, samples=m.vertices), np.eye(4)))
    True
    """
    A = mass_matrix(mesh, mass_kind)
    X = _gaussian_bumps(mesh, 4 * k, seed) if samples is None else samples
    a = np.asarray(A @ np.ones(mesh.n_vertices)).ravel()
    X = X - np.outer(np.ones(mesh.n_vertices), (a @ X) / a.sum())  # remove each sample's A-mean
    K = X.T @ (A @ X)
    s, U = np.linalg.eigh(K)
    s, U = s[::-1], U[:, ::-1]
    if k > 1 and not s[k - 2] > 1e-12 * max(s[0], 1e-300):
        raise ValueError(f"the samples span fewer than k - 1 = {k - 1} directions besides the constant; add samples.")
    components = X @ (U[:, : k - 1] / np.sqrt(s[: k - 1]))
    return _constant_first(mesh, A, components, k)


def _umbrella_laplacian(mesh: Mesh) -> sp.csr_matrix:
    e = mesh.edges
    nv = mesh.n_vertices
    adj = sp.coo_matrix((np.ones(2 * len(e)), (np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]])), shape=(nv, nv)).tocsr()
    return (sp.diags(np.asarray(adj.sum(axis=1)).ravel()) - adj).tocsr()


@validated(**_BASIS)
def umbrella_basis(mesh: Mesh, k: int, *, mass_kind: MassKind = "voronoi") -> NDArray[np.float64]:
    """Eigenvectors of the combinatorial graph Laplacian ``L = D - Adj`` (uniform "umbrella" weights).

    The graph Laplacian ignores the geometry (edge lengths and angles): only connectivity counts.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, mass_matrix
    >>> m = shapes.bumpy_sphere(2)
    >>> B = umbrella_basis(m, 8)
    >>> bool(np.allclose(B.T @ mass_matrix(m) @ B, np.eye(8)))
    True
    """
    return _identity_mass_eigenbasis(mesh, k, mass_kind, _umbrella_laplacian)


@validated(**_BASIS)
def identity_mass_basis(mesh: Mesh, k: int, *, mass_kind: MassKind = "voronoi") -> NDArray[np.float64]:
    """Eigenvectors of the cotangent ``W`` with the identity as mass (``W x = mu x``, no area weights).

    Right on a uniform mesh, wrong where triangle sizes vary: the missing ``A`` is exactly the
    difference between a graph signal and a function on a surface.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, mass_matrix
    >>> m = shapes.bumpy_sphere(2)
    >>> B = identity_mass_basis(m, 8)
    >>> bool(np.allclose(B.T @ mass_matrix(m) @ B, np.eye(8)))
    True
    """
    return _identity_mass_eigenbasis(mesh, k, mass_kind, stiffness_matrix)


def _legendre(x: NDArray[np.float64], degree: int) -> NDArray[np.float64]:
    """Legendre polynomials P_0..P_degree at x, shape (len(x), degree + 1) (three-term recurrence)."""
    out = np.empty((x.size, degree + 1))
    out[:, 0] = 1.0
    if degree >= 1:
        out[:, 1] = x
    for k in range(1, degree):
        out[:, k + 1] = ((2 * k + 1) * x * out[:, k] - k * out[:, k - 1]) / (k + 1)
    return out


@validated(**_BASIS)
def polynomial_basis(mesh: Mesh, k: int, *, mass_kind: MassKind = "voronoi", max_degree: int = 30) -> NDArray[np.float64]:
    """Polynomials in the embedding coordinates x, y, z, by increasing total degree.

    Coordinates are mapped to [-1, 1] by the bounding box and the products
    ``P_a(x) P_b(y) P_c(z)`` of Legendre polynomials are used (better conditioned than monomials),
    in graded order ``a + b + c = 0, 1, 2, ...``. Products that are dependent on the surface (on a
    sphere ``x^2 + y^2 + z^2 = 1``; on a flat mesh ``z`` is constant) are skipped.

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> B = polynomial_basis(shapes.icosphere(3), 9)  # 1, x, y, z and 5 quadrics: x^2+y^2+z^2 = 1
    >>> B.shape
    (642, 9)
    """
    A = mass_matrix(mesh, mass_kind)
    lo, hi = mesh.vertices.min(axis=0), mesh.vertices.max(axis=0)
    extent = np.where(hi - lo > 1e-12 * mesh.diagonal, hi - lo, np.inf)
    x = 2.0 * (mesh.vertices - lo) / extent - 1.0  # a degenerate axis maps to -1: constant
    found = np.zeros((mesh.n_vertices, 0))
    for degree in range(max_degree + 1):
        P = [_legendre(x[:, i], degree) for i in range(3)]
        block = [
            P[0][:, a] * P[1][:, b] * P[2][:, degree - a - b]
            for a in range(degree, -1, -1)
            for b in range(degree - a, -1, -1)
        ]
        candidates = np.column_stack([found] + block) if found.size else np.column_stack(block)
        found = a_orthonormalize(candidates, A, drop_dependent=True, rtol=1e-6)
        if found.shape[1] >= k:
            return found[:, :k]
    raise ValueError(
        f"polynomials up to degree {max_degree} span only {found.shape[1]} functions on this mesh; "
        f"ask for fewer than k = {k} or raise max_degree."
    )


@validated(**_BASIS)
def metric_basis(mesh: Mesh, k: int, metric: Metric, *, mass_kind: MassKind = "voronoi") -> NDArray[np.float64]:
    """The eigenbasis of a different metric, A-orthonormalised for the *regular* mass.

    Parameters
    ----------
    metric : sparse matrix, (W, A) tuple, or callable
        The other metric's mass matrix (the stiffness stays the cotangent ``W``: in 2-D a conformal
        change of metric only changes the mass), a full ``(W, A)`` pair, or a function
        ``metric(mesh)`` returning either. Notebook 08's scale-invariant metric plugs in as
        ``lambda m: curvature.metric_mass_matrix(m, alpha)``.

    Examples
    --------
    >>> import numpy as np, scipy.sparse as sp
    >>> from lbo_notebooks import shapes, mass_matrix
    >>> m = shapes.bumpy_sphere(2)
    >>> heavy_top = lambda m: sp.diags(1.0 + (m.vertices[:, 2] > 0)) @ mass_matrix(m)
    >>> B = metric_basis(m, 6, heavy_top)
    >>> bool(np.allclose(B.T @ mass_matrix(m) @ B, np.eye(6)))
    True
    """
    A = mass_matrix(mesh, mass_kind)
    value = metric(mesh) if callable(metric) else metric
    if isinstance(value, tuple) and len(value) == 2:
        W2, A2 = check_operators(*value)
    elif sp.issparse(value):
        W2, A2 = check_operators(stiffness_matrix(mesh), value)
    else:
        raise ValueError(
            "metric must be a sparse mass matrix, a (stiffness, mass) tuple, or a function of the mesh "
            f"returning one of those; got {type(value).__name__}."
        )
    if W2.shape[0] != mesh.n_vertices:
        raise ValueError(f"the metric's operators have size {W2.shape[0]}, the mesh has {mesh.n_vertices} vertices.")
    return _constant_first(mesh, A, _smallest_eigenvectors(W2, A2, k), k)


def competitor_bases(
    mesh: Mesh, k: int, *, mass_kind: MassKind = "voronoi", seed: int = 0, metric: Metric | None = None
) -> dict[str, NDArray[np.float64]]:
    """All the bases at once, keyed by a display name (the eigenbasis first).

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> sorted(competitor_bases(shapes.bumpy_sphere(2), 5))[:3]
    ['LBO eigenbasis', 'PCA of samples', 'identity mass']
    """
    bases = {
        "LBO eigenbasis": lbo_basis(mesh, k, mass_kind=mass_kind),
        "random smooth": random_smooth_basis(mesh, k, mass_kind=mass_kind, seed=seed),
        "PCA of samples": pca_basis(mesh, k, mass_kind=mass_kind, seed=seed),
        "umbrella Laplacian": umbrella_basis(mesh, k, mass_kind=mass_kind),
        "identity mass": identity_mass_basis(mesh, k, mass_kind=mass_kind),
        "polynomials": polynomial_basis(mesh, k, mass_kind=mass_kind),
    }
    if metric is not None:
        bases["other metric"] = metric_basis(mesh, k, metric, mass_kind=mass_kind)
    return bases
