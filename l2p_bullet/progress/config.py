"""The progress ensemble's architecture and the tensor shapes it implies.

Kept free of torch so that :func:`l2p_bullet.plugins.bundle.load_bundle` can check a weights file's shapes
against its manifest without importing torch (listing and validating bundles stays fast).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class ModelConfig:
    """Architecture (written to the manifest's ``[model]``)."""

    n_features: int
    hidden: int = 32
    ensemble: int = 5
    arch: str = "lstm"

    def to_dict(self) -> dict:
        return {"arch": self.arch, "n_features": self.n_features, "hidden": self.hidden, "ensemble": self.ensemble}

    @classmethod
    def from_dict(cls, d: dict) -> ModelConfig:
        return cls(n_features=int(d["n_features"]), hidden=int(d["hidden"]), ensemble=int(d["ensemble"]),
                   arch=str(d.get("arch", "lstm")))


def expected_shapes(cfg: ModelConfig) -> dict[str, tuple[int, ...]]:
    """Tensor name -> shape of a saved ensemble: member ``i``'s parameters are ``m<i>.<name>``."""
    H, F = cfg.hidden, cfg.n_features
    one = {"lstm.weight_ih_l0": (4 * H, F), "lstm.weight_hh_l0": (4 * H, H), "lstm.bias_ih_l0": (4 * H,),
           "lstm.bias_hh_l0": (4 * H,), "head.weight": (1, H), "head.bias": (1,)}
    return {f"m{i}.{k}": v for i in range(cfg.ensemble) for k, v in one.items()}
