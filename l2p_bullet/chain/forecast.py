"""The whole chain planned in 2-D before the arm moves: each clause from the end state the previous
clauses' plans predict, so a clause that cannot be planned is refused up front, naming it and the check.

Planned as a whole: each clause is planned with the planner's own end first; when a later clause cannot be
planned from there, or its judge accepts none of its ends there (a block left on the rim, then "around" it),
the earlier clauses' other end states (ends.py: a path stopped short, other seeds, the end turned about the
anchor) are tried, latest first, depth first, so one clause's greedy end (a block left
on the workspace's rim, a block already past its anchor) does not make the chain impossible when another end
of the same clause would keep it possible. Only the clauses that moved a block the failed check reads are
tried again (a room check reads the mover and the anchor, "room-around" the anchor alone; "blocked-around"
those and the blocks near enough the anchor to be in the way; every other check, the whole scene), and, once
every end of a clause failed, the clauses that moved its anchors (where they stand decides its ends).

A later clause's room check that reads nothing but its mover, its anchor and the workspace ("room-around",
"room-away": deadends.ahead_of), where the clauses between move neither, is made on a clause's end as soon as
it is planned: the later clause would fail there whatever the clauses between do, so they are not planned.

Once a later clause's room check has failed on where a clause left its mover, that clause's other ends that
leave it where the same check fails again are not planned past (the check reads nothing else, so it would
fail again; a turned end whose goal is such a place is not planned at all), and the places nearest the
planner's end where the check passes are tried as ends (aims.py), right after the planner's own end and its
cuts: the other ends are blind to what the later check needs. An end the clause's judge does not accept on
the plan is not chosen; the planner's own, so judged, is tried after every other end (and kept, as clause
by clause, when none works: the run judges what it does). A chain is refused only when no combination tried
works, with the first failure found (the clause and its check) and what was tried.

Each other end but a cut costs a search of the planner, often longer than the clause's own (a turned or aimed
end is a search to a target, which runs to its budget where the model does not rate the target as the
action), so the search asks cheap stand-ins before it pays for one: a turned end is searched to only where its
judge accepts a straight slide there (as an aimed end's place is chosen); once every place its judge accepts
a slide to was asked and none keeps the later room checks possible that read nothing but where the clause's
mover stands (aims.py), the other seeds and turns are not searched (they end in such places too); a later
clause whose judge rejects its own end sends the search back to the earlier clauses' ends (mostly cuts, free)
before its own seeds and turns are searched, which they are, from where the earlier clauses' own ends left
it, when none of those works (the search again, below); and a clause whose judge accepted none of its ends
from one start is planned with its own end alone from the others. Where the plans that search may make run out
(on the seeds of the clause just before the rejected one, say), every earlier clause's cuts, then its cuts and
turns, are tried before the chain is planned as clause by clause would plan it.

The checks per clause, in order: the arm's and the judge's feasibility checks (``grasp``, ``boxed-in``,
``room-*``: planning.feasibility), the planner itself (``plan``: no legal move), and the execution's path
check (``path``: the planned path leaves the workspace or runs into a block). The forecast is a prediction:
at run time each clause is planned again, with the end state chosen for it, from where the simulated world
really left the blocks.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..core.contracts import Plan
from ..core.scene import Scene
from ..errors import InfeasibleError, L2PError, PlanError
from ..judge import judge_for, plan_verdict
from ..judge.footprints import outlines_of
from ..manners import registry as manners
from ..options import RunOptions
from ..pipeline import carried_over, check_feasible, feasible_as
from ..plugins import registry
from .aims import CHECKS, accepted_via, aimed_goals, slide_accepted
from .clause import Clause
from .deadends import Ahead, Dead, ahead_fails, ahead_of, around_reads, kind, reads_of, refusal, wider
from .ends import DEFAULT, ENDS, End, plan_clause, turned_goal

SEARCH_PLANS = 4
"""Plans a chain's search may make, per clause, to look for other ends (each plan is one search of the
planner; a cut end costs none). A chain its clauses' own ends make possible is planned once per clause, as
before. Once spent, the search goes on with the planner's own ends alone, so a chain planned clause by
clause is never refused for the search's sake (chosen on the development chains, docs/benchmarks.md)."""
SHORT_PLANS = 8
"""Plans the search may still make, once a clause's judge accepted none of its ends, to find earlier ends that let it
accept one (the development chain 9705 needed 7); then the chain is planned as clause by clause would plan it."""


