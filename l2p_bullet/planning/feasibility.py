"""Up-front checks: a scene the arm cannot do is refused before anything is planned or moved, with the reason.

Every check is a *necessary* condition, measured with bounds that favour the arm, so a refusal is a
real impossibility and never a guess (docs/perform.md lists them with examples):

- ``grasp-width``: at no angle does the mover's footprint fit between the arm's open fingers
  (``ArmSpec.gripper_opening``; the width is measured across the footprint, ``embodiment.reach.grasp_width``):
  a 10 cm ball, a 9 x 9 cm box. Only the mover must fit; such an object is a fine anchor or bystander.
- ``grasp``: whichever way it turns (every 5 degrees), the hand coming down on the mover would meet
  another object (taller blocks too close beside a small one: ``embodiment.reach``).
- ``boxed-in``: no move at all is legal from the start: every short slide (72 directions) and every
  turn in place runs into another object or out of the workspace.
- ``room-around``: the mover's centre must stay in the workspace, so around an anchor near the disk's rim
  (or the edge of an arm's reach ring, ``core/workspace.py``) the directions it can take around the anchor
  cover less than the 0.8 turn "around" needs (even passing as close as two blocks' inscribed circles allow:
  along each bearing, whether the ray from that distance on meets the workspace at all, exactly).
- ``far-around`` (raised by the planner, ``planning/approach.py``): the mover starts farther from the anchor
  than ``near`` blocks and no straight slide (at its yaw, within the wrist's range, clear of every object
  and inside the workspace) brings it to where "around" is planned from. Before 2026-11-26 every start
  farther than ``near`` blocks was refused here: the rule then judged the approach too.
- ``blocked-around``: within ``near`` blocks of the anchor, the other objects and the workspace's rim leave
  the mover no legal pose (whatever its yaw) along some bearings, so no path sweeps the 0.8 turn: a
  continuous sweep passes every bearing of its arc, each frame a pose the 2-D world allows (issue 21).
  From afar (farther than ``near``), the rule reads "around" from the first frame within ``near`` on, so what
  counts is the way round, one way, from a legal pose where the mover can first come that near (an anchor
  near the rim is reachable from its inward side only, and its way round is cut at the rim, 2026-11-27). A
  bearing that the grid lets through only by its slack is looked at again finer (:func:`_crossable`); one with
  no legal pose is a wall no way round crosses.
- ``room-away``: no point of the workspace is one block farther from the anchor than the mover is now
  (the farthest point measured exactly, ``Workspace.farthest_from``).
- ``room-closer``: the mover cannot get close enough to close half the room "closer" asks for: two
  squares' centres are never nearer than the sum of their half sides plus the clearance the planner keeps
  between them (the world's margin, or the gap at the start where that is smaller: world2d.py's touching
  starts; measured with each hold's outline, the least over the holds, which favours the arm).
- ``no-motion`` (after the search, before anything is executed, :func:`check_moves`): the planner found
  no move that raises the progress, so its best plan leaves the mover where it is (one waypoint). It is
  refused, never executed and reported as a run ("swept 0.00 of a turn", exit 0, issue 27.8).

The room checks read the thresholds of the built-in rule judges (``judge/rules.py``: ``AROUND_TURNS``,
``AWAY_GAIN``, ``CLOSER_SHARE``, ``closer_room``) and apply to an action judged by those rules; a plugin
action judged otherwise gets the arm's checks only.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np

from ..core.geometry import posed_separation, separation
from ..core.scene import GRIPPER_MARGIN, Scene
from ..embodiment import reach
from ..embodiment.sim.arms import PANDA, ArmSpec
from ..errors import InfeasibleError
from ..judge.rules import AROUND_NEAR, AROUND_TURNS, AWAY_GAIN, CLOSER_SHARE, closer_room
from .problem import FRAME_STEP
from .world2d import World2D, place_outline

CHECKS = ("grasp-width", "grasp", "boxed-in", "room-around", "far-around", "blocked-around", "room-away", "room-closer", "no-motion")
MIN_TRAVEL_SIDES = 0.25  # a plan whose mover ends up nearer its start than this (and barely turned) did not move
MIN_TURN_RAD = math.radians(10.0)


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
        f'the arm "{arm.name}" cannot grasp "{mover}": its hand, coming down on the {m.height * 100:.0f} cm block, would hit '
        f'"{name}" ({other.height * 100:.0f} cm tall) or another taller block beside it whichever way it turns; '
        "move them apart",
        {"mover": mover, "blocking": name, "least_overlap_m": {k: round(-v, 6) for k, v in gaps.items() if v < 0}})


def check(scene: Scene, mover: str, anchor: str, rules: str | None = None, arm: ArmSpec = PANDA) -> list[reach.Hold]:
    """Run every check that applies; return the usable holds. ``rules``: the rule judge the action is
    judged by ("around", "away", "closer", ...), None for an action judged otherwise."""
    holds = grasp_holds(scene, mover, arm)
    _boxed_in(scene, mover, holds)
    if rules == "closer":
        _room_closer(scene, mover, anchor, holds)
    elif rules == "away":
        _room_away(scene, mover, anchor)
    elif rules == "around":
        _room_around(scene, mover, anchor)
        _blocked_around(scene, mover, anchor)
    return holds


def nearest_centres(m, a) -> float:
    """A bound (m) the two objects' centres are never nearer than: the sum of their footprints' inradii (two
    cubes: the half sides' sum, written as it always was so a cube scene's numbers stay bit-identical)."""
    if m.shape == "cube" and a.shape == "cube":
        return (m.size + a.size) / 2
    return m.inradius + a.inradius


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


def _room_around(scene: Scene, mover: str, anchor: str) -> None:
    m, a, ws = scene.get(mover), scene.get(anchor), scene.workspace
    rel = np.asarray(a.xy, float) - np.asarray(ws.center, float)
    rho_min = nearest_centres(m, a)  # centres never closer than the half sides' sum
    theta = np.linspace(-math.pi, math.pi, 1440, endpoint=False)
    u = np.column_stack([np.cos(theta), np.sin(theta)])
    if ws.ring is None:  # the disk's closed form (what the Panda's refusals have always used)
        rho = np.maximum(rho_min, -(u @ rel))  # the nearest point to the disk's centre along each bearing
        ok = np.linalg.norm(rel + rho[:, None] * u, axis=1) <= ws.radius + 1e-9
    else:  # disk and ring: the ray's intervals, the hole cut out (Workspace.rays_meet)
        ok = ws.rays_meet(a.xy, u, rho_min)
    arc = _longest_circular_run(ok) * 2 * math.pi / len(theta)
    if arc < AROUND_TURNS * 2 * math.pi - 2 * (2 * math.pi / len(theta)):
        raise InfeasibleError(
            "room-around",
            f'no room to move "{mover}" around "{anchor}": at {np.linalg.norm(rel):.3f} m from the workspace\'s '
            f"centre, the mover's centre can pass only {math.degrees(arc):.0f} deg of the way around it inside "
            f"the workspace ({f'radius {ws.radius} m' if ws.ring is None else ws.describe()}); around needs "
            f"{AROUND_TURNS * 360:.0f} deg",
            {"arc_deg": round(math.degrees(arc), 1), "needed_deg": AROUND_TURNS * 360})


SWEEP_GRID = (2.0, 0.05, 5.0)
"""The blocked-around grid: bearings every 2 degrees, centre distances every 0.05 of the mover's side, yaws every
5 degrees (over a quarter turn for a square); the poses between grid points are accounted for by a slack in the gap (favouring the arm)."""


def _blocked_around(scene: Scene, mover: str, anchor: str) -> None:
    m, a, ws = scene.get(mover), scene.get(anchor), scene.workspace
    world = World2D(scene, mover)  # the block's own outline: smaller than a hand-grown one, so it favours the arm
    bearing_deg, radius_sides, yaw_deg = SWEEP_GRID
    inner, outer = nearest_centres(m, a), AROUND_NEAR * m.size
    radii = np.linspace(inner, outer, max(2, math.ceil((outer - inner) / (radius_sides * m.size)) + 1))
    dr = float(radii[1] - radii[0]) / 2  # a legal pose is at most half a step from a grid radius ...
    dyaw = math.radians(yaw_deg) / 2  # ... and half a step from a grid yaw
    bearings = np.radians(np.arange(0.0, 360.0, bearing_deg))
    quarter = np.allclose(np.sort(np.round(world.mover.outline @ np.array([[0.0, 1.0], [-1.0, 0.0]]), 9), axis=0),
                          np.sort(np.round(world.mover.outline, 9), axis=0))  # a square looks the same a quarter turn on
    yaws = np.radians(np.arange(0.0, 90.0 if quarter else 360.0, yaw_deg))
    t, r, y = np.meshgrid(bearings, radii, yaws, indexing="ij")
    poses = np.column_stack([a.xy[0] + (r * np.cos(t)).ravel(), a.xy[1] + (r * np.sin(t)).ravel(), y.ravel()])
    # from afar (below): a pose is within half a step of radius and half a bearing step *at its radius* of a grid pose
    along = (r.ravel() + dr) * math.radians(bearing_deg) / 2
    clear = ws.clearance(poses[:, :2])
    if ws.ring is None:  # the disk's closed form
        centre_d = np.linalg.norm(poses[:, :2] - np.asarray(ws.center, float), axis=1)
        ok = centre_d <= ws.radius + dr + 1e-9
        ok_far = centre_d <= ws.radius + dr + along + 1e-9
    else:  # a grid pose within the slack of the region (its clearance's size never exceeds its distance to it)
        ok = clear >= -dr - 1e-9
        ok_far = clear >= -(dr + along) - 1e-9
    reach_m = float(np.linalg.norm(world.mover.outline, axis=1).max())
    slack = dr + reach_m * dyaw  # how much the gap can change within half a grid step
    wide = slack + outer * math.radians(bearing_deg) / 2  # ... and within half a bearing step, at the outer radius
    short = np.full(len(poses), np.inf)  # per pose: the least gap minus the margin it needs, over the obstacles
    margins = [min(world.margin, max(float(g), 0.0)) for g in world.gaps(m.pose)]  # the world's rule for a close start
    for body, poly, margin in zip(world.obstacles, world._obs_polys, margins, strict=True):
        reach_o = float(np.linalg.norm(body.outline, axis=1).max())
        near = ok_far & (np.linalg.norm(poses[:, :2] - body.pose[:2], axis=1) <= reach_m + reach_o + margin + wide)
        if near.any():
            gaps = posed_separation(world.mover.outline, poses[near], poly)
            idx = np.flatnonzero(near)
            short[idx] = np.minimum(short[idx], gaps - margin)
    legal = (clear >= 0.0) & (short >= 0.0)  # grid poses that are legal themselves
    cross = _crossable(world, margins, a.xy, bearings, radii, yaws, (ok & (short >= -slack)).reshape(len(bearings), -1),
                       legal.reshape(len(bearings), -1), dr, dyaw, reach_m)
    arc = _longest_circular_run(cross) * bearing_deg
    if arc < AROUND_TURNS * 360 - 2 * bearing_deg:
        raise InfeasibleError(
            "blocked-around",
            f'no way round "{anchor}" for "{mover}": within {AROUND_NEAR:g} blocks of it, the other objects and the '
            f"workspace's rim leave the mover room to pass only {arc:.0f} deg of the way round (at any yaw); "
            f"around needs {AROUND_TURNS * 360:.0f} deg", {"arc_deg": round(arc, 1), "needed_deg": AROUND_TURNS * 360})
    # the sweep must also be one connected way from the start: cells (bearing x radius) holding a legal pose
    # within half a step of each (any yaw), joined to their 8 neighbours (a continuous path's nearest cell
    # only ever moves to a neighbour)
    cells = (ok & (short >= -wide)).reshape(len(bearings), len(radii), -1).any(2) & cross[:, None]
    rel = np.asarray(m.xy, float) - a.xy
    k0 = int(round(math.degrees(math.atan2(rel[1], rel[0])) / bearing_deg)) % len(bearings)
    d0 = float(np.hypot(*rel))
    j0 = int(np.argmin(np.abs(radii - d0)))
    if cells[k0, j0] and d0 <= outer + 1e-9:
        way = _entry_sweep(cells, [(k0, j0)]) * bearing_deg
        if way < AROUND_TURNS * 360 - 2 * bearing_deg:
            raise InfeasibleError(
                "blocked-around",
                f'no way round "{anchor}" for "{mover}": within {AROUND_NEAR:g} blocks of it, the other objects and '
                f"the workspace's rim leave the mover a way of only {way:.0f} deg round from where it starts (at any "
                f"yaw); around needs {AROUND_TURNS * 360:.0f} deg",
                {"arc_deg": round(way, 1), "needed_deg": AROUND_TURNS * 360, "connected": True})
    elif d0 > outer + 1e-9:
        # from afar the mover first comes near (approach.py, where that slide ends is the planner's); the rule
        # reads "around" from the first frame within near on, and frames are at most FRAME_STEP of a side apart,
        # so that frame is a legal pose less than FRAME_STEP inside the near circle (a cell of the outer radii):
        # what counts is the way round from such an entry, one way (the turn is the bearing's net change)
        far_cells = (ok_far & (short >= -(slack + along))).reshape(len(bearings), len(radii), -1).any(2) & cross[:, None]
        entries = [(int(k), int(j)) for k, j in np.argwhere(far_cells)
                   if radii[j] >= outer - FRAME_STEP * m.size - 2 * dr]
        way = _entry_sweep(far_cells, entries) * bearing_deg
        if way < AROUND_TURNS * 360 - 2 * bearing_deg:
            raise InfeasibleError(
                "blocked-around",
                f'no way round "{anchor}" for "{mover}" from afar: it starts {d0 / m.size:.2f} blocks away, and from '
                f"wherever it can come within {AROUND_NEAR:g} blocks the other objects and the workspace's rim leave "
                f"it a way of only {way:.0f} deg round (at any yaw); around needs {AROUND_TURNS * 360:.0f} deg",
                {"arc_deg": round(way, 1), "needed_deg": AROUND_TURNS * 360, "connected": True, "from_afar": True})


REFINE_LEVELS = 3
"""Times a bearing's doubtful poses are cut into 3 x 3 (radius x yaw) finer ones by :func:`_crossable`."""
THIRDS = np.array([-2.0, 0.0, 2.0])


