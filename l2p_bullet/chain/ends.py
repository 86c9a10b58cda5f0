"""A clause's end states: the ways one clause can be planned, so a chain can pick the one that keeps its later
clauses possible (forecast.py searches over them).

The planner gives one plan for a seed: the end the learned progress reaches first. Another seed gives
another search and usually another end (another side of the anchor, another way past it); a plan's path can
also stop short (where the rule judge first accepts it, with the margin a "a bit" extent keeps, or halfway
from there to where the planner ended it), which keeps a block sent "away" or "past" off the workspace's
rim. Each such choice is an :class:`End`, applied the same way at run time, when the clause is planned
again from where the world really left the blocks (run.py), so the executed clause keeps the end state the
chain was planned with.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .. import planning
from ..arms import ArmSpec
from ..core.contracts import Plan
from ..core.scene import Scene
from ..embodiment.manners import manner_planning
from ..manners import registry as manners
from ..options import RunOptions
from ..planning.extent import STEP, apply_extent
from ..planning.world2d import interpolate
from .clause import Clause


@dataclass(frozen=True)
class End:
    """How a clause is planned: the planner's seed offset from the run's seed, and where its path stops:
    ``cut`` None (the planned end), "least" (the least the judge accepts, plus the "a bit" extent's margin:
    ``planning.extent``) or "half" (halfway from there to the planned end)."""

    seed: int = 0
    cut: str | None = None

    def to_dict(self) -> dict[str, Any]:
        return {"seed_offset": self.seed, "cut": self.cut}


DEFAULT = End()
"""The end a lone clause gets: the planner's own (a chain that needs nothing else is planned as before)."""

ENDS = tuple(End(seed, cut) for seed in range(3) for cut in (None, "half", "least"))
"""The end states tried per clause, in order: the planner's own, then cut short, then two other seeds' plans
and their cuts. A seed's plan costs a search; its cuts cost none."""


def plan_clause(clause: Clause, scene: Scene, bundle: Any, judge: Any, options: RunOptions, arm: ArmSpec,
                end: End = DEFAULT, *, base: Plan | None = None) -> Plan:
    """``clause`` planned from ``scene`` with ``end``'s seed, its extent and ``end``'s cut applied.
    ``base``: the same clause already planned with ``end``'s seed from ``scene`` (only the cut is left to do).
    The caller runs the feasibility and path checks."""
    cmd = clause.command
    if base is None:
        plan = planning.plan(scene, cmd.mover, list(cmd.anchors), bundle, planner=options.planner,
                             seed=options.seed + end.seed, budget=options.budget, threshold=options.threshold,
                             target=None if clause.target is None else clause.target(scene), arm=arm,
                             **manner_planning(manners.get(cmd.manner), scene.get(cmd.mover).size, arm))
        plan = apply_extent(plan, cmd.extent, judge, scene)  # "far away from", "a bit closer to"
    else:
        plan = base
    # an extent asked for ("far away from") stays as asked, and a composite's slot is where its block must end
    if end.cut is not None and cmd.extent is None and clause.target is None:
        plan = cut_short(plan, end.cut, judge, scene)
    if end != DEFAULT:  # a copy: the uncut plan may be tried again as it is
        plan = replace(plan, extra={**plan.extra, "end_state": end.to_dict()})
    return plan


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