@dataclass
class Step:
    """What one clause needs at run time: the clause, its loaded action, its forecast plan, the end state
    the chain chose for it (ends.py; run.py plans the clause again with it) and the state it was forecast from
    (run.py follows the forecast plan where the world is still that state)."""

    clause: Clause
    bundle: Any
    model: Any
    judge: Any
    forecast: Plan
    end: End = DEFAULT
    scene: Scene | None = None  # the predicted state the forecast planned the clause from (None: not known)

    @property
    def viewer(self):
        return getattr(self.model, "viewpoint", None)


@dataclass
class Search:
    """What a chain's search did (``forecast``'s ``search`` argument fills it): plans made, seconds spent, the
    seconds of the plans kept (the chain's clauses planned alone), and the end states that differ from the
    planner's own."""

    plans: int = 0
    seconds: float = 0.0
    kept_seconds: float = 0.0
    changed: list[int] = field(default_factory=list)
    dead_ends: dict[str, int] = field(default_factory=dict)  # "clause N (check)" -> times the search met it



def forecast(clauses: list[Clause], scene: Scene, plugins: list, options: RunOptions | None = None, *,
             bundles: dict | None = None, search: Search | None = None, **changes: Any) -> list[Step]:
    """Load each clause's action (once per action) and plan the chain as a whole from the predicted states
    with the options' planner, seed, budget and threshold, for their arm (its reach, hand and gripper: the
    same checks a one-clause run makes). ``changes``: options by name (``RunOptions.of``). ``search``: filled
    with what the search did.

    Raises the failing check's error (InfeasibleError with ``.check`` and ``details["clause"]``, or a
    PlanError / PathError) with the clause named in its message, before anything moves or is written.
    """
    opts = RunOptions.of(options, **changes)
    loaded: dict[str, tuple[Any, Any, Any]] = {}
    for c in clauses:
        name = c.command.action
        if name not in loaded:
            bundle = (bundles or {}).get(name) or registry.load(name, plugins)
            loaded[name] = (bundle, bundle.progress_model(), judge_for(bundle))
    stats = Search() if search is None else search
    t0 = time.perf_counter()
    try:
        searcher = _Searcher(clauses, plugins, opts, loaded, stats, short_ok=False)
        steps: list[Step] | None = []
        try:
            steps = searcher.steps(0, scene)
        except Dead:
            if not searcher.short_met:
                raise
            steps = None
            # no ends found that every judge accepts within the plans left, which may all have gone to the seeds of
            # the clause just before the rejected one (whose ends stay on one side of its anchor): every earlier
            # clause's cuts (no search), then its cuts and turns (where its block stands about its anchor), each
            # with as many plans again
            for only in ("cuts", "turns"):
                again = _Searcher(clauses, plugins, opts, loaded, stats, short_ok=False, memo=searcher.memo,
                                  cost=searcher.cost, only=only)
                try:
                    steps, searcher = again.steps(0, scene), again
                    break
                except Dead:
                    pass
        if steps is None:
            # none: the chain as clause by clause would plan it, the plans already made reused (the search
            # again, with a clause's own end kept where its judge accepts none)
            stats.dead_ends.clear()
            searcher = _Searcher(clauses, plugins, opts, loaded, stats, memo=searcher.memo, cost=searcher.cost)
            steps = searcher.steps(0, scene)
    except Dead as d:
        raise refusal(d, clauses, stats.plans, stats.dead_ends) from None
    finally:
        stats.seconds += time.perf_counter() - t0
    stats.kept_seconds = sum(searcher.kept.get(id(s.forecast), 0.0) for s in steps)
    stats.changed = [s.clause.index for s in steps if s.end != DEFAULT]
    return steps


