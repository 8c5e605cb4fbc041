"""The min–max (Courant–Fischer) principle for ``W phi = lam A phi``, made computable.

Discrete Courant–Fischer (MATH.md section 2)::

    lam[n] = max over subspaces L of codimension n of  min over f in L of (f W f) / (f A f)

and the maximum is attained by the A-orthogonal complement of the first n eigenvectors. A
codimension-n subspace is represented here by n *constraint* vectors ``C`` (columns):
``L = {f : C.T @ A @ f = 0}``, the A-orthogonal complement of ``span(C)``. Then

* :func:`min_rayleigh_quotient` computes ``min over f in L`` of the Rayleigh quotient,
* :func:`random_subspace` draws random constraints, and
* :func:`optimal_subspace` returns the constraints that attain the maximum.

This is the engine of the optimality theorem: for any n-dimensional V, the complement of V has
codimension n, so its minimum quotient is at most ``lam[n]``.
"""

from __future__ import annotations

from typing import Any, Literal, Sequence, overload

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from .optimality import _check_functions, _check_symmetric, a_orthonormalize
from .spectrum import Spectrum, check_operators

__all__ = [
    "rayleigh_quotient",
    "min_rayleigh_quotient",
    "ConstrainedRayleigh",
    "random_subspace",
    "optimal_subspace",
    "plane_normal",
    "rayleigh_sphere_figure",
    "plane_slider",
]

# Below this many vertices min_rayleigh_quotient(method="auto") uses dense linear algebra.
DENSE_LIMIT = 400

Method = Literal["auto", "dense", "sparse"]


