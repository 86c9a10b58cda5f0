"""Up-front checks: a scene the arm cannot do is refused before anything is planned or moved, with the reason.

Every check is a *necessary* condition, measured with bounds that favour the arm, so a refusal is a
real impossibility and never a guess (docs/perform.md lists them with examples):

- ``grasp-width``: at no angle does the mover's footprint fit between the arm's open fingers
  (``ArmSpec.gripper_opening``; the width is measured across the footprint, ``arms.reach.grasp_width``):
  a 10 cm ball, a 9 x 9 cm box. Only the mover must fit; such an object is a fine anchor or bystander.
- ``grasp``: whichever way it turns (every 5 degrees), the hand coming down on the mover would meet
  another object (taller blocks too close beside a small one: ``arms.reach``).
- ``boxed-in``: no move at all is legal from the start: every short slide (72 directions) and every
  turn in place runs into another object or out of the workspace.
- ``room-around``: the mover's centre must stay in the workspace, so around an anchor near the disk's rim
  (or the edge of an arm's reach ring, ``core/workspace.py``) the directions it can take around the anchor
  cover less than the 0.8 turn "around" needs (even passing as close as two blocks' inscribed circles allow:
  along each bearing, whether the ray from that distance on meets the workspace at all, exactly).
- ``far-around`` (raised by the planner, ``planning/approach.py``): the mover starts farther from the anchor
  than ``near`` blocks and no straight slide (at its yaw, within the wrist's range, clear of every object
  and inside the workspace) brings it to where "around" is planned from. A start farther than ``near`` blocks is not
  refused as such:
  the rule does not judge the approach.
- ``blocked-around``: within ``near`` blocks of the anchor, the other objects and the workspace's rim leave
  the mover no legal pose (whatever its yaw) along some bearings, so no path sweeps the 0.8 turn: a
  continuous sweep passes every bearing of its arc, each frame a pose the 2-D world allows.
  From afar (farther than ``near``), the rule reads "around" from the first frame within ``near`` on, so what
  counts is the way round, one way, from a legal pose where the mover can first come that near (an anchor
  near the rim is reachable from its inward side only, and its way round is cut at the rim). A
  bearing that the grid lets through only by its slack is looked at again finer; one with no legal pose is a
  wall no way round crosses. Both "around" checks live in ``sweep.py``.
- ``room-away``: no point of the workspace is one block farther from the anchor than the mover is now
  (the farthest point measured exactly, ``Workspace.farthest_from``).
- ``room-closer``: the mover cannot get close enough to close half the room "closer" asks for (the room
  its rule reads: to where two cubes touch face to face, or where the real footprints touch when one is not a
  cube, ``judge/rulesets/closer.py``): two objects' centres are never nearer than the sum of their inradii
  (two squares' half sides) plus the clearance the planner keeps
  between them (the world's margin, or the gap at the start where that is smaller: world2d.py's touching
  starts; measured with each hold's outline, the least over the holds, which favours the arm).
- ``no-motion`` (after the search, before anything is executed, :func:`check_moves`): the planner found
  no move that raises the progress, so its best plan leaves the mover where it is (one waypoint). It is
  refused, never executed and reported as a run ("swept 0.00 of a turn", exit 0).

The room checks (:data:`ROOM_CHECKS`) that apply to an action are those its spec declares
(``ActionSpec.planning.checks``), with the thresholds its rule reads (``ActionSpec.thresholds``): a built-in's
own, and for a plugin action those of the rule set its manifest names (``judge.rules.RULE_SPECS``); an action
that declares none gets the arm's checks only.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping

import numpy as np

from ..actions import ActionSpec
from ..arms import PANDA, ArmSpec, reach
from ..core.geometry import nearest_centres, separation
from ..core.scene import GRIPPER_MARGIN, Scene
from ..errors import InfeasibleError, PluginError
from ..judge.footprints import outlines_of
from ..judge.rules import RULE_SPECS, closer_room
from ..judge.rulesets.closer import touch_distance
from . import sweep
from .nearer import face_clearance
from .world2d import World2D, place_outline

CHECKS = (
    "grasp-width",
    "grasp",
    "boxed-in",
    "room-around",
    "far-around",
    "blocked-around",
    "room-away",
    "room-closer",
    "no-motion",
)
MIN_TRAVEL_SIDES = 0.25  # a plan whose mover ends up nearer its start than this (and barely turned) did not move
MIN_TRAVEL_FLOOR = 0.05  # ... or than this, nearer the anchor than half a block (min_travel)
MIN_TURN_RAD = math.radians(10.0)
TOUCHING_M = 0.001  # two objects nearer than this touch, as far as a refusal's words go


def grasp_width(scene: Scene, mover: str, arm: ArmSpec = PANDA) -> None:
    """InfeasibleError ("grasp-width") when no grasp angle fits the mover between the arm's open fingers."""
    m = scene.get(mover)
    if reach.width_angles(m, arm):
        return
    width, _ = m.geometry.narrowest()
    raise InfeasibleError(
        "grasp-width",
        f'the {arm.name} arm cannot grasp "{mover}": its narrowest width is {width * 100:.1f} cm and the '
        f"gripper opens to {arm.gripper_opening * 100:.1f} cm",
        {"mover": mover, "width_m": round(width, 6), "opening_m": arm.gripper_opening, "arm": arm.name})


