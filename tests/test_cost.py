"""lbo_notebooks.cost.recorded_benchmark: recorded results found from any working directory, a clear error when absent."""

from __future__ import annotations

import json

import pytest

from lbo_notebooks import cost


def test_recorded_results_are_found_from_the_package_not_the_working_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a notebook's or a user's directory: no relative path can work here
    recorded = cost.recorded_benchmark("mds")
    assert recorded == json.loads((cost.RESULTS / "mds.json").read_text())
    assert "scaling" in recorded and recorded["scaling"][0]["n"] > 0


def test_another_file_and_a_missing_one(tmp_path):
    mine = tmp_path / "mine.json"
    mine.write_text('{"scaling": []}')
    assert cost.recorded_benchmark("mine", mine) == {"scaling": []}
    with pytest.raises(FileNotFoundError, match="installed package does not include"):
        cost.recorded_benchmark("nothing", tmp_path / "nothing.json")
    with pytest.raises(FileNotFoundError, match="run benchmarks/never_run.py"):
        cost.recorded_benchmark("never_run")
    with pytest.raises(ValueError, match="benchmark's name"):
        cost.recorded_benchmark("../mds")
