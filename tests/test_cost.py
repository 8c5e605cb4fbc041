"""Recorded benchmarks found from any working directory (a clear error when absent), and the
benchmarks' fresh-process measurements (benchmarks/_measure.py)."""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

from lbo_notebooks.analyses import _cost as cost

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"


def benchmark_measure():
    """benchmarks/_measure.py, loaded by path (benchmarks/ is not a package)."""
    spec = importlib.util.spec_from_file_location("benchmark_measure", BENCHMARKS / "_measure.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_recorded_results_are_found_from_the_package_not_the_working_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a notebook's or a user's directory: no relative path can work here
    recorded = cost.recorded_benchmark("mds")
    assert recorded == json.loads((cost.RESULTS / "mds.json").read_text())
    assert "scaling" in recorded and recorded["scaling"][0]["n"] > 0


def test_another_file_and_a_missing_one(tmp_path):
    mine = tmp_path / "mine.json"
    mine.write_text('{"scaling": []}')
    assert cost.recorded_benchmark("mine", mine) == {"scaling": []}
    with pytest.raises(FileNotFoundError, match="no recorded benchmark at .*nothing.json"):
        cost.recorded_benchmark("nothing", tmp_path / "nothing.json")
    with pytest.raises(FileNotFoundError, match="run benchmarks/never_run.py"):
        cost.recorded_benchmark("never_run")
    with pytest.raises(ValueError, match="benchmark's name"):
        cost.recorded_benchmark("../mds")


def _allocate(mib: int) -> int:
    import numpy as np

    block = np.ones(mib * 2**20 // 8)
    return int(block.size)


def test_fresh_process_measurements():
    measure = benchmark_measure()
    cost_ = measure.measure_in_fresh_process(_allocate, 64)
    assert cost_["result"] == 64 * 2**20 // 8
    # The peak holds the whole 64 MiB block. The growth is measured from the child's peak before the
    # call, and pages it inherited may be reclaimed under memory pressure in between (57 MiB was seen
    # on a loaded machine), so it is asked only to show most of the block.
    assert cost_["peak_rss_mib"] >= 64 and cost_["peak_rss_mib"] >= cost_["rss_growth_mib"] >= 64 / 2
    assert cost_["wall_seconds"] >= 0
    assert measure.least_wall_time(2, lambda: None) >= 0
    with pytest.raises(ValueError, match="runs must be a positive integer"):
        measure.least_wall_time(0, lambda: None)

