"""A chain planned as a whole (chain/forecast.py, chain/ends.py): a clause's end state is chosen so the later
clauses stay possible, a refusal names the clause and why, the plan is deterministic, and the run re-plans
each clause with the end state the chain chose."""

from __future__ import annotations

import re
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from l2p_bullet.arms import PANDA, fit_scene
from l2p_bullet.chain import forecast as chain_forecast
from l2p_bullet.chain import perform_chain
from l2p_bullet.chain import replan as chain_replan
from l2p_bullet.chain.clauses import resolve_clauses
from l2p_bullet.chain.ends import DEFAULT, End, plan_clause, turned_goal
from l2p_bullet.chain.forecast import Search, forecast
from l2p_bullet.core.contracts import Plan
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.errors import InfeasibleError
from l2p_bullet.evaluate.chains import chain_scenes
from l2p_bullet.pipeline import check_feasible
from l2p_bullet.plugins import registry


@pytest.fixture(scope="module")
def plugins():
    return registry.discover()


def four_blocks() -> Scene:
    return Scene([SceneObject("A", "red", 0.04, (0.10, -0.08), 0.2), SceneObject("B", "green", 0.04, (0.0, 0.02), 0.0),
                  SceneObject("C", "blue", 0.04, (-0.12, -0.06), 0.4),
                  SceneObject("D", "yellow", 0.04, (-0.06, 0.10), 0.1)]).validate()


RIM = np.array([0.30, -0.10, 0.0])
"""Where the stand-in planner's own end (seed offset 0, no cut) leaves a block: the rim, in these tests."""


def stand_in(calls: list):
    """A planner that moves the mover straight to RIM for the planner's own end and elsewhere for every other
    end (each end its own place), recording (clause, end) per call; a cut of the rim plan ends short of it."""

    def plan(clause, scene, bundle, judge, options, arm, end=DEFAULT, *, base=None, **_):
        calls.append((clause.index, end))
        start = np.asarray(scene.get(clause.command.mover).pose, float)
        goal = RIM.copy() if end.seed == 0 else np.array([-0.05 * end.seed, 0.20, 0.0])
        if end.cut is not None:
            goal = start + (goal - start) * (0.5 if end.cut == "half" else 0.3)
        if end.turn:
            goal = turned_goal(clause, scene, base, end.turn)
        if getattr(end, "aim", None) is not None:
            goal = np.asarray(end.aim, float)
        path = np.linspace(start, goal, 6)
        anchor = scene.get(clause.command.anchor).pose
        return Plan(clause.command.action, clause.command.mover, clause.command.anchor, 0.04, np.asarray(anchor),
                    start, path, np.linspace(0, 1, 6), "stand-in", "threshold", {"final_progress": 1.0})

    return plan


def rim_refuses(check: str, *, reads: str, other: str | None = None):
    """A feasibility check that refuses (``check``) a clause whose ``reads`` block stands at RIM, and (``other``)
    every clause that moves ``reads`` from anywhere else."""

    def feasible(cmd, scene, plugins, arm=PANDA):
        at = np.asarray(scene.get(reads).xy)
        if cmd.anchor == reads and np.allclose(at, RIM[:2]):
            raise InfeasibleError(check, f'no room around "{reads}" on the rim')
        if other is not None and cmd.anchor == reads:
            raise InfeasibleError(other, f'"{reads}" is boxed in')

    return feasible


class Judge:
    """A stand-in judge: accepts every path, or (``refuse_rim``) none that ends at RIM."""

    def __init__(self, refuse_rim: bool = False):
        self.refuse_rim = refuse_rim

    def judge(self, path, anchor, size, **kwargs):
        ok = not (self.refuse_rim and np.allclose(path[-1][:2], RIM[:2]))
        return SimpleNamespace(to_dict=lambda: {"success": ok, "reason": "judged"})


@pytest.fixture
def stand_ins(monkeypatch):
    """The search over stand-ins for the planner, the judge and the path check: what is tested is the search."""
    calls: list = []
    monkeypatch.setattr(chain_forecast, "plan_clause", stand_in(calls))
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: Judge())
    from l2p_bullet.embodiment import execute

    monkeypatch.setattr(execute, "check_for", lambda *a, **k: None)
    return calls


def test_a_greedy_end_that_leaves_a_later_clause_impossible_is_replaced(plugins, stand_ins, monkeypatch):
    monkeypatch.setattr(chain_forecast, "check_feasible", rim_refuses("room-around", reads="A"))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move C around A", scene, plugins)
    search = Search()
    steps = forecast(clauses, scene, plugins, search=search)
    assert [s.end for s in steps] == [End(0, "half"), DEFAULT]  # the first other end that keeps clause 2 possible
    assert not np.allclose(steps[0].forecast.path[-1][:2], RIM[:2])
    assert search.changed == [1] and search.dead_ends == {"clause 2 (room-around)": 1}


