"""The rule of "closer": the centre distance shrinks steadily and closes at least ``share`` of the room there
was (room = start distance - the distance at which the two touch); the score also grows with the distance
covered (people graded short moves down).

The touching distance is what the words mean by "as close as it gets": for two cubes 1 block, where two
squares touch face to face (as the rule was fitted on people's demonstrations); where one of the objects
is not a cube, the centre distance at which their real footprints touch when the mover comes straight at the
anchor from where it starts (``footprints.touching``: a mover beside a 2:1 box's long face has less room to
close than one at its end). The centre distances themselves stay centre distances: "closer" says the mover
ends nearer, wherever on the anchor it aims."""

from __future__ import annotations

import numpy as np

from ...actions.closer import ACTION
from ..base import Verdict
from ..footprints import WOBBLE, touching

CLOSER_SHARE = ACTION.thresholds["share"]
"""Share of the room there was (:func:`closer_room`) that "closer" must close."""


def closer_room(start: float, touch: float = 1.0) -> float:
    """The room "closer" has, in blocks, from a start distance of ``start`` blocks: the distance to where the
    two touch (``touch`` blocks: two squares face to face by default), at least a quarter block
    (planning/feasibility.py reads it too)."""
    return max(start - touch, 0.25)


def touch_distance(rel0: np.ndarray, mover0: np.ndarray, anchor0: np.ndarray, size: float,
                   outlines: list[np.ndarray] | None) -> float:
    """The centre distance (blocks) at which the mover touches the anchor, from the start poses (mover's
    ``rel0`` in blocks from the anchor, both poses in metres): 1 for unit squares (``outlines`` None)."""
    if outlines is None:
        return 1.0
    return touching(np.r_[rel0, mover0[2]], np.r_[0.0, 0.0, anchor0[2]], size, outlines[:2])


def went_back(d: np.ndarray) -> float:
    """The most the centre distance ``d`` (blocks per frame) rose above its least so far: how far "closer" went
    back (planning/bounds.py bounds the planner's candidates by it, so both measure it the same way)."""
    return float(np.max(d - np.minimum.accumulate(d)))


def closer(rel: np.ndarray, d: np.ndarray, mover: np.ndarray, anchor: np.ndarray, size: float, *,
           outlines: list[np.ndarray] | None = None, **_: object) -> Verdict:
    room = closer_room(float(d[0]), touch_distance(rel[0], mover[0], anchor[0], size, outlines))
    moved = float(d[0]) - float(d[-1])
    closed = moved / room
    rise = went_back(d)
    # people also reward how far it came, not only the share of the room ("right, but too short")
    score = float(np.clip(closed, 0, 1) * np.clip(moved / 2.0, 0, 1)) * (1.0 if rise <= WOBBLE else 0.5)
    ok = closed >= CLOSER_SHARE and rise <= WOBBLE
    why = f"closed {closed:.0%} of the gap (start {d[0]:.2f}, end {d[-1]:.2f} blocks), went back {rise:.2f} blocks"
    return Verdict(ok, score, why)


RULES = {ACTION.rules: closer}
