"""Train one action's progress ensemble, deterministically for a seed, on a couple of CPU cores.

Each ensemble member is a small LSTM trained with Adam on a per-frame, per-sequence-averaged squared
error plus an extra term on the frame where the event ends (the planner reads the final value). The
members differ only in their seed; averaging them is cheaper than tuning one model to be stable.
The honest evaluation (split by capture session) lives in :mod:`l2p_bullet.learning.validation`.
"""

from __future__ import annotations

import hashlib
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch

from ..core.frames import Frame, declaration
from ..core.threads import torch_threads
from ..core.vocabulary import ACTIONS
from ..errors import BundleError, L2PError
from ..progress.config import ModelConfig
from ..progress.features import QSRConfig
from .demos import Demo, load_demos
from .progress_net import ProgressModel, ProgressNet, ensemble_arrays
from .trainset import DataConfig, TrainingSequence, build
from .views import viewer_sides


@dataclass(frozen=True)
class ProgressTrainConfig:
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
            for x in d.more_anchors:  # plugin actions' further anchors and viewpoint (none for the built-ins)
                h.update(np.ascontiguousarray(x, np.float64).tobytes())
            if d.viewer is not None:
                h.update(np.ascontiguousarray(d.viewer, np.float64).tobytes())
    return h.hexdigest()


def all_demos(files: dict[str, list] | None = None, sessions: set[str] | None = None) -> dict[str, list[Demo]]:
    """Every action's demonstrations (optionally only some capture sessions)."""
    out = {}
    for a in ACTIONS:
        ds = load_demos(a, (files or {}).get(a))
        out[a] = [d for d in ds if sessions is None or d.session in sessions]
    return out


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


def _train_net(seqs: list[TrainingSequence], n_features: int, cfg: ProgressTrainConfig, seed: int,
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
                 cfg: ProgressTrainConfig | None = None, tick: Callable[[], None] | None = None) -> TrainResult:
    """Build the training set and train the ensemble; ``tick`` is called once per member-epoch."""
    from ..errors import DataError

    qsr_cfg, data_cfg, cfg = qsr_cfg or QSRConfig(), data_cfg or DataConfig(), cfg or ProgressTrainConfig()
    if not demos.get(action):
        raise DataError(f'no demonstrations of "{action}" to learn from: the session files hold no events '
                        "(event_start_end is empty)")
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


def training_section(result: TrainResult, cfg: ProgressTrainConfig, seed: int, command: str,
                     data_cfg: DataConfig | None = None, own: list[Demo] | None = None,
                     qsr_cfg: QSRConfig | None = None) -> dict:
    """The manifest's ``[training]``: how to reproduce the weights and what data went in (for a
    viewer-frame action also on which sides its demonstrations end, which decides its negatives)."""
    section = {"command": command, "seed": seed, "data_digest": result.data_digest,
               "n_sequences": result.n_sequences, "n_positive": result.n_positive,
               "seconds": round(result.seconds, 1), **cfg.to_dict(), "data": (data_cfg or DataConfig()).to_dict()}
    if qsr_cfg is not None and qsr_cfg.viewer and own:
        lateral, depth = viewer_sides(own)
        section["viewer_sides"] = {"lateral": lateral, "depth": depth}
    return section


def declared(name: str, folder: Path | None) -> tuple[Frame, int]:
    """The frame and number of anchors a plugin action declares: in the manifest in ``folder`` (the one
    being trained), else in the installed plugin's; the defaults without either."""
    from ..plugins.bundle import MANIFEST, read_manifest
    from ..plugins.registry import resolve

    if folder is None or not (folder / MANIFEST).is_file():
        try:
            folder = resolve(name)[1]
        except L2PError:
            return Frame(), 1
    try:
        return declaration(read_manifest(folder))
    except BundleError as e:
        raise BundleError(f"{folder / MANIFEST}: {e}") from None


def training_target(action: str, out: Path | None, demo_files: Sequence[str]) -> tuple[str, bool]:
    """(action name, is it a plugin action still being authored) for ``l2p-bullet train ACTION``.

    An installed action (built-in or plugin) or a bundle folder resolves as everywhere else. A plugin
    action (``l2p-bullet new-action``) is trained before its package is installed, so it is recognised
    by the manifest the scaffold put in ``out``, which must name it, and it needs the author's demos.
    """
    from ..errors import PluginError
    from ..plugins.bundle import MANIFEST, read_manifest
    from ..plugins.registry import resolve

    try:
        name = resolve(action)[0]
    except (BundleError, PluginError):
        if out is None or not (out / MANIFEST).is_file() or str(read_manifest(out).get("name", "")) != action:
            raise
        name = action
    plugin = name not in ACTIONS
    if plugin and not demo_files:
        raise BundleError(f'the plugin action "{name}" has no shipped demonstrations: give yours with '
                          "--demos FILE (capture-session .npz, see the plugin's README)")
    return name, plugin


