""""closer" from a start on the anchor's diagonal, corner to corner: where the way in to the nearest face is blocked,
the way in to the other face on the mover's side is taken."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.actions.closer import ACTION
from l2p_bullet.core.scene import FACE_MARGIN, Scene, SceneObject
from l2p_bullet.judge.rules import rule_verdict
from l2p_bullet.planning.nearer import nearer_path
from l2p_bullet.planning.world2d import World2D, interpolate

SIZE = 0.05


@pytest.mark.slow  # the way in to the blocked face is tried first, as every gap and step count: a few seconds
def test_a_start_on_the_diagonal_takes_the_other_face_where_a_block_stands_before_the_nearest():
    # the chain start 21088, clause 5 ("move C closer to A"): C's centre 1.2503 blocks out of one face's line of A
    # and 1.2490 out of the other's, B beside A in front of the first face
    scene = Scene([SceneObject("A", "red", SIZE, (-0.152417, -0.076468), 0.511123),
                   SceneObject("B", "green", SIZE, (-0.206941, -0.107105), 0.511842),
                   SceneObject("C", "blue", SIZE, (-0.237491, -0.052581), 0.511405)]).validate()
    world = World2D(scene, "C")
    way = nearer_path(scene, "C", "A", ACTION, scene.get("C").pose, world, None)
    assert way is not None
    assert world.nearer_to("A", FACE_MARGIN).path_free(way)  # face to face nothing of the hand is between
    verdict = rule_verdict("closer", interpolate(way, 0.25 * SIZE), scene.get("A").pose, SIZE)
    assert verdict.success, verdict.reason
    assert np.hypot(*(way[-1, :2] - scene.get("B").xy)) > SIZE  # not in front of B's face
