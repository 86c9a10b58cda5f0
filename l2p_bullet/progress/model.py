"""The progress ensemble's forward pass in numpy: the model every stage but training scores with.

Why: ``perform`` is a command a person waits for, and importing torch alone costs 1.4-2.5 s on 2
cores; the models are one small LSTM layer per ensemble member, whose forward pass is a few lines of
numpy and, at the planner's batch sizes, as fast as torch's. Training stays in torch
(:mod:`l2p_bullet.learning.progress_net`); this module reads the same safetensors weights and computes
the same numbers, to float32 rounding. ``tests/progress/test_progress_model.py`` checks the two against each
other on random motions, so a change to the torch network that is not mirrored here fails loudly.
Batching and the mapping back to input frames are shared (:mod:`l2p_bullet.progress.scoring`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..core.contracts import PROGRESS_FILE
from ..errors import BundleError
from .config import ModelConfig, level_offsets
from .features import QSRConfig
from .scoring import ScoringMixin, shared_prefix


def _sigmoid(z: np.ndarray) -> np.ndarray:
    return 0.5 * (1.0 + np.tanh(0.5 * z))  # = 1 / (1 + exp(-z)), without overflow warnings


class NumpyProgressModel(ScoringMixin):
    """The scoring API of :mod:`l2p_bullet.progress.scoring` over the ensemble's numpy forward pass."""

    def __init__(self, tensors: dict[str, np.ndarray], model_cfg: ModelConfig, qsr_cfg: QSRConfig):
        if model_cfg.arch != "lstm":
            raise BundleError(f'no numpy inference for the architecture "{model_cfg.arch}"')
        self.model_cfg, self.qsr_cfg = model_cfg, qsr_cfg
        self.members = []
        for i in range(model_cfg.ensemble):
            def g(k: str, i: int = i) -> np.ndarray:
                return np.asarray(tensors[f"m{i}.{k}"], np.float32)

            # PyTorch's LSTM gate order is input, forget, cell, output; its two biases are added.
            # the read-out's thresholds: one (the plain sigmoid) unless the head is ordinal
            cuts = g("head.cuts") if model_cfg.levels > 1 else np.zeros(0, np.float32)
            self.members.append((g("lstm.weight_ih_l0").T.copy(), g("lstm.weight_hh_l0").T.copy(),
                                 g("lstm.bias_ih_l0") + g("lstm.bias_hh_l0"), g("head.weight")[0],
                                 g("head.bias")[0] - level_offsets(cuts)))

    @classmethod
    def from_bundle(cls, bundle: Any) -> NumpyProgressModel:
        """Read a loaded bundle's progress weights (digest checked again: the file may have changed)."""
        return cls(bundle.arrays(PROGRESS_FILE), ModelConfig.from_dict(bundle.manifest["model"]),
                   QSRConfig.from_dict(bundle.manifest["features"]))

    def forward_features(self, feats: np.ndarray, lengths: np.ndarray | None = None) -> np.ndarray:
        """Mean ensemble progress ``(B, K)`` for padded features ``(B, K, F)``.

        As in :meth:`ProgressModel.forward_features`, frames that every sequence shares at its start (a
        planner's candidates all extend the same path) run once, at batch size 1.
        """
        x = np.ascontiguousarray(feats, dtype=np.float32)
        B, K, _ = x.shape
        lengths, P = shared_prefix(x, lengths)
        out = np.zeros((B, K), np.float32)
        for member in self.members:
            if P >= 2:
                hp, h, c = self._lstm(member, x[:1, :P])
                hr, _, _ = self._lstm(member, x[:, P:], np.repeat(h, B, 0), np.repeat(c, B, 0))
                hs = np.concatenate([np.repeat(hp, B, 0), hr], axis=1)
            else:
                hs, _, _ = self._lstm(member, x)
            out += _sigmoid((hs @ member[3])[..., None] + member[4]).mean(axis=-1)
        return (out / len(self.members)).astype(float)

    @staticmethod
    def _lstm(member: tuple, x: np.ndarray, h: np.ndarray | None = None, c: np.ndarray | None = None):
        """One LSTM layer over ``x`` (B, T, F) from state (h, c): all hidden states, final h and c.

        The four gates share one tanh per step: sigmoid(z) = (1 + tanh(z / 2)) / 2, so the gate
        pre-activations are halved (exact in floating point) and the cell's candidate is not; the numbers
        are those of four separate calls, with a third of the numpy calls (the planner's small batches
        spend most of their time in call overhead).
        """
        w_ih, w_hh, bias = member[0], member[1], member[2]
        B, T, _ = x.shape
        H = w_hh.shape[0]
        scale = np.full(4 * H, 0.5, np.float32)
        scale[2 * H:3 * H] = 1.0  # PyTorch's gate order: input, forget, cell, output
        xi = (x.reshape(B * T, -1) @ w_ih).reshape(B, T, 4 * H) + bias
        h = np.zeros((B, H), np.float32) if h is None else h
        c = np.zeros((B, H), np.float32) if c is None else c
        hs = np.empty((B, T, H), np.float32)
        for t in range(T):
            z = np.tanh((xi[:, t] + h @ w_hh) * scale)
            gates = 0.5 * (1.0 + z)
            c = gates[:, H:2 * H] * c + gates[:, :H] * z[:, 2 * H:3 * H]
            h = gates[:, 3 * H:] * np.tanh(c)
            hs[:, t] = h
        return hs, h, c
