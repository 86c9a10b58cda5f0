"""A clause re-planned from the real state whose plan its judge rejects is planned with another seed (run.py)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from l2p_bullet.arms import PANDA
from l2p_bullet.chain import replan as chain_run
from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.chain.ends import DEFAULT, End
from l2p_bullet.chain.forecast import Step
from l2p_bullet.core.contracts import Plan
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.options import RunOptions
from l2p_bullet.plugins import registry

SHORT = np.array([0.02, 0.0, 0.0])
"""Where the stand-in planner's seed offset 0 ends: a place the stand-in judge rejects."""


@pytest.fixture(scope="module")
def plugins():
    return registry.discover()


def _scene() -> Scene:
    return Scene([SceneObject("A", "red", 0.04, (0.10, -0.08), 0.2),
                  SceneObject("B", "green", 0.04, (0.0, 0.02), 0.0)]).validate()


class Judge:
    def judge(self, path, anchor, size, **_):
        ok = not np.allclose(np.asarray(path)[-1][:2], SHORT[:2])
        return SimpleNamespace(to_dict=lambda: {"success": ok, "reason": "short" if not ok else "done"})


def _stand_in(calls: list, *, rejected_everywhere: bool = False):
    def plan(clause, scene, bundle, judge, options, arm, end=DEFAULT, *, base=None):
        calls.append(end)
        start = np.asarray(scene.get(clause.command.mover).pose, float)
        goal = SHORT if end.seed == 0 or rejected_everywhere else np.array([-0.1 * end.seed, 0.15, 0.0])
        path = np.linspace(start, goal, 6)
        anchor = np.asarray(scene.get(clause.command.anchor).pose)
        return Plan(clause.command.action, clause.command.mover, clause.command.anchor, 0.04, anchor, start, path,
                    np.linspace(0, 1, 6), "stand-in", "threshold", {"final_progress": 1.0})

    return plan


def _step(plugins, end: End = DEFAULT) -> Step:
    clause = resolve_clauses("move A past B", _scene(), plugins)[0]
    return Step(clause, None, None, Judge(), None, end)


@pytest.fixture
def no_path_check(monkeypatch):
    from l2p_bullet.embodiment import execute

    monkeypatch.setattr(execute, "check_for", lambda *a, **k: None)


def test_a_rejected_replan_is_planned_again_with_the_next_seed(plugins, monkeypatch, no_path_check):
    calls: list = []
    monkeypatch.setattr(chain_run, "plan_clause", _stand_in(calls))
    plan = chain_run.replanned(_step(plugins, End(0, "half")), _scene(), RunOptions(), PANDA)
    assert calls == [End(0, "half"), End(1, "half")]  # the chosen end's cut kept, another seed
    assert np.allclose(plan.path[-1], [-0.1, 0.15, 0.0])
    assert plan.extra["replanned"] == {"seed_offset": 1, "rejected": "short"}


def test_an_accepted_replan_is_planned_once(plugins, monkeypatch, no_path_check):
    calls: list = []
    monkeypatch.setattr(chain_run, "plan_clause", _stand_in(calls))
    plan = chain_run.replanned(_step(plugins, End(1)), _scene(), RunOptions(), PANDA)
    assert calls == [End(1)] and "replanned" not in plan.extra


def test_where_every_seed_is_rejected_the_chosen_end_is_kept(plugins, monkeypatch, no_path_check):
    calls: list = []
    monkeypatch.setattr(chain_run, "plan_clause", _stand_in(calls, rejected_everywhere=True))
    plan = chain_run.replanned(_step(plugins), _scene(), RunOptions(), PANDA)
    assert calls == [DEFAULT, End(1), End(2)]
    assert np.allclose(plan.path[-1], SHORT) and "replanned" not in plan.extra


