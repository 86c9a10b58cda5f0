"""How feedback becomes training: targets, sequences, weights, and grades from a rule judge.

A graded motion (:class:`~l2p_bullet.learning.feedback.FeedbackItem`) becomes sequences labelled like a
demonstration cropped to its event, rising to the graded target instead of 1 (:func:`feedback_sequences`);
blind labels that mostly name another action make it a negative. :func:`judge_items` produces graded
motions without people: the model's own plans, graded by a judge (the original's automatic feedback).
Torch-free; the fine-tuning is :func:`l2p_bullet.learning.train_progress.fine_tune`.
"""

from __future__ import annotations

import zlib
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..actions import BUILTIN
from ..core.scene import random_scene
from ..planning import plan
from ..planning.world2d import interpolate
from ..progress.features import QSRConfig
from .feedback import GRADE_MAX, FeedbackItem
from .trainset import DataConfig, TrainingSequence, _labelled, mirror


@dataclass(frozen=True)
class FeedbackConfig:
    """How feedback becomes training and fine-tuning (written to the manifest's ``[training.feedback]``).
    How each value was chosen, and on what data, is in docs/learning.md ("Feedback")."""

    target: str = "grade"
    """"grade": end target = mean grade / 10; "clear": the original's cold feedback (only clear cases, 0 or 1)."""
    clear: dict = field(default_factory=lambda: {"default": (3.5, 7.0), **{
        a: s.training.clear_grades for a, s in BUILTIN.items() if s.training.clear_grades is not None}})
    """"clear" targets: mean grade <= low -> 0, >= high -> 1, the rest unused (the original's thresholds; an
    action's own, ``ActionSpec.training.clear_grades``, where it declares them: away, around)."""
    weight: float = 0.3
    """Total weight of the feedback sequences relative to the demonstrations' positives."""
    epochs: int = 10
    """Fine-tuning epochs after the 30 on the demonstrations (the original fine-tuned 10)."""
    lr: float = 0.003
    """Adam learning rate of the fine-tuning (cosine decay to 0): a third of the training's."""
    demo_fraction: float = 0.3
    """Share of the demonstration batches replayed in each fine-tuning epoch (0: feedback only), so the
    model does not forget what the demonstrations taught while it learns the grades."""
    blind_majority: float = 0.5
    """A motion is a negative of its action when more than this share of blind labels named something else."""
    copies: int = 4
    """Perturbed copies per graded motion (and per mirror image), same target: a dozen graded motions per
    action are learnt by heart otherwise, and a grade does not hinge on a fifth of a block."""
    jitter: float = 0.2
    """Standard deviation (blocks) of the copies' smooth displacement (4 control points along the path)."""
    stretch: float = 0.1
    """The copies are also stretched about the anchor by a factor within 1 +- this."""

    def to_dict(self) -> dict:
        return {"target": self.target, "clear": {k: list(v) for k, v in self.clear.items()}, "weight": self.weight,
                "epochs": self.epochs, "lr": self.lr, "demo_fraction": self.demo_fraction,
                "blind_majority": self.blind_majority, "copies": self.copies, "jitter": self.jitter,
                "stretch": self.stretch}


def target_of(item: FeedbackItem, cfg: FeedbackConfig) -> float | None:
    """The progress a graded motion should end at, or None when the item gives no graded target."""
    g = item.grade
    if g is None:
        return None
    if cfg.target == "grade":
        return float(np.clip(g / GRADE_MAX, 0.0, 1.0))
    if cfg.target == "clear":
        lo, hi = cfg.clear.get(item.action, cfg.clear["default"])
        return 0.0 if g <= lo else 1.0 if g >= hi else None
    raise ValueError(f'unknown feedback target "{cfg.target}"')


def is_blind_negative(item: FeedbackItem, cfg: FeedbackConfig) -> bool:
    """Blind reviewers mostly took the motion for another action (or for none)."""
    if not item.labels:
        return False
    other = sum(lab != item.action for lab in item.labels) / len(item.labels)
    return other > cfg.blind_majority