def _crossable(world: World2D, margins: list[float], centre: np.ndarray, bearings: np.ndarray, radii: np.ndarray,
               yaws: np.ndarray, passing: np.ndarray, legal: np.ndarray, dr: float, dyaw: float,
               reach_m: float) -> np.ndarray:
    """Per grid bearing, whether the mover can stand on it (a path sweeping round crosses every bearing of its
    arc). ``passing`` (bearings x poses): a legal pose may lie within half a grid step, by the slack; ``legal``:
    the grid pose is legal itself. A bearing with a legal grid pose is crossable; one whose poses pass only by
    the slack is settled by cutting each such pose's half-step box into 3 x 3 finer boxes (radius x yaw), keeping
    those that still pass with their own, 3 times smaller slack, :data:`REFINE_LEVELS` times: none left, and no
    legal pose met, means no legal pose on that bearing (its slack sound as the grid's); some left, crossable
    (favouring the arm). Why (2026-11-27): near the far edge of the arm's reach ring the grid's slack let "around"
    through where no pose of the block fits within 24 degrees of bearing (analysis chain 5334, clause 2)."""
    cross = passing.any(1)
    r_of, y_of = (g.ravel() for g in np.meshgrid(radii, yaws, indexing="ij"))
    ws = world.workspace
    for k in np.flatnonzero(cross & ~legal.any(1)):
        r, y, hr, hy = r_of[passing[k]], y_of[passing[k]], dr, dyaw
        c, s = math.cos(bearings[k]), math.sin(bearings[k])
        cross[k] = False
        for _ in range(REFINE_LEVELS):
            hr, hy = hr / 3, hy / 3  # each box's 9 boxes: centres 2/3 of the half-width either side, and its own
            dr9, dy9 = (g.ravel() for g in np.meshgrid(THIRDS * hr, THIRDS * hy, indexing="ij"))
            r, y = (r[:, None] + dr9).ravel(), (y[:, None] + dy9).ravel()
            poses = np.column_stack([centre[0] + r * c, centre[1] + r * s, y])
            clear = ws.clearance(poses[:, :2])
            short = np.full(len(poses), np.inf)
            for outline, poly, margin in zip(world._outlines, world._obs_polys, margins, strict=True):
                short = np.minimum(short, posed_separation(outline, poses, poly) - margin)
            if ((clear >= 0.0) & (short >= 0.0)).any():
                cross[k] = True
                break
            keep = (clear >= -hr - 1e-12) & (short >= -(hr + reach_m * hy) - 1e-12)
            r, y = r[keep], y[keep]
            if not len(r):
                break
        else:
            cross[k] = len(r) > 0
    return cross


