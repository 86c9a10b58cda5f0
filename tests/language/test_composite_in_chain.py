"""A composite stands anywhere in a chain: its steps run among the other clauses and the row is judged."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main

FOUR = Path(__file__).resolve().parents[2] / "examples" / "four_blocks.json"


@pytest.mark.slow
def test_a_row_then_a_clause(tmp_path):
    out = tmp_path / "run"
    r = CliRunner().invoke(main, ["perform", "make a row of A, B and C, then move D away from A", "--scene", str(FOUR),
                                  "--no-render", "--quiet", "--out", str(out)])
    assert r.exit_code == 0, r.output
    summary = json.loads((out / "summary.json").read_text())
    assert summary["row"]["success"] and summary["chain"]["completed"] == 3
    segs = json.loads((out / "trajectory.json").read_text())["segments"]
    assert [(s["mover"], s["action"]) for s in segs] == [("B", "next-to"), ("C", "next-to"), ("D", "away")]
