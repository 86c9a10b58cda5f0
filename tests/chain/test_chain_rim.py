"""A clause planned to end on the workspace's rim can end a hair beyond it when the arm executes it; the next clause
is planned from the rim, not refused as a block that cannot move at all (run.py: ``on_rim``)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from l2p_bullet.arms import PANDA
from l2p_bullet.chain import replan
from l2p_bullet.chain import run as chain_run
from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.chain.forecast import Step
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.core.workspace import Workspace
from l2p_bullet.errors import InfeasibleError, PlanError
from l2p_bullet.pipeline import check_feasible
from l2p_bullet.plugins import registry

WS = Workspace((0.0, 0.0), 0.35, (-0.53, 0.0, 0.27, 0.79))
"""The Panda's workspace: the disk cut by its reach ring (as ``admit`` gives it)."""


@pytest.fixture(scope="module")
def plugins():
    return registry.discover()


def _scene(beyond: float) -> Scene:
    """A beyond the disk's rim by ``beyond`` m, where the seed 25015 chain's "move A away from B" left it (0.02 mm
    beyond; its plan ended 0.07 mm inside)."""
    bearing = np.array([-0.7229, 0.6909]) / np.hypot(-0.7229, 0.6909)
    a = (0.35 + beyond) * bearing
    return Scene([SceneObject("A", "red", 0.05, (float(a[0]), float(a[1])), 1.16),
                  SceneObject("B", "green", 0.05, (0.0, 0.02), 1.06),
                  SceneObject("D", "yellow", 0.05, (-0.207, -0.022), 0.68)], workspace=WS)


def test_a_block_a_hair_beyond_the_rim_cannot_move_as_it_stands(plugins):
    cmd = resolve_clauses("move A next to D", _scene(0.0), plugins)[0].command
    with pytest.raises(InfeasibleError) as e:
        check_feasible(cmd, _scene(2.4e-5), plugins, PANDA)
    assert e.value.check == "boxed-in"


def test_it_is_planned_from_the_rim(plugins):
    now = _scene(2.4e-5)
    rim = replan.on_rim(now)
    a, b = np.asarray(rim.get("A").xy), np.asarray(now.get("A").xy)
    assert WS.contains(a[None])[0] and np.hypot(*(a - b)) < 1e-4 and rim.get("A").yaw == now.get("A").yaw
    assert rim.get("B") == now.get("B") and rim.get("D") == now.get("D")
    cmd = resolve_clauses("move A next to D", rim, plugins)[0].command
    check_feasible(cmd, rim, plugins, PANDA)  # not boxed in


def test_a_block_well_beyond_the_rim_is_left_where_it_is():
    now = _scene(0.002)  # 2 mm: not the arm's small miss, a block the next clause must not be planned from
    assert replan.on_rim(now).get("A") == now.get("A")


def test_the_next_clause_is_replanned_from_the_rim(plugins, monkeypatch):
    now = _scene(2.4e-5)
    seen = []

    def replanned(step, scene, options, arm, **_):
        seen.append(scene)
        raise PlanError("stop here")

    monkeypatch.setattr(chain_run, "replanned", replanned)
    clause = resolve_clauses("move A next to D", now, plugins)[0]
    prims = SimpleNamespace(recorder=SimpleNamespace(frames=[{}], traj_every=1), world=SimpleNamespace(dt=0.01),
                            hold=lambda seconds: None, grasp=None)
    r = chain_run._clause(Step(clause, None, None, None, None), now, prims, np.zeros(9), plugins,
                          chain_run.RunOptions(), PANDA, first=0, replan=True)
    assert r.failed_stage == "plan" and "stop here" in r.verdict["reason"]  # not "plan (boxed-in)"
    assert len(seen) == 1 and WS.contains(np.asarray(seen[0].get("A").xy)[None])[0]
