"""Where "closer" goes from a start touching the anchor: square to the anchor's nearest face, not touching.

From a start within the world's margin of the anchor (the blocks touch, corner to face), the learned
"closer" model has nothing to climb: nobody in the study started a "closer" that near (people's nearest start
was 2.25 blocks apart), and its search either finds no move that raises the progress or a nudge that closes a
fifth of the room the rule asks half of. What room there is lies in turning: two squares touching corner to
face have centres 1.1-1.5 blocks apart, face to face 1. So where the search ends short of the share of the
room the action's rule asks for (``room-closer``'s reading: ``judge/rulesets/closer.py``), the mover's path is
built here instead: turned square to the anchor's nearest face while it slides in, its centre ending in front
of that face, slid along it as far as the share needs. The world never lets a move bring the mover nearer the
anchor than the move's start (``world2d.py``: the hand beside it needs the room), so the gap grows a little at
every waypoint; corner to corner, where the world lets the mover only leave, it first goes out to the margin,
then squares up. People graded "closer" motions that ended in contact down, so the end keeps its gap rather
than touching (docs/perform.md, "Closer from touching"). A push does not turn the block: its way in keeps the
yaw (the mover, turned to the anchor, meets it nearer than face to face: the gap is measured at that yaw), and a
pushed move that does not head in to the anchor runs along its face, pushed from the block's trailing side with
the fingers clear of the anchor; the room check (``feasibility.py``) refuses it up front where the yaws leave
no room.
"""

from __future__ import annotations

import math

import numpy as np

from ..actions import ActionSpec
from ..arms.reach import PUSH_CLEARANCE, PUSH_SHIFT, Wrist
from ..core.geometry import separation
from ..core.scene import FACE_MARGIN, GRIPPER_MARGIN, Scene
from ..judge.footprints import outlines_of
from ..judge.rulesets.closer import closer_room
from .problem import FRAME_STEP
from .world2d import World2D, interpolate, place_outline

CHECK = "room-closer"
"""The room check of the actions this applies to (``ActionSpec.planning.checks``)."""
SPARE = 0.05
"""Blocks of the share beyond what the rule asks, so the executed run (within a millimetre or two of the plan)
is not judged on the rule's edge."""
LEAST_SPARE = 0.01
"""Blocks of spare taken where :data:`SPARE` leaves no room face to face."""
KEEP_M = 0.001
"""Metres added to the start's gap at the end: the world never lets the mover nearer than it started."""
NEAR = 0.5
"""Blocks between the footprints within which this applies: where "next to" and a level start leave the mover
(the learned model is flat there too: from a start level with the anchor the search closed 26-47 % of the room)."""


