"""Measuring what a computation costs: CPU time, traced peak memory and growth exponents.

Two ways, for two questions. In the same process (:func:`measure_cost`, :func:`least_cost`): CPU
time and the peak of NumPy and Python allocations, cheap enough for a notebook. In a fresh process
(:func:`measure_in_fresh_process`, :func:`least_wall_time`): wall time and the growth of the whole
process's peak memory (RSS, compiled libraries included), what the benchmarks (``benchmarks/README.md``)
report against other libraries.

Used by the notebooks to show live how classical and spectral MDS scale with the number of
vertices (small sizes, measured in the same run), and by the benchmarks. Costs that take minutes
to measure are recorded by a benchmark run instead: :func:`recorded_benchmark` reads them.
"""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._support.validation import check_integer

__all__ = [
    "growth_exponent", "measure_cost", "least_cost", "measure_in_fresh_process", "least_wall_time",
    "recorded_benchmark",
    "RESULTS",
]

#: Where ``benchmarks/*.py`` record their runs: the package's own ``recorded/`` folder (package
#: data), so an installed package, or one notebook handed out alone, reads them too.
RESULTS = Path(__file__).resolve().parents[1] / "recorded"


def growth_exponent(sizes: ArrayLike, costs: ArrayLike) -> float:
    """Least-squares slope of ``log(cost)`` against ``log(size)``: cost ~ size^exponent.

    Examples
    --------
    >>> growth_exponent([100, 200, 400], [3.0, 12.0, 48.0])
    2.0
    """
    n, c = np.asarray(sizes, dtype=np.float64), np.asarray(costs, dtype=np.float64)
    if n.shape != c.shape or n.ndim != 1 or n.size < 2:
        raise ValueError("sizes and costs must be 1-D arrays of the same length, at least 2.")
    if np.any(n <= 0) or np.any(c <= 0) or not np.all(np.isfinite(c)):
        raise ValueError("sizes and costs must be positive and finite (logarithms are taken).")
    return float(round(np.polyfit(np.log(n), np.log(c), 1)[0], 12))


def measure_cost(function: Any, *args: Any, **kwargs: Any) -> dict[str, Any]:
    """Run ``function(*args, **kwargs)``; return its ``result``, ``cpu_seconds`` and ``peak_bytes``.

    ``cpu_seconds`` is the process CPU time (``time.process_time``), which on a shared machine is
    steadier than wall time. The call runs with one BLAS thread
    (:func:`~lbo_notebooks._engine.threads.one_blas_thread`, unless you set the count yourself):
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

    from .._engine.threads import one_blas_thread

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
    check_integer(runs, "runs", 1)
    return min((measure_cost(function, *args, **kwargs) for _ in range(int(runs))), key=lambda cost: cost["cpu_seconds"])


def _settle_blas_threads(timeout: float = 1.0) -> None:
    """Give a forked child the idle BLAS thread pools a process of its own has.

    OpenBLAS tears its thread pool down across ``fork`` and builds it again at the child's first
    change of its thread count. The new threads spin for a while before they sleep: on two cores,
    a first call that limits BLAS to one thread (as the package's solvers do) competed with two
    spinning pools and was timed slower than in a new interpreter, where the pools were built and
    went idle at import. So the pools are rebuilt here, before any timing (setting each
    library's own count again changes nothing else), and the child waits until it is idle: less
    than a tenth of a core used over 20 ms, at most ``timeout`` seconds.
    """
    from .._engine.threads import rebuild_thread_pools

    rebuild_thread_pools()
    deadline = time.perf_counter() + timeout
    while time.perf_counter() < deadline:
        cpu = time.process_time()
        time.sleep(0.02)
        if time.process_time() - cpu < 0.002:
            return


def _in_child(function: Any, args: tuple, queue: Any) -> None:
    import resource

    _settle_blas_threads()
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    start = time.perf_counter()
    result = function(*args)
    elapsed = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux
    queue.put({"wall_seconds": elapsed, "peak_rss_mib": peak / 1024.0, "rss_growth_mib": (peak - base) / 1024.0, "result": result})


def measure_in_fresh_process(function: Any, *args: Any) -> dict[str, Any]:
    """Run ``function(*args)`` in a forked process: ``wall_seconds``, ``peak_rss_mib``, ``rss_growth_mib``, ``result``.

    The child starts as a copy of this process (``fork``, so Linux or macOS), and its peak
    resident memory is read before and after the call: ``rss_growth_mib`` is what the call added,
    compiled libraries included, and peaks of earlier measurements do not leak in. The result
    comes back pickled. Before the clock starts, the child's BLAS thread pools are rebuilt and left
    to go idle, as they are in a process of its own (OpenBLAS drops them across ``fork``; see
    ``_settle_blas_threads``).

    Examples
    --------
    >>> cost = measure_in_fresh_process(sum, [1, 2, 3])
    >>> cost["result"], cost["wall_seconds"] >= 0, cost["peak_rss_mib"] > 0
    (6, True, True)
    """
    import multiprocessing as mp

    context = mp.get_context("fork")
    queue = context.Queue()
    child = context.Process(target=_in_child, args=(function, args, queue))
    child.start()
    out = queue.get()
    child.join()
    return out


def least_wall_time(runs: int, function: Any) -> float:
    """The least wall time, in seconds, of ``runs`` calls of ``function()`` (the least noisy single number).

    Examples
    --------
    >>> least_wall_time(3, lambda: sum(range(1000))) >= 0
    True
    """
    check_integer(runs, "runs", 1)
    best = float("inf")
    for _ in range(int(runs)):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


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
    if path is None:
        if not isinstance(name, str) or not name or Path(name).name != name:
            raise ValueError(f"name must be a benchmark's name such as 'mds' (a file of {RESULTS}), got {name!r}.")
        file = RESULTS / f"{name}.json"
    else:
        file = Path(path)
    if not file.is_file():
        raise FileNotFoundError(
            f"no recorded benchmark at {file}: run benchmarks/{name}.py with its --record/--json option in the "
            "repository to record it."
        )
    return json.loads(file.read_text())