def _entry_sweep(cells: np.ndarray, entries: list[tuple[int, int]]) -> int:
    """The most bearing steps one way round that a chain of 8-neighbouring True cells of ``cells`` (bearings x
    radii, bearings circular) reaches from any of ``entries`` (bearing, radius indices): per component, its
    cells' bearings unwrapped from one of them; a component that closes round the anchor gives a full turn
    (at most one). One entry: the sweep from where the mover starts; several: from wherever it can come near,
    one search per component rather than one per entry."""
    n, m = cells.shape
    seen: set[tuple[int, int]] = set()
    best = 0
    for start in entries:
        if start in seen:
            continue
        where = {start: start[0]}  # cell -> its unwrapped bearing index
        queue = deque([start])
        while queue:
            k, j = queue.popleft()
            u = where[(k, j)]
            for dk in (-1, 0, 1):
                for dj in (-1, 0, 1):
                    nj, cell = j + dj, ((k + dk) % n, j + dj)
                    if not (dk or dj) or not 0 <= nj < m or not cells[cell]:
                        continue
                    if cell not in where:
                        where[cell] = u + dk
                        queue.append(cell)
                    elif where[cell] != u + dk:
                        return n  # reached again a turn on: a way all round
        seen.update(where)
        lo, hi = min(where.values()), max(where.values())
        best = max([best] + [max(hi - where[e], where[e] - lo) for e in entries if e in where])
        if best >= n:
            return n
    return best