def grasp_holds(scene: Scene, mover: str, arm: ArmSpec = PANDA) -> list[reach.Hold]:
    """The ways to hold the mover whose hand clears its neighbours (``reach.holds``); InfeasibleError
    ("grasp-width") when the mover fits no grasp, ("grasp") naming the object in the way when no hand clears."""
    grasp_width(scene, mover, arm)
    found = reach.holds(scene, mover, arm)
    if found:
        return found
    m = scene.get(mover)
    gaps = {}
    for angle in np.arange(0.0, math.pi, reach.ANGLE_STEP):
        for name, gap in reach.hold_gaps(scene, mover, float(angle), arm).items():
            gaps[name] = max(gaps.get(name, -math.inf), gap)  # each object's best case over the angles
    name = min(gaps, key=gaps.get)
    other = scene.get(name)
    raise InfeasibleError(
        "grasp",
        f'the arm "{arm.name}" cannot grasp "{mover}": its hand, coming down on the {m.height * 100:.0f} cm block, '
        "would hit "
        f'"{name}" ({other.height * 100:.0f} cm tall) or another taller block beside it whichever way it turns; '
        "move them apart",
        {"mover": mover, "blocking": name, "least_overlap_m": {k: round(-v, 6) for k, v in gaps.items() if v < 0}},
    )


def check(scene: Scene, mover: str, anchor: str, rules: str | ActionSpec | None = None,
          arm: ArmSpec = PANDA, *, turns: bool = True, airborne: bool = False) -> list[reach.Hold]:
    """Run every check that applies; return the usable holds. ``rules``: the action's spec, or the name of the
    rule set it is judged by (its manifest's ``[judge] rules``: the checks of the action that declares that
    rule set), None (or a rule set no action declares) for the arm's checks only. ``turns``: whether the manner
    turns the mover as it moves it (a push does not: ``room-closer`` then keeps the mover's yaw). ``airborne``:
    whether the manner carries the mover above the other objects (a carry): ``blocked-around`` then reads the
    anchor and the workspace alone, as the planner does (the bystanders are obstacles only where it is set down,
    and "around" may set it down anywhere past its turn), and ``boxed-in`` the workspace alone (it is lifted)."""
    spec = RULE_SPECS.get(rules) if isinstance(rules, str) else rules
    holds = grasp_holds(scene, mover, arm)
    # a carried block is lifted straight up, whatever stands round it: only the workspace can box it in
    _boxed_in(scene.only((mover,)) if airborne else scene, mover, holds)
    for name in spec.planning.checks if spec is not None else ():
        missing = [k for k in READS[name] if k not in spec.thresholds]
        if missing:  # a plugin's spec declares the check but not the numbers it reads
            raise PluginError(f'the action "{spec.name}" declares the room check "{name}", which reads the '
                              f"thresholds {', '.join(READS[name])}: add {', '.join(missing)} to its "
                              "ActionSpec")
        if name == "room-closer" and not turns:
            _room_closer(scene, mover, anchor, holds, spec.thresholds, turns=False)
            continue
        if name == "blocked-around" and airborne:
            _blocked_around(scene.only((mover, anchor)), mover, anchor, holds, spec.thresholds)
            continue
        ROOM_CHECKS[name](scene, mover, anchor, holds, spec.thresholds)
    return holds


def _boxed_in(scene: Scene, mover: str, holds: list[reach.Hold]) -> None:
    m = scene.get(mover)
    ang = np.linspace(0.0, 2 * math.pi, 72, endpoint=False)
    step = 0.25 * m.size
    ends = np.column_stack([m.xy[0] + step * np.cos(ang), m.xy[1] + step * np.sin(ang), np.full(72, m.yaw)])
    turns = np.array([[m.xy[0], m.xy[1], m.yaw + t] for t in (-math.pi / 4, math.pi / 4)])
    for hold in holds:
        if World2D(scene, mover, outlines=hold.outlines).moves_free(m.pose, np.vstack([ends, turns])).any():
            return
    raise InfeasibleError("boxed-in", f'"{mover}" cannot move at all: every way it could slide or turn runs into '
                          "another object or out of the workspace", {"mover": mover})


