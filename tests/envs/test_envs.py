"""The Gymnasium environments: registration, Gymnasium's own checker, determinism, rewards, the example."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

from l2p_bullet.core.scene import random_scene

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def _quiet_checker(recwarn):
    """check_env's advice to normalise the action space to [-1, 1]: ours is a move in block units."""


def test_registered_through_the_module_id_and_the_entry_point():
    env = gym.make("l2p_bullet.envs:l2p_bullet/Plan2D-v0", action="around")
    assert env.unwrapped.action_name == "around"
    from importlib.metadata import entry_points

    (ep,) = [e for e in entry_points(group="gymnasium.envs") if e.name == "l2p_bullet"]
    ep.load()()  # what Gymnasium 0.26-0.29 call on import: idempotent
    assert {"l2p_bullet/Plan2D-v0", "l2p_bullet/Arm-v0"} <= set(gym.registry)


def test_the_action_is_required():
    """Issue 26: gym.make("l2p_bullet/Plan2D-v0") silently made an "around" environment."""
    import l2p_bullet.envs  # noqa: F401 - registers the ids (Gymnasium 1.x)
    from l2p_bullet.errors import L2PError

    for env_id in ("l2p_bullet/Plan2D-v0", "l2p_bullet/Arm-v0"):
        with pytest.raises(L2PError, match=r'say which action .*installed: .*around'):
            gym.make(env_id)


def test_plan2d_passes_gymnasiums_checker():
    check_env(gym.make("l2p_bullet/Plan2D-v0", action="closer").unwrapped, skip_render_check=False)


def test_seeded_resets_and_steps_are_deterministic():
    def episode(seed):
        env = gym.make("l2p_bullet/Plan2D-v0", action="closer")
        env.action_space.seed(seed)
        obs, _ = env.reset(seed=seed)
        out = [obs]
        for _ in range(5):
            obs, r, term, trunc, _ = env.step(env.action_space.sample())
            out += [obs, np.array([r])]
            if term or trunc:
                break
        return np.concatenate(out)

    np.testing.assert_array_equal(episode(7), episode(7))
    assert not np.array_equal(episode(7), episode(8))


def test_rewards_add_up_to_the_learned_progress_and_the_threshold_ends_it():
    """Moving A straight at B: the rewards sum to the model's progress; a collision ends the episode."""
    env = gym.make("l2p_bullet/Plan2D-v0", action="closer", max_steps=20)
    scene = random_scene(4)
    obs, info = env.reset(options={"scene": scene.to_dict()})
    start = info["progress"]
    total, done, info = 0.0, False, {}
    while not done:
        rel = obs[3:5] - obs[0:2]
        d = float(np.hypot(*rel))
        step = rel / d * min(1.0, d - 1.3)  # toward B, stopping short of touching it
        obs, r, term, trunc, info = env.step(np.array([*step, 0.0], np.float32))
        total += r
        done = term or trunc or np.hypot(*(obs[3:5] - obs[0:2])) < 1.35
    assert total == pytest.approx(info["progress"] - start, abs=1e-5)
    u = env.unwrapped
    assert u.model.final(u.frames, u.anchor_pose, u.block) == pytest.approx(info["progress"], abs=1e-6)
    if term or trunc:  # the episode is over (a step now asks for a reset): a new one from where A stopped
        obs, _ = env.reset(options={"scene": scene.with_pose("A", u.pose)})
    _, r, term, _, info = env.step(np.array([*(obs[3:5] - obs[0:2]), 0.0], np.float32))  # straight into B
    assert term and info["illegal"] == "collision" and r == 0.0
    assert np.array_equal(u.path[-1], u.pose)  # the block stayed where it was


@pytest.mark.slow
def test_arm_env_moves_the_simulated_block_and_renders():
    env = gym.make("l2p_bullet.envs:l2p_bullet/Arm-v0", action="closer", render_mode="rgb_array")
    check_env(env.unwrapped, skip_render_check=True)
    obs, _ = env.reset(seed=3)
    rel = obs[3:5] - obs[0:2]
    move = np.array([*(rel / np.hypot(*rel) * 1.0), 0.1], np.float32)  # one block towards B, turning 0.1 rad
    obs2, _, _, _, info = env.step(move)
    assert "illegal" not in info
    # observations are in blocks: where the simulated arm left the block, within 1 mm (0.02 block)
    np.testing.assert_allclose(obs2[:2], obs[:2] + move[:2], atol=0.02)
    assert obs2[2] == pytest.approx(obs[2] + move[2], abs=0.02)  # the block turned with the hand
    np.testing.assert_allclose(obs2[3:6], obs[3:6], atol=0.02)  # the anchor was not touched
    assert np.hypot(*(obs2[3:5] - obs2[0:2])) < np.hypot(*rel)  # closer, as asked
    img = env.render()
    assert img.shape == (240, 320, 3) and img.dtype == np.uint8 and img.std() > 5
    env.close()


@pytest.mark.slow
def test_the_docs_example_trains_and_performs(tmp_path):
    r = subprocess.run([sys.executable, "-W", "ignore", str(ROOT / "examples" / "plan2d_reinforce.py"),
                        "--action", "closer", "--episodes", "20", "--batch", "10", "--frame", str(tmp_path / "f.png")],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["episodes"] == 20 and out["arm_steps"] >= 1 and 0.0 <= out["arm_progress"] <= 1.0
    assert (tmp_path / "f.png").stat().st_size > 1000