def test_the_search_only_tries_again_the_clauses_that_moved_what_failed(plugins, stand_ins, monkeypatch):
    """Clause 1 moves D, which the room check of clause 3 does not read: only clause 2 (it moved A) is tried
    with other ends; clause 1 is planned once."""
    monkeypatch.setattr(chain_forecast, "check_feasible", rim_refuses("room-around", reads="A"))
    scene = four_blocks()
    clauses = resolve_clauses("move D next to B, then move A away from B, then move C around A", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert [s.end for s in steps] == [DEFAULT, End(0, "half"), DEFAULT]
    assert [c for c, _ in stand_ins].count(1) == 1


def test_an_end_the_judge_accepts_is_chosen_over_one_it_does_not(plugins, stand_ins, monkeypatch):
    """The planner's own end is judged not done on the plan (it ends at RIM): another end of the same clause
    that the judge accepts is chosen; when none is, the planner's own is kept (the run judges what it does)."""
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: Judge(refuse_rim=True))
    scene = four_blocks()
    clauses = resolve_clauses("move A past B, then move C next to A", scene, plugins)
    assert [s.end for s in forecast(clauses, scene, plugins)] == [End(0, "half")] * 2  # both stand-ins end at RIM
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: SimpleNamespace(
        judge=lambda *a, **k: SimpleNamespace(to_dict=lambda: {"success": False})))
    stand_ins.clear()
    steps = forecast(clauses, scene, plugins)
    assert [s.end for s in steps] == [DEFAULT, DEFAULT]
    assert [s.clause.command.manner for s in steps] == ["slide", "slide"]  # carried, it is rejected too: kept
    searched = [e for c, e in stand_ins if c == 1 and e.cut is None]  # each a search: cuts cost none
    # no turned end: a judge that rejects every path rejects a straight slide to it, so it is not searched to;
    # the slide's three seeds, then the clause carried over the others ("move" says where, not how), the same
    assert searched == [End(0), End(1), End(2)] * 2


class OnlyAt:
    """A stand-in judge that accepts only a path ending at ``xy``."""

    def __init__(self, xy):
        self.xy = np.asarray(xy, float)

    def judge(self, path, anchor, size, **kwargs):
        ok = bool(np.allclose(path[-1][:2], self.xy))
        return SimpleNamespace(to_dict=lambda: {"success": ok, "reason": "ends elsewhere"})


@pytest.mark.parametrize("verb, manner", [("move", "carry"), ("slide", "slide")])
def test_a_clause_whose_slide_no_end_of_which_its_judge_accepts_is_carried_where_its_verb_says_where(
        plugins, stand_ins, monkeypatch, verb, manner):
    """"move" says where, not how: where its judge accepts no end of the slide (the bystanders in the way), the
    clause is planned carried over them, and kept carried where its judge accepts that. "slide" says how: its
    own end is kept, rejected, as before (the run judges what it does)."""
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)
    over = np.array([-0.20, -0.15, 0.0])
    slid = chain_forecast.plan_clause

    def carried_elsewhere(clause, scene, bundle, judge, options, arm, end=DEFAULT, *, base=None, **_):
        p = slid(clause, scene, bundle, judge, options, arm, end, base=base)
        if clause.command.manner == "carry" and end == DEFAULT:  # a carried path is free of the others
            p = replace(p, path=np.linspace(p.path[0], over, 6))
        return p

    monkeypatch.setattr(chain_forecast, "plan_clause", carried_elsewhere)
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: OnlyAt(over[:2]))
    scene = four_blocks()
    [step] = forecast(resolve_clauses(f"{verb} A past B", scene, plugins), scene, plugins)
    assert step.clause.command.manner == manner and step.forecast.extra["verdict"]["success"] == (manner == "carry")
    if manner == "carry":
        assert step.clause.command.manner_why == ("carried over the other objects, which leave a slide no end its "
                                                  "judge accepts (ends elsewhere)")
        assert np.allclose(step.forecast.path[-1], over)


class AsFarAsRim:
    """A stand-in judge that accepts a path ending as far from the anchor as RIM is, but not at RIM: only the
    planner's end turned about the anchor (or a straight slide there)."""

    def judge(self, path, anchor, size, **kwargs):
        end, a = np.asarray(path[-1][:2], float), np.asarray(anchor[:2], float)
        ok = abs(np.hypot(*(end - a)) - np.hypot(*(RIM[:2] - a))) < 1e-6 and not np.allclose(end, RIM[:2])
        return SimpleNamespace(to_dict=lambda: {"success": bool(ok), "reason": "judged"})


def test_a_turned_end_is_searched_to_only_where_its_judge_accepts_a_straight_slide_there(plugins, stand_ins,
                                                                                         monkeypatch):
    """A turned end costs a search to a target; the clause's judge is asked first about a straight slide there
    (as an aimed end's is), so a turn that cannot fix what the judge rejects costs nothing."""
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: AsFarAsRim())
    scene = four_blocks()
    clauses = resolve_clauses("move A past B", scene, plugins)
    [step] = forecast(clauses, scene, plugins)
    assert step.end.turn and step.forecast.extra["verdict"]["success"]
    assert [e for _, e in stand_ins if e.turn] == [step.end]  # the first turn with room, searched once


