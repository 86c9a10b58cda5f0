"""A sentence's extent ("far away from", "a bit closer to", "right next to") applied to a plan.

The learned progress model says when an event is complete, not how far past completion to go, and the
rule judge says the least that counts as the event. So an extent is read against the action's judge and
the 2-D world, the same for every action that declares it (``extents`` in its manifest):

- ``little``: the plan is cut at its shortest start the judge accepts: the least motion that still is
  the action ("a bit closer", "slightly away", "just past");
- ``far``: the plan goes on along its last heading until the mover has travelled ``FAR_TRAVEL`` times its
  planned length, or until the next step would leave the workspace or touch another object; the end kept
  is the farthest the judge still accepts ("far away from", "well past", "much closer");
- ``right``: the end is drawn straight towards the anchor until the next step would come closer to an
  object than the world's margin ("right next to").

A plan the extent cannot change (already the least, or no room to go farther) is kept as planned; the
change made is recorded in ``plan.extra["extent"]`` either way.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from ..core.contracts import Plan
from ..core.scene import Scene
from ..judge.base import judge_context
from ..judge.footprints import outlines_of
from .already import STOPPED as STANDING
from .world2d import World2D, interpolate

FAR_TRAVEL = 2.0
"""A far extent's travel, as a multiple of the planned path's length (people's "far" about doubles it)."""
STEP = 0.002
"""Metres between the poses an extent tests."""
LITTLE_MARGIN = 0.15
"""Block sides of path kept beyond the least the judge accepts, so the executed motion (which ends within
a millimetre or two of the plan) is not judged on the very edge of the rule."""


def apply_extent(plan: Plan, extent: str | None, judge: Any, scene: Scene) -> Plan:
    """``plan`` changed as ``extent`` asks (None: unchanged); see the module docstring. A plan that moves
    nothing because the relation already holds (``already.py``) is kept: there is no motion to extend."""
    if extent is None or plan.stopped == STANDING:
        return plan
    dense = interpolate(plan.path, STEP)
    # the objects' real footprints where one is not a cube, for a judge that reads them (judge/footprints.py)
    kw = judge_context([plan.anchor_pose], None, judge=judge,
                       outlines=outlines_of([scene.get(plan.mover), scene.get(plan.anchor)]))
    length = float(np.hypot(*np.diff(dense[:, :2], axis=0).T).sum()) if len(dense) > 1 else 0.0
    if extent == "little":
        new = _least(dense, plan, judge, int(math.ceil(LITTLE_MARGIN * plan.size / STEP)), kw)
    elif extent == "far":
        new = _farther(dense, plan, judge, World2D(scene, plan.mover), FAR_TRAVEL * length - length, kw)
    elif extent == "right":
        new = _closer_to_anchor(dense, plan, World2D(scene, plan.mover))
    else:
        raise ValueError(f"unknown extent {extent!r}")
    new_length = float(np.hypot(*np.diff(new[:, :2], axis=0).T).sum()) if len(new) > 1 else 0.0
    extra = {**plan.extra, "extent": {"asked": extent, "planned_m": round(length, 6), "m": round(new_length, 6)}}
    progress = _progress_along(plan, dense, new)
    return replace(plan, path=new, progress=progress, extra=extra)


def _accepts(judge: Any, plan: Plan, poses: np.ndarray, context: dict) -> bool:
    return bool(judge.judge(poses, plan.anchor_pose, plan.size, **context).success)


def _least(dense: np.ndarray, plan: Plan, judge: Any, margin: int, context: dict) -> np.ndarray:
    """The shortest start of the path the judge accepts and ``margin`` poses more (the whole path when no
    shorter start is accepted)."""
    for k in range(2, len(dense)):
        if _accepts(judge, plan, dense[:k], context):
            return dense[:min(len(dense), k + margin)]
    return dense


def _farther(dense: np.ndarray, plan: Plan, judge: Any, world: World2D, more: float, context: dict) -> np.ndarray:
    """The path continued along its last heading by up to ``more`` metres while the moves stay legal; the
    longest continuation the judge accepts."""
    tail = dense[-1, :2] - dense[max(0, len(dense) - 6), :2]
    norm = float(np.hypot(*tail))
    if norm < 1e-9 or more <= 0:
        return dense
    step = tail / norm * STEP
    out = [dense[-1]]
    for _ in range(int(math.floor(more / STEP))):
        nxt = out[-1].copy()
        nxt[:2] += step
        if not world.inside(nxt[None, :2])[0] or not world.moves_free(out[-1], nxt[None])[0]:
            break
        out.append(nxt)
    longer = np.vstack([dense, np.array(out[1:]).reshape(-1, 3)])
    for k in range(len(longer), len(dense), -1):
        if _accepts(judge, plan, longer[:k], context):
            return longer[:k]
    return dense


def _closer_to_anchor(dense: np.ndarray, plan: Plan, world: World2D) -> np.ndarray:
    """The path's end drawn straight towards the anchor while the moves stay legal."""
    towards = np.asarray(plan.anchor_pose[:2], float) - dense[-1, :2]
    norm = float(np.hypot(*towards))
    if norm < 1e-9:
        return dense
    step = towards / norm * STEP
    out = [dense[-1]]
    while len(out) * STEP < norm:
        nxt = out[-1].copy()
        nxt[:2] += step
        if not world.inside(nxt[None, :2])[0] or not world.moves_free(out[-1], nxt[None], relax=False)[0]:
            break
        out.append(nxt)
    return np.vstack([dense, np.array(out[1:]).reshape(-1, 3)])


def _progress_along(plan: Plan, dense: np.ndarray, new: np.ndarray) -> np.ndarray:
    """Per pose of ``new``: the planned progress at the nearest planned pose (held at its last value past
    the planned end), so plan.json keeps one value per pose."""
    planned = np.interp(np.arange(len(dense)), np.linspace(0, len(dense) - 1, len(plan.progress)),
                        np.asarray(plan.progress, float)) if len(plan.progress) else np.zeros(len(dense))
    idx = np.minimum(np.arange(len(new)), len(dense) - 1)
    return planned[idx]
