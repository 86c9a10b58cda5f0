"""The ``auto`` camera: framed on the action, from the side where the hand hides the mover least.

A fixed camera has to take in the whole arm and the whole workspace, so the blocks come out small and
the arm fills the picture. What a person grading a run wants to see is the region the action uses: every
object, the planned path, and the hand (whole, even at rest, where it starts and ends). So the camera's
target and distance are fitted per run to the bounding box of those, plus a margin.

Its direction is chosen per run too. From behind the robot (so the robot's left stays the picture's left,
as the viewer-frame prepositions, the 2-D view and the rule judge have it), a camera at several angles
is scored by how often, along the path, a simple model of the hand and forearm (spheres where the manner
puts them: beside the block for a push, above it for a slide or a carry; the forearm and upper arm rising
to a model elbow and the shoulder) hides more than half of the mover, and cameras that the model arm
passes within :data:`CLEARANCE` of are refused (a link passing the lens fills the picture). The best one
wins; among equals, the one nearest the ``viewer`` camera's angle.

Pure geometry, no simulator: the same scene and plan always give the same camera.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

FOV = 40.0  # vertical, degrees
MARGIN = 0.03  # metres around the bounding box of what must be seen
EDGE = 0.97  # the box's projection fills at most this share of the frame's half-width and half-height
AZIMUTHS = tuple(range(-60, 61, 15))  # degrees, 0: looking along +x (from behind the robot), positive: from its left
ELEVATIONS = (35.0, 45.0, 55.0)  # degrees above the table
PREFERRED = (-31.0, 39.0)  # the viewer camera's azimuth and elevation: ties go to the nearest
HAND_HEIGHT = 0.2  # the hand and wrist above the tool point, metres
TIPS_HEIGHT = 0.03  # the fingertips only
CUBE_PX = 1500  # an unoccluded 4 cm cube at the mover's start must cover this many pixels of a 480-row frame
CUBE_AREA = 1.68  # a cube's pixel area over its side's squared pixel length, as seen from above at an angle
HAND_HALF_WIDTH = 0.08  # half the Panda hand's width across its fingers, with a little room
SAMPLES = 16  # path points scored per candidate
ELBOW = (0.45, 0.72)  # the model elbow: this share of the way from the base to the wrist, this high (m)
SHOULDER_Z = 0.33  # the model shoulder's height above the base (m)
CLEARANCE = 0.2  # m the eye keeps from the model arm: nearer, a link fills the picture as it passes


@dataclass(frozen=True)
class Action:
    """What the camera must show: every object's box and the paths the movers follow (scene frame)."""

    boxes: tuple[tuple[tuple[float, float, float], tuple[float, float, float]], ...]  # (low corner, high corner)
    paths: tuple[np.ndarray, ...]  # each (N, 3): a mover's centre along its plan
    sizes: tuple[float, ...]  # each path's mover's size (m)
    pushes: tuple[bool, ...]  # whether each path is pushed (the hand beside the block, not above it)
    hand_rest: tuple[float, float, float]  # the tool point at rest
    base: tuple[float, float, float]  # the arm's base


def look(azimuth: float, elevation: float) -> np.ndarray:
    """Unit vector from the eye towards the target."""
    a, e = math.radians(azimuth), math.radians(elevation)
    return np.array([math.cos(e) * math.cos(a), -math.cos(e) * math.sin(a), -math.sin(e)])


UP = (0.0, 0.0, 1.0)


def _cross(a, b) -> np.ndarray:
    """``np.cross`` of two 3-vectors, the same products and differences in the same order (so the same bits),
    in plain floats: numpy's generic version costs 30 microseconds a call, and choosing a camera makes thousands."""
    a0, a1, a2 = a.tolist() if isinstance(a, np.ndarray) else a
    b0, b1, b2 = b.tolist() if isinstance(b, np.ndarray) else b
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def project(points: np.ndarray, eye: np.ndarray, target: np.ndarray, fov: float,
            aspect: float) -> tuple[np.ndarray, np.ndarray]:
    """Normalised image coordinates (x right, y up, the frame's edges at +-1) and depth of ``points`` (M, 3)."""
    f = target - eye
    f = f / np.linalg.norm(f)
    r = _cross(f, UP)
    r /= np.linalg.norm(r)
    u = _cross(r, f)
    rel = np.asarray(points, float) - eye
    depth = rel @ f
    t = math.tan(math.radians(fov) / 2)
    d = np.maximum(depth, 1e-6)
    return np.stack([(rel @ r) / (d * t * aspect), (rel @ u) / (d * t)], axis=1), depth


