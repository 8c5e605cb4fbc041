"""Spectrum slicing: the lowest eigenpairs of ``W phi = lam A phi`` with a proof that none is missed.

One shift-invert Lanczos run for ``k`` eigenpairs carries a Krylov space of ``2k + 1`` vectors, and
orthogonalising it costs ``O(n k^2)`` per restart: at 50k vertices and ``k = 300`` that, not the
sparse solves, is most of the time. Slicing (Vallet & Lévy 2008) cuts the spectrum into a few
windows and runs one small block Lanczos (:mod:`~lbo_notebooks.spectral._engine.krylov`) per window, the windows in
parallel threads.

Each shift ``b`` is factorised once, ``P (W - b A) P^T = L U`` with a symmetric ordering and no
row pivoting, so that ``U = D L^T`` and, by Sylvester's law of inertia, the number of negative
pivots in ``D`` *is* the number of eigenvalues below ``b``. The same factorisation runs the
shift-invert Lanczos for the window around ``b``. Between two consecutive shifts the difference
of their counts says exactly how many eigenpairs the interval holds, and an interval that comes
back short is completed (the missing pairs are looked for apart from the found ones), redone or
raises instead of silently dropping one.
"""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ..._support.validation import Array, Integer, Number, Relation, Satisfies, validated
from .._inner_product import is_square_matrix
from .._mass_products import cholesky_qr
from .factor import NESTED_DISSECTION_MIN, SliceFactor, fill_reducing_order, return_freed_memory, symmetric_lu
from .krylov import BLOCK_SIZE, nearest_eigenpairs
from .policy import default_shift
from .slicing import Pencil, WindowPlan, centred_target, place_shift, plan_sets, plan_window
from .threads import default_workers, one_blas_thread

__all__ = ["SLICE_SIZE", "TOL", "slice_eigsh"]

# Eigenvalues per window: the orthogonalisation cost (n * basis^2 per window) against one
# factorisation per window (in time about 40 block solves at 50k vertices, in memory about 125
# eigenvectors: 48 MiB).
SLICE_SIZE = 100
# Lanczos convergence tolerance (ARPACK's, relative to the shifted-inverted eigenvalue).
TOL = 1e-10
# A floor -shift more than this many default shifts below 0 is raised to -default_shift (when a
# count proves no eigenvalue below it). The floor's count (0) and distance place the first shift
# and plan its window: from -1600 on a 642-vertex icosphere of unit area (shift=100 in its own
# units) the top window reached to 3800, held most of the spectrum, and its basis grew past n.
FAR_FLOOR = 10.0


@dataclass
class _Slice:
    """One shift of the spectrum: its inertia count and its Lanczos set (plan and running result).

    The slice at ``-shift`` (the floor, no eigenvalue below it) has no set: ``window`` and
    ``result`` are ``None``. A set that is redone gets a wider ``window``.
    """

    shift: float
    n_below: int
    window: WindowPlan | None = None
    result: Future | None = None


@dataclass(frozen=True)
class _Slices:
    """What the placement hands to the stitching: the slices, ascending, and the count at the top of the top window.

    ``top_count`` is ``None`` when that point is an eigenvalue (then a count in a gap certifies the top).
    """

    slices: list[_Slice]
    top_count: int | None


