"""What the arm can do, as plain geometry (numpy, no simulator): the room its hand takes beside the block
it holds, and the grasp yaws that keep its wrist inside its range.

The planner, the up-front checks (``planning.feasibility``) and the executor all ask this module, so a
path the planner accepts is one the arm can perform, and a scene the arm cannot do is refused before
anything is planned.

**The hand at block height.** The arm holds a block from above, its closed fingertips resting on the
block's top. Nothing of it is lower than that top, so a block no taller than the one held never meets
the hand. A taller block does: the fingers (about 2 x 4 to 3 x 6 cm, widening upwards) reach
``depth = other's height - held block's height`` below its top, and from 4.6 cm above the fingertips the
hand itself (21 cm long). A 2 cm block slid past an 8 cm one carries the hand into it. So, per other
object, the mover's outline is grown by the arm's measured profile at that object's height
(:func:`hold_outlines`); the arm's profile lives in :class:`~l2p_bullet.arms.ArmSpec`.

The hand turns with the tool's yaw, which is the block's yaw plus the grasp's **angle** (fixed while the
block is held). The hand's profile is symmetric under a half turn, so the angle counts modulo 180 degrees.
The arm grasps with its fingers square to the block's faces (an angle of 0 or 90 degrees) whenever one
of these clears the block's neighbours; only a small block hemmed in by taller ones on two sides is
grasped at another angle (5 degree steps), and one that no angle frees cannot be grasped. When the hand
adds nothing beside the block at any other object's height, the angle is free (``None``: any multiple of
90 degrees will do).

**The wrist.** Pointing down, a Panda's tool yaw is set by its base joint (the azimuth of the tool seen
from the base) and its wrist: wrist = pi/4 + azimuth - tool yaw, exactly, as long as the inverse
kinematics keeps the arm in its vertical plane (it does, seeded continuously: tests/embodiment/test_robustness.py, the
wrist tests). The
wrist turns within +-2.97 rad, less than a full turn, so a block whose yaw keeps accumulating (around a
circle, turning a little at every move) runs the wrist out of range. The grasp picks, among the offsets
its angle allows (the angle plus any multiple of a half turn; any multiple of 90 degrees when the angle
is free), the one that centres the wrist's values over the whole slide (:func:`wrist_offsets`); the
planner only keeps paths for which one exists.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.geometry import convex_hull, separation
from ..core.scene import ROBOT_BASE_XY, Scene
from .builtin import PANDA
from .spec import ArmSpec

HEIGHT_CLEARANCE = 0.002
"""An object whose top is less than this (m) below the held block's top still counts as reaching the
hand's height: fingertips resting on a block may sink a little into it, and blocks settle."""

WRIST_MARGIN = 0.12
"""Radians kept from the wrist's limit: the tracking lag and the model's residual stay well inside it."""

PUSH_SHIFT = 0.012
"""Metres a push may slide its fingers along the block's face to keep clear of another object (the closed-loop
push, embodiment/push.py, and the planner's pushed moves along an anchor's face, planning/nearer.py)."""
PUSH_CLEARANCE = 0.003
"""Metres a push keeps between its fingers and every other object (the same two)."""

QUARTER = math.pi / 2


# --- the hand beside the block ----------------------------------------------------------------------
def hand_extent(depth: float, arm: ArmSpec = PANDA) -> tuple[float, float] | None:
    """Half extents (along the tool's x, across it) of every part of the hand lower than ``depth`` above the
    fingertips; None when nothing is (``depth`` <= 0). Conservative: the profile's next depth up is used."""
    if depth <= 0.0 or not arm.hand_profile:
        return None
    for d, hx, hy in arm.hand_profile:
        if d >= depth - 1e-12:
            return hx, hy
    return arm.hand_profile[-1][1:]


SQUARE_ANGLES = (0.0, QUARTER)
"""The grasp angles tried first: fingers square to the block's faces."""
ANGLE_STEP = math.radians(5.0)
"""The grid of other grasp angles tried when neither square one clears the block's neighbours."""


