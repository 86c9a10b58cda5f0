"""Where the next move could go: the proposal distributions the searches draw candidates from.

- ``random_moves``: the paper's continuous space, a Gaussian around the mover's pose in x, y and
  rotation (the baseline knows nothing about the action or the anchor);
- ``discrete_moves``: the paper's qualitative space, cardinal direction x quantised distance **around the
  anchor**, in the anchor's own frame (so "east of B at 1.25 blocks" is face to face with B). It is a
  small fixed set, so a step costs one forward pass over about 40 paths. A viewer-frame action adds the
  same rings in the viewer's frame (left, in front, ... of B exactly as the viewer sees them), a
  two-anchor action cells along and beside the segment between its anchors and the rings of its second;
- the learned policy's proposals live in ``policy.py``.

Every proposal keeps rotations moderate (at most ``MAX_TURN`` per move); illegal ones (colliding,
leaving the workspace) are dropped later by the 2-D simulator, not here.
"""

from __future__ import annotations

import numpy as np

from .problem import MAX_TURN, Node, Problem

STEP_STD = 2.0
"""Standard deviation (block sizes) of a random move's x and y."""

TURN_STD = 0.3
"""Standard deviation (radians) of a random move's rotation."""

DIRECTIONS = 8
"""Cardinal and intercardinal directions around the anchor (E, NE, N, ... in the anchor's frame)."""

DISTANCES = (1.25, 1.75, 2.5, 3.5, 5.0, 6.5)
"""Quantised centre distances from the anchor, in block sizes (1.25 = face to face with a small gap; the
outer rings only exist where the workspace reaches, which is what "away" needs)."""


def random_moves(problem: Problem, node: Node, n: int) -> np.ndarray:
    """``n`` end poses drawn from a Gaussian around the current pose (the paper's random search)."""
    d = problem.rng.normal(0.0, 1.0, size=(n, 3)) * np.array([STEP_STD * problem.size] * 2 + [TURN_STD])
    d[:, 2] = np.clip(d[:, 2], -MAX_TURN, MAX_TURN)
    return node.pose + d


def _rings(centre: np.ndarray, angle0: float, size: float) -> np.ndarray:
    """DIRECTIONS x DISTANCES cells (x, y) around ``centre``, the first direction at ``angle0``."""
    ang = angle0 + 2 * np.pi * np.arange(DIRECTIONS) / DIRECTIONS
    dist = np.asarray(DISTANCES) * size
    xy = centre[:2] + dist[None, :, None] * np.stack([np.cos(ang), np.sin(ang)], -1)[:, None, :]
    return xy.reshape(-1, 2)


SEGMENT_T = (0.25, 0.5, 0.75)
"""Where along the segment between two anchors the two-anchor cells lie (0 = the first anchor)."""

SEGMENT_OFFSETS = (0.0, 1.25, -1.25, 2.5, -2.5)
"""Their offsets across the segment, in block sizes."""


def discrete_targets(problem: Problem) -> np.ndarray:
    """All (direction, distance) cells around the anchor as mover poses' x, y: (DIRECTIONS*len(DISTANCES), 2),
    then a viewer-frame action's rings in the viewer's frame and a two-anchor action's segment cells and
    rings around its second anchor (see the module docstring)."""
    a = problem.anchor_pose
    cells = [_rings(a, a[2], problem.size)]
    if problem.viewer is not None:
        sight = a[:2] - np.asarray(problem.viewer, float)[:2]
        cells.append(_rings(a, float(np.arctan2(sight[1], sight[0])), problem.size))
    for c in problem.more_anchor_poses:
        e = np.asarray(c, float)[:2] - a[:2]
        n = np.array([-e[1], e[0]]) / max(float(np.linalg.norm(e)), 1e-9)
        cells.append(np.array([a[:2] + t * e + k * problem.size * n for t in SEGMENT_T for k in SEGMENT_OFFSETS]))
        cells.append(_rings(np.asarray(c, float), float(c[2]), problem.size))
    return np.concatenate(cells)