def _window_set(
    pencil: Pencil, factor: SliceFactor, window: tuple[float, float], expected: int, block_size: int = BLOCK_SIZE
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The eigenpairs with ``window[0] < lam < window[1]`` (block shift-invert Lanczos at ``factor.shift``), ascending."""
    nev = int(min(max(expected, 1), pencil.n - 1))
    return nearest_eigenpairs(
        factor.lu.solve, pencil.W, pencil.A, factor.shift, nev, start=pencil.v0, window=window, tol=pencil.tol,
        block_size=block_size,
    )


def _n(stiffness: sp.spmatrix, **_: object) -> int:
    """The number of unknowns (vertices): the size of ``stiffness``."""
    return int(np.shape(stiffness)[0])


@validated(
    stiffness=Satisfies(is_square_matrix, message="stiffness must be a square (n, n) matrix (see operators.stiffness_matrix), "
                                         "got {type}."),
    mass=Relation(lambda stiffness, mass, **_: is_square_matrix(mass) and np.shape(mass) == np.shape(stiffness),
                  lambda stiffness, mass, **_: f"mass must be a square matrix of the size of stiffness "
                                               f"{np.shape(stiffness)}, got {type(mass).__name__} of shape {np.shape(mass)}"),
    k=Integer(1, lambda stiffness, **_: _n(stiffness) - 1, what="an integer between 1 and n - 1 = {high}"),
    slice_size=Integer(1),
    shift=Number(0, open_low=True),
    tol=Number(0, 1, open_low=True, open_high=True, what="a number between 0 and 1 (e.g. 1e-10)"),
    v0=Array(1, rows=_n, what="be a finite vector of shape ({rows},)"),
    workers=Integer(1, none=True),
)
def slice_eigsh(
    stiffness: sp.spmatrix,
    mass: sp.spmatrix,
    k: int,
    *,
    v0: NDArray[np.float64],
    shift: float,
    slice_size: int = SLICE_SIZE,
    workers: int | None = None,
    order: NDArray[np.intp] | None = None,
    tol: float = TOL,
    on_progress: Callable[[int], None] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """The ``k`` smallest eigenpairs of ``stiffness phi = lam mass phi`` by spectrum slicing.

    About ``k / slice_size`` shifts (a multiple of ``workers``) are placed: the top one about half
    a set's share of eigenvalues (``k / n_sets``) below ``lam_k``, each lower one in the middle of
    the window left to it (windows need not hold equally many); each is factorised once, which counts the
    eigenvalues below it. At each shift a block Lanczos run returns the eigenpairs in its window,
    centred on the shift (Lanczos converges last at the edge farthest from it), neighbouring
    windows overlapping a little (:mod:`~lbo_notebooks.spectral._engine.slicing`); the runs
    go in ``workers`` threads while the next shifts are placed, from the top of the spectrum down
    (higher windows take longer, so they start first). The interval between two shifts
    takes the lower set's eigenvalues below a split point and the upper set's above it, the split
    sitting in the widest gap of the overlap so that no cluster of (near-)equal eigenvalues is cut
    (or, failing that, one set alone). The number taken must equal the difference of the two
    inertia counts, and a last count in a gap just above ``lam_k`` certifies the top. An interval
    that comes out short (a block of 4 finds at most 4 copies of an exactly repeated eigenvalue:
    5-fold ones on an icosphere) is completed by one small run, A-orthogonal to the pairs found,
    at a shift in its middle; failing that a window is redone twice as wide, and finally a
    ``RuntimeError`` is raised: an eigenvalue is never silently missed.

    Parameters
    ----------
    stiffness, mass : scipy.sparse matrix
        Symmetric; ``stiffness`` positive semidefinite, ``mass`` positive definite.
    k : int
        Number of eigenpairs, ``1 <= k < n``.
    v0 : ndarray, shape (n,)
        Lanczos start vector (the same for every shift, so results are deterministic).
    shift : float > 0
        ``stiffness + shift * mass`` is positive definite; the floor of the slices (no eigenvalue
        below it) is ``-shift``, or ``-default_shift(mass)`` when ``shift`` is more than
        ``FAR_FLOOR`` times that and a count proves no eigenvalue below it (one more
        factorisation): a floor far below the spectrum would mislead the placement of the shifts.
    slice_size : int
        Target number of eigenvalues per window.
    workers : int, optional
        Threads for the windows; default :func:`default_workers` (the usable cores, at most 2). The
        result is the same, bit for bit, for any number.
    order : ndarray (n,), optional
        A fill-reducing order shared by every shift, e.g. the mesh's
        :func:`~lbo_notebooks.spectral._solvers.mesh_order`; default: METIS on the pattern of
        ``stiffness`` and ``mass`` from :data:`~lbo_notebooks.spectral._engine.factor.NESTED_DISSECTION_MIN`
        unknowns on, below that the first factorisation's own (SuperLU's minimum degree), kept
        for the others.
    tol : float
        Lanczos convergence: each returned pair's residual in the shift-inverted problem,
        relative to its eigenvalue there (see :func:`~lbo_notebooks.spectral._engine.krylov.nearest_eigenpairs`).
        Eigenvalues converge as its square: 1e-8 still gives them to about 1e-14 relative.
    on_progress : callable, optional
        Called in the calling thread (never in a worker) each time a Lanczos set has finished,
        with the number of the ``k`` eigenpairs that set stands for (about ``k / n_sets``; the
        numbers add up to at most ``k``). A progress bar's ``update``, e.g.; it does not change
        the result.

    Returns
    -------
    values : ndarray, shape (k,)
        Ascending.
    vectors : ndarray, shape (n, k)
        Eigenvectors, A-orthonormal within each shift's set (across sets up to residual / gap).
    n_below : int
        Inertia count at the last point checked (above ``lam_k``): exactly ``n_below >= k``
        eigenvalues lie below it and all of them were found, so none below ``values[-1]`` is
        missing.

    Examples
    --------
    >>> import numpy as np
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> from lbo_notebooks.spectral import count_below
    >>> m = shapes.icosphere(4)
    >>> W, A = stiffness_matrix(m), mass_matrix(m)
    >>> values, vectors, n_below = slice_eigsh(W, A, 25, v0=np.ones(m.n_vertices), shift=0.01, slice_size=8)
    >>> np.round(values[[1, 4, 9, 16]]).tolist()  # l (l + 1), l = 1..4, with multiplicities 2l + 1
    [2.0, 6.0, 12.0, 20.0]
    >>> n_below >= 25 and count_below(W, A, values[-1] * (1 + 1e-6)) == 25  # l <= 4: 25 eigenvalues
    True
    """
    W, A = sp.csr_matrix(stiffness, dtype=np.float64), sp.csr_matrix(mass, dtype=np.float64)
    n = W.shape[0]
    if workers is None:
        workers = default_workers()
    n_sets = plan_sets(k, slice_size, int(workers))
    if order is None and n >= NESTED_DISSECTION_MIN:
        order = fill_reducing_order(abs(W) + abs(A))  # every shift's W - b A has this pattern
    pencil = Pencil(W, A, order, v0, tol)
    floor = float(shift)
    nearer = default_shift(A)
    if floor > FAR_FLOOR * nearer:
        try:
            if pencil.factor(-nearer).n_below == 0:
                floor = nearer
        except ValueError:  # -nearer is an eigenvalue: keep the caller's floor
            pass
    # One BLAS thread per worker (unless the user chose the count): no oversubscription, and the
    # same round-off for any `workers`. The count is process-wide: blas_threads owns it.
    with one_blas_thread(), ThreadPoolExecutor(max_workers=int(workers)) as pool:
        slices = _submit_sets(pool, int(workers), pencil, floor, k, n_sets, on_progress)
        return _stitch(pencil, k, slices)


def _submit_sets(
    pool: ThreadPoolExecutor, workers: int, pencil: Pencil, shift: float, k: int, n_sets: int,
    on_progress: Callable[[int], None] | None = None,
) -> _Slices:
    """Place the shifts (in this thread), from the top down, and start each one's Lanczos set in ``pool`` at once.

    The top shift aims at ``k - k / (2 n_sets)`` eigenvalues below it; each lower one at the middle
    of the window left to it (:func:`~lbo_notebooks.spectral._engine.slicing.centred_target`), every window centred
    on its shift (:func:`~lbo_notebooks.spectral._engine.slicing.plan_window`). The sets start from the top: a window higher in
    the spectrum takes longer (there are eigenvalues on both sides of it, and they lie closer
    together relative to their distance from the shift), and the longest jobs first keep the
    workers busy to the end. A factorisation is large (about the size of 125 eigenvectors), so the
    next shift is factorised only when at most ``workers`` sets are unfinished: one set waits,
    factorised, for the first worker to come free (a worker never idles while a factorisation is
    made), at most ``workers + 1`` factorisations are alive, and a set drops its own when it ends.
    This thread also makes the one count that is not a set's shift: at the top of the top window
    (usually the certificate above ``lam_k``; ``None`` if that point is an eigenvalue), as soon as
    the top set has started, so that it runs beside one set whose basis is still small. At
    ``-shift`` no count is needed: when the first interval holds exactly its count, no eigenvalue
    can lie below ``-shift``.
    Returns the slices in ascending order (the first, at ``-shift``, has no set) and the top count.
    ``on_progress(pairs)`` is called here, in this thread, as each set is found finished: set
    ``j`` stands for the eigenpairs ``round((j - 1) k / n_sets) .. round(j k / n_sets)``.
    """
    # Weyl's law N(lam) ~ area lam / (4 pi) places the top shift; the others interpolate the
    # measured counts (N grows about linearly in lam on a surface).
    slope = float(pencil.A.sum()) / (4.0 * np.pi)
    # No eigenvalue lies below -shift: proved by the first interval's count (see _stitch).
    first = SliceFactor(shift=-shift, n_below=0, lu=None)
    per_set = k / n_sets
    placed: dict[int, _Slice] = {}  # by set, from the top down
    # Factorisations are made and freed in this thread: glibc keeps much of a large block that
    # another thread frees, so a factorisation freed by a worker would stay resident.
    alive: dict[int, SliceFactor] = {}

    def run(j: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        window = placed[j].window
        return _window_set(pencil, alive[j], (window.low, window.high), window.expected)

    def make_room() -> None:
        # Wait until at most `workers` sets are unfinished (running or queued), then free the
        # factorisations of finished ones.
        unfinished = [s.result for s in placed.values() if not s.result.done()]
        if len(unfinished) > workers:
            wait(unfinished, return_when=FIRST_COMPLETED)
        finished = [j for j in alive if placed[j].result.done()]
        for j in finished:
            del alive[j]
            if on_progress is not None:
                on_progress(round(j * per_set) - round((j - 1) * per_set))
        if finished:
            return_freed_memory()

    above: _Slice | None = None  # the slice placed last, the nearest above
    top_count: int | None = None
    for j in range(n_sets, 0, -1):
        make_room()
        if above is None:
            target = (j - 0.5) * per_set
        else:  # centred in its window, with room below for the j - 1 sets still to place
            target = centred_target(above.window, above.n_below, first.shift, per_set, j == 1)
            target = min(max(target, 0.5 * (j - 1) * per_set + 1), above.n_below - 1)
        reference = first if above is None else SliceFactor(shift=above.shift, n_below=above.n_below, lu=None)
        factor = place_shift(pencil, target, max(1.0, per_set / 3), first, None if above is None else reference, slope)
        if factor is None:  # one cluster fills the rest of the bracket: the neighbours cover it
            continue
        return_freed_memory()  # SuperLU's work space, freed when the factorisation ended
        alive[j] = factor
        # Local density of eigenvalues (per unit of lam) from the counts above and at this shift.
        slope = max(abs(reference.n_below - factor.n_below), 1) / abs(reference.shift - factor.shift)
        window = plan_window(
            factor.shift,
            factor.n_below,
            None if above is None else (above.shift, above.n_below),
            None if above is None else above.window,
            (j - 1.5) * per_set if j > 1 else None,
            first.shift,
            k,
            n_sets,
            slope,
        )
        placed[j] = _Slice(factor.shift, factor.n_below, window)
        placed[j].result = pool.submit(run, j)
        if above is None:
            # The top set has started: count at the top of its window now, while one set runs
            # and its Krylov basis is still small (later, beside every set and full bases, the
            # extra factorisation would slow them all and raise the peak memory).
            try:
                top_count = pencil.factor(window.high).n_below
            except ValueError:  # the top of the window is an eigenvalue: certify from a gap later
                top_count = None
            return_freed_memory()
        above = placed[j]
    if not placed:  # no shift fitted anywhere between -shift and the top: nothing to slice
        raise RuntimeError("spectrum slicing could not place a shift; use solver='arpack'.")
    while alive:  # free each factorisation as soon as its set ends, not when the last one does
        wait([placed[j].result for j in alive], return_when=FIRST_COMPLETED)
        make_room()
    return _Slices([_Slice(first.shift, first.n_below)] + [placed[j] for j in sorted(placed)], top_count)


def _split(
    carry: NDArray[np.float64],
    carry_top: float,
    values: NDArray[np.float64],
    low_shift: float,
    shift: float,
    trusted: float,
    count: int | None,
) -> tuple[NDArray[np.bool_], NDArray[np.bool_]] | None:
    """Masks of ``carry`` and ``values`` that together hold exactly ``count`` eigenvalues of ``(low_shift, shift)``.

    ``carry`` (the lower set's eigenvalues above ``low_shift``) is trusted below ``carry_top``, the
    set at ``shift`` above ``trusted`` (the bounds of their windows). The split sits in the widest gap of the overlap (no
    cluster is cut), or one set alone is taken. ``None`` when no split gives ``count``: Lanczos can
    return only part of an exactly multiple eigenvalue and farther ones instead, so "complete
    inside its window" is a hope, not a fact; the count decides. ``count=None``: the masks of the
    preferred split, whatever they hold.
    """
    low, top = max(trusted, low_shift), min(carry_top, shift)
    splits = [low_shift]
    if low < top:  # the overlap is not empty
        inside = np.sort(np.concatenate(([low, top], carry[(carry > low) & (carry < top)])))
        gaps = np.diff(inside)
        splits.insert(0, float(inside[np.argmax(gaps)] + gaps.max() / 2))
    if carry_top > shift:
        splits.append(shift)
    for split in splits:
        from_carry = carry < split
        mine = (values > split) & (values < shift)
        if count is None or np.count_nonzero(from_carry) + np.count_nonzero(mine) == count:
            return from_carry, mine
    return None


def _stitch(pencil: Pencil, k: int, slices: _Slices) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """Join consecutive sets interval by interval, each holding exactly its inertia count; certify the top.

    Between the last shift and ``lam_k`` there is no shift: ``top_count``, the count at the top of
    the last window, proves that none below it is missing when the last set holds that many; else
    a count at a point in a gap just above ``lam_k`` (among the last set's eigenvalues) decides. An
    interval that comes out short is first completed (``complete``: only the missing pairs are
    looked for), then its set is redone with a window twice as wide.
    """
    return _Stitcher(pencil, k, slices).run()


class _Stitcher:
    """The state of :func:`_stitch`: the results filled so far and the upper part of the last set (the carry)."""

    def __init__(self, pencil: Pencil, k: int, slices: _Slices) -> None:
        self.pencil, self.k = pencil, k
        self.slices, self.top_count = slices.slices, slices.top_count
        # Intervals come in increasing order and each is ascending, so results fill in order; only
        # the first k are kept (preallocated: no list of blocks plus a concatenated copy).
        self.values = np.empty(k)
        self.vectors = np.empty((pencil.n, k))
        self.filled = 0
        self.carry_values, self.carry_vectors = np.empty(0), np.empty((pencil.n, 0))
        self.carry_top = self.slices[0].shift

    def run(self) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
        for j in range(1, len(self.slices)):
            self.join(j)
        return self.certify_top()

    def fill(self, vals: NDArray[np.float64], vecs: NDArray[np.float64]) -> None:
        take = min(vals.size, self.k - self.filled)
        self.values[self.filled : self.filled + take] = vals[:take]
        self.vectors[:, self.filled : self.filled + take] = vecs[:, :take]
        self.filled += take

    def result(self, n_below: int) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
        return self.values, self.vectors, n_below

    def carry_from(self, j: int, values: NDArray[np.float64], vectors: NDArray[np.float64]) -> None:
        """Keep the pairs of set ``j`` above its shift for the next interval."""
        above = values > self.slices[j].shift
        self.carry_values, self.carry_vectors, self.carry_top = values[above], vectors[:, above], self.slices[j].window.high

    def join(self, j: int) -> None:
        """Fill the interval between shifts ``j - 1`` and ``j`` with exactly its inertia count of pairs."""
        below, here = self.slices[j - 1], self.slices[j]
        interval = here.n_below - below.n_below
        values, vectors = here.result.result()
        here.result = None  # the set is copied out below: let it go
        completed = None
        for attempt in range(3):
            masks = _split(self.carry_values, self.carry_top, values, below.shift, here.shift, here.window.low, interval)
            if masks is not None or attempt == 2:
                break
            # The first interval, when complete, proves that no eigenvalue lies below -shift (the
            # count at shift 1 has no room for one); only when it is not is that count worth making.
            if j == 1 and self.pencil.factor(below.shift).n_below:
                raise ValueError(
                    f"stiffness + {-below.shift:g} mass is not positive definite: stiffness must be positive semidefinite."
                )
            if attempt == 0:  # first look only for what is missing
                from_carry, mine = _split(self.carry_values, self.carry_top, values, below.shift, here.shift, here.window.low, None)
                completed = self.complete(
                    below.shift,
                    here.shift,
                    interval,
                    np.concatenate((self.carry_values[from_carry], values[mine])),
                    np.hstack((self.carry_vectors[:, from_carry], vectors[:, mine])),
                )
                if completed is not None:
                    break
            values, vectors = self.redo(j, attempt + 1)
        if completed is not None:
            self.fill(*completed)
        elif masks is None:
            raise RuntimeError(
                f"spectrum slicing did not find the {interval} eigenvalues that the inertia counts put between "
                f"the shifts {below.shift:.6g} and {here.shift:.6g}; use solver='arpack'."
            )
        else:
            self.fill(self.carry_values[masks[0]], self.carry_vectors[:, masks[0]])
            self.fill(values[masks[1]], vectors[:, masks[1]])
        self.carry_from(j, values, vectors)

    def certify_top(self) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
        """Take the last set's pairs up to ``lam_k``, proved complete by a count above them."""
        last = self.slices[-1]
        if self.filled == self.k:  # the last shift is already above lam_k
            return self.result(last.n_below)
        top_count = self.top_count
        if top_count is not None and self.carry_values.size >= self.k - self.filled and top_count == last.n_below + self.carry_values.size:
            self.fill(self.carry_values, self.carry_vectors)
            return self.result(top_count)
        if top_count is not None and top_count - last.n_below >= self.k - self.filled:  # pairs are missing below the top count
            completed = self.complete(last.shift, last.window.high, top_count - last.n_below, self.carry_values, self.carry_vectors)
            if completed is not None:
                self.fill(*completed)
                return self.result(top_count)
        for attempt in range(3):
            # The last count goes in the widest gap between lam_k and the top of the last window.
            need = self.k - self.filled
            if self.carry_values.size >= need:
                edges = np.append(self.carry_values[need - 1 :], self.carry_top)
                gaps = np.diff(edges)
                top = float(edges[np.argmax(gaps)] + gaps.max() / 2)
                n_below = self.pencil.factor(top).n_below
                if n_below == last.n_below + np.count_nonzero(self.carry_values < top):
                    self.fill(self.carry_values, self.carry_vectors)
                    return self.result(n_below)
            if attempt == 2:
                break
            self.carry_from(len(self.slices) - 1, *self.redo(len(self.slices) - 1, attempt + 1))
        raise RuntimeError(
            f"spectrum slicing could not certify the eigenvalues above {last.shift:.6g} with an inertia count; use solver='arpack'."
        )

    def complete(
        self, low: float, high: float, count: int, found_values: NDArray[np.float64], found_vectors: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
        """The ``count`` eigenpairs in ``(low, high)`` given the ones found; ``None`` when they do not all come."""
        # The `count` eigenpairs in (low, high), of which these were found (a set misses copies of
        # an exactly repeated eigenvalue beyond its block size, see redo). The missing ones are
        # looked for A-orthogonally to the found ones, with twice the block, at a shift in the
        # middle of the interval, where they are nearer than any eigenvalue outside it. None when
        # that does not give them all.
        # The tolerance is relative to the distance from the shift, which is larger here than
        # from the shift of the set that missed them: with a hundredth of it a completed pair is
        # as accurate as the sets' own (a dropped pair on a bumpy sphere came back with relative
        # residual 2e-12, the sets' pairs up to 1e-10; at the sets' tolerance it was 4e-10).
        pencil = self.pencil
        missing = count - found_values.size
        if missing <= 0 or found_values.size + missing + 4 * BLOCK_SIZE >= pencil.n:
            return None
        basis = np.empty_like(found_vectors)
        if found_values.size and cholesky_qr(found_vectors, pencil.A, out=basis) is None:
            return None
        # No inertia count is needed at this shift, only the solves: a plain factorisation.
        for middle in (0.5 * (low + high), 0.5 * (low + high) + 1e-3 * (high - low)):
            try:
                lu = symmetric_lu(pencil.W - middle * pencil.A, pencil.order)
                break
            except RuntimeError:  # the middle is an eigenvalue: a little off it is as good
                continue
        else:
            return None
        try:
            new_values, new_vectors = nearest_eigenpairs(
                lu.solve, pencil.W, pencil.A, middle, missing, start=pencil.v0, window=(low, high), tol=1e-2 * pencil.tol,
                block_size=2 * BLOCK_SIZE, deflate=basis, min_found=missing,
            )
        except RuntimeError:
            return None
        if new_values.size != missing:
            return None
        values = np.concatenate((found_values, new_values))
        ascending = np.argsort(values, kind="stable")
        return values[ascending], np.hstack((basis, new_vectors))[:, ascending]

    def redo(self, j: int, attempt: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Set ``j`` again, with twice the window and ``2**attempt`` times the block."""
        # Twice the window (its factorisation was dropped: factorise again, same result) and
        # twice the block: a block of b vectors finds at most b copies of an exactly repeated
        # eigenvalue (symmetric shapes: 5 on an icosphere), the rest only by round-off.
        here, old = self.slices[j], self.slices[j].window
        here.window = WindowPlan(
            shift=old.shift,
            low=max(old.shift - 2 * (old.shift - old.low), self.slices[0].shift),
            high=old.shift + 2 * (old.high - old.shift),
            expected=2 * old.expected,
        )
        window = (here.window.low, here.window.high)
        return _window_set(self.pencil, self.pencil.factor(here.shift), window, here.window.expected, BLOCK_SIZE * 2**attempt)
