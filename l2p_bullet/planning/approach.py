"""The approach: "around" from afar is planned as people would do it, going there first.

The rule of "around" reads a motion from its first frame within ``near`` blocks of the anchor
(judge/rulesets/around.py), and people's 40 demonstrations of it all start near (median 2.5 blocks): they
set the blocks down close. A mover that starts farther (the 2-D study's starts reach 7.7 blocks; chains
and the arms' benchmark draw such pairs) is first slid straight towards the anchor until its centre is
``approach`` blocks from the anchor's (``ActionSpec.thresholds["approach"]``, where people start), keeping
its yaw; the learned model then plans the action from there, scoring only what follows (the lead-in of
:class:`~l2p_bullet.planning.problem.Problem`). The up-front check (``far-around``) refuses only a
start from which no straight slide gets there.

The slide aims at the anchor; where another object or the workspace's rim blocks that line, at points of
the same circle a little to either side (every 10 degrees, up to a quarter turn), nearest first; where the
whole circle has no room (a small mover by a big anchor), at circles a quarter block farther out, short of
``near``. Each
slide is checked as the search checks its moves: the 2-D world (the mover's outline grown by the hand,
the workspace) and the wrist's range for the grasp being planned.

Where no straight slide gets there (a block between the mover and the anchor's near side, one beside it, the
rim), the mover goes there as a person would reach round what is in the way: two straight slides at its yaw,
the first to a corner that stays farther than ``near`` from the anchor (the rule reads "around" from the
first frame within ``near``: a first slide that dipped in and out again would be read as leaving), the
second from there to the approach circle, people's start first and the shortest such pair on it first
(:func:`_round_the_way`). Only where neither gets there is the start refused (``far-around``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator

import numpy as np

from ..arms.reach import Wrist
from ..errors import InfeasibleError
from .world2d import World2D, segment_frames

AIM_OFFSETS_DEG = tuple(d * s for d in range(0, 91, 10) for s in ((1,) if d == 0 else (1, -1)))
"""Where on the approach circle the slide may end, in degrees of bearing from the start's own."""
RADIUS_STEP = 0.25
"""Blocks between the circles tried when people's start distance has no room (a big anchor)."""


def approach_radii(approach_sides: float, near_sides: float) -> list[float]:
    """The distances (blocks) the slide may end at, people's start first, then farther out in quarter blocks
    short of ``near``: a small mover by a big anchor cannot be 2.5 of its own sides from the anchor's centre."""
    return [approach_sides, *np.arange(approach_sides + RADIUS_STEP, near_sides - 0.05 + 1e-9, RADIUS_STEP).tolist()]


WAY_TRIES = 8
"""Legal slide ends (in the order above) asked whether a way round starts there, when the planner asks
(:func:`lead_in`'s ``way_round``); the first legal end is taken when none of them has one."""


def lead_in(world: World2D, anchor_pose: np.ndarray, near_sides: float, approach_sides: float, step: float,
            wrist: Wrist | None = None, mover: str = "the mover", anchor: str = "the anchor",
            way_round: Callable[[np.ndarray], bool] | None = None) -> np.ndarray | None:
    """Frames (T0,3) of the straight slide from the mover's start to ``approach_sides`` blocks from the
    anchor, the start included; None when the mover already starts within ``near_sides`` blocks.
    InfeasibleError ``far-around`` when no such slide is legal.

    ``way_round`` (a slide's frames -> whether the 2-D world has a way round the anchor from its end, counted
    from where it came near, :func:`swept_near`: detour.py): the first of the first :data:`WAY_TRIES` legal
    slides from whose end it has one, else the first legal slide. Why: among bystanders the nearest legal end
    can lie in a pocket between the anchor and another block, from which no move at all is legal (analysis
    chain/5044: the search ended at its first step, 0.01 of a turn)."""
    start = np.asarray(world.mover.pose, float)
    a = np.asarray(anchor_pose, float)[:2]
    rel = start[:2] - a
    d0 = float(np.hypot(*rel))
    if d0 <= near_sides * world.size + 1e-9:
        return None
    b0 = math.atan2(rel[1], rel[0])
    bearings = b0 + np.radians(AIM_OFFSETS_DEG)

    def straight() -> Iterator[tuple[np.ndarray, np.ndarray]]:
        for sides in approach_radii(approach_sides, near_sides):
            r = sides * world.size
            ends = np.column_stack([a[0] + r * np.cos(bearings), a[1] + r * np.sin(bearings),
                                    np.full(len(bearings), start[2])])
            for end in ends[world.moves_free(start, ends)]:
                yield np.vstack([start[None], segment_frames(start, end, step)]), end

    first = _first_way_round(straight(), wrist, way_round)
    if first is not None:
        return first
    found = _round_the_way(world, start, a, near_sides, approach_sides, step, wrist, way_round)
    if found is not None:
        return found
    raise InfeasibleError(
        "far-around",
        f'"{mover}" starts {d0 / world.size:.2f} blocks from "{anchor}", and no straight slide brings it to '
        f"{approach_sides:g}-{near_sides:g} blocks from it, nor two round what is in the way (other objects, the "
        "workspace's rim or the wrist's range "
        f"are in the way): around must come within {near_sides:g} blocks first; move it closer first",
        {"start_blocks": round(d0 / world.size, 3), "near_blocks": near_sides, "approach_blocks": approach_sides})