_SCENE = object()
"""``_Searcher._try``'s answer when the clause's planner met a check of the scene: no other seed does better."""


@dataclass
class _Clause:
    """One clause's place in the search: where it starts, what it loaded, and what its ends have met."""

    k: int
    clause: Clause
    predicted: Scene
    bundle: Any
    model: Any
    judge: Any
    checked: float  # seconds its feasibility checks took
    first: Dead | None = None  # the first failure met: what it is refused with if no end works
    judged_short: tuple[Plan, End] | None = None  # the planner's own end, when the judge does not accept it
    planned: dict[int, Plan | None] = field(default_factory=dict)  # seed offset -> its plan (None: it failed)
    needs: list[Dead] = field(default_factory=list)  # later room checks that failed on where it left its mover
    nowhere: bool = False  # no place its judge accepts keeps its needs (aims.py asked every one): no other end can


def _outlines(at: _Clause) -> list[np.ndarray] | None:
    """The real outlines of the clause's mover and anchors, as its judge reads them (None for cubes)."""
    c = at.clause.command
    return outlines_of([at.predicted.get(o) for o in (c.mover, *c.anchors)])


def _known(d: Dead) -> bool:
    """Whether ``d``'s check reads nothing but its own clause's mover and anchors: where an earlier clause left
    one of them decides it, whatever the clauses between do with the others."""
    return d.blocks is not None and d.blocks <= {d.command.mover, *d.command.anchors}


