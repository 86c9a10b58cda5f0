"""A clause's end states: the ways one clause can be planned, so a chain can pick the one that keeps its later
clauses possible (forecast.py searches over them).

The planner gives one plan for a seed: the end the learned progress reaches first. Another seed gives
another search and usually another end (another side of the anchor, another way past it); a plan's path can
also stop short (where the rule judge first accepts it, with the margin a "a bit" extent keeps, or halfway
from there to where the planner ended it), which keeps a block sent "away" or "past" off the workspace's
rim; or the planner's end can be turned about the anchor (as far from it, on another bearing) and planned
to as a target, which keeps a block sent "away" from an anchor near the rim inside it. Each such choice is
an :class:`End`, applied the same way at run time, when the clause is planned again from where the world
really left the blocks (run.py), so the executed clause keeps the end state the chain was planned with.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .. import planning
from ..arms import ArmSpec
from ..core.contracts import Plan
from ..core.scene import Scene
from ..embodiment.manners import manner_planning
from ..errors import PlanError
from ..manners import registry as manners
from ..options import RunOptions
from ..planning.extent import STEP, apply_extent
from ..planning.world2d import World2D, interpolate
from .aims import slide_parts
from .clause import Clause


@dataclass(frozen=True)
class End:
    """How a clause is planned: the planner's seed offset from the run's seed, and where its path stops:
    ``cut`` None (the planned end), "least" (the least the judge accepts, plus the "a bit" extent's margin:
    ``planning.extent``) or "half" (halfway from there to the planned end); or ``turn``; or ``aim``."""

    seed: int = 0
    cut: str | None = None
    turn: int = 0  # degrees: the planned end turned about the anchor, then planned to as a target
    aim: tuple[float, float, float] | None = None  # x, y, yaw: a place planned to as a target (aims.py)
    via: str | None = None  # with ``aim``: reached by a straight slide after this start of the plan (aims.VIAS)

    def to_dict(self) -> dict[str, Any]:
        return {"seed_offset": self.seed, "cut": self.cut, **({"turn_deg": self.turn} if self.turn else {}),
                **({"aim": [round(v, 6) for v in self.aim]} if self.aim is not None else {}),
                **({"via": self.via} if self.via is not None else {})}


DEFAULT = End()
"""The end a lone clause gets: the planner's own (a chain that needs nothing else is planned as before)."""

ENDS = (*(End(seed, cut) for seed in range(2) for cut in (None, "half", "least")),
        *(End(0, None, turn) for turn in (30, -30, 60, -60)), End(2), End(2, "half"), End(2, "least"))
"""The end states tried per clause, in order: the planner's own, then cut short, another seed's plan and its
cuts, the planner's end turned 30 and 60 degrees either way about the anchor, a third seed's. A seed's plan
and a turned end each cost a search; a cut costs none. (Turns of 30 and 60 degrees: on the development
chains "away" then "around" that anchor needed 60.)"""


def plan_clause(clause: Clause, scene: Scene, bundle: Any, judge: Any, options: RunOptions, arm: ArmSpec,
                end: End = DEFAULT, *, base: Plan | None = None, slide_only: bool = False) -> Plan:
    """``clause`` planned from ``scene`` with ``end``'s seed, its extent and ``end``'s cut applied.
    ``base``: the same clause already planned with ``end``'s seed from ``scene`` (only the cut is left to do).
    ``slide_only``: an aimed slide that is not free here is a PlanError (the forecast, whose search tries the
    search to that place as an end of its own); else (the run, from where the world really left the blocks) the
    place is searched to as a target instead. The caller runs the feasibility and path checks."""
    cmd = clause.command
    if end.turn:
        return _turned(clause, scene, bundle, judge, options, arm, end, base)
    if end.aim is not None and end.via is not None:
        try:
            return _slid(clause, scene, bundle, judge, options, arm, end, base)
        except PlanError:
            if slide_only:
                raise
            plan = plan_clause(clause, scene, bundle, judge, options, arm, replace(end, via=None), base=base)
            return replace(plan, extra={**plan.extra, "end_state": end.to_dict()})
    if end.aim is not None:
        plan = _search(clause, scene, bundle, options, arm, end.seed, np.asarray(end.aim, float))
        return replace(plan, extra={**plan.extra, "end_state": end.to_dict()})
    if base is None:
        plan = _search(clause, scene, bundle, options, arm, end.seed,
                       None if clause.target is None else clause.target(scene))
        plan = apply_extent(plan, cmd.extent, judge, scene)  # "far away from", "a bit closer to"
    else:
        plan = base
    # an extent asked for ("far away from") stays as asked, and a composite's slot is where its block must end
    if end.cut is not None and cmd.extent is None and clause.target is None:
        plan = cut_short(plan, end.cut, judge, scene)
    if end != DEFAULT:  # a copy: the uncut plan may be tried again as it is
        plan = replace(plan, extra={**plan.extra, "end_state": end.to_dict()})
    return plan


