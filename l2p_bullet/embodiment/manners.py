"""The embodiment's side of the manners of motion (l2p_bullet/manners): what each motion checks before the
arm moves, and how it runs once the path is checked.

- **slide** (today's behaviour): execute.py's own checks and :meth:`Primitives.move`.
- **carry**: the block goes up, along the path in the air and down, so its path may cross other objects'
  footprints; only where it is set down (the path's end) must be clear. It is lifted so that its bottom
  clears every object whose footprint comes near its path by :data:`CLEARANCE` (at least
  :data:`MIN_LIFT`). Refused before moving: an object wider than the gripper's opening
  (``ArmSpec.gripper_opening``: a manner that closes the fingers across an object checks it) or heavier
  than the arm's payload (``ArmSpec.payload``; an object's ``mass``, else :data:`core.shapes.BLOCK_MASS`).
- **push**: no grasp at all (embodiment/push.py).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..arms import PANDA, ArmSpec, reach
from ..core.geometry import separation
from ..core.scene import Scene
from ..core.shapes import BLOCK_FRICTION
from ..errors import InfeasibleError, PathError
from ..manners import registry as manner_registry
from ..manners.spec import MannerSpec
from . import motion
from .push_path import dense as push_path_dense
from .push_path import drop_spurs
from .smoothing import Pace

CLEARANCE = 0.02
"""m between a carried block's bottom and the top of the tallest object under its path."""
MIN_LIFT = 0.03
"""m: a carry lifts the block at least this high (its judge wants 2 cm) even over an empty table."""


def manner_of(manner: MannerSpec | str | None) -> MannerSpec:
    """The manner declaration (by name; None: slide)."""
    return manner if isinstance(manner, MannerSpec) else manner_registry.get(manner)


def carry_refusal(scene: Scene, mover: str, arm: ArmSpec = PANDA) -> str | None:
    """Why the arm cannot carry ``mover`` (one line), or None."""
    obj = scene.get(mover)
    # the narrowest width the fingers can close across (a cube's side; a box's, cylinder's or mesh's from its outline)
    width = float(obj.size) if obj.shape == "cube" else float(obj.geometry.narrowest()[0])
    if width > arm.gripper_opening + 1e-9:
        return (f'cannot carry "{mover}": it is {width * 100:.1f} cm wide and the {arm.name}\'s gripper opens '
                f"{arm.gripper_opening * 100:.1f} cm; slide or push it instead")
    mass = obj.mass_kg
    if mass > arm.payload + 1e-9:
        return (f'cannot carry "{mover}": it weighs {mass:g} kg and the {arm.name} lifts at most {arm.payload:g} kg '
                "(ArmSpec.payload); slide or push it instead")
    return None


def carry_lift(scene: Scene, mover: str, path: np.ndarray) -> float:
    """How high (m) to lift ``mover`` so that its bottom clears, by :data:`CLEARANCE`, every object whose
    footprint comes within reach of the block anywhere along ``path`` (the held hand is above the block)."""
    m = scene.get(mover)
    p = np.asarray(path, float).reshape(-1, 3)
    dense = np.concatenate(motion.slide_chunks(p, radius=0.0)) if len(p) > 1 else p
    r_m = float(np.linalg.norm(m.footprint(np.zeros(3)), axis=1).max())
    tallest = 0.0
    for o in scene.objects:
        if o.name == mover:
            continue
        r_o = float(np.linalg.norm(o.footprint() - np.asarray(o.xy), axis=1).max())
        if float(np.hypot(*(dense[:, :2] - np.asarray(o.xy)).T).min()) < r_m + r_o + CLEARANCE:
            tallest = max(tallest, float(o.height))  # its top, not its side in blocks (a tall cylinder)
    return max(MIN_LIFT, tallest + CLEARANCE if tallest > 0 else 0.0)


