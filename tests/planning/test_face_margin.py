"""A "closer" that meets the anchor face to face, nothing of the hand between them, may end nearer than the
planner's 5 mm margin (``FACE_MARGIN``): from a start level with the anchor 1-1.2 cm away half the room ends
within about 6 mm, which the margin kept out of reach (planning/nearer.py)."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.actions.closer import ACTION as CLOSER
from l2p_bullet.arms.reach import Hold
from l2p_bullet.core.geometry import separation
from l2p_bullet.core.scene import FACE_MARGIN, GRIPPER_MARGIN, Scene, SceneObject
from l2p_bullet.errors import InfeasibleError
from l2p_bullet.planning.feasibility import check, clearance
from l2p_bullet.planning.nearer import face_clearance
from l2p_bullet.planning.world2d import World2D

SIZE = 0.04


def _level(gap: float) -> Scene:
    """A level with B (both yaw 0), east of it, ``gap`` m between their faces; C a bystander north of A."""
    return Scene([SceneObject("A", "red", SIZE, (SIZE + gap, 0.0), 0.0),
                  SceneObject("B", "green", SIZE, (0.0, 0.0), 0.0),
                  SceneObject("C", "blue", SIZE, (SIZE + gap, 0.08), 0.0)]).validate()


def _gap(scene: Scene, pose) -> float:
    return float(separation(scene.get("A").footprint(np.asarray(pose, float))[None], scene.get("B").footprint())[0])


def test_the_world_lets_the_mover_nearer_one_obstacle_only_where_told():
    scene = _level(0.011)
    world = World2D(scene, "A")
    near = world.nearer_to("B", FACE_MARGIN)
    start = np.asarray(scene.get("A").pose, float)
    in_b = start - [0.011 - 0.002, 0.0, 0.0]  # 2 mm from B's face
    assert not world.moves_free(start, in_b[None])[0] and near.moves_free(start, in_b[None])[0]
    assert near.margin_to("B") == FACE_MARGIN and near.margin_to("C") == world.margin_to("C") == GRIPPER_MARGIN
    to_c = start + [0.0, 0.08 - SIZE - 0.002, 0.0]  # 2 mm from C: C keeps the world's margin
    assert not near.moves_free(start, to_c[None])[0]


def test_the_room_check_reads_the_face_clearance_for_a_level_start():
    # 8 mm apart, half the room is 4 mm: within reach of a bare face (2.4 mm kept), not of the 5 mm margin
    scene = _level(0.008)
    assert clearance(scene, "A", "B") == pytest.approx(face_clearance(scene, "A", "B", None))
    assert FACE_MARGIN < clearance(scene, "A", "B") < GRIPPER_MARGIN
    check(scene, "A", "B", CLOSER)
    with pytest.raises(InfeasibleError) as e:  # 6 mm apart: 3 mm is the most half the room leaves
        check(_level(0.006), "A", "B", CLOSER)
    assert e.value.check == "room-closer"


def test_fingers_between_keep_the_margin():
    # where the hand reaches down beside A at B's height (a taller B), a grasp whose fingers face B keeps 5 mm
    scene = _level(0.008)
    grown = np.array([[-0.03, -0.02], [0.03, -0.02], [0.03, 0.02], [-0.03, 0.02]])  # fingers on A's x faces
    assert face_clearance(scene, "A", "B", [Hold(0.0, {"B": grown}, 0.01)]) is None
    both = [Hold(0.0, {"B": grown}, 0.01), Hold(np.pi / 2, {"B": grown[:, ::-1]}, 0.01)]
    assert face_clearance(scene, "A", "B", both) is not None  # the other square grasp puts them aside
    assert face_clearance(_level(0.03), "A", "B", None) is None  # farther than half a block: the search's own


@pytest.mark.slow
@pytest.mark.parametrize("verb", ["slide", "carry", "push"])
def test_closer_from_a_level_start_a_centimetre_away_closes_half_its_room(verb):
    from l2p_bullet.pipeline import judged_plan, prepare

    scene = _level(0.011)  # 0.275 blocks apart: half the room ends 5.5 mm from B, inside the 5 mm margin + 1 mm
    plan, verdict = judged_plan(prepare(f"{verb} A closer to B", scene, seed=6100))
    assert verdict["success"], verdict["reason"]
    end = _gap(scene, plan.path[-1])
    assert FACE_MARGIN < end < GRIPPER_MARGIN + 0.001


@pytest.mark.parametrize("a_pose,b_pose", [
    # turned 36 deg to B, 1.9 mm from it (development start SlideToward/12, touching): squared up in 16 moves
    ((-0.09491925509209428, -0.08947512886316385, 1.108437), (-0.14472453333333332, -0.0776872, 0.476385)),
    # corner to corner 0.8 mm apart (SlideAway/3, touching): out to the face margin, then square
    ((-0.02635574559398878, 0.052525615492478354, 0.442999), (-0.016196266666666667, 0.1083376, 0.764349)),
])
def test_a_turned_touching_start_squares_up_to_the_face_margin(a_pose, b_pose):
    from l2p_bullet.planning.nearer import nearer_path

    scene = Scene([SceneObject("A", "red", SIZE, a_pose[:2], a_pose[2]),
                   SceneObject("B", "green", SIZE, b_pose[:2], b_pose[2])]).validate()
    start = np.asarray(scene.get("A").pose, float)
    path = nearer_path(scene, "A", "B", CLOSER, start, World2D(scene, "A"), None)
    assert path is not None
    d = [float(np.hypot(*(p[:2] - np.asarray(b_pose[:2])))) / SIZE for p in (path[0], path[-1])]
    need = d[0] - CLOSER.thresholds["share"] * max(d[0] - 1.0, 0.25)
    assert d[1] < need and _gap(scene, path[-1]) >= FACE_MARGIN


def _pushed_in(a_pose, b_pose):
    from l2p_bullet.embodiment.manners import push_pusher
    from l2p_bullet.planning.nearer import nearer_path

    scene = Scene([SceneObject("A", "red", SIZE, a_pose[:2], a_pose[2]),
                   SceneObject("B", "green", SIZE, b_pose[:2], b_pose[2])]).validate()
    world = World2D(scene, "A", pusher=push_pusher(SIZE))
    return scene, world, nearer_path(scene, "A", "B", CLOSER, np.asarray(scene.get("A").pose, float), world, None,
                                     turns=False)


@pytest.mark.parametrize("a_pose,b_pose", [
    # turned 2 deg to B, touching it beside its face (development start SlideToward/3, touching)
    ((0.05972793589761988, -0.06226583713427432, 0.162139), (0.09784933333333333, -0.030810133333333333, 0.201357)),
    # turned 8 deg to B, off its corner (SlideAway/14, touching)
    ((-0.061968825145341425, -0.06340569624408243, 1.008121), (-0.005726133333333333, -0.06123413333333333, 0.861925)),
])
def test_a_push_from_a_turned_touching_start_slides_along_the_face_at_its_yaw(a_pose, b_pose):
    # a push keeps the yaw: the block slides along B's face toward B's centre line, pushed from its trailing
    # side with the fingers clear of B, and ends within half the room (both performed: 54 % and 62 % closed)
    scene, world, path = _pushed_in(a_pose, b_pose)
    assert path is not None
    assert np.allclose(path[:, 2], a_pose[2])  # never turned
    d = [float(np.hypot(*(p[:2] - np.asarray(b_pose[:2])))) / SIZE for p in (path[0], path[-1])]
    need = d[0] - CLOSER.thresholds["share"] * max(d[0] - 1.0, 0.25)
    assert d[1] < need and _gap(scene, path[-1]) >= FACE_MARGIN
    assert world.nearer_to("B", FACE_MARGIN).path_free(path)


def test_a_push_does_not_slide_the_block_out_from_beside_the_anchors_corner():
    # turned 17 deg, its corner past B's (SlideToward/10, touching): the way along the face first heads out of
    # it, where the flat fingers turned the block into B in the simulator (B moved 9 mm): no such path
    assert _pushed_in((0.06243704374523812, -0.11489298709460316, 0.486512),
                      (0.11974826666666667, -0.11838213333333333, 0.790743))[2] is None


def test_the_planner_keeps_the_fingers_as_clear_as_the_push_does():
    from l2p_bullet.embodiment.manners import PUSH_CLEARANCE
    from l2p_bullet.planning.nearer import FINGERS_CLEAR

    assert FINGERS_CLEAR == PUSH_CLEARANCE