def test_a_refusal_names_the_clause_its_check_and_what_was_tried(plugins, stand_ins, monkeypatch):
    monkeypatch.setattr(chain_forecast, "check_feasible", rim_refuses("room-around", reads="A", other="boxed-in"))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move C around A", scene, plugins)
    with pytest.raises(InfeasibleError) as e:
        forecast(clauses, scene, plugins)
    msg = str(e.value)
    assert msg.startswith('clause 2 ("move C around A") cannot be planned (room-around): no room around "A"')
    assert "no other end state of the clauses before it keeps it possible" in msg
    assert re.search(r"; the other end states tried met clause 2 \(boxed-in\) x\d+\)$", msg)  # every other end
    assert e.value.check == "room-around" and e.value.details["clause"] == 2


def test_a_clause_refused_from_the_scene_as_drawn_is_named_as_before(plugins, stand_ins, monkeypatch):
    """Nothing before clause 1 could help: the refusal is the clause's own, word for word."""
    monkeypatch.setattr(chain_forecast, "check_feasible", rim_refuses("room-around", reads="A"))
    scene = four_blocks().with_pose("A", RIM)
    clauses = resolve_clauses("move C around A, then move A away from B", scene, plugins)
    with pytest.raises(InfeasibleError) as e:
        forecast(clauses, scene, plugins)
    assert str(e.value) == 'clause 1 ("move C around A") cannot be planned (room-around): no room around "A" on the rim'
    assert stand_ins == []


def _case_7002(plugins):
    """A chain found on the development chain scenes (seed 7002): "past" leaves C where B cannot get round
    it; stopped halfway past B, it can."""
    scene = fit_scene(chain_scenes(1, 7002)[0].scene, PANDA)
    return scene, resolve_clauses("move C past B, then move B around C", scene, plugins)


@pytest.mark.slow
def test_a_chain_refused_for_a_greedy_end_now_plans_and_deterministically(plugins):
    scene, clauses = _case_7002(plugins)
    first = forecast(clauses[:1], scene, plugins, seed=7002)[0]
    after = scene.with_pose("C", first.forecast.path[-1])
    with pytest.raises(InfeasibleError) as e:  # what planning clause by clause met (the chain was refused)
        check_feasible(clauses[1].command, after, plugins, PANDA)
    assert e.value.check == "blocked-around"
    steps = forecast(clauses, scene, plugins, seed=7002)
    assert steps[0].end != DEFAULT and all(s.forecast.extra["verdict"]["success"] for s in steps)
    assert steps[0].forecast.extra["end_state"] == steps[0].end.to_dict()  # plan.json says which end
    again = forecast(clauses, scene, plugins, seed=7002)
    assert [s.end for s in again] == [s.end for s in steps]
    for a, b in zip(again, steps, strict=True):
        assert np.array_equal(a.forecast.path, b.forecast.path)


@pytest.mark.slow
def test_the_run_replans_each_clause_with_the_end_the_chain_chose(plugins, tmp_path, monkeypatch):
    scene, clauses = _case_7002(plugins)
    steps = forecast(clauses, scene, plugins, seed=7002)
    seen = []

    def recording(clause, *args, **kwargs):
        seen.append((clause.index, args[5] if len(args) > 5 else kwargs.get("end")))
        return plan_clause(clause, *args, **kwargs)

    monkeypatch.setattr(chain_replan, "plan_clause", recording)
    monkeypatch.setattr(chain_replan, "FOLLOW_TOL_M", -1.0)  # never the forecast's state: every clause planned again
    sentence = ", then ".join(c.text for c in clauses)
    r = perform_chain(sentence, scene, out_dir=tmp_path / "run", render=False, seed=7002, steps=steps)
    assert seen == [(2, steps[1].end)]  # clause 1 runs its forecast; clause 2 is planned again, with its end
    assert r.completed >= 1


def test_a_turned_end_is_as_far_from_the_anchor_on_another_bearing(plugins):
    scene = four_blocks()
    clause = resolve_clauses("move A away from B, then move C next to B", scene, plugins)[0]
    b = np.asarray(scene.get("B").xy)
    base = SimpleNamespace(path=np.array([[0.10, -0.08, 0.2], [0.0, -0.12, 0.3]]))
    goal = turned_goal(clause, scene, base, 90)
    assert np.isclose(np.hypot(*(goal[:2] - b)), np.hypot(*(base.path[-1][:2] - b)))
    assert np.allclose(goal[:2], b + (0.14, 0.0)) and goal[2] == 0.3  # a quarter turn anticlockwise, same yaw
    assert turned_goal(clause, scene, SimpleNamespace(path=np.array([[0.0, -0.32, 0.0]])), 180) is None  # off the disk
    far = resolve_clauses("move A far away from B", scene, plugins)[0]
    assert turned_goal(far, scene, base, 90) is None  # an extent asked for is kept


@pytest.mark.slow
def test_away_then_around_it_plans_with_the_away_ended_off_the_rim(plugins):
    """Development chain seed 7003: every cut and seed of "away" leaves A too near the rim for "around A"
    (refused clause by clause: room-around); another end of it (aimed where "around A" has room, or, since "away"
    from afar grows the distance as people do, its path cut halfway) is judged away and keeps clause 2."""
    scene = fit_scene(chain_scenes(1, 7003)[0].scene, PANDA)
    clauses = resolve_clauses("move A away from C, then move C around A", scene, plugins)
    steps = forecast(clauses, scene, plugins, seed=7003)
    assert steps[0].end != DEFAULT and steps[0].forecast.extra["verdict"]["success"]
    check_feasible(clauses[1].command, scene.with_pose("A", steps[0].forecast.path[-1]), plugins, PANDA)


