"""Cross-validated agreement with people (``agreement`` measured for models trained on grades;
``heldout`` tests models on held-out demonstrations): is a model trained on some grades right about others?

The shipped graded motions are only 15 per folder, so agreement after training on grades is measured
by k-fold cross-validation: the folds are stratified by folder (each fold holds 15/k motions of every
folder, drawn with a fixed seed), a model is trained for each fold on the grades of the other folds,
and scores the held-out fold's motions by its final progress. Spearman's rank correlation with the mean
grade is then taken per folder over the pooled held-out predictions (each one from a model that never
saw that motion's grades), and averaged over the six folders.

Settings (how much the grades weigh, ...) are never chosen on the folds that are reported: with more
than one candidate, each outer fold picks its own by an inner cross-validation over its training
motions only (:func:`select`), and the report lists what each fold picked.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from l2p_bullet.learning.feedback import FeedbackItem, folder_agreement, score_items
from l2p_bullet.learning.feedback_targets import FeedbackConfig, feedback_sequences, weigh
from l2p_bullet.learning.trainset import DataConfig, build
from l2p_bullet.progress.config import ModelConfig
from l2p_bullet.progress.features import QSRConfig

Trainer = Callable[[str, list[FeedbackItem], dict], Any]
"""(action, training items of every action, setting) -> a model with ``final_batch``."""


def stratified_folds(items: Sequence[FeedbackItem], k: int, seed: int) -> dict[str, int]:
    """Fold index per item id: within each folder a seeded permutation dealt round-robin into ``k`` folds."""
    rng = np.random.default_rng(seed)
    out: dict[str, int] = {}
    for folder in sorted({it.folder for it in items}):
        ids = [it.id for it in items if it.folder == folder]
        for j, i in enumerate(rng.permutation(len(ids))):
            out[ids[i]] = j % k
    return out


@dataclass
class CVReport:
    """Held-out predictions, agreement per folder, and what each outer fold chose (with its inner scores)."""

    finals: dict[str, float] = field(default_factory=dict)
    spearman: dict[str, float] = field(default_factory=dict)
    choices: list[dict] = field(default_factory=list)

    @property
    def mean(self) -> float:
        return float(np.mean(list(self.spearman.values()))) if self.spearman else float("nan")


def cross_validate(trainer: Trainer, items: Sequence[FeedbackItem], *, k: int = 5, seed: int = 0,
                   grid: Sequence[dict] = ({},), inner_k: int = 3,
                   log: Callable[[str], None] | None = None) -> CVReport:
    """k-fold cross-validation of ``trainer`` over graded ``items`` (see the module docstring).

    Each outer fold f trains, per action, on the items outside f with the setting its inner CV chose
    (the only one when ``grid`` has one), and predicts the items in f.
    """
    items = list(items)
    folds = stratified_folds(items, k, seed)
    rep = CVReport()
    for f in range(k):
        train = [it for it in items if folds[it.id] != f]
        test = [it for it in items if folds[it.id] == f]
        if len(grid) > 1:
            setting, scores = select(trainer, train, grid, inner_k, seed + 1 + f, log)
            rep.choices.append({"fold": f, "setting": setting, "inner_mean": scores})
        else:
            setting = dict(grid[0])
        for action in sorted({it.action for it in test}):
            model = trainer(action, train, setting)
            rep.finals.update(score_items(model, [it for it in test if it.action == action]))
        if log:
            log(f"  fold {f + 1}/{k} done" + (f" (chose {setting})" if len(grid) > 1 else ""))
    rep.spearman = folder_agreement(items, rep.finals)
    return rep


def select(trainer: Trainer, items: Sequence[FeedbackItem], grid: Sequence[dict], k: int, seed: int,
           log: Callable[[str], None] | None = None) -> tuple[dict, list[float]]:
    """The setting of ``grid`` with the best mean folder agreement in a ``k``-fold CV over ``items`` only
    (ties: the first), and every setting's inner mean."""
    scores = []
    for setting in grid:
        scores.append(cross_validate(trainer, items, k=k, seed=seed, grid=(setting,)).mean)
        if log:
            log(f"    inner CV {setting}: mean {scores[-1]:.3f}")
    best = int(np.nanargmax(scores))
    return dict(grid[best]), [round(s, 4) for s in scores]


class FineTuner:
    """The trainer of ``l2p-bullet train --feedback``, made cheap to repeat: every action's ensemble is
    trained on the demonstrations once (or given, ``base``), then each call fine-tunes it on the given
    items' feedback with the call's setting (fields of :class:`FeedbackConfig`)."""

    def __init__(self, demos: dict, *, seed: int = 0, cfg=None, base: dict | None = None,
                 fcfg: FeedbackConfig | None = None, log: Callable[[str], None] | None = None):
        # lazy: these modules import torch; only when a network is trained
        from l2p_bullet.learning.train_progress import ProgressTrainConfig

        self.demos, self.seed, self.log = demos, seed, log
        self.cfg = cfg or ProgressTrainConfig()
        self.fcfg = fcfg or FeedbackConfig()
        self.qcfg, self.dcfg = QSRConfig(), DataConfig()
        self.base: dict = dict(base or {})
        self._seqs: dict[str, list] = {}

    def nets(self, action: str) -> list:
        """The ensemble trained on the demonstrations only (trained at the first call)."""
        if action not in self.base:
            # lazy: these modules import torch; only when a network is trained
            from l2p_bullet.learning.train_progress import train_action

            if self.log:
                self.log(f"  training {action} on the demonstrations ({self.cfg.ensemble} x {self.cfg.epochs} epochs)")
            self.base[action] = train_action(action, self.demos, seed=self.seed, cfg=self.cfg).model.nets
        return self.base[action]

    def seqs(self, action: str) -> list:
        if action not in self._seqs:
            self._seqs[action] = build(action, self.demos, self.qcfg, self.dcfg, seed=self.seed)
        return self._seqs[action]

    def __call__(self, action: str, items: list[FeedbackItem], setting: dict) -> Any:
        # lazy: these modules import torch; only when a network is trained
        from l2p_bullet.learning.progress_net import ProgressModel
        from l2p_bullet.learning.train_progress import fine_tune

        fcfg = dataclasses.replace(self.fcfg, **setting)
        nets = self.nets(action)
        fb = feedback_sequences(action, items, self.qcfg, self.dcfg, fcfg)
        if fb:
            weigh(self.seqs(action), fb, fcfg.weight)
            nets = fine_tune(nets, self.seqs(action), fb, fcfg, self.cfg, seed=self.seed)
        mcfg = ModelConfig(n_features=self.qcfg.n_features, hidden=self.cfg.hidden, ensemble=len(nets),
                           levels=self.cfg.levels)
        return ProgressModel.from_nets(nets, mcfg, self.qcfg)
