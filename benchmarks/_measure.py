"""The benchmarks' measurements in a fresh process: wall time and the whole process's peak memory.

:func:`measure_in_fresh_process` runs a call in a forked child (peak RSS, compiled libraries
included, is what the benchmarks report against other libraries); :func:`least_wall_time` is the
least noisy single wall time. The package's own in-notebook measurements (CPU time, traced
allocations) are ``lbo_notebooks.analyses.measure_cost`` and ``least_cost``.
"""

from __future__ import annotations

import time
from typing import Any, Callable

from lbo_notebooks.spectral._engine.threads import rebuild_thread_pools
from lbo_notebooks._support.validation import check_integer


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


def measure(fn: Callable[..., Any], *args: Any) -> tuple[float, float, float, Any]:
    """(seconds, peak RSS of the process in MiB, growth of peak RSS during the call in MiB, result), in a fresh process."""
    cost = measure_in_fresh_process(fn, *args)
    return cost["wall_seconds"], cost["peak_rss_mib"], cost["rss_growth_mib"], cost["result"]


def best_time(fn: Callable[[], object], repeat: int = 3) -> float:
    """Best wall time of ``repeat`` calls of ``fn`` (:func:`least_wall_time`)."""
    return least_wall_time(repeat, fn)