def _room_away(scene: Scene, mover: str, anchor: str) -> None:
    m, a, ws = scene.get(mover), scene.get(anchor), scene.workspace
    d0 = float(np.hypot(*(np.asarray(m.xy) - a.xy)))
    if ws.ring is None:  # the disk's closed form
        farthest = ws.radius + float(np.hypot(*(np.asarray(a.xy) - ws.center)))
    else:
        farthest = ws.farthest_from(a.xy)[0]
    if farthest < d0 + AWAY_GAIN * m.size - 1e-9:
        raise InfeasibleError(
            "room-away",
            f'no room to move "{mover}" away from "{anchor}": it is {d0 / m.size:.2f} blocks away and no point of '
            f"the workspace is more than {farthest / m.size:.2f}; away needs {AWAY_GAIN:.0f} block more",
            {"start_blocks": round(d0 / m.size, 3), "farthest_blocks": round(farthest / m.size, 3)})


def clearance(scene: Scene, mover: str, anchor: str, holds: list[reach.Hold] | None = None) -> float:
    """The least gap (m) the planner ever lets the mover's footprint come to the anchor's: the world's margin, or
    the gap where the mover starts when that is smaller (world2d.py: a move's margin is the smaller of the
    margin and the gap at its start, so no move brings it nearer than it started). The start's gap is measured
    with each hold's outline (the block grown by the hand against a taller anchor; that outline's gap is what
    the planner keeps, and the footprint's is never smaller), the least over ``holds`` (all: favours the arm)."""
    m, a = scene.get(mover), scene.get(anchor)
    own = m.footprint(np.zeros(3))
    poly = a.footprint(a.pose)
    outlines = [h.outlines.get(anchor, own) for h in holds] if holds else [own]
    g0 = min(float(separation(place_outline(np.asarray(o, float), m.pose)[None], poly)[0]) for o in outlines)
    return max(0.0, min(GRIPPER_MARGIN, max(g0, 0.0) - 1e-9))


