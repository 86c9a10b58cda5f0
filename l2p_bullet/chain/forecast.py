"""The whole chain planned in 2-D before the arm moves: each clause from the end state the previous
clauses' plans predict, so a clause that cannot be planned is refused up front, naming it and the check.

Planned as a whole: each clause is planned with the planner's own end first; when a later clause cannot be
planned from there, the earlier clauses' other end states (ends.py: a path stopped short, other seeds, the
end turned about the anchor) are tried, latest first, depth first, so one clause's greedy end (a block left
on the workspace's rim, a block already past its anchor) does not make the chain impossible when another end
of the same clause would keep it possible. Only the clauses that moved a block the failed check reads are
tried again (a room check reads the mover and the anchor; every other check, the whole scene). An end the
clause's judge does not accept on the plan is not chosen; the planner's own, so judged, is tried after every
other end (and kept, as clause by clause, when none works: the run judges what it does). A chain is refused
only when no combination tried works, with the first failure found (the clause and its check) and what was
tried.

The checks per clause, in order: the arm's and the judge's feasibility checks (``grasp``, ``boxed-in``,
``room-*``: planning.feasibility), the planner itself (``plan``: no legal move), and the execution's path
check (``path``: the planned path leaves the workspace or runs into a block). The forecast is a prediction:
at run time each clause is planned again, with the end state chosen for it, from where the simulated world
really left the blocks.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..core.contracts import Plan
from ..core.scene import Scene
from ..errors import InfeasibleError, L2PError, PathError, PlanError
from ..judge import judge_context, judge_for
from ..judge.footprints import outlines_of
from ..manners import registry as manners
from ..options import RunOptions
from ..pipeline import check_feasible
from ..plugins import registry
from .clause import Clause, named
from .ends import DEFAULT, ENDS, End, plan_clause, turned_goal

SEARCH_PLANS = 4
"""Plans a chain's search may make, per clause, to look for other ends (each plan is one search of the
planner; a cut end costs none). A chain its clauses' own ends make possible is planned once per clause, as
before. Once spent, the search goes on with the planner's own ends alone, so a chain planned clause by
clause is never refused for the search's sake (chosen on the development chains, docs/benchmarks.md)."""


@dataclass
class Step:
    """What one clause needs at run time: the clause, its loaded action, its forecast plan, and the end state
    the chain chose for it (ends.py; run.py plans the clause again with it)."""

    clause: Clause
    bundle: Any
    model: Any
    judge: Any
    forecast: Plan
    end: End = DEFAULT

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


@dataclass
class _Dead(Exception):
    """A subtree of the search with no way through: the first failure found (already named) and the blocks
    whose poses its check reads (None: every block)."""

    error: L2PError
    clause: int
    blocks: frozenset[str] | None


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
        searcher = _Searcher(clauses, plugins, opts, loaded, stats)
        steps = searcher.steps(0, scene)
    except _Dead as d:
        raise _refusal(d, clauses, stats) from None
    finally:
        stats.seconds += time.perf_counter() - t0
    stats.kept_seconds = sum(searcher.kept.get(id(s.forecast), 0.0) for s in steps)
    stats.changed = [s.clause.index for s in steps if s.end != DEFAULT]
    return steps


