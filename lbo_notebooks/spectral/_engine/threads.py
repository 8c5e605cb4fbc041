"""The engine's thread policy, decided here once: how many worker threads, and how many BLAS threads.

* :func:`default_workers` -- the threads the package's own parallel loops use (the eigensolver's
  slices, the heat method's blocks, ZoomOut's starts): the cores this process may run on, at most
  2, since each worker holds a sparse factorisation and its work space.
* :func:`one_blas_thread` -- BLAS on one thread while those workers run (below);
  :func:`blas_threads_for` -- the same, except for large work on an idle machine, where BLAS may
  use every core (:func:`machine_is_idle`).

**One BLAS thread, one owner of a process-wide setting.** The eigensolver's slices and the heat method's blocks run in two threads, each calling BLAS;
two threads each running a multi-threaded BLAS compete for the same cores and were no faster
than one. So while they run, BLAS gets one thread.

That count is *process-wide* (OpenBLAS with pthreads keeps one pool for the whole process), so a
``threadpool_limits`` per call is wrong as soon as calls overlap: each call records the count it
finds on entry and restores it on exit, and a call that entered while another held the limit
records the limit and restores it for good (after four threads called ``eigenbasis`` at once,
OpenBLAS stayed at one thread). Here one owner does it for the whole process:

* :func:`one_blas_thread` counts the regions that are open. The first one in records the
  caller's count and sets one thread; the last one out restores what the first one recorded.
  A lock makes the count and the switch atomic, so overlapping calls from any threads are safe.
* The switch and the restore both run in one dedicated thread: threadpoolctl (3.8) lets only
  the thread that set an OpenBLAS limit change it again, and silently ignores the others.
* A count the user chose is respected: when one of the thread environment variables
  (:data:`ENVIRONMENT`) is set, or the user holds their own ``threadpool_limits`` in another
  thread (threadpoolctl then ignores ours), the count is left as it is.

While a region is open, the whole process runs BLAS on one thread (there is nothing per-thread
to set); the caller's own count is back as soon as the last region closes. To keep the package
from touching it at all, set the count yourself, e.g. ``OPENBLAS_NUM_THREADS=2``.

**Whether the machine's other cores are idle.** OpenBLAS threads spin while they wait for a core, so beside another busy program a call running
BLAS on every core can take several times longer than on one thread (regularized PCA
on a large mesh, for one), while on an idle machine the same threads make it faster.
:func:`machine_is_idle` tells the two apart at the start of a call: it reads the kernel's CPU counters (``/proc/stat``)
twice, ``interval`` seconds apart, and counts the idle cores in between. The answer can be wrong
later in the call (another program may start), and it is only a guess where the counters do not
show the CPU quota (a container's cgroup limit is read from ``/sys/fs/cgroup/cpu.max`` when
there is one); where nothing can be read (not Linux) the answer is "not idle", the safe side.
"""

from __future__ import annotations

import os
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from contextlib import AbstractContextManager, contextmanager, nullcontext
from typing import Any, Iterator

__all__ = [
    "ENVIRONMENT", "blas_threads_for", "default_workers", "machine_is_idle", "one_blas_thread",
    "rebuild_thread_pools",
    "usable_cores", "user_chose_threads",
]

#: Environment variables by which a user sets the BLAS thread count of a process.
ENVIRONMENT = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")

_lock = threading.Lock()
_open = 0  # regions open
_limiter: Any = None  # the threadpoolctl limiter of the first region in, or None if nothing was set
_owner: tuple[int, ThreadPoolExecutor] | None = None  # (process id, the one thread that sets and restores)


def user_chose_threads() -> bool:
    """True when one of the :data:`ENVIRONMENT` variables sets the BLAS thread count.

    Examples
    --------
    >>> import os
    >>> user_chose_threads() == any(os.environ.get(name, "").strip() for name in ENVIRONMENT)
    True
    """
    return any(os.environ.get(name, "").strip() for name in ENVIRONMENT)


def _in_owner_thread(function: Any) -> Any:
    global _owner
    if _owner is None or _owner[0] != os.getpid():  # a forked child has the executor but not its thread
        _owner = (os.getpid(), ThreadPoolExecutor(max_workers=1, thread_name_prefix="lbo-blas-threads"))
    return _owner[1].submit(function).result()


def _limit() -> Any:
    from threadpoolctl import threadpool_limits

    limiter = threadpool_limits(limits=1, user_api="blas")
    limiter.__enter__()  # threadpoolctl's bookkeeping of which thread controls OpenBLAS
    return limiter


