"""Where the spectrum is cut: the shared problem, the placement of the shifts and each window's plan.

:mod:`~lbo_notebooks.eigensolver` slices the spectrum of ``W phi = lam A phi`` into windows, one
block Lanczos set per window. This module decides where: :func:`plan_sets` how many sets,
:func:`place_shift` each shift (a factorisation whose inertia count is near a target), and
:func:`plan_window` the window of eigenvalues the set at a shift returns. :class:`Pencil` is the
problem every step shares (``W``, ``A``, the fill-reducing order, the Lanczos start vector and
tolerance), so that they do not travel as five separate arguments.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .sparse_factor import SliceFactor

__all__ = ["MIN_SET", "OVERLAP", "Pencil", "WindowPlan", "place_shift", "plan_sets", "plan_window"]

# Fewest eigenpairs worth a Lanczos set of their own (a set costs a factorisation).
MIN_SET = 20
# Each window reaches this fraction of the interval between neighbouring shifts past its middle,
# so neighbouring windows overlap by twice it (room for the split to sit in a gap). 0.1 cost 6-13%
# more time at 50k vertices than 0.05 and redid no fewer windows on spheres, tori, rectangles and
# bumpy spheres of 10-50k vertices.
OVERLAP = 0.05


@dataclass(eq=False)
class Pencil:
    """The problem ``W phi = lam A phi`` as the eigensolver's steps share it.

    ``order`` is the fill-reducing order every shift's ``W - b A`` shares. When it is ``None``
    the first factorisation orders the matrix itself (SuperLU's minimum degree, what pays below
    :data:`~lbo_notebooks.sparse_factor.NESTED_DISSECTION_MIN` unknowns) and its order is kept
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
    return WindowPlan(shift=shift, low=low, high=high, expected=int(np.ceil(n_below) + np.ceil(n_above)) + 2)


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
