"""Bounds from people's demonstrations on the candidates the search ranks (an action declares its own,
``ActionSpec.planning.bound`` and ``more_bounds``, by the kinds of :data:`WEIGHTS`): where "past" passes and
where it starts, how far "closer" goes back.

The learned models rate some motions done that no person made, and chains meet them where the 2-D study never
started a motion:

- "past" slid by the anchor 4-5 blocks away at 0.98-0.997, while people's 43 demonstrations pass it at a median
  1.9 blocks, nine in ten within 3.23 (``ActionSpec.thresholds["passes_within"]`` of past, that 90 % quantile
  rounded to 3.2; docs/planning.md);
- "past" from beside the anchor (touching it, or level with it) slid along it, which the model rates done, while
  39 of people's 43 started before it, along their overall direction, by at least half their distance from it
  (``thresholds["starts_before"]`` of past, their 10 % quantile): two people's starts from beside it do not make
  a slide along it "past";
- "closer" from a block touching the anchor, or level with it a fraction of a block away, found no move at all:
  the model rates every short move there 0.01-0.04, so the search saw no slope; the rule asks that the centre
  distance close at least ``thresholds["share"]`` of the room (0.5), and a candidate closing less is weighted down
  by how much less (``"closes-at-least"``, from within half a block of room only: from farther out the model has a
  slope of its own);
- "away" from afar (6-10 blocks, where the chains send it and no person started but two) was rated done by the
  model after the distance grew 0.7 blocks, while the rule asks one block and 35 of people's 37 grew it by at
  least 1.8 (``thresholds["grows_at_least"]`` of away, their 5 % quantile rounded down): from farther than
  :data:`FAR_SIDES` a candidate growing it less is weighted down by how much less (``"grows-at-least"``);
- "closer" from within 1.8 blocks wiggles: the model rates a back-and-forth higher than a straight slide to
  touching, while people's 41 demonstrations went back at most 0.176 of the room they had (start distance - 1
  block; ``thresholds["goes_back_within"]`` of closer, rounded up to 0.18).

So, like "around"'s reach, planner settings from people's data: the model is unchanged, and its final progress
of a candidate path is weighted down by how far beyond people's bound the path goes. The weights are smooth, not
cuts, so that every step back within the bound pays. The plan's per-frame ``curve`` (what the plan and the video
show) stays the model's own; its ``extra.final_progress`` is the score the search ranked by, the model's own
wherever the path keeps within the bound.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import numpy as np

from ..actions import Bound
from ..judge.rules import closer_room, went_back

SCALE_SIDES = 1.0
"""Blocks of closest approach beyond the room at which a candidate's score is multiplied by 1/e (as
``target.SCALE_SIDES``; not tuned)."""


def _distances(mover: np.ndarray, anchor_pose: np.ndarray, size: float) -> np.ndarray:
    """Centre distance to the anchor per frame of a (T,3) path, in blocks."""
    return np.hypot(*(np.asarray(mover, float)[:, :2] - np.asarray(anchor_pose, float)[:2]).T) / size


def pass_weight(movers: list[np.ndarray], anchor_pose: np.ndarray, size: float, within: float) -> np.ndarray:
    """Per path (T,3 centres): 1 where its closest centre distance to the anchor is at most ``within`` blocks,
    else exp(-(closest - within) / SCALE_SIDES)."""
    closest = np.array([_distances(m, anchor_pose, size).min() for m in movers])
    return np.exp(-np.clip(closest - within, 0.0, None) / SCALE_SIDES)


def back_weight(movers: list[np.ndarray], anchor_pose: np.ndarray, size: float, within: float) -> np.ndarray:
    """Per path: 1 where the most its centre distance went back above its least so far (the rule's "went
    back") is at most the share ``within`` of its room, else exp(-(rise - share room) / (share room)): the
    share is its own scale."""
    out = np.empty(len(movers))
    for i, m in enumerate(movers):
        d = _distances(m, anchor_pose, size)
        allowed = within * closer_room(float(d[0]))
        out[i] = np.exp(-max(went_back(d) - allowed, 0.0) / allowed)
    return out


def start_weight(movers: list[np.ndarray], anchor_pose: np.ndarray, size: float, within: float) -> np.ndarray:
    """Per path: 1 where it starts before the anchor, along its overall direction (start to end, as the rule
    reads it), by at least the share ``within`` of its start distance, else exp(-(short of it) / (share start
    distance)): the share is its own scale, as :func:`back_weight`'s. A path from beside the anchor that only
    slides along it starts before it by little of its distance; one that crosses to its far side, by much."""
    out = np.empty(len(movers))
    a = np.asarray(anchor_pose, float)[:2]
    for i, m in enumerate(movers):
        rel = (np.asarray(m, float)[:, :2] - a) / size
        travel = rel[-1] - rel[0]
        length = float(np.linalg.norm(travel))
        wanted = within * float(np.linalg.norm(rel[0]))
        if length < 1e-9 or wanted <= 0.0:
            out[i] = 1.0 if wanted <= 0.0 else float(np.exp(-1.0))
            continue
        before = -float(rel[0] @ travel) / length
        out[i] = np.exp(-max(wanted - before, 0.0) / wanted)
    return out


CLOSE_ROOM = 0.5
"""Blocks of room (``closer_room``) up to which "closes-at-least" weighs a candidate: a start touching the anchor or
level with it half a block away or nearer, where the model is flat; from farther its own slope leads (weighing it
there too reranked the search's first moves and left a start 1.6 blocks from the anchor short of half its room)."""


def close_weight(movers: list[np.ndarray], anchor_pose: np.ndarray, size: float, within: float) -> np.ndarray:
    """Per path from within :data:`CLOSE_ROOM` of the anchor: 1 where its centre distance closed at least the
    share ``within`` of its room (start distance less one block, at least a quarter: the rule's ``closer_room``)
    from start to end, else exp(-(short of it) / (share room)): the share is its own scale, as
    :func:`back_weight`'s; 1 for a path from farther out. From face to face, or a fraction of a block apart, the
    model rates every short move alike (0.01-0.04): this ranks the moves that close the little room there is
    above those that do not, where the model alone sees no slope."""
    out = np.ones(len(movers))
    for i, m in enumerate(movers):
        d = _distances(m, anchor_pose, size)
        room = closer_room(float(d[0]))
        if room <= CLOSE_ROOM:
            wanted = within * room
            out[i] = np.exp(-max(wanted - (float(d[0]) - float(d[-1])), 0.0) / wanted)
    return out


FAR_SIDES = 5.0
"""Blocks of start distance from which "grows-at-least" weighs a candidate: beyond every start of people's "away"
but two (the next farthest 4.5 blocks), where the model rates a growth short of the rule's done; from nearer its own
slope leads, as :data:`CLOSE_ROOM` leaves "closer" to the model from farther out."""


def grow_weight(movers: list[np.ndarray], anchor_pose: np.ndarray, size: float, within: float) -> np.ndarray:
    """Per path from farther than :data:`FAR_SIDES` from the anchor: 1 where its centre distance grew by at least
    ``within`` blocks from start to end, else exp(-(short of it) / within): the least is its own scale, as
    :func:`close_weight`'s share; 1 for a path from nearer."""
    out = np.ones(len(movers))
    for i, m in enumerate(movers):
        d = _distances(m, anchor_pose, size)
        if float(d[0]) > FAR_SIDES:
            out[i] = np.exp(-max(within - (float(d[-1]) - float(d[0])), 0.0) / within)
    return out


WEIGHTS: dict[str, Callable[..., np.ndarray]] = {"passes-within": pass_weight,
                                                  "goes-back-within": back_weight,
                                                  "starts-before": start_weight,
                                                  "closes-at-least": close_weight,
                                                  "grows-at-least": grow_weight}
"""The bounds by kind (``actions.spec.Bound.kind``): each weighs a batch of candidate paths by its measure."""


def people_weight(bound: Bound) -> functools.partial:
    """The weight ``(movers, anchor_pose, size) -> per path`` of a declared bound."""
    return functools.partial(WEIGHTS[bound.kind], within=bound.within)


def product_weight(movers: list[np.ndarray], anchor_pose: np.ndarray, size: float,
                   weights: tuple[Callable[..., np.ndarray], ...]) -> np.ndarray:
    """Per path: the product of ``weights``' (several bounds held together)."""
    out = np.ones(len(movers))
    for w in weights:
        out = out * w(movers, anchor_pose, size)
    return out


def people_weights(bounds: tuple[Bound, ...]) -> functools.partial:
    """The weight of one or more declared bounds: one's own (:func:`people_weight`), several multiplied."""
    if len(bounds) == 1:
        return people_weight(bounds[0])
    return functools.partial(product_weight, weights=tuple(people_weight(b) for b in bounds))


class BoundScorer:
    """The action's progress model with its final progress multiplied by ``weight(movers, anchors, size)``."""

    def __init__(self, model: Any, weight: Callable[[list[np.ndarray], Any, float], np.ndarray]):
        self.model, self.weight = model, weight

    def __getattr__(self, name: str) -> Any:  # anchors, viewpoint... as the model declares them
        return getattr(self.model, name)

    def final_batch(self, movers: list[np.ndarray], anchors: Any, size: float, **context) -> np.ndarray:
        return np.asarray(self.model.final_batch(movers, anchors, size, **context), float) * self.weight(
            movers, anchors, size)

    def curve(self, mover: np.ndarray, anchor: np.ndarray, size: float, **context) -> np.ndarray:
        return self.model.curve(mover, anchor, size, **context)


__all__ = ["BoundScorer", "back_weight", "close_weight", "grow_weight", "pass_weight", "people_weight",
           "people_weights", "product_weight", "start_weight", "CLOSE_ROOM", "FAR_SIDES", "SCALE_SIDES", "WEIGHTS"]
