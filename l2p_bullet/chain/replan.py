"""A clause re-planned at run time (run.py), from where the world really left the blocks: where it is planned from,
and what its plan is held to besides its judge.

Where from: a clause planned to end on the workspace's rim ends within a tenth of a millimetre of its plan, on
either side; a block left a hair outside could not move at all (every move must start inside), so the next clause
is planned from the nearest point of the edge (:func:`on_rim`).

Held to: the chain's later clauses stay possible from where it ends, as the forecast found them from where its own
plan ended. A start a tenth of a millimetre off the predicted one can send the planner's search to another end: a
"next to" that leaves the block nearer its anchor than forecast, so the "closer" after it has no room left
(``room-closer``), or a "closer" whose search from the real start closes 46 % of the gap where the forecast's
closed 58 %. The forecast's path itself, from the real start, is the end the whole chain was planned on; it is the
first other plan tried (run.py: ``replanned``).
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
from ..pipeline import check_feasible
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
