"""Eigenbasis of the Laplace–Beltrami operator and the A-inner-product algebra around it.

The eigenvectors of ``W phi = lam A phi`` are orthonormal in the *A* inner product
``<f, g>_A = f @ A @ g``, not the Euclidean one. :class:`Spectrum` makes the right thing the easy
thing: ``project`` returns ``Phi.T @ (A @ f)``, ``reconstruct`` and ``error`` use the same inner
product.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Union

import numpy as np
import scipy.linalg
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike, NDArray

from .._support.progress import LARGE_MESH, PROGRESS, progress_bar
from .._support.validation import Array, Integer, Number, Options, Relation, check_integer, validated
from .._support.warning import warn
from ._inner_product import a_orthonormalize, check_operators, fix_signs_in_place
from ._mass_products import cholesky_qr
from ..operators._laplace_beltrami import laplace_beltrami
from ..geometry._mesh import Mesh
from ..operators._cotangent import MassKind
from ._engine.policy import SHIFT_LIMIT, default_shift, max_shift, start_vector, use_dense
from ._solvers import mesh_order_where_it_pays
from ..geometry._rescaling import unit_area_exponent

__all__ = ["Spectrum", "eigenbasis"]

Operators = tuple[sp.spmatrix, sp.spmatrix]

# k of project/reconstruct/error: None means all the eigenpairs computed.
_N_FUNCTIONS = (
    Integer(what="an integer number of eigenfunctions", none=True),
    Integer(0, lambda self, **_: self.k, none=True,
            message="k must be between 0 and k={high} (the eigenpairs computed), got {value}."),
)
# f of project/reconstruct/error: one value per vertex, a column per function (as check_functions).
_F = Array((1, 2), rows=lambda self, **_: self.n_vertices, meaning="one value per vertex", hint="replace them first")

# eigenbasis with the caller's own (stiffness, mass): the options that build operators from a Mesh do not apply.
_OPERATORS_GIVEN = {
    "laplacian": Relation(
        lambda mesh, laplacian, **_: not isinstance(mesh, tuple) or laplacian == "auto",
        "laplacian chooses how to build operators from a Mesh; with a (stiffness, mass) tuple leave it out.",
    ),
    "alpha": Relation(
        lambda mesh, alpha, **_: not isinstance(mesh, tuple) or alpha == 0.0,
        "alpha applies to a Mesh; with explicit operators pass the scaled mass yourself.",
    ),
    "mesh": Relation(
        lambda mesh, **_: not isinstance(mesh, tuple) or len(mesh) == 2,
        lambda mesh, **_: f"eigenbasis takes a Mesh or a (stiffness, mass) tuple, got a tuple of {len(mesh)}.",
    ),
}


def _is_long(n: int, k: int) -> bool:
    """Whether ``eigenbasis`` of ``k`` pairs on ``n`` vertices takes more than about two seconds (a bar by default).

    The Lanczos sets cost in proportion to ``n k``, and the factorisation grows faster than ``n``,
    so from 40k vertices even a small ``k`` takes about that long: a bar from 40,000 vertices, or
    from 10,000 when ``n k >= 3e6`` (10k at k >= 300, 25k at k >= 120).
    """
    return n >= LARGE_MESH and (n >= 4 * LARGE_MESH or n * k >= 3_000_000)


_VALUES = Array(1, meaning="one eigenvalue per eigenpair")
_VECTORS = Array(2, cols=lambda values, **_: values.size, cols_name="k",
                 meaning="one column per eigenvalue, one row per vertex")


@dataclass(frozen=True, eq=False)
class Spectrum:
    """The first ``k`` eigenpairs of ``W phi = lam A phi``.

    Attributes
    ----------
    values : ndarray, shape (k,)
        Eigenvalues, ascending; ``values[0]`` is 0 (up to round-off) on a connected surface.
    vectors : ndarray, shape (n, k)
        Eigenvectors, A-orthonormal (``vectors.T @ mass @ vectors == I``), signs fixed by
        :func:`~lbo_notebooks.spectral.fix_signs`.
    stiffness, mass : scipy.sparse.csr_matrix
        The operators the spectrum was computed from.

    Examples
    --------
    >>> from lbo_notebooks import shapes, eigenbasis
    >>> s = eigenbasis(shapes.icosphere(3), 16)
    >>> s.values[1:4].round(1).tolist()
    [2.0, 2.0, 2.0]
    """

    values: NDArray[np.float64]
    vectors: NDArray[np.float64]
    stiffness: sp.csr_matrix
    mass: sp.csr_matrix

    def __post_init__(self) -> None:
        # Checked like a table's arguments (a Spectrum built by hand, e.g. from saved arrays), then
        # kept as read-only views: the arrays are not copied, and the caller's stay writable.
        values = _VALUES.check(self.values, "values", {})
        vectors = _VECTORS.check(self.vectors, "vectors", {"values": values})
        n = vectors.shape[0]
        for name in ("stiffness", "mass"):
            M = getattr(self, name)
            if not (sp.issparse(M) and M.shape == (n, n)):
                raise ValueError(f"{name} must be a scipy.sparse ({n}, {n}) matrix, one row per row of vectors; "
                                 f"got {type(M).__name__} of shape {getattr(M, 'shape', None)}.")
        for name, array in (("values", values), ("vectors", vectors)):
            view = array.view()
            view.setflags(write=False)
            object.__setattr__(self, name, view)

    @property
    def k(self) -> int:
        """Number of eigenpairs."""
        return int(self.values.shape[0])

    @property
    def n_vertices(self) -> int:
        return int(self.vectors.shape[0])

    def __len__(self) -> int:
        return self.k

    def __repr__(self) -> str:
        return f"Spectrum(k={self.k}, n_vertices={self.n_vertices}, values=[{self.values[0]:.4g} .. {self.values[-1]:.4g}])"

    # --- the A-inner-product algebra -------------------------------------------------------
    @validated(k=_N_FUNCTIONS, f=_F)
    def project(self, f: ArrayLike, k: int | None = None) -> NDArray[np.float64]:
        """Coefficients ``Phi_n.T @ (A @ f)`` of ``f`` in the first ``k`` eigenfunctions.

        ``f`` is (n_vertices,) or (n_vertices, c); the result is (k,) or (k, c).
        """
        return self._coefficients(f, k)

    @validated(k=_N_FUNCTIONS, f=_F)
    def reconstruct(self, f: ArrayLike, k: int | None = None) -> NDArray[np.float64]:
        """The A-orthogonal projection of ``f`` onto the span of the first ``k`` eigenfunctions."""
        return self._projection(f, k)

    @validated(k=_N_FUNCTIONS, f=_F)
    def error(self, f: ArrayLike, k: int | None = None) -> NDArray[np.float64] | float:
        """A-norm of ``f - reconstruct(f, k)``: a float for 1-D ``f``, an array per column for 2-D."""
        r = f - self._projection(f, k)
        sq = np.einsum("i...,i...->...", r, self.mass @ r)
        out = np.sqrt(np.maximum(sq, 0.0))
        return float(out) if f.ndim == 1 else out

    # The bodies, on f and k the tables above have checked (so each public call checks once).
    def _coefficients(self, f: NDArray[np.float64], k: int | None) -> NDArray[np.float64]:
        k = self.k if k is None else k
        return self.vectors[:, :k].T @ (self.mass @ f)

    def _projection(self, f: NDArray[np.float64], k: int | None) -> NDArray[np.float64]:
        k = self.k if k is None else k
        return self.vectors[:, :k] @ self._coefficients(f, k)


@validated(
    shift=Number(0, open_low=True, none=True, what="a positive finite number (shift-invert runs at sigma = -shift)",
                 hint="leave shift out for its default, 1e-2 * 4 pi / area"),
    solver=Options("auto", "slicing", "arpack", message="solver must be 'auto', 'slicing' or 'arpack', got {value!r}."),
    tol=Number(0, 1, open_low=True, open_high=True, none=True,
               what="a number between 0 and 1 (e.g. 1e-8), or None for the solver's default"),
    progress=PROGRESS,
    **_OPERATORS_GIVEN,
)
def eigenbasis(
    mesh: Union[Mesh, Operators],
    k: int,
    *,
    mass_kind: MassKind = "voronoi",
    alpha: float = 0.0,
    shift: float | None = None,
    curvature_floor: float | None = None,
    laplacian: str = "auto",
    n_neighbors: int = 30,
    solver: str = "auto",
    tol: float | None = None,
    progress: bool | None = None,
) -> Spectrum:
    """The ``k`` smallest eigenpairs of ``W phi = lam A phi``.

    Parameters
    ----------
    mesh : Mesh, PointCloud or (stiffness, mass) tuple
        A mesh, a :class:`~lbo_notebooks.PointCloud`, or precomputed sparse operators (so that
        other metrics can reuse the solver). One eigenvalue is (near) zero per connected component.
    k : int
        Number of eigenpairs, ``1 <= k <= n_vertices``.
    mass_kind : {"voronoi", "barycentric", "consistent"}
        Mass matrix kind when ``mesh`` is a :class:`Mesh`.
    alpha : float in [0, 1]
        Exponent of the metric ``|K|^alpha g`` (notebook 08). ``0`` is exactly the regular metric;
        otherwise ``W`` is unchanged and the mass is
        :func:`~lbo_notebooks.operators.metric_mass_matrix` (``1``: scale-invariant spectrum).
    shift : float, optional
        Positive number ``s`` (in the units of the eigenvalues); shift-invert Lanczos runs at
        ``sigma = -s``. The shift is *negative* because ``W`` is singular (constants are in its
        kernel), so ``sigma = 0`` would factorise a singular matrix, while ``W + s A`` is positive
        definite. The default scales with the surface area. Results do not depend on the units of
        the data: every path solves the problem scaled to about unit area
        (:mod:`lbo_notebooks.geometry._rescaling`), so a shape scaled by ``s`` gets eigenvalues divided by ``s^2``.
        Nor do they depend on the shift: it only tunes ARPACK (a small one, of the order of the
        first nonzero eigenvalue or below, is fastest), and whatever ARPACK returns at it is
        checked by an inertia count and completed by slicing, whose floor is ``-s`` or, when that
        is far below the spectrum, a nearer point proved by a count. ``s`` must be finite and at
        most :func:`~lbo_notebooks.spectral._engine.policy.max_shift` (``SHIFT_LIMIT = 10`` times a bound on
        the largest eigenvalue: past the top of the spectrum shift-invert separates nothing);
        otherwise a ``ValueError`` says so.
    curvature_floor : float > 0, optional
        Only used when ``alpha != 0``: the regularisation of ``|K|`` as a fraction of
        ``4 pi / area`` (``rho = max(one-ring mean |K|, curvature_floor * 4 pi / area)``, see
        :mod:`lbo_notebooks.operators._curvature`). Default ``curvature.DEFAULT_FLOOR`` (1e-3).
    laplacian : {"auto", "cotan", "robust"}
        ``"auto"``: the cotangent operator, unless the mesh has a defect it cannot serve
        (non-manifold edges or vertices, zero-area or needle triangles; see
        :func:`~lbo_notebooks.operators.cotan_defects`); then the robust intrinsic tufted Laplacian
        (Sharp & Crane 2020) with a :class:`~lbo_notebooks.operators.LaplacianWarning` naming the
        reasons. ``"cotan"`` refuses such a mesh with :class:`MeshError`; ``"robust"`` always takes
        the tufted Laplacian (with its own lumped mass). Point clouds always get the robust
        point-cloud Laplacian.
    n_neighbors : int
        Point clouds only: neighbours in each point's local triangulation. The default 30 means
        ``n_points - 1`` on a cloud of at most 30 points, so every cloud that
        :class:`~lbo_notebooks.PointCloud` accepts (5 points or more) works with the defaults;
        any other value must lie between 3 and ``n_points - 1``.
    solver : {"auto", "slicing", "arpack"}
        Above ``DENSE_LIMIT`` vertices: ``"slicing"`` runs a few block shift-invert Lanczos solves,
        in parallel threads, whose inertia counts prove that no eigenvalue is missed
        (:func:`~lbo_notebooks.spectral.slice_eigsh`); ``"arpack"`` is the single
        ``eigsh(W, k, M=A, sigma=-shift)`` call peer libraries make. ``"auto"`` slices from
        ``k = eigensolver.SLICE_SIZE`` (100) on, where it is faster (below, one ARPACK run is as
        fast or faster: ``benchmarks/eigen.py``), and falls back to ARPACK with a
        ``RuntimeWarning`` in the unlikely case that slicing cannot certify its result. Below
        100, ARPACK's set is checked by one inertia count (it can miss copies of a repeated
        eigenvalue) and completed by slicing when it is short (or when ARPACK fails). Under
        ``"auto"`` every result is certified: when neither ARPACK's count nor slicing can certify
        it, a ``RuntimeError``, never a short set. ``"arpack"`` is ARPACK's set unchecked.
    tol : float, optional
        Convergence tolerance of the Lanczos runs: each pair's residual in the shift-inverted
        problem, relative to its eigenvalue there. Default: slicing's ``1e-10``, ARPACK's machine
        precision. Eigenvalues converge as its square, and the basis is A-orthonormalised to
        round-off either way; a looser ``1e-8`` is faster at large ``k`` and still gives the
        eigenvalues to about 1e-14 and the span of all but the last few eigenvectors to round-off (:func:`spectral_mds` asks for ``1e-6``).
    progress : bool or None, default None
        A progress bar over the ``k`` eigenpairs, with the stage it is in (ordering, Lanczos sets
        or ARPACK, orthonormalising). Spectrum slicing advances it as each Lanczos set finishes
        (a few steps: 2 sets at ``k = 100``, 4 at ``k = 300``); ARPACK has no progress to report,
        so its bar names the stage and fills when the run ends. ``True``: always; ``False``:
        never; ``None``: only for calls that take more than a few seconds (40,000 vertices or
        more, or 10,000 or more with ``n_vertices * k >= 3e6``, e.g. ``k = 300`` at 10k) and only
        in a notebook or a terminal (never in a log file or under pytest); see
        :mod:`lbo_notebooks._support.progress`. The result does not depend on it.

    Returns
    -------
    Spectrum

    Examples
    --------
    >>> from lbo_notebooks import shapes
    >>> s = eigenbasis(shapes.icosphere(3), 9)
    >>> bool(abs(s.values[4:9] / 6 - 1).max() < 0.02)  # l = 2: lam = l (l + 1) = 6
    True
    """
    if isinstance(mesh, tuple):  # the caller's own operators (no Mesh option given: _OPERATORS_GIVEN)
        W, A = check_operators(*mesh)
    else:
        W, A = laplace_beltrami(
            mesh, laplacian=laplacian, mass_kind=mass_kind, alpha=alpha, curvature_floor=curvature_floor, n_neighbors=n_neighbors
        )

    n = W.shape[0]
    check_integer(k, "k", 1, n, what=f"an integer between 1 and the number of vertices ({n})")
    if shift is not None:
        limit = max_shift(W, A)
        if shift > limit:
            raise ValueError(
                f"shift={shift:g} lies far above the whole spectrum: every eigenvalue is below about {limit / SHIFT_LIMIT:.3g} "
                f"(so shift must be at most {limit:.3g}), and shift-invert at sigma = -shift would separate none of them. "
                f"Leave shift out for its default (1e-2 * 4 pi / area = {default_shift(A):.3g}), or give one of the order of "
                "the first nonzero eigenvalue or below."
            )
    # A Mesh's operators have its edge pattern: on large meshes the METIS order is made once per
    # mesh and shared with the heat method's factorisations; below, the solver orders the first
    # matrix it factorises (sparse_factor).
    order = (lambda: mesh_order_where_it_pays(mesh)) if isinstance(mesh, Mesh) else (lambda: None)
    with progress_bar(int(k), "eigenbasis", progress, long=_is_long(n, int(k))) as bar:
        values, vectors = _solve_in_unit_area(W, A, int(k), shift=shift, solver=solver, tol=tol, order=order, bar=bar)
    return Spectrum(values=values, vectors=vectors, stiffness=W, mass=A)


def _solve_in_unit_area(
    W: sp.csr_matrix,
    A: sp.csr_matrix,
    k: int,
    *,
    shift: float | None,
    solver: str,
    tol: float | None,
    order: Callable[[], NDArray[np.intp] | None],
    bar: Any,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The ``k`` smallest eigenpairs of ``W phi = lam A phi``, independent of the units of ``A``.

    The one place where every solver path (dense, ARPACK, slicing) is made unit-free: the
    problem is solved with ``A / 4**q``, ``4**q`` the power of four nearest the area
    (:func:`~lbo_notebooks.geometry._rescaling.unit_area_exponent`), and the eigenvalues are multiplied by
    ``4**-q``, the eigenvectors by ``2**-q`` (A-orthonormal for the caller's ``A``). Powers of two
    make both steps exact, so the caller's ``shift`` (in the caller's units) and every tolerance
    act on a surface of about unit area, whatever its units: ARPACK's convergence test, relative in
    name, lost copies of repeated eigenvalues on a mesh scaled by 1e-8 before this.

    ``bar`` (a :func:`~lbo_notebooks._support.progress.progress_bar` over the ``k`` pairs, silent or not,
    updated only in this thread) is told the stage and the pairs found; it changes nothing else.
    """
    def stage(name: str) -> None:
        bar.set_postfix_str(name, refresh=True)

    n = W.shape[0]
    q = unit_area_exponent(A.data)
    if abs(q) > 500:  # 4**q would leave the eigenvalues or the eigenvectors out of double precision
        raise ValueError(
            f"the mass matrix's total (the area) is about 4**{q}: out of double precision's usable range for the "
            "eigenvalues (1 / area) and eigenvectors (1 / sqrt(area)). Rescale the shape or the mass matrix."
        )
    A = A * np.ldexp(1.0, -2 * q)
    if shift is None:
        shift = default_shift(A)
    else:
        shift = float(np.ldexp(float(shift), 2 * q))
        if not (np.isfinite(shift) and shift > 0):
            raise ValueError("shift is out of range for this mesh's units; leave it at its default.")

    if use_dense(n) or 2 * k + 1 > n:
        stage("dense eigh")
        values, vectors = scipy.linalg.eigh(W.toarray(), A.toarray(), subset_by_index=[0, k - 1])
    else:
        from ._engine.eigensolver import SLICE_SIZE, TOL, slice_eigsh

        def sliced(fallback: bool) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
            # fallback: on a RuntimeError warn and return None (ARPACK's set is tried and counted next).
            try:
                stage("ordering")
                fill_order = order()
                stage("Lanczos sets (spectrum slicing)")
                return slice_eigsh(
                    W, A, k, v0=start_vector(n), shift=shift, order=fill_order, tol=TOL if tol is None else float(tol),
                    on_progress=bar.update,
                )[:2]
            except RuntimeError as error:
                if not fallback:
                    raise
                warn(f"{error} Falling back to one ARPACK run for k={k}.", RuntimeWarning)
                bar.update(-bar.n)  # back to no pair found: ARPACK starts over
                return None

        slicing_first = solver == "slicing" or (solver == "auto" and k >= SLICE_SIZE)
        pairs = sliced(fallback=solver == "auto") if slicing_first else None
        if pairs is None:
            stage("ARPACK (shift-invert Lanczos)")
            try:
                values, vectors = spla.eigsh(W, k=k, M=A, sigma=-shift, which="LM", v0=start_vector(n), tol=tol or 0.0)
            except RuntimeError as error:  # ArpackError, ArpackNoConvergence, a singular W + shift A
                if solver == "arpack":
                    raise RuntimeError(
                        f"ARPACK failed at sigma = -shift ({error}); solver='auto' completes and certifies its result."
                    ) from error
                if slicing_first:
                    raise RuntimeError(f"neither spectrum slicing nor ARPACK ({error}) found the {k} eigenpairs.") from error
                values = None
            if values is not None:
                ascending = np.argsort(values)
                values, vectors = values[ascending], vectors[:, ascending]
            if solver == "auto":
                stage("inertia count (is ARPACK's set complete?)")
                if values is None or not _arpack_is_complete(W, A, values, order):
                    if slicing_first:  # slicing has already failed: nothing left can certify the set
                        raise RuntimeError(
                            f"neither spectrum slicing nor ARPACK's set (checked by an inertia count) could certify the {k} "
                            "smallest eigenpairs; try another shift, or solver='arpack' for ARPACK's set unchecked."
                        )
                    pairs = sliced(fallback=False)  # certified by inertia counts, or a RuntimeError
        if pairs is not None:
            values, vectors = pairs
        # ARPACK and the slices return A-orthonormal vectors up to round-off; re-orthonormalising
        # in order (no mixing) keeps Phi.T A Phi = I to machine precision. The arrays are the
        # solver's own: refined and sign-fixed in place (no second and third n x k copy).
        bar.update(k - bar.n)  # every pair found
        stage("orthonormalising, fixing signs")
        if cholesky_qr(vectors, A, out=vectors) is None:  # not nearly orthonormal: Gram-Schmidt
            vectors = a_orthonormalize(vectors, A)
    vectors = fix_signs_in_place(np.ascontiguousarray(vectors, dtype=np.float64), A)
    # Back to the caller's units, exactly: Phi.T (4**q A_unit) Phi = I.
    vectors *= np.ldexp(1.0, -q)
    return np.ascontiguousarray(np.ldexp(values, -2 * q)), vectors


