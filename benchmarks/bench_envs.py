"""Environment steps per second of Arm-v0 in each observation and control mode, side by side in one run.

    .venv/bin/python benchmarks/bench_envs.py [--steps 300] [--size 128] [--action closer]

One process, one core (numpy and the renderer single-threaded: OMP_NUM_THREADS=1 is set before numpy
loads); random actions, resets counted in. The goal is at least 50 steps a second with 128x128 RGB
observations; the state-only rate stands beside it. The machine's load average is printed before and
after: on a shared machine compare the ratios of one run, not absolute rates across runs.
"""

from __future__ import annotations

import os

os.environ.setdefault("OMP_NUM_THREADS", "1")

import argparse  # noqa: E402
import time  # noqa: E402

import gymnasium as gym  # noqa: E402

import l2p_bullet.envs  # noqa: E402,F401 - registers the ids

MODES = [("state", "joint_delta"), ("rgb", "joint_delta"), ("state", "ee_delta_pos"), ("rgb", "ee_delta_pos"),
         ("rgbd", "ee_delta_pos"), ("state+rgb", "ee_delta_pos"), ("state", "block_delta"), ("rgb", "block_delta")]


def rate(obs_mode: str, control_mode: str, steps: int, size: int, action: str) -> float:
    env = gym.make("l2p_bullet/Arm-v0", action=action, obs_mode=obs_mode, control_mode=control_mode,
                   image_size=(size, size))
    env.reset(seed=0)
    env.action_space.seed(0)
    n = steps if control_mode != "block_delta" else max(3, steps // 30)  # a block move is a whole slide
    t0 = time.perf_counter()
    for _ in range(n):
        *_, terminated, truncated, _ = env.step(env.action_space.sample())
        if terminated or truncated:
            env.reset()
    seconds = time.perf_counter() - t0
    env.close()
    return n / seconds


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=300)
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--action", default="closer")
    args = ap.parse_args()
    print(f"load average before: {os.getloadavg()[0]:.2f}")
    print(f"| obs_mode | control_mode | steps/s ({args.size}x{args.size} images) |\n|---|---|---:|")
    for om, cm in MODES:
        print(f"| {om} | {cm} | {rate(om, cm, args.steps, args.size, args.action):.1f} |", flush=True)
    print(f"load average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
