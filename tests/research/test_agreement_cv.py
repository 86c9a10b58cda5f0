"""Cross-validated agreement with people (research/agreement_cv.py): stratified folds, and a model never
scored on the grades it was trained on."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.learning.feedback import folder_agreement, original_items
from research.agreement_cv import cross_validate, select, stratified_folds


def test_folds_are_stratified_by_folder_and_seeded():
    items = original_items()
    f = stratified_folds(items, 5, seed=0)
    for folder in {it.folder for it in items}:
        counts = np.bincount([f[it.id] for it in items if it.folder == folder], minlength=5)
        assert counts.tolist() == [3] * 5
    assert f == stratified_folds(items, 5, seed=0) and f != stratified_folds(items, 5, seed=1)


class _Peeking:
    """A trainer that records which items it was given: cross-validation must never give it the motions
    it is then scored on."""

    def __init__(self):
        self.seen: list[set[str]] = []

    def __call__(self, action, items, setting):
        self.seen.append({it.id for it in items})

        class Model:
            def final_batch(self, movers, anchors, size):
                return np.arange(len(movers), dtype=float)

        return Model()


def test_cross_validation_never_scores_a_motion_with_its_own_grades():
    items = [it for it in original_items() if it.action in ("past", "closer")]
    trainer = _Peeking()
    rep = cross_validate(trainer, items, k=3, seed=0)
    folds = stratified_folds(items, 3, 0)
    assert len(rep.finals) == len(items)
    assert len(trainer.seen) == 3 * 2  # 3 folds x 2 actions, in order: the loop below checks every training
    for i, seen in enumerate(trainer.seen):
        assert seen and not any(folds[x] == i // 2 for x in seen)
    assert set(rep.spearman) == {"SlideToward", "SlidePast"}


def test_select_chooses_by_the_inner_folds_only():
    items = [it for it in original_items() if it.folder == "SlidePast"]

    def trainer(action, train, setting):
        class Model:  # setting "good" ranks by the true grade, "bad" against it
            def final_batch(self, movers, anchors, size):
                g = [next(it.grade for it in items if it.mover is m) for m in movers]
                return np.asarray(g) * (1 if setting["kind"] == "good" else -1)
        return Model()

    best, scores = select(trainer, items, [{"kind": "bad"}, {"kind": "good"}], k=3, seed=0)
    assert best == {"kind": "good"} and scores[1] > scores[0]
    rep = cross_validate(trainer, items, k=3, grid=[{"kind": "bad"}, {"kind": "good"}])
    assert all(c["setting"] == {"kind": "good"} for c in rep.choices) and rep.spearman["SlidePast"] == pytest.approx(
        1.0
    )
    assert folder_agreement(items, {it.id: it.grade for it in items}) == {"SlidePast": pytest.approx(1.0)}