PUSH_TIP_Z = 0.006
"""m: the fingertips' height above the table while pushing (embodiment/push.py reads it, and the next four)."""
PUSH_LOOKAHEAD = 0.6  # block sides ahead along the path: where a push aims
PUSH_GAP = 0.012  # m between the pusher and the block when the hand comes down beside it
PUSH_SHIFT = reach.PUSH_SHIFT  # m the pusher may slide along the block's face to keep clear of another object
PUSH_CLEARANCE = reach.PUSH_CLEARANCE  # m kept between the pusher and every other object
PUSH_FACE_TURN = math.radians(55.0)  # rad: a turn beyond this from the pushing side changes face (go round)


TIP_FRICTION = 1 / 3
"""The share of its weight a push must overcome to slide an object (the table's and the object's friction,
0.5 each, make 0.25; the rest is margin for the push's accelerations and the fingers' own friction). An
object tips instead of sliding where this times the height at which the hand meets it exceeds the distance
from its centre to its leading edge (half its narrowest width). Measured with the Panda: a 15 cm cereal box
3 cm deep tips under a push (5.6 cm x 1/3 > 1.5 cm), a 16 cm milk carton 4.4 cm wide (2.2 cm) and a 16 cm
bottle 5.6 cm wide slide. A cube is never taller than wide, and never tips."""
TALL_RATIO = 1.5
"""An object taller than this many times its narrowest width is tall: it is carried and slid with
:data:`TALL_ACCELERATION` (a cube, as tall as wide, never is)."""
TALL_ACCELERATION = 0.5
"""Factor on the acceleration and jerk of every motion that holds a tall object: the hand starts and stops
softly, so the object does not rock or slip in the fingers (the speed is unchanged)."""


def _narrowest(obj) -> float:
    return float(obj.size) if obj.shape == "cube" else float(obj.geometry.narrowest()[0])


def tip_refusal(scene: Scene, mover: str, arm: ArmSpec = PANDA) -> str | None:
    """Why a push would tip ``mover`` over rather than slide it (one line), or None: an object taller than
    wide whose friction on the table, times the height at which the pushing hand meets it (up to the hand's
    body, where the profile widens), exceeds half its narrowest width (:data:`TIP_FRICTION`)."""
    obj = scene.get(mover)
    width = _narrowest(obj)
    if obj.shape == "cube" or obj.height <= width:
        return None
    widen = next((d for d, _, hy in arm.hand_profile if hy > 0.05), None)
    meets = min(float(obj.height), PUSH_TIP_Z + (widen if widen is not None else float(obj.height)))
    friction = TIP_FRICTION * (obj.friction if obj.friction is not None else BLOCK_FRICTION) / BLOCK_FRICTION
    if friction * meets <= width / 2:
        return None
    return (f'a push would tip "{mover}" over: it is {obj.height * 100:.0f} cm tall and {width * 100:.1f} cm wide, and '
            f"the pushing hand meets it up to {meets * 100:.1f} cm above the table; carry or slide \"{mover}\" instead")


def push_tip_ceiling(obj, arm: ArmSpec = PANDA) -> float:
    """The highest fingertip height (m above the table) at which :func:`tip_refusal`'s rule still lets a push of
    ``obj`` through (inf where no height tips it): a push made at another height than :data:`PUSH_TIP_Z`
    (embodiment/push_height.py) keeps below it, so the check that passed it still holds."""
    width = _narrowest(obj)
    if obj.shape == "cube" or obj.height <= width:
        return math.inf
    friction = TIP_FRICTION * (obj.friction if obj.friction is not None else BLOCK_FRICTION) / BLOCK_FRICTION
    if friction * float(obj.height) <= width / 2:
        return math.inf
    widen = next((d for d, _, hy in arm.hand_profile if hy > 0.05), None)
    return PUSH_TIP_Z if widen is None else width / 2 / friction - widen


