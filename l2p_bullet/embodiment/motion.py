"""From a 2-D path of the block to end-effector paths: approach, descend, slide, retract.

All functions here are geometry (numpy only): the simulator consumes their output. End-effector poses
are ``[x, y, z, yaw]`` with the tool pointing down; yaw is unwrapped (continuous) along a path so that
interpolating it never turns the wrist the long way round.

Corners of the 2-D path are rounded with arcs so the block can keep moving through them; a corner
sharper than ``STOP_ANGLE`` is not rounded (the deviation would be large) but becomes a stop: the path
is split there into rest-to-rest chunks, each of which is timed on its own (see smoothing.py).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import PathError

CORNER_RADIUS = 0.02
"""Blend radius (m) for path corners: at 0.1 m/s the curvature adds v^2/r = 0.5 m/s^2."""
STOP_ANGLE = math.radians(50.0)
"""Corners turning more than this are not rounded: the block stops there and sets off again."""
ARC_STEP = math.radians(3.0)
"""Angular sampling of rounded corners (the dense path is linear between samples)."""
LINE_STEP = 0.002
"""Spacing (m) of dense samples along straight pieces."""
MIN_MOVE = 1e-4
"""Path points closer than this (m) in x-y are one point (a pure rotation if the yaw differs)."""


def unwrap_yaw(path: np.ndarray) -> np.ndarray:
    """Copy of a (N,3) or (N,4) path with its yaw (last column) made continuous."""
    out = np.array(path, dtype=float)
    out[:, -1] = np.unwrap(out[:, -1])
    return out


def clean_path(path: np.ndarray) -> np.ndarray:
    """Validate a 2-D path (N,3), unwrap its yaw and merge points that do not move."""
    p = np.asarray(path, dtype=float)
    if p.ndim != 2 or p.shape[1] != 3 or len(p) < 1:
        raise PathError(f"a 2-D path must be a list of [x, y, yaw] poses (got shape {p.shape})")
    if not np.all(np.isfinite(p)):
        raise PathError("the 2-D path contains non-finite numbers")
    p = unwrap_yaw(p)
    keep = [0]
    for i in range(1, len(p)):
        moved = np.hypot(*(p[i, :2] - p[keep[-1], :2])) >= MIN_MOVE
        turned = abs(p[i, 2] - p[keep[-1], 2]) > 1e-6
        if moved or turned:
            keep.append(i)
    return p[keep]


def line(a: np.ndarray, b: np.ndarray, step: float = LINE_STEP) -> np.ndarray:
    """Dense straight path (M,4) from pose ``a`` to pose ``b`` (yaw interpolated linearly)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    dist = max(float(np.linalg.norm(b[:3] - a[:3])), 0.05 * abs(b[3] - a[3]))
    n = max(2, math.ceil(dist / step) + 1)
    w = np.linspace(0.0, 1.0, n)[:, None]
    return a + w * (b - a)


def _corner(prev_xy, xy, next_xy, t_in_max, t_out_max, radius):
    """Rounded-corner geometry at ``xy``: (tangent length, turning angle, arc points) or None."""
    u_in, u_out = xy - prev_xy, next_xy - xy
    l_in, l_out = np.linalg.norm(u_in), np.linalg.norm(u_out)
    u_in, u_out = u_in / l_in, u_out / l_out
    turn = math.atan2(u_in[0] * u_out[1] - u_in[1] * u_out[0], float(np.dot(u_in, u_out)))
    if abs(turn) < 1e-6:
        return 0.0, 0.0, None
    t = min(radius * math.tan(abs(turn) / 2), t_in_max, t_out_max)
    r = t / math.tan(abs(turn) / 2)
    start = xy - t * u_in
    normal = np.array([-u_in[1], u_in[0]]) * math.copysign(1.0, turn)
    centre = start + r * normal
    a0 = math.atan2(start[1] - centre[1], start[0] - centre[0])
    n = max(2, math.ceil(abs(turn) / ARC_STEP) + 1)
    angles = a0 + np.linspace(0.0, turn, n)
    arc = centre + r * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    return t, turn, arc


