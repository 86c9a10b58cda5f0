"""The path a push follows, made from the learned plan: a push does not control the block's yaw, so a part of
the plan that only goes out and comes back the same way (the planner backing up to turn the block, which a
slide does on the spot) is dropped: the pusher would have to go round to the block's other side for it and,
next to another block, come down on that block (measured: random_scene(5004) "next to", a 17 mm spur
that ended beside the anchor; the hand came down on the anchor and threw it 86 cm).
"""

from __future__ import annotations

import math

import numpy as np

SPUR_TURN = math.radians(120.0)
"""A turn of the path sharper than this is a spur's tip (it goes back the way it came)."""
SPUR_TOL = 0.25
"""Block sides: the legs of a spur are within this of each other (they retrace each other)."""
STEP = 0.001
"""m between the dense path's points."""


def dense(xy: np.ndarray, step: float = STEP) -> np.ndarray:
    """The polyline ``xy`` (N,2) resampled every ``step`` m, keeping its vertices (where it turns)."""
    out = [xy[:1]]
    for a, b in zip(xy[:-1], xy[1:], strict=True):
        n = max(1, math.ceil(float(np.hypot(*(b - a))) / step))
        out.append(a + (b - a) * (np.arange(1, n + 1) / n)[:, None])
    return np.concatenate(out)


def _tip(p: np.ndarray) -> int | None:
    """The first vertex of ``p`` (dense) where it turns more than :data:`SPUR_TURN`, or None."""
    d = np.diff(p, axis=0)
    n = np.hypot(*d.T)
    cos = np.sum(d[:-1] * d[1:], axis=1) / np.maximum(n[:-1] * n[1:], 1e-18)
    hit = np.flatnonzero(cos < math.cos(SPUR_TURN))
    return int(hit[0]) + 1 if len(hit) else None


def drop_spurs(xy: np.ndarray, size: float) -> np.ndarray:
    """``xy`` (N,2) with every spur cut off: from a tip, both legs are walked back while they stay within
    :data:`SPUR_TOL` sides of each other, and the path jumps from where the incoming leg leaves the other
    to where the outgoing one does (a spur at the path's end ends where its outgoing leg ends, the
    plan's end). A path without a spur is returned as it was (the same points)."""
    xy = np.asarray(xy, float)
    if len(xy) < 3:
        return xy
    p = dense(xy)
    if _tip(p) is None:
        return xy
    tol = SPUR_TOL * size
    while (k := _tip(p)) is not None:
        j = 1
        while k - j > 0 and k + j < len(p) - 1 and float(np.hypot(*(p[k - j] - p[k + j]))) < tol:
            j += 1
        if k + j >= len(p) - 1:  # the spur ends the path: stop where the plan ends
            p = np.concatenate([p[: max(1, k - j)], p[-1:]])
        elif k - j <= 0:  # the path starts with a spur: start where its outgoing leg leaves it
            p = np.concatenate([p[:1], p[k + j:]])
        else:
            p = np.concatenate([p[: k - j + 1], p[k + j:]])
    return p
