"""Arm-v0's observation and control modes, named as ManiSkill names them where they fit.

Observation modes (``obs_mode``):

- ``state``: the 7 numbers of Plan2D-v0 (a ``Box``), unchanged; the instruction is ``info["instruction"]``;
- ``rgb``, ``rgbd``, ``state+rgb``: a ``Dict`` with ``rgb`` (H, W, 3 uint8, the project's camera behind the
  robot), ``depth`` (H, W, 1 float32, metres from the camera; rgbd), ``state`` (state+rgb) and
  ``instruction`` (the sentence, text). Images are ``image_size`` (width, height), 128x128 by default.

Control modes (``control_mode``):

- ``block_delta``: a move of the block (dx, dy, dyaw in block units), slid there by the arm (Plan2D-v0's
  action; the arm grasps the block at reset);
- ``ee_delta_pos``: (dx, dy, dz, gripper): the tool moves at most ``EE_STEP`` metres per axis in one control
  period (1/60 s), pointing down; gripper > 0 closes (a grasp by constraint when the closed fingers are on
  the block's top, as ``perform`` grasps), <= 0 opens;
- ``joint_delta``: (dq_1 ... dq_n, gripper): each joint moves at most ``JOINT_STEP`` rad in one control
  period, within its limits.

In every mode the reward is the increase of the action's learned progress over the mover's motion so far
(dense) and ``info["success"]`` is the action's rule judge on that motion; the ee and joint modes end an
episode when the judge accepts it, block_delta when the progress reaches the threshold, as before.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces

from .checks import EnvError

OBS_MODES = ("state", "rgb", "rgbd", "state+rgb")
CONTROL_MODES = ("block_delta", "ee_delta_pos", "joint_delta")
EE_STEP = 0.01
"""Metres per axis the tool may move in one control period (0.6 m/s at 60 Hz)."""
JOINT_STEP = 0.05
"""Radians a joint may turn in one control period."""
GRASP_REACH = 0.015
"""Metres above the block's top (and half a side across) within which a closing gripper grasps it."""
MAX_TEXT = 200


def check_modes(obs_mode: object, control_mode: object, image_size: object) -> tuple[str, str, tuple[int, int]]:
    """The modes and the image size, or a one-line EnvError naming what is known."""
    if obs_mode not in OBS_MODES:
        raise EnvError(f"obs_mode must be one of {', '.join(OBS_MODES)} (got {obs_mode!r})")
    if control_mode not in CONTROL_MODES:
        raise EnvError(f"control_mode must be one of {', '.join(CONTROL_MODES)} (got {control_mode!r})")
    try:
        w, h = (int(v) for v in image_size)  # type: ignore[union-attr]
    except (TypeError, ValueError):
        raise EnvError(f"image_size must be (width, height) in pixels (got {image_size!r})") from None
    if not (16 <= w <= 1024 and 16 <= h <= 1024) or (w, h) != tuple(image_size):  # type: ignore[arg-type]
        raise EnvError(f"image_size must be two whole numbers of 16 to 1024 pixels (got {image_size!r})")
    return str(obs_mode), str(control_mode), (w, h)


def observation_space(obs_mode: str, state: spaces.Box, size: tuple[int, int]) -> spaces.Space:
    if obs_mode == "state":
        return state
    w, h = size
    parts: dict[str, spaces.Space] = {"rgb": spaces.Box(0, 255, (h, w, 3), np.uint8)}
    if obs_mode == "rgbd":
        parts["depth"] = spaces.Box(0.0, np.inf, (h, w, 1), np.float32)
    if obs_mode == "state+rgb":
        parts["state"] = state
    parts["instruction"] = spaces.Text(MAX_TEXT, charset=_CHARSET)
    return spaces.Dict(parts)


_CHARSET = frozenset(chr(c) for c in range(32, 127))


def action_space(control_mode: str, block: spaces.Box, joints: int) -> spaces.Box:
    if control_mode == "block_delta":
        return block
    n = 3 if control_mode == "ee_delta_pos" else joints
    return spaces.Box(-np.ones(n + 1, np.float32), np.ones(n + 1, np.float32), dtype=np.float32)


def observe(obs_mode: str, state: np.ndarray, images: dict[str, np.ndarray] | None, instruction: str) -> Any:
    if obs_mode == "state":
        return state
    assert images is not None
    out: dict[str, Any] = {"rgb": images["rgb"]}
    if obs_mode == "rgbd":
        out["depth"] = images["depth"]
    if obs_mode == "state+rgb":
        out["state"] = state
    out["instruction"] = "".join(c for c in instruction if c in _CHARSET)[:MAX_TEXT]
    return out
