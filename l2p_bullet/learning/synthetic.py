"""Generated demonstrations of simple geometric prepositions, in the shipped capture-session format.

Why: to try the plugin path end to end (scaffold, train, install, perform) without recording anything,
and for the test that does exactly that. They are written like a real capture: one continuous
recording per session, blocks put back to fresh places between events (frames that are not annotated),
still frames around every event (the loader's context), slow-in slow-out slides with a little jitter,
paths that go round the other blocks instead of through them. Real demonstrations are better: record
them in the browser (``l2p-bullet teach``) or with any tracker.

Kinds (``KINDS``):
- ``left-of``, ``right-of``, ``in-front-of``, ``behind``: the mover ends 1.3-1.8 blocks to that side of
  the anchor **as seen from the viewer**, who stands where the robot's base stands relative to the
  table (``viewer_xy`` is written into every session): train them with ``frame = "viewer"``;
- ``between``: three blocks; the mover ends on the segment between the two anchors, near its middle:
  train it with ``anchors = 2``.

    python -c "from l2p_bullet.learning.synthetic import write_sessions; write_sessions('demos', 'left-of')"
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..core.frames import viewer_axes
from ..core.scene import ROBOT_BASE_XY
from ..data.demos import DEMO_BLOCK_SIZE, save_session

SIZE = DEMO_BLOCK_SIZE
"""Block side in the demonstrations' frame (metres), as in the shipped captures."""

STILL = 50
"""Frames of rest around each event (the loader cuts 45 frames of context)."""

VIEWER = np.array(ROBOT_BASE_XY) / 0.05 * SIZE
"""Where the viewer stands: the robot base's place relative to the table centre, in blocks of the
scene's default 5 cm, scaled to these 15 cm blocks (10.6 blocks in front of the table's centre)."""

SIDES = {"left-of": (1.0, 0.0), "right-of": (-1.0, 0.0), "in-front-of": (0.0, -1.0), "behind": (0.0, 1.0)}
"""Viewer-frame kinds: (lateral, depth) direction of the goal from the anchor (lateral > 0: the viewer's left)."""

KINDS = (*SIDES, "between")


def _ease(n: int, rng: np.random.Generator) -> np.ndarray:
    """Arc parameter of a human-like slide: slow start and end, a little jitter."""
    t = np.linspace(0.0, 1.0, n)
    s = 0.5 - 0.5 * np.cos(np.pi * t ** rng.uniform(0.85, 1.15))
    return np.clip(s + rng.normal(0, 0.003, n) * np.sin(np.pi * t), 0.0, 1.0)


def _clearance(path: np.ndarray, obstacles: list[np.ndarray]) -> float:
    """Smallest centre distance (blocks) of a path from any obstacle."""
    if not obstacles:
        return np.inf
    return float(min(np.linalg.norm(path - o[:2], axis=1).min() for o in obstacles)) / SIZE


def slide_path(start: np.ndarray, goal: np.ndarray, obstacles: list[np.ndarray], rng: np.random.Generator,
               clear: float = 1.5) -> np.ndarray | None:
    """(n, 2) positions of a slide from ``start`` to ``goal`` that keeps ``clear`` blocks from every
    obstacle's centre: straight when it can, else a curve bowing out round the nearest obstacle.
    None when no such curve is found."""
    n = int(rng.integers(45, 90))
    s = _ease(n, rng)[:, None]
    straight = start + s * (goal - start)
    if _clearance(straight, obstacles) >= clear:
        return straight
    mid = 0.5 * (start + goal)
    near = min(obstacles, key=lambda o: float(np.linalg.norm(mid - o[:2])))[:2]
    along = (goal - start) / max(float(np.linalg.norm(goal - start)), 1e-9)
    for bulge in (2.2, 2.6, 3.0, 3.5):
        for sign in rng.permutation([-1.0, 1.0]):
            away = mid - near
            if np.linalg.norm(away) < 0.3 * SIZE:
                away = sign * np.array([-along[1], along[0]])
            away = away / np.linalg.norm(away)
            top = near + away * bulge * SIZE  # where the curve's middle passes
            ctrl = 2 * top - mid  # a quadratic Bezier's middle is (start + 2 ctrl + goal) / 4
            path = (1 - s) ** 2 * start + 2 * (1 - s) * s * ctrl + s**2 * goal
            if _clearance(path, obstacles) >= clear:
                return path
    return None