def must_see(action: Action, hand: float = HAND_HEIGHT) -> np.ndarray:
    """The corners of everything the frame holds: each object's box, each path swept by its block, the hand
    at rest (``hand`` metres of it above the tool point), all widened by :data:`MARGIN`."""
    pts = []
    for lo, hi in action.boxes:
        pts.append(_corners(np.array(lo) - MARGIN, np.array(hi) + MARGIN))
    for path, size in zip(action.paths, action.sizes, strict=True):
        p = np.asarray(path, float)
        lo, hi = p.min(axis=0) - size / 2 - MARGIN, p.max(axis=0) + size / 2 + MARGIN
        pts.append(_corners(np.maximum(lo, [-np.inf, -np.inf, 0.0]), hi))
    h = np.array(action.hand_rest)
    w = np.array([HAND_HALF_WIDTH, HAND_HALF_WIDTH, 0.0])
    pts.append(_corners(h - w - [0, 0, 0.02], h + w + [0, 0, hand]))
    return np.concatenate(pts)


def _corners(lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    return np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])], float)


def fit(points: np.ndarray, azimuth: float, elevation: float, fov: float = FOV,
        aspect: float = 4 / 3) -> tuple[np.ndarray, np.ndarray]:
    """(eye, target) looking along (azimuth, elevation) from as near as keeps every point inside
    :data:`EDGE` of the frame, the points' projection centred."""
    d = look(azimuth, elevation)
    target = (points.min(axis=0) + points.max(axis=0)) / 2
    span = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))
    eye = target - d * span
    for _ in range(3):  # centre, then pull back or in until the widest point sits on the edge
        lo_d, hi_d = 0.05, 20.0
        for _ in range(22):  # to 5 micrometres
            mid = (lo_d + hi_d) / 2
            xy, depth = project(points, target - d * mid, target, fov, aspect)
            if depth.min() > 0.05 and np.abs(xy).max() <= EDGE:
                hi_d = mid
            else:
                lo_d = mid
        eye = target - d * hi_d
        xy, depth = project(points, eye, target, fov, aspect)
        cx, cy = (xy.min(axis=0) + xy.max(axis=0)) / 2
        f = d
        r = _cross(f, UP)
        r /= np.linalg.norm(r)
        u = _cross(r, f)
        t = math.tan(math.radians(fov) / 2)
        dist = float(np.median(depth))
        target = target + r * cx * dist * t * aspect + u * cy * dist * t
    return target - d * hi_d, target


def hand_spheres(centre: np.ndarray, size: float, push: bool, heading: np.ndarray,
                 base: np.ndarray) -> np.ndarray:
    """(K, 4): centres and radii of spheres standing for the hand and forearm while the block is at ``centre``:
    above the block (a grasp) or behind it, against ``heading`` (a push), the forearm rising towards the base."""
    if push:
        foot = centre + np.r_[-heading[:2] * (size / 2 + 0.035), 0.0]
        foot[2] = 0.03
    else:
        foot = centre + [0.0, 0.0, size / 2 + 0.045]  # the fingers straddle the block, the hand above it
    spheres = [(*(foot + [0, 0, z]), 0.045) for z in np.arange(0.0, HAND_HEIGHT, 0.025)]
    wrist = foot + [0.0, 0.0, HAND_HEIGHT + 0.03]
    elbow = np.array([*(base[:2] + ELBOW[0] * (wrist[:2] - base[:2])), ELBOW[1]])
    shoulder = np.array([base[0], base[1], SHOULDER_Z])
    for s in np.linspace(0.0, 1.0, 8):
        spheres.append((*(wrist + s * (elbow - wrist)), 0.055))
    for s in np.linspace(0.0, 1.0, 6)[1:]:
        spheres.append((*(elbow + s * (shoulder - elbow)), 0.07))
    return np.array(spheres, float)


@dataclass(frozen=True)
class _Sample:
    """One sampled point of a mover's path and what no camera changes there: the mover's test points (a 3 x 3 x 3
    grid over its block) and the model arm's spheres (:func:`hand_spheres`)."""

    points: np.ndarray  # (27, 3)
    spheres: np.ndarray  # (K, 4)


def samples(action: Action) -> tuple[tuple[_Sample, ...], ...]:
    """Per path, its :data:`SAMPLES` points with the mover's grid and the arm's spheres there: made once per action,
    since every camera a choice weighs (54 to 108) asks the same ones (:func:`clearance`, :func:`hidden_share`)."""
    grid = np.array([[x, y, z] for x in (-.4, 0, .4) for y in (-.4, 0, .4) for z in (-.4, 0, .4)])
    base = np.asarray(action.base, float)
    out = []
    for path, size, push in zip(action.paths, action.sizes, action.pushes, strict=True):
        p = np.asarray(path, float)
        rows = []
        for k in np.unique(np.linspace(0, len(p) - 1, SAMPLES).round().astype(int)) if len(p) else []:
            ahead = p[min(k + 1, len(p) - 1)] - p[max(k - 1, 0)]
            n = float(np.hypot(*ahead[:2]))
            heading = ahead / n if n > 1e-9 else np.array([1.0, 0.0, 0.0])
            rows.append(_Sample(p[k] + grid * size, hand_spheres(p[k], size, push, heading, base)))
        out.append(tuple(rows))
    return tuple(out)