def train_bundle(action: str, out: Path | None, *, demo_files: Sequence[str] = (), seed: int = 0,
                 cfg: ProgressTrainConfig | None = None, force: bool = False,
                 tick: Callable[[], None] | None = None) -> tuple[Path, TrainResult]:
    """``l2p-bullet train``: train ``action``'s progress ensemble and write it into a bundle folder.

    The default folder is ``runs/bundles/<action>``. An existing trained bundle is only replaced with
    ``force``; a scaffolded plugin's manifest without weights is a template to fill, not a bundle to
    protect. Built-in actions train on the shipped demonstrations (or ``demo_files``); a plugin action on
    its author's files, with the built-in actions' demonstrations as negatives and no random negatives
    (no rule says a random motion is not the new action).
    """
    from ..errors import DataError, RunFolderError
    from ..plugins.bundle import MANIFEST, PROGRESS_FILE, write_progress_bundle
    from .demos import expand_files, load_demos

    demo_files = [str(f) for f in expand_files(list(demo_files))]

    name, plugin = training_target(action, out, demo_files)
    out = out if out is not None else Path("runs") / "bundles" / name
    if (out / MANIFEST).exists() and (out / PROGRESS_FILE).exists() and not force:
        raise RunFolderError(f"{out} already holds a bundle; pass --force to overwrite it")
    cfg = cfg or ProgressTrainConfig()
    qsr_cfg = QSRConfig()
    if plugin:
        demos = {**all_demos(), name: load_demos(name, list(demo_files))}
        data_cfg = DataConfig(random_negatives=0)
        frame, anchors = declared(name, out)
        qsr_cfg = QSRConfig(frame=frame.name, anchors=anchors)
    else:
        demos = all_demos({name: list(demo_files)} if demo_files else None)
        data_cfg = DataConfig()
    if demo_files and not demos[name]:
        raise DataError(f"the demonstration files ({', '.join(str(f) for f in demo_files)[:200]}) hold no events "
                        f'of "{name}" (event_start_end is empty): nothing to learn, no bundle written')
    result = train_action(name, demos, seed=seed, cfg=cfg, data_cfg=data_cfg, qsr_cfg=qsr_cfg, tick=tick)
    arrays = ensemble_arrays(result.model.nets)
    if not (np.isfinite(result.final_loss) and all(np.all(np.isfinite(a)) for a in arrays.values())):
        raise DataError(f'training "{name}" diverged (the loss or a weight is not a number); no bundle written')
    default = ProgressTrainConfig()
    cmd = (f"l2p-bullet train {name} --seed {seed}" + "".join(f" --demos {f}" for f in demo_files)
           + (f" --ensemble {cfg.ensemble}" if cfg.ensemble != default.ensemble else "")
           + (f" --epochs {cfg.epochs}" if cfg.epochs != default.epochs else ""))
    write_progress_bundle(out, name, arrays, result.model.model_cfg,
                          result.model.qsr_cfg,
                          training=training_section(result, cfg, seed, cmd, data_cfg, demos[name], qsr_cfg),
                          metrics={"train_loss": round(result.final_loss, 6)})
    return out, result


@dataclass(frozen=True)
class BundleTrainer:
    """:func:`train_bundle` with fixed settings, handed to code outside ``learning/`` that must not import
    torch itself (the teach page gets one from its command, which may)."""

    cfg: ProgressTrainConfig = field(default_factory=ProgressTrainConfig)

    @property
    def ticks(self) -> int:
        """How many times a training calls ``tick`` (once per member-epoch)."""
        return self.cfg.ensemble * self.cfg.epochs

    def __call__(self, action: str, out: Path, demo_files: Sequence[str], seed: int = 0,
                 tick: Callable[[], None] | None = None) -> tuple[Path, TrainResult]:
        return train_bundle(action, out, demo_files=demo_files, seed=seed, cfg=self.cfg, force=True, tick=tick)
