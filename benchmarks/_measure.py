"""The benchmarks' spellings of :mod:`lbo_notebooks.analyses._cost`'s fresh-process measurements (the code lives there)."""

from __future__ import annotations

from typing import Any, Callable

from lbo_notebooks.analyses._cost import least_wall_time, measure_in_fresh_process


def measure(fn: Callable[..., Any], *args: Any) -> tuple[float, float, float, Any]:
    """(seconds, peak RSS of the process in MiB, growth of peak RSS during the call in MiB, result), in a fresh process."""
    cost = measure_in_fresh_process(fn, *args)
    return cost["wall_seconds"], cost["peak_rss_mib"], cost["rss_growth_mib"], cost["result"]


def best_time(fn: Callable[[], object], repeat: int = 3) -> float:
    """Best wall time of ``repeat`` calls of ``fn`` (:func:`lbo_notebooks.analyses._cost.least_wall_time`)."""
    return least_wall_time(repeat, fn)
