"""The 2-D simulator the planners move blocks in: polygons, swept-move collision, frames.

Why a separate 2-D world: planning needs thousands of "would this move be legal, and what does the
motion look like?" questions per second; PyBullet answers them a thousand times slower and is only needed
once the path is fixed.

Rules of the world (the same ones the arm obeys when it executes the path):

- Every object is a convex polygon (its footprint from ``scene.py``) with a transform ``[x, y, yaw]``.
- The mover slides in straight moves, translating and rotating linearly. A move is rejected when its
  **swept area** overlaps another object inflated by :data:`~l2p_bullet.core.scene.GRIPPER_MARGIN`. The arm
  grasps from above with closed fingers resting on the block's top, so nothing of it reaches down beside
  the block to the height of a block no taller than the mover; against a taller object the mover's
  outline is grown by what the hand puts at that object's height (``outlines``, from
  :func:`l2p_bullet.arms.reach.hold_outlines`).
- A mover that starts closer than the margin to an object (blocks placed touching) may still move, as
  long as no move brings it closer to that object than it was where the move began: the margin of a move
  is the smaller of the margin and the gap at its start.
- One obstacle may be given a smaller margin (:meth:`World2D.nearer_to`): the anchor a "closer" ends face to
  face with, where nothing of the hand comes between the two (``planning/nearer.py``).
- A move is rejected when the grasp point (the mover's centre) leaves the workspace, the region the arm
  reaches pointing down (``core/workspace.py``). The disk is convex, so for it checking a straight move's
  end points suffices; an arm whose reach ring bites into the disk (the KUKA iiwa's) makes the
  region non-convex, and a move must also keep its closest approach to the arm's base outside the ring's
  hole (``Workspace.segments_inside``).
- A pushed block (``pusher``, l2p_bullet/manners) has the closed fingers behind it along each move, never
  beside or ahead of it: each sub-pose of a move has the pusher's rectangle behind the block's face opposite
  the travel (tested as its own polygon), so a block may be pushed right up to another ("closer", "next to")
  while a move away from a block it touches needs room for the fingers between them.
- Moves are interpolated at a given speed into frames (one frame every ``step`` metres of travel, or
  every ``rot_step`` radians of turn, whichever needs more), so a path can be scored by a progress
  model that reads pose sequences.

The swept area of a move is covered by the convex hulls of consecutive sub-poses (sub-steps turn at
most 0.1 rad, where a corner's arc bulges past the hull by under 0.1 mm for a 5 cm block). A separating
axis found among the sub-poses' edge normals, the obstacle's edge normals and the normal of the travel
direction proves the move free; none found counts as a collision (conservative).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np

from ..core.geometry import edge_normals, posed_separation, separation, wrap_angle
from ..core.scene import GRIPPER_MARGIN, Scene

SUB_ROTATION = 0.1
"""Largest turn (radians) between two sub-poses of the swept-area test."""


@dataclass(frozen=True)
class Body:
    """A convex polygon with a transform: ``outline`` is the unit-pose outline (K,2), counter-clockwise."""

    name: str
    outline: np.ndarray
    pose: np.ndarray  # [x, y, yaw]

    def polygon(self, poses: np.ndarray | None = None) -> np.ndarray:
        """The outline placed at ``poses`` ((3,) -> (K,2); (N,3) -> (N,K,2)); default: its own pose."""
        p = self.pose if poses is None else np.asarray(poses, float)
        return place_outline(self.outline, p)


def place_outline(outline: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """Rotate and translate ``outline`` (K,2) to each pose ((3,) or (N,3)); vectorised."""
    poses = np.asarray(poses, float)
    single = poses.ndim == 1
    p = poses.reshape(-1, 3)
    c, s = np.cos(p[:, 2]), np.sin(p[:, 2])
    x = outline[None, :, 0] * c[:, None] - outline[None, :, 1] * s[:, None] + p[:, None, 0]
    y = outline[None, :, 0] * s[:, None] + outline[None, :, 1] * c[:, None] + p[:, None, 1]
    out = np.stack([x, y], axis=-1)
    return out[0] if single else out


class World2D:
    """The mover and its obstacles taken from a scene; answers legality questions in batches.

    ``outlines`` maps an obstacle's name to the mover's outline (block frame) to test against it: the block
    grown by the hand beside it at that obstacle's height. Obstacles not named use the block's footprint.
    ``over`` (a carried block, l2p_bullet/manners): the objects it passes above, so a move is tested against
    them only where it ends (where the block could be set down), not along the way. ``pusher`` (a pushed
    block): the pushing fingers' depth along the push (m, from the block's face back, the gap it comes down
    at included) and half width across it; every move is tested with them behind the block.
    """

    def __init__(self, scene: Scene, mover: str, margin: float = GRIPPER_MARGIN,
                 outlines: dict[str, np.ndarray] | None = None, over: frozenset[str] = frozenset(),
                 pusher: tuple[float, float] | None = None):
        obj = scene.get(mover)
        self.scene = scene
        self.mover = Body(mover, obj.footprint(np.zeros(3)), obj.pose)
        self.size = obj.size
        self.margin = margin
        self.obstacles = [Body(o.name, o.footprint(np.zeros(3)), o.pose) for o in scene.objects if o.name != mover]
        self._margins = np.full(len(self.obstacles), margin)  # per obstacle: the world's unless nearer_to says
        outlines = outlines or {}
        self._outlines = [np.asarray(outlines.get(b.name, self.mover.outline), float) for b in self.obstacles]
        self._obs_polys = [b.polygon() for b in self.obstacles]
        self._obs_normals = [edge_normals(p) for p in self._obs_polys]
        self._obs_centres = np.array([b.pose[:2] for b in self.obstacles]).reshape(-1, 2)
        self._obs_radii = np.array([np.linalg.norm(b.outline, axis=1).max() for b in self.obstacles])
        self._mover_radii = np.array([np.linalg.norm(o, axis=1).max() for o in self._outlines])
        self.pusher = None if pusher is None else (float(pusher[0]), float(pusher[1]))
        if self.pusher is not None:  # the pusher's far corners reach beyond the block's
            depth, half = self.pusher
            self._mover_radii = np.hypot(self._mover_radii + depth, half)
        # obstacles grouped by the mover outline they are tested against (most share the block's own)
        groups: dict[bytes, list[int]] = {}
        for i, o in enumerate(self._outlines):
            groups.setdefault(o.tobytes() + bytes(str(o.shape), "ascii"), []).append(i)
        self._groups = list(groups.values())
        self._over = np.array([b.name in over for b in self.obstacles], bool)
        ws = scene.workspace
        self.workspace = ws
        self.center = np.array(ws.center, float)
        self.radius = float(ws.radius)  # the disk's, ring or not (the policy's features use FEATURE_RADIUS, policy.py)

    # --- legality -------------------------------------------------------------------------------
    def inside(self, xy: np.ndarray) -> np.ndarray:
        """Per point (..., 2): the grasp point lies in the workspace."""
        xy = np.asarray(xy, float)
        return self.workspace.contains(xy).reshape(xy.shape[:-1])

    def gaps(self, pose: np.ndarray) -> np.ndarray:
        """The mover's gap (m, separating-axis) to each obstacle at ``pose``, with that obstacle's outline."""
        pose = np.asarray(pose, float)
        return np.array([float(separation(place_outline(o, pose)[None], p)[0])
                         for o, p in zip(self._outlines, self._obs_polys, strict=True)])

    def start_margins(self, less: float = 0.0) -> np.ndarray:
        """Per obstacle, the margin a pose of the mover must keep from it: the world's, or the gap where the mover
        starts when that is smaller (a close start may stay as close, never come closer), ``less`` taken off
        that gap (the way round takes 1e-9 off, so that its start cell passes)."""
        return np.minimum(self._margins, np.maximum(self.gaps(self.mover.pose), 0.0) - less)

    def margin_to(self, name: str) -> float:
        """The margin (m) the mover keeps from the obstacle ``name`` (the world's, unless :meth:`nearer_to`)."""
        return float(self._margins[self._index(name)])

    def outline_against(self, name: str) -> np.ndarray:
        """The mover's outline (block frame) tested against the obstacle ``name``: the block grown by what the
        hand puts at that obstacle's height, or the block's own."""
        return self._outlines[self._index(name)]

    def _index(self, name: str) -> int:
        return [b.name for b in self.obstacles].index(name)

    def nearer_to(self, name: str, margin: float) -> World2D:
        """A copy of this world in which the mover may come to ``margin`` (m) of the obstacle ``name`` instead of
        the world's margin: where the mover meets that obstacle with a bare face, nothing of the hand between
        (``planning/nearer.py`` decides where). Every other obstacle keeps its margin."""
        out = copy.copy(self)
        out._margins = np.where([b.name == name for b in self.obstacles], margin, self._margins)
        return out

    def shortfall(self, poses: np.ndarray, margins: np.ndarray, mask: np.ndarray | None = None,
                  within: float | None = None) -> np.ndarray:
        """Per pose (N,3, each at its own yaw): the least, over the obstacles, of the mover's gap (with that
        obstacle's outline) minus the margin it must keep there (``margins``: :meth:`start_margins`); >= 0 is
        legal among the obstacles, +inf where none was tested. ``mask`` and ``within`` (m) spare the work: only
        the poses in ``mask`` whose centre lies within the two outlines' reaches plus the margin plus ``within``
        of an obstacle's centre are tested against it (a pose farther away is farther than ``within`` from it).
        One place for what the up-front sweep, its refinement and the way round each wrote out (sweep.py,
        detour.py)."""
        poses = np.asarray(poses, float).reshape(-1, 3)
        short = np.full(len(poses), np.inf)
        for i, (outline, poly, margin) in enumerate(zip(self._outlines, self._obs_polys, margins, strict=True)):
            if within is None and mask is None:
                short = np.minimum(short, posed_separation(outline, poses, poly) - margin)
                continue
            near = np.ones(len(poses), bool) if mask is None else np.asarray(mask, bool)
            if within is not None:
                near = near & (np.linalg.norm(poses[:, :2] - self.obstacles[i].pose[:2], axis=1)
                               <= self._mover_radii[i] + self._obs_radii[i] + margin + within)
            if near.any():
                idx = np.flatnonzero(near)
                short[idx] = np.minimum(short[idx], posed_separation(outline, poses[near], poly) - margin)
        return short

    def moves_free(self, start: np.ndarray, ends: np.ndarray, relax: bool = True) -> np.ndarray:
        """For straight moves from ``start`` (3,) to each of ``ends`` (M,3): legal or not, (M,) bool.

        ``relax``: an obstacle the start is already closer to than the margin only needs the gap of the start
        (moves must not bring the mover closer to it); False holds every move to the full margin.
        """
        ends = np.asarray(ends, float).reshape(-1, 3)
        start = np.asarray(start, float)
        ok = self.workspace.segments_inside(start[:2], ends[:, :2])  # the ring's hole: not just the end points
        if not self.obstacles or not ok.any():
            return ok
        # cheap pre-test: a move whose centre line stays farther from every obstacle than the two bounding
        # circles plus the margin cannot touch it; only the others need the swept-area test
        per = self._near(start[:2], ends[:, :2], per_obstacle=True) & ok  # (O, M)
        near = per.any(0)
        if not near.any():
            return ok
        margins = self._margins.copy()
        if relax:
            close = self._near(start[:2], start[None, :2], per_obstacle=True)[:, 0]
            if close.any():
                gaps = self.gaps(start)
                margins = np.where(close, np.minimum(margins, np.maximum(gaps, 0.0) - 1e-9), margins)
        if self._over.any():  # objects passed over: tested only where each move ends (a zero-length sweep)
            ends_only = np.where(self._over, margins, -np.inf)
            margins = np.where(self._over, -np.inf, margins)
            idx = np.flatnonzero(near)
            ok[idx] = self._swept_free(ends[idx], ends[idx], ends_only)  # each end its own start: no sweep
            near = near & ok
            if not near.any():
                return ok
        ok[near] = self._swept_free(start, ends[near], margins, per[:, near])
        return ok

    def _near(self, a: np.ndarray, b: np.ndarray, per_obstacle: bool = False) -> np.ndarray:
        ab = b - a
        t = np.clip(((self._obs_centres - a) @ ab.T) / np.maximum((ab * ab).sum(1), 1e-18), 0.0, 1.0)  # (O, M)
        closest = a + t[..., None] * ab
        d = np.linalg.norm(closest - self._obs_centres[:, None], axis=-1)
        # the exact test inflates by the margin along edge normals, so past a corner it reaches up to
        # margin / sin(half the corner angle): sqrt(2) x margin for squares (2 x covers any corner of 60+ deg)
        hit = d <= (self._obs_radii + self._mover_radii + 2.0 * self.margin)[:, None] + 1e-9
        return hit if per_obstacle else hit.any(0)

    def _swept_free(self, start: np.ndarray, ends: np.ndarray, margins: np.ndarray,
                    near: np.ndarray | None = None) -> np.ndarray:
        """Per move from ``start`` to each of ``ends``: its swept area keeps ``margins`` from every obstacle.
        ``start`` is one pose (3,) for every move, or one per move (M,3): ``ends`` as their own starts test each
        end where it stands (a carried block's objects passed over) in one pass, since numpy's set-up per call
        costs more than one end's test; every step is elementwise or per move, so each move's answer is the one
        a call of its own gives.

        ``near`` (O, M): which obstacles each move comes near (``_near``); a move is tested only against those
        (one farther than the bounding circles plus twice the margin cannot touch it, the same pre-test that
        lets ``moves_free`` pass a move near none), and against no further obstacle once one blocks it. Why:
        this test was most of a slow plan's time (profiled on benchmarks/bench_objects.py seed 951003,
        "closer": 42 of 54 s), mostly spent testing bystanders far from the move; the answers are the same.
        """
        ok = np.ones(len(ends), bool)
        starts = np.broadcast_to(start, ends.shape)  # (M,3), one start per move
        dyaw = wrap_angle(ends[:, 2] - starts[:, 2])
        n_sub = max(1, math.ceil(float(np.abs(dyaw).max()) / SUB_ROTATION))
        t = np.linspace(0.0, 1.0, n_sub + 1)
        sub = np.empty((len(ends), n_sub + 1, 3))
        sub[..., :2] = starts[:, None, :2] + t[None, :, None] * (ends[:, None, :2] - starts[:, None, :2])
        sub[..., 2] = starts[:, 2, None] + t[None, :] * dyaw[:, None]
        travel = ends[:, :2] - starts[:, :2]
        perp = np.stack([-travel[:, 1], travel[:, 0]], axis=-1)
        length = np.linalg.norm(perp, axis=-1, keepdims=True)
        # a move that does not travel has no travel direction: use the x axis there (a valid, redundant axis)
        perp = np.where(length > 1e-12, perp / np.maximum(length, 1e-12), np.array([1.0, 0.0]))
        if near is None:
            near = np.ones((len(self.obstacles), len(ends)), bool)
        for group in self._groups:
            idx = np.flatnonzero(near[group].any(0) & ok)  # the moves this group's outline is needed for
            if len(idx) == 0:
                continue
            outline = self._outlines[group[0]]
            polys = place_outline(outline, sub[idx].reshape(-1, 3)).reshape(len(idx), n_sub + 1, -1, 2)
            normals = edge_normals(polys)  # each sub-pose's once: a sub-step pairs it with the next
            m_axes = np.concatenate(
                [normals[:, :-1], normals[:, 1:],
                 np.broadcast_to(perp[idx, None, None, :], (len(idx), n_sub, 1, 2))], axis=2)
            hulls = np.concatenate([polys[:, :-1], polys[:, 1:]], axis=2)  # (M, S, 2K, 2) sub-step pairs
            parts = [(hulls, m_axes)]
            if self.pusher is not None:  # the fingers' rectangle, tested on its own (below)
                rects = self._pusher_rects(polys, sub[idx], perp[idx], length[idx, 0] > 1e-12)
                along = np.stack([perp[idx, 1], -perp[idx, 0]], axis=-1)  # the travel direction: the pusher's sides
                r_axes = np.broadcast_to(np.stack([perp[idx], along], axis=1)[:, None], (len(idx), n_sub, 2, 2))
                parts.append((np.concatenate([rects[:, :-1], rects[:, 1:]], axis=2), r_axes))
            for i in group:
                j = np.flatnonzero(near[i, idx] & ok[idx])
                if len(j) == 0:
                    continue
                poly, normals, margin = self._obs_polys[i], self._obs_normals[i], margins[i]
                free = np.ones(len(j), bool)
                for shapes, s_axes in parts:
                    axes = np.concatenate([s_axes[j], np.broadcast_to(normals, (len(j), n_sub, *normals.shape))],
                                          axis=2)
                    pm = np.einsum("msad,mskd->msak", axes, shapes[j])
                    po = np.einsum("msad,kd->msak", axes, poly)
                    sep = ((pm.max(-1) + margin <= po.min(-1) + 1e-12)
                           | (po.max(-1) + margin <= pm.min(-1) + 1e-12))
                    free &= sep.any(-1).all(-1)
                ok[idx[j]] = free
        return ok

    def _pusher_rects(self, polys: np.ndarray, sub: np.ndarray, perp: np.ndarray, travels: np.ndarray) -> np.ndarray:
        """The pusher's four corners per sub-pose of each move (M, S+1, 4, 2): a rectangle ``pusher[0]`` deep behind
        the block's face opposite the travel (``polys``: the block's outline per sub-pose) and ``2 * pusher[1]``
        wide across it. A move that does not travel has no pusher (its corners are put on the block's centre).
        Tested apart from the block, not as one hull with it: the fingers touch a turned block at its corner
        only, and the hull filled the notch between the block's slanting back and the fingers' flat front, where
        the anchor's corner stands when the block touches the anchor beside that corner (a block pushed along
        the anchor's face found no legal first move)."""
        depth, half = self.pusher
        u = np.stack([perp[:, 1], -perp[:, 0]], axis=-1)  # (M, 2) unit travel direction
        centre = sub[..., :2]  # (M, S+1, 2)
        face = np.einsum("mskd,md->msk", polys - centre[:, :, None, :], u).max(-1)  # the block's support along u
        corners = []
        for back, sides in ((face, (-half, half)), (face + depth, (half, -half))):  # in order round the rectangle
            for side in sides:
                corners.append(centre - back[..., None] * u[:, None, :] + side * perp[:, None, :])
        pts = np.stack(corners, axis=2)  # (M, S+1, 4, 2)
        return np.where(travels[:, None, None, None], pts, centre[:, :, None, :])

    def path_free(self, path: np.ndarray) -> bool:
        """Every straight move of the waypoint path (N,3) is legal."""
        path = np.asarray(path, float)
        return all(bool(self.moves_free(a, b[None])[0]) for a, b in zip(path[:-1], path[1:], strict=True))

    def overlaps(self, pose: np.ndarray) -> bool:
        """The mover at ``pose`` overlaps an obstacle inflated by the full margin: a zero-length move's test."""
        return not bool(self.moves_free(pose, np.asarray(pose, float)[None], relax=False)[0])


def segment_frames(start: np.ndarray, end: np.ndarray, step: float, rot_step: float = 0.2) -> np.ndarray:
    """Frames (n,3) of the straight move from ``start`` to ``end``, excluding ``start``, including ``end``.

    One frame per ``step`` metres of travel or ``rot_step`` radians of turn, whichever needs more, so a
    slow and a fast move of the same length look alike to an arc-length-based model.
    """
    start, end = np.asarray(start, float), np.asarray(end, float)
    dyaw = float(wrap_angle(end[2] - start[2]))
    dist = float(np.hypot(*(end[:2] - start[:2])))
    n = max(1, math.ceil(max(dist / step, abs(dyaw) / rot_step) - 1e-9))
    t = np.arange(1, n + 1) / n
    out = np.empty((n, 3))
    out[:, :2] = start[:2] + t[:, None] * (end[:2] - start[:2])
    out[:, 2] = wrap_angle(start[2] + t * dyaw)
    return out


def interpolate(waypoints: np.ndarray, step: float, rot_step: float = 0.2) -> np.ndarray:
    """Frames (T,3) of a waypoint path (N,3) moved at one frame per ``step`` metres (see segment_frames)."""
    w = np.asarray(waypoints, float).reshape(-1, 3)
    parts = [w[:1]] + [segment_frames(a, b, step, rot_step) for a, b in zip(w[:-1], w[1:], strict=True)]
    return np.concatenate(parts, axis=0)
