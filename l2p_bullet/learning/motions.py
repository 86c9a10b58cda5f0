"""A demonstration's event as the motions a planner makes of it: straight moves through its own poses,
snapped to the discrete planner's rings or to the 2-D study's move grid.

The shipped recipe's planner-domain positives, partials and strays (:mod:`l2p_bullet.learning.training_plan`) are made
with these, from each event cropped and smoothed (:func:`events`); ``research/generalise.py`` scores models
on the same motions.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.geometry import swept_angle
from ..data.demos import SMOOTH_FRAMES, Demo
from ..planning.proposals import DIRECTIONS, DISTANCES
from .augment import smooth_poses

__all__ = ["DISTANCES", "GRID_BLOCKS", "Event", "cut", "domain", "events", "grid_cells", "pushed_out", "ring_cells",
           "straight_moves", "waypoints"]

GRID_BLOCKS = 2.4
"""Spacing of the 2-D study's discrete move grid in block sides (0.36 m cells for its 0.15 m blocks:
SlideAroundDiscrete's moves go between cells 2.4 * sqrt(2) and 2.4 * 2 blocks from the anchor)."""

@dataclass
class Event:
    """One held-out demonstration's event, smoothed, in metres: mover (T,3), anchor pose (3,), block side."""

    id: str
    action: str
    mover: np.ndarray
    anchor: np.ndarray
    size: float
    turn: float
    """Net turn round the anchor over the event, in full turns (around's full-event label)."""


def events(demos: list[Demo], smooth_frames: int = SMOOTH_FRAMES) -> list[Event]:
    out = []
    for d in demos:
        m = smooth_poses(d.mover, smooth_frames)[d.start : d.end + 1]
        a = smooth_poses(d.anchor, smooth_frames)[d.start : d.end + 1].mean(axis=0)
        out.append(Event(d.id, d.action, m, a, d.size, min(abs(swept_angle(m, a)) / (2 * np.pi), 1.0)))
    return out


def _arc(m: np.ndarray) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(m[:, :2], axis=0), axis=1))])


def cut(m: np.ndarray, frac: float) -> np.ndarray:
    """The motion's first ``frac`` of arc length (at least two frames)."""
    s = _arc(m)
    return m[: max(2, int(np.searchsorted(s, frac * s[-1], side="right")))]


def straight_moves(way: np.ndarray, step: float) -> np.ndarray:
    """Dense frames along straight moves between waypoints (``step`` metres apart at most)."""
    parts = [way[:1]]
    for p, q in zip(way[:-1], way[1:], strict=True):
        n = max(1, int(np.ceil(np.linalg.norm(q[:2] - p[:2]) / step)))
        parts.append(np.linspace(p, q, n + 1)[1:])
    return np.concatenate(parts)


def waypoints(m: np.ndarray, n_moves: int) -> np.ndarray:
    """The event's poses at equal arc-length fractions: ``n_moves`` straight moves through its own path."""
    s = _arc(m)
    k = [int(np.clip(np.searchsorted(s, f * s[-1]), 0, len(m) - 1)) for f in np.linspace(0, 1, n_moves + 1)]
    return m[k]


def pushed_out(way: np.ndarray, k: int, anchor: np.ndarray, blocks: float, size: float) -> np.ndarray:
    """A copy of waypoints ``way`` with the ``k``-th moved along its bearing from the anchor to ``blocks`` blocks
    from it (around's strays: a corner out on one of the planner's far rings)."""
    out = way.copy()
    d = out[k, :2] - anchor[:2]
    out[k, :2] = anchor[:2] + d / max(float(np.linalg.norm(d)), 1e-9) * blocks * size
    return out


def _snap(way: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Waypoints after the first moved to their nearest cell, repeats dropped (a planner's moves)."""
    out = [way[0]]
    for p in way[1:]:
        q = p.copy()
        q[:2] = cells[np.argmin(np.hypot(*(cells - p[:2]).T))]
        if np.hypot(*(q[:2] - out[-1][:2])) > 1e-9:
            out.append(q)
    return np.array(out) if len(out) > 1 else np.array([way[0], way[-1]])


def ring_cells(anchor: np.ndarray, size: float) -> np.ndarray:
    """The discrete planner's cells (``planning.proposals``): 8 directions x 6 distances in the anchor's frame."""
    ang = anchor[2] + 2 * np.pi * np.arange(DIRECTIONS) / DIRECTIONS
    d = np.asarray(DISTANCES) * size
    return (anchor[:2] + d[None, :, None] * np.stack([np.cos(ang), np.sin(ang)], -1)[:, None, :]).reshape(-1, 2)


def grid_cells(anchor: np.ndarray, size: float, reach: int = 4) -> np.ndarray:
    """The 2-D study's square move grid around the anchor (its own cell left out: the block is there)."""
    g = np.arange(-reach, reach + 1)
    ij = np.array([(i, j) for i in g for j in g if (i, j) != (0, 0)], float)
    return anchor[:2] + ij * GRID_BLOCKS * size


def domain(e: Event, kind: str, n_moves: int = 3) -> np.ndarray:
    """The event as a planner would make it: ``straight`` moves through ``n_moves`` of its own poses,
    the same snapped to the discrete planner's ``rings``, or to the study's move ``grid``."""
    way = waypoints(e.mover, n_moves)
    if kind == "rings":
        way = _snap(way, ring_cells(e.anchor, e.size))
    elif kind == "grid":
        way = _snap(way, grid_cells(e.anchor, e.size))
    return straight_moves(way, 0.25 * e.size)
