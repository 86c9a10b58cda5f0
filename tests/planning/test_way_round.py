"""The way round among bystanders (planning/detour.py) counted as the rule counts "around": from where the mover
came within ``near`` of the anchor, and, where a wall of blocks cuts every way short of 0.9 of a turn, the farthest
way that still passes the rule's 0.8 with room to spare. 2-D only: no arm, no physics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from l2p_bullet.core.scene import Scene
from l2p_bullet.judge.rules import AROUND_NEAR, AROUND_TURNS
from l2p_bullet.planning import approach, detour
from l2p_bullet.planning.world2d import World2D

SIDE = 0.05


def _walled(bearing_deg: float, start_sides: float = 2.5) -> Scene:
    """A at the centre, E and C on the +x axis 2.3 and 3.8 blocks out (a wall from A to beyond ``near``: no gap
    the mover fits through), the mover D ``start_sides`` blocks from A at ``bearing_deg``."""
    b = math.radians(bearing_deg)
    at = {"A": (0.0, 0.0), "D": (start_sides * SIDE * math.cos(b), start_sides * SIDE * math.sin(b)),
          "E": (2.3 * SIDE, 0.0), "C": (3.8 * SIDE, 0.0)}
    return Scene.from_dict({"objects": [{"name": n, "xy": list(xy), "yaw": 0.0, "size": SIDE, "color": "red"}
                                        for n, xy in at.items()]})


def _turns(route: np.ndarray, anchor: np.ndarray) -> float:
    rel = route[:, :2] - anchor[:2]
    b = np.unwrap(np.arctan2(rel[:, 1], rel[:, 0]))
    return float(b[-1] - b[0]) / (2 * math.pi)


def _legal(world: World2D, route: np.ndarray, anchor: np.ndarray) -> None:
    assert world.path_free(route)
    assert np.hypot(*(route[:, :2] - anchor[:2]).T).max() <= AROUND_NEAR * SIDE + 1e-9


def test_a_wall_that_cuts_every_way_short_of_0_9_turn_still_gives_the_farthest_way_past_the_rule():
    # from 30 deg the wall on the +x axis leaves about 0.86 of a turn one way: no way of GOAL_TURNS, and before,
    # no way at all (the planner then searched blind and stopped short of 0.8: development chain 9707's kind)
    scene = _walled(30.0)
    world, anchor = World2D(scene, "D"), np.asarray(scene.get("A").pose, float)
    route = detour.around_route(world, anchor, AROUND_NEAR)
    assert route is not None
    _legal(world, route, anchor)
    assert detour.LEAST_TURNS <= abs(_turns(route, anchor)) < detour.GOAL_TURNS
    assert abs(_turns(route, anchor)) > AROUND_TURNS


def test_a_way_short_of_the_least_turn_is_still_none():
    scene = _walled(35.0)  # about 0.85 of a turn, a hair short of LEAST_TURNS
    world, anchor = World2D(scene, "D"), np.asarray(scene.get("A").pose, float)
    assert detour.around_route(world, anchor, AROUND_NEAR) is None


def test_the_turn_already_made_since_coming_near_counts_towards_the_way():
    # an approach that came within near 25 deg back (the way's direction) has swept that much already, as the rule
    # reads it: the way from its end then goes the 0.9 turn counted from there; the other way round, it has spent it
    scene = _walled(35.0)
    world, anchor = World2D(scene, "D"), np.asarray(scene.get("A").pose, float)
    route = detour.around_route(world, anchor, AROUND_NEAR, swept=math.radians(25.0))
    assert route is not None
    _legal(world, route, anchor)
    assert _turns(route, anchor) + 25.0 / 360 >= detour.GOAL_TURNS - 1e-9
    assert detour.around_route(world, anchor, AROUND_NEAR, swept=math.radians(-25.0)) is None


def test_swept_near_counts_from_the_first_frame_within_near():
    near = AROUND_NEAR * SIDE
    bearings = np.radians([-60.0, -40.0, -20.0, 0.0, 10.0])
    radii = np.array([6.0, 4.5, 3.9, 3.0, 2.5]) * SIDE  # within near from the third frame on
    frames = np.column_stack([radii * np.cos(bearings), radii * np.sin(bearings), np.zeros(5)])
    assert approach.swept_near(frames, np.zeros(2), near) == pytest.approx(math.radians(30.0))
    assert approach.swept_near(frames[:2], np.zeros(2), near) == 0.0  # never near


def _reference_way(legal, entries, goal, banned=frozenset(), turns=(), credit=0.0, least=None):
    """The search as first written (each cell read from the array, each step keyed by ``detour._edge``): what
    the faster search must find, cell for cell, ties included."""
    import heapq
    import itertools

    ny, n, m = legal.shape
    dist, prev, heap, count = {}, {}, [], itertools.count()
    for cell in entries:
        dist[cell], prev[cell] = 0.0, None
        heapq.heappush(heap, (0.0, next(count), cell))
    farthest = None

    def back(c, cell):
        way = [cell]
        while prev[way[-1]] is not None:
            way.append(prev[way[-1]])
        return c, way[::-1]

    while heap:
        c, _, cell = heapq.heappop(heap)
        if c > dist[cell]:
            continue
        k, j, y = cell
        if abs(k + credit) >= goal:
            return back(c, cell)
        if least is not None and (farthest is None or abs(k + credit) > farthest[0]):
            farthest = (abs(k + credit), c, cell)
        for dk in (-1, 0, 1):
            for dj in (-1, 0, 1):
                for dy in ((-1, 0, 1) if ny > 1 else (0,)):
                    nxt = (k + dk, j + dj, y + dy)
                    if (not (dk or dj or dy) or not 0 <= nxt[1] < m or not 0 <= nxt[2] < ny
                            or abs(nxt[0] + credit) > goal or not legal[nxt[2], nxt[0] % n, nxt[1]]
                            or (banned and detour._edge(cell, nxt, n) in banned)):
                        continue
                    nc = c + 1.0 + (turns[min(y, nxt[2])] if dy else 0.0)
                    if nc < dist.get(nxt, math.inf):
                        dist[nxt], prev[nxt] = nc, cell
                        heapq.heappush(heap, (nc, next(count), nxt))
    return back(farthest[1], farthest[2]) if farthest is not None and farthest[0] >= least else None


def test_the_search_finds_the_ways_the_plain_search_finds():
    """On random grids of one to three yaws, with banned steps, turn costs, a credit and a least turn."""
    rng = np.random.default_rng(0)
    found = 0
    for _ in range(150):
        ny, n, m = int(rng.choice([1, 1, 2, 3])), int(rng.integers(8, 40)), int(rng.integers(2, 7))
        legal = rng.random((ny, n, m)) < rng.uniform(0.5, 0.95)
        entries = [(0, int(rng.integers(0, m)), int(rng.integers(0, ny))) for _ in range(int(rng.integers(1, 3)))]
        goal = int(rng.integers(2, n + 3))
        turns = [float(rng.uniform(0, 3)) for _ in range(ny - 1)]
        credit = float(rng.choice([0.0, rng.uniform(-3, 3)]))
        least = None if rng.random() < 0.5 else int(rng.integers(1, goal + 1))
        banned = set()
        for _ in range(int(rng.integers(0, 40))):
            c0 = (int(rng.integers(-n, 2 * n)), int(rng.integers(0, m)), int(rng.integers(0, ny)))
            c1 = (c0[0] + int(rng.integers(-1, 2)), int(np.clip(c0[1] + rng.integers(-1, 2), 0, m - 1)),
                  int(np.clip(c0[2] + rng.integers(-1, 2), 0, ny - 1)))
            banned.add(detour._edge(c0, c1, n))
        way = detour._shortest_way(legal, entries, goal, banned, turns, credit, least)
        assert way == _reference_way(legal, entries, goal, banned, turns, credit, least)
        found += way is not None
    assert 50 < found < 150  # ways found and not found
