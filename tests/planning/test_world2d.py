"""The 2-D simulator: swept-move collision, the workspace, interpolation into frames."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from l2p_bullet.core.geometry import polygons_overlap
from l2p_bullet.core.scene import GRIPPER_MARGIN, Scene, SceneObject
from l2p_bullet.planning.world2d import World2D, interpolate, place_outline, segment_frames


def _scene(b_xy=(0.0, 0.0), a_xy=(-0.15, 0.0), size=0.05) -> Scene:
    return Scene([SceneObject("A", "red", size, a_xy, 0.0), SceneObject("B", "green", size, b_xy, 0.0)]).validate()


def test_a_move_through_the_anchor_is_rejected_even_though_both_ends_are_free():
    w = World2D(_scene(), "A")
    start = np.array([-0.15, 0.0, 0.0])
    ends = np.array([[0.15, 0.0, 0.0], [0.15, 0.12, 0.0], [0.15, 0.2, 0.0], [-0.15, 0.12, 0.0]])
    assert not w.overlaps(ends[0])
    # the second clips the anchor's corner with its trailing edge; the third clears it
    assert w.moves_free(start, ends).tolist() == [False, False, True, True]


def test_obstacles_are_inflated_by_the_gripper_margin_only():
    w = World2D(_scene(), "A")
    touching_gap = 0.05 + GRIPPER_MARGIN * 0.5  # centre distance: side + half the margin
    clear_gap = 0.05 + GRIPPER_MARGIN * 1.5
    assert w.overlaps(np.array([-touching_gap, 0.0, 0.0]))
    assert not w.overlaps(np.array([-clear_gap, 0.0, 0.0]))


def test_the_grasp_point_must_stay_in_the_workspace_disk():
    w = World2D(_scene(), "A")
    start = np.array([-0.15, 0.0, 0.0])
    assert w.moves_free(start, np.array([[0.0, 0.34, 0.0], [0.0, 0.36, 0.0]])).tolist() == [True, False]


def test_a_rotating_move_sweeps_the_corners():
    # mover right beside the anchor: sliding along it is fine, spinning in place would hit it
    w = World2D(_scene(a_xy=(-0.0575, 0.0)), "A")
    start = np.array([-0.0575, 0.0, 0.0])
    assert w.moves_free(start, np.array([[-0.0575, 0.06, 0.0]]))[0]
    assert not w.moves_free(start, np.array([[-0.0575, 0.0, np.pi / 4]]))[0]


@settings(max_examples=150, deadline=None)
@given(st.floats(-0.2, 0.2), st.floats(-0.2, 0.2), st.floats(-3.2, 3.2))
@example(0.0546875, 0.0546875, 0.0)  # corner to corner just inside the margin: the pre-test once missed it
def test_a_zero_length_move_agrees_with_the_polygon_overlap_test(x, y, yaw):
    scene = _scene()
    w = World2D(scene, "A")
    pose = np.array([x, y, yaw])
    inside = bool(np.hypot(x, y) <= scene.workspace.radius)
    expected = inside and not polygons_overlap(w.mover.polygon(pose), scene.get("B").footprint(), GRIPPER_MARGIN)
    assert bool(w.moves_free(pose, pose[None], relax=False)[0]) == expected
    assert w.overlaps(pose) == (not expected)
    # a start inside the margin may stay where it is (its own gap is its margin), but never overlap
    touching = inside and not polygons_overlap(w.mover.polygon(pose), scene.get("B").footprint())
    assert bool(w.moves_free(pose, pose[None])[0]) == touching


def test_frames_are_evenly_spaced_and_end_exactly_at_the_goal():
    f = segment_frames(np.zeros(3), np.array([0.1, 0.0, 0.3]), step=0.0125)
    assert len(f) == 8
    assert np.allclose(np.diff(f[:, 0]), 0.0125)
    assert np.allclose(f[-1], [0.1, 0.0, 0.3])
    path = interpolate(np.array([[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0]]), step=0.0125)
    assert len(path) == 17 and np.allclose(path[0], 0) and np.allclose(path[-1], [0.1, 0.1, 0])


def test_turns_take_the_short_way_round():
    f = segment_frames(np.array([0, 0, 3.0]), np.array([0, 0, -3.0]), step=0.01, rot_step=0.05)
    assert np.max(np.abs(np.diff(np.unwrap(f[:, 2])))) < 0.06
    assert abs(np.unwrap(np.r_[3.0, f[:, 2]])[-1] - 3.0) < 0.3  # about 0.28 rad, not 6 rad


def test_place_is_vectorised():
    sq = np.array([[0.5, 0.5], [-0.5, 0.5], [-0.5, -0.5], [0.5, -0.5]])
    poses = np.array([[0, 0, 0], [1, 2, np.pi / 2]])
    out = place_outline(sq, poses)
    assert out.shape == (2, 4, 2)
    assert np.allclose(out[1, 0], [1 - 0.5, 2 + 0.5])


@pytest.mark.parametrize("seed", range(5))
def test_moves_free_handles_batches_of_mixed_moves(seed):
    rng = np.random.default_rng(seed)
    w = World2D(_scene(), "A")
    start = np.array([-0.15, 0.0, 0.0])
    ends = np.c_[rng.uniform(-0.25, 0.25, (40, 2)), rng.uniform(-0.7, 0.7, 40)]
    batch = w.moves_free(start, ends)
    single = [bool(w.moves_free(start, e[None])[0]) for e in ends]
    assert batch.tolist() == single


@pytest.mark.slow
@settings(max_examples=60, deadline=None)  # 60 free moves checked (about 100 drawn: 60 % of them are free)
@given(st.floats(-0.2, 0.2), st.floats(-0.2, 0.2), st.floats(-0.8, 0.8))
def test_a_move_said_free_never_touches_the_anchor_on_the_way(x, y, turn):
    scene = _scene()
    w = World2D(scene, "A")
    start = np.array([-0.15, 0.0, 0.0])
    end = np.array([x, y, turn])
    # only the moves said free are checked: assume() (not a bare return) makes hypothesis give up, failing the
    # test, when too few are, so a moves_free that calls every move blocked cannot pass it vacuously
    assume(bool(w.moves_free(start, end[None])[0]))
    anchor = scene.get("B").footprint()
    for t in np.linspace(0, 1, 201):
        pose = start + t * (end - start)
        assert _distance(w.mover.polygon(pose), anchor) >= GRIPPER_MARGIN * 0.99


def _distance(a: np.ndarray, b: np.ndarray) -> float:
    """Exact Euclidean distance between two convex polygons (0 when they overlap).

    The oracle must be exact: a margin test on edge normals alone is conservative at corner-to-corner
    gaps (hypothesis found a move whose corners clear by 6.6 mm while both axis gaps are under 5 mm).
    """
    if polygons_overlap(a, b):
        return 0.0

    def point_to_edges(p: np.ndarray, poly: np.ndarray) -> float:
        q0, q1 = poly, np.roll(poly, -1, axis=0)
        d = q1 - q0
        t = np.clip(((p - q0) * d).sum(1) / (d * d).sum(1), 0.0, 1.0)
        return float(np.min(np.linalg.norm(q0 + t[:, None] * d - p, axis=1)))

    return min(min(point_to_edges(p, b) for p in a), min(point_to_edges(p, a) for p in b))


def test_shortfall_is_the_least_gap_less_the_margin_and_a_close_start_keeps_its_own_gap():
    # A starts 3 mm from B (closer than the 5 mm margin): B asks only those 3 mm, C (far) the full margin
    scene = Scene([SceneObject("A", "red", 0.05, (0.0, 0.0), 0.0), SceneObject("B", "green", 0.05, (0.053, 0.0), 0.0),
                   SceneObject("C", "blue", 0.05, (0.0, 0.2), 0.0)]).validate()
    w = World2D(scene, "A")
    margins = w.start_margins()
    assert np.allclose(margins, [0.003, GRIPPER_MARGIN])
    poses = np.array([[0.0, 0.0, 0.0], [-0.001, 0.0, 0.0], [0.001, 0.0, 0.0], [0.0, 0.147, 0.0], [-0.3, -0.3, 0.0]])
    short = w.shortfall(poses, margins)
    assert np.allclose(short[:4], [0.0, 0.001, -0.001, -0.002])  # the start itself just passes; C: 3 mm short
    # sparing the work changes nothing a comparison with a slack of up to ``within`` can see
    spared = w.shortfall(poses, margins, mask=np.array([True, True, True, True, False]), within=0.01)
    assert np.array_equal(spared[:4], short[:4]) and spared[4] == np.inf and short[4] > 0.01
