"""A clause of a chain planned again at run time (run.py), from where the world really left the blocks: which plan
it runs, where it is planned from, and what its plan is held to besides its judge.

Which plan: where every block still stands where the forecast predicted it (within :data:`FOLLOW_TOL_M`), the
forecast's own plan, started where the mover really is, with its path checked and its judge asked again
(:func:`followed`); the planner's search is not smooth in its start, and planned again from a state a few tenths of
a millimetre off it can end a clause centimetres elsewhere, where a later clause has no way left.

Where from: a clause planned to end on the workspace's rim ends within a tenth of a millimetre of its plan, on
either side; a block left a hair outside could not move at all (every move must start inside), so the next clause
is planned from the nearest point of the edge (:func:`on_rim`).

Held to: the chain's later clauses stay possible from where it ends, as the forecast found them from where its own
plan ended. A start a tenth of a millimetre off the predicted one can send the planner's search to another end: a
"next to" that leaves the block nearer its anchor than forecast, so the "closer" after it has no room left
(``room-closer``), or a "closer" whose search from the real start closes 46 % of the gap where the forecast's
closed 58 %. The forecast's path itself, from the real start, is the end the whole chain was planned on; it is the
first other plan tried (:func:`replanned`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import Any

import numpy as np

from ..arms import ArmSpec
from ..core.contracts import Plan
from ..core.scene import Scene
from ..embodiment.path_checks import START_TOLERANCE
from ..errors import InfeasibleError, L2PError
from ..judge import plan_verdict
from ..judge.footprints import outlines_of
from ..options import RunOptions
from ..pipeline import check_feasible
from ..planning.already import is_standing
from ..plugins import registry
from .ends import plan_clause
from .forecast import Step

RIM_SLACK = 0.001
"""How far (m) beyond the workspace's edge the arm may leave a block's centre and the next clause still plan it from
the edge: a clause planned to end on the rim ends within a tenth of a millimetre of its plan, on either side, and a
block a hair outside could not move at all (every move must start inside: ``boxed-in``). Well within the 3 mm a
path may start from its block (embodiment/path_checks.py)."""


def on_rim(now: Scene) -> Scene:
    """``now`` with each block whose centre lies outside the workspace by at most :data:`RIM_SLACK` put on the
    nearest point of its edge (yaw kept): where the next clause is planned from. The judges read the real frames."""
    ws, moved = now.workspace, []
    for o in now.objects:
        xy = np.array([o.xy], float)
        if not ws.contains(xy)[0]:
            edge = ws.nearest_inside(xy, 1e-6)[0]  # a micrometre in: the ring's corners are found to 1e-7
            if float(np.hypot(*(edge - xy[0]))) <= RIM_SLACK:
                o = o.moved(np.array([*edge, o.yaw]))
        moved.append(o)
    return Scene(moved, now.table, now.workspace)


def forecast_from(step: Step, now: Scene) -> Plan | None:
    """``step``'s forecast plan started where its mover really stands (its first waypoint moved there, the anchors'
    poses read from ``now``), or None when there is none or the mover stands farther than a path may start from it
    (``START_TOLERANCE``): the caller checks the path and judges it as any plan."""
    f = step.forecast
    if f is None or not len(f.path):
        return None
    cmd = step.clause.command
    start = np.asarray(now.get(cmd.mover).pose, float)
    if float(np.hypot(*(np.asarray(f.path[0][:2], float) - start[:2]))) > START_TOLERANCE:
        return None
    path = np.array(f.path, float)
    path[0] = start
    more = f.more_anchor_poses
    if more is not None:
        more = np.array([now.get(o).pose for o in f.more_anchors], float)
    return replace(f, start=start, path=path, anchor_pose=np.asarray(now.get(f.anchor).pose, float),
                   more_anchor_poses=more, extra=dict(f.extra))


SAME_END = (0.001, 0.02)
"""Metres and radians within which a re-plan's end is the forecast's own: its later clauses were checked there (a
plan executed ends within a tenth of a millimetre of itself), so they are not checked again."""


def same_end(plan: Plan, forecast: Plan | None) -> bool:
    """Whether ``plan`` ends where ``forecast`` does, within :data:`SAME_END`."""
    if forecast is None or not len(forecast.path):
        return False
    a, b = np.asarray(plan.path[-1], float), np.asarray(forecast.path[-1], float)
    turn = abs((a[2] - b[2] + np.pi) % (2 * np.pi) - np.pi)
    return float(np.hypot(*(a[:2] - b[:2]))) <= SAME_END[0] and turn <= SAME_END[1]


def later_fails(plan: Plan, now: Scene, later: Sequence[Step], plugins: list, arm: ArmSpec) -> str | None:
    """The first of the ``later`` clauses whose up-front checks fail when ``plan``'s mover ends where it does and
    each clause between ends where the forecast has it (as the forecast checked them), named with its check; None
    when every one passes."""
    scene = now.with_pose(plan.mover, plan.path[-1])
    for s in later:
        try:
            check_feasible(s.clause.command, scene, plugins, arm)
        except L2PError as e:
            check = e.check if isinstance(e, InfeasibleError) else type(e).__name__
            return f"clause {s.clause.index} ({check}) after it"
        if s.forecast is not None:
            scene = scene.with_pose(s.clause.command.mover, s.forecast.path[-1])
    return None


def noted(plan: Plan, how: dict[str, Any], rejected: str) -> Plan:
    """``plan`` with why it was chosen over the re-plan kept in ``extra["replanned"]``."""
    plan.extra["replanned"] = {**how, "rejected": rejected}
    return plan


OTHER_SEEDS = (1, 2)
"""Seed offsets (added to the chosen end's) a clause re-planned from the real state is planned with again where its
rule judge rejects the plan: the forecast planned it from the predicted state, and a block a few millimetres from
where it was predicted can turn the same seed's search to another end (a "past" from touching that starts 0.49
blocks before the anchor where the rule asks 0.5), which another seed's search does not share."""


