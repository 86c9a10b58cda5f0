"""Manners compose with chains (issue 23): "carry A past B, then push C next to A" in one episode."""

from __future__ import annotations

import json

import pytest

from l2p_bullet.chain.run import perform_chain
from l2p_bullet.core.scene import Scene, SceneObject


@pytest.mark.slow
def test_carry_then_push_in_one_chain(tmp_path):
    scene = Scene([SceneObject("A", "red", 0.04, (0.09, -0.06), 0.0), SceneObject("B", "green", 0.04, (0.0, 0.0), 0.0),
                   SceneObject("C", "blue", 0.04, (-0.1, 0.1), 0.0)])
    r = perform_chain("carry A past B, then push C next to A", scene, out_dir=tmp_path / "run", render=False)
    assert r.success, [c.verdict for c in r.results]
    traj = json.loads((tmp_path / "run" / "trajectory.json").read_text())
    assert [s.get("manner") for s in traj["segments"]] == ["carry", "push"]
    one, two = traj["segments"]
    frames = traj["frames"]
    lifted = max(f["poses"]["A"][2] for f in frames[one["first_frame"]:one["last_frame"] + 1]) - 0.02
    assert lifted >= 0.02
    assert all(f["grasped"] is None for f in frames[two["first_frame"]:two["last_frame"] + 1])
    assert any(f["gripper"]["contact"] for f in frames[two["first_frame"]:two["last_frame"] + 1])
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert [c["manner"] for c in summary["clauses"]] == ["carry", "push"]
    assert all(c["verdict"]["manner"]["success"] for c in summary["clauses"])