def _room_closer(scene: Scene, mover: str, anchor: str, holds: list[reach.Hold] | None = None) -> None:
    m, a = scene.get(mover), scene.get(anchor)
    d0 = float(np.hypot(*(np.asarray(m.xy) - a.xy))) / m.size
    room = closer_room(d0)
    target = d0 - CLOSER_SHARE * room
    gap = clearance(scene, mover, anchor, holds)
    nearest = (nearest_centres(m, a) + gap) / m.size
    if nearest > target + 1e-9:
        raise InfeasibleError(
            "room-closer",
            f'"{mover}" cannot come closer to "{anchor}" by the half of the room that "closer" asks for: their '
            f"centres are {d0:.3f} blocks apart, closer needs {target:.3f}, and the blocks' sizes with the "
            f"{gap * 1000:.1f} mm the planner keeps between them leave them at least {nearest:.3f} apart",
            {"start_blocks": round(d0, 3), "needed_blocks": round(target, 3), "nearest_blocks": round(nearest, 3),
             "clearance_m": round(gap, 6)})


def _longest_circular_run(ok: np.ndarray) -> int:
    if ok.all():
        return len(ok)
    if not ok.any():
        return 0
    k = int(np.argmin(ok))  # start the scan at a False so runs do not wrap
    best = run = 0
    for v in np.roll(ok, -k):
        run = run + 1 if v else 0
        best = max(best, run)
    return best


