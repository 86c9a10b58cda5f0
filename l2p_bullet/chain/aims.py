"""Aimed ends: places a clause may leave its mover so that a later clause's room check passes there.

Why: a clause's other end states (ends.py: cuts, other seeds, turns) are blind to what the later clause needs;
where all of them leave the mover where a later clause's room check fails (a block sent past an anchor by the
workspace's rim, then "around" it: ``room-around``), the chain was refused though other places on the same
side of the anchor keep it possible. The later check names what it needs; this module finds the places
nearest the planner's own end that meet it, and the search (forecast.py) tries each first as the straight slide
its judge accepted there (:func:`slide_parts`, ends.py: no search), then plans the clause to it as a target,
and judges the plan as any other end's.

Places are tried on rings round the planner's end (:data:`RINGS_SIDES`, :data:`BEARINGS`), nearest first. A
place is kept when the mover fits there (its centre in the workspace, clear of every other object by the
world's margin, in the scene the clause starts from and in each scene the later checks were made in), the
clause's judge accepts a straight slide to it (from the mover's start, or from where the planner's path came
nearest the anchor: a cheap stand-in for the plan, which is judged itself once planned), and every later
check passes with the mover there (``keeps``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..core.contracts import Plan
from ..core.scene import Scene
from ..judge import plan_verdict
from ..planning.problem import FRAME_STEP
from ..planning.world2d import World2D, segment_frames

RINGS_SIDES = tuple(float(r) for r in np.arange(0.5, 8.01, 0.5))
"""Distances (blocks) from the planner's end of the places tried: the workspace is about 14 blocks across."""
BEARINGS = 24
"""Places per ring (every 15 degrees) from 1.5 blocks out; nearer rings have fewer (8 at half a block, 16 at
one), about a block apart or less."""
AIMS = 2
"""Places returned per clause: each costs the search a plan."""
CHECKS = 96
"""Places at most asked ``keeps`` per clause (nearest first): a later "around"'s check sweeps a grid of poses,
so the time a hopeless aim costs stays bounded."""


def aimed_goals(scene: Scene, mover: str, base: Plan, judge: Any, keeps: Callable[[np.ndarray], bool], *,
                scenes: tuple[Scene, ...] = (), limit: int = AIMS,
                outlines: list[np.ndarray] | None = None) -> list[np.ndarray]:
    """Up to ``limit`` target poses (x, y, yaw: the planner's end's yaw) for ``mover``, nearest ``base``'s end
    first, each one the mover fits at in ``scene`` and ``scenes``, a straight slide to which ``judge`` accepts,
    and at which ``keeps`` (pose -> whether the later clauses' checks pass) holds, among the first
    :data:`CHECKS` such places asked."""
    end = np.asarray(base.path[-1], float)
    size = scene.get(mover).size
    rings = [(r, min(BEARINGS, round(16 * r))) for r in RINGS_SIDES]
    r = np.concatenate([np.full(n, ring * size) for ring, n in rings])
    t = np.concatenate([np.arange(n) * (2 * math.pi / n) for _, n in rings])
    poses = np.column_stack([end[0] + r * np.cos(t), end[1] + r * np.sin(t), np.full(len(r), end[2])])
    fits = np.ones(len(poses), bool)
    for s in (scene, *scenes):
        world = World2D(s, mover)
        fits &= world.inside(poses[:, :2])
        if world.obstacles:
            fits &= world.shortfall(poses, np.full(len(world.obstacles), world.margin), mask=fits) >= 0.0
    starts = _slide_starts(base)
    out: list[np.ndarray] = []
    asked = 0
    for pose in poses[fits]:
        if not slide_accepted(judge, base, pose, size, outlines, starts):
            continue
        asked += 1
        if asked > CHECKS:
            break
        if keeps(pose):
            out.append(pose)
            if len(out) >= limit:
                break
    return out


def slide_accepted(judge: Any, base: Plan, pose: np.ndarray, size: float, outlines: list[np.ndarray] | None = None,
                   starts: list[np.ndarray] | None = None) -> bool:
    """Whether ``judge`` accepts a straight slide to ``pose`` after one of :func:`_slide_starts` (``starts``:
    those of ``base``, computed once by a caller that asks many places): the cheap stand-in for a plan to
    ``pose`` as a target, asked before that search is paid for."""
    return accepted_via(judge, base, pose, size, outlines, starts) is not None


def accepted_via(judge: Any, base: Plan, pose: np.ndarray, size: float, outlines: list[np.ndarray] | None = None,
                 starts: list[np.ndarray] | None = None) -> str | None:
    """Which of :data:`VIAS` the first straight slide to ``pose`` that ``judge`` accepts comes after, or None."""
    starts = _slide_starts(base) if starts is None else starts
    for via, s in zip(VIAS, starts, strict=False):
        if _accepts(judge, base, np.vstack([s, segment_frames(s[-1], pose, FRAME_STEP * size)]), outlines):
            return via
    return None


VIAS = ("start", "nearest")
"""Where a straight slide to an aimed place starts (:func:`slide_parts`): the mover's start, or the end of the
planner's path up to where it came nearest the anchor."""


def slide_parts(base: Plan, pose: np.ndarray, size: float, via: str) -> tuple[np.ndarray, np.ndarray]:
    """``via``'s start of ``base`` (:data:`VIAS`) and the straight slide from its end to ``pose``: the path
    :func:`slide_accepted` judges, in two parts."""
    starts = _slide_starts(base)
    s = starts[min(VIAS.index(via), len(starts) - 1)]
    return s, segment_frames(s[-1], np.asarray(pose, float), FRAME_STEP * size)


def _slide_starts(base: Plan) -> list[np.ndarray]:
    """The paths a straight slide to a place is judged after: the mover's start alone, and the planner's path
    up to where it came nearest the anchor (a pass that must come near it first)."""
    path = np.asarray(base.path, float)
    k = int(np.argmin(np.hypot(*(path[:, :2] - np.asarray(base.anchor_pose, float)[:2]).T)))
    return [path[:1], path[:k + 1]] if k > 0 else [path[:1]]


def _accepts(judge: Any, base: Plan, path: np.ndarray, outlines: list[np.ndarray] | None = None) -> bool:
    return bool(plan_verdict(judge, base, path, outlines=outlines)["success"])
