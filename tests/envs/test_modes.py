"""Arm-v0's observation and control modes: every combination passes Gymnasium's checker, images have the
size asked for, the instruction is in the observation, the vector envs run, and bad modes are one-line
errors."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import l2p_bullet.envs  # noqa: F401 - registers the ids
from l2p_bullet.envs.checks import EnvError
from l2p_bullet.envs.modes import CONTROL_MODES, OBS_MODES

pytestmark = pytest.mark.slow


@pytest.mark.parametrize("control_mode", CONTROL_MODES)
@pytest.mark.parametrize("obs_mode", OBS_MODES)
def test_every_mode_passes_gymnasiums_checker(obs_mode, control_mode):
    env = gym.make("l2p_bullet/Arm-v0", action="closer", obs_mode=obs_mode, control_mode=control_mode,
                   image_size=(48, 32))
    try:
        check_env(env.unwrapped, skip_render_check=True)
        obs, info = env.reset(seed=3)
        assert env.observation_space.contains(obs)
        assert info["instruction"] == "move A closer to B"
        if obs_mode != "state":
            assert obs["rgb"].shape == (32, 48, 3) and obs["rgb"].dtype == np.uint8
            assert obs["instruction"] == "move A closer to B"
            assert obs["rgb"].std() > 5, "the image shows nothing"
        if obs_mode == "rgbd":
            assert obs["depth"].shape == (32, 48, 1) and 0.1 < float(obs["depth"].min()) < 3.0 <= float(
                obs["depth"].max()
            )
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        assert np.isfinite(reward) and isinstance(info["success"], bool)
    finally:
        env.close()


def test_ee_control_moves_the_tool_and_a_closed_gripper_on_the_block_grasps_it():
    env = gym.make("l2p_bullet/Arm-v0", action="around", control_mode="ee_delta_pos", max_steps=1000).unwrapped
    try:
        env.reset(seed=0)
        prims = env._prims
        block = env._world.pose("A")
        for _ in range(400):  # fly to above the block, then down onto its top
            err = np.r_[block[:2] - prims.pose[:2], prims.grasp_height("A") - prims.pose[2]]
            if np.abs(err).max() < 0.002:
                break
            env.step(np.r_[np.clip(err / 0.01, -1, 1), -1.0])
        env.step(np.array([0.0, 0.0, 0.0, 1.0]))
        assert prims.grasp is not None, "closing on the block's top grasps it"
        start = env._world.pose("A")
        for _ in range(15):
            *_, terminated, truncated, info = env.step(np.array([1.0, 0.0, 0.0, 1.0]))
            assert not (terminated or truncated), info
        assert env._world.pose("A")[0] > start[0] + 0.1, "the grasped block follows the tool"
        assert len(env.frames) > 1
    finally:
        env.close()


def test_vector_envs_sync_and_async():
    fns = [lambda: gym.make("l2p_bullet/Arm-v0", action="closer", obs_mode="rgb", control_mode="joint_delta",
                            image_size=(32, 32)) for _ in range(2)]
    for vec in (gym.vector.SyncVectorEnv(fns), gym.vector.AsyncVectorEnv(fns)):
        try:
            obs, _ = vec.reset(seed=1)
            assert obs["rgb"].shape == (2, 32, 32, 3)
            obs, reward, term, trunc, info = vec.step(vec.action_space.sample())
            assert reward.shape == (2,) and obs["rgb"].shape == (2, 32, 32, 3)
        finally:
            vec.close()


@pytest.mark.parametrize("kw, said", [
    ({"obs_mode": "pixels"}, "obs_mode must be one of state, rgb, rgbd, state+rgb"),
    ({"control_mode": "torque"}, "control_mode must be one of block_delta, ee_delta_pos, joint_delta"),
    ({"image_size": (8, 8)}, "image_size"),
    ({"image_size": "big"}, "image_size"),
])
def test_bad_modes_are_one_line_errors(kw, said):
    with pytest.raises(EnvError, match=said.replace("+", r"\+")):
        gym.make("l2p_bullet/Arm-v0", action="closer", **kw)


def test_a_wrong_sized_action_says_what_the_mode_wants():
    env = gym.make("l2p_bullet/Arm-v0", action="closer", control_mode="ee_delta_pos").unwrapped
    try:
        env.reset(seed=0)
        with pytest.raises(EnvError, match=r"4 numbers \(dx, dy, dz, gripper\)"):
            env.step(np.zeros(3))
    finally:
        env.close()