def nearer_path(scene: Scene, mover: str, anchor: str, spec: ActionSpec | None, end: np.ndarray, world: World2D,
                wrist: Wrist | None, *, turns: bool = True) -> np.ndarray | None:
    """Waypoints (N,3, scene frame, from the start) that bring ``mover``, starting within the margin of
    ``anchor``, square to the anchor's nearest face where the plan's ``end`` closes less than the share of the
    room ``spec``'s rule asks for: turned while it slides in (1-8 waypoints, the least gap kept first), or out
    to the margin and then square; each move legal in ``world`` and followable by the ``wrist``. None where
    none applies (not such an action or start, not cubes of one size, the search's end enough) or none is
    legal."""
    if spec is None or CHECK not in spec.planning.checks or "share" not in spec.thresholds:
        return None
    m, a = scene.get(mover), scene.get(anchor)
    if outlines_of([m, a]) is not None or not math.isclose(m.size, a.size, rel_tol=1e-6):
        return None
    g0 = _gap(m, m.pose, a)
    if g0 > NEAR * m.size:
        return None
    s = m.size
    d0 = float(np.hypot(*(np.asarray(m.xy) - a.xy))) / s
    need = d0 - spec.thresholds["share"] * closer_room(d0)  # blocks: the centre distance the rule asks for
    if float(np.hypot(*(np.asarray(end[:2]) - a.xy))) / s <= need - SPARE:
        return None  # the search's own plan already closes enough
    c, sn = math.cos(a.yaw), math.sin(a.yaw)
    rel = np.asarray(m.xy) - a.xy
    u, v = c * rel[0] + sn * rel[1], -sn * rel[0] + c * rel[1]  # the mover's centre in the anchor's frame
    quarter = math.pi / 2
    # square to the anchor, the least turn; a push keeps the yaw (the fingers push a face, never turn it)
    yaw = a.yaw + round((m.yaw - a.yaw) / quarter) * quarter if turns else m.yaw
    # the anchor's nearest face first, then (a block turned as it slides) the other face on the mover's side: from
    # a start on the anchor's diagonal (corner to corner) the two are as near, and the way in to one can be blocked
    # by another object where the way in to the other is free; a push keeps to the nearest face (along the other,
    # from beside the anchor's corner, the flat fingers turn the block into the anchor)
    faces = sorted(((u, np.array([c, sn])), (v, np.array([-sn, c]))), key=lambda f: -abs(f[0]))
    for coordinate, axis in faces if turns else faces[:1]:
        normal_dir = axis * math.copysign(1.0, coordinate)  # out of that face of the anchor
        along_dir = np.array([-normal_dir[1], normal_dir[0]])
        lat0 = float(rel @ along_dir) / s
        # face to face with nothing of the hand between, the mover may end nearer than the world's margin
        for margin in (FACE_MARGIN, GRIPPER_MARGIN):
            path = _slid_in(m, a, world.nearer_to(anchor, margin) if margin < world.margin else world, anchor, wrist,
                            g0, margin, need, (normal_dir, along_dir), lat0, yaw)
            if path is not None:
                return path
    return None


def _slid_in(m, a, world: World2D, anchor: str, wrist: Wrist | None, g0: float, margin: float, need: float,
             dirs: tuple[np.ndarray, np.ndarray], lat0: float, yaw: float) -> np.ndarray | None:
    """The way in of :func:`nearer_path` in ``world``, which keeps ``margin`` (m) from the anchor: turned and slid
    in together (the least gap kept first), else (corner to corner) out to the margin and then square; None
    where none closes to ``need`` blocks less the spare, none is legal, or something of the hand comes between
    the two nearer than the world's own margin (:func:`_bare_face`)."""
    s = m.size
    normal_dir, along_dir = dirs
    base = min(g0, margin)  # the least gap the world lets the first move come to
    normal = 1.0 + (base + KEEP_M) / s
    quarter = math.pi / 2
    if abs((yaw - a.yaw + quarter / 2) % quarter - quarter / 2) > 1e-9:  # kept turned (a push): its corner meets
        normal = float(np.hypot(*(_at_gap(m, a, normal_dir, along_dir, 0.0, yaw, base + KEEP_M)[:2] - a.xy))) / s
    reach = next((need - spare for spare in (SPARE, LEAST_SPARE) if normal < need - spare), None)
    if reach is None:
        return None  # not even face to face closes enough with the gap kept
    lateral = math.sqrt(reach * reach - normal * normal) - 1e-3
    lat1 = float(np.clip(lat0, -lateral, lateral))
    start = np.asarray(m.pose, float)
    for gap in base + KEEP_M * np.arange(1, 11):  # the least gap kept at the end whose way in is legal
        if 1.0 + gap / s >= reach:
            break
        for steps in STEPS:  # turned and slid in together, the gap growing a little at every waypoint
            way = [start]
            for k in range(1, steps + 1):
                t = k / steps
                turn, lat = start[2] + t * (yaw - start[2]), lat0 + t * (lat1 - lat0)
                way.append(_at_gap(m, a, normal_dir, along_dir, lat * s, turn, g0 + t * (gap - g0)))
            path = np.asarray(way)
            if float(np.hypot(*(path[-1, :2] - a.xy))) / s <= reach and _bare_face(world, anchor, path, normal_dir) \
                    and world.path_free(path) and _followable(path, wrist, s):
                return path
    # corner to corner the world's test lets the mover only leave: out to the margin, then square and along
    gap = margin + KEEP_M
    if g0 >= margin or 1.0 + gap / s >= reach:
        return None
    lat1 = float(np.clip(lat0, *(np.array([-1.0, 1.0]) * (math.sqrt(reach * reach - (1.0 + gap / s) ** 2) - 1e-3))))
    out = _at_gap(m, a, normal_dir, along_dir, lat0 * s, start[2], gap)
    goal = _at_gap(m, a, normal_dir, along_dir, lat1 * s, yaw, gap)
    path = np.vstack([start, out, goal])
    if float(np.hypot(*(goal[:2] - a.xy))) / s <= reach and _bare_face(world, anchor, path, normal_dir) \
            and world.path_free(path) and _followable(path, wrist, s):
        return path
    return None