def side_goal(kind: str, anchor: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Where a ``kind`` (left-of, ...) slide ends: 1.3-1.8 blocks to that side as the viewer sees it,
    give or take 0.4 block across."""
    depth_dir, left = viewer_axes(anchor[:2], VIEWER)
    lat, dep = SIDES[kind]
    main = lat * left + dep * depth_dir
    across = dep * left + lat * depth_dir
    return anchor[:2] + SIZE * (rng.uniform(1.3, 1.8) * main + rng.uniform(-0.4, 0.4) * across)


def between_goal(b: np.ndarray, c: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Where a "between" slide ends: 40-60 % of the way from ``b`` to ``c``, within 0.15 block of the line."""
    e = c[:2] - b[:2]
    n = np.array([-e[1], e[0]]) / np.linalg.norm(e)
    return b[:2] + rng.uniform(0.4, 0.6) * e + rng.uniform(-0.15, 0.15) * SIZE * n


class _Recording:
    """One continuous capture of several blocks: holds, slides, annotated events."""

    def __init__(self, poses: list[np.ndarray], rng: np.random.Generator):
        self.poses, self.rng = [p.copy() for p in poses], rng
        self.tracks: list[list[np.ndarray]] = [[] for _ in poses]
        self.events: list[list[int]] = []
        self.movers: list[int] = []
        self.anchors: list[list[int]] = []

    def hold(self, n: int) -> None:
        for b, p in enumerate(self.poses):
            self.tracks[b].extend(p + self.rng.normal(0, 0.0005, 3) * [1, 1, 0] for _ in range(n))

    def slide(self, b: int, xy: np.ndarray, turn: float) -> None:
        theta = self.poses[b][2] + np.linspace(0, turn, len(xy))
        for p, th in zip(xy, theta, strict=True):
            for o in range(len(self.poses)):
                self.tracks[o].append(np.array([p[0], p[1], th % (np.pi / 2)]) if o == b else self.poses[o].copy())
        self.poses[b] = np.array([xy[-1][0], xy[-1][1], theta[-1] % (np.pi / 2)])

    def put(self, b: int, xy: np.ndarray) -> None:
        """Put a block back somewhere (not annotated): a quick straight slide."""
        self.slide(b, np.linspace(self.poses[b][:2], xy, 30), self.rng.uniform(-0.3, 0.3))

    def event(self, mover: int, anchors: list[int], path: np.ndarray) -> None:
        start = len(self.tracks[0])
        self.slide(mover, path, self.rng.uniform(-0.4, 0.4))
        self.events.append([start, len(self.tracks[0]) - 1])
        self.movers.append(mover)
        self.anchors.append(anchors)


def _around(centre: np.ndarray, lo: float, hi: float, rng: np.random.Generator) -> np.ndarray:
    a = rng.uniform(-np.pi, np.pi)
    return centre[:2] + rng.uniform(lo, hi) * SIZE * np.array([np.cos(a), np.sin(a)])


def side_session(kind: str, rng: np.random.Generator, events: int) -> _Recording:
    """Two blocks; the mover alternates; before each event the anchor is put somewhere within a metre of
    the table centre (so lines of sight vary) and the mover 2-4 blocks from it in any direction."""
    rec = _Recording([np.array([0.0, 0.0, rng.uniform(0, np.pi / 2)]),
                      np.array([0.4, 0.0, rng.uniform(0, np.pi / 2)])], rng)
    for e in range(events):
        mover, anchor = e % 2, 1 - e % 2
        while True:
            a_xy = rng.uniform(-0.5, 0.5, 2)
            start = _around(a_xy, 2.0, 4.0, rng)
            goal = side_goal(kind, a_xy, rng)
            path = slide_path(start, goal, [np.r_[a_xy, 0.0]], rng)
            if path is not None:
                break
        rec.hold(STILL)
        rec.put(anchor, a_xy)
        rec.put(mover, start)
        rec.hold(STILL)
        rec.event(mover, [anchor], path)
    rec.hold(STILL)
    return rec


def between_session(rng: np.random.Generator, events: int) -> _Recording:
    """Three blocks; the mover cycles through them; before each event the two anchors are put 3-4.5 blocks
    apart and the mover 2-4 blocks from their middle, not already between them."""
    rec = _Recording([np.array([0.6 * k, 0.0, rng.uniform(0, np.pi / 2)]) for k in range(3)], rng)
    for e in range(events):
        mover = e % 3
        anchors = [int(k) for k in rng.permutation([k for k in range(3) if k != mover])]
        while True:
            mid = rng.uniform(-0.4, 0.4, 2)
            phi = rng.uniform(-np.pi, np.pi)
            half = 0.5 * rng.uniform(3.0, 4.5) * SIZE * np.array([np.cos(phi), np.sin(phi)])
            b, c = mid - half, mid + half
            start = _around(mid, 2.0, 4.0, rng)
            rel = start - b
            t = rel @ (c - b) / float((c - b) @ (c - b))
            off = abs(rel[0] * (c - b)[1] - rel[1] * (c - b)[0]) / np.linalg.norm(c - b) / SIZE
            if (0 < t < 1 and off < 1.5) or min(np.linalg.norm(start - b), np.linalg.norm(start - c)) < 1.6 * SIZE:
                continue
            path = slide_path(start, between_goal(b, c, rng), [np.r_[b, 0.0], np.r_[c, 0.0]], rng, clear=1.3)
            if path is not None:
                break
        rec.hold(STILL)
        for k, xy in zip(anchors, (b, c), strict=True):
            rec.put(k, xy)
        rec.put(mover, start)
        rec.hold(STILL)
        rec.event(mover, anchors, path)
    rec.hold(STILL)
    return rec


def write_sessions(folder: str | Path, kind: str, sessions: int = 2, events: int = 16, seed: int = 0) -> list[Path]:
    """Write ``<Kind>_Session<k>.npz`` files of ``kind`` (see :data:`KINDS`) into ``folder``; their paths."""
    if kind not in KINDS:
        raise ValueError(f'unknown kind "{kind}" (known: {", ".join(KINDS)})')
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    stem = "".join(w.capitalize() for w in kind.split("-"))
    out = []
    for k in range(sessions):
        rec = between_session(rng, events) if kind == "between" else side_session(kind, rng, events)
        tracks = [np.array(t) for t in rec.tracks]
        two = kind != "between"
        out.append(save_session(folder / f"{stem}_Session{k + 1}.npz", tracks, np.array(rec.events),
                                np.array(rec.movers), anchors=None if two else np.array(rec.anchors),
                                viewer=VIEWER if two else None))
    return out