CORNER_STEP = (15.0, 0.5)
"""Bearing step (degrees) and radius step (blocks) of the corners a slide round what is in the way may turn at:
circles about the anchor from half a block beyond ``near`` out to two blocks beyond the mover's start."""


def _round_the_way(world: World2D, start: np.ndarray, a: np.ndarray, near_sides: float, approach_sides: float,
                   step: float, wrist: Wrist | None,
                   way_round: Callable[[np.ndarray], bool] | None) -> np.ndarray | None:
    """Frames of two straight slides at the start's yaw to the approach circles (any bearing), turning at a
    corner whose first slide stays farther than ``near_sides`` from the anchor: on the nearest circle to people's
    start that has one, the shortest legal pair, or among the first :data:`WAY_TRIES` legal pairs the first whose
    end has a way round (``way_round``); None when none is legal."""
    size, yaw = world.size, float(start[2])
    d0 = float(np.hypot(*(start[:2] - a))) / size
    radii = np.arange(near_sides + CORNER_STEP[1], d0 + 2.0 + 1e-9, CORNER_STEP[1]) * size
    bearings = np.radians(np.arange(0.0, 360.0, CORNER_STEP[0]))
    r, b = (v.ravel() for v in np.meshgrid(radii, bearings, indexing="ij"))
    corners = np.column_stack([a[0] + r * np.cos(b), a[1] + r * np.sin(b), np.full(len(r), yaw)])
    corners = corners[_segment_distance(start[:2], corners[:, :2], a) > near_sides * size]
    corners = corners[world.moves_free(start, corners)] if len(corners) else corners
    if not len(corners):
        return None
    ends_b = np.radians(np.arange(0.0, 360.0, 10.0))
    rings = approach_radii(approach_sides, near_sides)
    ends = np.vstack([np.column_stack([a[0] + s * size * np.cos(ends_b), a[1] + s * size * np.sin(ends_b),
                                       np.full(len(ends_b), yaw)]) for s in rings])
    ring = np.repeat(np.arange(len(rings)), len(ends_b))
    pairs = []
    for corner in corners:
        first = float(np.hypot(*(corner[:2] - start[:2])))
        free = world.moves_free(corner, ends)
        for end, k in zip(ends[free], ring[free], strict=True):
            pairs.append((int(k), first + float(np.hypot(*(end[:2] - corner[:2]))), corner, end))
    pairs.sort(key=lambda p: p[:2])  # people's start first, as a straight slide's; then the shortest way there
    return _first_way_round(((np.vstack([start[None], segment_frames(start, corner, step),
                                         segment_frames(corner, end, step)]), end) for _, _, corner, end in pairs),
                            wrist, way_round)


def _first_way_round(candidates: Iterable[tuple[np.ndarray, np.ndarray]], wrist: Wrist | None,
                     way_round: Callable[[np.ndarray], bool] | None) -> np.ndarray | None:
    """The first candidate (frames, end) the wrist can follow whose end has a way round; else the first the wrist
    can follow among the first :data:`WAY_TRIES` of them; None when the wrist can follow none."""
    first, tried = None, 0
    for frames, _end in candidates:
        if wrist is not None and not wrist.fits(*wrist.span(frames[:, :2], frames[:, 2])):
            continue
        if way_round is None or way_round(frames):
            return frames
        first = frames if first is None else first
        tried += 1
        if tried >= WAY_TRIES:
            break
    return first


def swept_near(frames: np.ndarray, anchor_xy: np.ndarray, near_m: float) -> float:
    """How far round the anchor (radians, signed, bearings unwrapped) ``frames`` go from their first frame within
    ``near_m`` of it to their last; 0 when none is within. Why: the rule reads "around" from the first frame
    within ``near`` on, so a slide from afar that comes near on one bearing and ends on another has already
    swept (or spent) that much of the turn: a second slide round what is in the way crosses in beside a
    bystander and ends farther round (development chain 9707, "move D around A": a way round 0.9 of a turn from
    the slide's end was none, though one from where it came near was)."""
    p = np.asarray(frames, float).reshape(-1, 3)[:, :2] - np.asarray(anchor_xy, float)[:2]
    inside = np.flatnonzero(np.hypot(*p.T) <= near_m + 1e-9)
    if not len(inside):
        return 0.0
    b = np.unwrap(np.arctan2(p[inside[0]:, 1], p[inside[0]:, 0]))
    return float(b[-1] - b[0])


def _segment_distance(p: np.ndarray, q: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Per segment from ``p`` (2,) to each of ``q`` (N,2): its least distance to the point ``c`` (2,)."""
    d = q - p
    t = np.clip(((c - p) @ d.T) / np.maximum((d * d).sum(1), 1e-18), 0.0, 1.0)
    return np.hypot(*(p + t[:, None] * d - c).T)


__all__ = ["lead_in", "approach_radii", "swept_near", "AIM_OFFSETS_DEG", "RADIUS_STEP", "WAY_TRIES"]
