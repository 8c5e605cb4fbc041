"""Spectrum slicing: the lowest eigenpairs of ``W phi = lam A phi`` with a proof that none is missed.

One shift-invert Lanczos run for ``k`` eigenpairs carries a Krylov space of ``2k + 1`` vectors, and
orthogonalising it costs ``O(n k^2)`` per restart: at 50k vertices and ``k = 300`` that, not the
sparse solves, is most of the time. Slicing (Vallet & Lévy 2008) cuts the spectrum into a few
windows and runs one small block Lanczos (:mod:`~lbo_notebooks.krylov`) per window, the windows in
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

from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from ._platform import default_workers, return_freed_memory
from .blas_threads import one_blas_thread
from .inner_product import cholesky_qr
from .krylov import BLOCK_SIZE, nearest_eigenpairs
from .sparse_factor import SymmetricFactor, fill_reducing_order, symmetric_lu

__all__ = ["SliceFactor", "count_below", "plan_sets", "slice_eigsh"]

# Eigenvalues per window: the orthogonalisation cost (n * basis^2 per window) against one
# factorisation per window (in time about 40 block solves at 50k vertices, in memory about 125
# eigenvectors: 48 MiB).
SLICE_SIZE = 100
# Lanczos convergence tolerance (ARPACK's, relative to the shifted-inverted eigenvalue).
TOL = 1e-10
# Fewest eigenpairs worth a Lanczos set of their own (a set costs a factorisation).
MIN_SET = 20
# Each window reaches this fraction of the interval between neighbouring shifts past its middle,
# so neighbouring windows overlap by twice it (room for the split to sit in a gap). 0.1 cost 6-13%
# more time at 50k vertices than 0.05 and redid no fewer windows on spheres, tori, rectangles and
# bumpy spheres of 10-50k vertices.
OVERLAP = 0.05


@dataclass(frozen=True)
class SliceFactor:
    """``W - shift A`` factorised as ``L D L^T`` (via an unpivoted symmetric-ordering LU).

    Attributes
    ----------
    shift : float
        The point ``b`` of the spectrum.
    n_below : int
        Number of eigenvalues of ``W phi = lam A phi`` strictly below ``shift`` (Sylvester inertia).
    lu : SymmetricFactor or None
        The factorisation; ``lu.solve`` applies ``(W - shift A)^{-1}``. ``None`` once dropped (at
        50k vertices a factorisation takes as much memory as 125 eigenvectors; the count remains).
    """

    shift: float
    n_below: int
    lu: SymmetricFactor | None

    @classmethod
    def of(cls, stiffness: sp.spmatrix, mass: sp.spmatrix, shift: float, order: NDArray[np.intp] | None = None) -> "SliceFactor":
        """Factorise ``stiffness - shift * mass``; raise ``ValueError`` when ``shift`` is an eigenvalue.

        ``order``: a :func:`~lbo_notebooks.sparse_factor.fill_reducing_order` of the pattern of
        ``stiffness`` and ``mass``, shared by every shift (when omitted,
        :func:`~lbo_notebooks.sparse_factor.symmetric_lu` chooses one by size).
        """
        try:
            lu = symmetric_lu(stiffness - shift * mass, order)
        except RuntimeError as err:  # an exactly zero pivot: shift is (numerically) an eigenvalue
            raise ValueError(f"W - {shift:.17g} A is singular; move the shift off the eigenvalue.") from err
        try:
            n_below = lu.n_negative
        except ValueError as err:
            raise ValueError(f"W - {shift:.17g} A: {err}") from err
        return cls(shift=float(shift), n_below=n_below, lu=lu)


def count_below(stiffness: sp.spmatrix, mass: sp.spmatrix, value: float) -> int:
    """Number of eigenvalues of ``stiffness phi = lam mass phi`` below ``value`` (Sylvester inertia).

    Examples
    --------
    >>> from lbo_notebooks import shapes, stiffness_matrix, mass_matrix
    >>> m = shapes.icosphere(3)
    >>> count_below(stiffness_matrix(m), mass_matrix(m), 4.0)  # l = 0, 1: 1 + 3 eigenvalues below 4
    4
    """
    return SliceFactor.of(stiffness, mass, value).n_below


def _window_set(
    W: sp.csr_matrix,
    A: sp.csr_matrix,
    factor: SliceFactor,
    window: tuple[float, float],
    expected: int,
    v0: NDArray[np.float64],
    tol: float,
    block_size: int = BLOCK_SIZE,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The eigenpairs with ``window[0] < lam < window[1]`` (block shift-invert Lanczos at ``factor.shift``), ascending."""
    nev = int(min(max(expected, 1), W.shape[0] - 1))
    return nearest_eigenpairs(factor.lu.solve, W, A, factor.shift, nev, start=v0, window=window, tol=tol, block_size=block_size)