def test_a_spent_search_goes_on_with_the_planners_own_ends(plugins, stand_ins, monkeypatch):
    """Clause 1's own end is judged not done, and every other end of it leaves clause 2 impossible: once the
    search has spent its plans, the chain is planned as clause by clause (clause 1's own end kept), not
    refused for want of a plan for clause 2."""

    def only_from_the_rim(cmd, scene, plugins, arm=PANDA):
        if cmd.anchor == "A" and not np.allclose(scene.get("A").xy, RIM[:2]):
            raise InfeasibleError("room-around", "no room")

    monkeypatch.setattr(chain_forecast, "SEARCH_PLANS", 1)
    monkeypatch.setattr(chain_forecast, "check_feasible", only_from_the_rim)
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: Judge(refuse_rim=True))
    scene = four_blocks()
    clauses = resolve_clauses("move A past B, then move C around A", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert [s.end for s in steps] == [DEFAULT, DEFAULT]
    assert not steps[0].forecast.extra["verdict"]["success"]


def test_an_end_its_judge_rejects_is_never_chosen_to_keep_a_later_clause_possible(plugins, stand_ins, monkeypatch):
    """Only the planner's own end (at RIM) is judged done, and it leaves clause 2 impossible: the chain is
    refused, not planned with a clause 1 its judge rejects (that would fail when run, hiding a refusal)."""
    monkeypatch.setattr(chain_forecast, "check_feasible", rim_refuses("room-around", reads="A"))
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: SimpleNamespace(
        judge=lambda path, *a, **k: SimpleNamespace(to_dict=lambda: {"success": bool(np.allclose(path[-1][:2],
                                                                                            RIM[:2]))})))
    scene = four_blocks()
    clauses = resolve_clauses("move A past B, then move C around A", scene, plugins)
    with pytest.raises(InfeasibleError, match=r'^clause 2 \("move C around A"\) cannot be planned \(room-around\)'):
        forecast(clauses, scene, plugins)


def beyond(x: float, check: str = "room-around"):
    """A room check that refuses "around A" wherever A stands at x > ``x`` (the stand-in's rim side)."""

    def feasible(cmd, scene, plugins, arm=PANDA):
        if cmd.anchor == "A" and scene.get("A").xy[0] > x:
            raise InfeasibleError(check, 'no room around "A" by the rim')

    return feasible


def test_an_end_aimed_where_the_later_room_check_passes_keeps_the_chain(plugins, stand_ins, monkeypatch):
    """Every end of clause 1 that the planner makes leaves A where "around A" has no room (x > 0.2); the place
    nearest the planner's end where the check passes is planned to as a target, and the chain is planned."""
    monkeypatch.setattr(chain_forecast, "check_feasible", beyond(0.2))
    monkeypatch.setattr(chain_forecast, "plan_clause", _all_past(0.2, stand_ins))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move C around A", scene, plugins)
    search = Search()
    steps = forecast(clauses, scene, plugins, search=search)
    aim = steps[0].end.aim
    assert aim is not None and aim[0] <= 0.2 and steps[1].end == DEFAULT
    assert np.allclose(steps[0].forecast.path[-1], aim)
    assert np.hypot(*(np.asarray(aim[:2]) - RIM[:2])) <= 0.1 + 1e-9  # near the planner's own end: 2 blocks
    assert steps[0].end.to_dict()["aim"] == [round(v, 6) for v in aim]  # plan.json's end_state says where
    assert search.changed == [1]
    # aimed right after the planner's own end and its cuts, before the blind searches (other seeds, turns)
    assert all(e.seed == 0 and not e.turn for c, e in stand_ins if c == 1)


def _all_past(x: float, calls: list):
    """The stand-in planner with every end it makes itself (seeds, cuts, turns) beyond ``x``; an aimed end
    goes where it is aimed."""
    base = stand_in(calls)

    def plan(clause, scene, bundle, judge, options, arm, end=DEFAULT, *, base_plan=None, **kw):
        p = base(clause, scene, bundle, judge, options, arm, end, **kw)
        if getattr(end, "aim", None) is None and clause.index == 1:
            p.path[-1][0] = max(p.path[-1][0], x + 0.05 + 0.01 * end.seed)
        return p

    return plan


def test_ends_a_known_room_failure_meets_again_are_not_planned_past(plugins, stand_ins, monkeypatch):
    """Clause 3's room check reads only A, which clause 2 does not move: once it failed on A's place, clause 1's
    other ends that leave A where it fails again are not planned past (clause 2 is planned once per clause 1
    end that can work, not for every end)."""
    monkeypatch.setattr(chain_forecast, "check_feasible", beyond(0.2))
    monkeypatch.setattr(chain_forecast, "plan_clause", _all_past(0.2, stand_ins))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move D next to B, then move C around A", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert steps[0].end.aim is not None
    assert [c for c, _ in stand_ins].count(2) == 2  # after the planner's own end, and after the aimed one


