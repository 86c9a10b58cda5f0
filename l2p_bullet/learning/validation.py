"""Honest evaluation of progress models: session split, discrimination, agreement with people.

- **Session split**: models are trained on one person's capture session (all actions) and tested on the
  other person's, never on overlapping windows of the same demonstrations.
- **Discrimination**: an action's model must stay low on the other actions' held-out demonstrations,
  because the planner maximises it.
- **Agreement with people**: the graded 2-D demonstrations (evaluation only, never trained on) are turned
  into mover/anchor motions by sliding block 0 along each accepted straight move, and the model's final
  progress is rank-correlated (Spearman) with the mean of the two people's grades.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from ..judge.rules import spearman
from .demos import ACTIONS, Demo, canonical_action, load_graded_demos
from .progress_net import ProgressModel
from .trainset import smooth

GRADED_FOLDERS = {"SlideToward": "closer", "SlideAway": "away", "SlideNext": "next-to", "SlidePast": "past",
                  "SlideAround": "around", "SlideAroundDiscrete": "around"}


@dataclass
class GradedMotion:
    id: str
    folder: str
    action: str
    mover: np.ndarray  # (T, 3) metres
    anchor: np.ndarray  # (T, 3)
    grade: float  # mean of the two people's grades
    size: float = 0.15


def graded_motions(frames_per_move: int = 30) -> list[GradedMotion]:
    """The graded 2-D demonstrations as motions: block 0 slides along each accepted move, block 1 stays."""
    out = []
    for g in load_graded_demos():
        c0, c1 = g["start_config"]
        pose = np.array([c0["x"], c0["y"], c0["theta"]])
        pts = [pose[None]]
        for st in g["steps"]:
            if not st["accepted"] or st["object_index"] != 0:
                continue
            to = np.asarray(st["to"], float)
            pts.append(np.linspace(pose, to, frames_per_move + 1)[1:])
            pose = to
        mover = np.concatenate(pts)
        anchor = np.repeat(np.array([[c1["x"], c1["y"], c1["theta"]]]), len(mover), axis=0)
        grades = list(g["scores_txt"].values())
        out.append(GradedMotion(g["id"], g["folder"], GRADED_FOLDERS[g["folder"]], mover, anchor,
                                float(np.mean(grades)), float(c0["side"])))
    return out


def graded_agreement(models: dict[str, ProgressModel], motions: list[GradedMotion] | None = None) -> dict:
    """Spearman(final progress, mean grade) per graded folder, with the finals for the tables."""
    motions = motions if motions is not None else graded_motions()
    out = {}
    for folder in GRADED_FOLDERS:
        ms = [m for m in motions if m.folder == folder]
        model = models[canonical_action(GRADED_FOLDERS[folder])]
        finals = model.final_batch([m.mover for m in ms], [m.anchor for m in ms], ms[0].size)
        grades = np.array([m.grade for m in ms])
        out[folder] = {"spearman": spearman(finals, grades), "finals": finals, "grades": grades}
    return out


def demo_targets(d: Demo, model: ProgressModel, smooth_frames: int = 9) -> tuple[float, float]:
    """(final progress at the event's end, with the pre-event context), and the event-only final."""
    m, a = smooth(d.mover, smooth_frames), smooth(d.anchor, smooth_frames)
    with_ctx = model.final(m[: d.end + 1], a[: d.end + 1], d.size)
    ev = model.final(m[d.start : d.end + 1], a[d.start : d.end + 1], d.size)
    return with_ctx, ev


@dataclass
class SplitReport:
    """Session-split results, averaged over the two folds (train on one person, test on the other).

    ``matrix[i, j]``: mean final progress of action i's model on action j's held-out demonstrations
    (cut at the event's end, with the context before it); the diagonal is ``final_same``.
    """

    mse: dict[str, float] = field(default_factory=dict)
    final_same: dict[str, float] = field(default_factory=dict)
    final_event_only: dict[str, float] = field(default_factory=dict)
    matrix: np.ndarray = field(default_factory=lambda: np.zeros((len(ACTIONS), len(ACTIONS))))
    seconds: dict[str, float] = field(default_factory=dict)
    folds: list[tuple[str, str]] = field(default_factory=list)


FOLDS: list[tuple[str, str]] = [("Session1", "Session2"), ("Session2", "Session1")]
"""(train, test) sessions: the two people. SlideToward's extra Session3 is left out of this split."""


def session_split(train_cfg=None, data_cfg=None, qsr_cfg=None, seed: int = 0,
                  on_model: Callable[[str, str, float], None] | None = None) -> SplitReport:
    """Train every action on one session and test on the other, both ways (10 trainings)."""
    from ..progress.features import QSRConfig
    from .train_progress import all_demos, train_action
    from .trainset import DataConfig, demo_sequence

    q, dc = qsr_cfg or QSRConfig(), data_cfg or DataConfig()
    rep = SplitReport(folds=list(FOLDS))
    acc: dict[str, list] = {a: [] for a in ACTIONS}
    for train_s, test_s in FOLDS:
        dtr, dte = all_demos(sessions={train_s}), all_demos(sessions={test_s})
        for a in ACTIONS:
            r = train_action(a, dtr, seed=seed, qsr_cfg=q, data_cfg=dc, cfg=train_cfg)
            mse = held_out_mse(r.model, dte[a], lambda d: demo_sequence(d, q, dc))
            row = [float(np.mean([demo_targets(d, r.model, dc.smooth_frames)[0] for d in dte[b]])) for b in ACTIONS]
            ev = float(np.mean([demo_targets(d, r.model, dc.smooth_frames)[1] for d in dte[a]]))
            acc[a].append((mse, row, ev, r.seconds))
            if on_model:
                on_model(a, train_s, r.seconds)
    for i, a in enumerate(ACTIONS):
        rep.mse[a] = float(np.mean([x[0] for x in acc[a]]))
        rep.matrix[i] = np.mean([x[1] for x in acc[a]], axis=0)
        rep.final_same[a] = float(rep.matrix[i, i])
        rep.final_event_only[a] = float(np.mean([x[2] for x in acc[a]]))
        rep.seconds[a] = float(np.mean([x[3] for x in acc[a]]))
    return rep


def held_out_mse(model: ProgressModel, demos: list[Demo], label_fn: Callable) -> float:
    """Per-frame squared error on held-out demonstrations (whole context, resampled frames)."""
    errs = []
    for d in demos:
        seq = label_fn(d)
        p = model.forward_features(seq.x[None])[0]
        errs.append(np.mean((p - seq.y) ** 2))
    return float(np.mean(errs))