def slide_chunks(path: np.ndarray, radius: float = CORNER_RADIUS) -> list[np.ndarray]:
    """Split and round a cleaned 2-D path (N,3) into rest-to-rest chunks of dense block poses (M,3).

    The yaw of a dense sample is interpolated along the original path's x-y arc length, so the block
    turns as the plan says. A move with no x-y motion (a turn in place) is a chunk of its own.
    """
    p = clean_path(path)
    if len(p) < 2:
        return []
    seg = np.hypot(*np.diff(p[:, :2], axis=0).T)
    # Break points: sharp corners and the ends of pure rotations (a segment that does not move).
    breaks = [0]
    for i in range(1, len(p) - 1):
        if seg[i - 1] < MIN_MOVE or seg[i] < MIN_MOVE:
            breaks.append(i)
            continue
        u, v = p[i, :2] - p[i - 1, :2], p[i + 1, :2] - p[i, :2]
        ang = math.acos(max(-1.0, min(1.0, float(np.dot(u, v) / (seg[i - 1] * seg[i])))))
        if ang > STOP_ANGLE:
            breaks.append(i)
    breaks.append(len(p) - 1)
    chunks = []
    for a, b in zip(breaks[:-1], breaks[1:], strict=True):
        part = p[a : b + 1]
        if b - a == 1 and seg[a] < MIN_MOVE:  # a turn in place
            n = max(2, math.ceil(abs(part[1, 2] - part[0, 2]) / math.radians(2)) + 1)
            chunks.append(np.linspace(part[0], part[1], n))
            continue
        chunks.append(_round_chunk(part, radius))
    return chunks


def _round_chunk(part: np.ndarray, radius: float) -> np.ndarray:
    """Dense x-y samples with rounded interior corners, yaw interpolated along the original arc length."""
    xy = part[:, :2]
    seg = np.hypot(*np.diff(xy, axis=0).T)
    sigma = np.concatenate([[0.0], np.cumsum(seg)])  # original arc length at the vertices
    pts: list[np.ndarray] = [xy[:1]]
    sig: list[np.ndarray] = [sigma[:1]]
    for i in range(1, len(xy) - 1):
        t_in = seg[i - 1] * (1.0 if i == 1 else 0.5)
        t_out = seg[i] * (1.0 if i == len(xy) - 2 else 0.5)
        t, turn, arc = _corner(xy[i - 1], xy[i], xy[i + 1], t_in, t_out, radius)
        if arc is None:
            pts.append(xy[i : i + 1])
            sig.append(sigma[i : i + 1])
            continue
        pts.append(arc)
        sig.append(np.linspace(sigma[i] - t, sigma[i] + t, len(arc)))
    pts.append(xy[-1:])
    sig.append(sigma[-1:])
    pts_a, sig_a = np.concatenate(pts), np.concatenate(sig)
    # Densify the straight pieces between consecutive samples.
    dense_xy, dense_sig = [pts_a[:1]], [sig_a[:1]]
    for k in range(1, len(pts_a)):
        d = float(np.hypot(*(pts_a[k] - pts_a[k - 1])))
        n = max(1, math.ceil(d / LINE_STEP))
        w = np.linspace(0.0, 1.0, n + 1)[1:, None]
        dense_xy.append(pts_a[k - 1] + w * (pts_a[k] - pts_a[k - 1]))
        dense_sig.append(sig_a[k - 1] + w[:, 0] * (sig_a[k] - sig_a[k - 1]))
    dxy, dsig = np.concatenate(dense_xy), np.concatenate(dense_sig)
    yaw = np.interp(dsig, sigma, part[:, 2])
    return np.column_stack([dxy, yaw])


def resample_path(path: np.ndarray, step: float) -> np.ndarray:
    """Resample a (N,3) path every ``step`` metres of x-y arc length (yaw interpolated), ends kept."""
    p = unwrap_yaw(path)
    seg = np.hypot(*np.diff(p[:, :2], axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    if s[-1] < step:
        return p[[0, -1]] if len(p) > 1 else p
    q = np.append(np.arange(0.0, s[-1], step), s[-1])
    return np.stack([np.interp(q, s, p[:, i]) for i in range(3)], axis=1)


def polyline_distance(points: np.ndarray, path_xy: np.ndarray) -> np.ndarray:
    """Distance from each point (K,2) to the polyline ``path_xy`` (N,2)."""
    pts = np.asarray(points, float)[:, None, :]
    a, b = path_xy[:-1][None], path_xy[1:][None]
    if len(path_xy) == 1:
        return np.linalg.norm(pts[:, 0] - path_xy[0], axis=1)
    ab = b - a
    denom = np.maximum(np.sum(ab * ab, axis=2), 1e-18)
    w = np.clip(np.sum((pts - a) * ab, axis=2) / denom, 0.0, 1.0)
    proj = a + w[..., None] * ab
    return np.min(np.linalg.norm(pts - proj, axis=2), axis=1)