def _arpack_is_complete(
    W: sp.csr_matrix, A: sp.csr_matrix, values: NDArray[np.float64], order: Callable[[], NDArray[np.intp] | None]
) -> bool:
    """True when no eigenvalue below the cluster of ``values[-1]`` is missing from ``values`` (an inertia count).

    Lanczos with one start vector finds one copy of an exactly repeated eigenvalue in exact
    arithmetic, the others only through round-off: on an icosphere ARPACK returned, depending on
    the last bits of the mass matrix, the 20 smallest eigenvalues or 19 of them and a larger one
    (error 2e-3 at k = 20; 50% at k = 25 when it missed most of a cluster). Sylvester's law counts the
    eigenvalues below a point exactly, so a count just below the last value's cluster proves the
    set complete, or sends the problem to spectrum slicing, which completes it.

    The point sits below the top by ``1e-9`` of it, or by ``1e-3`` of the default shift (a
    unit-free floor for a top at 0), never by a fraction of the caller's shift: ``1e-3 shift``
    put it below a whole missing copy of a 5-fold eigenvalue at ``shift=1e4`` (the count then
    matched a set that was short).
    """
    from ._engine.factor import SliceFactor

    top = float(values[-1])
    point = top - max(1e-9 * abs(top), 1e-3 * default_shift(A))
    # One factorisation (the METIS order only on large meshes: see eigenbasis).
    try:
        count = SliceFactor.of(W, A, point, order()).n_below
    except ValueError:  # the point is an eigenvalue (or the pivots are off the diagonal): no proof
        return False
    return count == int(np.count_nonzero(values < point))
