"""The rule of "closer": the centre distance shrinks steadily and closes at least ``share`` of the room there
was (room = start distance - 1 block, the distance at which two squares touch face to face); the score also
grows with the distance covered (people graded short moves down)."""

from __future__ import annotations

import numpy as np

from ...actions.closer import ACTION
from ..base import Verdict
from ..footprints import WOBBLE

CLOSER_SHARE = ACTION.thresholds["share"]
"""Share of the room there was (:func:`closer_room`) that "closer" must close."""


def closer_room(start: float) -> float:
    """The room "closer" has, in blocks, from a start distance of ``start`` blocks: the distance to where two
    squares touch face to face (1 block), at least a quarter block (planning/feasibility.py reads it too)."""
    return max(start - 1.0, 0.25)


def went_back(d: np.ndarray) -> float:
    """The most the centre distance ``d`` (blocks per frame) rose above its least so far: how far "closer" went
    back (planning/bounds.py bounds the planner's candidates by it, so both measure it the same way)."""
    return float(np.max(d - np.minimum.accumulate(d)))


def closer(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    room = closer_room(float(d[0]))
    moved = float(d[0]) - float(d[-1])
    closed = moved / room
    rise = went_back(d)
    # people also reward how far it came, not only the share of the room ("right, but too short")
    score = float(np.clip(closed, 0, 1) * np.clip(moved / 2.0, 0, 1)) * (1.0 if rise <= WOBBLE else 0.5)
    ok = closed >= CLOSER_SHARE and rise <= WOBBLE
    why = f"closed {closed:.0%} of the gap (start {d[0]:.2f}, end {d[-1]:.2f} blocks), went back {rise:.2f} blocks"
    return Verdict(ok, score, why)


RULES = {ACTION.rules: closer}
