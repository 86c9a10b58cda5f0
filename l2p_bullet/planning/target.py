"""A place the mover must end at, given to the planner by a composite action (a row's next slot).

The learned single action still plans: every candidate is scored by its progress model, and the plan is
the path the model rates best. The target only says *which* of the many places that satisfy the action is
wanted ("next to A" has a whole ring of them; the row needs the one on its axis): the score of a
candidate is the model's final progress times :func:`closeness` of its end to the target, and the target
itself (turned as close to the mover's yaw as the square allows) is proposed from every node, so the
search can reach it exactly when a straight move is free, or through the moves around an obstacle.
A target the model does not rate as the action (progress below the threshold there) keeps the search
going to its budget, and the plan's ``final_progress`` says so.
"""

from __future__ import annotations

from typing import Any

import numpy as np

SCALE_SIDES = 1.0
"""Distance from the target (block sides) at which a candidate's score is multiplied by 1/e. Exponential,
not Gaussian: a mover that cannot reach the target in one move (a block in the way) still sees every
step towards it pay; and the threshold (0.9) is only reached within a few millimetres of it."""


YAW_SCALE = 0.5
"""Turn from the target's yaw (radians, modulo a quarter turn) at which the score is multiplied by 1/e."""

AT_TARGET = (0.001, 0.02)
"""Within this distance (m) and turn (rad) of the target an end *is* the target; any other end's score is
multiplied by :data:`SHORT` (0.95), so that only a path that really ends there reaches the threshold."""
SHORT = 0.95


def closeness(ends: np.ndarray, target: np.ndarray, size: float) -> np.ndarray:
    """Per end pose (M, 3): exp(-d / (SCALE_SIDES * size) - |turn| / YAW_SCALE), d the centre's distance to
    the target and turn its yaw's difference from the target's modulo a quarter turn, times SHORT unless
    the end is at the target (:data:`AT_TARGET`)."""
    e, t = np.asarray(ends, float).reshape(-1, 3), np.asarray(target, float)
    d = np.hypot(*(e[:, :2] - t[:2]).T)
    turn = np.abs((e[:, 2] - t[2] + np.pi / 4) % (np.pi / 2) - np.pi / 4)
    at = (d <= AT_TARGET[0]) & (turn <= AT_TARGET[1])
    return np.exp(-d / (SCALE_SIDES * size) - turn / YAW_SCALE) * np.where(at, 1.0, SHORT)


LOOKAHEAD = (0.85, 0.8)
"""A candidate from which a straight, legal move reaches the target scores the model's final progress of
its path continued to the target, times the first (below the threshold's 0.9: only a path that really
ends at the target can stop the search); one from which a legal move reaches an approach point that has
a legal move to the target (a *gate*, :func:`approach_points`), its path continued through the gate,
times the second. Without it, greedy search stalls short of a target hidden behind blocks: the points on
the way are rated low by the model and by their distance."""


def approach_points(target: np.ndarray, size: float) -> np.ndarray:
    """(16, 3) points on two rings (:data:`RING_SIDES`) around ``target``, square to its faces and diagonal,
    turned like it."""
    t = np.asarray(target, float)
    a = t[2] + np.arange(8) * np.pi / 4  # square to the target's faces: a slot between two blocks is entered straight
    return np.vstack([np.column_stack([t[0] + r * size * np.cos(a), t[1] + r * size * np.sin(a), np.full(8, t[2])])
                      for r in RING_SIDES])


class TargetScorer:
    """The action's progress model with its final progress weighted by the end's closeness to ``target``
    (or, one move short of it, the progress of going on to it: :data:`LOOKAHEAD`); the per-frame ``curve``
    (what the plan and the video show) stays the model's own. ``world`` (planning.world2d.World2D) says
    which moves are legal; ``step`` is the planner's frame spacing (m)."""

    def __init__(self, model: Any, target: np.ndarray, world: Any = None, step: float = 0.0):
        self.model, self.target, self.world, self.step = model, np.asarray(target, float), world, step
        self.gates = np.zeros((0, 3))
        if world is not None:
            pts = approach_points(self.target, world.size)
            ok = [not world.overlaps(q) and bool(world.moves_free(q, self.target[None])[0]) for q in pts]
            self.gates = pts[np.array(ok, bool)]

    def __getattr__(self, name: str) -> Any:  # anchors, viewpoint... as the model declares them
        return getattr(self.model, name)

    def final_batch(self, movers: list[np.ndarray], anchors: Any, size: float, **context) -> np.ndarray:
        ends = np.array([np.asarray(m)[-1] for m in movers]).reshape(-1, 3)
        near = closeness(ends, self.target, size)
        more = []  # (index, factor, the path continued to the target)
        if self.world is not None and self.step > 0:
            from .world2d import segment_frames

            for i, (m, e) in enumerate(zip(movers, ends, strict=True)):
                if near[i] > 0.99:  # at the target already
                    continue
                turn = np.round((e[2] - self.target[2]) / (np.pi / 2)) * (np.pi / 2)
                t = self.target + [0.0, 0.0, turn]
                if self.world.moves_free(e, t[None])[0]:
                    more.append((i, LOOKAHEAD[0], np.vstack([np.asarray(m), segment_frames(e, t, self.step)])))
                elif len(self.gates):
                    gates = self.gates + [0.0, 0.0, turn]
                    free = np.flatnonzero(self.world.moves_free(e, gates))
                    if len(free):
                        g = gates[free[np.argmin(np.hypot(*(gates[free, :2] - e[:2]).T))]]
                        more.append((i, LOOKAHEAD[1], np.vstack([np.asarray(m), segment_frames(e, g, self.step),
                                                                 segment_frames(g, t, self.step)])))
        p = np.asarray(self.model.final_batch(list(movers) + [x for *_, x in more], anchors, size, **context), float)
        score = p[: len(movers)] * near
        for (i, f, _), q in zip(more, p[len(movers):], strict=True):
            score[i] = max(score[i], f * q)
        return score

    def curve(self, mover: np.ndarray, anchor: np.ndarray, size: float, **context) -> np.ndarray:
        return self.model.curve(mover, anchor, size, **context)


RING_SIDES = (1.5, 2.5)
"""Radii (block sides) of the rings of approach points proposed around the target (8 on each, square to
its faces and diagonal): when a block stands between the mover and the target, one of them is a way round
it, and a slot between two blocks is entered face-on."""


class TargetProposer:
    """Another proposer's candidates plus the target, turned by the multiple of 90 degrees nearest the
    node's yaw (a square looks the same every quarter turn; the wrist is spared the rest), and rings of
    approach points around it."""

    def __init__(self, base: Any, target: np.ndarray):
        self.base, self.target = base, np.asarray(target, float)
        self.deterministic = getattr(base, "deterministic", False)

    def __call__(self, problem: Any, node: Any, n: int) -> np.ndarray:
        t = self.target.copy()
        t[2] += np.round((node.pose[2] - t[2]) / (np.pi / 2)) * (np.pi / 2)
        ring = approach_points(t, problem.size)
        return np.vstack([np.asarray(self.base(problem, node, n), float).reshape(-1, 3), t[None], ring])
