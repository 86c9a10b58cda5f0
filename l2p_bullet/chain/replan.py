"""A clause of a chain planned again at run time, from the world as it really is after the clauses before it.

The forecast (chain/forecast.py) planned every clause from the state it predicted; the run (chain/run.py) asks here
for the plan it executes: the forecast's own plan where the world still stands where it was predicted (checked and
judged from the real state), else the clause planned again from the real state with the end the chain chose for it,
and with other seeds where its judge rejects that plan.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..arms import ArmSpec
from ..core.contracts import Plan
from ..core.scene import Scene
from ..errors import L2PError
from ..judge import plan_verdict
from ..judge.footprints import outlines_of
from ..options import RunOptions
from ..planning.already import is_standing
from .ends import plan_clause
from .forecast import Step

OTHER_SEEDS = (1, 2)
"""Seed offsets (added to the chosen end's) a clause re-planned from the real state is planned with again where its
rule judge rejects the plan: the forecast planned it from the predicted state, and a block a few millimetres from
where it was predicted can turn the same seed's search to another end (a "past" from touching that starts 0.49
blocks before the anchor where the rule asks 0.5), which another seed's search does not share."""


FOLLOW_TOL_M = 0.002
"""How far (m) any block may stand from where the forecast predicted it, at a clause's start, for the run to follow
the forecast's plan of that clause instead of planning it again. Why: the planner's search is not smooth in its
start; planned again from a state a few tenths of a millimetre off the predicted one, it can end a clause centimetres
from the forecast's end (chain/25305: "move D around C" 27 mm, then "move D closer to C" 39 mm), where a later
clause the chain was planned for has no way left ("move C around D": 1.07 of a turn on the forecast, 0.62 run).
Two millimetres: the blocks stand within half a millimetre of the forecast after a clause, and a path may start
3 mm from a block (embodiment/path_checks.py)."""


def followed(step: Step, now: Scene, arm: ArmSpec) -> Plan | None:
    """``step``'s forecast plan, started from where its mover really stands, where every block of ``now`` stands
    within :data:`FOLLOW_TOL_M` of the state it was forecast from (``step.scene``), the arm can follow its path
    there and its judge accepts it from there (the anchors where they really are); else None (planned again)."""
    from ..embodiment import execute as ex

    plan, cmd, predicted = step.forecast, step.clause.command, step.scene
    if plan is None or predicted is None or is_standing(plan) or sorted(predicted.names) != sorted(now.names):
        return None
    if any(np.hypot(*np.subtract(o.xy, predicted.get(o.name).xy)) > FOLLOW_TOL_M for o in now.objects):
        return None
    path = np.array(plan.path, float)
    path[0] = now.get(cmd.mover).pose
    more = None if plan.more_anchor_poses is None else np.array([now.get(a).pose for a in plan.more_anchors])
    kept = replace(plan, start=path[0].copy(), path=path, anchor_pose=np.asarray(now.get(plan.anchor).pose, float),
                   more_anchor_poses=more, extra={**plan.extra, "followed_forecast": True})
    try:
        ex.check_for(ex.manner_of(cmd.manner), now, cmd.mover, kept.path, arm)
    except L2PError:
        return None
    outlines = outlines_of([now.get(o) for o in (cmd.mover, *cmd.anchors)])
    return kept if plan_verdict(step.judge, kept, outlines=outlines)["success"] else None


def replanned(step: Step, now: Scene, options: RunOptions, arm: ArmSpec) -> Plan:
    """``step``'s clause as the forecast planned it, where the world is still the state it was forecast from
    (:func:`followed`); else planned from ``now`` with the end the chain chose for it; where its judge rejects that
    plan, the first plan with :data:`OTHER_SEEDS` that its judge accepts and whose path the arm can follow (kept in
    ``extra["replanned"]``), else the plan with the chosen end (the run judges what it does). A plan that moves
    nothing because the relation already holds is kept as it is."""
    from ..embodiment import execute as ex

    kept = followed(step, now, arm)
    if kept is not None:
        return kept
    cmd = step.clause.command
    plan = plan_clause(step.clause, now, step.bundle, step.judge, options, arm, step.end)
    outlines = outlines_of([now.get(o) for o in (cmd.mover, *cmd.anchors)])
    if is_standing(plan) or plan_verdict(step.judge, plan, outlines=outlines)["success"]:
        return plan
    for offset in OTHER_SEEDS:
        end = replace(step.end, seed=step.end.seed + offset)
        try:
            other = plan_clause(step.clause, now, step.bundle, step.judge, options, arm, end)
            ex.check_for(ex.manner_of(cmd.manner), now, cmd.mover, other.path, arm)
        except L2PError:
            continue
        if not is_standing(other) and plan_verdict(step.judge, other, outlines=outlines)["success"]:
            other.extra["replanned"] = {"seed_offset": end.seed, "rejected": plan_verdict(
                step.judge, plan, outlines=outlines)["reason"]}
            return other
    return plan
