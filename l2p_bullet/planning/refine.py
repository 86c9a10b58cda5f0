"""A final local refinement of the best plan: small changes to its last move, kept while the learned progress rises.

Why: the searches' proposals are coarse (random moves of about 2 blocks, rings 1.25 blocks from the anchor,
turns of up to 45 degrees). Far from other objects that is what finds a path quickly; close to the anchor
almost all of them collide, and a search that ends its budget short of the threshold there has usually
stopped a fraction of a block from poses the model scores far higher (a "closer" start 1.61 blocks from the
anchor, analysis seed 5002: 0.40 where the search stopped, 0.67 after refining). So
when the search stops short of the threshold, this hill-climbs on the same objective, the action's progress
model on the whole path, with moves on a shrinking local stencil:

- the last waypoint moved by ``scale`` blocks in 8 directions, each with the yaw kept, turned by
  :data:`TURN_PER_BLOCK` x ``scale`` either way, or squared up with the anchor (its faces parallel to the
  anchor's, which lets two squares come face to face);
- the same offsets appended as one more short move from the last waypoint.

A candidate is kept only if it raises the model's progress by more than the search's ``IMPROVE``; the 2-D
world and the wrist judge every candidate exactly as they judge the search's (``problem.children``). The
stencil starts at :data:`SCALES`[0] and shrinks when nothing helps. Each pass is one forward pass of the
model; at most :data:`PASSES`. Only the learned progress decides (a path it rates done that the action's rule
judge rejects is held short of the threshold, as in the search: ``problem.held_short``).
"""

from __future__ import annotations

import time

import numpy as np

from .problem import Node, Problem
from .search import IMPROVE

SCALES = (0.5, 0.25, 0.125)
"""Stencil sizes (blocks), largest first: half a block, then finer (the last about the world's 5 mm margin)."""

TURN_PER_BLOCK = 0.4
"""Radians of turn per block of the stencil's offset (0.2 rad at half a block)."""

PASSES = 12
"""Forward passes the refinement may spend (the mixed planner's default search spends at most 20)."""


def stencil(problem: Problem, pose: np.ndarray, scale: float) -> np.ndarray:
    """End poses near ``pose``: 8 directions x ``scale`` blocks, each with the yaw kept, turned either way, and
    squared up with the anchor; (32, 3)."""
    ang = np.arange(8) * np.pi / 4
    step = scale * problem.size
    xy = pose[:2] + step * np.column_stack([np.cos(ang), np.sin(ang)])
    quarter = np.pi / 2
    square = pose[2] + ((problem.anchor_pose[2] - pose[2] + quarter / 2) % quarter - quarter / 2)
    turn = TURN_PER_BLOCK * scale
    yaws = (pose[2], pose[2] + turn, pose[2] - turn, square)
    return np.vstack([np.column_stack([xy, np.full(8, y)]) for y in yaws])


def refine(problem: Problem, node: Node, passes: int = PASSES) -> tuple[Node, int]:
    """Hill-climb ``node``'s last move on the learned progress (module docstring): (best node, passes spent).

    The root (a plan that never moved) is returned unchanged: there is no last move to refine.
    """
    if node.parent is None:
        return node, 0
    spent, level = 0, 0
    while (
        spent < passes and level < len(SCALES) and (problem.deadline is None or time.perf_counter() < problem.deadline)
    ):
        scale = SCALES[level]
        moved = stencil(problem, node.pose, scale)
        kids = problem.children([node.parent, node], [moved, moved])
        spent += 1
        top = max(kids, key=lambda k: k.progress, default=None)
        if top is not None and top.progress > node.progress + IMPROVE:
            node = top  # keep the scale: a slope found is climbed further at the same step
        else:
            level += 1
    return node, spent