def grasp_outline(size: float, depth: float, angle: float, arm: ArmSpec = PANDA) -> np.ndarray:
    """The held block's outline (block frame, counter-clockwise) grown by the hand at ``depth`` below another
    object's top, for a grasp at ``angle`` (the tool's yaw minus the block's; 0: the tool's x axis along the
    block's x axis)."""
    h = size / 2
    square = np.array([[h, -h], [h, h], [-h, h], [-h, -h]])
    box = _hand_box(depth, angle, arm)
    if box is None or np.all(np.abs(box) <= h + 1e-9):
        return square
    return convex_hull(np.vstack([square, box]))


def shaped_outline(footprint: np.ndarray, depth: float, angle: float, arm: ArmSpec = PANDA) -> np.ndarray | None:
    """:func:`grasp_outline` for any footprint (K,2, block frame): None when the hand adds nothing to it."""
    box = _hand_box(depth, angle, arm)
    if box is None:
        return None
    grown = convex_hull(np.vstack([footprint, box]))
    return None if _area(grown) <= _area(footprint) + 1e-12 else grown


def _hand_box(depth: float, angle: float, arm: ArmSpec) -> np.ndarray | None:
    """The hand's rectangle at ``depth`` (block frame) for a grasp at ``angle``; None where the hand has none."""
    ext = hand_extent(depth, arm)
    if ext is None:
        return None
    hx, hy = ext
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[hx, -hy], [hx, hy], [-hx, hy], [-hx, -hy]]) @ np.array([[c, s], [-s, c]])