class _Searcher:
    """Depth first over the clauses' end states, back-jumping past clauses that moved no block a failure reads."""

    def __init__(self, clauses: list[Clause], plugins: list, opts: RunOptions, loaded: dict, stats: Search):
        self.clauses, self.plugins, self.opts, self.loaded, self.stats = clauses, plugins, opts, loaded, stats
        self.arm = opts.arm_spec()
        self.left = SEARCH_PLANS * len(clauses)
        self.cost: dict[int, float] = {}  # id(plan) -> seconds to make it (a cut: to cut it)
        self.kept: dict[int, float] = {}  # id(plan) -> seconds to check and plan its clause alone

    def steps(self, k: int, predicted: Scene) -> list[Step]:
        if k == len(self.clauses):
            return []
        c = self.clauses[k]
        bundle, model, judge = self.loaded[c.command.action]
        t0 = time.perf_counter()
        try:
            check_feasible(c.command, predicted, self.plugins, self.arm)
        except L2PError as e:  # no end state of this clause helps: the scene it starts from is what fails
            raise self._dead(c, e) from None
        checked = time.perf_counter() - t0
        first: _Dead | None = None
        judged_short: tuple[Plan, End] | None = None  # the planner's own end, when the judge does not accept it
        planned: dict[int, Plan | None] = {}  # seed offset -> its plan (None: it failed)
        for end in ENDS:
            if self.left <= 0 and end != DEFAULT:
                break  # the search is spent: the planner's own ends only, as clause by clause
            if end.seed not in planned:
                self.left -= 1
                planned[end.seed] = None
                try:
                    planned[end.seed] = self._plan(c, predicted, bundle, judge, end)
                except _Dead as d:
                    first = first or d
                    if isinstance(d.error, InfeasibleError) and d.error.check != "no-motion":
                        break  # a check of the scene (no way in from afar...): another seed meets it again
                    continue
                plan = planned[end.seed]
            elif planned[end.seed] is None:
                continue
            else:
                if end.turn:  # a turned end is planned to: a search, where there is one to plan to
                    if turned_goal(c, predicted, planned[end.seed], end.turn) is None:
                        continue
                    self.left -= 1
                try:
                    plan = self._plan(c, predicted, bundle, judge, end, base=planned[end.seed])
                except _Dead as d:
                    first = first or d
                    continue
            if end.cut is not None and np.allclose(plan.path[-1], planned[end.seed].path[-1]):
                continue  # the cut leaves the end where it was: nothing new to try
            self.kept[id(plan)] = checked + self.cost[id(plan)] + (
                self.cost[id(planned[end.seed])] if end.cut is not None or end.turn else 0.0)
            step = self._step(c, bundle, model, judge, plan, end, predicted)
            if not step.forecast.extra["verdict"]["success"]:
                if end == DEFAULT:  # kept for last: clause by clause, it is what the chain would run
                    judged_short = (plan, end)
                continue  # another end of this clause may be one its judge accepts; no other end it rejects is
            try:
                return [step, *self.steps(k + 1, predicted.with_pose(c.command.mover, plan.path[-1]))]
            except _Dead as d:
                first = first or d
                if d.blocks is not None and c.command.mover not in d.blocks:
                    raise first from None  # this clause's end does not move what failed: try an earlier one
        if judged_short is not None:  # no end the judge accepts: planned as it was (the run judges what it does)
            plan, end = judged_short
            step = self._step(c, bundle, model, judge, plan, end, predicted)
            return [step, *self.steps(k + 1, predicted.with_pose(c.command.mover, plan.path[-1]))]
        raise first if first is not None else self._dead(c, PlanError("no end state left to try"))

    def _plan(self, c: Clause, predicted: Scene, bundle: Any, judge: Any, end: End, base: Plan | None = None) -> Plan:
        from ..embodiment.execute import check_for  # lazy: the arm's modules load only when a chain is forecast

        t0 = time.perf_counter()
        try:
            plan = plan_clause(c, predicted, bundle, judge, self.opts, self.arm, end, base=base)
            check_for(manners.get(c.command.manner), predicted, c.command.mover, plan.path, self.arm)
        except L2PError as e:
            raise self._dead(c, e) from None
        finally:
            self.stats.plans += base is None or bool(end.turn)
        self.cost[id(plan)] = time.perf_counter() - t0
        return plan

    def _step(self, c: Clause, bundle: Any, model: Any, judge: Any, plan: Plan, end: End, scene: Scene) -> Step:
        poses = [plan.anchor_pose, *([] if plan.more_anchor_poses is None else list(plan.more_anchor_poses))]
        outlines = outlines_of([scene.get(o) for o in (c.command.mover, *c.command.anchors)])
        plan.extra["verdict"] = judge.judge(plan.path, plan.anchor_pose, plan.size,
                                            final_progress=plan.extra.get("final_progress"),
                                            **judge_context(poses, plan.viewer, judge=judge,
                                                            outlines=outlines)).to_dict()
        plan.extra.setdefault("sentence", c.text)
        return Step(c, bundle, model, judge, plan, end)

    def _dead(self, c: Clause, e: L2PError) -> _Dead:
        check = e.check if isinstance(e, InfeasibleError) else None
        key = f"clause {c.index} ({check or _kind(e)})"
        self.stats.dead_ends[key] = self.stats.dead_ends.get(key, 0) + 1
        reads = frozenset(c.command.anchors) | {c.command.mover} if check and check.startswith("room-") else None
        return _Dead(e, c.index, reads)


def _kind(e: L2PError) -> str:
    return "plan" if isinstance(e, PlanError) else "path" if isinstance(e, PathError) else type(e).__name__


def _refusal(d: _Dead, clauses: list[Clause], stats: Search) -> L2PError:
    """The first failure, named by its clause, with what the search tried before it gave up."""
    c, e = clauses[d.clause - 1], d.error
    first = f"clause {c.index} ({e.check if isinstance(e, InfeasibleError) else _kind(e)})"
    others = {k: n for k, n in stats.dead_ends.items() if k != first}
    tried = "" if d.clause == 1 or not others else (
        "; no other end state of the clauses before it keeps it possible (" + str(stats.plans) + " plans; "
        + "the other end states tried met " + ", ".join(f"{k} x{n}" for k, n in others.items()) + ")")
    if isinstance(e, InfeasibleError):
        e.details["clause"] = c.index
        return named(e, f"{c.label()} cannot be planned ({e.check})", tried)
    if isinstance(e, PlanError):
        return named(PlanError(str(e)), f"{c.label()} cannot be planned (plan)", tried)
    if isinstance(e, PathError):
        return named(PathError(str(e)), f"{c.label()} cannot be planned (path)", tried)
    return named(e, c.label(), tried)
