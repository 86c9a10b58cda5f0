"""The fingertips' height for pushing a mesh: where the hand meets a side that stands upright.

The pushing hand is a vertical plate only roughly: the Panda's closed fingertips taper over their lowest 5 mm
(``ArmSpec.hand_profile``: 9 mm half thickness at the tip, 13 mm 5 mm up) and the hand's body, 5 cm up, is
thicker again. Advancing on an object, the hand first touches it where the object's section at a height, plus
the hand's own half thickness at that height, reaches furthest back: that is where it pushes. A box's or a
bottle's side stands upright there; a round stick's or a rounded camera body's slopes, and a hand pushing on a
sloping side presses the object down into the table (or rides up over it) instead of driving it (measured: a
1 cm coffee stirrer and a camera pushed past stayed where they were).

:func:`push_height` measures the object's collision surface (its convex parts, ``World.surfaces``) in slices a
millimetre apart, in :data:`DIRECTIONS` directions round it, and for each fingertip height finds where the hand
would touch it from each side and how steep the object's side is there. The default height
(``manners.PUSH_TIP_Z``) is kept wherever the side it meets stands within :data:`UPRIGHT` of vertical (every
box, cylinder and upright bottle); otherwise the nearest height where it does (the least change: pushed
lower than its widest point, a round stick is lifted and flips; measured), else the height whose contacts
stand most nearly upright; no lower than :data:`LOWEST` above the table and no higher than the push's tip
check allows (``manners.push_tip_ceiling``), so a push that was not refused as tipping is not made to tip.
"""

from __future__ import annotations

import math

import numpy as np

STEP = 0.001
"""m between the slices, and between the fingertip heights tried."""
DIRECTIONS = 16
"""Directions round the object (its frame) in which its sides are measured: a push turns the object."""
LOWEST = 0.002
"""m: the lowest fingertip height tried (the fingers do not scrape the table)."""
UPRIGHT = 0.15
"""The steepest mean slope (horizontal m per vertical m of the object's side where the hand meets it, about 8.5
degrees off vertical) at which the default height is kept."""
GAIN = 0.05
"""Where no height meets an upright side: how much less slope another must give to leave the default one."""
TOUCH = 0.001
"""m: the slices whose reach comes this close to the farthest are all met by the pushing hand."""


def sections(tri: np.ndarray, heights: np.ndarray, dirs: np.ndarray) -> np.ndarray:
    """(H, D): the farthest reach of the surface ``tri`` (T,3,3) cut at each of ``heights`` along each unit
    direction ``dirs`` (D,2); -inf where a cut meets nothing. Any triangle soup: only where its edges cross
    each plane counts, so a surface with holes or open rims is measured as it is."""
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])  # (3T, 2, 3)
    p, q = edges[:, 0], edges[:, 1]
    reach_p, reach_q = p[:, :2] @ dirs.T, q[:, :2] @ dirs.T  # (E, D)
    out = np.full((len(heights), len(dirs)), -np.inf)
    for k, z in enumerate(heights):
        dp, dq = p[:, 2] - z, q[:, 2] - z
        cut = (dp * dq <= 0.0) & (dp != dq)
        if not cut.any():
            continue
        t = (dp[cut] / (dp[cut] - dq[cut]))[:, None]
        out[k] = (reach_p[cut] + t * (reach_q[cut] - reach_p[cut])).max(axis=0)
    return out


def hand_front(profile: tuple, depth: np.ndarray) -> np.ndarray:
    """The hand's half thickness along the push (m) at each ``depth`` above the fingertips, interpolated on
    the arm's measured profile (depth, half x, half y)."""
    d = np.array([p[0] for p in profile], float)
    hx = np.array([p[1] for p in profile], float)
    return np.interp(depth, d, hx)


def slopes(s: np.ndarray, heights: np.ndarray, profile: tuple, tip: float) -> np.ndarray:
    """(D,) how steeply the object's side leans (|horizontal / vertical|) where the hand, fingertips at ``tip``,
    touches it from each direction: the most upright slice among those whose reach (``s`` from :func:`sections`)
    plus the hand's half thickness at that height comes within :data:`TOUCH` of the greatest (the hand bites
    millimetres deep, so it meets all of them). Empty when no slice is above ``tip``."""
    k0 = int(np.searchsorted(heights, tip - 1e-12))
    span = s[k0:]
    if len(span) < 2:
        return np.zeros(0)
    reach = span + hand_front(profile, heights[k0:] - tip)[:, None]
    lean = np.abs(np.gradient(span, STEP, axis=0))  # -inf - -inf: nan, where a cut meets nothing
    touched = (reach >= np.nanmax(np.where(np.isfinite(reach), reach, np.nan), axis=0) - TOUCH) & np.isfinite(lean)
    return np.where(touched, lean, np.inf).min(axis=0)


