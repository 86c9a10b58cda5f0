"""The grade-free validation suite (research/generalise.py): scores, contained pairs and exploit probes."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.core.geometry import swept_angle
from l2p_bullet.core.vocabulary import ACTIONS
from l2p_bullet.learning.train_progress import all_demos
from l2p_bullet.learning.trainset import DataConfig
from research import generalise as g


@pytest.fixture(scope="module")
def held_out() -> dict[str, list[g.Event]]:
    return {a: g.events(ds) for a, ds in all_demos(sessions={"Session2"}).items()}


def test_contained_pairs_are_the_pairs_left_out_of_the_negatives():
    neg = DataConfig().negatives
    for a in ACTIONS:
        assert set(g.CONTAINED.get(a, ())) == {b for b in ACTIONS if b != a and b not in neg[a]}


def test_probes_are_what_they_say(held_out):
    c = held_out["closer"][0]
    p = g.probe(c)
    r = np.hypot(*(p[:, :2] - c.anchor[:2]).T) / c.size
    assert r.max() == pytest.approx(r[0] + 3, abs=1e-6) and r[-1] == pytest.approx(r[0], abs=1e-6)
    a = held_out["around"][0]
    half = abs(swept_angle(g.probe(a), a.anchor))
    assert 0.3 * abs(swept_angle(a.mover, a.anchor)) < half < 0.7 * abs(swept_angle(a.mover, a.anchor))
    ps = held_out["past"][0]
    end = np.hypot(*(g.probe(ps)[-1, :2] - ps.anchor[:2])) / ps.size
    assert end == pytest.approx(np.min(np.hypot(*(ps.mover[:, :2] - ps.anchor[:2]).T)) / ps.size, abs=1e-6)


def test_the_suite_separates_the_shipped_closer_model_from_its_probe(held_out):
    """Real model, real demonstrations: the shipped closer bundle (trained on both sessions, so in sample
    here) scores Session 2's events high, other actions low, and backing off and returning lower."""
    from l2p_bullet.learning.progress_net import ProgressModel
    from l2p_bullet.plugins.bundle import builtin_bundle_dir, load_bundle

    models = {a: ProgressModel.from_bundle(load_bundle(builtin_bundle_dir(a))) for a in ACTIONS}
    r = g.score_fold(models, held_out)
    assert r["closer"].full > 0.8 and r["closer"].off < 0.2 and r["closer"].probe < r["closer"].plain - 0.2
    assert r["closer"].partial[0] < r["closer"].partial[1] < r["closer"].partial[2] < r["closer"].full
    assert -1.0 < g.suite_score(r) < 1.0