def _place_shift(
    W: sp.csr_matrix,
    A: sp.csr_matrix,
    order: NDArray[np.intp],
    target: float,
    spread: float,
    below: SliceFactor,
    above: SliceFactor | None,
    slope: float,
) -> SliceFactor | None:
    """Factorise a shift with about ``target`` eigenvalues below it, between ``below`` and ``above``.

    A count within ``spread`` of ``target`` is taken. Otherwise the shift moves: by the density
    ``slope`` (eigenvalues per unit) from the nearer known count, then by interpolating the counts
    of the bracket of shifts that gave too few and too many, falling back to bisection. A cluster
    of (near-)equal eigenvalues wider than ``spread`` cannot be split: once the bracket is that
    narrow, the new shift on either side of it nearer ``target`` is taken. ``None`` when no shift
    strictly between the two counts exists (the whole bracket is one cluster).
    """
    spacing = 1.0 / slope  # typical distance between eigenvalues
    low, high = below, above  # the bracket: counts at most / at least target
    candidates: list[SliceFactor] = []  # factorised strictly inside the bracket
    if above is None:
        shift = below.shift + max(target - below.n_below, 1.0) / slope
    else:
        shift = above.shift - max(above.n_below - target, 1.0) / slope
    for _ in range(60):
        if high is not None and not low.shift < shift < high.shift:
            shift = 0.5 * (low.shift + high.shift)
        try:
            factor = SliceFactor.of(W, A, shift, order)
        except ValueError as error:  # the shift hit an eigenvalue (e.g. 0 on a mesh of many pieces): step off it
            if "singular" not in str(error):
                raise
            shift += 1e-6 * spacing
            continue
        count = factor.n_below
        inside = below.n_below < count and (above is None or count < above.n_below)
        if inside and abs(count - target) <= spread:
            return factor
        if inside:
            candidates.append(factor)
        if count <= target:
            low = factor
        else:
            high = factor
        if high is None:  # still below the target: step up by the density, at least doubling the step
            shift = low.shift + max((target - count) / slope, 2.0 * (low.shift - below.shift))
        elif high.shift - low.shift <= 1e-9 * max(abs(high.shift), spacing):
            break
        elif high.n_below > low.n_below:
            fraction = (target - low.n_below) / (high.n_below - low.n_below)
            shift = low.shift + min(max(fraction, 0.1), 0.9) * (high.shift - low.shift)
        else:
            shift = 0.5 * (low.shift + high.shift)
    if not candidates:
        return None
    return min(candidates, key=lambda f: (abs(f.n_below - target), f.shift))


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
) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """The ``k`` smallest eigenpairs of ``stiffness phi = lam mass phi`` by spectrum slicing.

    About ``k / slice_size`` shifts (a multiple of ``workers``) are placed so that each holds about
    the same number of eigenvalues around it; each is factorised once, which counts the
    eigenvalues below it. At each shift a block Lanczos run returns the eigenpairs in a window
    reaching about halfway to the neighbouring shifts, the windows overlapping a little; the runs
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
        ``stiffness + shift * mass`` is positive definite; the first shift is ``-shift``.
    slice_size : int
        Target number of eigenvalues per window.
    workers : int, optional
        Threads for the windows; default :func:`default_workers` (the usable cores, at most 2). The
        result is the same, bit for bit, for any number.
    order : ndarray (n,), optional
        A fill-reducing order shared by every shift, e.g. the mesh's
        :func:`~lbo_notebooks.sparse_factor.mesh_order`; default: METIS on the pattern of
        ``stiffness`` and ``mass``.
    tol : float
        Lanczos convergence: each returned pair's residual in the shift-inverted problem,
        relative to its eigenvalue there (see :func:`~lbo_notebooks.krylov.nearest_eigenpairs`).
        Eigenvalues converge as its square: 1e-8 still gives them to about 1e-14 relative.

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
    if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or not 1 <= k < n:
        raise ValueError(f"k must be an integer between 1 and n - 1 = {n - 1}, got {k!r}.")
    if isinstance(slice_size, bool) or not isinstance(slice_size, (int, np.integer)) or slice_size < 1:
        raise ValueError(f"slice_size must be a positive integer, got {slice_size!r}.")
    if isinstance(shift, bool) or not (np.isscalar(shift) and np.isfinite(shift) and shift > 0):
        raise ValueError(f"shift must be a positive number, got {shift!r}.")
    if isinstance(tol, bool) or not isinstance(tol, (int, float, np.integer, np.floating)) or not 0 < tol < 1:
        raise ValueError(f"tol must be a number between 0 and 1 (e.g. 1e-10), got {tol!r}.")
    v0 = np.asarray(v0, dtype=np.float64)
    if v0.shape != (n,) or not np.all(np.isfinite(v0)):
        raise ValueError(f"v0 must be a finite vector of shape ({n},), got shape {v0.shape}.")
    if workers is None:
        workers = default_workers()
    elif isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ValueError(f"workers must be a positive integer, got {workers!r}.")
    n_sets = plan_sets(k, slice_size, int(workers))
    if order is None:
        order = fill_reducing_order(abs(W) + abs(A))  # every shift's W - b A has this pattern
    # One BLAS thread per worker (unless the user chose the count): no oversubscription, and the
    # same round-off for any `workers`. The count is process-wide: blas_threads owns it.
    with one_blas_thread(), ThreadPoolExecutor(max_workers=int(workers)) as pool:
        shifts, counts, plans, sets, top_count = _submit_sets(pool, int(workers), W, A, order, float(shift), k, v0, tol, n_sets)
        return _stitch(W, A, order, k, v0, tol, shifts, counts, plans, sets, top_count)


def plan_sets(k: int, slice_size: int, workers: int) -> int:
    """Number of Lanczos sets for ``k`` eigenpairs: about ``k / slice_size``, a multiple of ``workers``.

    Examples
    --------
    >>> plan_sets(300, 100, 2), plan_sets(100, 100, 2), plan_sets(100, 100, 1), plan_sets(9, 100, 2)
    (4, 2, 1, 1)
    """
    sets = -(-k // slice_size)
    if workers > 1 and k >= MIN_SET * workers:  # balance: every worker gets as many sets
        sets = workers * -(-sets // workers)
    return max(1, min(sets, k // MIN_SET))


@dataclass(frozen=True)
class _Set:
    """One Lanczos run: its shift, the window of eigenvalues it returns, and how many it expects there."""

    shift: float
    low: float
    high: float
    expected: int


def _plan_set(
    shift: float,
    count: int,
    above: tuple[float, int] | None,
    above_plan: _Set | None,
    target_below: float | None,
    floor: float,
    k: int,
    n_sets: int,
    slope: float,
) -> _Set:
    """The window of the set at ``shift`` (``count`` eigenvalues below it).

    It reaches from about the middle of the interval below to about the middle of the interval
    above. Shifts are placed from the top down, so the shift above (``above``: its shift and count)
    and its set's window are known, and the shift below is not: its target count
    ``target_below`` and the local density ``slope`` stand in for it (the lowest set, with no
    target below, reaches down to ``floor``). The top set reaches past ``lam_k`` instead, so that
    the final count can sit in a gap above ``lam_k``. Windows of neighbouring sets overlap by twice
    ``OVERLAP`` of the interval between them, so that the split between them can sit in a gap.
    """
    if above is None:
        n_above = max(k - count, 0) + max(3, k // (10 * n_sets))
        high = shift + n_above / slope
    else:
        width = above[0] - shift
        high = max(shift + (0.5 + OVERLAP) * width, above_plan.low + OVERLAP * width)
        n_above = np.ceil((above[1] - count) * (high - shift) / width)
    if target_below is None:
        low, n_below = floor, count
    else:
        n_below = max(count - target_below, 1.0) * (0.5 + OVERLAP)
        low = shift - n_below / slope
    return _Set(shift=shift, low=low, high=high, expected=int(np.ceil(n_below) + np.ceil(n_above)) + 2)


def _submit_sets(
    pool: ThreadPoolExecutor,
    workers: int,
    W: sp.csr_matrix,
    A: sp.csr_matrix,
    order: NDArray[np.intp],
    shift: float,
    k: int,
    v0: NDArray[np.float64],
    tol: float,
    n_sets: int,
) -> tuple[list[float], list[int], list[_Set | None], list[Future | None], int | None]:
    """Place the shifts (in this thread), from the top down, and start each one's Lanczos set in ``pool`` at once.

    Shift ``j`` aims at ``(j - 1/2) k / n_sets`` eigenvalues below it, so that set ``j`` holds about
    ``k / n_sets`` of them, centred on its shift. The sets start from the top: a window higher in
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
    Returns, in ascending order, the shifts, their counts, the sets' plans and futures (index 0,
    the shift ``-shift``, has no set: ``None``) and the top count.
    """
    # Weyl's law N(lam) ~ area lam / (4 pi) places the top shift; the others interpolate the
    # measured counts (N grows about linearly in lam on a surface).
    slope = float(A.sum()) / (4.0 * np.pi)
    # No eigenvalue lies below -shift: proved by the first interval's count (see _stitch).
    first = SliceFactor(shift=-shift, n_below=0, lu=None)
    per_set = k / n_sets
    placed: dict[int, SliceFactor] = {}  # by set, shift and count only
    plans: dict[int, _Set] = {}
    futures: dict[int, Future] = {}
    # Factorisations are made and freed in this thread: glibc keeps much of a large block that
    # another thread frees, so a factorisation freed by a worker would stay resident.
    alive: dict[int, SliceFactor] = {}

    def run(j: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        return _window_set(W, A, alive[j], (plans[j].low, plans[j].high), plans[j].expected, v0, tol)

    def make_room() -> None:
        # Wait until at most `workers` sets are unfinished (running or queued), then free the
        # factorisations of finished ones.
        unfinished = [f for f in futures.values() if not f.done()]
        if len(unfinished) > workers:
            wait(unfinished, return_when=FIRST_COMPLETED)
        finished = [j for j in alive if futures[j].done()]
        for j in finished:
            del alive[j]
        if finished:
            return_freed_memory()

    above: int | None = None  # the set placed last, the nearest above
    top_count: int | None = None
    for j in range(n_sets, 0, -1):
        make_room()
        target = (j - 0.5) * per_set
        factor = _place_shift(
            W, A, order, target, max(1.0, per_set / 3), first, None if above is None else placed[above], slope
        )
        if factor is None:  # one cluster fills the rest of the bracket: the neighbours cover it
            continue
        return_freed_memory()  # SuperLU's work space, freed when the factorisation ended
        alive[j] = factor
        placed[j] = SliceFactor(shift=factor.shift, n_below=factor.n_below, lu=None)
        # Local density of eigenvalues (per unit of lam) from the counts above and at this shift.
        reference = first if above is None else placed[above]
        slope = max(abs(reference.n_below - factor.n_below), 1) / abs(reference.shift - factor.shift)
        plans[j] = _plan_set(
            factor.shift,
            factor.n_below,
            None if above is None else (placed[above].shift, placed[above].n_below),
            None if above is None else plans[above],
            (j - 1.5) * per_set if j > 1 else None,
            first.shift,
            k,
            n_sets,
            slope,
        )
        futures[j] = pool.submit(run, j)
        if above is None:
            # The top set has started: count at the top of its window now, while one set runs
            # and its Krylov basis is still small (later, beside every set and full bases, the
            # extra factorisation would slow them all and raise the peak memory).
            try:
                top_count = SliceFactor.of(W, A, plans[j].high, order).n_below
            except ValueError:  # the top of the window is an eigenvalue: certify from a gap later
                top_count = None
            return_freed_memory()
        above = j
    if not plans:  # no shift fitted anywhere between -shift and the top: nothing to slice
        raise RuntimeError("spectrum slicing could not place a shift; use solver='arpack'.")
    while alive:  # free each factorisation as soon as its set ends, not when the last one does
        wait([futures[j] for j in alive], return_when=FIRST_COMPLETED)
        make_room()
    sets = sorted(plans)
    shifts = [first.shift] + [placed[j].shift for j in sets]
    counts = [first.n_below] + [placed[j].n_below for j in sets]
    return shifts, counts, [None] + [plans[j] for j in sets], [None] + [futures[j] for j in sets], top_count


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


def _stitch(
    W: sp.csr_matrix,
    A: sp.csr_matrix,
    order: NDArray[np.intp],
    k: int,
    v0: NDArray[np.float64],
    tol: float,
    shifts: list[float],
    counts: list[int],
    plans: list[_Set | None],
    sets: list[Future | None],
    top_count: int | None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """Join consecutive sets interval by interval, each holding exactly its inertia count; certify the top.

    Between the last shift and ``lam_k`` there is no shift: ``top_count``, the count at the top of
    the last window, proves that none below it is missing when the last set holds that many; else
    a count at a point in a gap just above ``lam_k`` (among the last set's eigenvalues) decides. An
    interval that comes out short is first completed (``complete``: only the missing pairs are
    looked for), then its set is redone with a window twice as wide.
    """
    n = W.shape[0]
    # Intervals come in increasing order and each is ascending, so results fill in order; only
    # the first k are kept (preallocated: no list of blocks plus a concatenated copy).
    out_values = np.empty(k)
    out_vectors = np.empty((n, k))
    filled = 0

    def fill(vals: NDArray[np.float64], vecs: NDArray[np.float64]) -> None:
        nonlocal filled
        take = min(vals.size, k - filled)
        out_values[filled : filled + take] = vals[:take]
        out_vectors[:, filled : filled + take] = vecs[:, :take]
        filled += take

    def complete(
        low: float, high: float, count: int, found_values: NDArray[np.float64], found_vectors: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
        # The `count` eigenpairs in (low, high), of which these were found (a set misses copies of
        # an exactly repeated eigenvalue beyond its block size, see redo). The missing ones are
        # looked for A-orthogonally to the found ones, with twice the block, at a shift in the
        # middle of the interval, where they are nearer than any eigenvalue outside it. None when
        # that does not give them all.
        # The tolerance is relative to the distance from the shift, which is larger here than
        # from the shift of the set that missed them: with a hundredth of it a completed pair is
        # as accurate as the sets' own (a dropped pair on a bumpy sphere came back with relative
        # residual 2e-12, the sets' pairs up to 1e-10; at the sets' tolerance it was 4e-10).
        missing = count - found_values.size
        if missing <= 0 or found_values.size + missing + 4 * BLOCK_SIZE >= n:
            return None
        basis = np.empty_like(found_vectors)
        if found_values.size and cholesky_qr(found_vectors, A, out=basis) is None:
            return None
        # No inertia count is needed at this shift, only the solves: a plain factorisation.
        for middle in (0.5 * (low + high), 0.5 * (low + high) + 1e-3 * (high - low)):
            try:
                lu = symmetric_lu(W - middle * A, order)
                break
            except RuntimeError:  # the middle is an eigenvalue: a little off it is as good
                continue
        else:
            return None
        try:
            new_values, new_vectors = nearest_eigenpairs(
                lu.solve, W, A, middle, missing, start=v0, window=(low, high), tol=1e-2 * tol,
                block_size=2 * BLOCK_SIZE, deflate=basis, min_found=missing,
            )
        except RuntimeError:
            return None
        if new_values.size != missing:
            return None
        values = np.concatenate((found_values, new_values))
        ascending = np.argsort(values, kind="stable")
        return values[ascending], np.hstack((basis, new_vectors))[:, ascending]

    def redo(j: int, attempt: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        # Twice the window (its factorisation was dropped: factorise again, same result) and
        # twice the block: a block of b vectors finds at most b copies of an exactly repeated
        # eigenvalue (symmetric shapes: 5 on an icosphere), the rest only by round-off.
        old = plans[j]
        plans[j] = _Set(
            shift=old.shift,
            low=max(old.shift - 2 * (old.shift - old.low), shifts[0]),
            high=old.shift + 2 * (old.high - old.shift),
            expected=2 * old.expected,
        )
        window = (plans[j].low, plans[j].high)
        block_size = BLOCK_SIZE * 2**attempt
        return _window_set(W, A, SliceFactor.of(W, A, shifts[j], order), window, plans[j].expected, v0, tol, block_size)

    carry_values, carry_vectors, carry_top = np.empty(0), np.empty((n, 0)), shifts[0]
    for j in range(1, len(shifts)):
        interval = counts[j] - counts[j - 1]
        values, vectors = sets[j].result()
        sets[j] = None  # the set is copied out below: let it go
        completed = None
        for attempt in range(3):
            masks = _split(carry_values, carry_top, values, shifts[j - 1], shifts[j], plans[j].low, interval)
            if masks is not None or attempt == 2:
                break
            # The first interval, when complete, proves that no eigenvalue lies below -shift (the
            # count at shift 1 has no room for one); only when it is not is that count worth making.
            if j == 1 and SliceFactor.of(W, A, shifts[0], order).n_below:
                raise ValueError(
                    f"stiffness + {-shifts[0]:g} mass is not positive definite: stiffness must be positive semidefinite."
                )
            if attempt == 0:  # first look only for what is missing
                from_carry, mine = _split(carry_values, carry_top, values, shifts[j - 1], shifts[j], plans[j].low, None)
                completed = complete(
                    shifts[j - 1],
                    shifts[j],
                    interval,
                    np.concatenate((carry_values[from_carry], values[mine])),
                    np.hstack((carry_vectors[:, from_carry], vectors[:, mine])),
                )
                if completed is not None:
                    break
            values, vectors = redo(j, attempt + 1)
        if completed is not None:
            fill(*completed)
        elif masks is None:
            raise RuntimeError(
                f"spectrum slicing did not find the {interval} eigenvalues that the inertia counts put between "
                f"the shifts {shifts[j - 1]:.6g} and {shifts[j]:.6g}; use solver='arpack'."
            )
        else:
            fill(carry_values[masks[0]], carry_vectors[:, masks[0]])
            fill(values[masks[1]], vectors[:, masks[1]])
        above = values > shifts[j]
        carry_values, carry_vectors, carry_top = values[above], vectors[:, above], plans[j].high
    if filled == k:  # the last shift is already above lam_k
        return out_values, out_vectors, counts[-1]
    if top_count is not None and carry_values.size >= k - filled and top_count == counts[-1] + carry_values.size:
        fill(carry_values, carry_vectors)
        return out_values, out_vectors, top_count
    if top_count is not None and top_count - counts[-1] >= k - filled:  # pairs are missing below the top count
        completed = complete(shifts[-1], plans[-1].high, top_count - counts[-1], carry_values, carry_vectors)
        if completed is not None:
            fill(*completed)
            return out_values, out_vectors, top_count
    for attempt in range(3):
        # The last count goes in the widest gap between lam_k and the top of the last window.
        need = k - filled
        if carry_values.size >= need:
            edges = np.append(carry_values[need - 1 :], carry_top)
            gaps = np.diff(edges)
            top = float(edges[np.argmax(gaps)] + gaps.max() / 2)
            n_below = SliceFactor.of(W, A, top, order).n_below
            if n_below == counts[-1] + np.count_nonzero(carry_values < top):
                fill(carry_values, carry_vectors)
                return out_values, out_vectors, n_below
        if attempt == 2:
            break
        values, vectors = redo(len(shifts) - 1, attempt + 1)
        above = values > shifts[-1]
        carry_values, carry_vectors, carry_top = values[above], vectors[:, above], plans[-1].high
    raise RuntimeError(
        f"spectrum slicing could not certify the eigenvalues above {shifts[-1]:.6g} with an inertia count; use solver='arpack'."
    )