def test_a_clause_with_no_end_left_sends_the_search_back_to_who_moved_its_anchor(plugins, stand_ins, monkeypatch):
    """Clause 2 always leaves C a block and a half beyond A, whichever end; "around C" has no room when C is at
    x > 0.3. No end of clause 2 helps; clause 1, which moved clause 2's anchor A, is tried again, and its end
    cut short keeps the chain possible (before, clause 1 was skipped: it moves no block the check reads)."""

    def around_c(cmd, scene, plugins, arm=PANDA):
        if cmd.anchor == "C" and scene.get("C").xy[0] > 0.3:
            raise InfeasibleError("room-around", 'no room around "C" by the rim')

    def plan(clause, scene, bundle, judge, options, arm, end=DEFAULT, *, base=None, **_):
        p = stand_in(stand_ins)(clause, scene, bundle, judge, options, arm, end, base=base)
        if clause.index == 2:
            p.path[-1][:2] = np.asarray(scene.get("A").xy) + (0.075, 0.0)
        return p

    monkeypatch.setattr(chain_forecast, "check_feasible", around_c)
    monkeypatch.setattr(chain_forecast, "plan_clause", plan)
    monkeypatch.setattr(chain_forecast, "aimed_goals", lambda *a, **k: [])  # no aimed end rescues clause 2
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move C past A, then move D around C", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert steps[0].end != DEFAULT and steps[0].forecast.path[-1][0] + 0.075 <= 0.3


def test_aimed_places_are_the_nearest_that_fit_pass_and_are_judged_and_asked_at_most_checks(plugins):
    """aims.py on a real scene with stand-in checks: the places come nearest the planner's end first, inside
    the workspace and clear of the other blocks, each one ``keeps`` accepts; ``keeps`` is asked at most
    CHECKS times."""
    from l2p_bullet.chain import aims

    scene = four_blocks()
    base = SimpleNamespace(path=np.array([[0.10, -0.08, 0.2], [0.28, -0.10, 0.2]]), anchor_pose=np.zeros(3),
                           more_anchor_poses=None, size=0.04, viewer=None)
    asked = []

    def keeps(q):
        asked.append(q)
        return q[0] <= 0.21

    judge = SimpleNamespace(judge=lambda *a, **k: SimpleNamespace(to_dict=lambda: {"success": True}))
    got = aims.aimed_goals(scene, "A", base, judge, keeps)
    assert len(got) == aims.AIMS and all(q[0] <= 0.21 and q[2] == 0.2 for q in got)
    d = [np.hypot(*(q[:2] - base.path[-1][:2])) for q in got]
    assert d == sorted(d) and d[0] <= 0.08 + 1e-9  # the first ring that reaches x <= 0.2 from x = 0.28
    assert all(np.hypot(*q[:2]) <= 0.35 for q in asked)  # only places in the workspace are asked about
    asked.clear()
    assert aims.aimed_goals(scene, "A", base, judge, lambda q: asked.append(q) and False) == []
    assert len(asked) == aims.CHECKS


def test_room_around_sends_the_search_back_past_a_clause_that_moved_only_its_mover(plugins, stand_ins, monkeypatch):
    """"room-around" reads where the anchor stands, not the mover: clause 2 moved C, the mover of clause 3, and
    no end of it can make room round A, so it is planned once per end of clause 1 (the one that moved A) and
    not searched over (before, its ends spent the search's plans)."""
    monkeypatch.setattr(chain_forecast, "check_feasible", rim_refuses("room-around", reads="A"))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move C next to D, then move C around A", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert [s.end for s in steps] == [End(0, "half"), DEFAULT, DEFAULT]
    assert [c for c, _ in stand_ins].count(2) == 2  # after clause 1's own end, and after its end cut short


