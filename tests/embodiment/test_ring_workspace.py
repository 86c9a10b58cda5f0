"""The KUKA iiwa performs in its whole workspace: the disk cut by its reach ring (issue 22), not the 0.17 m disk it
had before (core/workspace.py, arms/fit.py: fit_workspace)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from l2p_bullet.arms import KUKA_IIWA, fit_scene, fit_workspace
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.embodiment.execute import check_waypoints
from l2p_bullet.errors import PathError, SceneError
from l2p_bullet.pipeline import perform

BASE = np.array(KUKA_IIWA.mount[:2])


def _scene(a: tuple[float, float], b: tuple[float, float]) -> Scene:
    return Scene([SceneObject("A", "red", 0.04, a, 0.3), SceneObject("B", "green", 0.04, b, 0.1)]).validate()


def _mover_track(run) -> np.ndarray:
    frames = json.loads((run / "trajectory.json").read_text())["frames"]
    return np.array([f["poses"]["A"][:2] for f in frames])


@pytest.mark.parametrize("sentence, a, b", [
    ("move A around B", (0.0, 0.21), (0.0, 0.12)),  # A 0.21 m from the centre: outside the old 0.17 m disk
    ("move A away from B", (-0.03, -0.2), (0.0, -0.13)),
])
def test_a_block_outside_the_old_disk_but_inside_the_ring_is_performed(sentence, a, b, tmp_path):
    scene = _scene(a, b)
    assert np.hypot(*a) > fit_workspace(scene.workspace, KUKA_IIWA).inner_radius
    r = perform(sentence, scene, out_dir=tmp_path / "run", render=False, seed=3, arm="kuka-iiwa")
    assert r.verdict["success"], r.verdict
    assert r.anchor_displacement_m < 0.001
    ws = fit_workspace(scene.workspace, KUKA_IIWA)
    assert ws.contains(_mover_track(tmp_path / "run"), margin=-0.002).all()  # the block stayed where the arm reaches


def test_blocks_either_side_of_the_rings_hole_are_brought_together_round_it(tmp_path):
    # A and B 0.44 m from the base, either side of its axis: the straight line between them passes 0.42 m from the
    # base, inside the ring's hole (0.43 m), so the planner must go round it and the arm must follow
    a, b = (-0.18, 0.13), (-0.18, -0.13)
    ws = fit_workspace(_scene(a, b).workspace, KUKA_IIWA)
    assert not ws.segments_inside(np.array(a), np.array([b]))[0]
    r = perform("move A closer to B", _scene(a, b), out_dir=tmp_path / "run", render=False, seed=3, arm="kuka-iiwa")
    assert r.verdict["success"], r.verdict
    assert r.anchor_displacement_m < 0.001
    track = _mover_track(tmp_path / "run")
    assert np.hypot(*(track - BASE).T).min() >= ws.ring[2] - 0.002  # never into the hole (2 mm of tracking lag)
    plan = np.array(json.loads((tmp_path / "run" / "plan.json").read_text())["waypoints"])[:, :2]
    assert ws.path_inside(plan) is None


def test_a_block_nearer_the_base_than_the_ring_is_refused_naming_the_arm(tmp_path):
    with pytest.raises(SceneError) as e:
        perform("move A around B", _scene((-0.22, 0.02), (0.0, 0.0)), out_dir=tmp_path / "run", render=False,
                arm="kuka-iiwa")
    msg = str(e.value)
    assert "\n" not in msg and 'the arm "kuka-iiwa"' in msg and "0.43-0.77 m from its base" in msg
    assert not (tmp_path / "run").exists()


def test_a_path_through_the_hole_is_refused_before_anything_moves():
    scene = fit_scene(_scene((-0.18, 0.13), (0.05, -0.05)), KUKA_IIWA)
    with pytest.raises(PathError, match="between waypoints 0 and 1"):
        check_waypoints(scene, "A", np.array([[-0.18, 0.13, 0.3], [-0.18, -0.13, 0.3]]))
    check_waypoints(scene, "A", np.array([[-0.18, 0.13, 0.3], [0.0, 0.0, 0.3], [-0.18, -0.13, 0.3]]))


def test_a_push_near_the_rings_hole_is_refused_up_front_not_half_way(tmp_path):
    # the pushing hand stands behind the block: along the hole's edge it would need a point the arm does not reach
    # (before this check such pushes stopped half-way with a ReachError)
    from l2p_bullet.errors import InfeasibleError

    with pytest.raises(InfeasibleError) as e:
        perform("push A closer to B", _scene((-0.18, 0.13), (-0.18, -0.13)), out_dir=tmp_path / "run", render=False,
                seed=3, arm="kuka-iiwa")
    assert e.value.check == "push" and 'the arm "kuka-iiwa"' in str(e.value) and "\n" not in str(e.value)


def test_a_replayed_motion_is_pulled_out_of_the_rings_hole():
    from l2p_bullet.embodiment.retarget import retarget

    scene = fit_scene(_scene((-0.06, 0.0), (-0.12, 0.0)), KUKA_IIWA)
    t = np.linspace(0.0, 2 * np.pi, 80)
    demo = np.column_stack([0.45 * np.cos(t), 0.45 * np.sin(t), t])  # round the anchor at 3 sides (0.15 m blocks)
    out = retarget(demo, np.zeros(3), 0.15, scene, "A", "B")
    assert out.clamped > 0  # the circle (0.12 m round B) passes through the hole (x < -0.17 on the axis)
    assert scene.workspace.path_inside(out.path) is None


def test_the_pushing_hand_stands_behind_the_block_and_goes_round_over_it_at_a_corner():
    from l2p_bullet.embodiment.manners import hand_points

    leg1 = np.column_stack([np.linspace(0.0, 0.1, 21), np.zeros(21)])
    leg2 = np.column_stack([np.full(20, 0.1), np.linspace(0.005, 0.1, 20)])
    hands = hand_points(np.vstack([leg1, leg2]), 0.04, 0.05)
    np.testing.assert_allclose(hands[0], [-0.05, 0.0], atol=1e-9)  # behind the block, opposite the push
    np.testing.assert_allclose(hands[40], [0.1, 0.05], atol=1e-9)  # the path's end: behind it along the last step
    # going round at the corner: a straight line over the block from the -x side to the -y side
    chord = hands[41:]
    assert len(chord) == 16 and chord[0][0] < 0.1 and chord[-1][1] < 0.0


@pytest.mark.parametrize("ends, refused", [
    (((-0.24, 0.0), (-0.10, 0.0)), True),  # pushed away from the Panda's base: its hand stands on the base side
    (((-0.10, 0.0), (-0.24, 0.0)), False),  # pushed towards it: the hand stands on the far side
])
def test_a_push_is_refused_only_when_its_hand_would_stand_in_the_rings_hole(ends, refused):
    # the Panda's ring (0.27 m from its base at x = -0.53) cuts its 0.35 m workspace: a block 0.29 m from the base
    # can be pushed with the hand beyond it, not with the hand between it and the base (the first bound refused both)
    from l2p_bullet.arms import PANDA
    from l2p_bullet.embodiment.manners import push_refusal

    scene = fit_scene(_scene(ends[0], (0.1, 0.2)), PANDA)
    assert scene.workspace.ring is not None
    path = np.array([[*ends[0], 0.0], [*ends[1], 0.0]])
    why = push_refusal(scene, "A", path, PANDA)
    assert (why is not None and 'the arm "panda"' in why) == refused, why
