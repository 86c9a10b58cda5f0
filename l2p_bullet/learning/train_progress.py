"""Train one action's progress ensemble, deterministically for a seed, on a couple of CPU cores.

Each ensemble member is a small LSTM trained with Adam on a per-frame, per-sequence-averaged squared
error plus an extra term on the frame where the event ends (the planner reads the final value). The
members differ only in their seed; averaging them is cheaper than tuning one model to be stable.
The honest evaluation (split by capture session) lives in :mod:`l2p_bullet.learning.validation`.
"""

from __future__ import annotations

import hashlib
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import torch

from ..progress.config import ModelConfig
from ..progress.features import QSRConfig
from .demos import ACTIONS, Demo, load_demos
from .progress_net import ProgressModel, ProgressNet
from .trainset import DataConfig, Sequence, build


@dataclass(frozen=True)
class TrainConfig:
    """Optimisation settings (written to the manifest's ``[training]``)."""

    hidden: int = 32
    ensemble: int = 5
    epochs: int = 30
    batch: int = 32
    lr: float = 0.01
    end_weight: float = 2.0
    """Extra weight of the squared error at the event's end frame (or a negative's last frame)."""
    threads: int = 1
    """Intra-op threads while training: tiny LSTMs gain nothing from more, and spinning threads stall
    badly when the cores are shared."""

    def to_dict(self) -> dict:
        return {k: getattr(self, k) for k in ("hidden", "ensemble", "epochs", "batch", "lr", "end_weight")}


@dataclass
class TrainResult:
    model: ProgressModel
    seconds: float
    n_sequences: int
    n_positive: int
    final_loss: float
    data_digest: str
    history: list[float] = field(default_factory=list)


def data_digest(demos: dict[str, list[Demo]]) -> str:
    """sha256 over the demonstrations actually used (ids and poses), for the manifest."""
    h = hashlib.sha256()
    for action in sorted(demos):
        for d in demos[action]:
            h.update(d.id.encode())
            h.update(np.ascontiguousarray(d.mover, np.float64).tobytes())
            h.update(np.ascontiguousarray(d.anchor, np.float64).tobytes())
    return h.hexdigest()


def all_demos(files: dict[str, list] | None = None, sessions: set[str] | None = None) -> dict[str, list[Demo]]:
    """Every action's demonstrations (optionally only some capture sessions)."""
    out = {}
    for a in ACTIONS:
        ds = load_demos(a, (files or {}).get(a))
        out[a] = [d for d in ds if sessions is None or d.session in sessions]
    return out


def _pad(seqs: list[Sequence]) -> tuple[torch.Tensor, ...]:
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


def train_net(seqs: list[Sequence], n_features: int, cfg: TrainConfig, seed: int,
              tick: Callable[[], None] | None = None) -> tuple[ProgressNet, list[float]]:
    """Train one ensemble member. Batches are length-sorted chunks (little padding), shuffled per epoch."""
    prev_threads = torch.get_num_threads()
    torch.set_num_threads(cfg.threads)
    try:
        return _train_net(seqs, n_features, cfg, seed, tick)
    finally:
        torch.set_num_threads(prev_threads)


def _train_net(seqs: list[Sequence], n_features: int, cfg: TrainConfig, seed: int,
               tick: Callable[[], None] | None) -> tuple[ProgressNet, list[float]]:
    torch.manual_seed(seed)
    rng = np.random.default_rng(seed)
    net = ProgressNet(n_features, cfg.hidden)
    opt = torch.optim.Adam(net.parameters(), lr=cfg.lr)
    sched = torch.optim.lr_scheduler.CosineAnnealingLR(opt, T_max=cfg.epochs)
    order = np.argsort([len(s.y) for s in seqs], kind="stable")
    chunks = [order[i : i + cfg.batch] for i in range(0, len(order), cfg.batch)]
    batches = [_pad([seqs[j] for j in c]) for c in chunks]
    total_w = sum(s.weight for s in seqs)
    history = []
    for _ in range(cfg.epochs):
        ep = 0.0
        for b in rng.permutation(len(batches)):
            x, y, mask, endw = batches[b]
            p = net(x)
            err = (p - y) ** 2
            loss = ((err * mask).sum() + cfg.end_weight * (err * endw).sum()) / total_w * len(batches)
            opt.zero_grad()
            loss.backward()
            torch.nn.utils.clip_grad_norm_(net.parameters(), 1.0)
            opt.step()
            ep += float(loss.detach()) / len(batches)
        sched.step()
        history.append(ep)
        if tick:
            tick()
    net.eval()
    return net, history


def train_action(action: str, demos: dict[str, list[Demo]], *, seed: int = 0,
                 qsr_cfg: QSRConfig | None = None, data_cfg: DataConfig | None = None,
                 cfg: TrainConfig | None = None, tick: Callable[[], None] | None = None) -> TrainResult:
    """Build the training set and train the ensemble; ``tick`` is called once per member-epoch."""
    qsr_cfg, data_cfg, cfg = qsr_cfg or QSRConfig(), data_cfg or DataConfig(), cfg or TrainConfig()
    t0 = time.perf_counter()
    seqs = build(action, demos, qsr_cfg, data_cfg, seed=seed)
    nets, last = [], []
    for i in range(cfg.ensemble):
        net, hist = train_net(seqs, qsr_cfg.n_features, cfg, seed * 1000 + i, tick)
        nets.append(net)
        last.append(hist[-1])
    mcfg = ModelConfig(n_features=qsr_cfg.n_features, hidden=cfg.hidden, ensemble=cfg.ensemble)
    return TrainResult(
        model=ProgressModel.from_nets(nets, mcfg, qsr_cfg),
        seconds=time.perf_counter() - t0,
        n_sequences=len(seqs),
        n_positive=sum(s.positive for s in seqs),
        final_loss=float(np.mean(last)),
        data_digest=data_digest(demos),
        history=last,
    )


def training_section(result: TrainResult, cfg: TrainConfig, seed: int, command: str,
                     data_cfg: DataConfig | None = None) -> dict:
    """The manifest's ``[training]``: how to reproduce the weights and what data went in."""
    return {"command": command, "seed": seed, "data_digest": result.data_digest,
            "n_sequences": result.n_sequences, "n_positive": result.n_positive,
            "seconds": round(result.seconds, 1), **cfg.to_dict(), "data": (data_cfg or DataConfig()).to_dict()}
