"""The manners of motion in the simulator (issue 23): a carry lifts the block and sets it down where planned, a
push moves it along the plan with no grasp at all, the anchor stays where it was, a slide's files are as before,
and a push recorded twice is byte-identical."""

from __future__ import annotations

import json

import numpy as np
import pytest

from l2p_bullet.core.scene import Scene, SceneObject, default_scene
from l2p_bullet.embodiment.motion import polyline_distance
from l2p_bullet.pipeline import perform

SCENE = Scene([SceneObject("A", "red", 0.04, (0.08, -0.07), 0.2), SceneObject("B", "green", 0.04, (0.0, 0.01), 0.0)])


def _run(sentence, tmp_path, name, scene=SCENE):
    r = perform(sentence, scene, out_dir=tmp_path / name, render=False, seed=3)
    traj = json.loads((tmp_path / name / "trajectory.json").read_text())
    summary = json.loads((tmp_path / name / "summary.json").read_text())
    return r, traj, summary


@pytest.mark.slow
def test_carry_lifts_the_block_and_sets_it_down_where_planned(tmp_path):
    r, traj, summary = _run("carry A past B", tmp_path, "carry")
    assert r.success, r.verdict
    assert traj["manner"] == "carry" and summary["manner"] == "carry"
    assert r.verdict["manner"]["success"] and r.verdict["manner"]["judge"] == "manner"
    z = np.array([f["poses"]["A"][2] for f in traj["frames"]]) - 0.02
    assert z.max() >= 0.02 and z.max() == pytest.approx(summary["grasp"]["lift_m"], abs=0.002)  # as planned
    assert abs(z[-1]) < 0.003  # set down on the table
    assert r.final_error_m < 0.002 and r.anchor_displacement_m < 0.001
    held = [f["gripper"]["holding"] for f in traj["frames"]]
    assert "A" in held and held[0] is None and held[-1] is None


@pytest.mark.slow
def test_push_moves_the_block_along_the_plan_without_any_grasp(tmp_path):
    r, traj, summary = _run("push A past B", tmp_path, "push")
    assert r.success, r.verdict
    frames = traj["frames"]
    assert traj["manner"] == "push" and all(f["grasped"] is None for f in frames)
    assert all(f["gripper"]["opening_m"] <= 0.001 for f in frames)  # the fingers stay closed
    touching = [f["gripper"]["contact"] for f in frames if f["gripper"]["contact"] is not None]
    assert len(touching) > len(frames) / 4  # the hand pushed the block, by contact
    xy = np.array([f["poses"]["A"][:2] for f in frames])
    assert polyline_distance(xy, r.plan.path[:, :2]).max() < 0.02  # within half a side of the plan
    assert r.final_error_m < 0.02
    assert r.anchor_displacement_m < 0.001
    assert summary["grasp"]["push"]["stopped"] == "end"
    assert summary["execution"]["constraint_removed"] is True


@pytest.mark.slow
def test_a_push_scene_recorded_twice_is_byte_identical(tmp_path):
    _run("push A next to B", tmp_path, "one")
    _run("push A next to B", tmp_path, "two")
    assert (tmp_path / "one" / "trajectory.json").read_bytes() == (tmp_path / "two" / "trajectory.json").read_bytes()


def test_a_slide_records_no_manner(tmp_path):
    r, traj, summary = _run("move A next to B", tmp_path, "slide", default_scene())
    assert "manner" not in traj and "manner" not in summary and "manner" not in r.verdict
    assert all("gripper" not in f for f in traj["frames"])


@pytest.mark.slow
def test_a_carried_path_may_cross_another_block_a_slid_one_may_not():
    from l2p_bullet.embodiment.execute import execute_path
    from l2p_bullet.errors import PathError

    scene = Scene([SceneObject("A", "red", 0.04, (0.10, 0.0), 0.0), SceneObject("B", "green", 0.05, (0.0, 0.0), 0.0)])
    path = np.array([[0.10, 0.0, 0.0], [-0.10, 0.0, 0.0]])  # straight through B
    with pytest.raises(PathError, match='runs into "B"'):
        execute_path(scene, "A", path, out_dir=None, render=None)
    ex = execute_path(scene, "A", path, out_dir=None, render=None, manner="carry")
    lift = ex.stats["grasp"]["lift_m"]
    assert lift == pytest.approx(0.05 + 0.02)  # B's top, and 2 cm to spare
    assert ex.max_lift_m == pytest.approx(lift, abs=0.002)
    end = ex.frames[-1]["poses"]["A"]
    assert np.hypot(end[0] + 0.10, end[1]) < 0.002 and abs(end[2] - 0.02) < 0.003
    assert ex.displacements_m["B"] < 0.001  # it touched nothing on the way
    with pytest.raises(PathError, match='sets it down on "B"'):
        execute_path(scene, "A", np.array([[0.10, 0.0, 0.0], [0.01, 0.0, 0.0]]), out_dir=None, render=None,
                     manner="carry")
