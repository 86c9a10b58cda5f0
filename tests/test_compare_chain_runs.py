"""benchmarks/compare_chain_runs.py: two chain runs compared on the seeds both ran, from their results.sqlite alone."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from benchmark_scripts import run_folder, script


def _module():
    return script("compare_chain_runs")


def _run(folder: Path, rows: list[tuple]) -> Path:
    return run_folder(folder, "seed integer, completed integer, error_type text, error text, timings text", rows)


def test_seeds_both_ran_are_compared_and_a_worse_chain_says_why(tmp_path, capsys):
    timed = json.dumps({"forecast": 3.0, "forecast_alone": 2.0})
    old = _run(tmp_path / "old", [(1, 5, None, None, timed), (2, 2, None, None, timed), (3, 5, None, None, timed),
                                  (9, 5, None, None, timed)])
    refused = 'clause 1 ("move A around B") cannot be planned (room-around): no room'
    new = _run(tmp_path / "new", [(1, 5, None, None, timed), (2, 5, None, None, timed),
                                  (3, 0, "refused", refused, None)])
    assert _module().main([str(old), str(new)]) == 0
    out = capsys.readouterr().out
    assert "3 seeds both ran, 1-3" in out  # seed 9 ran only in the old run
    assert "| 100.0 % | 100.0 % | 66.7 % | 66.7 % | 66.7 % | 4.00 | 0 of 3 | 1.50 mean" in out
    assert "| 66.7 % | 66.7 % | 66.7 % | 66.7 % | 66.7 % | 3.33 | 1 of 3 (room-around 1) | 1.50 mean" in out
    assert "2 chains changed: 1 completed more, 1 fewer" in out
    assert "3: 5 -> 0  clause 1" in out


def test_a_folder_without_results_is_a_clear_error(tmp_path):
    with pytest.raises(SystemExit, match="results.sqlite does not exist"):
        _module().main([str(tmp_path), str(tmp_path)])
