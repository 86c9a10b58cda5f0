"""An extent changes how far the relation goes: "a bit" is the least the judge accepts (and a little
more), "far" goes on along the last heading, "right next to" draws the end towards the anchor; each is
still the action by its rule judge, and a run of it ends where it was planned."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main


def _plan(tmp_path, sentence: str) -> dict:
    out = tmp_path / sentence.replace(" ", "-")
    r = CliRunner().invoke(main, ["plan", sentence, "--json", "--no-plot", "--out", str(out)])
    assert r.exit_code == 0, r.output
    return {**json.loads(r.output), "plan": json.loads((out / "plan.json").read_text())}


def _length(plan: dict) -> float:
    import numpy as np

    xy = np.asarray(plan["path"], float)[:, :2]
    return float(np.hypot(*np.diff(xy, axis=0).T).sum())


@pytest.mark.parametrize("plain, little, far", [
    ("move A away from B", "move A a bit away from B", "move A far away from B"),
    ("move A past B", "move A just past B", "move A well past B"),
    ("move A closer to B", "move A slightly closer to B", "move A much closer to B"),
])
def test_little_is_shorter_and_far_longer_and_each_is_still_the_action(tmp_path, plain, little, far):
    p, lt, fr = (_plan(tmp_path, s) for s in (plain, little, far))
    assert p["success"] and lt["success"] and fr["success"], (p["reason"], lt["reason"], fr["reason"])
    assert _length(lt["plan"]) < _length(p["plan"]) <= _length(fr["plan"])
    assert lt["plan"]["extent"]["asked"] == "little" and fr["plan"]["extent"]["asked"] == "far"
    assert "extent" not in p["plan"]


def test_right_next_to_ends_closer_than_next_to(tmp_path):
    p, r = _plan(tmp_path, "move A next to B"), _plan(tmp_path, "move A right next to B")
    assert p["success"] and r["success"]
    def gap(d):
        return (float(d["reason"].split("ends ")[1].split(" blocks")[0]))
    assert gap(r) < gap(p)


@pytest.mark.slow
def test_far_away_runs_and_ends_farther(tmp_path):
    runs = {}
    for name, s in (("plain", "move A away from B"), ("far", "move A far away from B")):
        r = CliRunner().invoke(main, ["perform", s, "--no-render", "--quiet", "--out", str(tmp_path / name)])
        assert r.exit_code == 0, r.output
        runs[name] = json.loads((tmp_path / name / "summary.json").read_text())
    assert runs["far"]["success"] and runs["far"]["command"]["extent"] == "far"
    def grew(d):
        return (float(d["verdict"]["reason"].split("grew by ")[1].split(" blocks")[0]))
    assert grew(runs["far"]) > grew(runs["plain"]) + 0.5