def tall_pace(pace: Pace, obj) -> Pace:
    """``pace`` for a motion holding ``obj``: with :data:`TALL_ACCELERATION` where the object is tall."""
    if obj.shape == "cube" or obj.height <= TALL_RATIO * _narrowest(obj):
        return pace
    return replace(pace, acceleration=pace.acceleration * TALL_ACCELERATION, jerk=pace.jerk * TALL_ACCELERATION)


def push_outline(size: float, arm: ArmSpec = PANDA, n: int = 16) -> np.ndarray:
    """What a push puts at block height, in the block's frame: the block with the closed fingers pushing it
    from any side, as a regular ``n``-gon round the block's centre. The pusher is about as wide as the
    fingers (their long side across the push, up to the block's top), wider than a 4 cm block, and turns
    with the direction of travel, not with the block: so the planner keeps that much room (radius: the
    larger of the block's corners and the pusher's half width, 2 mm more) from every other object."""
    ext = reach.hand_extent(max(size - PUSH_TIP_Z, 1e-3), arm)
    r = max(size / np.sqrt(2.0), 0.0 if ext is None else ext[1]) + 0.002
    r /= np.cos(np.pi / n)  # the polygon's edges, not only its corners, outside the circle
    a = np.arange(n) * 2 * np.pi / n
    return np.column_stack([r * np.cos(a), r * np.sin(a)])


def push_refusal(scene: Scene, mover: str, path: np.ndarray, arm: ArmSpec = PANDA) -> str | None:
    """Why no push can follow ``path`` (one line), or None: another object taller than the pushing hand's
    clearance (the hand's body, 21 cm wide, starts where the fingers end, about 5 cm above the table while
    pushing) within the hand's reach of the path would be swept over, as would one the hand passes when it
    goes round the block."""
    m = scene.get(mover)
    p = np.asarray(path, float).reshape(-1, 3)
    dense = np.concatenate(motion.slide_chunks(p, radius=0.0)) if len(p) > 1 else p
    hole = _near_the_hole(scene, m, dense, arm)
    if hole is not None:
        return hole
    widen = next((d for d, _, hy in arm.hand_profile if hy > 0.05), None)
    if widen is None:
        return None
    clear = PUSH_TIP_Z + widen - 0.003
    hand = max(hy for _, _, hy in arm.hand_profile)
    # where the push starts: along the path the controller follows (its spurs dropped, embodiment/push_path.py)
    plan_xy = p[:, :2]
    xy = drop_spurs(plan_xy, m.size)
    spurless = np.array_equal(xy, plan_xy)  # drop_spurs keeps a path without spurs as it is
    blocked = _no_room_to_start(scene, m, dense if spurless else push_path_dense(xy), arm)
    if blocked is not None:
        return (f'no room for the pushing hand behind "{mover}": it would come down on "{blocked}"; '
                f'carry or slide "{mover}" instead')
    reach_m = float(np.linalg.norm(m.footprint(np.zeros(3)), axis=1).max()) + 0.03 + hand
    for o in scene.objects:
        if o.name == mover or o.height <= clear:
            continue
        r_o = float(np.linalg.norm(o.footprint() - np.asarray(o.xy), axis=1).max())
        if float(np.hypot(*(dense[:, :2] - np.asarray(o.xy)).T).min()) < reach_m + r_o:
            return (
                f'no push can pass "{o.name}" ({o.height * 100:.0f} cm tall): the pushing hand is {clear * 100:.1f} cm '
                f'above the table and {2 * hand * 100:.0f} cm wide; carry or slide "{mover}" instead'
            )
    return None


