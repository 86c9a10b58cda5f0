"""An interrupted chain's summary.json says where it was: the stage and the clause (a one-clause run's
names its stage already), beside ``"failed_stage": "interrupted"`` that marks the folder replaceable."""

from __future__ import annotations

import json

import pytest
from test_chain import four_blocks

import l2p_bullet.chain.run as chain_run
from l2p_bullet.chain import perform_chain
from l2p_bullet.core.runfolder import run_folder_state


@pytest.mark.slow
def test_an_interrupted_chain_names_the_stage_and_the_clause(tmp_path, monkeypatch):
    calls = []
    real = chain_run.scene_now

    def ctrl_c_at_the_second_clause(scene, world):
        calls.append(1)
        if len(calls) == 2:  # the second clause starts: planned from the blocks' real poses
            raise KeyboardInterrupt
        return real(scene, world)

    monkeypatch.setattr(chain_run, "scene_now", ctrl_c_at_the_second_clause)
    out = tmp_path / "run"
    with pytest.raises(KeyboardInterrupt):
        perform_chain("move D around B; move A next to C", four_blocks(), out_dir=out, render=False)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["ok"] is False and summary["failed_stage"] == "interrupted", summary
    assert summary["interrupted_stage"] == "clause" and summary["interrupted_clause"] == 2, summary
    assert summary["chain"] is True and summary["sentence"] == "move D around B; move A next to C"
    assert "clause 1" in summary["timings_s"]
    assert run_folder_state(out) == "incomplete"