@pytest.mark.parametrize("second", ["move D closer to C", "move C away from D"])
def test_blocked_around_sends_the_search_back_past_a_clause_whose_block_is_not_in_the_way(plugins, stand_ins,
                                                                                        monkeypatch, second):
    """"blocked-around" reads the blocks near enough the anchor to be in the way: clause 2 leaves its block far
    from A (a bystander, or the mover of "around", which from afar may come near wherever it starts), so no end
    of it can clear the way round A; it is planned once per end of clause 1 (before, every check but a room
    check sent the search through every earlier clause's ends)."""

    def blocked_by_the_rim(cmd, scene, plugins, arm=PANDA):
        if cmd.anchor == "A" and np.allclose(scene.get("A").xy, RIM[:2]):
            raise InfeasibleError("blocked-around", 'no way round "A" by the rim')

    def plan(clause, scene, bundle, judge, options, arm, end=DEFAULT, *, base=None, **_):
        p = stand_in(stand_ins)(clause, scene, bundle, judge, options, arm, end, base=base)
        if clause.index == 2:
            p.path[-1][:2] = (-0.20, 0.15)
        return p

    monkeypatch.setattr(chain_forecast, "check_feasible", blocked_by_the_rim)
    monkeypatch.setattr(chain_forecast, "plan_clause", plan)
    scene = four_blocks()
    clauses = resolve_clauses(f"move A away from B, then {second}, then move C around A", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert steps[0].end != DEFAULT and [s.end for s in steps[1:]] == [DEFAULT, DEFAULT]
    assert [c for c, _ in stand_ins].count(2) == 2


def test_a_later_clause_no_end_of_which_its_judge_accepts_sends_the_search_back(plugins, stand_ins, monkeypatch):
    """Clause 1's own end leaves A at RIM, where clause 2's judge accepts no plan of "around A" (a block on the
    rim, then around it: the sweep falls short) though its room check passes: clause 1's other ends are tried
    before clause 2 is kept as its planner ends it; where none helps, the chain is planned as clause by clause,
    and the plans already made are not made again."""
    monkeypatch.setattr(chain_forecast, "SEARCH_PLANS", 8)  # clause 2's own ends spend the default's 8 of 2 clauses
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)

    def anchor_off_the_rim(path, anchor, size, **kwargs):
        ok = not np.allclose(np.asarray(anchor)[:2], RIM[:2])
        return SimpleNamespace(to_dict=lambda: {"success": ok, "reason": "swept short"})

    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: SimpleNamespace(judge=anchor_off_the_rim))
    scene = four_blocks()
    # "slide" says how: no clause is carried over the others when its judge accepts no end (what is counted here is
    # the search over a slide's ends)
    clauses = resolve_clauses("slide A away from B, then slide C around A", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert [s.end for s in steps] == [End(0, "half"), DEFAULT]
    assert [s.forecast.extra["verdict"]["success"] for s in steps] == [True, True]

    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: SimpleNamespace(
        judge=lambda path, anchor, size, **k: SimpleNamespace(to_dict=lambda: {"success": False, "reason": "no"})))
    stand_ins.clear()
    search = Search()
    steps = forecast(clauses, scene, plugins, search=search)
    assert [s.end for s in steps] == [DEFAULT, DEFAULT]  # clause by clause: each planner's own end
    made = [(c, e) for c, e in stand_ins]
    assert len(made) == len(set(made))  # the second pass made no plan again
    assert search.dead_ends == {}


def test_a_clause_no_place_its_judge_accepts_keeps_possible_is_not_searched_past_its_aims(plugins, stand_ins,
                                                                                        monkeypatch):
    """Clause 1's judge accepts only ends by the rim (x >= 0.25), and "around A" has no room wherever A stands
    at x > 0.2 (a check that reads A alone): the aimed places, every one its judge accepts, all fail it, so
    the other seeds and turns (each a search, each ending where its judge accepts it) are not planned; the
    chain is refused for clause 2 as before."""
    monkeypatch.setattr(chain_forecast, "check_feasible", beyond(0.2))
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: SimpleNamespace(
        judge=lambda path, *a, **k: SimpleNamespace(to_dict=lambda: {"success": bool(path[-1][0] >= 0.25)})))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move C around A", scene, plugins)
    with pytest.raises(InfeasibleError, match=r'^clause 2 \("move C around A"\) cannot be planned \(room-around\)'):
        forecast(clauses, scene, plugins)
    assert [e for c, e in stand_ins if c == 1 and e.cut is None] == [DEFAULT]


def test_a_clause_its_judge_rejects_in_every_end_is_planned_with_its_own_end_alone_from_later_starts(
        plugins, stand_ins, monkeypatch):
    """Clause 2's judge accepts none of its ends: the search sends clause 1 to its other ends, and from each
    new start clause 2 is planned with its own end (and its cuts) alone, not searched over again; with none
    accepted the chain is planned as clause by clause would plan it."""
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)
    c_pose = four_blocks().get("C").pose

    def judge(path, anchor, *a, **k):  # "past C" is never done; every other clause is
        return SimpleNamespace(to_dict=lambda: {"success": not np.allclose(anchor, c_pose), "reason": "judged"})

    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: SimpleNamespace(judge=judge))
    scene = four_blocks()
    clauses = resolve_clauses("move D next to B, then slide A past C", scene, plugins)  # "slide": never carried
    steps = forecast(clauses, scene, plugins)
    assert [s.end for s in steps] == [DEFAULT, DEFAULT] and not steps[1].forecast.extra["verdict"]["success"]
    clause2 = [e for c, e in stand_ins if c == 2 and e.cut is None]
    assert clause2.count(End(1)) == 1 and clause2.count(End(2)) == 1  # from clause 1's own end alone
    assert clause2.count(DEFAULT) > 1  # from clause 1's other ends too


