"""Progress model: labels, batching, prefix sharing, training, and the shipped models' behaviour."""

from __future__ import annotations

import numpy as np
import pytest
import torch

from l2p_bullet.core.vocabulary import ACTIONS
from l2p_bullet.data.demos import load_demos
from l2p_bullet.learning.progress_net import ProgressModel, ProgressNet
from l2p_bullet.learning.train_progress import ProgressTrainConfig, train_net
from l2p_bullet.learning.trainset import DataConfig, demo_sequence, violates
from l2p_bullet.plugins.bundle import builtin_bundle_dir, load_bundle
from l2p_bullet.progress.config import ModelConfig
from l2p_bullet.progress.features import QSRConfig


@pytest.fixture(scope="module")
def models() -> dict[str, ProgressModel]:
    return {a: ProgressModel.from_bundle(load_bundle(builtin_bundle_dir(a))) for a in ACTIONS}


def _line(p0, p1, n=40):
    return np.linspace(np.r_[p0, 0.0], np.r_[p1, 0.0], n)


def _circle(radius=2.5, turns=1.0, n=120):
    a = np.linspace(0, 2 * np.pi * turns, n)
    return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.zeros(n)])


def _tiny_model(seed=0, ensemble=2, hidden=8) -> ProgressModel:
    torch.manual_seed(seed)
    q = QSRConfig()
    nets = [ProgressNet(q.n_features, hidden) for _ in range(ensemble)]
    return ProgressModel.from_nets(nets, ModelConfig(q.n_features, hidden, ensemble), q)


def test_demo_labels_are_zero_before_and_rise_linearly_to_one_at_the_end():
    # the first demonstration whose block is moved on by over a block after the event (the reset)
    d = next(d for d in load_demos("closer")
             if np.linalg.norm(np.diff(d.mover[d.end:, :2], axis=0), axis=1).sum() > 1.5 * d.size)
    seq = demo_sequence(d, QSRConfig(), DataConfig())
    y = seq.y
    assert y[0] == 0.0 and np.isclose(y[seq.end], 1.0, atol=0.05)
    rising = y[: seq.end + 1][(y[: seq.end + 1] > 0) & (y[: seq.end + 1] < 1)]
    assert len(rising) > 5 and np.all(np.diff(rising) > 0)
    steps = np.diff(rising)
    assert steps.max() - steps.min() < 0.02  # linear in arc length (equal steps)
    after = y[seq.end:]
    assert len(after) > 1 and np.all(np.diff(after) <= 0) and after[-1] < 1.0  # the reset decays


def test_batch_scoring_matches_one_by_one_and_prefix_sharing_is_exact():
    model = _tiny_model()
    rng = np.random.default_rng(1)
    base = _line((4, 0), (2, 1), 30)
    movers = [np.concatenate([base, base[-1] + np.linspace(0, 1, 5)[:, None] * np.r_[rng.normal(0, 1, 2), 0]])
              for _ in range(6)] + [_circle(n=17)]
    batch = model.final_batch(movers, np.zeros(3), 1.0)
    single = np.array([model.final(m, np.zeros(3), 1.0) for m in movers])
    np.testing.assert_allclose(batch, single, atol=1e-5)
    curves = model.curve_batch(movers, np.zeros(3), 1.0)
    assert [len(c) for c in curves] == [len(m) for m in movers]
    assert np.allclose([c[-1] for c in curves], batch, atol=1e-6)
    assert np.all((batch >= 0) & (batch <= 1))
    assert model.final_batch([], np.zeros(3), 1.0).shape == (0,)


def test_anchor_may_be_a_track_per_motion():
    model = _tiny_model()
    m = _line((4, 0), (2, 0))
    track = np.zeros((len(m), 3))
    assert np.isclose(model.final(m, track, 1.0), model.final(m, np.zeros(3), 1.0), atol=1e-6)
    assert len(model.curve(m, track, 1.0)) == len(m)