def hand_points(dense: np.ndarray, size: float, standoff: float) -> np.ndarray:
    """Where the pushing hand's tool point goes along a push of the block's centre along ``dense`` (N,>=2), as
    ``embodiment/push.py`` drives it: ``standoff`` behind the block, opposite the point :data:`PUSH_LOOKAHEAD`
    sides further along the path it aims at; when that direction turns more than :data:`PUSH_FACE_TURN` from the
    side the hand is on, the hand goes round over the block, a straight line from the old side to the new."""
    p = np.asarray(dense, float)[:, :2]
    if len(p) < 2:
        return p
    s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(p, axis=0).T))]
    ahead = np.minimum(np.searchsorted(s, s + PUSH_LOOKAHEAD * size), len(p) - 1)
    v = p[ahead] - p
    v[-1] = p[-1] - p[-2]  # at the end: the last step's direction
    n = np.hypot(v[:, 0], v[:, 1])
    for i in range(len(p) - 2, -1, -1):  # a standstill keeps the direction that follows it
        if n[i] < 1e-9:
            v[i], n[i] = v[i + 1], n[i + 1]
    u = v / np.maximum(n, 1e-12)[:, None]
    hands, out, side = p - standoff * u, [], u[0]
    for i in range(len(p)):
        if float(np.dot(u[i], side)) < np.cos(PUSH_FACE_TURN):
            t = np.linspace(0.0, 1.0, 16)[:, None]
            out.append((p[i] - standoff * side) * (1 - t) + hands[i] * t)
            side = u[i]
    return np.vstack([hands, *out])


def _near_the_hole(scene: Scene, m, dense: np.ndarray, arm: ArmSpec) -> str | None:
    """Why the pushing hand could need a point the arm does not reach, or None. With an arm's reach ring cutting
    the workspace (core/workspace.py), the hand stands behind the block (:func:`hand_points`): up to the
    block's farthest corner, the hand's half thickness and the gap from its centre, slid along the face by up to
    :data:`PUSH_SHIFT`. A push whose hand would come nearer the base than the ring's near edge is refused up front
    (measured: KUKA pushes along the hole's edge stop half-way with the arm out of reach). The
    side the hand is on counts: a first bound that put it on every side refused 7 of the Panda's 150 study
    pushes that had been performed (bench_manners, once the Panda's ring cut its 0.35 m workspace)."""
    ws = scene.workspace
    if ws.ring is None:
        return None
    half = reach.hand_extent(m.size / 2, arm) or (0.0145, 0.03)
    standoff = float(np.linalg.norm(m.footprint(np.zeros(3)), axis=1).max()) + half[0] + PUSH_GAP
    hands = hand_points(dense, m.size, standoff)
    d = np.hypot(hands[:, 0] - ws.ring[0], hands[:, 1] - ws.ring[1])
    if float(d.min()) >= ws.ring[2] + PUSH_SHIFT:
        return None
    return (f'the pushing hand would need a point nearer the base of the arm "{arm.name}" than it reaches '
            f"({ws.ring[2]:.2f} m): behind \"{m.name}\" on this path it comes {float(d.min()):.3f} m from the base; "
            f'carry or slide "{m.name}" instead')


def _no_room_to_start(scene: Scene, m, dense: np.ndarray, arm: ArmSpec) -> str | None:
    """The object the pusher would come down on behind the block at the path's start (its middle, or slid
    along the face by up to PUSH_SHIFT), or None when one of those places is clear."""
    ahead = np.cumsum(np.r_[0.0, np.hypot(*np.diff(dense[:, :2], axis=0).T)])
    k = int(np.searchsorted(ahead, PUSH_LOOKAHEAD * m.size))
    d = dense[min(k, len(dense) - 1), :2] - dense[0, :2]
    if float(np.hypot(*d)) < 1e-9:
        return None
    phi = float(np.arctan2(d[1], d[0]))
    half = reach.hand_extent(m.size / 2, arm) or (0.0145, 0.03)
    wide = reach.hand_extent(m.size - PUSH_TIP_Z + 0.005, arm) or half
    a = phi - m.yaw
    support = m.size / 2 * (abs(np.cos(a)) + abs(np.sin(a)))
    u, across = np.array([np.cos(phi), np.sin(phi)]), np.array([-np.sin(phi), np.cos(phi)])
    centre = dense[0, :2] - u * (support + half[0] + PUSH_GAP)
    hx, hy = half[0] + PUSH_CLEARANCE, wide[1] + PUSH_CLEARANCE
    first = None
    for shift in [0.0] + [s * PUSH_SHIFT * k / 6 for k in range(1, 7) for s in (1.0, -1.0)]:
        c = centre + across * shift
        rect = np.array([c + u * dx + across * dy for dx, dy in ((hx, hy), (-hx, hy), (-hx, -hy), (hx, -hy))])
        hit = next((o.name for o in scene.objects if o.name != m.name
                    and float(separation(rect[None], o.footprint())[0]) < 0.0), None)
        if hit is None:
            return None
        first = first or hit
    return first


