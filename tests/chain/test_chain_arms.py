"""Chains run on any arm (issues 21 and 22): the same arm plans and performs every clause in one episode,
and the run folder names it; an unknown arm is refused before anything is planned or written."""

from __future__ import annotations

import json

import pytest

from l2p_bullet.chain.run import perform_chain
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.errors import L2PError

SCENE = Scene([SceneObject("A", "red", 0.04, (0.09, -0.06), 0.0), SceneObject("B", "green", 0.04, (0.0, 0.0), 0.0),
               SceneObject("C", "blue", 0.04, (-0.1, 0.1), 0.0)])


@pytest.mark.slow
def test_the_xarm_performs_a_chain_of_two_manners(tmp_path):
    r = perform_chain("move A closer to B, then carry A away from B", SCENE, out_dir=tmp_path / "run", render=False,
                      arm="xarm6")
    assert r.success, [c.verdict for c in r.results]
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    traj = json.loads((tmp_path / "run" / "trajectory.json").read_text())
    assert summary["arm"] == "xarm6" and traj["arm"]["name"] == "xarm6"
    assert len(traj["frames"][0]["arm"]) == len(traj["arm"]["joints"])  # the xArm's joints, not the Panda's
    assert max(summary["displacements_m"].values()) < 0.001  # B and C stay where they were


def test_an_unknown_arm_is_refused_before_anything_is_written(tmp_path):
    with pytest.raises(L2PError, match="xarm6"):  # the did-you-mean names the arm meant
        perform_chain("move A closer to B, then move C next to B", SCENE, out_dir=tmp_path / "run", render=False,
                      arm="xarm-6")
    assert not (tmp_path / "run").exists()
