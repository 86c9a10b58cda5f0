"""Physics honesty, determinism and bad input for execute_path (headless, no rendering)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from l2p_bullet.arms import PANDA
from l2p_bullet.core.scene import Scene, SceneObject, Workspace, default_scene
from l2p_bullet.embodiment import motion
from l2p_bullet.embodiment.execute import execute_path
from l2p_bullet.embodiment.sim.camera import RenderSettings
from l2p_bullet.embodiment.sim.robot import Kinematics
from l2p_bullet.errors import PathError, ReachError, UnknownObjectError


def circle_around(scene: Scene, mover: str = "A", anchor: str = "B", n: int = 121) -> np.ndarray:
    """A full circle of the mover around the anchor, starting where the mover is, yaw held."""
    a, b = scene.get(mover), scene.get(anchor)
    c, p0 = np.array(b.xy), np.array(a.xy)
    r = float(np.hypot(*(p0 - c)))
    ang = math.atan2(p0[1] - c[1], p0[0] - c[0]) + np.linspace(0, 2 * math.pi, n)
    return np.column_stack([c[0] + r * np.cos(ang), c[1] + r * np.sin(ang), np.full(n, a.yaw)])


@pytest.fixture(scope="module")
def circle_run(tmp_path_factory):
    scene = default_scene()
    path = circle_around(scene)
    out = tmp_path_factory.mktemp("circle")
    ex = execute_path(scene, "A", path, out_dir=out, render=None, meta={"anchor": "B"})
    return scene, path, ex, out


def test_block_follows_the_planned_circle(circle_run):
    scene, path, ex, _ = circle_run
    held = [f for f in ex.frames if f["grasped"] == "A"]
    assert len(held) > 100
    # After the arm's lag settles (first 0.5 s of holding), the block stays within 3 mm of the path.
    t0 = held[0]["t"] + 0.5
    xy = np.array([f["poses"]["A"][:2] for f in held if f["t"] >= t0])
    dev = motion.polyline_distance(xy, path[:, :2])
    assert dev.max() < 0.003
    assert ex.max_deviation_m < 0.003
    # and it really went round: its angle about B covers the whole circle
    b = np.array(scene.get("B").xy)
    ang = np.unwrap(np.arctan2(xy[:, 1] - b[1], xy[:, 0] - b[0]))
    assert ang.max() - ang.min() > 1.9 * math.pi


def test_block_never_rises_and_anchor_stays(circle_run):
    scene, _, ex, _ = circle_run
    z = np.array([f["poses"]["A"][2] for f in ex.frames])
    assert z.max() - 0.025 < 0.003  # never lifted more than 3 mm off the table
    b0 = np.array(ex.frames[0]["poses"]["B"][:2])
    moved = max(np.hypot(*(np.array(f["poses"]["B"][:2]) - b0)) for f in ex.frames)
    assert moved < 0.001 and ex.anchor_displacement_m < 0.001


def test_grasp_is_released_and_the_arm_retracts(circle_run):
    _, path, ex, out = circle_run
    assert ex.constraint_removed
    grasped = [f["grasped"] for f in ex.frames]
    assert grasped[0] is None and grasped[-1] is None and "A" in grasped
    end = np.array(ex.frames[-1]["poses"]["A"])
    assert np.hypot(*(end[:2] - path[-1, :2])) < 0.003  # left where the path ends
    assert ex.frames[-1]["ee"][2] > end[2] + 0.1  # the hand went back up
    doc = json.loads((out / "trajectory.json").read_text())
    assert doc["schema"] == 1 and doc["mover"] == "A" and doc["anchor"] == "B"
    assert all(set(f["poses"]) == {"A", "B"} for f in doc["frames"])
    assert all(f["progress"] is None for f in doc["frames"])  # no progress_fn given
    ts = [f["t"] for f in doc["frames"]]
    assert np.allclose(np.diff(ts), 1 / doc["fps"], atol=1e-6)
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["timings_s"]) >= {"engage", "move", "disengage"} and "pybullet" in summary["versions"]


def _short_path(scene: Scene) -> np.ndarray:
    a = scene.get("A")
    return np.array([[a.xy[0], a.xy[1], a.yaw], [a.xy[0] + 0.06, a.xy[1] - 0.02, a.yaw + 0.3]])


def test_two_runs_give_identical_trajectory_json(tmp_path):
    scene = default_scene()
    calls = []

    def progress(m, a):
        calls.append(len(m))
        return np.linspace(0, 1, len(m))

    # The third run renders: the arm is then loaded with its visual meshes, which must not change physics.
    for name, render in (("one", None), ("two", None), ("three", RenderSettings(width=80, height=60, fps=2))):
        (tmp_path / name).mkdir()
        execute_path(scene, "A", _short_path(scene), out_dir=tmp_path / name, render=render,
                     progress_fn=progress, meta={"anchor": "B", "action": "closer"})
    one, two, three = ((tmp_path / n / "trajectory.json").read_bytes() for n in ("one", "two", "three"))
    assert one == two == three
    assert (tmp_path / "three" / "video.mp4").exists() and not (tmp_path / "one" / "video.mp4").exists()
    frames = json.loads(one)["frames"]
    assert calls[0] == len(frames) and frames[-1]["progress"] == 1.0


def test_unknown_object():
    with pytest.raises(UnknownObjectError, match='no object named "C"'):
        execute_path(default_scene(), "C", np.zeros((2, 3)), out_dir=None, render=None)


def test_path_leaving_the_workspace():
    scene = default_scene()
    a = scene.get("A")
    path = np.array([[a.xy[0], a.xy[1], 0.0], [0.3, -0.2, 0.0]])  # 0.36 m from the centre
    with pytest.raises(PathError, match="leaves the workspace"):
        execute_path(scene, "A", path, out_dir=None, render=None)


def test_path_into_the_anchor():
    scene = default_scene()
    a, b = scene.get("A"), scene.get("B")
    path = np.array([[a.xy[0], a.xy[1], a.yaw], [b.xy[0], b.xy[1], a.yaw]])
    with pytest.raises(PathError, match='runs into "B"'):
        execute_path(scene, "A", path, out_dir=None, render=None)


def test_path_not_starting_at_the_block():
    with pytest.raises(PathError, match="path starts at"):
        execute_path(default_scene(), "A", np.array([[0.1, 0.1, 0], [0.12, 0.1, 0]]), out_dir=None, render=None)


def test_unreachable_path_raises_before_simulating():
    # A workspace wider than the arm's reach lets the path through the 2-D checks; IK must catch it.
    scene = Scene([SceneObject("A", "red", 0.05, (0.2, 0.0)), SceneObject("B", "green", 0.05, (0.0, 0.1))],
                  workspace=Workspace(radius=0.6))
    path = np.array([[0.2, 0.0, 0.0], [0.45, 0.0, 0.0]])
    stages: list[str] = []
    with pytest.raises(ReachError, match=r"cannot reach \((0\.2[6-9]|0\.[34])") as err:
        execute_path(scene, "A", path, out_dir=None, render=None, on_stage=stages.append)
    assert "residual" in str(err.value)
    assert "engage" not in stages  # failed in the reach check, before the arm moved


def test_ik_detects_residual_and_accepts_reachable():
    kin = Kinematics(PANDA, (-0.53, 0.0, 0.0))
    try:
        home = np.array(PANDA.home)
        q = kin.solve([0.1, 0.1, 0.06], 0.3, home, seeds=PANDA.ik_seeds)
        pos, _ = kin.fk(q)
        assert np.linalg.norm(pos - [0.1, 0.1, 0.06]) < 0.002
        with pytest.raises(ReachError, match="residual"):
            kin.solve([0.6, 0.0, 0.06], 0.0, home, seeds=PANDA.ik_seeds)
    finally:
        kin.close()
