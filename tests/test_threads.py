"""eigenbasis is safe to call from threads and leaves the caller's BLAS thread count alone.

The BLAS thread count is process-wide. The tests set the caller's count the way a program that
set it once would leave it: from a thread that has ended (so threadpoolctl holds no limit), with
the environment variables of :mod:`lbo_notebooks.spectral._engine.threads` unset, so that the library
limits BLAS while its worker threads run and must restore the caller's count afterwards.
"""

from __future__ import annotations

import contextlib
import threading
import time

import numpy as np
import pytest
from threadpoolctl import threadpool_info, threadpool_limits

import lbo_notebooks as lbo
from lbo_notebooks import shapes
from lbo_notebooks.spectral._engine import eigensolver
from lbo_notebooks.spectral._engine.threads import ENVIRONMENT

K = 120  # with 642 vertices: the slicing path, whose worker threads run with one BLAS thread


def blas_threads() -> list[int]:
    return [pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"]


def set_blas_threads(n: int) -> None:
    """Set the process's BLAS thread count, leaving no threadpoolctl limit held."""
    setter = threading.Thread(target=lambda: threadpool_limits(limits=n, user_api="blas"))
    setter.start()
    setter.join()


@pytest.fixture(scope="module")
def mesh():
    return shapes.bumpy_sphere(3)


@pytest.fixture
def caller_threads(monkeypatch):
    """The caller runs BLAS on 2 threads, set by no environment variable."""
    for name in ENVIRONMENT:
        monkeypatch.delenv(name, raising=False)
    before = blas_threads()
    set_blas_threads(2)
    caller = blas_threads()  # a BLAS built without threads (loaded by another test's library) stays at 1
    assert 2 in caller, caller
    yield caller
    set_blas_threads(max(before))


def concurrently(function, n_threads: int = 4) -> list:
    out: list = [None] * n_threads
    errors: list = []

    def run(i: int) -> None:
        try:
            out[i] = function()
        except BaseException as error:  # reported below
            errors.append(error)

    threads = [threading.Thread(target=run, args=(i,)) for i in range(n_threads)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    return out


def hold_inside_stitch(monkeypatch, n_threads: int, seen: list) -> None:
    """Make the calls meet inside their BLAS-limited regions and leave in the order they came in.

    That order broke a per-call ``threadpool_limits``: the first call recorded the caller's count,
    the others the limit it had set, and the last one out restored the limit for good. The hold
    sits at the end of slice_eigsh's region (its sets placed and stitched), inside the public
    :func:`~lbo_notebooks.spectral._engine.threads.one_blas_thread` it holds.
    """
    region = eigensolver.one_blas_thread
    lock, arrived = threading.Lock(), []
    all_in = threading.Barrier(n_threads)

    @contextlib.contextmanager
    def held():
        with region():
            yield
            with lock:
                rank = len(arrived)
                arrived.append(rank)
            all_in.wait(timeout=120)
            seen.append(blas_threads())
            time.sleep(0.05 * rank)

    monkeypatch.setattr(eigensolver, "one_blas_thread", held)


def test_four_threads_give_the_serial_result_and_keep_the_callers_blas_threads(mesh, caller_threads, monkeypatch):
    serial = lbo.eigenbasis(mesh, K)
    assert blas_threads() == caller_threads
    for repetition in range(3):
        seen: list = []
        if repetition == 0:
            hold_inside_stitch(monkeypatch, 4, seen)
        else:
            monkeypatch.undo()
            for name in ENVIRONMENT:
                monkeypatch.delenv(name, raising=False)
        for spectrum in concurrently(lambda: lbo.eigenbasis(mesh, K)):
            np.testing.assert_allclose(spectrum.values, serial.values, rtol=1e-12, atol=1e-12 * serial.values[-1])
            np.testing.assert_allclose(spectrum.vectors, serial.vectors, rtol=0, atol=1e-8 * np.abs(serial.vectors).max())
        assert blas_threads() == caller_threads, repetition
        # Inside the worker threads' regions BLAS ran on one thread.
        assert all(counts == [1] * len(counts) for counts in seen), seen


def test_a_thread_count_set_by_an_environment_variable_is_not_touched(caller_threads, monkeypatch):
    from lbo_notebooks.spectral._engine.threads import one_blas_thread

    with one_blas_thread():  # nobody chose the count: one thread inside
        assert blas_threads() == [1] * len(caller_threads)
    assert blas_threads() == caller_threads
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "2")
    with one_blas_thread():
        assert blas_threads() == caller_threads
    assert blas_threads() == caller_threads


def test_a_threadpoolctl_limit_the_user_holds_is_kept(mesh, caller_threads):
    with threadpool_limits(limits=1, user_api="blas"):
        concurrently(lambda: lbo.eigenbasis(mesh, K), n_threads=2)
        assert blas_threads() == [1] * len(caller_threads)
    assert blas_threads() == caller_threads


def test_measure_cost_and_the_heat_method_restore_the_blas_threads(caller_threads):
    sphere = shapes.icosphere(2)
    concurrently(lambda: lbo.analyses.measure_cost(np.linalg.eigh, np.eye(50)), n_threads=4)
    assert blas_threads() == caller_threads
    concurrently(lambda: lbo.analyses.geodesic_distances(sphere, np.arange(20)), n_threads=3)
    assert blas_threads() == caller_threads


def test_a_forked_child_can_still_limit_its_blas_threads(caller_threads):
    """The owner thread does not survive os.fork: the child must start its own, not wait forever."""
    import multiprocessing

    from lbo_notebooks.spectral._engine.threads import one_blas_thread

    with one_blas_thread():  # the parent's owner thread exists now
        pass
    context = multiprocessing.get_context("fork")
    with context.Pool(1) as pool:
        result = pool.apply_async(_limited_in_child)
        assert result.get(timeout=60) == "done"


def _limited_in_child() -> str:
    from lbo_notebooks.spectral._engine.threads import one_blas_thread

    with one_blas_thread():
        pass
    return "done"


def _blas_in_a_measured_child() -> dict:
    """In a measured (forked) child: the idle CPU time after a limit is set, and the counts inside and after it."""
    from lbo_notebooks.spectral._engine.threads import one_blas_thread

    with one_blas_thread():
        cpu = time.process_time()
        time.sleep(0.1)
        idle = time.process_time() - cpu
        inside = blas_threads()
    return {"idle_cpu": idle, "inside": inside, "after": blas_threads()}


@pytest.mark.parametrize("timed", [False, pytest.param(True, marks=pytest.mark.timing)], ids=["counts", "idle-cpu"])
def test_a_measured_child_has_idle_blas_threads_that_the_library_can_still_limit(caller_threads, timed):
    """OpenBLAS rebuilds its pool in a forked child at the first change of its count, and the new
    threads spin for about 0.1 s: on two cores 0.2 s of CPU during this 0.1 s sleep, which slowed the
    first measured call by 10-20%. The benchmarks' measure_in_fresh_process rebuilds the pools before timing, from
    the thread that owns the setting, so the library's limit still takes effect in the child."""
    from .test_cost import benchmark_measure

    child = benchmark_measure().measure_in_fresh_process(_blas_in_a_measured_child)["result"]
    if timed:  # a CPU time: opt-in (LBO_TIMING_TESTS=1, tests/conftest.py)
        assert child["idle_cpu"] < 0.03, child
    assert set(child["inside"]) == {1}, child
    assert child["after"] == caller_threads, child
    assert blas_threads() == caller_threads  # the parent is untouched
