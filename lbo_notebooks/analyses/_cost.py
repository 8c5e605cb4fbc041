"""Measuring what a computation costs in a notebook: CPU time, traced peak memory, growth exponents.

In the same process (:func:`measure_cost`, :func:`least_cost`): CPU time and the peak of NumPy and
Python allocations, cheap enough to show live how classical and spectral MDS scale with the number
of vertices (small sizes, measured in the same run). Costs that take minutes to measure are
recorded by a benchmark run instead, and :func:`recorded_benchmark` reads them; the benchmarks'
own fresh-process measurements (wall time, whole-process memory) live with them, in
``benchmarks/_measure.py``.
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._support.validation import Array, Integer, Relation, Satisfies, validated

__all__ = ["growth_exponent", "measure_cost", "least_cost", "recorded_benchmark", "RESULTS"]

#: Where the benchmark scripts record their runs: the package's own ``recorded/`` folder (package
#: data), so an installed package, or one notebook handed out alone, reads them too.
RESULTS = Path(__file__).resolve().parents[1] / "recorded"


_SERIES = "sizes and costs must be 1-D arrays of the same length, at least 2"
#: ``sizes`` and ``costs``: 1-D (NaN and inf are refused below, for the costs only, as the logarithms see them).
_ONE_D = Array(1, finite=False, message=_SERIES + "; {name} has shape {shape}.")


def _loggable(sizes: Any, costs: Any, **_: Any) -> bool:
    return not (np.any(sizes <= 0) or np.any(costs <= 0) or not np.all(np.isfinite(costs)))


def _benchmark_name(name: Any, path: Any, **_: Any) -> bool:
    return path is not None or (isinstance(name, str) and bool(name) and Path(name).name == name)


@validated(
    sizes=_ONE_D,
    costs=(
        _ONE_D,
        Relation(lambda sizes, costs, **_: sizes.shape == costs.shape and sizes.size >= 2,
                 lambda sizes, costs, **_: f"{_SERIES}; got lengths {sizes.size} and {costs.size}."),
        Relation(_loggable, "sizes and costs must be positive and finite (logarithms are taken)."),
    ),
)
def growth_exponent(sizes: ArrayLike, costs: ArrayLike) -> float:
    """Least-squares slope of ``log(cost)`` against ``log(size)``: cost ~ size^exponent.

    Examples
    --------
    >>> growth_exponent([100, 200, 400], [3.0, 12.0, 48.0])
    2.0
    """
    return float(round(np.polyfit(np.log(sizes), np.log(costs), 1)[0], 12))


@validated(function=Satisfies(
    callable, message=lambda name, value: f"{name} must be the function to measure (a callable), got {value!r:.60}."))
def measure_cost(function: Any, *args: Any, **kwargs: Any) -> dict[str, Any]:
    """Run ``function(*args, **kwargs)``; return its ``result``, ``cpu_seconds`` and ``peak_bytes``.

    ``cpu_seconds`` is the process CPU time (``time.process_time``), which on a shared machine is
    steadier than wall time. The call runs with one BLAS thread
    (``one_blas_thread``, unless you set the count yourself):
    otherwise idle BLAS threads spinning for work are counted as CPU time too, and on a busy
    machine they can double a dense-heavy method's figure. ``peak_bytes`` is the peak of Python and NumPy allocations during the
    call, traced by :mod:`tracemalloc` (memory allocated inside compiled libraries, e.g. a sparse
    factorisation, is not counted): a lower bound that tracks the dense arrays, which dominate MDS.

    Examples
    --------
    >>> cost = measure_cost(np.ones, (1000, 1000))
    >>> cost["peak_bytes"] >= 8 * 10**6 and cost["result"].shape == (1000, 1000)
    True
    """
    import tracemalloc

    from ..spectral._solvers import one_blas_thread

    started = tracemalloc.is_tracing()
    if not started:
        tracemalloc.start()
    tracemalloc.reset_peak()
    base = tracemalloc.get_traced_memory()[0]
    cpu = time.process_time()
    try:
        with one_blas_thread():
            result = function(*args, **kwargs)
        cpu = time.process_time() - cpu
        peak = tracemalloc.get_traced_memory()[1] - base
    finally:
        if not started:
            tracemalloc.stop()
    return {"result": result, "cpu_seconds": cpu, "peak_bytes": int(peak)}


@validated(runs=Integer(1))
def least_cost(runs: int, function: Any, *args: Any, **kwargs: Any) -> dict[str, Any]:
    """:func:`measure_cost` of ``runs`` calls of ``function``: the one that took the least CPU time.

    A call of a few tenths of a second can be slowed by anything else on the machine, never
    sped up, so the least of a few runs is the steadiest estimate of its cost.

    Examples
    --------
    >>> cost = least_cost(3, np.ones, (100, 100))
    >>> sorted(cost), cost["result"].shape
    (['cpu_seconds', 'peak_bytes', 'result'], (100, 100))
    """
    return min((measure_cost(function, *args, **kwargs) for _ in range(runs)), key=lambda cost: cost["cpu_seconds"])


@validated(path=Relation(_benchmark_name, lambda name, **_: (
    f"name must be a benchmark's name such as 'mds' (a file of {RESULTS}), got {name!r}.")))
def recorded_benchmark(name: str, path: str | Path | None = None) -> dict[str, Any]:
    """The results a benchmark run recorded: ``lbo_notebooks/recorded/<name>.json``, as a dict.

    The file is package data (:data:`RESULTS`), so a notebook reads it from any working directory,
    in a checkout or an installed package alike. ``path`` reads another file instead. A missing
    file raises a ``FileNotFoundError`` that says how to record it.

    Examples
    --------
    >>> recorded = recorded_benchmark("mds")
    >>> sorted(recorded)[:3]
    ['accuracy', 'blas_threads', 'cores']
    """
    file = RESULTS / f"{name}.json" if path is None else Path(path)
    if not file.is_file():
        raise FileNotFoundError(
            f"no recorded benchmark at {file}: run benchmarks/{name}.py with its --record/--json option in the "
            "repository to record it."
        )
    return json.loads(file.read_text())