FOLLOW_TOL_M = 0.002
"""How far (m) any block may stand from where the forecast predicted it, at a clause's start, for the run to follow
the forecast's plan of that clause instead of planning it again. Why: the planner's search is not smooth in its
start; planned again from a state a few tenths of a millimetre off the predicted one, it can end a clause centimetres
from the forecast's end, where a later clause the chain was planned for has no way left (an "around" the forecast
swept a whole turn finds less than the 0.8 its judge asks; docs/benchmarks.md, "Chains drawn whole").
Two millimetres: the blocks stand within half a millimetre of the forecast after a clause, and a path may start
3 mm from a block (embodiment/path_checks.py)."""


def _runs(plan: Plan, step: Step, now: Scene, arm: ArmSpec, outlines: Any) -> bool:
    """Whether the arm can follow ``plan``'s path in ``now`` and ``step``'s judge accepts it (``outlines``: the mover's
    and the anchors' where they really are)."""
    from ..embodiment import execute as ex

    cmd = step.clause.command
    try:
        ex.check_for(ex.manner_of(cmd.manner), now, cmd.mover, plan.path, arm)
    except L2PError:
        return False
    return bool(plan_verdict(step.judge, plan, outlines=outlines)["success"])


def followed(step: Step, now: Scene, arm: ArmSpec, outlines: Any) -> Plan | None:
    """``step``'s forecast plan, started from where its mover really stands (:func:`forecast_from`), where every block
    of ``now`` stands within :data:`FOLLOW_TOL_M` of the state it was forecast from (``step.scene``), the arm can
    follow its path there and its judge accepts it from there (:func:`_runs`); else None (planned again)."""
    plan, predicted = step.forecast, step.scene
    if plan is None or predicted is None or is_standing(plan) or sorted(predicted.names) != sorted(now.names):
        return None
    if any(np.hypot(*np.subtract(o.xy, predicted.get(o.name).xy)) > FOLLOW_TOL_M for o in now.objects):
        return None
    kept = forecast_from(step, now)
    if kept is None:
        return None
    kept.extra["followed_forecast"] = True
    return kept if _runs(kept, step, now, arm, outlines) else None


def replanned(step: Step, now: Scene, options: RunOptions, arm: ArmSpec, *, later: Sequence[Step] = (),
              plugins: list | None = None) -> Plan:
    """``step``'s clause as the forecast planned it, where the world is still the state it was forecast from
    (:func:`followed`); else planned from ``now`` with the end the chain chose for it, where its judge accepts that
    plan and the ``later`` clauses' up-front checks pass after it; else the first other plan that does, of the
    forecast's own path from the real start and the plans with :data:`OTHER_SEEDS` (each followable by the arm; why
    kept in ``extra["replanned"]``); else the first of them its judge accepts, else the plan with the chosen end (the
    run judges what it does). A plan that moves nothing because the relation already holds is kept as it is."""
    cmd = step.clause.command
    outlines = outlines_of([now.get(o) for o in (cmd.mover, *cmd.anchors)])
    kept = followed(step, now, arm, outlines)
    if kept is not None:
        return kept
    plan = plan_clause(step.clause, now, step.bundle, step.judge, options, arm, step.end)
    if is_standing(plan):
        return plan
    plugins = registry.discover() if later and plugins is None else plugins

    def fails(p: Plan) -> str | None:
        return later_fails(p, now, later, plugins, arm) if later and not same_end(p, step.forecast) else None

    verdict = plan_verdict(step.judge, plan, outlines=outlines)
    why = None if verdict["success"] else verdict["reason"]
    why = why or fails(plan)
    if why is None:
        return plan
    accepted = None  # the first other plan its judge accepts: taken where none keeps the later clauses possible
    for how in ({"forecast": True}, *({"seed_offset": step.end.seed + k} for k in OTHER_SEEDS)):
        if "forecast" in how:
            other = forecast_from(step, now)
        else:
            try:
                other = plan_clause(step.clause, now, step.bundle, step.judge, options, arm,
                                    replace(step.end, seed=how["seed_offset"]))
            except L2PError:
                continue
        if other is None or is_standing(other) or not _runs(other, step, now, arm, outlines):
            continue
        if fails(other) is None:
            return noted(other, how, why)
        accepted = accepted or (other, how)
    if accepted is not None and not verdict["success"]:
        return noted(*accepted, why)
    return plan
