"""The geometry every rule set reads, in units of block size: footprints of objects, the gap between two,
the distance at which two touch, the motion in the anchor's frame, and how far a "steady" change may wobble
(``rules.py`` and ``rulesets/``); how far an outline reaches in a direction, which the learned features read
too, is ``core.geometry.radial_extent`` (the features' floor is below the judges').

**Which footprint.** A verdict reads each object's real outline (``SceneObject.footprint``: the polygon the
planner keeps clear, in the object's own frame, turned with its yaw at every frame of the motion) wherever
one of the objects it reads is not a cube: "next to" a 2:1 box's long face is the gap to that face, not to
the square of equal area. Where every object is a cube, it reads unit squares of the mover's side, as the
rules were written and fitted against people's demonstrations (two cubes of different sides included): the
caller passes no ``outlines`` (:func:`outlines_of` gives None), and :func:`gap` and :func:`overlap` call
:func:`square_gap` and :func:`overlaps` exactly as before, so a cube's verdict is the same bit for bit.
A unit square given as an outline measures the same gap as :func:`square_gap` (the same code,
:func:`polygon_gap`, reads both).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..core.geometry import convex_hull, polygons_overlap, radial_extent

WOBBLE = 0.5
"""Blocks a 'steady' change may go back against its running best (motion-capture jitter in the human
demonstrations reaches this: at 0.3 the rule rejected 37 % of people's "closer" demonstrations)."""

OVERLAP_SLIVER = 0.02
"""Blocks two footprints may interpenetrate and still count as touching, not overlapping (a sliver)."""


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


def polygon_gap(pa: np.ndarray, pb: np.ndarray) -> float:
    """Gap between two convex polygons (K,2) in the same units; 0 when they touch or overlap."""
    if polygons_overlap(pa, pb):
        return 0.0
    d = [float(_point_segment(p, q[i], q[(i + 1) % len(q)]).min()) for p, q in ((pa, pb), (pb, pa))
         for i in range(len(q))]
    return min(d)


def square_gap(a: np.ndarray, b: np.ndarray) -> float:
    """Gap between two unit squares at poses a, b (block units); 0 when they touch or overlap."""
    return polygon_gap(unit_square(a), unit_square(b))


def overlaps(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two unit squares at poses a, b overlap by more than a sliver (touching is not overlapping)."""
    return polygons_overlap(unit_square(a), unit_square(b), margin=-OVERLAP_SLIVER)


def outlines_of(objects: Sequence[Any]) -> list[np.ndarray] | None:
    """The real outlines (K,2) in metres, each in its object's own frame, of the objects a verdict reads
    (the mover first, then the anchors), or None when every one is a cube: the rules then read unit squares,
    as they always have (module docstring)."""
    if all(getattr(o, "shape", "cube") == "cube" for o in objects):
        return None
    return [np.asarray(o.footprint(np.zeros(3)), float) for o in objects]


def placed(outline: np.ndarray, pose: np.ndarray, size: float) -> np.ndarray:
    """An outline in metres (own frame) at ``pose`` [x, y, yaw] given in block units, in block units."""
    c, s = math.cos(pose[2]), math.sin(pose[2])
    return (np.asarray(outline, float) / size) @ np.array([[c, s], [-s, c]]) + np.asarray(pose[:2], float)


def gap(a: np.ndarray, b: np.ndarray, size: float, shapes: Sequence[np.ndarray] | None = None) -> float:
    """Gap (blocks) between the footprints of two objects at poses a, b (block units): ``shapes`` their
    outlines in metres (own frames), or None for two unit squares (:func:`square_gap`)."""
    if shapes is None:
        return square_gap(a, b)
    return polygon_gap(placed(shapes[0], a, size), placed(shapes[1], b, size))


def overlap(a: np.ndarray, b: np.ndarray, size: float, shapes: Sequence[np.ndarray] | None = None) -> bool:
    """Whether the two footprints (as :func:`gap` reads them) overlap by more than a sliver."""
    if shapes is None:
        return overlaps(a, b)
    return polygons_overlap(placed(shapes[0], a, size), placed(shapes[1], b, size), margin=-OVERLAP_SLIVER)


def touching(a: np.ndarray, b: np.ndarray, size: float, shapes: Sequence[np.ndarray]) -> float:
    """The centre distance (blocks) at which object a's footprint touches b's when a comes straight at b
    along the line of their centres (poses a, b in block units, ``shapes`` their outlines in metres): the
    extent of the Minkowski difference of the two outlines along that line. Two squares face to face: 1."""
    pa = placed(shapes[0], np.r_[0.0, 0.0, a[2]], size)
    pb = placed(shapes[1], np.r_[0.0, 0.0, b[2]], size)
    diff = convex_hull((pb[:, None, :] - pa[None, :, :]).reshape(-1, 2))
    d = np.asarray(a[:2], float) - np.asarray(b[:2], float)
    return float(radial_extent(diff, math.atan2(d[1], d[0])))


def relative(mover: np.ndarray, anchor: np.ndarray, size: float) -> tuple[np.ndarray, np.ndarray]:
    """The mover's centre in the anchor's frame (T,2) and its distance (T,), both in blocks of side ``size``."""
    mover = np.asarray(mover, float).reshape(-1, 3)
    anchor = np.asarray(anchor, float).reshape(-1, 3)
    if len(anchor) == 1:
        anchor = np.repeat(anchor, len(mover), axis=0)
    rel = (mover[:, :2] - anchor[:, :2]) / size
    return rel, np.linalg.norm(rel, axis=1)
