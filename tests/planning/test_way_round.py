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
