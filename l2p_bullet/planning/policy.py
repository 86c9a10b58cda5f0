"""The learned move proposer: a Gaussian policy over (x, y, rotation), trained by REINFORCE.

Why this shape: the policy must serve any scene, so it sees the situation the way the action's words
do, relative to the anchor and in block units. Its input is the mover's state in the anchor-centred
polar frame (distance, how far it has already turned around the anchor, the last move, the progress
so far); its output is a Gaussian over the next move in that frame (radial, tangential, in blocks,
and a rotation). One small network per action; the weights live in the action's bundle
(``policy.safetensors``) with the settings in the manifest's ``[policy]`` section.

Planning never imports torch: the network (``learning/policy_net.py``, trained in torch) is evaluated
here in numpy from the bundle's safetensors, as the progress model is in ``progress/model.py``
(importing torch costs 1.4-2.5 s, more than the rest of ``perform``).
"""

from __future__ import annotations

import math

import numpy as np

from ..core.geometry import swept_angle
from ..errors import BundleError
from .problem import MAX_TURN, Node, Problem

FEATURES = 12
HIDDEN = 64
LOG_STD_RANGE = (-3.0, 1.0)
FEATURE_RADIUS = 0.25
"""The length (m) the policy's "room" features are divided by: the workspace disk's radius the shipped policies
were trained on, not the current 0.35 m one: fixed, so that their inputs do not change."""


def policy_features(frames: list[np.ndarray], anchor_poses: np.ndarray, size: float, progress: np.ndarray,
             moves: np.ndarray, centres: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """The policy's view of B paths: features (B, FEATURES) and the frame's handedness (B,) of +-1.

    Block units, in the anchor's polar frame (radial, tangential). ``frames`` in metres; ``anchor_poses``
    and the workspace ``centres`` one for all ((3,), (2,)) or one per path. The workspace's centre, seen
    from the mover, tells the policy where there is room to move.

    The actions are mirror-symmetric (a mirrored "past" is a "past"), so the frame is mirrored to make
    the tangential direction point the way the mover already turns around the anchor, or, before it has
    turned, the way with more room. The policy then learns one of the two mirror-image solutions
    instead of hesitating between them; ``to_poses`` applies the same handedness to its moves.
    """
    out = np.zeros((len(frames), FEATURES), dtype=np.float32)
    hand = np.ones(len(frames))
    anchors = np.broadcast_to(np.asarray(anchor_poses, float), (len(frames), 3))
    centres = np.broadcast_to(np.asarray(centres, float), (len(frames), 2))
    for i, f in enumerate(frames):
        anchor_pose = anchors[i]
        rel = (f[:, :2] - anchor_pose[:2]) / size
        r = max(float(np.hypot(*rel[-1])), 1e-6)
        e1 = rel[-1] / r
        e2 = np.array([-e1[1], e1[0]])
        last = (rel[-1] - rel[-2]) if len(rel) > 1 else np.zeros(2)
        phi = math.atan2(rel[-1, 1], rel[-1, 0]) - anchor_pose[2]
        yaw = f[-1, 2] - anchor_pose[2]
        room = (centres[i] - f[-1, :2]) / size
        swept = swept_angle(rel)
        h = (1.0 if swept > 0 else -1.0) if abs(swept) > 0.05 else (1.0 if room @ e2 >= 0 else -1.0)
        hand[i] = h
        out[i] = [r / 5.0, 1.0 / r, progress[i], h * swept / (2 * math.pi), last @ e1, h * (last @ e2),
                  moves[i] / 8.0, h * math.sin(4 * phi), math.cos(4 * phi), math.cos(4 * yaw),
                  room @ e1 / (radius / size), h * (room @ e2) / (radius / size)]
    return out, hand


def to_poses(actions: np.ndarray, poses: np.ndarray, anchor_pose: np.ndarray, size: float,
             hand: np.ndarray | float = 1.0) -> np.ndarray:
    """Moves in the anchor-polar frame (B,3: radial, tangential blocks; turn) -> end poses (B,3) in metres;
    ``anchor_pose`` is (3,) or (B,3); ``hand`` mirrors the tangential direction and the turn (see policy_features)."""
    hand = np.broadcast_to(np.asarray(hand, float), (len(actions),))
    rel = poses[:, :2] - np.asarray(anchor_pose, float)[..., :2]
    e1 = rel / np.maximum(np.linalg.norm(rel, axis=1, keepdims=True), 1e-9)
    e2 = np.stack([-e1[:, 1], e1[:, 0]], axis=1)
    out = poses.copy()
    out[:, :2] += size * (actions[:, :1] * e1 + (hand * actions[:, 1])[:, None] * e2)
    out[:, 2] += np.clip(hand * actions[:, 2], -MAX_TURN, MAX_TURN)
    return out


class NumpyPolicy:
    """The trained network's forward pass in numpy: features (B, FEATURES) -> mean, log_std (B, 3)."""

    def __init__(self, arrays: dict[str, np.ndarray]):
        try:
            self.w = [np.asarray(arrays[f"{k}.weight"], np.float64).T for k in ("body.0", "body.2", "mean", "log_std")]
            self.b = [np.asarray(arrays[f"{k}.bias"], np.float64) for k in ("body.0", "body.2", "mean", "log_std")]
        except KeyError as e:
            raise BundleError(f"the policy weights lack the tensor {e.args[0]}") from None
        if self.w[0].shape[0] != FEATURES:
            raise BundleError(f"the policy expects {self.w[0].shape[0]} features, this planner gives {FEATURES}")

    def __call__(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        h = np.tanh(np.tanh(x @ self.w[0] + self.b[0]) @ self.w[1] + self.b[1])
        return h @ self.w[2] + self.b[2], np.clip(h @ self.w[3] + self.b[3], *LOG_STD_RANGE)


def load_policy(bundle) -> NumpyPolicy | None:
    """The bundle's policy (its digest-checked ``policy_arrays``), or None when it has none."""
    arrays = bundle.policy_arrays()
    return None if arrays is None else NumpyPolicy(arrays)


class PolicyProposer:
    """Candidates for the next move: the policy's mean and samples from its Gaussian (seeded numpy draws)."""

    deterministic = False

    def __init__(self, net: NumpyPolicy, spread: float = 1.0):
        self.net = net
        self.spread = spread

    def __call__(self, problem: Problem, node: Node, n: int) -> np.ndarray:
        # the policy sees the action's own moves (after a lead-in), as it was trained
        x, hand = policy_features(
            [node.frames[problem.lead :]],
            problem.anchor_pose,
            problem.size,
            np.array([node.progress]),
            np.array([node.moves - problem.lead_moves]),
            problem.world.center,
            FEATURE_RADIUS,
        )
        mean, log_std = self.net(x.astype(np.float64))
        mean, std = mean[0], np.exp(log_std[0]) * self.spread
        acts = mean + std * problem.rng.normal(size=(max(n, 1), 3))
        acts[0] = mean
        return to_poses(acts, np.repeat(node.pose[None], len(acts), 0), problem.anchor_pose, problem.size,
                        hand[0])
