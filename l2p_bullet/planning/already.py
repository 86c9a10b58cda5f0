"""Whether the relation a sentence asks for already holds where the mover stands, so that nothing is moved.

"Move A next to B" said of a block that already stands where people end their own "next to" is answered
"already next to B", not with a motion: people put a block next to another and stop; nobody in the study's
demonstrations nudged one that was already there, and the planner, asked to raise a progress that the start
has already reached, finds no move that raises it (docs/perform.md, "Already next to"). An action declares
where it already holds (``ActionSpec.planning.holds_within``, blocks between the footprints, from people's
own ends); the rule judge must accept the start as it stands as well, so an answer "already" is never one the
judge would fail. Actions that ask for a motion ("closer", "away", "past", "around") declare nothing: their
rules read a motion, never a place.

The answer is a plan of one pose, the start, ``stopped`` "already" (plan.json's ``extra.already`` says why);
``perform`` and a chain's clause record the world standing still for one frame instead of moving the arm.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..actions import ActionSpec
from ..core.contracts import Plan
from ..core.scene import Scene
from ..judge.footprints import gap as footprint_gap
from ..judge.footprints import outlines_of
from ..judge.rules import RULES, rule_verdict

STOPPED = "already"
"""``Plan.stopped`` of a plan that moves nothing because the relation already holds."""


def already(scene: Scene, mover: str, anchors: list[str], spec: ActionSpec | None) -> dict[str, Any] | None:
    """The rule judge's verdict on the start as it stands (with ``gap_blocks``) where ``spec`` declares where
    its relation already holds and the start is there; None where a motion is needed."""
    within = None if spec is None else spec.planning.holds_within
    if within is None or spec.rules not in RULES:
        return None
    m = scene.get(mover)
    objects = [m, *(scene.get(a) for a in anchors)]
    outlines = outlines_of(objects)
    a = objects[1]
    size = m.size
    gap = footprint_gap(np.r_[np.asarray(m.xy) / size, m.yaw], np.r_[np.asarray(a.xy) / size, a.yaw], size, outlines)
    if gap > within + 1e-9:
        return None
    more = [np.asarray(o.pose, float)[None] for o in objects[1:]]
    context: dict[str, Any] = {"outlines": outlines} if outlines is not None else {}
    if len(more) > 1:
        context["anchors"] = more
    verdict = rule_verdict(spec.rules, np.asarray(m.pose, float)[None], more[0], size, **context)
    if not verdict.success:
        return None
    return verdict.to_dict() | {"gap_blocks": round(float(gap), 4), "holds_within": within}


def standing_plan(scene: Scene, mover: str, anchors: list[str], action: str, planner: str, verdict: dict[str, Any],
                  model: Any) -> Plan:
    """The plan that moves nothing: the start as its one pose, scored by the action's ``model``."""
    m, a = scene.get(mover), scene.get(anchors[0])
    start = np.asarray(m.pose, float)[None]
    progress = np.asarray(model.curve(start, np.asarray(a.pose, float), m.size), float).reshape(-1)[:1]
    more = [np.asarray(scene.get(n).pose, float) for n in anchors[1:]]
    return Plan(
        action=action, mover=mover, anchor=anchors[0], size=m.size, anchor_pose=np.asarray(a.pose, float),
        start=start[0].copy(), path=start, progress=progress, planner=planner, stopped=STOPPED,
        extra={"final_progress": round(float(progress[-1]), 6) if len(progress) else None,
               "waypoints": start.round(6).tolist(), "steps": 0, "evaluations": 0, "forward_passes": 1,
               "seconds": 0.0, "already": {k: verdict[k] for k in ("reason", "gap_blocks", "holds_within")}},
        more_anchors=list(anchors[1:]),
        more_anchor_poses=np.array(more, float).reshape(-1, 3) if more else None,
        viewer=getattr(model, "viewpoint", None),
    )


def is_standing(plan: Any) -> bool:
    """Whether ``plan`` moves nothing because the relation already holds (:func:`standing_plan`)."""
    return getattr(plan, "stopped", None) == STOPPED


def already_said(verdict: dict[str, Any], plan: Any) -> dict[str, Any]:
    """The judge's ``verdict`` on a run of ``plan``, saying so where it moved nothing because the relation
    already holds (``already`` true; the reason begins "already holds, nothing moved"); else as it is."""
    if not is_standing(plan):
        return verdict
    held = plan.extra.get("already", {})
    where = f" (within {held['holds_within']:g} blocks, where people end it)" if "holds_within" in held else ""
    return verdict | {"already": True,
                      "reason": f"already holds{where}, nothing moved: {verdict.get('reason', '')}"}
