"""Platform details kept out of the algorithms: how many worker threads, and giving memory back.

* :func:`default_workers` — the threads the package's own parallel loops use (the eigensolver's
  slices, the heat method's blocks): the cores this process may run on, at most 2, since each
  worker holds a sparse factorisation and its work space.
* :func:`return_freed_memory` — after a large factorisation is freed, glibc keeps its heap pages;
  ``malloc_trim(0)`` hands them back to the system, so the resident size of a notebook kernel
  falls back. On other C libraries (macOS, Windows, musl) it does nothing.
"""

from __future__ import annotations

import ctypes
import os

__all__ = ["default_workers", "return_freed_memory"]


def default_workers() -> int:
    """Threads for the package's parallel loops: the usable cores, at most 2 (each holds a factorisation).

    Examples
    --------
    >>> default_workers() in (1, 2)
    True
    """
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    return max(1, min(2, cores))


def return_freed_memory() -> None:
    """Ask glibc to hand freed heap pages back to the system (a factorisation leaves many behind).

    Does nothing where the C library is not glibc.

    Examples
    --------
    >>> return_freed_memory()  # never fails, whatever the platform
    """
    try:
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):  # not glibc (macOS, Windows, musl): nothing to do
        pass