def _room_away(scene: Scene, mover: str, anchor: str, holds: list[reach.Hold],
               thresholds: Mapping[str, float]) -> None:
    gain = thresholds["gain"]
    m, a, ws = scene.get(mover), scene.get(anchor), scene.workspace
    d0 = float(np.hypot(*(np.asarray(m.xy) - a.xy)))
    if ws.ring is None:  # the disk's closed form
        farthest = ws.radius + float(np.hypot(*(np.asarray(a.xy) - ws.center)))
    else:
        farthest = ws.farthest_from(a.xy)[0]
    if farthest < d0 + gain * m.size - 1e-9:
        raise InfeasibleError(
            "room-away",
            f'no room to move "{mover}" away from "{anchor}": it is {d0 / m.size:.2f} blocks away and no point of '
            f"the workspace is more than {farthest / m.size:.2f}; away needs {gain:.0f} block more",
            {"start_blocks": round(d0 / m.size, 3), "farthest_blocks": round(farthest / m.size, 3)})


def clearance(scene: Scene, mover: str, anchor: str, holds: list[reach.Hold] | None = None) -> float:
    """The least gap (m) the planner ever lets the mover's footprint come to the anchor's: the world's margin (the
    smaller one a "closer" face to face with the anchor ends at, ``nearer.face_clearance``, where it applies), or
    the gap where the mover starts when that is smaller (world2d.py: a move's margin is the smaller of the
    margin and the gap at its start, so no move brings it nearer than it started). The start's gap is measured
    with each hold's outline (the block grown by the hand against a taller anchor; that outline's gap is what
    the planner keeps, and the footprint's is never smaller), the least over ``holds`` (all: favours the arm)."""
    m, a = scene.get(mover), scene.get(anchor)
    own = m.footprint(np.zeros(3))
    poly = a.footprint(a.pose)
    outlines = [h.outlines.get(anchor, own) for h in holds] if holds else [own]
    g0 = min(float(separation(place_outline(np.asarray(o, float), m.pose)[None], poly)[0]) for o in outlines)
    face = face_clearance(scene, mover, anchor, holds)  # a bare face may end nearer than the margin (nearer.py)
    return max(0.0, min(GRIPPER_MARGIN if face is None else face, max(g0, 0.0) - 1e-9))


def nearest_at_yaws(m, a) -> float:
    """How near (m) the two objects' centres can come with both yaws kept: the distance from the anchor's centre
    to the nearest edge of the Minkowski sum of its footprint and the mover's mirrored one (both convex outlines;
    the sum's edge normals are those of the two outlines). Two squares turned 45 degrees to each other: 1.21
    sides; face to face: 1, as :func:`~l2p_bullet.core.geometry.nearest_centres`, which never exceeds it."""
    fm = m.footprint() - np.asarray(m.xy)
    fa = a.footprint() - np.asarray(a.xy)
    normals = []
    for f in (fm, fa):
        e = np.roll(f, -1, axis=0) - f
        n = np.column_stack([e[:, 1], -e[:, 0]])
        normals.append(n / np.maximum(np.hypot(*n.T), 1e-18)[:, None])
    n = np.vstack(normals)
    support = (fa @ n.T).max(axis=0) + (-fm @ n.T).max(axis=0)  # h_A(n) + h_(-M)(n), per normal
    return max(float(support.min()), nearest_centres(m, a))


def _room_closer(scene: Scene, mover: str, anchor: str, holds: list[reach.Hold] | None,
                 thresholds: Mapping[str, float], turns: bool = True) -> None:
    m, a = scene.get(mover), scene.get(anchor)
    d0 = float(np.hypot(*(np.asarray(m.xy) - a.xy))) / m.size
    outlines = outlines_of([m, a])  # the judge's room: to where the real footprints touch, unless both are cubes
    room = closer_room(d0, touch_distance((np.asarray(m.xy) - a.xy) / m.size, m.pose, a.pose, m.size, outlines))
    target = d0 - thresholds["share"] * room
    gap = clearance(scene, mover, anchor, holds)
    nearest = ((nearest_centres(m, a) if turns else nearest_at_yaws(m, a)) + gap) / m.size
    if nearest > target + 1e-9:
        kept = "" if turns else f' at the yaws they have now (a push does not turn "{mover}")'
        touches = f'"{mover}" already touches "{anchor}"; ' if gap < TOUCHING_M else ""
        raise InfeasibleError(
            "room-closer",
            f'{touches}"{mover}" cannot come closer to "{anchor}" by the half of the room that "closer" asks for: '
            "their "
            f"centres are {d0:.3f} blocks apart, closer needs {target:.3f}, and the blocks' sizes{kept} with the "
            f"{gap * 1000:.1f} mm the planner keeps between them leave them at least {nearest:.3f} apart",
            {"start_blocks": round(d0, 3), "needed_blocks": round(target, 3), "nearest_blocks": round(nearest, 3),
             "clearance_m": round(gap, 6), "turns": turns})


