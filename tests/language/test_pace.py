"""A manner adverb changes how the arm moves: "slowly" takes longer, "quickly" less, the block still ends
where planned, and the run records the pace (summary.json's ``command``, a chain's ``segments``)."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.embodiment.smoothing import PACES, Limits, pace

pytestmark = pytest.mark.slow


def _run(tmp_path, sentence: str, name: str) -> dict:
    out = tmp_path / name
    r = CliRunner().invoke(main, ["perform", sentence, "--no-render", "--quiet", "--out", str(out)])
    assert r.exit_code == 0, r.output
    return json.loads((out / "summary.json").read_text())


def test_slowly_takes_longer_and_quickly_less(tmp_path):
    normal = _run(tmp_path, "move A past B", "normal")
    slow = _run(tmp_path, "slowly move A past B", "slow")
    fast = _run(tmp_path, "move A past B quickly, please", "fast")
    assert normal["success"] and slow["success"] and fast["success"]
    assert "pace" not in normal["command"]
    assert (slow["command"]["pace"], fast["command"]["pace"]) == ("slow", "fast")
    assert slow["simulated_s"] > 1.4 * normal["simulated_s"] > 1.4 * fast["simulated_s"]
    for s in (slow, fast):  # the block still ends where the plan said
        assert s["final_error_m"] < 0.003


def test_a_chain_records_each_clause_pace(tmp_path):
    out = tmp_path / "chain"
    r = CliRunner().invoke(main, ["perform", "gently move A next to B, then move it past B", "--no-render", "--quiet",
                                  "--out", str(out)])
    assert r.exit_code == 0, r.output
    segs = json.loads((out / "trajectory.json").read_text())["segments"]
    assert [s.get("pace") for s in segs] == ["gentle", None]


def test_the_normal_pace_leaves_every_limit_as_it_is():
    lim = Limits(0.1, 0.5, 5.0, 0.5)
    assert pace(None).apply(lim) is lim
    assert all(p.apply(lim).velocity <= 1.5 * lim.velocity for p in PACES.values())
    assert PACES["gentle"].apply(lim).acceleration < PACES["slow"].apply(lim).acceleration