def _discrete_moves(problem: Problem, node: Node, n: int = 0, squared_within: float = np.inf) -> np.ndarray:
    """Every cell of the discrete space keeping the mover's yaw, and again squared up with the anchor.

    ``n`` is ignored (the set is fixed). ``squared_within`` (blocks) limits the squared-up copies to the
    inner rings, where alignment matters (face to face); cells the mover stands in are dropped.
    """
    xy = discrete_targets(problem)
    xy = xy[np.hypot(*(xy - node.pose[:2]).T) > 0.25 * problem.size]
    quarter = np.pi / 2
    square = node.pose[2] + ((problem.anchor_pose[2] - node.pose[2] + quarter / 2) % quarter - quarter / 2)
    inner = xy[np.hypot(*(xy - problem.anchor_pose[:2]).T) <= squared_within * problem.size + 1e-9]
    out = np.empty((len(xy) + len(inner), 3))
    out[:, :2] = np.vstack([xy, inner])
    out[: len(xy), 2] = node.pose[2]
    out[len(xy):, 2] = square
    return out


_discrete_moves.deterministic = True  # type: ignore[attr-defined]
discrete_moves = _discrete_moves


ARC_STEPS_DEG = (20.0, 40.0, 60.0, 90.0)
"""Bearing steps (degrees, both ways round) of the short arcs proposed among bystanders (:func:`arc_moves`)."""

ARC_RADII = (1.25, 1.5, 1.75, 2.25, 2.75, 3.5)
"""Centre distances from the anchor (block sizes) the short arcs end at: a polar lattice fine enough to pass
between two blocks standing two block sizes apart (the closest :mod:`evaluate.scenes` places bystanders)."""


def arc_moves(problem: Problem, node: Node, n: int = 0) -> np.ndarray:
    """Short steps around the anchor: from the mover's bearing, :data:`ARC_STEPS_DEG` either way at each of
    :data:`ARC_RADII`, keeping the yaw and again turned with the bearing (modulo a quarter turn, so the wrist
    swings back and forth instead of winding up).

    Why: the discrete rings are 45 degrees apart, so a way round the anchor is a chain of long chords, and
    a bystander near the anchor blocks some of them; then "around" (or "past") stalls part of the way
    (0.26-0.76 of a turn). Shorter steps at several radii pass between the anchor and a bystander, or
    outside it, wherever the 2-D world finds room. ``n`` is ignored (the set is fixed for a node).
    """
    a = problem.anchor_pose
    rel = node.pose[:2] - a[:2]
    b0 = float(np.arctan2(rel[1], rel[0]))
    steps = np.radians(np.asarray(ARC_STEPS_DEG))
    delta = np.concatenate([steps, -steps])
    radii = np.asarray(ARC_RADII) * problem.size
    d, r = np.meshgrid(delta, radii, indexing="ij")
    d, r = d.ravel(), r.ravel()
    xy = a[:2] + r[:, None] * np.column_stack([np.cos(b0 + d), np.sin(b0 + d)])
    quarter = np.pi / 2
    turn = (d + quarter / 2) % quarter - quarter / 2
    out = np.empty((2 * len(d), 3))
    out[:, :2] = np.vstack([xy, xy])
    out[: len(d), 2] = node.pose[2]
    out[len(d):, 2] = node.pose[2] + turn
    return out


class MixedProposer:
    """The discrete cells, the policy's proposals (when the bundle has a policy) and random moves, together.

    Each source covers another's blind spot: the cells reach exact places around the anchor (face to face,
    the far side), the policy proposes the moves that paid off in training, random moves fill the gaps
    between cells. The model still decides, in one forward pass over all of them.
    """

    deterministic = False

    def __init__(self, policy=None, random_share: int = 16, arcs: bool = False, route: np.ndarray | None = None):
        self.policy = policy
        self.random_share = random_share
        self.arcs = arcs  # also the short arcs around the anchor (planning.plan: where bystanders stand)
        self.route = route  # also the corners of a way round the anchor (detour.py), from every node

    def __call__(self, problem: Problem, node: Node, n: int) -> np.ndarray:
        parts = [discrete_moves(problem, node, squared_within=1.75), random_moves(problem, node, self.random_share)]
        if self.policy is not None:
            parts.append(self.policy(problem, node, n))
        if self.arcs:
            parts.append(arc_moves(problem, node))
        if self.route is not None:
            parts.append(self.route[1:])
        return np.vstack(parts)
