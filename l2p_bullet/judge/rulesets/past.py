"""The rule of "past": the mover crosses from one side of the anchor to the other along its overall direction
of travel (starting at least ``margin`` blocks before it and ending at least ``margin`` beyond it), passes
near it (closest centre distance at most ``near`` blocks) and does not circle it (turns at most
``max_turn_deg`` around it: more is going around)."""

from __future__ import annotations

import math

import numpy as np

from ...actions.past import ACTION
from ...core.geometry import swept_angle
from ..base import Verdict

PAST_MARGIN = ACTION.thresholds["margin"]
"""Blocks "past" must start before the anchor and end beyond it (along its direction of travel)."""
PAST_NEAR = ACTION.thresholds["near"]
"""Largest closest centre distance (blocks) of "past"."""
PAST_MAX_TURN_DEG = ACTION.thresholds["max_turn_deg"]
"""Most degrees "past" may turn around the anchor (more is going around)."""


def past(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    travel = rel[-1] - rel[0]
    length = float(np.linalg.norm(travel))
    if length < 1e-9:
        return Verdict(False, 0.0, "did not move")
    u = travel / length
    before, beyond = -float(rel[0] @ u), float(rel[-1] @ u)
    near = float(d.min())
    swept = math.degrees(abs(swept_angle(rel)))
    crossing = min(np.clip(before / PAST_MARGIN, 0, 1), np.clip(beyond / PAST_MARGIN, 0, 1))
    nearness = float(np.clip(1.0 - (near - PAST_NEAR) / 8.0, 0.5, 1.0))
    straight = float(np.clip((200.0 - swept) / 40.0, 0.3, 1.0))  # more than a half-turn is circling
    score = float(crossing * nearness * straight)
    ok = before >= PAST_MARGIN and beyond >= PAST_MARGIN and near <= PAST_NEAR and swept <= PAST_MAX_TURN_DEG
    why = (f"started {before:.2f} blocks before and ended {beyond:.2f} beyond the anchor, "
           f"closest {near:.2f} blocks, turned {swept:.0f} deg around it")
    return Verdict(ok, score, why)


RULES = {ACTION.rules: past}
