"""The geometry every rule set reads, in units of block size: footprints of blocks, the gap between two, the
motion in the anchor's frame, and how far a "steady" change may wobble (``rules.py`` and ``rulesets/``)."""

from __future__ import annotations

import math

import numpy as np

from ..core.geometry import polygons_overlap

WOBBLE = 0.5
"""Blocks a 'steady' change may go back against its running best (motion-capture jitter in the human
demonstrations reaches this: at 0.3 the rule rejected 37 % of people's "closer" demonstrations)."""


def unit_square(pose: np.ndarray) -> np.ndarray:
    """The four corners of a unit square at ``pose`` [x, y, yaw] (block units)."""
    x, y, t = pose
    c, s = math.cos(t), math.sin(t)
    corners = np.array([[0.5, 0.5], [-0.5, 0.5], [-0.5, -0.5], [0.5, -0.5]])
    return corners @ np.array([[c, s], [-s, c]]) + np.array([x, y])


def _point_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = np.clip(((p - a) @ ab) / max(float(ab @ ab), 1e-12), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=-1)


def square_gap(a: np.ndarray, b: np.ndarray) -> float:
    """Gap between two unit squares at poses a, b (block units); 0 when they touch or overlap."""
    pa, pb = unit_square(a), unit_square(b)
    if polygons_overlap(pa, pb):
        return 0.0
    d = [float(_point_segment(p, q[i], q[(i + 1) % 4]).min()) for p, q in ((pa, pb), (pb, pa)) for i in range(4)]
    return min(d)


def overlaps(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two unit squares at poses a, b overlap by more than a sliver (touching is not overlapping)."""
    return polygons_overlap(unit_square(a), unit_square(b), margin=-0.02)


def relative(mover: np.ndarray, anchor: np.ndarray, size: float) -> tuple[np.ndarray, np.ndarray]:
    """The mover's centre in the anchor's frame (T,2) and its distance (T,), both in blocks of side ``size``."""
    mover = np.asarray(mover, float).reshape(-1, 3)
    anchor = np.asarray(anchor, float).reshape(-1, 3)
    if len(anchor) == 1:
        anchor = np.repeat(anchor, len(mover), axis=0)
    rel = (mover[:, :2] - anchor[:, :2]) / size
    return rel, np.linalg.norm(rel, axis=1)
