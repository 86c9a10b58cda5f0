"""Behaviour cloning from the planner's demonstrations, on camera images, with the arm doing every move.

    .venv/bin/python examples/bc_from_planner.py --action closer --demos 60 --tests 20

1. Demonstrations: for each seed, Arm-v0 (``obs_mode="rgb"``, 64x64 images, ``control_mode="block_delta"``)
   poses a random scene; the project's planner plans the move on it, and its waypoints are played in the
   environment as block moves (split where one is longer than the action space allows). Every (image,
   move) pair is kept.
2. A small CNN (torch, CPU) learns the move from the image (mean squared error, a few epochs).
3. The policy acts alone on scenes it has never seen (other seeds) until the episode ends; the rule judge's
   ``info["success"]`` at the end is counted.

Prints one JSON line: demonstrations, training loss, success rate of the planner's own moves and of the
cloned policy on the test seeds, and the minutes it took.
"""

from __future__ import annotations

import argparse
import json
import time

import gymnasium as gym
import numpy as np
import torch

import l2p_bullet.envs  # noqa: F401  (registers the environments)
from l2p_bullet import planning


def make(action: str) -> gym.Env:
    return gym.make("l2p_bullet/Arm-v0", action=action, obs_mode="rgb", control_mode="block_delta",
                    image_size=(64, 64))


def planned_moves(env) -> list[np.ndarray]:
    """The planner's waypoints on the episode's scene as actions (block units), each within the space."""
    u = env.unwrapped
    plan = planning.plan(u.scene, u.mover, u.anchor, u.bundle, seed=0)
    pts = np.asarray(plan.extra.get("waypoints", plan.path), float)
    hi = u.action_space.high.astype(float)
    moves = []
    for a, b in zip(pts[:-1], pts[1:], strict=True):
        d = np.array([(b[0] - a[0]) / u.block, (b[1] - a[1]) / u.block,
                      (b[2] - a[2] + np.pi) % (2 * np.pi) - np.pi])
        n = int(np.ceil(np.max(np.abs(d) / hi)))
        moves += [d / max(n, 1)] * max(n, 1)
    return moves


class Policy(torch.nn.Module):
    def __init__(self, scale: np.ndarray):
        super().__init__()
        self.net = torch.nn.Sequential(
            torch.nn.Conv2d(3, 16, 5, stride=2), torch.nn.ReLU(), torch.nn.Conv2d(16, 32, 5, stride=2), torch.nn.ReLU(),
            torch.nn.Conv2d(32, 32, 3, stride=2), torch.nn.ReLU(), torch.nn.Flatten(), torch.nn.LazyLinear(64),
            torch.nn.ReLU(), torch.nn.Linear(64, 3))
        self.scale = torch.as_tensor(scale, dtype=torch.float32)

    def forward(self, rgb: torch.Tensor) -> torch.Tensor:
        x = rgb.permute(0, 3, 1, 2).float() / 255.0
        return torch.tanh(self.net(x)) * self.scale


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--action", default="closer")
    ap.add_argument("--demos", type=int, default=60)
    ap.add_argument("--tests", type=int, default=20)
    ap.add_argument("--epochs", type=int, default=30)
    args = ap.parse_args()
    t0 = time.time()
    torch.manual_seed(0)
    env = make(args.action)
    images, actions, planner_ok = [], [], 0
    for seed in range(args.demos):
        obs, info = env.reset(seed=seed)
        for a in planned_moves(env):
            images.append(obs["rgb"])
            actions.append(a)
            obs, _, terminated, truncated, info = env.step(a.astype(np.float32))
            if terminated or truncated:
                break
        planner_ok += bool(info.get("success"))
    x, y = torch.as_tensor(np.stack(images)), torch.as_tensor(np.stack(actions), dtype=torch.float32)
    policy = Policy(env.action_space.high)
    policy(x[:1])  # sizes the lazy layer
    opt = torch.optim.Adam(policy.parameters(), lr=1e-3)
    for _ in range(args.epochs):
        for idx in torch.randperm(len(x)).split(32):
            loss = torch.nn.functional.mse_loss(policy(x[idx]), y[idx])
            opt.zero_grad()
            loss.backward()
            opt.step()
    with torch.no_grad():
        final_loss = float(torch.nn.functional.mse_loss(policy(x), y))
    cloned_ok = 0
    for seed in range(10_000, 10_000 + args.tests):
        obs, info = env.reset(seed=seed)
        done = False
        while not done:
            with torch.no_grad():
                a = policy(torch.as_tensor(obs["rgb"])[None])[0].numpy()
            obs, _, terminated, truncated, info = env.step(a)
            done = terminated or truncated
        cloned_ok += bool(info.get("success"))
    env.close()
    print(json.dumps({"action": args.action, "demos": args.demos, "samples": len(x), "train_mse": round(final_loss, 4),
                      "planner_success": round(planner_ok / args.demos, 3),
                      "cloned_success": round(cloned_ok / args.tests, 3), "tests": args.tests,
                      "minutes": round((time.time() - t0) / 60, 2)}))


if __name__ == "__main__":
    main()
