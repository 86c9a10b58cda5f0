"""The progress ensemble's architecture and the tensor shapes it implies.

Kept free of torch so that :func:`l2p_bullet.plugins.bundle.load_bundle` can check a weights file's shapes
against its manifest without importing torch (listing and validating bundles stays fast).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class ModelConfig:
    """Architecture (written to the manifest's ``[model]``)."""

    n_features: int
    hidden: int = 32
    ensemble: int = 5
    arch: str = "lstm"
    levels: int = 1
    """Thresholds of the read-out: 1 is the plain sigmoid; more is a cumulative-link ordinal head
    (one read-out, ``levels`` ordered thresholds, progress = the mean of their probabilities). Written
    to the manifest only when above 1, so bundles without it are read as they always were."""

    def to_dict(self) -> dict:
        out = {"arch": self.arch, "n_features": self.n_features, "hidden": self.hidden, "ensemble": self.ensemble}
        return out | ({"levels": self.levels} if self.levels > 1 else {})

    @classmethod
    def from_dict(cls, d: dict) -> ModelConfig:
        return cls(n_features=int(d["n_features"]), hidden=int(d["hidden"]), ensemble=int(d["ensemble"]),
                   arch=str(d.get("arch", "lstm")), levels=int(d.get("levels", 1)))


def expected_shapes(cfg: ModelConfig) -> dict[str, tuple[int, ...]]:
    """Tensor name -> shape of a saved ensemble: member ``i``'s parameters are ``m<i>.<name>``."""
    H, F = cfg.hidden, cfg.n_features
    one = {"lstm.weight_ih_l0": (4 * H, F), "lstm.weight_hh_l0": (4 * H, H), "lstm.bias_ih_l0": (4 * H,),
           "lstm.bias_hh_l0": (4 * H,), "head.weight": (1, H), "head.bias": (1,)}
    if cfg.levels > 1:
        one["head.cuts"] = (cfg.levels - 1,)
    return {f"m{i}.{k}": v for i in range(cfg.ensemble) for k, v in one.items()}


def level_offsets(cuts: np.ndarray) -> np.ndarray:
    """The ordinal thresholds' offsets below the first, from the raw ``head.cuts``: 0 then running sums
    of softplus(cuts), so they stay ordered whatever training does (numpy; torch mirrors it)."""
    c = np.asarray(cuts, np.float64)
    return np.concatenate([[0.0], np.cumsum(np.logaddexp(0.0, c))]).astype(np.float32)