def _forecast_step(plugins, scene: Scene) -> Step:
    """A step whose forecast plan ends at (-0.1, 0.15), planned from ``scene``."""
    clause = resolve_clauses("move A past B", scene, plugins)[0]
    start = np.asarray(scene.get("A").pose, float)
    path = np.linspace(start, [-0.1, 0.15, 0.0], 6)
    plan = Plan("past", "A", "B", 0.04, np.asarray(scene.get("B").pose), start, path, np.linspace(0, 1, 6),
                "stand-in", "threshold", {"final_progress": 1.0})
    return Step(clause, None, None, Judge(), plan, DEFAULT, scene)


def _nudged(scene: Scene, name: str, dx: float) -> Scene:
    pose = np.asarray(scene.get(name).pose, float)
    return scene.with_pose(name, pose + [dx, 0.0, 0.0])


def test_where_the_world_is_the_forecast_state_its_plan_is_followed(plugins, monkeypatch, no_path_check):
    calls: list = []
    monkeypatch.setattr(chain_run, "plan_clause", _stand_in(calls))
    step = _forecast_step(plugins, _scene())
    now = _nudged(_nudged(_scene(), "A", 0.0004), "B", -0.0003)  # the arm left them a few tenths of a mm off
    plan = chain_run.replanned(step, now, RunOptions(), PANDA)
    assert calls == []  # not planned again: a new search from a start a hair off can end elsewhere
    assert np.allclose(plan.path[-1], [-0.1, 0.15, 0.0]) and plan.extra["followed_forecast"] is True
    assert np.allclose(plan.path[0], now.get("A").pose) and np.allclose(plan.start, now.get("A").pose)
    assert np.allclose(plan.anchor_pose, now.get("B").pose)


def test_a_block_off_the_forecast_state_is_planned_again(plugins, monkeypatch, no_path_check):
    calls: list = []
    monkeypatch.setattr(chain_run, "plan_clause", _stand_in(calls))
    step = _forecast_step(plugins, _scene())
    plan = chain_run.replanned(step, _nudged(_scene(), "B", 0.005), RunOptions(), PANDA)
    assert calls[0] == DEFAULT and "followed_forecast" not in plan.extra  # planned again first
    # the re-plan its judge rejects gives way to the forecast's path from the real start, before any other seed
    assert calls == [DEFAULT] and plan.extra["replanned"]["forecast"] is True


def test_a_forecast_plan_its_judge_rejects_from_the_real_state_is_planned_again(plugins, monkeypatch,
                                                                                 no_path_check):
    calls: list = []
    monkeypatch.setattr(chain_run, "plan_clause", _stand_in(calls))
    step = _forecast_step(plugins, _scene())
    step.forecast.path[-1] = SHORT  # where the stand-in judge rejects it
    plan = chain_run.replanned(step, _scene(), RunOptions(), PANDA)
    assert calls == [DEFAULT, End(1)] and "followed_forecast" not in plan.extra


def test_a_forecast_path_the_arm_cannot_follow_there_is_planned_again(plugins, monkeypatch):
    from l2p_bullet.embodiment import execute
    from l2p_bullet.errors import PathError

    def blocked(manner, scene, mover, path, arm):
        raise PathError("runs into B")

    calls: list = []
    monkeypatch.setattr(chain_run, "plan_clause", _stand_in(calls))
    monkeypatch.setattr(execute, "check_for", blocked)
    plan = chain_run.replanned(_forecast_step(plugins, _scene()), _scene(), RunOptions(), PANDA)
    assert calls[0] == DEFAULT and "followed_forecast" not in plan.extra


def test_the_forecast_keeps_the_state_each_clause_was_planned_from(plugins):
    from l2p_bullet.chain.forecast import forecast

    scene = Scene([SceneObject("A", "red", 0.05, (0.12, -0.10), 0.0),
                   SceneObject("B", "green", 0.05, (-0.02, 0.02), 0.0)]).validate()
    clauses = resolve_clauses("move A away from B, then move B closer to A", scene, plugins)
    steps = forecast(clauses, scene, plugins, planner="discrete", seed=0)
    assert steps[0].scene is scene
    assert np.allclose(steps[1].scene.get("A").pose, steps[0].forecast.path[-1])
    assert np.allclose(steps[1].scene.get("B").pose, scene.get("B").pose)
