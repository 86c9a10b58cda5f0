"""Stand-ins for a learned bundle in planner tests: fast, deterministic, no weights needed.

``RuleProgress`` scores a path with the rule-based evaluator's graded score, so a planner that
maximises it must produce the action's motion. It is a test double only: the shipped planners always
maximise the bundle's learned model.
"""

from __future__ import annotations

import numpy as np

from l2p_bullet.judge.rules import rule_verdict


class RuleProgress:
    def __init__(self, action: str):
        self.action = action
        self.batches: list[int] = []

    def final_batch(self, movers, anchors, size):
        self.batches.append(len(movers))
        shared = not isinstance(anchors, list)
        return np.array([rule_verdict(self.action, m, anchors if shared else anchors[i], size).score
                         for i, m in enumerate(movers)])

    def curve(self, mover, anchor, size):
        return np.array([rule_verdict(self.action, mover[: i + 1], anchor, size).score for i in range(len(mover))])


class FakeBundle:
    def __init__(self, action: str, policy=None, settings: dict | None = None):
        self.name = action
        self.manifest = {"policy": settings or {}, "judge": {"rules": action}}
        self.model = RuleProgress(action)
        self._policy = policy

    def progress_model(self):
        return self.model

    def policy_arrays(self):
        return self._policy