def _area(poly: np.ndarray) -> float:
    x, y = poly[:, 0], poly[:, 1]
    return float(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def hold_outlines(scene: Scene, mover: str, angle: float | None, arm: ArmSpec = PANDA) -> dict[str, np.ndarray]:
    """Per other object (by name), the mover's outline grown by what the arm puts at that object's height
    for a grasp at ``angle``; objects the hand never reaches are left out (the block's own outline applies).
    ``angle`` None (any multiple of 90 degrees): the hull over both square angles. Heights are the
    objects' tops (a box's, a cylinder's or a mesh's height; a cube's side)."""
    m = scene.get(mover)
    out = {}
    for o in scene.objects:
        if o.name == mover:
            continue
        depth = o.height - m.height + HEIGHT_CLEARANCE
        angles = SQUARE_ANGLES if angle is None else (angle,)
        if m.shape != "cube":
            foot = m.footprint(np.zeros(3))
            grown = [g for g in (shaped_outline(foot, depth, a, arm) for a in angles) if g is not None]
            if grown:
                out[o.name] = convex_hull(np.vstack(grown))
            continue
        outline = convex_hull(np.vstack([grasp_outline(m.size, depth, a, arm) for a in angles]))
        if len(outline) != 4 or not np.allclose(np.abs(outline), m.size / 2):
            out[o.name] = outline
    return out


FINGER_AXIS = QUARTER
"""The fingers close along the tool's y axis (the Panda's prismatic fingers; an arm whose tool frame differs
describes its tool link so that this holds): a grasp at angle ``a`` squeezes the object across ``a + 90
degrees`` of its own frame."""
MAX_WIDTH_HOLDS = 2
"""Grasp angles tried for a non-cube mover (narrowest first): each costs the planner one more search."""


def grasp_width(obj, angle: float) -> float:
    """The width (m) the open fingers must span to close across ``obj`` held at grasp ``angle``."""
    return obj.geometry.width(angle + FINGER_AXIS)


def width_angles(obj, arm: ArmSpec = PANDA) -> list[float]:
    """Grasp angles (in [0, 180) degrees) whose width fits between the arm's open fingers, narrowest first:
    across the footprint's narrowest squeeze, then the square angles, then a 5 degree grid. Empty: no grasp
    fits (``planning.feasibility`` refuses it, check "grasp-width")."""
    _, across = obj.geometry.narrowest()
    cands = [(across - FINGER_AXIS) % math.pi, *SQUARE_ANGLES, *np.arange(0.0, math.pi, ANGLE_STEP)]
    seen: list[float] = []
    for a in cands:
        if all(abs(a - b) > 1e-9 for b in seen):
            seen.append(float(a))
    fits = [a for a in seen if grasp_width(obj, a) <= arm.gripper_opening + 1e-9]
    return sorted(fits, key=lambda a: round(grasp_width(obj, a), 4))  # stable: ties keep the order above


def hand_matters(scene: Scene, mover: str, arm: ArmSpec = PANDA) -> bool:
    """Whether the hand reaches beyond the block at some other object's height (then its angle counts)."""
    return bool(hold_outlines(scene, mover, None, arm))


@dataclass(frozen=True)
class Hold:
    """A way to hold the mover: the grasp's angle (None: any multiple of 90 degrees) and the outlines it
    gives per other object."""

    angle: float | None
    outlines: dict[str, np.ndarray]
    start_gap: float  # the hand's smallest gap to another object at the start (inf when it adds nothing)


def hold_gaps(scene: Scene, mover: str, angle: float | None, arm: ArmSpec = PANDA) -> dict[str, float]:
    """Per object the hand reaches beside the mover (held at ``angle``), its gap (m) to the hand where the
    mover stands now; negative: the hand would come down on it."""
    m = scene.get(mover)
    return {name: float(separation(place(outline, m.pose)[None], scene.get(name).footprint())[0])
            for name, outline in hold_outlines(scene, mover, angle, arm).items()}


def holds(scene: Scene, mover: str, arm: ArmSpec = PANDA) -> list[Hold]:
    """The grasps whose hand clears every other object where the mover stands, roomiest first: the square
    angles that do; if neither does, the roomiest angle of a 5 degree grid that does.

    One ``Hold(None, {}, inf)`` when the hand never reaches beyond the block; an empty list when no angle of
    the hand clears the block's neighbours (the mover cannot be grasped).
    """
    if scene.get(mover).shape != "cube":  # its width decides the angles first (a cube fits at both square ones)
        found = []
        for angle in width_angles(scene.get(mover), arm):
            outlines = hold_outlines(scene, mover, angle, arm)
            gap = min(hold_gaps(scene, mover, angle, arm).values(), default=math.inf)
            if gap >= 0.0:
                found.append(Hold(angle, outlines, gap))
            if len(found) == MAX_WIDTH_HOLDS:
                break
        return found
    if not hand_matters(scene, mover, arm):
        return [Hold(None, {}, math.inf)]

    def clear(angles) -> list[Hold]:
        found = []
        for angle in angles:
            gap = min(hold_gaps(scene, mover, angle, arm).values(), default=math.inf)
            if gap >= 0.0:
                found.append(Hold(float(angle), hold_outlines(scene, mover, angle, arm), gap))
        return sorted(found, key=lambda h: -h.start_gap)

    square = clear(SQUARE_ANGLES)
    if square:
        return square
    others = [a for a in np.arange(0.0, math.pi, ANGLE_STEP) if min(abs(a - b) for b in SQUARE_ANGLES) > 1e-9]
    return clear(others)[:1]


def place(outline: np.ndarray, poses: np.ndarray) -> np.ndarray:
    """An outline (K,2) in the block frame placed at ``poses`` [x, y, yaw]: (3,) -> (K,2), (M,3) -> (M,K,2)."""
    poses = np.asarray(poses, float)
    p = poses.reshape(-1, 3)
    c, s = np.cos(p[:, 2])[:, None], np.sin(p[:, 2])[:, None]
    o = np.asarray(outline, float)
    out = np.stack([o[:, 0] * c - o[:, 1] * s + p[:, :1], o[:, 0] * s + o[:, 1] * c + p[:, 1:2]], axis=-1)
    return out[0] if poses.ndim == 1 else out


def blocked_by(scene: Scene, mover: str, poses: np.ndarray, angle: float | None, arm: ArmSpec = PANDA,
               hand: bool = True) -> tuple[str, int] | None:
    """The first other object that the mover, held at ``angle`` and moved through ``poses`` (M,3), overlaps
    (the block or, with ``hand``, the hand beside it), and the pose's index; None when all are clear."""
    m = scene.get(mover)
    outlines = hold_outlines(scene, mover, angle, arm) if hand else {}
    poses = np.asarray(poses, float).reshape(-1, 3)
    first: tuple[int, str] | None = None
    for o in scene.objects:
        if o.name == mover:
            continue
        outline = outlines.get(o.name, m.footprint(np.zeros(3)))
        reach = float(np.linalg.norm(outline, axis=1).max() + np.linalg.norm(o.footprint() - o.xy, axis=1).max())
        near = np.flatnonzero(np.hypot(*(poses[:, :2] - np.asarray(o.xy)).T) < reach)
        if not len(near):
            continue
        gaps = separation(place(outline, poses[near]), o.footprint())
        hit = np.flatnonzero(gaps < -1e-9)
        if len(hit) and (first is None or near[hit[0]] < first[0]):
            first = (int(near[hit[0]]), o.name)
    return None if first is None else (first[1], first[0])


# --- the wrist ------------------------------------------------------------------------------------------
def wrist_values(xy: np.ndarray, yaw: np.ndarray, base_xy: tuple[float, float] = ROBOT_BASE_XY,
                 arm: ArmSpec = PANDA) -> np.ndarray:
    """wrist offset (the Panda's pi/4) + azimuth - yaw: the wrist angle of a tool at ``xy`` with ``yaw``
    (unwrapped), before the grasp's offset is taken off (wrist = value - offset for a tool yaw of block yaw +
    offset)."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    az = np.arctan2(xy[:, 1] - base_xy[1], xy[:, 0] - base_xy[0])
    return arm.wrist_offset + az - np.asarray(yaw, float).reshape(-1)


def wrist_offsets(lo: float, hi: float, angle: float | None, arm: ArmSpec = PANDA,
                  margin: float = WRIST_MARGIN) -> list[float]:
    """Grasp offsets (``angle`` plus multiples of a half turn, or any multiple of 90 degrees when ``angle`` is
    None) that keep every wrist value in [lo, hi] within the wrist's range less ``margin`` and less the arm's
    measured stray from the model (``ArmSpec.wrist_error``), best centred first."""
    limit = arm.wrist_limit - margin - arm.wrist_error
    if hi - lo > 2 * limit:
        return []
    base, step = (0.0, QUARTER) if angle is None else (angle, 2 * QUARTER)
    k = math.ceil((hi - limit - base) / step - 1e-12)
    out = []
    while base + k * step <= lo + limit + 1e-12:
        out.append(base + k * step)
        k += 1
    return sorted(out, key=lambda off: (max(hi - off, off - lo), abs(off)))


@dataclass(frozen=True)
class Wrist:
    """The wrist's constraint on a planned path, for a grasp at ``angle``: some offset must fit the path's
    whole range of :func:`wrist_values`."""

    angle: float | None
    base_xy: tuple[float, float] = ROBOT_BASE_XY
    arm: ArmSpec = PANDA

    def values(self, xy: np.ndarray, yaw: np.ndarray) -> np.ndarray:
        return wrist_values(xy, yaw, self.base_xy, self.arm)

    def fits(self, lo: float, hi: float) -> bool:
        return bool(wrist_offsets(lo, hi, self.angle, self.arm))

    def span(self, xy: np.ndarray, yaw: np.ndarray, so_far: tuple[float, float] | None = None) -> tuple[float, float]:
        """The range of :meth:`values` over a track, merged with the range ``so_far`` of the path before it:
        what :meth:`fits` is asked about a path that grows move by move (the planner's search, the approach)."""
        v = self.values(xy, yaw)
        lo, hi = float(v.min()), float(v.max())
        return (lo, hi) if so_far is None else (min(so_far[0], lo), max(so_far[1], hi))
