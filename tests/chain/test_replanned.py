"""A clause re-planned from the real state whose plan its judge rejects is planned with another seed (run.py)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from l2p_bullet.arms import PANDA
from l2p_bullet.chain import run as chain_run
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
