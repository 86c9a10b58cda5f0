"""The search ends where the model rates a path done only if the action's rule judge accepts it too.

A learned model can rate a path done that its rule rejects (a "closer" that closed a little of the gap, a "past"
a few millimetres short of its margin); a search stopping there hands on a plan that runs and fails. Here a
stand-in model rates "closer" done after any approach of a tenth of a block, which the rule (half the room) rejects.
"""

from __future__ import annotations

import numpy as np
from planning_fakes import FakeBundle

from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.judge.rules import rule_verdict
from l2p_bullet.planning import plan


class EagerCloser:
    """Rates a path 0.99 where its centre distance fell by less than half a block, 0.92 by 1.5 blocks or more."""

    def final_batch(self, movers, anchor, size, **_):
        a = np.asarray(anchor, float)[:2]
        out = []
        for m in movers:
            d = np.hypot(*(np.asarray(m, float)[:, :2] - a).T) / size
            closed = d[0] - d[-1]
            out.append(0.99 if 0.0 < closed < 0.5 else 0.92 if closed >= 1.5 else 0.2)
        return np.array(out)

    def curve(self, mover, anchor, size, **_):
        return np.array([self.final_batch([mover[: i + 1]], anchor, size)[0] for i in range(len(mover))])


def _bundle(rules: str | None) -> FakeBundle:
    b = FakeBundle("closer")
    b.model = EagerCloser()
    b.manifest = {"policy": {}, "judge": {"rules": rules} if rules else {"threshold": 0.9}}
    return b


def _scene() -> Scene:
    return Scene([SceneObject("A", "red", 0.05, (0.15, 0.0), 0.0), SceneObject("B", "blue", 0.05, (-0.05, 0.0), 0.0)])


def test_a_path_the_model_rates_done_but_the_rule_rejects_does_not_end_the_search():
    scene = _scene()
    p = plan(scene, "A", "B", _bundle("closer"), planner="greedy", seed=0)
    verdict = rule_verdict("closer", p.path, scene.get("B").pose, p.size)
    assert verdict.success, verdict.reason
    assert p.stopped == "threshold" and p.extra["final_progress"] >= 0.9


def test_an_action_judged_otherwise_is_still_planned_by_its_model_alone():
    scene = _scene()
    p = plan(scene, "A", "B", _bundle(None), planner="greedy", seed=0)
    assert p.stopped == "threshold"  # the model's first "done", as before
    assert not rule_verdict("closer", p.path, scene.get("B").pose, p.size).success


def test_held_short_stays_below_the_threshold_in_the_model_order():
    from l2p_bullet.planning.problem import held_short

    held = [held_short(p, 0.9) for p in (0.9, 0.95, 1.0, 1.3)]
    assert all(h < 0.9 for h in held) and held[0] < held[1] < held[2] == held[3]