def test_training_is_deterministic_and_learns():
    """Approaching lines labelled as rising progress, receding lines as 0: a tiny net must fit them."""
    q = QSRConfig()
    rng = np.random.default_rng(0)
    from l2p_bullet.learning.trainset import TrainingSequence
    from l2p_bullet.progress.features import features, resample

    seqs = []
    for i in range(8):
        r0, r1 = (6.0, 2.0) if i % 2 else (2.0, 6.0)
        b = rng.uniform(-np.pi, np.pi)
        m = _line((r0 * np.cos(b), r0 * np.sin(b)), (r1 * np.cos(b + 0.3), r1 * np.sin(b + 0.3)), 20)
        rs = resample(m, np.zeros(3), 1.0, q)
        x = features(rs.mover, rs.anchor, q)
        y = np.linspace(0, 1, len(x)).astype(np.float32) if i % 2 else np.zeros(len(x), np.float32)
        seqs.append(TrainingSequence(x, y, positive=bool(i % 2), end=len(x) - 1))
    cfg = ProgressTrainConfig(hidden=8, ensemble=1, epochs=30, batch=8, lr=0.03)
    n1, h1 = train_net(seqs, q.n_features, cfg, seed=5)
    n2, h2 = train_net(seqs, q.n_features, cfg, seed=5)
    assert h1 == h2
    assert all(torch.equal(a, b) for a, b in zip(n1.state_dict().values(), n2.state_dict().values(), strict=True))
    assert h1[-1] < 0.3 * h1[0]


def test_random_negatives_only_reject_clear_non_instances():
    a = np.zeros((40, 3))
    toward, away = _line((6, 0), (2, 0)), _line((2, 0), (6, 0))
    assert violates("closer", away, a) and not violates("closer", toward, a)
    assert violates("away", toward, a) and not violates("away", away, a)
    assert violates("next-to", away, a) and not violates("next-to", _line((6, 0), (1.1, 0)), a)
    radial = _line((2, 0), (7, 0))
    assert violates("around", radial, a) and not violates("around", _circle(n=40)[:20], a[:20])
    assert violates("past", _circle(n=40), a)  # a full turn is around, not past


# ---- the shipped bundles behave as the planner needs (loose bounds: a guard, not a benchmark) ----

def test_standing_still_earns_no_progress(models):
    still = np.repeat([[3.0, 0.0, 0.2]], 30, axis=0)
    for a, m in models.items():
        assert m.final(still, np.zeros(3), 1.0) < 0.15, a


def test_each_model_prefers_its_own_action(models):
    anchor = np.zeros(3)
    motions = {
        "closer": _line((6, 0), (2.2, 0.3)),
        "away": _line((2, 0), (6.5, 0.5)),
        "next-to": _line((5, 0.2), (1.05, 0.0)),
        "past": np.column_stack([np.full(40, -2.0), np.linspace(-4, 4, 40), np.zeros(40)]),
        "around": _circle(2.5, 1.0),
    }
    scores = {a: m.final_batch(list(motions.values()), anchor, 1.0) for a, m in models.items()}
    names = list(motions)
    for a in ("closer", "away", "past", "around"):
        own = scores[a][names.index(a)]
        assert own > 0.4, (a, scores[a])
        others = [scores[a][i] for i, b in enumerate(names) if b != a and {a, b} != {"closer", "next-to"}]
        assert own > max(others), (a, scores[a])


def test_approach_copies_start_farther_back_and_pass_as_near():
    from l2p_bullet.learning.augment import approach as _approach

    m = _line((-3, 2), (3, 2), 30)
    a = _approach(m, 2.5)
    assert np.allclose(a[-len(m):], m) and np.allclose(a[0, :2], (-5.5, 2.0))
    assert np.isclose(np.abs(a[:, 1] - 2).max(), 0)  # along the first direction: the pass is unchanged


def test_past_only_copies_leave_the_other_actions_training_sets_alone():
    from dataclasses import replace

    from l2p_bullet.learning.train_progress import all_demos
    from l2p_bullet.learning.trainset import build

    demos = {a: ds[:2] for a, ds in all_demos().items()}
    q = QSRConfig()
    plain = replace(DataConfig(), approach={}, scale_ranges={k: v for k, v in DataConfig().scale_ranges.items()
                                                             if k != "past"}, random_negatives=5, static_negatives=2)
    new = replace(plain, approach=DataConfig().approach, scale_ranges=DataConfig().scale_ranges)
    a, b = build("away", demos, q, plain), build("away", demos, q, new)
    assert len(a) == len(b) and all(
        np.array_equal(x.x, y.x) and np.array_equal(x.y, y.y) for x, y in zip(a, b, strict=True)
    )
    assert len(build("past", demos, q, new)) > len(build("past", demos, q, plain))
