"""The numpy forward pass perform uses gives the torch model's numbers (to float32 rounding)."""

from __future__ import annotations

import numpy as np
import pytest

torch = pytest.importorskip("torch")

from l2p_bullet.learning.progress_net import ProgressModel, ProgressNet, ensemble_state  # noqa: E402
from l2p_bullet.progress.config import ModelConfig  # noqa: E402
from l2p_bullet.progress.features import QSRConfig  # noqa: E402
from l2p_bullet.progress.model import NumpyProgressModel  # noqa: E402


@pytest.fixture(scope="module")
def models():
    torch.manual_seed(0)
    qcfg = QSRConfig()
    mcfg = ModelConfig(n_features=qcfg.n_features, hidden=16, ensemble=3)
    nets = [ProgressNet(mcfg.n_features, mcfg.hidden) for _ in range(mcfg.ensemble)]
    for net in nets:  # larger weights than the init so that the gates saturate somewhere
        with torch.no_grad():
            for p in net.parameters():
                p.mul_(3.0)
    tensors = ensemble_state(nets)
    ref = ProgressModel(tensors, mcfg, qcfg)
    fast = NumpyProgressModel({k: v.numpy() for k, v in tensors.items()}, mcfg, qcfg)
    return ref, fast


def motions(seed: int, n: int):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        steps = rng.normal(0, 0.012, (int(rng.integers(2, 160)), 3))
        out.append(np.array([0.1, -0.05, 0.2]) + np.cumsum(steps, axis=0))
    return out


@pytest.mark.parametrize("seed", [0, 1])
def test_same_numbers_as_torch(models, seed):
    ref, fast = models
    movers = motions(seed, 24)
    anchor = np.array([0.0, 0.02, 0.4])
    np.testing.assert_allclose(fast.final_batch(movers, anchor, 0.05), ref.final_batch(movers, anchor, 0.05),
                               atol=2e-5)
    for a, b in zip(fast.curve_batch(movers, anchor, 0.05), ref.curve_batch(movers, anchor, 0.05), strict=True):
        assert a.shape == b.shape
        np.testing.assert_allclose(a, b, atol=2e-5)
    tracks = [np.repeat(anchor[None], len(m), axis=0) for m in movers[:3]]
    np.testing.assert_allclose(fast.curve(movers[0], tracks[0], 0.05), ref.curve(movers[0], tracks[0], 0.05),
                               atol=2e-5)


def test_resampled_curve_ends_at_the_final_and_its_ramp_spans_the_motion(models):
    """``resampled``: the model's own arc-length frames, their last value the motion's final progress, and
    each frame's share of the arc length rising from 0 to 1 (what recognition's tried ramp rules compare)."""
    _, fast = models
    anchor = np.array([0.0, 0.02, 0.4])
    for m in motions(2, 6):
        p, share = fast.resampled(m, anchor, 0.05)
        assert p.shape == share.shape and len(p) >= 1
        assert p[-1] == pytest.approx(fast.final(m, anchor, 0.05), abs=1e-9)
        assert share[0] == 0.0 and share[-1] == pytest.approx(1.0) and np.all(np.diff(share) >= 0)


def test_shared_prefix_batch_matches(models):
    """A planner's batch: every candidate extends the same path (the prefix runs once, at batch size 1)."""
    ref, fast = models
    base = motions(5, 1)[0][:80]
    rng = np.random.default_rng(3)
    movers = [np.vstack([base, base[-1] + np.cumsum(rng.normal(0, 0.01, (int(rng.integers(2, 30)), 3)), 0)])
              for _ in range(16)]
    anchor = np.array([0.0, 0.0, 0.0])
    np.testing.assert_allclose(fast.final_batch(movers, anchor, 0.05), ref.final_batch(movers, anchor, 0.05),
                               atol=2e-5)


def test_ordinal_head_same_numbers_as_torch_and_in_the_manifest():
    """An ordinal read-out (issue 25): the numpy twin reads its thresholds; the manifest names the levels,
    and a manifest without them is the plain sigmoid head of the shipped bundles."""
    torch.manual_seed(1)
    qcfg = QSRConfig()
    mcfg = ModelConfig(n_features=qcfg.n_features, hidden=8, ensemble=2, levels=4)
    nets = [ProgressNet(mcfg.n_features, mcfg.hidden, mcfg.levels) for _ in range(2)]
    with torch.no_grad():
        for net in nets:
            net.head.cuts.copy_(torch.tensor([-1.0, 0.5, 2.0]))
            net.head.bias.fill_(1.5)
    tensors = ensemble_state(nets)
    assert tensors["m0.head.cuts"].shape == (3,)
    ref = ProgressModel(tensors, mcfg, qcfg)
    fast = NumpyProgressModel({k: v.numpy() for k, v in tensors.items()}, mcfg, qcfg)
    movers, anchor = motions(7, 10), np.array([0.0, 0.02, 0.4])
    got, want = fast.final_batch(movers, anchor, 0.05), ref.final_batch(movers, anchor, 0.05)
    np.testing.assert_allclose(got, want, atol=2e-5)
    assert np.ptp(got) > 0.01  # the thresholds matter: not a constant
    assert ModelConfig.from_dict(mcfg.to_dict()) == mcfg
    plain = ModelConfig(n_features=qcfg.n_features)
    assert "levels" not in plain.to_dict() and ModelConfig.from_dict(plain.to_dict()).levels == 1
