"""benchmarks/forced_refusals.py: a refused chain is forced by its start where no clause before the refused one moves
its blocks and the clause is refused on the start scene even carried; one whose blocks an earlier clause moved is
not."""

from __future__ import annotations

from pathlib import Path

import pytest
from benchmark_scripts import run_folder, script


def _module():
    return script("forced_refusals")


def _run(folder: Path, rows: list[tuple]) -> Path:
    return run_folder(folder, "scene_id text, sentence text, error_type text, error text", rows)


def test_a_refusal_the_start_forces_is_told_from_one_an_earlier_clause_could_change(tmp_path, capsys):
    """chain/25572/5b: "move B around C" at clause 1, the rim alone leaves 188 deg (forced); the same clause said
    after a clause that moves B is not forced (B's start may change); a chain performed is not listed."""
    refusal = 'clause {k} ("move B around C") cannot be planned (blocked-around): no way round "C" for "B"'
    run = _run(tmp_path / "run", [
        ("chain/25572/5b", "move B around C, then move A past D", "refused", refusal.format(k=1)),
        ("chain/25572/5b", "move B past D, then move B around C", "refused", refusal.format(k=2)),
        ("chain/25573/5b", "move A past B", None, None),
    ])
    assert _module().main([str(run)]) == 0
    out = capsys.readouterr().out
    assert "| chain/25572/5b | 1 | blocked-around | move B around C | - | carried, refused on the start scene | " \
           "**forced** |" in out
    assert "| chain/25572/5b | 2 | blocked-around | move B around C | B | carried, refused on the start scene | - |" \
        in out
    assert "forced by the start: 1 of 2 refused" in out


def test_a_folder_without_results_is_a_clear_error(tmp_path):
    with pytest.raises(SystemExit, match="results.sqlite does not exist"):
        _module().main([str(tmp_path)])