FINGERS_CLEAR = PUSH_CLEARANCE
"""Metres a push keeps between its fingers and every other object (the closed-loop push's own): where a pushed move
runs along the anchor's face, not into it."""
FINGERS_SHIFT = PUSH_SHIFT
"""Metres the push may slide its fingers along the block's face, which World2D's ``pusher`` takes off their half
width: along the anchor's face they are tested at their full width."""
ALONG_OUT = math.sin(math.radians(15.0))
"""Most sine of the angle a pushed move that does not head in to the anchor may head out of its face by: the push
runs along the face. Pushed out from beside the anchor's corner, the flat fingers turn the block's corner into
the anchor (measured in the simulator: the anchor moved 9-11 mm)."""
PUSH_HEADING = math.cos(math.pi / 4)
"""Least cosine between a pushed move and the way in to the anchor for the fingers behind the block to count as
not beside it: pushed more sideways, their rectangle behind the block may reach past the face toward the anchor."""


def _bare_face(world: World2D, anchor: str, path: np.ndarray, normal_dir: np.ndarray) -> bool:
    """Whether nothing of the hand comes between mover and anchor along ``path``, where ``world`` lets the mover
    nearer the anchor than the world's margin (else True: the margin keeps room for it): at every waypoint the
    outline tested against the anchor (the block grown by the hand at the anchor's height, ``arms.reach``)
    reaches no farther toward the anchor than the block's own face, and a pushed block's fingers (World2D's
    ``pusher``) stay behind it, every move heading in to the anchor, or all the moves that do not running along
    its face (:data:`ALONG_OUT`) with the fingers, at their full width, :data:`FINGERS_CLEAR` from it."""
    if world.margin_to(anchor) >= world.margin:
        return True
    toward = -np.asarray(normal_dir, float)
    held = place_outline(world.outline_against(anchor), path) @ toward
    own = place_outline(world.mover.outline, path) @ toward
    if bool((held.max(-1) > own.max(-1) + 1e-6).any()):
        return False
    if world.pusher is None:
        return True
    travel = np.diff(np.asarray(path, float)[:, :2], axis=0)
    length = np.hypot(*travel.T)
    moving = length > 1e-9
    heading_in = (travel @ toward) >= PUSH_HEADING * length
    if bool(heading_in[moving].all()):
        return True
    along = moving & ~heading_in
    return bool(((travel[along] @ toward) >= -ALONG_OUT * length[along]).all()) \
        and _fingers_clear(world, anchor, path, along)


