"""Single clauses from a block touching the anchor or level with it (the starts a chain leaves): "closer" weights
down candidates that close less of the room than the rule asks (the model is flat there), a push's "closer" keeps
the block's yaw in its room check (a push does not turn it), and a random search draws again when its first
batch holds no legal move (from touching most moves run into the anchor)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from l2p_bullet.actions.closer import ACTION as CLOSER
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.errors import InfeasibleError
from l2p_bullet.pipeline import judged_plan, prepare
from l2p_bullet.planning import PEOPLE_BOUNDS
from l2p_bullet.planning.bounds import back_weight, close_weight
from l2p_bullet.planning.feasibility import nearest_at_yaws
from l2p_bullet.planning.search import greedy

SIZE = 0.04


def _pair(a_xy, a_yaw, b_xy=(0.0, 0.0), b_yaw=0.0) -> Scene:
    return Scene([SceneObject("A", "red", SIZE, tuple(map(float, a_xy)), float(a_yaw)),
                  SceneObject("B", "green", SIZE, tuple(map(float, b_xy)), float(b_yaw))]).validate()


def _touching(turn: float, gap: float = 0.002) -> Scene:
    """A turned ``turn`` rad to B (yaw 0), east of it, its corner ``gap`` m from B's east face."""
    half = SIZE / 2 * (math.cos(turn) + math.sin(turn))  # A's support along x at that yaw
    return _pair((SIZE / 2 + gap + half, 0.0), turn)


def test_closer_plans_with_its_goes_back_bound_alone():
    """"closes-at-least" is a bound a plugin may declare; the built-in "closer" does not: measured on chains of
    seeds 9600-9699, it left five clauses from 1.25 blocks short of half their room (docs/planning.md)."""
    bound = PEOPLE_BOUNDS[CLOSER.rules]
    assert bound.func is back_weight and bound.keywords == {"within": CLOSER.thresholds["goes_back_within"]}


def test_a_candidate_closing_less_than_half_its_room_is_weighted_down_by_how_much_less():
    # from 1.3 blocks the room is 0.3: closing 0.15 (half) or more keeps the score, none loses 1/e, 0.075 e^-0.5
    start = [1.3, 0.0, 0.0]
    paths = [np.array([start, [x, 0.0, 0.0]]) for x in (1.15, 1.1, 1.3, 1.225, 1.4)]
    w = close_weight(paths, np.zeros(3), 1.0, 0.5)
    assert w[:2] == pytest.approx([1.0, 1.0])
    assert w[2] == pytest.approx(math.exp(-1.0)) and w[3] == pytest.approx(math.exp(-0.5))
    assert w[4] < w[2]  # going away is worse than staying
    far = [np.array([[3.0, 0.0, 0.0], [2.9, 0.0, 0.0]])]  # from 3 blocks the model has a slope of its own
    assert close_weight(far, np.zeros(3), 1.0, 0.5) == pytest.approx([1.0])


def test_two_squares_come_no_nearer_than_their_yaws_allow():
    assert nearest_at_yaws(_pair((0.1, 0.0), 0.0).get("A"), _pair((0.1, 0.0), 0.0).get("B")) == pytest.approx(SIZE)
    s = _pair((0.1, 0.0), math.pi / 4)
    assert nearest_at_yaws(s.get("A"), s.get("B")) / SIZE == pytest.approx((1 + math.sqrt(2)) / 2)
    s = _pair((0.1, 0.05), math.radians(30.0), b_yaw=math.radians(10.0))  # only the yaws between them count
    t = _pair((0.1, 0.05), math.radians(20.0))
    assert nearest_at_yaws(s.get("A"), s.get("B")) == pytest.approx(nearest_at_yaws(t.get("A"), t.get("B")))


def test_push_closer_from_a_turned_touching_start_is_refused_and_slide_closer_is_not():
    scene = _touching(math.radians(40.0))  # 1.33 blocks apart: half the room needs 1.17, at its yaw >= 1.26
    with pytest.raises(InfeasibleError) as e:
        prepare("push A closer to B", scene)
    assert e.value.check == "room-closer" and "a push does not turn" in str(e.value)
    assert e.value.details["turns"] is False
    prepare("slide A closer to B", scene)  # a slide may square it up: not refused


def test_push_closer_face_to_face_is_checked_as_before():
    scene = _touching(0.0, gap=0.3 * SIZE)  # level, 1.3 blocks apart: the yaw costs nothing
    prepare("push A closer to B", scene)


class _Node:
    def __init__(self, progress, pose):
        self.progress, self.pose, self.dead = progress, np.asarray(pose, float), []


class _Problem:
    """The search's view of a problem: the first batch has no legal move, the second one good one."""

    threshold = 0.9

    def __init__(self):
        self.batches = 0

    def root(self):
        return _Node(0.01, [0.0, 0.0, 0.0])

    def go_on(self, best, steps):
        return best.progress < self.threshold and steps < 10

    def children(self, parents, ends):
        self.batches += 1
        return [] if self.batches == 1 else [_Node(0.95, ends[0][0])]


def test_a_random_search_draws_again_when_its_first_batch_has_no_legal_move():
    problem = _Problem()
    node, stopped, steps = greedy(problem, lambda p, n, k: np.ones((k, 3)), 4)
    assert (stopped, steps, node.progress) == ("threshold", 2, 0.95)


def test_a_deterministic_search_stops_when_nothing_is_legal_from_the_start():
    def proposer(p, n, k):
        return np.ones((k, 3))

    proposer.deterministic = True
    problem = _Problem()
    node, stopped, steps = greedy(problem, proposer, 4)
    assert (stopped, steps, node.progress) == ("budget", 1, 0.01)


@pytest.mark.slow
def test_push_away_from_a_block_it_touches_plans_a_way_out():
    # a study start slid to 4 mm from the anchor (bench_clauses.py, development split): every first batch of
    # pushes straight away put the fingers into the anchor, and the search gave up after one batch
    scene = _pair((0.06892133854646196, 0.09238579045968268), 1.29202, (0.08083866666666667, 0.1434352), 0.407494)
    plan, verdict = judged_plan(prepare("push A away from B", scene, seed=6100))
    assert verdict["success"], verdict["reason"]
    assert len(plan.path) > 2


def test_a_few_millimetres_towards_a_level_anchor_is_a_move_and_staying_is_not():
    from l2p_bullet.planning.feasibility import MIN_TRAVEL_SIDES, check_moves, min_travel

    level = _touching(0.0, gap=0.0106)  # 10.6 mm face to face: 5.6 mm before the planner's 5 mm margin
    assert min_travel(level, "A", "B") == pytest.approx(0.0028)
    assert min_travel(_touching(0.0, gap=0.002), "A", "B") == pytest.approx(0.05 * SIZE)  # the floor
    assert min_travel(_touching(0.0, gap=3 * SIZE), "A", "B") == pytest.approx(MIN_TRAVEL_SIDES * SIZE)
    a = np.asarray(level.get("A").pose, float)
    closer = np.array([a, a - [0.004, 0.0, 0.0]])  # 4 mm towards B (west of A)
    check_moves(level, "A", "B", closer, action="closer", stopped="budget", progress=0.03, steps=100)
    with pytest.raises(InfeasibleError) as e:
        check_moves(level, "A", "B", np.array([a, a - [0.001, 0.0, 0.0]]), action="closer", stopped="budget",
                    progress=0.03, steps=100)
    assert e.value.check == "no-motion"