def feedback_sequences(action: str, items: Sequence[FeedbackItem], qcfg: QSRConfig, dcfg: DataConfig,
                       cfg: FeedbackConfig) -> list[TrainingSequence]:
    """Training sequences from the items performed for ``action``, each also mirrored (left/right does not
    change an action). A graded motion is labelled like a demonstration cropped to its event (a graded
    motion is the event, without context): progress rises linearly with arc length, here to the graded
    target instead of 1. A blind negative is labelled like the demonstrations' negatives (0, penalised on
    the last part of its motion). Weights are set by the caller (:func:`weigh`)."""
    out = []
    for it in items:
        if it.action != action:
            continue
        t = target_of(it, cfg)
        blind_neg = is_blind_negative(it, cfg)
        rng = np.random.default_rng(zlib.crc32(it.id.encode()))
        for mm, aa in ((it.mover, it.anchor), (mirror(it.mover), mirror(it.anchor))):
            if t is not None:
                for k in range(1 + cfg.copies):
                    m = mm if k == 0 else _perturbed(mm, aa, it.size, rng, cfg)
                    s = _labelled(m, aa, it.size, 0, len(m) - 1, qcfg, dcfg, True)
                    s.y = (s.y * t).astype(np.float32)
                    s.positive = False  # not a demonstration: n_positive keeps counting those
                    out.append(s)
            if blind_neg:
                out.append(_labelled(mm, aa, it.size, 0, 0, qcfg, dcfg, False))
    return out


def _perturbed(mover: np.ndarray, anchor: np.ndarray, size: float, rng: np.random.Generator,
               cfg: FeedbackConfig) -> np.ndarray:
    """The motion stretched about the anchor by 1 +- ``cfg.stretch`` and displaced smoothly: offsets of
    ``cfg.jitter`` blocks drawn at 4 points along its arc length, interpolated in between."""
    step = np.linalg.norm(np.diff(mover[:, :2], axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(step)]) / max(float(step.sum()), 1e-9)
    ctrl = rng.normal(0.0, cfg.jitter * size, (4, 2))
    knots = np.linspace(0.0, 1.0, 4)
    offset = np.column_stack([np.interp(arc, knots, ctrl[:, j]) for j in range(2)])
    out = mover.copy()
    c = anchor[:, :2]
    out[:, :2] = c + (mover[:, :2] - c) * rng.uniform(1 - cfg.stretch, 1 + cfg.stretch) + offset
    return out


def weigh(demo_seqs: Sequence[TrainingSequence], fb_seqs: Sequence[TrainingSequence], weight: float) -> None:
    """Give the feedback sequences together ``weight`` times the total weight of the demonstrations' positives."""
    n_pos = sum(s.weight for s in demo_seqs if s.positive) or 1.0
    if fb_seqs:
        w = weight * n_pos / len(fb_seqs)
        for s in fb_seqs:
            s.weight = w


@dataclass
class _ModelOnly:
    """What the planner needs of a bundle, for a progress model that is not in one yet (no policy)."""

    name: str
    model: object
    manifest: dict = field(default_factory=dict)

    def progress_model(self):
        return self.model

    def policy_arrays(self):
        return None


def judge_items(action: str, model, seeds: Sequence[int], judge, budgets: Sequence[int] = (40, 6, 2),
                log=None) -> list[FeedbackItem]:
    """Automatic feedback: plan ``action`` with ``model`` (a progress model) on ``random_scene(seed)`` for
    each seed and grade each plan 10 x the judge's score.

    The planner is random search with back-up (the paper's baseline, no policy needed), stopped after
    each of ``budgets`` steps: its default budget, then a few steps only, so the judge also sees partial
    and poor motions (plans that finish are nearly all good; grading only those would teach little).
    Planning with the model being trained, not an installed bundle, keeps ``make bundles`` reproducible.
    """

    holder = _ModelOnly(action, model)
    out = []
    for i, seed in enumerate(seeds):
        scene = random_scene(seed)
        for b in budgets:
            p = plan(scene, "A", "B", holder, seed=seed, planner="greedy", budget=b)
            mover = interpolate(np.asarray(p.path, float), step=0.25 * p.size)
            anchor = np.repeat(np.asarray(p.anchor_pose, float)[None], len(mover), axis=0)
            v = judge.judge(mover, anchor, p.size)
            out.append(FeedbackItem(f"rules/{action}/{seed}/{b}", action, mover, anchor, p.size,
                                    [GRADE_MAX * float(v.score)], [], "rules"))
        if log and (i + 1) % 10 == 0:
            log(f"graded plans of {i + 1}/{len(seeds)} scenes with the {judge.name} judge")
    return out