def push_height(tri: np.ndarray, profile: tuple, default: float, ceiling: float) -> float:
    """The fingertips' height above the table (m) for pushing the object whose collision surface is ``tri``
    (T,3,3; its frame, any origin: its lowest point stands on the table), for a hand of ``profile``
    (``ArmSpec.hand_profile``): ``default`` where the side met there stands upright, else the fingertip
    height from :data:`LOWEST` to ``ceiling`` whose contacts stand most nearly upright (module docstring)."""
    tri = np.asarray(tri, float)
    if not len(tri) or not profile:
        return default
    tri = tri - np.array([0.0, 0.0, float(tri[..., 2].min())])
    top = float(tri[..., 2].max())
    a = np.arange(DIRECTIONS) * 2 * math.pi / DIRECTIONS
    heights = np.arange(STEP / 2, top, STEP)
    if len(heights) < 3:
        return default
    s = sections(tri, heights, np.column_stack([np.cos(a), np.sin(a)]))

    def cost(tip: float) -> float:
        lean = slopes(s, heights, profile, tip)
        return float(lean.mean()) if len(lean) else math.inf

    base = cost(default)
    if base <= UPRIGHT:
        return default
    tips = np.arange(LOWEST, min(float(ceiling), top - STEP) + 1e-9, STEP)
    if not len(tips):
        return default
    costs = np.array([cost(float(t)) for t in tips])
    upright = tips[costs <= UPRIGHT]
    if len(upright):  # the upright contact nearest the default height: the least change to how it pushes
        return round(float(upright[np.argmin(np.abs(upright - default))]), 6)
    if float(costs.min()) > base - GAIN:
        return default
    return round(float(tips[int(np.argmin(costs))]), 6)


CONTACT_DIRECTIONS = 72
"""Directions round the object (its frame) in which :func:`contact_reach` measures where the hand meets it."""


def contact_reach(tri: np.ndarray, profile: tuple, tip: float,
                  directions: int = CONTACT_DIRECTIONS) -> tuple[np.ndarray, np.ndarray]:
    """(angles (D,), reach (D,)): how far from the object's centre (its frame's origin, m) the tool's axis is
    when the hand, fingertips ``tip`` m above the table and its axis on a line through the centre, first
    touches the object advancing on it from each direction (angle: from the centre towards the hand). Each
    slice of the object is met only within the hand's half width across the push at that height: a concave
    side (between a gamepad's two grips) lets the fingers in past its outline until they meet the body.
    Empty arrays where no slice is above ``tip`` (nothing there to meet)."""
    tri = np.asarray(tri, float)
    if not len(tri) or not profile:
        return np.zeros(0), np.zeros(0)
    tri = tri - np.array([0.0, 0.0, float(tri[..., 2].min())])
    heights = np.arange(tip + STEP / 2, float(tri[..., 2].max()), STEP)
    a = np.arange(directions) * 2 * math.pi / directions
    dirs = np.column_stack([np.cos(a), np.sin(a)])
    across = np.column_stack([-dirs[:, 1], dirs[:, 0]])
    d = np.array([p[0] for p in profile], float)
    half_x, half_y = (np.array([p[k] for p in profile], float) for k in (1, 2))
    best = np.full(directions, -np.inf)
    for z in heights:
        seg = _cut(tri, float(z))
        if not len(seg):
            continue
        w = float(np.interp(z - tip, d, half_y))
        along0, along1 = seg[:, 0] @ dirs.T, seg[:, 1] @ dirs.T  # (S, D)
        side0, side1 = seg[:, 0] @ across.T, seg[:, 1] @ across.T
        step = side1 - side0
        flat = np.abs(step) < 1e-12
        with np.errstate(divide="ignore", invalid="ignore"):
            ta, tb = (-w - side0) / step, (w - side0) / step
        lo = np.where(flat, np.where(np.abs(side0) <= w, 0.0, 2.0), np.clip(np.minimum(ta, tb), 0.0, None))
        hi = np.where(flat, 1.0, np.clip(np.maximum(ta, tb), None, 1.0))
        met = np.maximum(along0 + lo * (along1 - along0), along0 + hi * (along1 - along0))
        met = np.where(lo <= hi, met, -np.inf).max(axis=0)
        best = np.maximum(best, met + float(np.interp(z - tip, d, half_x)))
    if not np.isfinite(best).any():
        return np.zeros(0), np.zeros(0)
    return a, best


def _cut(tri: np.ndarray, z: float) -> np.ndarray:
    """(S, 2, 2): the segments in which the triangles ``tri`` (T,3,3) cross the plane at height ``z``."""
    v = tri[:, :, 2] - z
    nxt = [1, 2, 0]
    p, q = tri, tri[:, nxt]
    dp, dq = v, v[:, nxt]
    cross = (dp * dq <= 0.0) & (dp != dq)  # (T, 3): the edges that cross
    keep = cross.sum(axis=1) >= 2
    if not keep.any():
        return np.zeros((0, 2, 2))
    p, q, dp, dq, cross = p[keep], q[keep], dp[keep], dq[keep], cross[keep]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(cross, dp / (dp - dq), 0.0)
    pts = p[..., :2] + t[..., None] * (q[..., :2] - p[..., :2])  # (T, 3, 2)
    order = np.argsort(~cross, axis=1, kind="stable")[:, :2]  # the first two edges that cross
    return np.take_along_axis(pts, order[..., None], axis=1)
