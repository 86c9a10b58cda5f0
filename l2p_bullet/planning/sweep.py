"""Can "around" go round? The two up-front checks of the sweep (feasibility.py runs them, docs/perform.md):

- ``room-around`` (:func:`room_around`): the mover's centre must stay in the workspace, so around an anchor near
  the disk's rim (or the edge of an arm's reach ring, ``core/workspace.py``) the directions it can take around
  the anchor cover less than the 0.8 turn "around" needs (exactly, along each bearing).
- ``blocked-around`` (:func:`blocked_around`): within ``near`` blocks of the anchor the other objects and the
  workspace's rim leave the mover no legal pose along some bearings, or no connected way of 0.8 turn from where
  it starts (or, from afar, from where it can first come near). A grid of bearings x radii x yaws with a slack
  that favours the arm; a bearing the grid lets through only by its slack is settled finer
  (:func:`crossable`).

Both are necessary conditions, measured with bounds that favour the arm, like every check of feasibility.py:
a refusal is a real impossibility. feasibility.py raises the refusals; the gap test
is ``World2D.shortfall``, which the way round (detour.py) uses too.
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np

from ..core.geometry import nearest_centres
from ..core.scene import Scene
from ..errors import InfeasibleError
from ..judge.rules import AROUND_NEAR, AROUND_TURNS
from .problem import FRAME_STEP
from .world2d import World2D


def room_around(scene: Scene, mover: str, anchor: str, *, turns: float = AROUND_TURNS) -> None:
    """InfeasibleError("room-around") when the workspace leaves the mover's centre less than the 0.8 turn
    round the anchor (the bystanders aside: that is :func:`blocked_around`'s); ``turns``: the share of a turn
    the rule asks for (the around rule's by default)."""
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
    arc = longest_circular_run(ok) * 2 * math.pi / len(theta)
    if arc < turns * 2 * math.pi - 2 * (2 * math.pi / len(theta)):
        raise InfeasibleError(
            "room-around",
            f'no room to move "{mover}" around "{anchor}": at {np.linalg.norm(rel):.3f} m from the workspace\'s '
            f"centre, the mover's centre can pass only {math.degrees(arc):.0f} deg of the way around it inside "
            f"the workspace ({f'radius {ws.radius} m' if ws.ring is None else ws.describe()}); around needs "
            f"{turns * 360:.0f} deg",
            {"arc_deg": round(math.degrees(arc), 1), "needed_deg": turns * 360})


SWEEP_GRID = (2.0, 0.05, 5.0)
"""The blocked-around grid: bearings every 2 degrees, centre distances every 0.05 of the mover's side, yaws every
5 degrees (over a quarter turn for a square); the poses between grid points are accounted for by a slack in the
gap (favouring the arm)."""


def blocked_around(scene: Scene, mover: str, anchor: str, *, turns: float = AROUND_TURNS,
                   near: float = AROUND_NEAR) -> None:
    """InfeasibleError("blocked-around") when, within ``near`` blocks, the bystanders and the workspace leave no
    legal pose along enough bearings, or no connected way of 0.8 turn from the start (or, from afar, from where
    the mover can first come near). ``turns`` and ``near``: the rule's (the around rule's by default)."""
    m, a, ws = scene.get(mover), scene.get(anchor), scene.workspace
    # what is in the way, as the refusal says it: a carry's check reads the anchor and the rim alone
    walls = ("the other objects and the workspace's rim leave" if len(scene.objects) > 2
             else "the workspace's rim leaves")
    world = World2D(scene, mover)  # the block's own outline: smaller than a hand-grown one, so it favours the arm
    bearing_deg, radius_sides, yaw_deg = SWEEP_GRID
    inner, outer = nearest_centres(m, a), near * m.size
    radii = np.linspace(inner, outer, max(2, math.ceil((outer - inner) / (radius_sides * m.size)) + 1))
    dr = float(radii[1] - radii[0]) / 2  # a legal pose is at most half a step from a grid radius ...
    dyaw = math.radians(yaw_deg) / 2  # ... and half a step from a grid yaw
    bearings = np.radians(np.arange(0.0, 360.0, bearing_deg))
    quarter = np.allclose(np.sort(np.round(world.mover.outline @ np.array([[0.0, 1.0], [-1.0, 0.0]]), 9), axis=0),
                          # a square looks the same a quarter turn on
                          np.sort(np.round(world.mover.outline, 9), axis=0))
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
    margins = world.start_margins()  # the world's rule for a close start
    short = world.shortfall(poses, margins, mask=ok_far, within=wide)  # per pose: the least gap less its margin
    legal = (clear >= 0.0) & (short >= 0.0)  # grid poses that are legal themselves
    cross = crossable(world, margins, a.xy, bearings, radii, yaws, (ok & (short >= -slack)).reshape(len(bearings), -1),
                       legal.reshape(len(bearings), -1), dr, dyaw, reach_m)
    arc = longest_circular_run(cross) * bearing_deg
    if arc < turns * 360 - 2 * bearing_deg:
        raise InfeasibleError(
            "blocked-around",
            f'no way round "{anchor}" for "{mover}": within {near:g} blocks of it, {walls} the mover room to '
            f"pass only {arc:.0f} deg of the way round (at any yaw); "
            f"around needs {turns * 360:.0f} deg", {"arc_deg": round(arc, 1), "needed_deg": turns * 360})
    # the sweep must also be one connected way from the start: cells (bearing x radius) holding a legal pose
    # within half a step of each (any yaw), joined to their 8 neighbours (a continuous path's nearest cell
    # only ever moves to a neighbour)
    cells = (ok & (short >= -wide)).reshape(len(bearings), len(radii), -1).any(2) & cross[:, None]
    rel = np.asarray(m.xy, float) - a.xy
    k0 = int(round(math.degrees(math.atan2(rel[1], rel[0])) / bearing_deg)) % len(bearings)
    d0 = float(np.hypot(*rel))
    j0 = int(np.argmin(np.abs(radii - d0)))
    if cells[k0, j0] and d0 <= outer + 1e-9:
        way = entry_sweep(cells, [(k0, j0)]) * bearing_deg
        if way < turns * 360 - 2 * bearing_deg:
            raise InfeasibleError(
                "blocked-around",
                f'no way round "{anchor}" for "{mover}": within {near:g} blocks of it, {walls} the mover a '
                f"way of only {way:.0f} deg round from where it starts (at any yaw); around needs "
                f"{turns * 360:.0f} deg",
                {"arc_deg": round(way, 1), "needed_deg": turns * 360, "connected": True})
    elif d0 > outer + 1e-9:
        # from afar the mover first comes near (approach.py, where that slide ends is the planner's); the rule
        # reads "around" from the first frame within near on, and frames are at most FRAME_STEP of a side apart,
        # so that frame is a legal pose less than FRAME_STEP inside the near circle (a cell of the outer radii):
        # what counts is the way round from such an entry, one way (the turn is the bearing's net change)
        far_cells = (ok_far & (short >= -(slack + along))).reshape(len(bearings), len(radii), -1).any(2) & cross[
            :, None
        ]
        entries = [(int(k), int(j)) for k, j in np.argwhere(far_cells)
                   if radii[j] >= outer - FRAME_STEP * m.size - 2 * dr]
        way = entry_sweep(far_cells, entries) * bearing_deg
        if way < turns * 360 - 2 * bearing_deg:
            raise InfeasibleError(
                "blocked-around",
                f'no way round "{anchor}" for "{mover}" from afar: it starts {d0 / m.size:.2f} blocks away, and from '
                f"wherever it can come within {near:g} blocks {walls} it a way of only {way:.0f} deg round "
                f"(at any yaw); around needs {turns * 360:.0f} deg",
                {"arc_deg": round(way, 1), "needed_deg": turns * 360, "connected": True, "from_afar": True})


REFINE_LEVELS = 3
"""Times a bearing's doubtful poses are cut into 3 x 3 (radius x yaw) finer ones by :func:`crossable`."""
THIRDS = np.array([-2.0, 0.0, 2.0])


def crossable(world: World2D, margins: np.ndarray, centre: np.ndarray, bearings: np.ndarray, radii: np.ndarray,
               yaws: np.ndarray, passing: np.ndarray, legal: np.ndarray, dr: float, dyaw: float,
               reach_m: float) -> np.ndarray:
    """Per grid bearing, whether the mover can stand on it (a path sweeping round crosses every bearing of its
    arc). ``passing`` (bearings x poses): a legal pose may lie within half a grid step, by the slack; ``legal``:
    the grid pose is legal itself. A bearing with a legal grid pose is crossable; one whose poses pass only by
    the slack is settled by cutting each such pose's half-step box into 3 x 3 finer boxes (radius x yaw), keeping
    those that still pass with their own, 3 times smaller slack, :data:`REFINE_LEVELS` times: none left, and no
    legal pose met, means no legal pose on that bearing (its slack sound as the grid's); some left, crossable
    (favouring the arm). Why: near the far edge of the arm's reach ring the grid's slack let "around"
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
            short = world.shortfall(poses, margins)
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


def entry_sweep(cells: np.ndarray, entries: list[tuple[int, int]]) -> int:
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


def longest_circular_run(ok: np.ndarray) -> int:
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
