"""Motion transformations that turn one demonstration into the training set's copies of it.

Why a module of their own: each is a small piece of geometry on a ``(T, 3)`` motion (metres or block
units alike; ``c`` is the anchor's pose, ``size`` the block side where a distance is in blocks), and
:mod:`l2p_bullet.learning.trainset` decides which copies an action gets and how they are labelled. A
transformation that draws random numbers takes the caller's generator, so the training sets, and with
them the shipped bundles, stay reproducible from the seed.
"""

from __future__ import annotations

import numpy as np

from ..core.geometry import swept_angle


def polyline(demo_m: np.ndarray, c: np.ndarray, rng: np.random.Generator,
              tol: float = np.radians(30)) -> np.ndarray | None:
    """Replace a motion by straight moves between 0-3 of its own intermediate poses (dense frames).

    The angle swept around the anchor (at ``c``) must stay within ``tol`` of the original's: an "around"
    cut down to one straight hop would teach that a short hop is an around. None if no try keeps it.
    """
    target = swept_angle(demo_m, c)
    for _ in range(8):
        n_mid = int(rng.integers(0, 4))
        ks = np.sort(rng.choice(np.arange(1, len(demo_m) - 1), size=min(n_mid, len(demo_m) - 2), replace=False))
        way = demo_m[np.concatenate([[0], ks, [len(demo_m) - 1]]).astype(int)]
        poly = np.concatenate([np.linspace(way[i], way[i + 1], 20, endpoint=i == len(way) - 2)
                               for i in range(len(way) - 1)])
        if abs(swept_angle(poly, c) - target) < tol:
            return poly
    return None


def event_or_polyline(ev_m: np.ndarray, c: np.ndarray, rng: np.random.Generator) -> np.ndarray | None:
    """The event itself or (half the time) one of its straight-line simplifications: the base of a copy."""
    return polyline(ev_m, c, rng) if rng.random() < 0.5 else ev_m


def scaled(m: np.ndarray, centre: np.ndarray, k: float) -> np.ndarray:
    """A copy of the motion with its positions scaled by ``k`` about ``centre`` (x, y); yaw unchanged."""
    out = m.copy()
    out[:, :2] = centre[:2] + (m[:, :2] - centre[:2]) * k
    return out


def turn_about(poses: np.ndarray, centre: np.ndarray, angle: float | np.ndarray) -> np.ndarray:
    """Poses (T,3) or one pose (3,) turned about ``centre`` (x, y) by ``angle``: one angle, or one per pose."""
    p = np.array(poses, float).reshape(-1, 3)
    c, s = np.cos(angle), np.sin(angle)
    d = p[:, :2] - centre[:2]
    p[:, 0], p[:, 1] = centre[0] + c * d[:, 0] - s * d[:, 1], centre[1] + s * d[:, 0] + c * d[:, 1]
    p[:, 2] += angle
    return p.reshape(np.shape(poses))


def twist(m: np.ndarray, c: np.ndarray, angle: float) -> np.ndarray:
    """Rotate the mover about the anchor progressively (``angle`` at the start, 0 at the end, by arc
    length): distances and the end state are unchanged, so "closer"/"away"/"next to" stay what they
    were while the bearing drifts. People graded sweeping motions as good; the captures are almost radial."""
    step = np.linalg.norm(np.diff(m[:, :2], axis=0), axis=1)
    frac = np.concatenate([[0.0], np.cumsum(step)]) / max(step.sum(), 1e-9)
    return turn_about(m, c, angle * (1.0 - frac))


def detour(m: np.ndarray, c: np.ndarray, rng: np.random.Generator, size: float) -> np.ndarray | None:
    r0 = float(np.linalg.norm(m[0, :2] - c[:2])) / size
    r1 = float(np.linalg.norm(m[-1, :2] - c[:2])) / size
    lo, hi = sorted((r0, r1))
    if hi - lo < 2.0:
        return None
    # a new start between the two distances, at least 1 block short of the end's: net motion kept
    r_new = rng.uniform(lo, hi - 1.0) if r1 > r0 else rng.uniform(lo + 1.0, hi)
    b = np.arctan2(*(m[0, 1::-1] - c[1::-1])) + rng.uniform(-1.0, 1.0)
    p0 = np.array([c[0] + r_new * size * np.cos(b), c[1] + r_new * size * np.sin(b), m[0, 2]])
    return np.concatenate([np.linspace(p0, m[0], 20, endpoint=False), m])


def approach(m: np.ndarray, extra: float) -> np.ndarray:
    """The motion with a straight run-up of ``extra`` (metres) before it, along its first direction of
    travel: a start farther away that still passes the anchor as near as the person did."""
    d = m[min(len(m) - 1, max(1, len(m) // 5)), :2] - m[0, :2]
    n = float(np.linalg.norm(d))
    if n < 1e-9:
        return m
    p0 = m[0].copy()
    p0[:2] = m[0, :2] - d / n * extra
    return np.concatenate([np.linspace(p0, m[0], 20, endpoint=False), m])


def back(m: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The motion, then back along its own path for 30-100 % of its frames (net turn shrinks)."""
    k = max(2, int(len(m) * rng.uniform(0.3, 1.0)))
    return np.concatenate([m, m[-2:-k - 1:-1]])


def dip(m: np.ndarray, c: np.ndarray, rng: np.random.Generator, size: float) -> np.ndarray:
    """The motion with an inward dip of 0.5-1.5 blocks (towards ``c``) inserted at 30-80 % of it."""
    k = int(len(m) * rng.uniform(0.3, 0.8))
    p = m[k]
    d = p[:2] - c[:2]
    r = float(np.linalg.norm(d))
    depth = min(rng.uniform(0.5, 1.5) * size, 0.6 * r)
    q = p.copy()
    q[:2] = p[:2] - d / max(r, 1e-9) * depth
    return np.concatenate([m[:k], np.linspace(p, q, 10, endpoint=False), np.linspace(q, p, 10, endpoint=False), m[k:]])


def close_circle(m: np.ndarray, c: np.ndarray, rng: np.random.Generator) -> np.ndarray | None:
    """The motion continued along a circle round ``c`` at its end's distance, in the direction it
    turned, to 0.85-1.25 turns in all; None if it already turned that far."""
    net = swept_angle(m, c)
    extra = np.sign(net) * 2 * np.pi * rng.uniform(0.85, 1.25) - net
    if np.sign(extra) != np.sign(net):
        return None
    d = m[-1, :2] - c[:2]
    r, a0 = float(np.linalg.norm(d)), float(np.arctan2(d[1], d[0]))
    phi = np.linspace(0, extra, max(10, int(abs(extra) / 0.05)) + 1)[1:]
    arc = np.column_stack([c[0] + r * np.cos(a0 + phi), c[1] + r * np.sin(a0 + phi), m[-1, 2] + phi])
    return np.concatenate([m, arc])
