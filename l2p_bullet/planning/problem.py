"""What every planner shares: the problem, the search node, batched scoring and the finished plan.

A planner grows a path of straight moves from the mover's start. A search node is such a path (its
waypoints and its frames); a child appends one move. Children are judged by the action's learned progress
model on the whole path so far (the model reads history: "around" is only progress if the earlier moves
went round too), and all children of a step are scored in **one** ``final_batch`` call.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from ..arms.reach import Wrist
from ..core.contracts import Plan
from ..core.geometry import wrap_angle
from .world2d import World2D, segment_frames

FRAME_STEP = 0.25
"""Frames are spaced this many block sizes apart along a move (the progress models' arc-length grid)."""

MAX_TURN = np.pi / 4
"""Largest rotation of the mover in one move (radians): moderate, so the arm's wrist follows comfortably,
and just enough to square a block up with any other (a square's yaw matters modulo a quarter turn)."""


class ProgressScorer(Protocol):
    """The part of a learned ProgressModel the planners use (see docs/INTERFACES.md, Learning).

    ``context`` (``more_anchors``, ``viewer``) is only passed for actions that declare a second anchor or
    a viewer frame (:attr:`Problem.context`), so a scorer of relative one-anchor actions may ignore it;
    ``outlines`` only to a scorer that sets ``reads_outlines = True``, where an object is not a cube.
    """

    def final_batch(self, movers: list[np.ndarray], anchors: object, size: float, **context) -> np.ndarray: ...

    def curve(self, mover: np.ndarray, anchor: np.ndarray, size: float, **context) -> np.ndarray: ...


@dataclass
class Node:
    """A path of straight moves: ``waypoints`` (n,3), its frames (T,3) and the model's final progress.

    ``yaw`` is the mover's yaw at the end, unwrapped along the path (the frames' yaws are wrapped);
    ``wrist`` the range of :func:`~l2p_bullet.arms.reach.wrist_values` over the frames so far.
    """

    waypoints: np.ndarray
    frames: np.ndarray
    progress: float
    parent: Node | None = None
    dead: list[np.ndarray] = field(default_factory=list)  # ends already backed up from (greedy search)
    yaw: float = 0.0
    wrist: tuple[float, float] = (0.0, 0.0)

    @property
    def pose(self) -> np.ndarray:
        return self.waypoints[-1]

    @property
    def moves(self) -> int:
        return len(self.waypoints) - 1


@dataclass
class Problem:
    """One planning problem: the world, the action's model, the anchor and the stopping rules."""

    world: World2D
    model: ProgressScorer
    anchor_pose: np.ndarray
    size: float
    threshold: float
    budget: int
    rng: np.random.Generator
    max_moves: int = 12
    evaluations: int = 0
    forward_passes: int = 0
    started: float = field(default_factory=time.perf_counter)
    deadline: float | None = None  # perf_counter time after which the search stops (equal-time runs)
    wrist: Wrist | None = None  # the arm's wrist range: paths no grasp yaw can follow are illegal
    more_anchor_poses: list[np.ndarray] = field(default_factory=list)  # a two-anchor action's second anchor
    viewer: np.ndarray | None = None  # (2,) the viewpoint of a viewer-frame action (scene frame, metres)
    # (T0,3) frames of the straight slide (or two, round what is in the way) from the mover's start that comes
    # before the action (approach.py: "around" from afar): every node starts with it, and the model scores only
    # what follows its last frame
    lead_in: np.ndarray | None = None
    # metres from the anchor that no move may end beyond ("around": as far as people went round, planning/__init__)
    reach: float | None = None
    # a deterministic bound on the search's work (planning.CHECK_CAP): it takes no step once ``children`` has
    # been asked about this many candidate moves (each tested for legality, the legal ones scored)
    check_cap: int | None = None
    checked: int = 0  # candidate moves proposed to ``children`` so far
    bounded: bool = False  # the cap ended the search (it would have gone on)
    # the objects' real footprints (judge/footprints.py outlines_of) for a model that reads them, where one
    # is not a cube; None: the model reads unit squares, as it was trained
    outlines: list[np.ndarray] | None = None
    # whether the rule judge accepts a path's frames (the lead-in included): a path the model rates done but the
    # rule rejects does not end the search (:func:`held_short`); None: the model alone says when it is done
    accepts: Callable[[np.ndarray], bool] | None = None
    _lead_moves: int | None = field(default=None, repr=False)  # lead_moves, counted once

    @property
    def context(self) -> dict:
        """What the model reads besides the mover and the anchor (empty for a relative one-anchor action among
        cubes)."""
        kw: dict = {}
        if self.more_anchor_poses:
            kw["more_anchors"] = list(self.more_anchor_poses)
        if self.viewer is not None:
            kw["viewer"] = self.viewer
        if self.outlines is not None:
            kw["outlines"] = self.outlines
        return kw

    def go_on(self, best: Node, steps: int) -> bool:
        """Whether the search may take another step."""
        if best.progress >= self.threshold or steps >= self.budget:
            return False
        if self.check_cap is not None and self.checked >= self.check_cap:
            self.bounded = True
            return False
        return self.deadline is None or time.perf_counter() < self.deadline

    @property
    def step(self) -> float:
        return FRAME_STEP * self.size

    @property
    def lead(self) -> int:
        """Frames of a node's path before the part the model scores (0 without a lead-in)."""
        return 0 if self.lead_in is None else len(self.lead_in) - 1

    @property
    def lead_moves(self) -> int:
        """Moves of a node's path before the action's own (the lead-in's straight slides, or none)."""
        if self.lead_in is None:
            return 0
        if self._lead_moves is None:
            self._lead_moves = len(lead_corners(self.lead_in)) - 1
        return self._lead_moves

    def root(self) -> Node:
        start = self.world.mover.pose.copy()
        frames = start[None].copy() if self.lead_in is None else np.asarray(self.lead_in, float).copy()
        waypoints = start[None].copy() if self.lead_in is None else lead_corners(frames)
        p = float(self.model.final_batch([frames[self.lead:]], self.anchor_pose, self.size, **self.context)[0])
        p = self.judged(frames, p)
        self.forward_passes += 1
        wrist = self.wrist.span(frames[:, :2], frames[:, 2]) if self.wrist is not None else (0.0, 0.0)
        return Node(waypoints, frames, p, yaw=float(frames[-1, 2]), wrist=wrist)

    def children(self, parents: list[Node], ends: list[np.ndarray]) -> list[Node]:
        """Legal children of each parent (ends[i] (Mi,3) proposed for parents[i]), scored in one pass."""
        kids: list[Node] = []
        self.checked += sum(np.size(e) // 3 for e in ends)
        for node, e in zip(parents, ends, strict=True):
            if len(e) == 0 or node.moves - self.lead_moves >= self.max_moves:
                continue
            e = np.asarray(e, float).reshape(-1, 3)
            if node.dead:
                dead = np.asarray(node.dead)
                gap = np.abs(e[:, None, :] - dead[None]).max(-1).min(1)
                e = e[gap > 1e-6]
            if self.reach is not None:  # a disk is convex: every straight move between ends inside stays inside
                e = e[np.hypot(*(e[:, :2] - self.anchor_pose[:2]).T) <= self.reach]
            for end in e[self.world.moves_free(node.pose, e)]:
                seg = segment_frames(node.pose, end, self.step)
                yaws = node.yaw + np.cumsum(wrap_angle(np.diff(np.r_[node.pose[2], seg[:, 2]])))
                wrist = node.wrist
                if self.wrist is not None:
                    wrist = self.wrist.span(seg[:, :2], yaws, wrist)
                    if not self.wrist.fits(*wrist):
                        continue  # no grasp yaw keeps the wrist in range over this path
                kids.append(Node(np.vstack([node.waypoints, end]), np.vstack([node.frames, seg]), 0.0, node,
                                 yaw=float(yaws[-1]), wrist=wrist))
        if kids:
            scores = np.asarray(self.model.final_batch([k.frames[self.lead:] for k in kids], self.anchor_pose,
                                                       self.size, **self.context))
            self.forward_passes += 1
            self.evaluations += len(kids)
            for k, s in zip(kids, scores, strict=True):
                k.progress = self.judged(k.frames, float(s))
        return kids

    def judged(self, frames: np.ndarray, progress: float) -> float:
        """``progress`` of the path ``frames``, held short of the threshold where it reaches it but the rule
        judge rejects the path (:func:`held_short`); the model's own everywhere else."""
        if self.accepts is None or progress < self.threshold or self.accepts(frames):
            return progress
        return held_short(progress, self.threshold)


def lead_corners(frames: np.ndarray) -> np.ndarray:
    """The waypoints of a lead-in's frames: its start, each frame where its heading turns, its end (a straight
    slide: its two ends; a slide round what is in the way, approach.py: its corner too)."""
    frames = np.asarray(frames, float)
    d = np.diff(frames[:, :2], axis=0)
    sine = (d[:-1, 0] * d[1:, 1] - d[:-1, 1] * d[1:, 0]) / np.maximum(np.hypot(*d[:-1].T) * np.hypot(*d[1:].T), 1e-18)
    turn = np.abs(sine) > 1e-6
    return np.vstack([frames[:1], frames[1:-1][turn], frames[-1:]])


HELD = 0.99
"""A path the model rates done but the rule judge rejects scores ``HELD * threshold * min(progress, 1)``: below the
threshold, so the search goes on, and in the model's order among such paths, so the search still climbs from the
nearest to done (a "past" a few millimetres short of its margin, a "closer" that closed a little less than its
share). Why: a search that stops at the model's first "done" hands on a plan its own rule fails: 9 of the 24
clauses that ran and failed in the chains of seeds 21000-21409 were such plans (docs/benchmarks.md)."""


def held_short(progress: float, threshold: float) -> float:
    """The score of a path rated ``progress`` (at least ``threshold``) that the rule judge rejects (:data:`HELD`)."""
    return HELD * threshold * min(progress, 1.0)


Proposer = Callable[[Problem, Node, int], np.ndarray]
"""A proposal distribution: (problem, node, how many) -> candidate end poses (M,3) of the next move."""


def finish(problem: Problem, node: Node, *, action: str, mover: str, anchor: str, planner: str,
           stopped: str, steps: int, more_anchors: list[str] | None = None) -> Plan:
    """The plan.json of the best node: frames as the path, the model's curve as per-point progress."""
    path = node.frames
    scored = path[problem.lead:]
    progress = np.asarray(problem.model.curve(scored, problem.anchor_pose, problem.size, **problem.context),
                          float).reshape(-1)
    if len(progress) != len(scored):  # a model that resamples internally: spread its curve over the frames
        progress = np.interp(np.linspace(0, 1, len(scored)), np.linspace(0, 1, max(len(progress), 1)), progress)
    progress = np.r_[np.full(problem.lead, progress[0]), progress]  # the lead-in holds the action's first value
    return Plan(
        action=action, mover=mover, anchor=anchor, size=problem.size,
        anchor_pose=np.asarray(problem.anchor_pose, float), start=path[0].copy(), path=path,
        progress=progress, planner=planner, stopped=stopped,
        extra={
            "final_progress": round(float(node.progress), 6),
            "waypoints": np.asarray(node.waypoints, float).round(6).tolist(),
            "steps": steps,
            "evaluations": problem.evaluations,
            "forward_passes": problem.forward_passes,
            "threshold": problem.threshold,
            "budget": problem.budget,
            "seconds": round(time.perf_counter() - problem.started, 4),
        },
        more_anchors=list(more_anchors or []),
        more_anchor_poses=np.array(problem.more_anchor_poses, float).reshape(-1, 3) if more_anchors else None,
        viewer=problem.viewer,
    )

