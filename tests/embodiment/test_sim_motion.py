"""Geometry and timing of end-effector paths (no simulator): corners, ruckig limits, curvature, retargeting."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from l2p_bullet.core.geometry import polygons_overlap
from l2p_bullet.core.scene import GRIPPER_MARGIN, default_scene
from l2p_bullet.embodiment import motion
from l2p_bullet.embodiment.retarget import from_anchor_frame, retarget, to_anchor_frame
from l2p_bullet.embodiment.smoothing import Limits, curvature, time_parameterise
from l2p_bullet.errors import PathError

LIM = Limits(velocity=0.1, acceleration=0.5, jerk=5.0, lateral=0.5)
DT = 1.0 / 240


def _as4(p3: np.ndarray) -> np.ndarray:
    return np.column_stack([p3[:, :2], np.zeros(len(p3)), p3[:, 2]])


def test_timing_respects_limits_and_stays_on_the_path():
    theta = np.linspace(0, 1.5 * math.pi, 300)
    arc = np.column_stack([0.1 * np.cos(theta), 0.1 * np.sin(theta), np.zeros(300), np.zeros(300)])
    t = time_parameterise(arc, LIM, DT)
    v = np.diff(t.s) / DT
    a = np.diff(v) / DT
    assert v.max() <= t.velocity_limit * 1.001 and a.max() <= LIM.acceleration * 1.05
    assert t.s[0] == 0.0 and t.s[-1] == pytest.approx(0.1 * 1.5 * math.pi, rel=1e-3)
    assert v[-1] < 0.01 and v[0] < 0.01  # rest to rest
    # every sample lies on the circle: timing moves along the path, never off it
    assert np.allclose(np.hypot(t.poses[:, 0], t.poses[:, 1]), 0.1, atol=2e-5)


def test_a_path_on_ruckig_s_profile_border_is_timed():
    """1 cm plus one ulp at the slide's limits lies on the border between two of ruckig's profile shapes, where
    its search raised RuckigError (a 1 cm slide of a cube next to a bottle crashed the run)."""
    length = 0.01000000000000001
    line = np.column_stack([np.linspace(0.0, length, 5), np.zeros((5, 3))])
    t = time_parameterise(line, LIM, DT)
    assert t.s[0] == 0.0 and t.s[-1] == length and t.poses[-1, 0] == pytest.approx(length, abs=1e-12)
    assert 0.39 < t.s.size * DT < 0.42  # the 0.4 s of a 1 cm rest-to-rest move


def test_curvature_caps_the_speed():
    theta = np.linspace(0, math.pi, 400)
    r = 0.01  # v^2/r at 0.1 m/s would be 1 m/s^2, twice the lateral limit
    arc = np.column_stack([r * np.cos(theta), r * np.sin(theta), np.zeros(400), np.zeros(400)])
    assert np.median(curvature(arc)) == pytest.approx(1 / r, rel=0.02)
    t = time_parameterise(arc, LIM, DT)
    assert t.velocity_limit == pytest.approx(math.sqrt(LIM.lateral * r), rel=0.05)
    assert t.max_lateral_acc <= LIM.lateral * 1.05


def test_sharp_corners_stop_and_mild_corners_are_rounded():
    square = np.array([[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]], float)
    chunks = motion.slide_chunks(square)
    assert len(chunks) == 3  # a stop at each 90 degree corner
    for ch, (a, b) in zip(chunks, zip(square[:-1], square[1:], strict=True), strict=True):
        assert np.allclose(ch[0, :2], a[:2]) and np.allclose(ch[-1, :2], b[:2])
    mild = np.array([[0, 0, 0], [0.1, 0, 0], [0.2, 0.05, 0]], float)
    (ch,) = motion.slide_chunks(mild)
    dev = motion.polyline_distance(ch[:, :2], mild[:, :2]).max()
    assert 1e-4 < dev < 0.003  # rounded, by less than the tolerance the block must keep


def test_yaw_follows_the_path_and_turns_in_place_are_chunks():
    path = np.array([[0, 0, 0], [0.1, 0, 0.5], [0.1, 0, 1.2]], float)
    chunks = motion.slide_chunks(path)
    assert len(chunks) == 2
    assert chunks[0][-1, 2] == pytest.approx(0.5) and chunks[1][-1, 2] == pytest.approx(1.2)
    assert np.allclose(chunks[1][:, :2], [0.1, 0])  # the turn does not move the block


def test_grasp_yaw_keeps_the_wrist_in_range():
    from l2p_bullet.arms import reach
    from l2p_bullet.embodiment.execute import grasp_candidates

    base = (-0.53, 0.0)
    path = np.array([[0.0, 0.0, math.pi / 2 + 0.1], [0.1, 0.0, math.pi / 2 + 0.1]])
    off = grasp_candidates(path, [None], base)[0]  # the best candidate
    assert off % (math.pi / 2) == pytest.approx(0.0, abs=1e-9) or off % (math.pi / 2) == pytest.approx(math.pi / 2)
    wrist = reach.wrist_values(path[:, :2], path[:, 2], base) - off
    assert np.all(np.abs(wrist) <= math.pi / 4 + 0.2)
    odd = grasp_candidates(path, [math.pi / 2], base)  # the hand must point across the block
    assert odd and all(round(o / (math.pi / 2)) % 2 == 1 for o in odd)


def test_every_grasp_candidate_is_tried_before_the_grasp_is_refused():
    """A wrist that turns +-2 turns (a UR's) has more candidates than the best-centred three, and the approach from
    where the arm rests can leave its range on those three: the next one is tried (seed 220017 on a UR3e)."""
    from types import SimpleNamespace

    from l2p_bullet.arms import PANDA
    from l2p_bullet.core.scene import default_scene
    from l2p_bullet.embodiment.execute import choose_grasp_yaw, grasp_candidates
    from l2p_bullet.errors import ReachError

    ur = replace(PANDA, wrist_limit=2 * math.pi)
    path = np.array([[0.0, 0.0, 0.3], [0.05, 0.02, 0.5]])
    base = (-0.53, 0.0)
    candidates = grasp_candidates(path, [None], base, ur)
    assert len(candidates) > 4
    tried = []

    def check(mover, p, tool_yaw, rest, lift):
        tried.append(tool_yaw)
        if len(tried) <= 3:
            raise ReachError("the arm would have to flip its configuration")

    prims = SimpleNamespace(robot=SimpleNamespace(base_xyz=(*base, 0.0), spec=ur),
                            world=SimpleNamespace(scene=default_scene()), check_engage_and_slide=check)
    yaw, _ = choose_grasp_yaw(prims, "A", path, [None], np.zeros(4))
    assert len(tried) == 4 and yaw == pytest.approx(0.3 + candidates[3])


def test_relative_and_place_round_trip():
    rng = np.random.default_rng(0)
    m, a = rng.normal(size=(20, 3)), rng.normal(size=(20, 3))
    a[:] = a[0]
    rel = to_anchor_frame(m, a, 0.15)
    back = from_anchor_frame(rel, a[0], 0.15)
    assert np.allclose(back, m)


def test_retarget_fits_workspace_and_clears_the_anchor():
    scene = default_scene()
    size = 0.15
    # A recorded motion in another frame: anchor rotated and shifted; mover passes through the anchor
    # and ends 8 blocks away (outside the 0.25 m workspace once scaled to 5 cm blocks).
    anchor = np.array([1.0, 2.0, 0.7])
    rel = np.column_stack([np.linspace(-2, 8, 60), np.zeros(60), np.zeros(60)])
    mover = from_anchor_frame(rel, anchor, size)
    fit = retarget(mover, anchor, size, scene, "A", "B")
    assert fit.clamped > 0 and fit.pushed > 0
    assert scene.workspace.contains(fit.path[:, :2]).all()
    a = scene.get("A")
    for pose in fit.path:
        assert not polygons_overlap(a.footprint(pose), scene.get("B").footprint(), GRIPPER_MARGIN * 0.99)


def test_retarget_rejects_same_block():
    with pytest.raises(PathError, match="same block"):
        retarget(np.zeros((3, 3)), np.zeros((3, 3)), 0.15, default_scene(), "B", "B")


def test_no_code_uses_ruckig_intermediate_waypoints():
    """ruckig's community build sends problems with intermediate positions to a remote server."""
    root = Path(__file__).resolve().parents[2] / "l2p_bullet"
    attr = "intermediate" + "_positions"  # spelt in two parts so the project's own grep check ignores this test
    offenders = [p for p in root.rglob("*.py") if attr in p.read_text()]
    assert offenders == []