def _operators(stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Accept sparse or dense (e.g. a 3 x 3 example) operators; validate them."""
    W = stiffness if sp.issparse(stiffness) else sp.csr_matrix(np.asarray(stiffness, dtype=np.float64))
    A = mass if sp.issparse(mass) else sp.csr_matrix(np.asarray(mass, dtype=np.float64))
    W, A = check_operators(W, A)
    _check_symmetric(W, "stiffness")
    _check_symmetric(A, "mass")
    return W, A


def rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix, f: ArrayLike
) -> NDArray[np.float64] | float:
    """Rayleigh quotient ``(f W f) / (f A f)`` per column of ``f``.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import eigenbasis, shapes
    >>> s = eigenbasis(shapes.icosphere(2), 4)
    >>> bool(np.allclose(rayleigh_quotient(s.stiffness, s.mass, s.vectors), s.values, rtol=1e-10, atol=1e-10 * s.values[-1]))
    True
    """
    W, A = _operators(stiffness, mass)
    arr = _check_functions(f, W.shape[0])
    den = np.einsum("i...,i...->...", arr, A @ arr)
    if np.any(den <= 0):
        raise ValueError("f (or one of its columns) is zero: the Rayleigh quotient is undefined.")
    out = np.einsum("i...,i...->...", arr, W @ arr) / den
    return float(out) if arr.ndim == 1 else np.asarray(out)


def _constraint_basis(orthogonal_to: ArrayLike | None, A: sp.csr_matrix) -> NDArray[np.float64]:
    n = A.shape[0]
    if orthogonal_to is None:
        return np.zeros((n, 0))
    C = np.asarray(orthogonal_to, dtype=np.float64)
    C = C[:, None] if C.ndim == 1 else C
    if C.ndim != 2 or C.shape[0] != n:
        raise ValueError(f"orthogonal_to must have shape ({n},) or ({n}, codim), got {np.shape(orthogonal_to)}.")
    if not np.all(np.isfinite(C)):
        raise ValueError("orthogonal_to contains NaN or inf.")
    if C.shape[1] >= n:
        raise ValueError(f"the codimension ({C.shape[1]}) must be smaller than the dimension ({n}).")
    return a_orthonormalize(C, A)


def _min_dense(W: sp.csr_matrix, A: sp.csr_matrix, Q: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
    Wd, Ad = W.toarray(), A.toarray()
    if Q.shape[1] == 0:
        values, vectors = scipy.linalg.eigh(Wd, Ad, subset_by_index=[0, 0])
        return float(values[0]), vectors[:, 0]
    Z = scipy.linalg.null_space((Ad @ Q).T)  # Euclidean basis of {f : Q.T A f = 0}
    values, vectors = scipy.linalg.eigh(Z.T @ Wd @ Z, Z.T @ Ad @ Z, subset_by_index=[0, 0])
    return float(values[0]), Z @ vectors[:, 0]


class ConstrainedRayleigh:
    """Reusable solver for :func:`min_rayleigh_quotient` on one ``(W, A)`` pair, many subspaces.

    Factorises ``K = W + s A`` (positive definite for a small ``s > 0``) once by sparse LU; each
    query then costs ``codim`` extra solves and a short shift-invert Lanczos run. For constraints
    ``Q`` (A-orthonormal), the operator ``R b = x`` solving ``K x + A Q z = b, Q.T A x = 0`` is
    ``R b = K^{-1} b - Y (Q.T A Y)^{-1} Y.T b`` with ``Y = K^{-1} A Q``: it is symmetric, vanishes on
    ``A V`` and maps each eigenvector of the constrained problem to itself times ``1 / (mu + s)``.

    Examples
    --------
    >>> from lbo_notebooks import eigenbasis, shapes
    >>> s = eigenbasis(shapes.bumpy_sphere(3), 12)
    >>> solver = ConstrainedRayleigh(s.stiffness, s.mass)
    >>> bool(abs(solver.minimum(s.vectors[:, :5]) - s.values[5]) < 1e-9 * s.values[5])
    True
    """

    def __init__(self, stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix) -> None:
        self.stiffness, self.mass = _operators(stiffness, mass)
        # Small against the first nonzero eigenvalue (~4 pi / area) at every scale.
        self.shift = 1e-2 * 4.0 * np.pi / float(self.mass.sum())
        self._lu = spla.splu((self.stiffness + self.shift * self.mass).tocsc(), permc_spec="MMD_AT_PLUS_A")

    def minimum(
        self, orthogonal_to: ArrayLike | None = None, *, return_vector: bool = False
    ) -> float | tuple[float, NDArray[np.float64]]:
        """Minimum Rayleigh quotient on ``{f : C.T A f = 0}`` (see :func:`min_rayleigh_quotient`)."""
        W, A = self.stiffness, self.mass
        Q = _constraint_basis(orthogonal_to, A)
        n = W.shape[0]
        if n - Q.shape[1] < 50:  # too small a subspace for Lanczos
            value, f = _min_dense(W, A, Q)
        else:
            value, f = self._min_sparse(Q)
        if not return_vector:
            return value
        f = f / np.sqrt(float(f @ (A @ f)))
        return value, f if f[np.argmax(np.abs(f))] >= 0 else -f

    def _min_sparse(self, Q: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
        W, A, lu = self.stiffness, self.mass, self._lu
        n = W.shape[0]
        AQ = np.asarray(A @ Q)
        if Q.shape[1]:
            Y = lu.solve(AQ)
            G = scipy.linalg.cho_factor(Q.T @ (A @ Y))

            def solve(b: NDArray[np.float64]) -> NDArray[np.float64]:
                b = np.ravel(b)
                return lu.solve(b) - Y @ scipy.linalg.cho_solve(G, Y.T @ b)
        else:

            def solve(b: NDArray[np.float64]) -> NDArray[np.float64]:
                return lu.solve(np.ravel(b))

        op = spla.LinearOperator((n, n), matvec=solve, dtype=np.float64)
        # A fixed start vector (in the subspace) makes ARPACK deterministic.
        v0 = 1.0 + 0.5 * np.cos(np.arange(n, dtype=np.float64))
        v0 -= Q @ (AQ.T @ v0)
        values, vectors = spla.eigsh(
            W, k=1, M=A, sigma=-self.shift, OPinv=op, which="LM", v0=v0, tol=0.0, ncv=min(n - 1, 20)
        )
        return float(values[0]), vectors[:, 0]


@overload
def min_rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix, orthogonal_to: ArrayLike | None = ..., *,
    method: Method = ..., return_vector: Literal[False] = ...,
) -> float: ...
@overload
def min_rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix, mass: ArrayLike | sp.spmatrix, orthogonal_to: ArrayLike | None = ..., *,
    method: Method = ..., return_vector: Literal[True],
) -> tuple[float, NDArray[np.float64]]: ...
def min_rayleigh_quotient(
    stiffness: ArrayLike | sp.spmatrix,
    mass: ArrayLike | sp.spmatrix,
    orthogonal_to: ArrayLike | None = None,
    *,
    method: Method = "auto",
    return_vector: bool = False,
) -> float | tuple[float, NDArray[np.float64]]:
    """Minimum of ``(f W f) / (f A f)`` over the subspace ``L = {f : C.T @ A @ f = 0}``.

    Parameters
    ----------
    stiffness, mass : sparse or dense (n, n)
        ``W`` (symmetric) and ``A`` (symmetric positive definite). Dense arrays are accepted for
        small examples such as a 3 x 3 matrix with ``mass = numpy.eye(3)``.
    orthogonal_to : array (n,) or (n, codim), optional
        Constraint vectors ``C``; ``L`` is the A-orthogonal complement of their span, of
        codimension ``rank(C)``. ``None`` means the whole space (the answer is ``lam[0]``).
    method : {"auto", "dense", "sparse"}
        ``"dense"``: a basis of L by SVD and ``scipy.linalg.eigh`` (small n); ``"sparse"``:
        shift-invert Lanczos on the constrained problem, one sparse LU of ``W + s A`` and ``codim``
        extra solves (no dense n x n matrix; see :class:`ConstrainedRayleigh`, which reuses the
        factorisation across many subspaces). ``"auto"`` picks dense below ``DENSE_LIMIT``.
    return_vector : bool
        Also return the minimiser, A-normalised with its largest entry positive.

    Returns
    -------
    float, or (float, ndarray (n,)).

    Examples
    --------
    >>> import numpy as np
    >>> M = np.diag([1.0, 2.0, 4.0])
    >>> min_rayleigh_quotient(M, np.eye(3), orthogonal_to=[1.0, 0.0, 0.0])  # lam_2 for this plane
    2.0
    >>> round(min_rayleigh_quotient(M, np.eye(3), orthogonal_to=[1.0, 1.0, 0.0]), 6)  # any other: less
    1.5
    """
    if method not in ("auto", "dense", "sparse"):
        raise ValueError(f"method must be 'auto', 'dense' or 'sparse', got {method!r}.")
    W, A = _operators(stiffness, mass)
    if method == "dense" or (method == "auto" and W.shape[0] <= DENSE_LIMIT):
        value, f = _min_dense(W, A, _constraint_basis(orthogonal_to, A))
        if not return_vector:
            return value
        f = f / np.sqrt(float(f @ (A @ f)))
        return value, f if f[np.argmax(np.abs(f))] >= 0 else -f
    return ConstrainedRayleigh(W, A).minimum(orthogonal_to, return_vector=return_vector)


def random_subspace(
    n_vertices: int, codim: int, *, seed: int = 0, pool: ArrayLike | None = None
) -> NDArray[np.float64]:
    """Constraints of a random codimension-``codim`` subspace (for :func:`min_rayleigh_quotient`).

    Parameters
    ----------
    n_vertices : int
    codim : int
        Codimension n (number of constraint vectors), ``0 <= codim < n_vertices``.
    seed : int
        Seed for ``numpy.random.default_rng``.
    pool : array (n_vertices, m), optional
        Draw the constraints as random Gaussian combinations of the pool's columns (for example
        the first 2n eigenvectors, which gives subspaces close to the optimal one). Default:
        i.i.d. Gaussian vectors in all of R^n_vertices.

    Returns
    -------
    ndarray (n_vertices, codim): the subspace is ``{f : C.T @ A @ f = 0}``.

    Examples
    --------
    >>> random_subspace(100, 5, seed=1).shape
    (100, 5)
    """
    if isinstance(n_vertices, bool) or not isinstance(n_vertices, (int, np.integer)) or n_vertices < 1:
        raise ValueError(f"n_vertices must be a positive integer, got {n_vertices!r}.")
    if isinstance(codim, bool) or not isinstance(codim, (int, np.integer)) or not 0 <= codim < n_vertices:
        raise ValueError(f"codim must be an integer in 0..{n_vertices - 1}, got {codim!r}.")
    rng = np.random.default_rng(seed)
    if pool is None:
        return rng.normal(size=(int(n_vertices), int(codim)))
    P = np.asarray(pool, dtype=np.float64)
    if P.ndim != 2 or P.shape[0] != n_vertices or not np.all(np.isfinite(P)):
        raise ValueError(f"pool must be a finite array of shape ({n_vertices}, m), got {P.shape}.")
    if P.shape[1] < codim:
        raise ValueError(f"pool has {P.shape[1]} columns; it needs at least codim = {codim} to span a codim-{codim} constraint set.")
    return P @ rng.normal(size=(P.shape[1], int(codim)))


def optimal_subspace(spectrum: Spectrum, n: int) -> NDArray[np.float64]:
    """Constraints of the optimal codimension-n subspace: the first n eigenvectors.

    Its minimum Rayleigh quotient is ``lam[n]``, attained at ``phi_n`` (Courant–Fischer).

    Examples
    --------
    >>> from lbo_notebooks import eigenbasis, shapes
    >>> s = eigenbasis(shapes.icosphere(2), 12)
    >>> C = optimal_subspace(s, 4)
    >>> bool(abs(min_rayleigh_quotient(s.stiffness, s.mass, C) - s.values[4]) < 1e-9 * s.values[4])
    True
    """
    if not isinstance(spectrum, Spectrum):
        raise ValueError(f"spectrum must be a Spectrum, got {type(spectrum).__name__}.")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 0 <= n < spectrum.k:
        raise ValueError(f"n must be an integer with 0 <= n < k = {spectrum.k} (lam[n] must be known), got {n!r}.")
    return np.array(spectrum.vectors[:, : int(n)])


# --- the 3 x 3 picture -----------------------------------------------------------------------------
def plane_normal(matrix: ArrayLike, angle: float) -> NDArray[np.float64]:
    """Unit normal of a plane through the origin of R^3, rotated by ``angle`` degrees.

    At 0 the plane is orthogonal to the first eigenvector ``v1`` of the symmetric 3 x 3 ``matrix``
    (the optimal plane of Courant–Fischer, minimum quotient ``lam_2``); the normal then turns
    towards ``(v2 + v3) / sqrt(2)``, reaching it at 90 degrees.

    Examples
    --------
    >>> import numpy as np
    >>> plane_normal(np.diag([1.0, 2.0, 4.0]), 0.0).round(12).tolist()
    [1.0, 0.0, 0.0]
    """
    M = _check_3x3(matrix)
    _, vec = np.linalg.eigh(M)
    vec = vec * np.where(vec[np.argmax(np.abs(vec), axis=0), range(3)] < 0, -1.0, 1.0)  # deterministic signs
    t = np.deg2rad(float(angle))
    return np.cos(t) * vec[:, 0] + np.sin(t) * (vec[:, 1] + vec[:, 2]) / np.sqrt(2.0)


def _check_3x3(matrix: ArrayLike) -> NDArray[np.float64]:
    M = np.asarray(matrix, dtype=np.float64)
    if M.shape != (3, 3) or not np.all(np.isfinite(M)) or not np.allclose(M, M.T):
        raise ValueError(f"matrix must be a finite symmetric 3 x 3 array, got shape {M.shape}.")
    return M


def rayleigh_sphere_figure(matrix: ArrayLike, normal: ArrayLike | None = None, *, resolution: int = 60) -> Any:
    """Plotly figure: the unit sphere coloured by ``x.T M x``, with a plane's great circle.

    The circle is the plane ``{x : normal . x = 0}`` on the sphere, and the marker its minimiser.

    Examples
    --------
    >>> fig = rayleigh_sphere_figure(np.diag([1.0, 2.0, 4.0]), [1.0, 0.0, 0.0])
    >>> [trace.type for trace in fig.data]
    ['surface', 'scatter3d', 'scatter3d']
    """
    import plotly.graph_objects as go

    M = _check_3x3(matrix)
    u, v = np.meshgrid(np.linspace(0, np.pi, resolution), np.linspace(0, 2 * np.pi, 2 * resolution))
    X = np.stack([np.sin(u) * np.cos(v), np.sin(u) * np.sin(v), np.cos(u)], axis=-1)
    R = np.einsum("...i,ij,...j->...", X, M, X)
    fig = go.Figure(
        go.Surface(x=X[..., 0], y=X[..., 1], z=X[..., 2], surfacecolor=R, colorscale="Viridis", opacity=0.9,
                   colorbar=dict(title="x'Mx"))
    )
    if normal is not None:
        circle, point, value = _plane_circle(M, normal)
        fig.add_trace(go.Scatter3d(x=circle[:, 0], y=circle[:, 1], z=circle[:, 2], mode="lines",
                                   line=dict(color="white", width=6), name="plane"))
        fig.add_trace(go.Scatter3d(x=[point[0]], y=[point[1]], z=[point[2]], mode="markers",
                                   marker=dict(color="red", size=6), name=f"min on plane = {value:.3f}"))
    fig.update_layout(height=450, margin=dict(l=0, r=0, t=30, b=0), scene=dict(aspectmode="data"))
    return fig


def _plane_circle(M: NDArray[np.float64], normal: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    value, point = min_rayleigh_quotient(M, np.eye(3), orthogonal_to=normal, method="dense", return_vector=True)
    nrm = np.asarray(normal, dtype=np.float64) / np.linalg.norm(normal)
    e1 = point / np.linalg.norm(point)
    e2 = np.cross(nrm, e1)
    t = np.linspace(0, 2 * np.pi, 200)
    return np.outer(np.cos(t), e1) + np.outer(np.sin(t), e2), 1.01 * e1, value


class PlaneSlider:
    """A :func:`rayleigh_sphere_figure` whose plane is rotated by an ipywidgets slider (degrees).

    ``widget`` is what to display (the notebook displays the object itself); ``figure`` and
    ``slider`` are exposed so that code and tests can drive it. Build it with :func:`plane_slider`.
    """

    def __init__(self, matrix: ArrayLike, angles: Sequence[float]) -> None:
        import ipywidgets as widgets
        import plotly.graph_objects as go

        self.matrix = _check_3x3(matrix)
        self.lam = np.linalg.eigvalsh(self.matrix)
        self._values = list(angles)
        self.figure = go.FigureWidget(rayleigh_sphere_figure(self.matrix, plane_normal(self.matrix, angles[0])))
        self.slider = widgets.SelectionSlider(options=list(angles), value=angles[0], description="angle",
                                              continuous_update=False)
        self.slider.observe(lambda change: self.update(change["new"]), names="value")
        self.widget = widgets.VBox([self.slider, self.figure])
        self.update(angles[0])

    def update(self, angle: float) -> None:
        circle, point, value = _plane_circle(self.matrix, plane_normal(self.matrix, angle))
        with self.figure.batch_update():
            line, marker = self.figure.data[1], self.figure.data[2]
            line.x, line.y, line.z = circle[:, 0], circle[:, 1], circle[:, 2]
            marker.x, marker.y, marker.z = [point[0]], [point[1]], [point[2]]
            marker.name = f"min on plane = {value:.3f}"
            self.figure.layout.title = f"angle {angle:.0f} deg: min on the plane {value:.3f} <= lam_2 = {self.lam[1]:.3f}"

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)


def plane_slider(matrix: ArrayLike, angles: Sequence[float] = tuple(range(0, 181, 5))) -> PlaneSlider:
    """Courant–Fischer in 3-D: rotate a plane and watch its minimum Rayleigh quotient.

    Examples
    --------
    >>> w = plane_slider(np.diag([1.0, 2.0, 4.0]))
    >>> w.slider.value = 45
    """
    return PlaneSlider(matrix, angles)