def test_a_later_clause_its_judge_rejects_tries_the_earlier_clauses_ends_before_its_own_seeds(plugins, stand_ins,
                                                                                              monkeypatch):
    """Clause 2's own end is judged not done from where clause 1's own end leaves D (its plan then ends at RIM),
    and done from where clause 1 cut short leaves it: the cut (no search) is tried before clause 2's other seeds
    (each a search), and chosen."""
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: Judge(refuse_rim=True))
    base = stand_in(stand_ins)

    def plan(clause, scene, bundle, judge, options, arm, end=DEFAULT, **kw):
        p = base(clause, scene, bundle, judge, options, arm, end, **kw)
        if clause.index == 1 and end == DEFAULT:
            p.path[-1] = (0.25, 0.05, 0.0)  # clause 1's own end, judged done
        if clause.index == 2 and end.seed == 0:  # from there clause 2's own end, cut or not, ends at RIM; from
            done = not np.allclose(scene.get("D").xy, (0.25, 0.05))  # another start it is done
            p.path[-1] = (0.25, -0.02, 0.0) if done else RIM
        return p

    monkeypatch.setattr(chain_forecast, "plan_clause", plan)
    scene = four_blocks()
    clauses = resolve_clauses("move D next to B, then move A past C", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert [s.end for s in steps] == [End(0, "half"), DEFAULT]
    assert all(s.forecast.extra["verdict"]["success"] for s in steps)
    assert [e for c, e in stand_ins if c == 2 and e.cut is None] == [DEFAULT, DEFAULT]  # no other seed searched


def test_a_later_room_check_no_clause_between_can_change_is_met_before_they_are_planned(plugins, stand_ins,
                                                                                         monkeypatch):
    """Clause 1's own end leaves A on the rim, where "around A" (clause 3) has no room; clause 2 moves D, which
    that check does not read. The check is made on clause 1's end as soon as it is planned, so clause 2 is planned
    only after the end that keeps clause 3 possible (before, it was planned after the doomed end too: a search
    that could not help)."""
    from l2p_bullet.planning.sweep import room_around

    def plan(clause, scene, bundle, judge, options, arm, end=DEFAULT, *, base=None, **_):
        p = stand_in(stand_ins)(clause, scene, bundle, judge, options, arm, end, base=base)
        if clause.index == 1 and end == DEFAULT:
            p.path[-1][:2] = (0.33, 0.0)  # the real room-around check fails here (234 of 288 degrees)
        return p

    def feasible(cmd, scene, plugins, arm=PANDA):
        if cmd.anchor == "A":
            room_around(scene, cmd.mover, "A")

    monkeypatch.setattr(chain_forecast, "plan_clause", plan)
    monkeypatch.setattr(chain_forecast, "check_feasible", feasible)
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move D next to B, then move C around A", scene, plugins)
    search = Search()
    steps = forecast(clauses, scene, plugins, search=search)
    assert [s.end for s in steps] == [End(0, "half"), DEFAULT, DEFAULT]
    assert [c for c, _ in stand_ins].count(2) == 1
    assert search.dead_ends == {"clause 3 (room-around)": 1}


def _base_plan(clause, scene, path) -> Plan:
    anchor = scene.get(clause.command.anchor).pose
    path = np.asarray(path, float)
    return Plan(clause.command.action, clause.command.mover, clause.command.anchor, 0.04, np.asarray(anchor),
                path[0], path, np.linspace(0, 1, len(path)), "stand-in", "threshold", {"final_progress": 1.0})


def test_an_aimed_end_is_the_slide_its_judge_accepted_after_the_planners_pass_with_no_search(plugins, monkeypatch):
    """An aimed end with ``via`` is the planner's path up to where it came nearest the anchor, then a straight
    slide to the place (what the judge accepted when the place was chosen): no search. A slide into a block is a
    PlanError in the forecast, and searched to as a target at run time."""
    from l2p_bullet.chain import ends
    from l2p_bullet.errors import PlanError
    from l2p_bullet.options import RunOptions

    searched = []
    monkeypatch.setattr(ends, "_search", lambda *a, **k: searched.append(a[-1]) or base)
    scene = four_blocks()  # A (0.10, -0.08), B (0.0, 0.02)
    clause = resolve_clauses("move A past B", scene, plugins)[0]
    base = _base_plan(clause, scene, [[0.10, -0.08, 0.2], [0.06, 0.0, 0.2], [0.0, 0.08, 0.2], [-0.05, 0.20, 0.2]])
    aim = (0.03, 0.25, 0.3)
    opts = RunOptions()
    plan = plan_clause(clause, scene, None, None, opts, PANDA, End(0, aim=aim, via="nearest"), base=base,
                       slide_only=True)
    assert not searched
    assert np.allclose(plan.path[:3], base.path[:3]) and np.allclose(plan.path[-1], aim)  # nearest B at (0, 0.08)
    steps = np.hypot(*np.diff(plan.path[2:, :2], axis=0).T)
    assert np.allclose(steps, steps[0]) and len(plan.progress) == len(plan.path)  # one straight slide
    assert plan.extra["end_state"] == {"seed_offset": 0, "cut": None, "aim": list(aim), "via": "nearest"}
    start = plan_clause(clause, scene, None, None, opts, PANDA, End(0, aim=aim, via="start"), base=base)
    assert len(start.path) > 1 and np.allclose(start.path[0], base.path[0]) and np.allclose(start.path[-1], aim)
    into_c = End(0, aim=(-0.12, -0.06, 0.2), via="start")  # C stands there
    with pytest.raises(PlanError):
        plan_clause(clause, scene, None, None, opts, PANDA, into_c, base=base, slide_only=True)
    assert not searched
    plan_clause(clause, scene, None, None, opts, PANDA, into_c, base=base)  # the run: searched to instead
    assert len(searched) == 1 and np.allclose(searched[0], into_c.aim)


def test_the_forecast_tries_an_aimed_place_first_as_the_slide_its_judge_accepted(plugins, stand_ins, monkeypatch):
    """The aimed end first tried is the slide (``via``) its judge accepted there, which costs no search of the
    planner: the chain is planned with one plan per clause."""
    monkeypatch.setattr(chain_forecast, "check_feasible", beyond(0.2))
    monkeypatch.setattr(chain_forecast, "plan_clause", _all_past(0.2, stand_ins))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move C around A", scene, plugins)
    search = Search()
    steps = forecast(clauses, scene, plugins, search=search)
    assert steps[0].end.aim is not None and steps[0].end.via == "start"
    assert steps[0].end.to_dict()["via"] == "start"
    assert search.plans == 2  # clause 1's own end and clause 2's: the slide and the cuts cost none


@pytest.mark.slow
def test_past_aimed_where_around_it_has_room_keeps_its_close_pass(plugins):
    """A chain of the evaluation's scenes (seed 21158): "past" leaves C by the rim, where "A around C" has no
    room; the places with room that its judge accepts a slide to are reached by the planner's pass of B, then a
    straight slide (the search to them as targets passed B 4.9 blocks off, and its judge refused every one: the
    chain was refused up front)."""
    scene = fit_scene(chain_scenes(1, 21158)[0].scene, PANDA)
    clauses = resolve_clauses("move B away from C, then move C away from B, then move C past B, then move A around C",
                              scene, plugins)
    steps = forecast(clauses, scene, plugins, seed=21158)
    assert steps[2].end.via == "nearest" and all(s.forecast.extra["verdict"]["success"] for s in steps)


def test_the_earlier_clauses_cuts_are_all_tried_before_a_rejected_clause_is_kept(plugins, stand_ins, monkeypatch):
    """Clause 1's own end leaves A at RIM, where clause 3's judge accepts no "past A"; clause 1 cut short does not.
    The search back from clause 3 spends the plans it has left on clause 2's seeds and turns (each a search, and
    clause 3 planned again after each) before it comes back to clause 1: the cuts of every earlier clause (no
    search, the clauses after them planned again) are then tried before the chain is kept as clause by clause
    would plan it, with a clause its judge rejects (seed 25023: "away" to the rim, then "past" it)."""
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)

    def anchor_off_the_rim(path, anchor, size, **kwargs):
        ok = not np.allclose(np.asarray(anchor)[:2], RIM[:2])
        return SimpleNamespace(to_dict=lambda: {"success": ok, "reason": "ended before the anchor"})

    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: SimpleNamespace(judge=anchor_off_the_rim))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move D next to B, then move C past A", scene, plugins)
    search = Search()
    steps = forecast(clauses, scene, plugins, search=search)
    assert [s.end for s in steps] == [End(0, "half"), DEFAULT, DEFAULT]
    assert [s.forecast.extra["verdict"]["success"] for s in steps] == [True, True, True]
    assert any(c == 2 and e.seed for c, e in stand_ins)  # clause 2's seeds were searched first, as before


