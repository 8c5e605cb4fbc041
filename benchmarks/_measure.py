"""Run a callable in a fresh process and report its wall time and peak memory (shared by benchmarks)."""

from __future__ import annotations

import multiprocessing as mp
import resource
import time
from typing import Any, Callable

import numpy as np


def _child(fn: Callable[..., Any], args: tuple, queue: Any) -> None:
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    start = time.perf_counter()
    result = fn(*args)
    elapsed = time.perf_counter() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    queue.put((elapsed, peak / 1024.0, (peak - base) / 1024.0, result))


def measure(fn: Callable[..., Any], *args: Any) -> tuple[float, float, float, Any]:
    """(seconds, peak RSS of the process in MiB, growth of peak RSS during the call in MiB, result).

    ``fn`` runs in a fresh process (fork), so peaks of earlier measurements do not leak in.
    """
    ctx = mp.get_context("fork")
    queue = ctx.Queue()
    proc = ctx.Process(target=_child, args=(fn, args, queue))
    proc.start()
    out = queue.get()
    proc.join()
    return out


def best_time(fn: Callable[[], object], repeat: int = 3) -> float:
    """Best wall time of ``repeat`` calls of ``fn`` (the least noisy single number on a busy machine)."""
    best = np.inf
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best
