"""The LSTM progress model in torch (the training half): QSR features -> per-frame progress in [0, 1].

Progress is the paper's f(S, i, e): 0 before (and outside) the event, rising linearly to 1 at its end.
A bundle holds an **ensemble** of small LSTMs trained from different seeds; their outputs are averaged
because one model's agreement with people varies a lot between seeds (DESIGN.md section 5).

Inference is batched: every candidate path of a planner step is resampled, padded and scored in one
forward pass per ensemble member under ``torch.inference_mode``. The net is causal, so the progress
at a frame only depends on the frames before it: scoring a path's prefix gives the same values.
Everything but training scores with the numpy twin, :class:`l2p_bullet.progress.model.NumpyProgressModel`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import torch
from torch import nn

from ..core.threads import torch_threads
from ..plugins.bundle import PROGRESS_FILE
from ..progress.config import ModelConfig
from ..progress.features import QSRConfig
from ..progress.scoring import ScoringMixin, shared_prefix


class OrdinalHead(nn.Linear):
    """A linear read-out with ``levels`` ordered thresholds (a cumulative-link ordinal head): the
    probability that progress is past threshold k is sigmoid(w.h + b - offset_k), offsets 0 then running
    sums of softplus(``cuts``), so the thresholds stay ordered. One level is the plain sigmoid read-out
    (no ``cuts`` parameter: the state dict of the shipped bundles)."""

    def __init__(self, hidden: int, levels: int = 1):
        super().__init__(hidden, 1)
        self.levels = levels
        if levels > 1:  # offsets start one logit apart
            self.cuts = nn.Parameter(torch.full((levels - 1,), float(np.log(np.e - 1))))

    def level_probs(self, h: torch.Tensor) -> torch.Tensor:  # (..., H) -> (..., levels)
        z = super().forward(h)
        if self.levels == 1:
            return torch.sigmoid(z)
        off = torch.cat([torch.zeros(1), torch.cumsum(nn.functional.softplus(self.cuts), 0)])
        return torch.sigmoid(z - off)

    def progress(self, h: torch.Tensor) -> torch.Tensor:  # (..., H) -> (...)
        return self.level_probs(h).mean(-1)


class ProgressNet(nn.Module):
    """One LSTM layer and a sigmoid (or ordinal, :class:`OrdinalHead`) read-out per frame."""

    def __init__(self, n_features: int, hidden: int, levels: int = 1):
        super().__init__()
        self.lstm = nn.LSTM(n_features, hidden, batch_first=True)
        self.head = OrdinalHead(hidden, levels)

    def forward(self, x: torch.Tensor) -> torch.Tensor:  # (B, T, F) -> (B, T)
        h, _ = self.lstm(x)
        return self.head.progress(h)

    def level_probs(self, x: torch.Tensor) -> torch.Tensor:  # (B, T, F) -> (B, T, levels)
        h, _ = self.lstm(x)
        return self.head.level_probs(h)


def ensemble_state(nets: Sequence[ProgressNet]) -> dict[str, torch.Tensor]:
    """Flatten an ensemble into one safetensors-ready dict (``m<i>.<param>``)."""
    return {f"m{i}.{k}": v.detach().contiguous().clone() for i, n in enumerate(nets) for k, v in n.state_dict().items()}


def ensemble_arrays(nets: Sequence[ProgressNet]) -> dict[str, np.ndarray]:
    """The same as numpy arrays, what :func:`l2p_bullet.plugins.bundle.write_progress_bundle` stores."""
    return {k: v.numpy() for k, v in ensemble_state(nets).items()}


class ProgressModel(ScoringMixin):
    """A loaded ensemble plus its feature settings: scores metric motions of blocks of side ``size``."""

    threads: int = 1
    """Intra-op threads while scoring. One: these LSTMs are too small to gain from more, and on shared
    cores a second spinning thread made batch scoring 3-4x slower (measured)."""

    def __init__(self, tensors: dict[str, torch.Tensor], model_cfg: ModelConfig, qsr_cfg: QSRConfig):
        self.model_cfg, self.qsr_cfg = model_cfg, qsr_cfg
        self.nets: list[ProgressNet] = []
        for i in range(model_cfg.ensemble):
            net = ProgressNet(model_cfg.n_features, model_cfg.hidden, model_cfg.levels)
            net.load_state_dict({k.split(".", 1)[1]: v for k, v in tensors.items() if k.startswith(f"m{i}.")})
            net.eval()
            self.nets.append(net)

    @classmethod
    def from_bundle(cls, bundle) -> ProgressModel:
        """The torch ensemble of a loaded bundle (for training and validation; scoring uses numpy)."""
        tensors = {k: torch.from_numpy(v.copy()) for k, v in bundle.arrays(PROGRESS_FILE).items()}
        return cls(tensors, ModelConfig.from_dict(bundle.manifest["model"]),
                   QSRConfig.from_dict(bundle.manifest["features"]))

    @classmethod
    def from_nets(cls, nets: Sequence[ProgressNet], model_cfg: ModelConfig, qsr_cfg: QSRConfig) -> ProgressModel:
        return cls(ensemble_state(nets), model_cfg, qsr_cfg)

    def forward_features(self, feats: np.ndarray, lengths: np.ndarray | None = None) -> np.ndarray:
        """Mean ensemble progress ``(B, K)`` for padded features ``(B, K, F)``.

        Frames that every sequence of the batch shares at its start (a planner's candidates all extend
        the same path) go through the LSTMs once, at batch size 1; only the rest runs for the batch.
        """
        B, K, _ = feats.shape
        lengths, P = shared_prefix(feats, lengths)
        x = torch.from_numpy(np.ascontiguousarray(feats, dtype=np.float32))
        out = torch.zeros(B, K)
        with torch_threads(self.threads):
            self._forward(x, out, B, P)
        return (out / len(self.nets)).numpy().astype(float)

    def _forward(self, x: torch.Tensor, out: torch.Tensor, B: int, P: int) -> None:
        with torch.inference_mode():
            for net in self.nets:
                if P >= 2:
                    hp, (h, c) = net.lstm(x[:1, :P])
                    hr, _ = net.lstm(x[:, P:], (h.expand(-1, B, -1).contiguous(), c.expand(-1, B, -1).contiguous()))
                    h_all = torch.cat([hp.expand(B, -1, -1), hr], dim=1)
                else:
                    h_all, _ = net.lstm(x)
                out += net.head.progress(h_all)
