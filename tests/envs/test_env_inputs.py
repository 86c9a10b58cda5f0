"""What a user hands Plan2D-v0 / Arm-v0: bad actions, bad reset options and constructor arguments, a failed
reset, a step after the end. Each is a one-line L2PError (the audit found numpy and attribute errors from
deep inside, silently accepted values, and a failed reset that left the old pose in the new scene)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.error import ResetNeeded

import l2p_bullet.envs  # noqa: F401 - registers the ids (Gymnasium 1.x)
from l2p_bullet.core.scene import default_scene
from l2p_bullet.envs.plan2d import Plan2DEnv
from l2p_bullet.errors import L2PError, SceneError, UnknownObjectError

PLAN2D = "l2p_bullet/Plan2D-v0"


@pytest.fixture(autouse=True)
def _quiet_checker(recwarn):
    """Gymnasium's passive checker warns about the actions these tests get wrong on purpose."""


@pytest.fixture
def env():
    e = gym.make(PLAN2D, action="closer")
    e.reset(seed=1)
    return e


@pytest.mark.parametrize("bad", [np.array([np.nan, 0, 0], np.float32), np.zeros(2), np.zeros(4), np.zeros((2, 3)),
                                 None, 1, "abc", [1.0, None, 2.0]])
def test_a_bad_action_is_a_one_line_error_naming_the_action_space(env, bad):
    with pytest.raises(L2PError, match=r"^an action must be 3 numbers \(dx, dy, dyaw\) in the action space Box\(3,\)"):
        env.step(bad)


def test_nan_does_not_end_the_episode_and_inf_is_clipped(env):
    u = env.unwrapped
    with pytest.raises(L2PError, match="NaN"):
        env.step(np.array([np.nan, 0, 0], np.float32))
    assert u.steps == 0  # nothing happened: the episode goes on
    start = u.pose.copy()
    _, _, term, _, info = env.step(np.array([[np.inf], [0.0], [0.0]]))  # (3, 1) holds 3 numbers: accepted
    assert "illegal" not in info and not term
    np.testing.assert_allclose(u.pose[:2] - start[:2], [2.0 * u.block, 0.0])  # clipped to max_move


@pytest.mark.parametrize(("options", "error", "match"), [
    ({"mover": "Z"}, UnknownObjectError, 'no object named "Z"'),
    ({"anchor": "Z"}, UnknownObjectError, 'no object named "Z"'),
    ({"mover": "A", "anchor": "A"}, L2PError, "mover and the anchor are both"),
    ({"mover": 3}, L2PError, r"options\['mover'\] must be an object's name"),
    ({"scen": {}}, L2PError, r"unknown reset option 'scen'.*Did you mean \"scene\""),
    ({"scene": "scene.json"}, SceneError, r"options\['scene'\] must be a Scene or a dict.*load_scene"),
    ({"scene": {"foo": 1}}, SceneError, r"options\['scene'\]"),
    ("scene.json", L2PError, "reset options must be a dict"),
])
def test_bad_reset_options_fail_before_anything_changes_and_step_then_needs_a_reset(env, options, error, match):
    u = env.unwrapped
    env.step(np.array([0.5, 0.0, 0.0], np.float32))
    before = (u.scene, u.mover, u.anchor, u.pose.copy(), u.steps)
    with pytest.raises(error, match=match):
        env.reset(seed=2, options=options)
    assert (u.scene, u.mover, u.anchor, u.steps) == before[:3] + before[4:]
    np.testing.assert_array_equal(u.pose, before[3])
    for e in (env, u):  # wrapped or not: the same "call reset() first" as before the first reset
        with pytest.raises(ResetNeeded, match=r"^Cannot call env\.step\(\) before calling env\.reset\(\)"):
            e.step(np.zeros(3, np.float32))
    env.reset(seed=2)
    env.step(np.zeros(3, np.float32))  # a good reset starts an episode again


def test_step_before_any_reset_is_the_same_error_unwrapped():
    u = gym.make(PLAN2D, action="closer").unwrapped
    with pytest.raises(ResetNeeded, match="no episode has started") as info:
        u.step(np.zeros(3, np.float32))
    assert isinstance(info.value, L2PError)


def test_a_scene_object_or_dict_is_accepted(env):
    scene = default_scene()
    obs_obj, _ = env.reset(options={"scene": scene})
    obs_dict, _ = env.reset(options={"scene": scene.to_dict()})
    np.testing.assert_array_equal(obs_obj, obs_dict)
    # ... and the episode starts in that scene: A and B where it puts them (block units about the centre)
    a, b = scene.get("A"), scene.get("B")
    np.testing.assert_allclose(obs_dict[:6], [a.xy[0] / a.size, a.xy[1] / a.size, a.yaw,
                                              b.xy[0] / a.size, b.xy[1] / a.size, b.yaw], atol=1e-6)
    assert env.unwrapped.scene.to_dict() == scene.to_dict()


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"size": "a"}, r"^size \(the block side, m\) must be a finite number in \[0.02, 0.08\], got 'a'$"),
    ({"size": 0.01}, r"size .* in \[0.02, 0.08\]"),
    ({"size": 0.5}, r"size .* in \[0.02, 0.08\]"),
    ({"max_move": -1}, r"^max_move must be a finite number > 0, got -1$"),
    ({"max_move": float("nan")}, "max_move must be a finite number > 0"),
    ({"max_steps": -1}, r"^max_steps must be a whole number >= 1, got -1$"),
    ({"max_steps": 2.5}, "max_steps must be a whole number"),
    ({"threshold": 5}, r"^threshold must be a finite number in \(0, 1\], got 5$"),
    ({"threshold": 0}, r"threshold must be a finite number in \(0, 1\]"),
    ({"illegal_penalty": float("inf")}, "illegal_penalty must be a finite number"),
    ({"render_mode": "bogus"}, "render_mode must be one of"),
])
def test_bad_constructor_arguments_are_one_line_errors(kwargs, match):
    with pytest.raises(L2PError, match=match) as info:
        Plan2DEnv(action="closer", **kwargs)  # not gym.make: it turns render_mode="human" into a wrapper
    assert isinstance(info.value, ValueError)  # what a bad size or render_mode raised before
    assert "\n" not in str(info.value)


def test_step_after_the_episode_ended_needs_a_reset():
    env = gym.make(PLAN2D, action="closer", max_steps=2)
    env.reset(seed=1)
    env.step(np.zeros(3, np.float32))
    *_, term, trunc, _ = env.step(np.zeros(3, np.float32))
    assert trunc and not term
    with pytest.raises(ResetNeeded, match="the episode has ended"):
        env.step(np.zeros(3, np.float32))
    env.reset(seed=1)
    env.step(np.zeros(3, np.float32))


@pytest.mark.slow
def test_arm_env_after_a_failed_reset_needs_a_reset():
    """Arm-v0 raised a KeyError deep inside its step after a reset with an unknown mover."""
    env = gym.make("l2p_bullet/Arm-v0", action="closer")
    try:
        env.reset(seed=0)
        with pytest.raises(UnknownObjectError):
            env.reset(seed=1, options={"mover": "Z"})
        with pytest.raises(ResetNeeded, match="the last reset"):
            env.step(np.zeros(3, np.float32))
        env.reset(seed=1)
        with pytest.raises(L2PError, match="NaN"):
            env.step(np.array([np.nan, 0, 0], np.float32))
    finally:
        env.close()
