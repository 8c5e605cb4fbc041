"""Where the spectrum is cut: the shared problem, the placement of the shifts and each window's plan.

:mod:`~lbo_notebooks.spectral._engine.eigensolver` slices the spectrum of ``W phi = lam A phi`` into windows, one
block Lanczos set per window. This module decides where: :func:`plan_sets` how many sets,
:func:`place_shift` each shift (a factorisation whose inertia count is near a target), and
:func:`plan_window` the window of eigenvalues the set at a shift returns (and :func:`centred_target`
where the next shift down should go for its window to be centred on it). :class:`Pencil` is the
problem every step shares (``W``, ``A``, the fill-reducing order, the Lanczos start vector and
tolerance), so that they do not travel as five separate arguments.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .factor import SliceFactor

__all__ = [
    "LOWEST_CENTRE", "MIN_SET", "OVERLAP", "REACH", "Pencil", "WindowPlan", "centred_target", "place_shift",
    "plan_sets",
    "plan_window",
]

# Fewest eigenpairs worth a Lanczos set of their own (a set costs a factorisation).
MIN_SET = 20
# Neighbouring windows overlap by twice this fraction of the interval between their shifts (room
# for the split to sit in a gap). A wider overlap cost more time and redid no
# fewer windows.
OVERLAP = 0.05
# Lanczos converges last at the window's edge farthest from the shift, and a lopsided window costs
# a set more than its extra pairs: a window reaches down at most this many times as far as up
# (all but the lowest, which reaches the floor). A set converges fastest with its shift in the
# middle of its window (and the lower windows aimed at their middle too: centred_target); larger
# reaches saved no time and left the pairs either side of a split less A-orthogonal.
REACH = 1.0
# Where the lowest set's shift sits between the floor and the top of its window (its low
# eigenvalues lie far apart, so their side converges early); nearby values made little difference.
LOWEST_CENTRE = 0.55


@dataclass(eq=False)
class Pencil:
    """The problem ``W phi = lam A phi`` as the eigensolver's steps share it.

    ``order`` is the fill-reducing order every shift's ``W - b A`` shares. When it is ``None``
    the first factorisation orders the matrix itself (SuperLU's minimum degree, what pays below
    :data:`~lbo_notebooks.spectral._engine.factor.NESTED_DISSECTION_MIN` unknowns) and its order is kept
    for the others, which then skip that step. ``v0`` is the Lanczos start vector of every set and
    ``tol`` their tolerance.
    """

    W: sp.csr_matrix
    A: sp.csr_matrix
    order: NDArray[np.intp] | None
    v0: NDArray[np.float64]
    tol: float

    @property
    def n(self) -> int:
        """Number of unknowns (vertices)."""
        return int(self.W.shape[0])

    def factor(self, shift: float) -> SliceFactor:
        """``W - shift A`` factorised, with its inertia count (:meth:`SliceFactor.of`)."""
        factor = SliceFactor.of(self.W, self.A, shift, self.order)
        if self.order is None:
            self.order = factor.lu.permutation
        return factor


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
class WindowPlan:
    """One Lanczos set: its shift, the window of eigenvalues it returns, and how many it expects there."""

    shift: float
    low: float
    high: float
    expected: int


def plan_window(
    shift: float,
    count: int,
    above: tuple[float, int] | None,
    above_plan: WindowPlan | None,
    target_below: float | None,
    floor: float,
    k: int,
    n_sets: int,
    slope: float,
) -> WindowPlan:
    """The window of the set at ``shift`` (``count`` eigenvalues below it).

    The top set reaches past ``lam_k``, so that the final count can sit in a gap above ``lam_k``;
    every other set reaches past the bottom of the window above (``above_plan``) by ``2 OVERLAP``
    of the interval between their shifts, so that the split between them can sit in a gap. Down,
    a window reaches at most ``REACH`` times as far as it reaches up (centred on its shift), and no
    farther than about halfway to ``target_below`` (where the shift below would sit if every set
    held an equal share). Shifts are placed from the top down, so the shift above (``above``: its shift
    and count) is known and the shift below is not: its target count ``target_below`` and the
    local density ``slope`` stand in for it (the lowest set, with no target below, reaches down
    to ``floor``).
    """
    if above is None:
        n_above = max(k - count, 0) + max(3, k // (10 * n_sets))
        high = shift + n_above / slope
    else:
        width = above[0] - shift
        # Not past the shift above: the split lies below it, and a cluster just above it could
        # hold many times the pairs this set expects.
        high = min(max(above_plan.low + 2 * OVERLAP * width, shift + OVERLAP * width), above[0])
        n_above = np.ceil((above[1] - count) * (high - shift) / width)
    if target_below is None:
        low, n_below = floor, count
    else:
        low = max(shift - max(count - target_below, 1.0) * (0.5 + OVERLAP) / slope, shift - REACH * (high - shift))
        # The local density can be far off next to a cluster: the count interpolated from the floor
        # is the second estimate, and the larger one sizes the basis.
        n_below = max(slope, count / (shift - floor)) * (shift - low)
    return WindowPlan(shift=shift, low=low, high=high, expected=int(np.ceil(n_below) + np.ceil(n_above)) + 2)


def centred_target(above: WindowPlan, above_count: int, floor: float, per_set: float, lowest: bool) -> float:
    """The count to aim the next shift down at, so that its window is about centred on it.

    That window reaches up to just past the bottom of ``above`` (see :func:`plan_window`). The
    lowest one reaches down to ``floor`` and its shift sits ``LOWEST_CENTRE`` of the way up; any
    other holds about ``per_set`` eigenvalues. Counts are interpolated between ``floor`` (none
    below it) and the shift above (Weyl's law: on a surface the count grows about linearly in
    ``lam``), not extrapolated from the density between two shifts, which a cluster of equal
    eigenvalues can make many times too high or too low.
    """
    density = above_count / (above.shift - floor)
    top = above.low + 2 * OVERLAP * (above.shift - above.low) / (0.5 + OVERLAP)  # about as plan_window will
    shift = floor + LOWEST_CENTRE * (top - floor) if lowest else top - (0.5 + OVERLAP) * per_set / density
    return density * (shift - floor)


def place_shift(
    pencil: Pencil,
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
            factor = pencil.factor(shift)
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
