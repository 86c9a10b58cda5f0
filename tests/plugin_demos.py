"""Write geometric demonstrations of "to the left of" in the shipped capture-session format.

"Left" is taken from the mover's point of view at its start, looking at the anchor (the deictic
reading: "put the cup to the left of the bowl" as seen from where you stand). That reading is
rotation invariant, like the project's features, so a progress model can learn it from relative
geometry alone; the robot-frame reading (+y of the table) could not be told apart from "right" by a
rotation-invariant model.

Each session is one continuous recording, like a real capture: between events a block is put back to
a fresh start (unannotated frames), and every event has still frames before and after it so the
context the loader cuts around an event (45 frames) is still blocks, as in the human sessions.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

SIZE = 0.15  # block side in the demonstrations' frame (see l2p_bullet/data/README.md)
STILL = 50  # frames of rest around each event


def left_goal(start: np.ndarray, anchor: np.ndarray, gap: float) -> np.ndarray:
    """Where "to the left of anchor" is, seen from ``start``: ``gap`` blocks beside it, on the left."""
    facing = anchor - start
    facing /= np.linalg.norm(facing)
    left = np.array([-facing[1], facing[0]])
    return anchor + gap * SIZE * left


def _bezier(p0: np.ndarray, p1: np.ndarray, p2: np.ndarray, s: np.ndarray) -> np.ndarray:
    s = s[:, None]
    return (1 - s) ** 2 * p0 + 2 * (1 - s) * s * p1 + s**2 * p2


def _ease(n: int, rng: np.random.Generator) -> np.ndarray:
    """Arc parameter of a human-like slide: slow start and end, a little jitter."""
    t = np.linspace(0.0, 1.0, n)
    s = 0.5 - 0.5 * np.cos(np.pi * t ** rng.uniform(0.85, 1.15))
    return np.clip(s + rng.normal(0, 0.003, n) * np.sin(np.pi * t), 0.0, 1.0)


def event_path(start: np.ndarray, anchor: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """(n, 2) positions of one slide from ``start`` to the left of ``anchor``, bowing away from it."""
    goal = left_goal(start, anchor, rng.uniform(1.3, 1.8))
    mid = 0.5 * (start + goal)
    away = mid - anchor
    away /= max(np.linalg.norm(away), 1e-9)
    ctrl = mid + away * SIZE * rng.uniform(0.2, 0.8)
    n = int(rng.integers(45, 90))
    return _bezier(start, ctrl, goal, _ease(n, rng))


def session(rng: np.random.Generator, events: int) -> dict[str, np.ndarray]:
    """One capture session: both blocks' tracks and the annotated events (mover alternates)."""
    poses = [np.array([0.0, 0.0, rng.uniform(0, np.pi / 2)]), np.array([0.4, 0.0, rng.uniform(0, np.pi / 2)])]
    tracks: list[list[np.ndarray]] = [[], []]
    spans, movers = [], []

    def hold(n: int) -> None:
        for b in (0, 1):
            tracks[b].extend(poses[b] + rng.normal(0, 0.0005, 3) * [1, 1, 0] for _ in range(n))

    def slide(b: int, xy: np.ndarray, turn: float) -> None:
        theta = poses[b][2] + np.linspace(0, turn, len(xy))
        for p, th in zip(xy, theta, strict=True):
            tracks[b].append(np.array([p[0], p[1], th % (np.pi / 2)]))
            tracks[1 - b].append(poses[1 - b].copy())
        poses[b] = np.array([xy[-1][0], xy[-1][1], theta[-1] % (np.pi / 2)])

    t = 0
    for e in range(events):
        mover = e % 2
        anchor_xy = poses[1 - mover][:2]
        # Reset (not annotated): put the mover 2-4 blocks from the anchor, in a random direction.
        a = rng.uniform(-np.pi, np.pi)
        fresh = anchor_xy + rng.uniform(2.0, 4.0) * SIZE * np.array([np.cos(a), np.sin(a)])
        hold(STILL)
        slide(mover, np.linspace(poses[mover][:2], fresh, 30), rng.uniform(-0.3, 0.3))
        hold(STILL)
        t = len(tracks[0])
        path = event_path(poses[mover][:2].copy(), anchor_xy.copy(), rng)
        slide(mover, path, rng.uniform(-0.4, 0.4))
        spans.append([t, len(tracks[0]) - 1])
        movers.append(mover)
    hold(STILL)
    shell, stella = np.array(tracks[0]), np.array(tracks[1])
    n = len(shell)
    return {
        "frame": np.arange(n, dtype=np.int32),
        "shell_pose": shell, "stella_pose": stella,
        "shell_observed": np.ones(n, bool), "stella_observed": np.ones(n, bool),
        "event_start_end": np.array(spans, dtype=np.int32), "event_mover": np.array(movers, dtype=np.int8),
        "table_points_2d": np.array([[-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]]),
    }


def write_sessions(folder: str | Path, sessions: int = 2, events: int = 20, seed: int = 0) -> list[Path]:
    """Write ``LeftOf_Session<k>.npz`` files into ``folder``; return their paths."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    out = []
    for k in range(sessions):
        p = folder / f"LeftOf_Session{k + 1}.npz"
        np.savez(p, **session(rng, events))
        out.append(p)
    return out


def is_left_of(start: np.ndarray, end: np.ndarray, anchor: np.ndarray) -> bool:
    """True when ``end`` lies on the left half-plane of the line start -> anchor (seen from start)."""
    f = anchor[:2] - start[:2]
    r = end[:2] - anchor[:2]
    return float(f[0] * r[1] - f[1] * r[0]) > 0