def _room_around(scene: Scene, mover: str, anchor: str, holds: list[reach.Hold],
                 thresholds: Mapping[str, float]) -> None:
    sweep.room_around(scene, mover, anchor, turns=thresholds["turns"])


def _blocked_around(scene: Scene, mover: str, anchor: str, holds: list[reach.Hold],
                    thresholds: Mapping[str, float]) -> None:
    sweep.blocked_around(scene, mover, anchor, turns=thresholds["turns"], near=thresholds["near"])


ROOM_CHECKS: dict[str, Callable[[Scene, str, str, list[reach.Hold], Mapping[str, float]], None]] = {
    "room-closer": _room_closer, "room-away": _room_away, "room-around": _room_around,
    "blocked-around": _blocked_around,
}
"""The room checks by the name their refusal carries; each reads the thresholds of the action it checks for
(``ActionSpec.planning.checks`` names them), those :data:`READS` names."""

READS: dict[str, tuple[str, ...]] = {"room-closer": ("share",), "room-away": ("gain",),
                                     "room-around": ("turns",), "blocked-around": ("turns", "near")}
"""The thresholds (blocks, turns) each room check reads from the action's spec."""


def min_travel(scene: Scene, mover: str, anchor: str) -> float:
    """The least travel (m) of a plan that moves: :data:`MIN_TRAVEL_SIDES` of the mover's side, or, where the mover
    starts nearer the anchor than that room allows, half the way it can come towards it (its gap less what the
    planner keeps, world2d.py), at least :data:`MIN_TRAVEL_FLOOR` sides. A block level with the anchor 10 mm
    away can come 5 mm nearer: "closer" from there travels 3-5 mm, a real move, not a plan that stays."""
    m, a = scene.get(mover), scene.get(anchor)
    g0 = max(float(separation(m.footprint()[None], a.footprint())[0]), 0.0)
    room = g0 - min(GRIPPER_MARGIN, g0)
    return float(np.clip(room / 2, MIN_TRAVEL_FLOOR * m.size, MIN_TRAVEL_SIDES * m.size))


def check_moves(scene: Scene, mover: str, anchor: str, path: np.ndarray, *, action: str, stopped: str,
                progress: float, steps: int) -> None:
    """InfeasibleError ("no-motion") for a plan that does not move the mover (:func:`min_travel`), unless the
    action was already done at the start (the search stopped at its threshold)."""
    p = np.asarray(path, float).reshape(-1, 3)
    m, a = scene.get(mover), scene.get(anchor)
    travel = float(np.max(np.hypot(*(p[:, :2] - p[0, :2]).T))) if len(p) else 0.0
    turn = float(np.max(np.abs(p[:, 2] - p[0, 2]))) if len(p) else 0.0
    moved = travel >= min_travel(scene, mover, anchor) or turn >= MIN_TURN_RAD
    if stopped == "threshold" or (len(p) >= 2 and moved):
        return
    sides = float(np.hypot(*(np.asarray(m.xy) - np.asarray(a.xy)))) / m.size
    ratio = max(m.size, a.size) / min(m.size, a.size)
    g0 = max(float(separation(m.footprint()[None], a.footprint())[0]), 0.0)
    hint = (f'; "{mover}" starts {g0 * 1000:.1f} mm from "{anchor}" and the planner lets no move bring them nearer '
            f"than they start (it keeps {GRIPPER_MARGIN * 1000:.0f} mm for the hand): the moves left lead along or "
            "away" if g0 < GRIPPER_MARGIN else
            f"; the {m.size * 100:.0f} cm mover starts {sides:.1f} of its sides from the {a.size * 100:.0f} cm "
            "anchor, and the built-in actions measure distances in the mover's sides (learned from two blocks "
            "of one size): try blocks of similar size, nearer each other" if ratio > 1.5 or sides > 4.0
            else "; another --planner or --seed may find one")
    raise InfeasibleError(
        "no-motion",
        f'no plan moves "{mover}" for "{action}" relative to "{anchor}": no move raised the learned progress '
        f"(best {progress:.3f} after {steps} search steps), so it would stay where it is{hint}",
        {"waypoints": len(p), "travel_m": round(travel, 6), "progress": round(float(progress), 6), "steps": steps,
         "mover_size_m": m.size, "anchor_size_m": a.size, "distance_sides": round(sides, 2)})