def _fingers_clear(world: World2D, anchor: str, path: np.ndarray, moves: np.ndarray) -> bool:
    """Whether the pushed block's fingers (World2D's ``pusher`` rectangle behind the face opposite the travel,
    sampled along each of the ``moves`` flagged) keep :data:`FINGERS_CLEAR` from ``anchor``: a move along the
    anchor's face pushes the block from its trailing side, where the fingers stand clear of the anchor, so only
    the block itself comes to the face margin."""
    depth, half = world.pusher
    half += FINGERS_SHIFT  # the hand's full width: the push slides it along the face only to clear an object
    poly = next(b.polygon() for b in world.obstacles if b.name == anchor)
    path = np.asarray(path, float)
    for i in np.flatnonzero(moves):
        u = (path[i + 1, :2] - path[i, :2]) / float(np.hypot(*(path[i + 1, :2] - path[i, :2])))
        perp = np.array([-u[1], u[0]])
        for t in np.linspace(0.0, 1.0, 9):
            pose = path[i] + t * (path[i + 1] - path[i])
            block = place_outline(world.mover.outline, pose[None])[0]
            face = float(((block - pose[:2]) @ u).max())
            rect = np.array([pose[:2] - b * u + side * perp for b in (face, face + depth) for side in (-half, half)])
            rect = rect[[0, 1, 3, 2]]  # the four corners in order round the rectangle
            if float(separation(rect[None], poly)[0]) < FINGERS_CLEAR - 1e-9:
                return False
    return True


def face_clearance(scene: Scene, mover: str, anchor: str, holds: list | None) -> float | None:
    """The least gap (m) :func:`nearer_path` may end a "closer" at, face to face with the anchor (what the room
    check reads, ``feasibility.clearance``): :data:`FACE_MARGIN`, the :data:`KEEP_M` it adds and the
    :data:`LEAST_SPARE` it keeps on the share (a start that needs nearer is refused, not failed), where it applies
    (two cubes of one size within :data:`NEAR` blocks) and some grasp of ``holds`` leaves the face bare: the hand
    adds nothing at the anchor's height, or both square grasps clear the start (one has its fingers on the faces
    that do not face the anchor); None where the world's margin stays."""
    m, a = scene.get(mover), scene.get(anchor)
    if outlines_of([m, a]) is not None or not math.isclose(m.size, a.size, rel_tol=1e-6) \
            or _gap(m, m.pose, a) > NEAR * m.size:
        return None
    angles = {round(math.degrees(h.angle) % 180.0, 6) for h in holds or ()
              if anchor in h.outlines and h.angle is not None}
    if holds and not any(anchor not in h.outlines for h in holds) and not {0.0, 90.0} <= angles:
        return None
    return FACE_MARGIN + KEEP_M + LEAST_SPARE * m.size


STEPS = (1, 2, 4, 8, 16, 32)
"""Waypoints of the turn tried: a straight move between two of them dips less than the gap grows between them,
and the world's swept test (conservative by about the mover's radius times each move's turn) passes it."""


def _at_gap(m, a, normal_dir: np.ndarray, along_dir: np.ndarray, along: float, yaw: float, gap: float) -> np.ndarray:
    """The pose at ``yaw`` and ``along`` metres along the anchor's face whose footprint is ``gap`` from the
    anchor's, found along the face's normal (the gap grows with the distance out)."""
    lo, hi = 0.0, 3.0 * m.size
    for _ in range(40):
        mid = (lo + hi) / 2
        xy = np.asarray(a.xy) + mid * normal_dir + along * along_dir
        lo, hi = (mid, hi) if _gap(m, np.r_[xy, yaw], a) < gap else (lo, mid)
    xy = np.asarray(a.xy) + hi * normal_dir + along * along_dir
    return np.r_[xy, yaw]


def _gap(m, pose: np.ndarray, a) -> float:
    """Metres between ``m``'s footprint at ``pose`` and ``a``'s (0 where they touch or overlap)."""
    return max(float(separation(m.footprint(pose)[None], a.footprint())[0]), 0.0)


def _followable(path: np.ndarray, wrist: Wrist | None, size: float) -> bool:
    if wrist is None:
        return True
    frames = interpolate(path, FRAME_STEP * size)
    return wrist.fits(*wrist.span(frames[:, :2], frames[:, 2]))