def clearance(eye: np.ndarray, action: Action, sampled: tuple | None = None) -> float:
    """How near (m) the model arm comes to the eye along the paths (surface distance); ``sampled`` is
    :func:`samples` of ``action`` when the caller made it already."""
    near = math.inf
    for rows in samples(action) if sampled is None else sampled:
        for s in rows:
            near = min(near, float((np.linalg.norm(s.spheres[:, :3] - eye, axis=1) - s.spheres[:, 3]).min()))
    return near


def hidden_share(eye: np.ndarray, target: np.ndarray, action: Action, fov: float = FOV,
                 aspect: float = 4 / 3, sampled: tuple | None = None) -> float:
    """The share of sampled path points at which the model hand hides more than half of the mover; ``sampled`` is
    :func:`samples` of ``action`` when the caller made it already."""
    t = math.tan(math.radians(fov) / 2)
    bad, total = 0, 0
    for rows in samples(action) if sampled is None else sampled:
        for s in rows:
            xy, depth = project(s.points, eye, target, fov, aspect)
            sxy, sdepth = project(s.spheres[:, :3], eye, target, fov, aspect)
            radius = s.spheres[:, 3] / (np.maximum(sdepth, 1e-6) * t)  # in the image's vertical units
            gap = np.hypot((xy[:, None, 0] - sxy[None, :, 0]) * aspect, xy[:, None, 1] - sxy[None, :, 1])
            hidden = ((gap < radius[None, :]) & (sdepth[None, :] < depth[:, None])).any(axis=1)
            bad += hidden.mean() > 0.5
            total += 1
    return bad / max(total, 1)


def cube_px(eye: np.ndarray, centre: np.ndarray, fov: float = FOV, rows: int = 480) -> float:
    """About how many pixels a 4 cm cube at ``centre`` covers in a frame ``rows`` pixels high."""
    side = 0.04 / (float(np.linalg.norm(np.asarray(centre) - eye)) * math.tan(math.radians(fov) / 2)) * rows / 2
    return CUBE_AREA * side * side


def frame_action(action: Action, aspect: float = 4 / 3, fov: float = FOV) -> tuple[tuple, tuple, float]:
    """(eye, target, fov) of the camera that frames ``action`` (see the module docstring).

    The whole hand at rest stays in the frame where a 4 cm cube at the mover's start still covers
    :data:`CUBE_PX` pixels; where it would not (a high rest pose over blocks close together: the frame would
    be mostly air), the fingertips at rest stay in it and the hand's body may be cut by the top edge."""
    start = action.paths[0][0] if action.paths else np.mean([np.add(lo, hi) / 2 for lo, hi in action.boxes], axis=0)
    best, sampled = None, samples(action)
    for hand in (HAND_HEIGHT, TIPS_HEIGHT):
        pts = must_see(action, hand)
        for el in ELEVATIONS:
            for az in AZIMUTHS:
                eye, target = fit(pts, az, el, fov, aspect)
                hidden = math.ceil(round(hidden_share(eye, target, action, fov, aspect, sampled), 6) * 20) / 20
                small = cube_px(eye, start, fov) < CUBE_PX
                crowded = clearance(eye, action, sampled) < CLEARANCE
                score = (crowded, hidden, small, math.hypot(az - PREFERRED[0], el - PREFERRED[1]))
                if best is None or score < best[0]:
                    best = (score, eye, target)
        if not best[0][2]:
            break
    _, eye, target = best
    return tuple(round(float(v), 4) for v in eye), tuple(round(float(v), 4) for v in target), fov


def action_of(scene, paths: Sequence[tuple[str, np.ndarray, str]], hand_rest: Sequence[float],
              base: Sequence[float]) -> Action:
    """An :class:`Action` from a scene and its plans: ``paths`` lists (mover, path (N, 3): x, y, yaw, the
    manner's motion: "slide", "carry" or "push"); a carried block's centre is raised by the lift the carry will use."""
    boxes = []
    for o in scene.objects:
        r = _reach(o)
        boxes.append(((o.xy[0] - r, o.xy[1] - r, 0.0), (o.xy[0] + r, o.xy[1] + r, float(o.height))))
    centres, sizes = [], []
    for mover, path, manner in paths:
        obj = scene.get(mover)
        p = np.asarray(path, float).reshape(-1, 3)
        z = float(obj.height) / 2
        if manner == "carry":
            from ..manners import carry_lift

            z += carry_lift(scene, mover, p)
        centres.append(np.column_stack([p[:, :2], np.full(len(p), z)]))
        sizes.append(float(obj.size))
    return Action(tuple(boxes), tuple(centres), tuple(sizes), tuple(m == "push" for _, _, m in paths),
                  tuple(float(v) for v in hand_rest), tuple(float(v) for v in base))


def _reach(obj) -> float:
    """Half the object's widest horizontal extent, whatever its yaw (a cube's half diagonal)."""
    return float(getattr(obj, "size", 0.05)) * math.sqrt(2) / 2