def _turned(clause: Clause, scene: Scene, bundle: Any, judge: Any, options: RunOptions, arm: ArmSpec, end: End,
            base: Plan | None) -> Plan:
    """The plan to the planner's end (``base``, or planned here) turned ``end.turn`` degrees about the anchor."""
    base = base if base is not None else plan_clause(clause, scene, bundle, judge, options, arm, End(end.seed))
    goal = turned_goal(clause, scene, base, end.turn)
    if goal is None:
        raise PlanError(f"the end turned {end.turn} degrees about the anchor is outside the workspace")
    plan = _search(clause, scene, bundle, options, arm, end.seed, goal)
    return replace(plan, extra={**plan.extra, "end_state": end.to_dict()})


def _slid(clause: Clause, scene: Scene, bundle: Any, judge: Any, options: RunOptions, arm: ArmSpec, end: End,
          base: Plan | None) -> Plan:
    """The planner's plan (``base``, or planned here) up to ``end.via``'s start, then a straight slide to
    ``end.aim`` (aims.slide_parts: the path the judge accepted when the place was chosen), costing no search.
    Why: a search to the place as a target goes its own way there and can lose what the place was chosen with
    (a "past" whose planner passed the anchor close by passes it far off when searched to its aimed end). The
    slide is held to the planner's rule for a move (World2D.moves_free), and its frames keep the progress of
    where it starts (the model does not rate them: ``final_progress`` is left to the judge)."""
    base = base if base is not None else plan_clause(clause, scene, bundle, judge, options, arm, End(end.seed))
    head, slide = slide_parts(base, np.asarray(end.aim, float), scene.get(clause.command.mover).size, end.via)
    world = World2D(scene, clause.command.mover)
    if not world.inside(slide[:, :2]).all() or not world.moves_free(head[-1], slide[-1:])[0]:
        raise PlanError("the straight slide to the aimed end runs into another object or out of the workspace")
    n = len(base.path)
    planned = np.interp(np.arange(n), np.linspace(0, n - 1, len(base.progress)), np.asarray(base.progress, float)) \
        if len(base.progress) else np.zeros(n)
    progress = np.concatenate([planned[:len(head)], np.full(len(slide), planned[len(head) - 1])])
    return replace(base, path=np.vstack([head, slide]), progress=progress,
                   extra={**base.extra, "final_progress": None, "end_state": end.to_dict()})


def _search(clause: Clause, scene: Scene, bundle: Any, options: RunOptions, arm: ArmSpec, seed: int,
            target: np.ndarray | None) -> Plan:
    """One search of the planner for ``clause`` with the options' seed plus ``seed``, towards ``target`` if any."""
    cmd = clause.command
    return planning.plan(scene, cmd.mover, list(cmd.anchors), bundle, planner=options.planner,
                         seed=options.seed + seed, budget=options.budget, threshold=options.threshold,
                         target=target, arm=arm,
                         **manner_planning(manners.get(cmd.manner), scene.get(cmd.mover).size, arm))


def turned_goal(clause: Clause, scene: Scene, base: Plan, turn: int) -> np.ndarray | None:
    """``base``'s end turned ``turn`` degrees about the clause's anchor; None where there is no such end: it
    lies outside the workspace, or the clause asks for an extent or a composite's slot (kept as asked)."""
    cmd = clause.command
    if cmd.extent is not None or clause.target is not None:
        return None
    anchor = np.asarray(scene.get(cmd.anchor).xy, float)
    t, goal = math.radians(turn), np.array(base.path[-1], float)
    v = goal[:2] - anchor
    goal[:2] = anchor + (math.cos(t) * v[0] - math.sin(t) * v[1], math.sin(t) * v[0] + math.cos(t) * v[1])
    ws = scene.workspace
    inside = float(np.hypot(*(goal[:2] - np.asarray(ws.center)))) <= ws.radius - scene.get(cmd.mover).size / 2
    return goal if inside else None


def cut_short(plan: Plan, cut: str, judge: Any, scene: Scene) -> Plan:
    """``plan`` stopped at the shortest start of its path that the judge accepts (with the "a bit" extent's
    margin: ``cut`` "least"), or halfway (in path length) from there to its end ("half"); ``plan`` itself
    when the judge accepts no shorter start."""
    least = apply_extent(plan, "little", judge, scene)
    dense = interpolate(plan.path, STEP)
    cut = len(least.path) if cut == "least" else (len(least.path) + len(dense)) // 2
    if len(least.path) >= len(dense) or cut >= len(dense) - 1:
        return plan
    progress = np.interp(np.linspace(0, len(plan.progress) - 1, len(dense)), np.arange(len(plan.progress)),
                         np.asarray(plan.progress, float)) if len(plan.progress) else np.zeros(len(dense))
    extra = {**plan.extra, "final_progress": float(progress[cut - 1]) if len(progress) else None}
    return replace(plan, path=dense[:cut], progress=progress[:cut], extra=extra)
