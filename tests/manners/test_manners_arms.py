"""Manners compose with the other arms (issues 22 and 23): a carry by the xArm6 lifts the block and sets it
down where planned, a push by the KUKA moves it without a grasp, and the push's "fingers stay closed" check
reads a width in metres on an arm whose fingers turn (the xArm's linkage is in radians)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.pipeline import perform

SCENE = Scene([SceneObject("A", "red", 0.04, (0.08, -0.07), 0.2), SceneObject("B", "green", 0.04, (0.0, 0.01), 0.0)])


def _run(sentence, arm, tmp_path):
    out = tmp_path / arm
    r = perform(sentence, SCENE, out_dir=out, render=False, seed=3, arm=arm)
    return r, json.loads((out / "trajectory.json").read_text()), json.loads((out / "summary.json").read_text())


@pytest.mark.slow
def test_the_xarm_carries_the_block_over_the_table_and_sets_it_down_where_planned(tmp_path):
    r, traj, summary = _run("carry A past B", "xarm6", tmp_path)
    assert r.success, r.verdict
    assert summary["arm"] == "xarm6" and summary["manner"] == "carry"
    z = np.array([f["poses"]["A"][2] for f in traj["frames"]]) - 0.02
    assert z.max() >= 0.02 and abs(z[-1]) < 0.003
    assert r.final_error_m < 0.002 and r.anchor_displacement_m < 0.001


@pytest.mark.slow
def test_a_push_by_another_arm_never_grasps_and_keeps_its_fingers_closed(tmp_path):
    for arm in ("kuka-iiwa", "xarm6"):
        r, traj, summary = _run("push A next to B", arm, tmp_path)
        frames = traj["frames"]
        assert summary["arm"] == arm and all(f["grasped"] is None for f in frames)
        assert max(f["gripper"]["opening_m"] for f in frames) <= 0.001  # metres, for fingers that slide or turn
        assert r.verdict["manner"]["success"], r.verdict["manner"]
        assert r.anchor_displacement_m < 0.001
        moved = np.hypot(*(np.array(frames[-1]["poses"]["A"][:2]) - frames[0]["poses"]["A"][:2]))
        assert moved > 0.02  # the hand pushed it, by contact alone


@pytest.mark.slow
def test_a_carried_plan_replays_as_a_carry_and_a_chain_keeps_each_clause_manner(tmp_path):
    """replay PLAN.json does what the plan's sentence said: a carried path (which may cross blocks) is carried
    again, not slid; a chain's replay keeps each clause's manner."""
    from click.testing import CliRunner

    from l2p_bullet.cli import main

    _run("carry A past B", "panda", tmp_path)
    res = CliRunner().invoke(main, ["replay", str(tmp_path / "panda" / "plan.json"), "--no-render",
                                    "--out", str(tmp_path / "again")])
    assert res.exit_code == 0, res.output
    summary = json.loads((tmp_path / "again" / "summary.json").read_text())
    assert summary["manner"] == "carry" and summary["execution"]["grasp"]["lift_m"] >= 0.02
    res = CliRunner().invoke(main, ["plan", "move A closer to B, then carry A away from B", "--no-plot",
                                    "--out", str(tmp_path / "chain")])
    assert res.exit_code == 0, res.output
    res = CliRunner().invoke(main, ["replay", str(tmp_path / "chain" / "plan.json"), "--no-render",
                                    "--out", str(tmp_path / "chain-again")])
    assert res.exit_code == 0, res.output
    clauses = json.loads((tmp_path / "chain-again" / "summary.json").read_text())["clauses"]
    assert [c.get("manner", "slide") for c in clauses] == ["slide", "carry"]