def test_the_earlier_clauses_turns_are_tried_once_their_cuts_fail(plugins, stand_ins, monkeypatch):
    """Clause 3's judge accepts "past D" only with D turned about B, away from where clause 2's own end, its cuts and
    its other seeds leave it (seed 25090: "move B next to C" on C's side facing A, then "move C closer to A" backs
    off round B): the search back spends its plans on clause 2's seeds and first turn; every earlier clause's cuts,
    then its turns, are tried before the chain is kept with a clause its judge rejects."""
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)
    b = four_blocks().get("B").xy

    def judge(path, anchor, size, **kwargs):
        ok = bool(np.allclose(np.asarray(anchor)[:2], b) or anchor[1] < -0.15)
        return SimpleNamespace(to_dict=lambda: {"success": ok, "reason": "backed off"})

    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: SimpleNamespace(judge=judge))
    scene = four_blocks()
    clauses = resolve_clauses("move A away from B, then move D next to B, then move C past D", scene, plugins)
    steps = forecast(clauses, scene, plugins)
    assert [s.end for s in steps] == [DEFAULT, End(0, None, -30), DEFAULT]
    assert all(s.forecast.extra["verdict"]["success"] for s in steps)


class NearerThan:
    """A stand-in judge that accepts a path ending south of y = -0.16 and within 0.25 m of B: no seed, cut or turn of
    the stand-in planner ends there, an aimed slide can."""

    def judge(self, path, anchor, size, **kwargs):
        end = np.asarray(path[-1][:2], float)
        ok = bool(end[1] <= -0.16 and np.hypot(*(end - np.asarray(anchor[:2], float))) < 0.25)
        return SimpleNamespace(to_dict=lambda: {"success": ok, "reason": "ends elsewhere"})


def test_a_clause_its_judge_rejects_at_every_end_is_aimed_at_a_place_it_accepts(plugins, stand_ins, monkeypatch):
    """No end of "slide A past B" is one its judge accepts, and no earlier clause can help: before the rejected end is
    kept, the clause is aimed at the nearest place its judge accepts a slide to (as for a later clause's check)."""
    monkeypatch.setattr(chain_forecast, "check_feasible", lambda *a, **k: None)
    monkeypatch.setattr(chain_forecast, "judge_for", lambda bundle: NearerThan())
    scene = four_blocks()
    [step] = forecast(resolve_clauses("slide A past B", scene, plugins), scene, plugins)
    assert step.end.aim is not None and step.forecast.extra["verdict"]["success"]
    assert step.clause.command.manner == "slide"
