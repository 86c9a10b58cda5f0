"""A pushed block is planned with the closed fingers behind it along each move (World2D's ``pusher``), not a
disk of the pusher's reach all round it: pushed "towards" another block it comes up to it, as a slide does,
and a move away from a block it touches needs room for the fingers between the two."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.embodiment.manners import manner_planning, push_pusher
from l2p_bullet.manners import registry
from l2p_bullet.pipeline import judged_plan, prepare
from l2p_bullet.planning.world2d import World2D

LEVEL = Scene([SceneObject("A", "red", 0.04, (0.01986, -0.04089), 1.5237),
               SceneObject("B", "green", 0.04, (-0.03905, -0.03812), 1.5237)])
"""A study start (SlideToward 2) set level with the anchor, 1.47 sides apart face to face (bench_clauses.py)."""


def test_the_pusher_is_behind_the_block_along_the_move_only():
    scene = Scene([SceneObject("A", "red", 0.04, (0.0445, 0.0), 0.0), SceneObject("B", "green", 0.04, (0.0, 0.0), 0.0)])
    world = World2D(scene, "A", pusher=push_pusher(0.04))
    start = np.array([0.0445, 0.0, 0.0])
    side = np.array([0.062, 0.0, 0.0])  # 2.2 cm from B's face: room for the fingers' overhang beside the block
    assert World2D(scene, "A", pusher=push_pusher(0.04)).moves_free(side, np.array([[0.062, 0.08, 0.0]]))[0]
    assert not world.moves_free(start, np.array([[0.15, 0.0, 0.0]]))[0]  # away from B: the fingers come down on B
    free = World2D(scene, "A")
    assert free.moves_free(start, np.array([[0.15, 0.0, 0.0]]))[0]  # a held block may leave B straight away
    far = np.array([0.15, 0.0, 0.0])
    assert world.moves_free(far, np.array([[0.0455 + 0.005, 0.0, 0.0]]))[0]  # pushed up to B's margin


def test_the_manner_tells_the_planner_about_the_pusher():
    assert manner_planning(registry.get("push"), 0.04) == {"pusher": push_pusher(0.04)}
    assert manner_planning(registry.get("slide"), 0.04) == {}


@pytest.mark.slow
def test_push_towards_from_a_level_start_moves_the_block_and_passes_the_judge():
    plan, verdict = judged_plan(prepare("push A towards B", LEVEL, seed=6102))
    moved = float(np.hypot(*(plan.path[-1, :2] - plan.path[0, :2]))) / 0.04
    assert verdict["success"], verdict["reason"]
    assert moved > 0.25  # it closes the room, not a sliver of it


def test_a_block_touching_beside_the_anchors_corner_is_pushed_along_its_face():
    """A block turned 16 degrees whose corner is 4.8 mm from the anchor's face, its centre level with the anchor's
    corner (development start SlideToward/6 touching, in the anchor's frame): pushed along the face past that
    corner the fingers stay 6.5 mm from the anchor, though one hull of block and fingers would cover the anchor's
    corner (no pushed move was legal, and "push A past B" found no plan)."""
    s = 0.04
    scene = Scene([SceneObject("A", "red", s, (-1.144 * s, 0.498 * s), np.radians(-16.0)),
                   SceneObject("B", "green", s, (0.0, 0.0), 0.0)])
    start = np.array([-1.144 * s, 0.498 * s, np.radians(-16.0)])
    along = start + np.array([0.0, 0.02, 0.0])
    assert World2D(scene, "A").moves_free(start, along[None])[0]
    assert World2D(scene, "A", pusher=push_pusher(s)).moves_free(start, along[None])[0]
    away = start + np.array([-0.02, 0.0, 0.0])  # straight away from B the fingers would come down between them
    assert World2D(scene, "A").moves_free(start, away[None])[0]
    assert not World2D(scene, "A", pusher=push_pusher(s)).moves_free(start, away[None])[0]
