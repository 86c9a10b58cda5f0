"""Train a policy on ``l2p_bullet/Plan2D-v0`` with REINFORCE, then perform with it on the arm (``Arm-v0``).

    .venv/bin/python examples/plan2d_reinforce.py --action closer --episodes 300

The policy is a small Gaussian MLP in torch over what the observation says about the two blocks
(the mover relative to the anchor, both yaws, the progress so far); the reward is the increase of the
action's learned progress, so the return of an episode is the progress it reached. REINFORCE with a
mean-return baseline, one update per batch of episodes. Then the trained policy's mean moves are
performed by the Panda in PyBullet on a scene it has not seen (Arm-v0), judged by the action's judge,
and one camera frame is saved. Prints one JSON line with what it measured.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import gymnasium as gym
import numpy as np
import torch

import l2p_bullet.envs  # noqa: F401  (registers l2p_bullet/Plan2D-v0 and l2p_bullet/Arm-v0)


def features(obs: np.ndarray) -> torch.Tensor:
    """The mover relative to the anchor (block units), both yaws as cos/sin of 4x (squares), progress."""
    o = torch.as_tensor(np.asarray(obs, np.float32))
    rel = o[..., 0:2] - o[..., 3:5]
    dist = rel.norm(dim=-1, keepdim=True)
    return torch.cat([rel / 5.0, dist / 5.0, torch.cos(4 * o[..., 2:3]), torch.sin(4 * o[..., 2:3]),
                      torch.cos(4 * o[..., 5:6]), torch.sin(4 * o[..., 5:6]), o[..., 6:7]], dim=-1)


class Policy(torch.nn.Module):
    def __init__(self, n_in: int = 8, hidden: int = 64, scale: np.ndarray | None = None):
        super().__init__()
        self.body = torch.nn.Sequential(torch.nn.Linear(n_in, hidden), torch.nn.Tanh(),
                                        torch.nn.Linear(hidden, hidden), torch.nn.Tanh(), torch.nn.Linear(hidden, 3))
        self.log_std = torch.nn.Parameter(torch.full((3,), -1.0))
        self.scale = torch.as_tensor(scale if scale is not None else np.ones(3), dtype=torch.float32)

    def dist(self, x: torch.Tensor) -> torch.distributions.Normal:
        return torch.distributions.Normal(torch.tanh(self.body(x)) * self.scale, self.log_std.exp() * self.scale)


def train(action: str, episodes: int, batch: int, seed: int) -> tuple[Policy, list[float]]:
    torch.manual_seed(seed)
    env = gym.make("l2p_bullet/Plan2D-v0", action=action)
    policy = Policy(scale=env.action_space.high)
    opt = torch.optim.Adam(policy.parameters(), lr=1e-2)
    finals: list[float] = []
    for start in range(0, episodes, batch):
        logps, returns = [], []
        for ep in range(start, min(start + batch, episodes)):
            obs, info = env.reset(seed=seed * 100_000 + ep)
            lp, rewards, done = [], [], False
            while not done:
                d = policy.dist(features(obs))
                a = d.sample()
                lp.append(d.log_prob(a).sum())
                obs, r, term, trunc, info = env.step(a.numpy())
                rewards.append(r)
                done = term or trunc
            finals.append(info["progress"])
            ret = np.cumsum(rewards[::-1])[::-1].copy()  # return to go
            logps.append(torch.stack(lp))
            returns.append(torch.as_tensor(ret, dtype=torch.float32))
        base = torch.cat(returns).mean()
        loss = -sum((lp * (ret - base)).sum() for lp, ret in zip(logps, returns, strict=True)) / len(logps)
        opt.zero_grad()
        loss.backward()
        opt.step()
    env.close()
    return policy, finals


def perform(policy: Policy, action: str, seed: int, frame: Path | None) -> dict:
    """The policy's mean moves, carried out by the arm on a held-out scene; the action's judge reads them."""
    from l2p_bullet.judge import judge_for

    env = gym.make("l2p_bullet/Arm-v0", action=action, render_mode="rgb_array" if frame else None)
    obs, info = env.reset(seed=seed)
    done, steps = False, 0
    with torch.no_grad():
        while not done:
            obs, _, term, trunc, info = env.step(policy.dist(features(obs)).mean.numpy())
            done, steps = term or trunc, steps + 1
    arm = env.unwrapped
    if frame:
        import imageio.v2 as imageio

        imageio.imwrite(frame, env.render())
    verdict = judge_for(arm.bundle).judge(arm.frames, arm._anchor_now(), arm.block, final_progress=info["progress"])
    env.close()
    return {"arm_steps": steps, "arm_progress": round(info["progress"], 4), "arm_success": bool(verdict.success),
            "arm_reason": verdict.reason, "ended": info.get("illegal", "threshold" if term else "budget")}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--action", default="closer")
    ap.add_argument("--episodes", type=int, default=300)
    ap.add_argument("--batch", type=int, default=10)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--frame", type=Path, default=None, help="save the arm's last camera frame here (PNG)")
    args = ap.parse_args()
    t = time.perf_counter()
    policy, finals = train(args.action, args.episodes, args.batch, args.seed)
    k = max(1, min(len(finals) // 5, 50))
    out = {
        "action": args.action,
        "episodes": args.episodes,
        "train_s": round(time.perf_counter() - t, 1),
        "progress_first": round(float(np.mean(finals[:k])), 4),
        "progress_last": round(float(np.mean(finals[-k:])), 4),
    }
    out |= perform(policy, args.action, seed=10**6 + args.seed, frame=args.frame)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
