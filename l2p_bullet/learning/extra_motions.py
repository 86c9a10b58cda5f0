"""The motions a training plan's per-action extras are made of (:mod:`.training_plan`'s docstring says which
option adds which, and with what label): an own event and its mirror image, the wrong motions by kind
(:data:`WRONG_MOTIONS`), the graded wrong motions by kind (:data:`GRADED_WRONGS`), around's strays and
closer's near starts. Each kind is named in ``actions/spec.py`` and declared per action (``ActionSpec.training``).

Apart from the plans because these are geometry on one event (waypoints, rings, shares of a label), drawn
from the generator the plan hands them, while a plan decides which to add and labels the sequences; they
are re-exported from :mod:`.training_plan`, where the kinds have always been read.

Nothing here reads a grade.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from ..data.demos import Demo
from . import motions as g
from .augment import mirror
from .trainset import DataConfig


def _event_views(d: Demo, dcfg: DataConfig) -> list[g.Event]:
    """A demonstration's event and its mirror image, smoothed (metres)."""
    e = g.events([d], dcfg.smooth_frames)[0]
    return [e, dataclasses.replace(e, mover=mirror(e.mover), anchor=mirror(e.anchor[None])[0])]


def _backs_off(e: g.Event, rng: np.random.Generator) -> np.ndarray:
    """Out 1.5-4 blocks from its start, away from the anchor, and back to about its start distance."""
    p0, c = e.mover[0], e.anchor
    d = p0[:2] - c[:2]
    r0 = max(float(np.linalg.norm(d)), 1e-9)
    out, back = p0.copy(), p0.copy()
    out[:2] = p0[:2] + d / r0 * rng.uniform(1.5, 4.0) * e.size
    back[:2] = c[:2] + d / r0 * (r0 + rng.uniform(-0.3, 0.3) * e.size)
    return np.array([p0, out, back])


def _out_and_back(e: g.Event, rng: np.random.Generator) -> np.ndarray:
    """To its end and back to near its start."""
    p0, p1 = e.mover[0], e.mover[-1]
    return np.array([p0, p1, p0 + np.r_[rng.normal(0, 0.3 * e.size, 2), 0.0]])


def _reversed(e: g.Event, rng: np.random.Generator) -> np.ndarray:
    """From its end straight back to its start."""
    return np.array([e.mover[-1], e.mover[0]])


def _to_closest_and_back(e: g.Event, rng: np.random.Generator) -> np.ndarray:
    """To its closest approach to the anchor and straight back."""
    m, c = e.mover, e.anchor
    k = int(np.argmin(np.hypot(*(m[:, :2] - c[:2]).T)))
    return np.array([m[0], m[k], m[0]])


