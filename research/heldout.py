"""Held-out tests of progress models on demonstrations: session split and discrimination.

The three learning modules that measure a model each answer one question:

- ``heldout`` (here): does a model trained on one person's demonstrations score the other person's
  right (per-frame error, final progress), and stay low on the other actions'?
- ``agreement``: does a judge's score or a model's final progress rank the graded motions the way people
  graded them (Spearman, no training)?
- ``agreement_cv``: the same agreement for models *trained on grades*, cross-validated over the graded
  motions so that no motion is scored by a model that saw its grade.

Here:

- **Session split**: models are trained on one person's capture session (all actions) and tested on the
  other person's, never on overlapping windows of the same demonstrations.
- **Discrimination**: an action's model must stay low on the other actions' held-out demonstrations,
  because the planner maximises it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from l2p_bullet.core.vocabulary import ACTIONS
from l2p_bullet.data.demos import Demo
from l2p_bullet.learning.augment import smooth_poses
from l2p_bullet.learning.progress_net import ProgressModel
from l2p_bullet.learning.trainset import DataConfig, demo_sequence
from l2p_bullet.progress.features import QSRConfig


def demo_targets(d: Demo, model: ProgressModel, smooth_frames: int = 9) -> tuple[float, float]:
    """(final progress at the event's end, with the pre-event context), and the event-only final."""
    m, a = smooth_poses(d.mover, smooth_frames), smooth_poses(d.anchor, smooth_frames)
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
    # lazy: these modules import torch; only when a network is trained
    from l2p_bullet.learning.train_progress import all_demos, train_action

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