@contextmanager
def one_blas_thread() -> Iterator[None]:
    """Context manager: BLAS runs on one thread inside, the caller's count is restored after the last one.

    Reentrant and thread-safe (see the module docstring); does nothing when the user chose the
    count (:func:`user_chose_threads`).

    Examples
    --------
    >>> import numpy as np
    >>> with one_blas_thread():
    ...     with one_blas_thread():  # nested and overlapping regions share one limit
    ...         product = np.ones((2, 2)) @ np.ones(2)
    >>> product.tolist()
    [2.0, 2.0]
    """
    global _open, _limiter
    with _lock:
        if _open == 0 and not user_chose_threads():
            _limiter = _in_owner_thread(_limit)
        _open += 1
    try:
        yield
    finally:
        with _lock:
            _open -= 1
            if _open == 0 and _limiter is not None:
                limiter, _limiter = _limiter, None
                _in_owner_thread(lambda: limiter.__exit__(None, None, None))


def rebuild_thread_pools() -> None:
    """Have each BLAS library set its own thread count again, from the thread that owns the setting.

    Nothing changes but this: OpenBLAS, which drops its thread pool in a forked child, builds it
    again now rather than at the child's first change of the count (see
    the benchmarks' measurements in a fresh process). Done in the owner thread, like every
    change here, so that threadpoolctl still lets :func:`one_blas_thread` set the count later.

    Examples
    --------
    >>> rebuild_thread_pools()  # doctest: +SKIP

    Meant for a forked child (it is tested there, through ``measure_in_fresh_process``): afterwards
    the owner thread controls OpenBLAS's count, and threadpoolctl ignores a limit set in another thread.
    """
    from threadpoolctl import ThreadpoolController

    def again() -> None:
        for library in ThreadpoolController().lib_controllers:
            library.set_num_threads(library.num_threads)

    with _lock:  # like one_blas_thread: one owner thread, made once, whoever calls first
        _in_owner_thread(again)


def default_workers() -> int:
    """Threads for the package's parallel loops: the usable cores, at most 2 (each holds a factorisation).

    Examples
    --------
    >>> default_workers() in (1, 2)
    True
    """
    return max(1, min(2, _affinity()))


def _affinity() -> int:
    """The cores this process may run on (its CPU affinity; all of them where there is none)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def usable_cores() -> float:
    """Cores this process may use: its CPU affinity, capped by a cgroup (v2) CPU quota if any.

    Examples
    --------
    >>> usable_cores() >= 1
    True
    """
    cores = float(_affinity())
    try:
        with open("/sys/fs/cgroup/cpu.max") as fh:
            quota, period = fh.read().split()[:2]
        if quota != "max":
            cores = min(cores, max(1.0, int(quota) / int(period)))
    except (OSError, ValueError):
        pass
    return cores


def _cpu_times() -> tuple[int, int]:
    """(idle, total) jiffies of all CPUs from the first line of /proc/stat."""
    with open("/proc/stat") as fh:
        values = [int(v) for v in fh.readline().split()[1:9]]  # user .. steal; guest time is in user
    return values[3] + values[4], sum(values)  # idle + iowait


def machine_is_idle(interval: float = 0.05) -> bool:
    """True when, over the next ``interval`` seconds, at least all but half a usable core sat idle.

    This process sleeps meanwhile, so only other programs count. False where the counters
    cannot be read, or where this process may use only one core anyway.

    Examples
    --------
    >>> isinstance(machine_is_idle(0.01), bool)
    True
    """
    cores = usable_cores()
    if cores < 2:
        return False
    try:
        idle0, total0 = _cpu_times()
        time.sleep(interval)
        idle1, total1 = _cpu_times()
    except (OSError, ValueError, IndexError):
        return False
    if total1 <= total0:
        return False
    online = os.cpu_count() or 1  # /proc/stat sums over every online CPU
    idle = online * (idle1 - idle0) / (total1 - total0)
    busy_elsewhere = online - idle
    return busy_elsewhere <= 0.5 and idle >= cores - 0.5


def blas_threads_for(large: bool) -> AbstractContextManager[None]:
    """The BLAS threads of one heavy call: :func:`one_blas_thread`, unless ``large`` and the machine idle.

    Large work on an idle machine (every other core free, :func:`machine_is_idle`, 50 ms to
    tell) keeps the caller's BLAS threads, which make it faster there; beside another busy
    program they would spin against it, so then, and for small work always, BLAS gets one thread.

    Examples
    --------
    >>> import numpy as np
    >>> with blas_threads_for(large=False):  # one BLAS thread inside
    ...     product = np.ones((2, 2)) @ np.ones(2)
    >>> product.tolist()
    [2.0, 2.0]
    """
    return nullcontext() if large and machine_is_idle() else one_blas_thread()
