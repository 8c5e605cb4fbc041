"""Whether the machine's other cores are idle right now: when BLAS threads may be used without harm.

OpenBLAS threads spin while they wait for a core, so beside another busy program a call running
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
import time

__all__ = ["machine_is_idle", "usable_cores"]


def usable_cores() -> float:
    """Cores this process may use: its CPU affinity, capped by a cgroup (v2) CPU quota if any.

    Examples
    --------
    >>> usable_cores() >= 1
    True
    """
    try:
        cores: float = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = float(os.cpu_count() or 1)
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