class _Searcher:
    """Depth first over the clauses' end states, back-jumping past clauses that moved no block a failure reads."""

    def __init__(self, clauses: list[Clause], plugins: list, opts: RunOptions, loaded: dict, stats: Search, *,
                 short_ok: bool = True, memo: dict | None = None, cost: dict | None = None, only: str | None = None):
        self.plugins, self.opts, self.loaded, self.stats = plugins, opts, loaded, stats
        self.clauses = list(clauses)  # its own: a clause carried over the others stands in while it is tried
        self.arm = opts.arm_spec()
        # only "cuts": every clause's own end and its cuts alone; "turns": and its turns (no other seed, no aim)
        self.only = only
        self.left = SHORT_PLANS if only else SEARCH_PLANS * len(clauses)
        # short_ok False: a clause whose judge accepts none of its ends is a dead end, so the earlier clauses' other
        # ends are tried first (a block the greedy end left on the rim, then "around" it, sweeps short of the rule)
        self.short_ok, self.short_met = short_ok, False
        self.memo: dict[tuple, Plan | L2PError] = {} if memo is None else memo  # a plan made, or the error met
        self.cost: dict[int, float] = {} if cost is None else cost  # id(plan) -> seconds to make it (a cut: to cut it)
        self.kept: dict[int, float] = {}  # id(plan) -> seconds to check and plan its clause alone
        self.shorts: set[int] = set()  # clauses whose judge accepted no end (short_ok False): their own end alone now
        self.ahead: dict[int, list[Ahead]] = {}  # clause position -> the later room checks its end decides

    def steps(self, k: int, predicted: Scene) -> list[Step]:
        if k == len(self.clauses):
            return []
        c = self.clauses[k]
        t0 = time.perf_counter()
        try:
            done_as = feasible_as(c.command, predicted, self.plugins, self.arm, check=check_feasible)
        except L2PError as e:  # no end state of this clause helps: the scene it starts from is what fails
            raise self._dead(c, e, predicted) from None
        if done_as is not c.command:  # carried over the blocks in its slide's way from here (the run does so too)
            c = replace(c, command=done_as)
        at = _Clause(k, c, predicted, *self.loaded[c.command.action], checked=time.perf_counter() - t0)
        aimed = fell_back = False
        for end in ENDS:
            if self.only and (end.seed or (end.turn and self.only == "cuts")):
                continue
            if self.left <= 0 and end != DEFAULT:
                break  # the search is spent: the planner's own ends only, as clause by clause
            if at.needs and not aimed and (end.seed or end.turn) and not self.only:
                # a later room check failed on the planner's end and its cuts: aimed there before other
                # searches, which are blind to what it needs (aims.py)
                aimed = True
                found = self._aimed(at)
                if found is not None:
                    return found
                if at.nowhere:
                    break  # the other ends end where its judge accepts them, and no such place keeps it possible
            if (end.seed or end.turn) and (k in self.shorts or (
                    at.judged_short is not None and not self.short_ok and k > 0 and not at.needs)):
                # its judge rejects its own end here (or every end from an earlier start): the earlier clauses'
                # other ends first, from whose starts its own end may be done (each other seed or turn costs a
                # search); its other seeds and turns only when none is (the search again, forecast())
                break
            found = self._try(at, end)
            if found is _SCENE:
                break
            if found is not None:
                return found
        while True:
            if at.needs and not aimed and not self.only:
                aimed = True
                found = self._aimed(at)
                if found is not None:
                    return found
            if at.judged_short is None or fell_back:
                break
            if not self.short_ok:
                if not self.short_met:  # the earlier clauses' other ends, within a few plans more
                    self.left = min(self.left, SHORT_PLANS)
                self.short_met = True
                self.shorts.add(k)
                reason = at.judged_short[0].extra["verdict"].get("reason", "")
                raise self._dead(c, PlanError(f"its judge accepts none of its ends ({reason})"), predicted)
            if not aimed and not self.only:  # its judge rejects each of its ends, from every start the earlier
                aimed = True  # clauses give it: aimed at the places it accepts a slide to (aims.py)
                found = self._aimed(at)
                if found is not None:
                    return found
            found = None if self.only else self._carried_over(at)  # no end of the slide: carried over the others
            if found is not None:
                return found
            fell_back = True  # no end the judge accepts: planned as it was (the run judges what it does)
            plan, end = at.judged_short
            try:
                return [self._step(at, plan, end), *self.steps(k + 1, predicted.with_pose(c.command.mover,
                                                                                           plan.path[-1]))]
            except Dead as d:
                if aimed or not self._needed(at, d):
                    raise wider(d, c) from None
                at.first = d  # what the aimed ends are measured against, and refused with if none works
        raise wider(at.first, c) if at.first is not None else self._dead(c, PlanError("no end state left to try"))

    def _carried_over(self, at: _Clause) -> list[Step] | None:
        """``at``'s clause carried over the other objects where its judge accepts none of its slide's ends
        (pipeline.carried_over: its verb names no manner), and the clauses after it: their steps when its judge
        accepts the carried plan, else None (the slide's own end is kept, as before). Within one clause's share of the
        search's plans (:data:`SEARCH_PLANS`): a last resort, not a second search over the chain."""
        reason = at.judged_short[0].extra["verdict"].get("reason", "")
        over = carried_over(at.clause.command, f"no end its judge accepts ({reason})")
        if over is None or self.left <= 0:
            return None
        saved, left = self.clauses[at.k], self.left
        self.clauses[at.k] = replace(saved, command=over)
        self.left = granted = min(left, SEARCH_PLANS)
        try:
            steps = self.steps(at.k, at.predicted)
        except Dead:
            return None
        finally:
            self.clauses[at.k] = saved
            self.left = left - (granted - self.left)
        return steps if steps[0].forecast.extra["verdict"]["success"] else None

    def _try(self, at: _Clause, end: End) -> list[Step] | object | None:
        """Plan ``at``'s clause with ``end`` and the later clauses after it: their steps, None when this end
        leads nowhere (another may), or _SCENE when no other seed can do better (a check of the scene)."""
        c, predicted = at.clause, at.predicted
        if end.seed not in at.planned:
            self.left -= 1
            at.planned[end.seed] = None
            try:
                at.planned[end.seed] = self._plan(c, predicted, at.bundle, at.judge, end)
            except Dead as d:
                at.first = at.first or d
                if isinstance(d.error, InfeasibleError) and d.error.check != "no-motion":
                    return _SCENE  # a check of the scene (no way in from afar...): another seed meets it again
                return None
            plan = at.planned[end.seed]
        elif at.planned[end.seed] is None:
            return None
        else:
            if end.turn:  # a turned end is planned to: a search, where there is one to plan to
                goal = turned_goal(c, predicted, at.planned[end.seed], end.turn)
                if goal is None or not self._keeps(at, goal, known=True):
                    return None
                if not slide_accepted(at.judge, at.planned[end.seed], goal, predicted.get(c.command.mover).size,
                                      _outlines(at)):
                    return None  # its judge rejects even a straight slide there: the search to it would be judged so
            if end.turn or (end.aim is not None and end.via is None):
                self.left -= 1
            try:
                plan = self._plan(c, predicted, at.bundle, at.judge, end, base=at.planned[end.seed])
            except Dead as d:
                at.first = at.first or d
                return None
        base = at.planned[end.seed]
        if end.cut is not None and np.allclose(plan.path[-1], base.path[-1]):
            return None  # the cut leaves the end where it was: nothing new to try
        if not self._keeps(at, plan.path[-1], known=True):
            return None  # a later room check already failed for this mover's place there: it would again
        self.kept[id(plan)] = at.checked + self.cost[id(plan)] + (
            self.cost[id(base)] if end.cut is not None or end.turn or end.aim is not None else 0.0)
        step = self._step(at, plan, end)
        if not step.forecast.extra["verdict"]["success"]:
            if end == DEFAULT:  # kept for last: clause by clause, it is what the chain would run
                at.judged_short = (plan, end)
            return None  # another end of this clause may be one its judge accepts; no other end it rejects is
        ahead = self._ahead(at, plan.path[-1])
        if ahead is not None:  # a later clause fails here whatever the clauses between do: met without planning them
            at.first = at.first or ahead
            self._needed(at, ahead)
            return None
        try:
            return [step, *self.steps(at.k + 1, predicted.with_pose(c.command.mover, plan.path[-1]))]
        except Dead as d:
            at.first = at.first or d
            if d.blocks is not None and c.command.mover not in d.blocks:
                raise at.first from None  # this clause's end does not move what failed: try an earlier one
            self._needed(at, d)
            return None

    def _ahead(self, at: _Clause, pose: np.ndarray) -> Dead | None:
        """The dead end a later clause meets when ``at``'s mover ends at ``pose``, where one of its room checks that
        reads nothing the clauses between move fails there (deadends.ahead_of), else None."""
        if at.k not in self.ahead:
            self.ahead[at.k] = ahead_of(self.clauses, at.k, self.plugins)
        scene = at.predicted.with_pose(at.clause.command.mover, pose)
        for a in self.ahead[at.k]:
            e = ahead_fails(a, scene)
            if e is not None:
                return self._dead(a.clause, e, scene)
        return None

    def _needed(self, at: _Clause, d: Dead) -> bool:
        """Note ``d`` among the later room checks ``at``'s ends are measured against, where it is one that reads
        where ``at``'s mover stands (its mover or anchor: not a clause sent back for its anchor's sake); whether it
        is new."""
        reads = () if d.command is None else d.reads or (d.command.mover, *d.command.anchors)
        if not d.room or d.clause <= at.clause.index or at.clause.command.mover not in reads or any(
                (n.clause, n.room) == (d.clause, d.room) for n in at.needs):
            return False
        at.needs.append(d)
        return True

    def _aimed(self, at: _Clause) -> list[Step] | None:
        """``at``'s clause planned with its aimed ends (aims.py) while the search has plans left: the steps of
        the first that works, or None."""
        if at.planned.get(0) is None or self.left <= 0:
            return None
        asked = []

        def keeps(q: np.ndarray) -> bool:
            asked.append(q)
            return self._keeps(at, q)

        goals = aimed_goals(at.predicted, at.clause.command.mover, at.planned[0], at.judge, keeps,
                            scenes=tuple(d.scene for d in at.needs), outlines=_outlines(at))
        # every place its judge accepts a slide to was asked, none keeps a later check that reads nothing but
        # where its mover stands possible: no other end its judge accepts can (the other seeds and turns end
        # in such places too), so they are not searched
        at.nowhere = not goals and len(asked) < CHECKS and all(_known(d) for d in at.needs)
        size = at.predicted.get(at.clause.command.mover).size
        for pose in goals:
            aim = tuple(float(v) for v in pose)
            # first the slide its judge accepted there (no search), then a search to it as a target
            via = accepted_via(at.judge, at.planned[0], pose, size, _outlines(at))
            for end in ((End(0, aim=aim, via=via),) if via is not None else ()) + (End(0, aim=aim),):
                if self.left <= 0:
                    return None
                found = self._try(at, end)
                if isinstance(found, list):
                    return found
        return None

    def _plan(self, c: Clause, predicted: Scene, bundle: Any, judge: Any, end: End, base: Plan | None = None) -> Plan:
        from ..embodiment.execute import check_for  # lazy: the arm's modules load only when a chain is forecast

        key = (c.index, c.command.manner, end, id(base),
               tuple((o.name, *np.round(o.pose, 9)) for o in predicted.objects))
        made = self.memo.get(key)
        if isinstance(made, L2PError):
            raise self._dead(c, made, predicted)
        if made is not None:
            self.left += bool(self.only) and base is None  # made before: the plans left to it count plans made
            return made
        t0 = time.perf_counter()
        try:
            plan = plan_clause(c, predicted, bundle, judge, self.opts, self.arm, end, base=base, slide_only=True)
            check_for(manners.get(c.command.manner), predicted, c.command.mover, plan.path, self.arm)
        except L2PError as e:
            self.memo[key] = e
            raise self._dead(c, e, predicted) from None
        finally:
            self.stats.plans += base is None or bool(end.turn) or (end.aim is not None and end.via is None)
        self.cost[id(plan)] = time.perf_counter() - t0
        self.memo[key] = plan
        return plan

    def _step(self, at: _Clause, plan: Plan, end: End) -> Step:
        c, bundle, model, judge = at.clause, at.bundle, at.model, at.judge
        plan.extra["verdict"] = plan_verdict(judge, plan, final_progress=plan.extra.get("final_progress"),
                                             outlines=_outlines(at))
        plan.extra.setdefault("sentence", c.text)
        return Step(c, bundle, model, judge, plan, end, at.predicted)

    def _keeps(self, at: _Clause, pose: np.ndarray, known: bool = False) -> bool:
        """Whether every later check ``at`` needs passes with its clause's mover at ``pose`` (in the scene it
        failed in). ``known``: only the room checks that read nothing but the mover and the anchor (their
        failure again is certain), and only their own failure counts (counted as a dead end, as if met)."""
        c = at.clause
        for d in at.needs:
            if known and not _known(d):
                continue  # it reads other blocks too, which the clauses between may move
            try:
                check_feasible(d.command, d.scene.with_pose(c.command.mover, pose), self.plugins, self.arm)
            except L2PError as e:
                if not known:
                    return False
                if isinstance(e, InfeasibleError) and e.check == d.room:
                    self._count(self.clauses[d.clause - 1], e)
                    return False
        return True

    def _count(self, c: Clause, e: L2PError) -> str | None:
        check = e.check if isinstance(e, InfeasibleError) else None
        key = f"clause {c.index} ({check or kind(e)})"
        self.stats.dead_ends[key] = self.stats.dead_ends.get(key, 0) + 1
        return check

    def _dead(self, c: Clause, e: L2PError, scene: Scene | None = None) -> Dead:
        check = self._count(c, e)
        reads = reads_of(check, c.command)
        if check == "blocked-around" and scene is not None:
            reads = around_reads(scene, c.command, self.loaded[c.command.action][0])
        return Dead(e, c.index, reads, scene, c.command, reads)