def _half_round_and_back(e: g.Event, rng: np.random.Generator) -> np.ndarray:
    """Half of it (two straight moves) and straight back."""
    half = g.waypoints(e.mover[: max(2, len(e.mover) // 2)], 2)
    return np.concatenate([half, half[-2::-1]])


WRONG_MOTIONS: dict[str, Callable[[g.Event, np.random.Generator], np.ndarray]] = {
    "backs-off": _backs_off, "out-and-back": _out_and_back, "reversed": _reversed,
    "to-closest-and-back": _to_closest_and_back, "half-round-and-back": _half_round_and_back,
}
"""The wrong motions by kind (``Training.wrong_motions``): each makes the waypoints of one from an own
event."""


def _wrong(e: g.Event, rng: np.random.Generator, kinds: tuple[str, ...]) -> list[np.ndarray]:
    """Wrong piecewise-straight motions made from an own event (module docstring), of the kinds its action
    declares."""
    return [g.straight_moves(WRONG_MOTIONS[k](e, rng), 0.25 * e.size) for k in kinds]


def _goes_back(e: g.Event, rng: np.random.Generator) -> tuple[np.ndarray, float]:
    """Back a share u of the way to the start: 1 - u of it is left."""
    p0, p1 = e.mover[0], e.mover[-1]
    u = rng.uniform(0.2, 1.0)
    return (p1 + u * (p0 - p1))[None], 1.0 - u


def _moves_out(e: g.Event, rng: np.random.Generator) -> tuple[np.ndarray, float]:
    """k blocks straight out from its place beside the anchor: 1 - k / :data:`GRADED_FAR` of it is left."""
    p1, c = e.mover[-1], e.anchor
    k = rng.uniform(1.0, 5.0)
    q = p1.copy()
    q[:2] = c[:2] + (p1 - c)[:2] * (1 + k * e.size / max(float(np.linalg.norm((p1 - c)[:2])), 1e-9))
    return q[None], max(0.0, 1.0 - k / GRADED_FAR)


GRADED_WRONGS: dict[str, Callable[[g.Event, np.random.Generator], tuple[np.ndarray, float]]] = {
    "goes-back": _goes_back, "moves-out": _moves_out}
"""The graded wrong motions by kind (``Training.graded_wrong``): what follows the event, and the share of its
final label left at the end."""


def _graded(e: g.Event, rng: np.random.Generator,
            kind: str | None) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """Wrong planner motions that keep part of the credit (``graded_wrongs``): (the event as straight moves'
    waypoints, what follows it, the share of the event's final label left at the end); none for an action that
    declares no kind (the waypoints are drawn all the same, so every action's extras stay as they were)."""
    whole = g.waypoints(e.mover, int(rng.integers(1, 4)))
    if kind is None:
        return []
    tail, left = GRADED_WRONGS[kind](e, rng)
    return [(whole, tail, left)]


GRADED_FAR = 5.0
"""Blocks past its place at which a next-to keeps no credit (the planner's second-widest ring)."""

STRAY_RINGS = tuple(g.DISTANCES[-2:])
"""Where ``strays`` moves one of around's corners to (blocks from the anchor): the discrete planner's two
outer rings (``planning.proposals.DISTANCES``); at the outer one no credit is left."""


def _strayed(e: g.Event, rng: np.random.Generator, near: float) -> tuple[np.ndarray, float, float, float] | None:
    """around's ``strays`` copy of an own event: (waypoints with one moved out, where along the straight
    moves' length the move out to it starts and ends (fractions), the share of the label left from there);
    None when the chosen pose is already that far out."""
    n = int(rng.integers(4, 7))
    way = g.waypoints(e.mover, n)
    k = int(rng.integers(1, n + 1))
    far = float(rng.choice(STRAY_RINGS))
    r = float(np.linalg.norm(way[k, :2] - e.anchor[:2]))
    if r >= far * e.size or r < 1e-9:
        return None
    way = g.pushed_out(way, k, e.anchor, far, e.size)
    seg = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(way[:, :2], axis=0).T))])
    left = max(0.0, 1.0 - (far - near) / (STRAY_RINGS[-1] - near))
    return way, seg[k - 1] / seg[-1], seg[k] / seg[-1], left


NEAR_END = (1.05, 1.2)
"""Blocks (centre to centre) from the anchor at which a ``near_starts`` copy ends: touching, with the margin."""
NEAR_START = (1.25, 2.5)
"""Blocks from the anchor within which a ``near_starts`` copy starts (chains' "closer" clauses start 1.25-1.75)."""
NEAR_MIN_CLOSING = 0.1
"""Blocks a ``near_starts`` crop must close, or it is not made."""


def _near(e: g.Event, rng: np.random.Generator) -> list[np.ndarray]:
    """closer's ``near_starts`` copies of an own event: shrunk about the anchor to end :data:`NEAR_END` from it,
    cropped to start within :data:`NEAR_START`; as it is and as one straight move (none if it closes too little)."""
    c, size = e.anchor[:2], e.size
    d = np.hypot(*(e.mover[:, :2] - c).T) / size
    end, start = rng.uniform(*NEAR_END), rng.uniform(*NEAR_START)
    k = end / max(float(d[-1]), 1e-9)
    m = e.mover.copy()
    m[:, :2] = c + (m[:, :2] - c) * k
    i0 = int(np.flatnonzero(d * k <= start)[0])  # the last frame is at ``end`` < ``start``
    crop = m[i0:]
    if len(crop) < 2 or (d[i0] - d[-1]) * k < NEAR_MIN_CLOSING:
        return []
    return [crop, g.straight_moves(crop[[0, -1]], 0.25 * size)]