def planner_outline(manner: MannerSpec, size: float, arm: ArmSpec = PANDA) -> np.ndarray | None:
    """The mover's outline the planner tests against every other object for ``manner`` (None: its own,
    grown by the hand beside it where that matters, as for a slide; a push's pusher is :func:`push_pusher`)."""
    return None


def push_pusher(size: float, arm: ArmSpec = PANDA) -> tuple[float, float]:
    """What the planner puts behind a pushed block along each move (``planning.World2D``'s ``pusher``): the
    closed fingers' depth along the push, where they come down :data:`PUSH_GAP` behind the block's face, and
    their half width across it, 2 mm more (as :func:`push_outline`) less :data:`PUSH_SHIFT`, the most the pusher
    slides along the face, away from another object, to keep clear of it (embodiment/push.py). Only behind: the
    fingers push the face opposite the travel, so the block's front and the room beside it are the block's own (a
    16-gon of the pusher's reach all round kept a pushed block 1.4 sides or more from the anchor, too far for
    "closer"). With other objects on both sides of the block the shift can clear only one of them: the
    controller's own clearance then decides (docs/manners.md)."""
    ext = reach.hand_extent(max(size - PUSH_TIP_Z, 1e-3), arm) or (0.0145, 0.03)
    return 2.0 * float(ext[0]) + PUSH_GAP, max(float(ext[1]) + 0.002 - PUSH_SHIFT, 1e-3)


def manner_planning(manner: MannerSpec, size: float, arm: ArmSpec = PANDA) -> dict:
    """What ``planning.plan`` is told about the manner (docs/manners.md): a carried block passes above the
    other objects (``airborne``: only where it is set down is tested); a pushed one has the pusher behind
    it (``pusher``: the fingers behind the block along every move, tested against every other object).
    Nothing for a slide, so its plans are as before."""
    out: dict = {}
    if manner.airborne:
        out["airborne"] = True
    if manner.motion == "push":
        out["pusher"] = push_pusher(size, arm)
    shape = planner_outline(manner, size, arm)
    if shape is not None:
        out["outline"] = shape
    return out


def check_carry_path(scene: Scene, mover: str, p: np.ndarray) -> None:
    """A carried path may pass over other objects; where it sets the block down (its end) must be clear."""
    hit = reach.blocked_by(scene, mover, p[-1:], None, hand=False)
    if hit is not None:
        raise PathError(f'the path of "{mover}" sets it down on "{hit[0]}" at ({p[-1, 0]:.3f}, {p[-1, 1]:.3f})')


def check_manner(manner: MannerSpec, scene: Scene, mover: str, arm: ArmSpec = PANDA,
                 path: np.ndarray | None = None) -> None:
    """Refuse, before anything is moved, an object the manner cannot handle (and, given the ``path``, a
    path it cannot follow)."""
    if manner.motion == "push":
        why = tip_refusal(scene, mover, arm)
        if why:
            raise InfeasibleError("push", why)
    if manner.motion == "push" and path is not None:
        why = push_refusal(scene, mover, path, arm)
        if why:
            raise InfeasibleError("push", why)
    if manner.motion == "carry":
        why = carry_refusal(scene, mover, arm)
        if why:
            raise InfeasibleError("carry", why)
