"""What a judge is: a verdict on a motion, from rules written for the words or from a learned model."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np


@dataclass(frozen=True)
class Verdict:
    """A judge's answer: yes/no, a graded score in [0, 1], the reason in words, and which judge said it."""

    success: bool
    score: float
    reason: str
    judge: str = "rules"

    def to_dict(self) -> dict[str, Any]:
        """The verdict as run folders and ``--json`` outputs hold it (summary.json's ``verdict``)."""
        return {"success": bool(self.success), "score": round(float(self.score), 4), "reason": self.reason,
                "judge": self.judge}


@runtime_checkable
class Judge(Protocol):
    """Judges one motion of the mover relative to the anchor.

    ``mover`` is (T,3) ``[x, y, yaw]`` in metres, ``anchor`` (T,3) or one pose (3,), blocks of side
    ``size``; frames dense enough that the mover turns less than half a turn around the anchor between
    two of them. ``final_progress`` is the action's learned progress at the end when the caller already
    has it (a judge that needs it and is not given it computes it). ``name`` is what verdicts report as
    their ``judge`` ("rules", "progress-model", or a plugin's own).

    Two more keywords exist for actions that declare them (:mod:`l2p_bullet.core.frames`) and are passed
    **only** to those actions' judges, so a judge written for one-anchor relative actions, with exactly
    the signature above, keeps working:

    - ``anchors``: a two-anchor action's every reference object, a list of (T,3) tracks or (3,) poses,
      the first being ``anchor`` ("between B and C": ``[B, C]``);
    - ``viewer``: a viewer-frame action's viewpoint (2,) in the same metric frame (the robot's base in
      the scene frame for ``frame = "viewer"``).

    A third, ``outlines``, is passed only to a judge that sets ``reads_outlines = True`` (the rule and the
    progress-model judges), and only where an object the verdict reads is not a cube: each object's real
    footprint (K,2) in metres in its own frame, the mover's first, then every anchor's
    (``judge/footprints.py``).
    """

    name: str

    def judge(self, mover: np.ndarray, anchor: np.ndarray, size: float, *,
              final_progress: float | None = None, **context: Any) -> Verdict: ...


def judge_context(anchors: list[np.ndarray], viewer: np.ndarray | None, *, judge: Any = None,
                  outlines: list[np.ndarray] | None = None) -> dict[str, Any]:
    """The keywords a judge gets besides mover, anchor and size: ``anchors`` (every reference object's
    poses) only for a two-anchor action and ``viewer`` only for a viewer-frame one, so a plugin's judge
    written for one-anchor relative actions keeps working unchanged; ``outlines`` (``footprints.outlines_of``:
    None where every object is a cube) only to a ``judge`` that reads them (:class:`Judge`)."""
    kw: dict[str, Any] = {}
    if len(anchors) > 1:
        kw["anchors"] = anchors
    if viewer is not None:
        kw["viewer"] = np.asarray(viewer, float)
    if outlines is not None and getattr(judge, "reads_outlines", False):
        kw["outlines"] = outlines
    return kw


def plan_verdict(judge: Judge, plan: Any, path: np.ndarray | None = None, *, final_progress: float | None = None,
                 outlines: list[np.ndarray] | None = None) -> dict[str, Any]:
    """``judge``'s verdict (as a dict) on ``path`` (default: the plan's own) with the plan's anchors, block size
    and viewpoint (a :class:`~l2p_bullet.core.contracts.Plan`), and the objects' real ``outlines`` (None for
    cubes): how ``perform`` and a chain's forecast judge a plan before anything moves."""
    poses = [plan.anchor_pose, *([] if plan.more_anchor_poses is None else list(plan.more_anchor_poses))]
    return judge.judge(plan.path if path is None else path, plan.anchor_pose, plan.size,
                       final_progress=final_progress,
                       **judge_context(poses, plan.viewer, judge=judge, outlines=outlines)).to_dict()

