"""Regularized PCA, spectral MDS, fast classical scaling and match run BLAS on one thread and restore the caller's count.

OpenBLAS threads spin while they wait for a core, so beside another busy program these calls
took 4-20x the CPU time they need (benchmarks/busy.py). They now hold
:func:`~lbo_notebooks.spectral._engine.threads.one_blas_thread` (match's nearest-neighbour search runs its
own worker threads instead), which must leave the caller's process-wide count as it found it and
must not touch a count the user set by an environment variable. (rPCA keeps the caller's threads
on a large mesh when the rest of the machine is idle, where they make it faster.) The set-up is that of
test_threads.py: the caller's count is 2, set by no environment variable.
"""

from __future__ import annotations

import numpy as np
import pytest

import lbo_notebooks as lbo
from lbo_notebooks import shapes
from lbo_notebooks.analyses import _fast_classical_scaling as fast_scaling
from lbo_notebooks.analyses import _functional_maps as functional_maps
from lbo_notebooks.analyses import _mds as mds
from lbo_notebooks.analyses import _rpca as rpca
from lbo_notebooks.spectral._engine import threads as engine_threads
from tests.test_threads import blas_threads, caller_threads  # noqa: F401 - caller_threads is a fixture


def _recording(module, name: str, seen: list, monkeypatch) -> None:
    original = getattr(module, name)

    def recorded(*args, **kwargs):
        seen.append(blas_threads())
        return original(*args, **kwargs)

    monkeypatch.setattr(module, name, recorded)


@pytest.fixture(scope="module")
def sphere():
    return shapes.bumpy_sphere(3)  # 642 vertices: above the dense limit, so rPCA takes the sparse path


def test_heavy_calls_run_one_blas_thread_and_restore_the_callers_count(sphere, caller_threads, monkeypatch):  # noqa: F811
    seen: list = []
    _recording(rpca, "rayleigh_ritz", seen, monkeypatch)
    _recording(mds, "_scaling_with_fields", seen, monkeypatch)
    _recording(fast_scaling, "scaling_in_span", seen, monkeypatch)
    _recording(functional_maps, "_nearest_rows", seen, monkeypatch)
    W, A = lbo.stiffness_matrix(sphere), lbo.mass_matrix(sphere)
    X = np.hstack([sphere.vertices, sphere.vertices**2])
    solver = rpca.RegularizedPCA(X, W, A, center=True)
    solver.solve(20, beta=0.5)
    solver.solve(20, mu=0.0)
    assert blas_threads() == caller_threads
    mds.spectral_mds(sphere, n_samples=40, k=30)
    assert blas_threads() == caller_threads
    lbo.fast_classical_scaling(sphere, n_samples=30)
    assert blas_threads() == caller_threads
    lbo.match(sphere, sphere, k=10, k_final=20)
    assert blas_threads() == caller_threads
    assert len(seen) >= 4, seen
    assert all(counts == [1] * len(counts) for counts in seen), seen


def test_a_count_the_user_set_is_left_alone(sphere, caller_threads, monkeypatch):  # noqa: F811
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "2")
    seen: list = []
    _recording(mds, "_scaling_with_fields", seen, monkeypatch)
    mds.spectral_mds(sphere, n_samples=40, k=30)
    assert seen == [caller_threads]
    assert blas_threads() == caller_threads


def test_rpca_keeps_blas_threads_on_a_large_mesh_only_when_the_machine_is_idle(sphere, caller_threads, monkeypatch):  # noqa: F811
    seen: list = []
    _recording(rpca, "rayleigh_ritz", seen, monkeypatch)
    W, A = lbo.stiffness_matrix(sphere), lbo.mass_matrix(sphere)
    solver = rpca.RegularizedPCA(np.hstack([sphere.vertices, sphere.vertices**2]), W, A, center=True)
    reference = solver.solve(20, beta=0.5)
    monkeypatch.setattr(rpca, "LARGE_MESH", 100)  # as if the sphere were large
    for idle, inside in ((True, caller_threads), (False, [1] * len(caller_threads))):
        monkeypatch.setattr(engine_threads, "machine_is_idle", lambda idle=idle: idle)
        seen.clear()
        result = solver.solve(20, beta=0.5)
        assert seen and all(counts == inside for counts in seen), (idle, seen)
        assert blas_threads() == caller_threads
        scale = np.abs(reference.values).max()  # one eigenvalue is round-off zero: compare on the spectrum's scale
        np.testing.assert_allclose(result.values, reference.values, rtol=1e-9, atol=1e-12 * scale)


def test_machine_is_idle_reads_the_cpu_counters(monkeypatch):
    # Through the documented input, /proc/stat's first line (user nice system idle iowait irq
    # softirq steal ...), read twice: idle + iowait of the total jiffies is the idle share.
    import builtins
    import io

    idle_cores = engine_threads

    real_open, lines = builtins.open, []

    def proc_stat(path, *args, **kwargs):
        if path != "/proc/stat":
            return real_open(path, *args, **kwargs)
        if not lines:
            raise OSError("no /proc/stat")
        return io.StringIO(lines.pop(0) + "\ncpu0 1 2 3 4 5 6 7 8 0 0\n")

    monkeypatch.setattr(idle_cores, "usable_cores", lambda: 2.0)
    monkeypatch.setattr(idle_cores.os, "cpu_count", lambda: 2)
    monkeypatch.setattr(idle_cores, "open", proc_stat, raising=False)  # the module's open: /proc/stat
    lines[:] = ["cpu  800 0 100 60 40 0 0 0 7 0", "cpu  800 0 100 210 90 0 0 0 9 0"]  # 200 of 200 jiffies idle
    assert idle_cores.machine_is_idle(0.0)  # both cores idle
    lines[:] = ["cpu  800 0 100 60 40 0 0 0 0 0", "cpu  850 0 150 110 40 0 0 0 0 0"]  # 50 of 150 idle
    assert not idle_cores.machine_is_idle(0.0)  # another program holds a core
    lines[:] = []
    assert not idle_cores.machine_is_idle(0.0)  # unreadable: the safe side
    lines[:] = ["cpu  800 0 100 60 40 0 0 0 0 0"]
    assert not idle_cores.machine_is_idle(0.0)  # readable once, then not: the safe side
    lines[:] = ["cpu  800 0 100 60 40 0 0 0 0 0", "cpu  800 0 100 60 40 0 0 0 0 0"]
    assert not idle_cores.machine_is_idle(0.0)  # no time passed on the counters
    lines[:] = ["cpu  800 0 100 60 40 0 0 0 7 0", "cpu  800 0 100 210 90 0 0 0 9 0"]
    monkeypatch.setattr(idle_cores, "usable_cores", lambda: 1.0)
    assert not idle_cores.machine_is_idle(0.0)  # one core: nothing to share
    monkeypatch.undo()
    assert idle_cores.usable_cores() >= 1