def check_moves(scene: Scene, mover: str, anchor: str, path: np.ndarray, *, action: str, stopped: str,
                progress: float, steps: int) -> None:
    """InfeasibleError ("no-motion") for a plan that does not move the mover, unless the action was
    already done at the start (the search stopped at its threshold)."""
    p = np.asarray(path, float).reshape(-1, 3)
    m, a = scene.get(mover), scene.get(anchor)
    travel = float(np.max(np.hypot(*(p[:, :2] - p[0, :2]).T))) if len(p) else 0.0
    turn = float(np.max(np.abs(p[:, 2] - p[0, 2]))) if len(p) else 0.0
    if stopped == "threshold" or (len(p) >= 2 and (travel >= MIN_TRAVEL_SIDES * m.size or turn >= MIN_TURN_RAD)):
        return
    sides = float(np.hypot(*(np.asarray(m.xy) - np.asarray(a.xy)))) / m.size
    ratio = max(m.size, a.size) / min(m.size, a.size)
    hint = (f"; the {m.size * 100:.0f} cm mover starts {sides:.1f} of its sides from the {a.size * 100:.0f} cm "
            "anchor, and the built-in actions measure distances in the mover's sides (learned from two blocks "
            "of one size): try blocks of similar size, nearer each other" if ratio > 1.5 or sides > 4.0
            else "; another --planner or --seed may find one")
    raise InfeasibleError(
        "no-motion",
        f'no plan moves "{mover}" for "{action}" relative to "{anchor}": no move raised the learned progress '
        f"(best {progress:.3f} after {steps} search steps), so it would stay where it is{hint}",
        {"waypoints": len(p), "travel_m": round(travel, 6), "progress": round(float(progress), 6), "steps": steps,
         "mover_size_m": m.size, "anchor_size_m": a.size, "distance_sides": round(sides, 2)})

