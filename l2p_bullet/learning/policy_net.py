"""The move policy's network in torch, for training (planning evaluates it in numpy: ``planning/policy.py``)."""

from __future__ import annotations

import math

import torch
from torch import nn

from ..planning.policy import FEATURES, HIDDEN, LOG_STD_RANGE

INITIAL_STD = 2.5
"""Starting spread of a move (block sizes): wide enough to stumble on a long move past the anchor."""


class GaussianPolicy(nn.Module):
    """state features (B, FEATURES) -> mean (B,3) and log standard deviation (B,3) of the next move."""

    def __init__(self, hidden: int = HIDDEN):
        super().__init__()
        self.body = nn.Sequential(nn.Linear(FEATURES, hidden), nn.Tanh(), nn.Linear(hidden, hidden), nn.Tanh())
        self.mean = nn.Linear(hidden, 3)
        self.log_std = nn.Linear(hidden, 3)
        nn.init.zeros_(self.mean.weight)
        nn.init.zeros_(self.mean.bias)
        nn.init.zeros_(self.log_std.weight)
        nn.init.constant_(self.log_std.bias, math.log(INITIAL_STD))

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        h = self.body(x)
        return self.mean(h), self.log_std(h).clamp(*LOG_STD_RANGE)

    def distribution(self, x: torch.Tensor) -> torch.distributions.Normal:
        mean, log_std = self(x)
        return torch.distributions.Normal(mean, log_std.exp())
