"""The learned move proposer: a Gaussian policy over (x, y, rotation), trained by REINFORCE.

Why this shape: the policy must serve any scene, so it sees the situation the way the action's words
do, relative to the anchor and in block units. Its input is the mover's state in the anchor-centred
polar frame (distance, how far it has already turned around the anchor, the last move, the progress
so far); its output is a Gaussian over the next move in that frame (radial, tangential, in blocks,
and a rotation). One small network per action; the weights live in the action's bundle
(``policy.safetensors``) with the settings in the manifest's ``[policy]`` section.

torch is imported here (the planning layer's only torch dependency besides the progress model).
"""

from __future__ import annotations

import math

import numpy as np
import torch
from torch import nn

from ..evaluate import turn
from .problem import MAX_TURN, Node, Problem

FEATURES = 10
HIDDEN = 64
LOG_STD_RANGE = (-3.0, 1.0)


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
        nn.init.constant_(self.log_std.bias, math.log(1.5))

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        h = self.body(x)
        return self.mean(h), self.log_std(h).clamp(*LOG_STD_RANGE)

    def distribution(self, x: torch.Tensor) -> torch.distributions.Normal:
        mean, log_std = self(x)
        return torch.distributions.Normal(mean, log_std.exp())


def features(frames: list[np.ndarray], anchor_poses: np.ndarray, size: float, progress: np.ndarray,
             moves: np.ndarray, max_moves: int) -> np.ndarray:
    """The policy's view of B paths (frames in metres; anchors (3,) or (B,3)): (B, FEATURES), block units."""
    out = np.zeros((len(frames), FEATURES), dtype=np.float32)
    anchors = np.broadcast_to(np.asarray(anchor_poses, float), (len(frames), 3))
    for i, f in enumerate(frames):
        anchor_pose = anchors[i]
        rel = (f[:, :2] - anchor_pose[:2]) / size
        r = max(float(np.hypot(*rel[-1])), 1e-6)
        e1 = rel[-1] / r
        e2 = np.array([-e1[1], e1[0]])
        last = (rel[-1] - rel[-2]) if len(rel) > 1 else np.zeros(2)
        phi = math.atan2(rel[-1, 1], rel[-1, 0]) - anchor_pose[2]
        yaw = f[-1, 2] - anchor_pose[2]
        out[i] = [r / 5.0, 1.0 / r, progress[i], turn(rel) / (2 * math.pi), last @ e1, last @ e2,
                  moves[i] / max_moves, math.sin(4 * phi), math.cos(4 * phi), math.cos(4 * yaw)]
    return out


def to_poses(actions: np.ndarray, poses: np.ndarray, anchor_pose: np.ndarray, size: float) -> np.ndarray:
    """Moves in the anchor-polar frame (B,3: radial, tangential blocks; turn) -> end poses (B,3) in metres;
    ``anchor_pose`` is (3,) or (B,3)."""
    rel = poses[:, :2] - np.asarray(anchor_pose, float)[..., :2]
    e1 = rel / np.maximum(np.linalg.norm(rel, axis=1, keepdims=True), 1e-9)
    e2 = np.stack([-e1[:, 1], e1[:, 0]], axis=1)
    out = poses.copy()
    out[:, :2] += size * (actions[:, :1] * e1 + actions[:, 1:2] * e2)
    out[:, 2] += np.clip(actions[:, 2], -MAX_TURN, MAX_TURN)
    return out


def policy_from_tensors(tensors: dict[str, torch.Tensor]) -> GaussianPolicy:
    """Rebuild the network from a bundle's policy tensors (shapes checked by ``load_state_dict``)."""
    hidden = int(tensors["body.0.weight"].shape[0])
    net = GaussianPolicy(hidden)
    net.load_state_dict({k: v.float() for k, v in tensors.items()})
    net.eval()
    return net


class PolicyProposer:
    """Candidates for the next move: the policy's mean and samples from its Gaussian (seeded numpy draws)."""

    deterministic = False

    def __init__(self, net: GaussianPolicy, spread: float = 1.0):
        self.net = net
        self.spread = spread

    def __call__(self, problem: Problem, node: Node, n: int) -> np.ndarray:
        x = features([node.frames], problem.anchor_pose, problem.size, np.array([node.progress]),
                     np.array([node.moves]), problem.max_moves)
        with torch.no_grad():
            mean, log_std = self.net(torch.from_numpy(x))
        mean, std = mean.numpy()[0].astype(float), np.exp(log_std.numpy()[0]).astype(float) * self.spread
        acts = mean + std * problem.rng.normal(size=(max(n, 1), 3))
        acts[0] = mean
        return to_poses(acts, np.repeat(node.pose[None], len(acts), 0), problem.anchor_pose, problem.size)
