"""The optimisation of progress nets: one ensemble member trained from scratch (:func:`train_net`) and copies of
trained members fine-tuned on feedback while replaying demonstrations (:func:`fine_tune`), both on padded,
length-sorted batches, deterministic for a seed.

Apart from :mod:`.train_progress` (which builds the sets, calls these and writes bundles) because this is the
torch loop alone: what a member's loss is and how a step is taken, read and changed without the bundle's
bookkeeping around it.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence

import numpy as np
import torch

from ..core.threads import torch_threads
from .adam import Adam, CosineDecay
from .feedback_targets import FeedbackConfig
from .progress_net import ProgressNet
from .training_plan import ProgressTrainConfig
from .trainset import TrainingSequence


def _pad(seqs: list[TrainingSequence]) -> tuple[torch.Tensor, ...]:
    K = max(len(s.y) for s in seqs)
    F = seqs[0].x.shape[1]
    x = np.zeros((len(seqs), K, F), np.float32)
    y = np.zeros((len(seqs), K), np.float32)
    mask = np.zeros((len(seqs), K), np.float32)
    endw = np.zeros((len(seqs), K), np.float32)
    for i, s in enumerate(seqs):
        n = len(s.y)
        x[i, :n], y[i, :n] = s.x, s.y
        fw = np.ones(n, np.float32) if s.frame_w is None else s.frame_w
        mask[i, :n] = s.weight * fw / max(float(fw.sum()), 1.0)
        endw[i, s.end] = s.weight
    return tuple(torch.from_numpy(v) for v in (x, y, mask, endw))


def train_net(seqs: list[TrainingSequence], n_features: int, cfg: ProgressTrainConfig, seed: int,
              tick: Callable[[], None] | None = None) -> tuple[ProgressNet, list[float]]:
    """Train one ensemble member. Batches are length-sorted chunks (little padding), shuffled per epoch."""
    with torch_threads(cfg.threads):
        return _train_net(seqs, n_features, cfg, seed, tick)


def _batches(seqs: list[TrainingSequence], batch: int) -> list[tuple[torch.Tensor, ...]]:
    """Length-sorted chunks of ``batch`` sequences, padded (little padding per chunk)."""
    order = np.argsort([len(s.y) for s in seqs], kind="stable")
    return [_pad([seqs[j] for j in order[i : i + batch]]) for i in range(0, len(order), batch)]


def _step(net: ProgressNet, opt: Adam, batch: tuple[torch.Tensor, ...], total_w: float,
          times: float, end_weight: float) -> float:
    """One Adam step on a padded batch: its weighted error / ``total_w`` (the epoch's) x ``times``."""
    x, y, mask, endw = batch
    if net.head.levels > 1:  # ordinal: cross-entropy per threshold, averaged over the thresholds
        k = net.head.levels
        past = (y[..., None] > (2 * torch.arange(k) + 1) / (2 * k)).float()
        err = torch.nn.functional.binary_cross_entropy(net.level_probs(x).clamp(1e-6, 1 - 1e-6), past,
                                                       reduction="none").mean(-1)
    else:
        err = (net(x) - y) ** 2
    loss = ((err * mask).sum() + end_weight * (err * endw).sum()) / total_w * times
    opt.zero_grad()
    loss.backward()
    torch.nn.utils.clip_grad_norm_(net.parameters(), 1.0)
    opt.step()
    return float(loss.detach())


def _train_net(seqs: list[TrainingSequence], n_features: int, cfg: ProgressTrainConfig, seed: int,
               tick: Callable[[], None] | None) -> tuple[ProgressNet, list[float]]:
    torch.manual_seed(seed)
    rng = np.random.default_rng(seed)
    net = ProgressNet(n_features, cfg.hidden, cfg.levels)
    opt = (Adam(net.parameters(), lr=cfg.lr, weight_decay=cfg.weight_decay, decoupled=True) if cfg.weight_decay > 0
           else Adam(net.parameters(), lr=cfg.lr))
    sched = CosineDecay(opt, cfg.epochs)
    batches = _batches(seqs, cfg.batch)
    total_w = sum(s.weight for s in seqs)
    history = []
    for _ in range(cfg.epochs):
        ep = 0.0
        for b in rng.permutation(len(batches)):
            ep += _step(net, opt, batches[b], total_w, len(batches), cfg.end_weight) / len(batches)
        sched.step()
        history.append(ep)
        if tick:
            tick()
    net.eval()
    return net, history


def fine_tune(nets: Sequence[ProgressNet], demo_seqs: list[TrainingSequence], fb_seqs: list[TrainingSequence],
              fcfg: FeedbackConfig, cfg: ProgressTrainConfig, seed: int = 0,
              tick: Callable[[], None] | None = None) -> list[ProgressNet]:
    """Continue training copies of ``nets`` on the feedback sequences, replaying demonstrations.

    Each epoch takes every feedback batch and a random ``fcfg.demo_fraction`` of the demonstration
    batches (each scaled up by 1 / fraction, so the two keep the weights :func:`feedback_targets.weigh` gave
    them), shuffled; fresh Adam at ``fcfg.lr`` with cosine decay over ``fcfg.epochs``. Member ``i`` uses
    seed ``seed * 1000 + i``: deterministic for a seed. The inputs are left unchanged.
    """
    with torch_threads(cfg.threads):
        demo_b = _batches(demo_seqs, cfg.batch) if demo_seqs and fcfg.demo_fraction > 0 else []
        fb_b = _batches(fb_seqs, cfg.batch) if fb_seqs else []
        frac = fcfg.demo_fraction if demo_b else 0.0
        total_w = frac * sum(s.weight for s in demo_seqs) * (1 if demo_b else 0) + sum(s.weight for s in fb_seqs)
        n_demo = int(round(frac * len(demo_b)))
        out = []
        for i, base in enumerate(nets):
            torch.manual_seed(seed * 1000 + i)
            rng = np.random.default_rng(seed * 1000 + i)
            net = copy.deepcopy(base).train()
            opt = Adam(net.parameters(), lr=fcfg.lr)
            sched = CosineDecay(opt, max(fcfg.epochs, 1))
            for _ in range(fcfg.epochs):
                chosen = [(b, 1.0 / frac) for b in rng.choice(len(demo_b), n_demo, replace=False)] if n_demo else []
                plan = [(demo_b[b], s) for b, s in chosen] + [(b, 1.0) for b in fb_b]
                n = len(plan)
                for j in rng.permutation(n):
                    batch, s = plan[j]
                    _step(net, opt, batch, max(total_w, 1e-9), s * n, cfg.end_weight)
                sched.step()
                if tick:
                    tick()
            out.append(net.eval())
        return out
