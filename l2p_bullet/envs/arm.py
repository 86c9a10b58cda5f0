"""``l2p_bullet/Arm-v0``: Plan2D-v0 with the Panda in PyBullet carrying out every move.

The spaces, the reward and the ends of an episode are Plan2D-v0's; the difference is who moves the
block. At reset the arm grasps the mover (a fixed constraint on its top, as in ``perform``); each legal
move is then slid by the arm (``Primitives.move``: ruckig timing, IK at 60 Hz, physics at 240 Hz), and
the observation and the learned progress read the block where the simulation left it, not where it
was told to go. A move the arm cannot make (out of reach, the grasp lost) ends the episode with
``info["illegal"] = "arm"`` and the reason in ``info["error"]``. ``render_mode="rgb_array"`` renders the
project's camera with TinyRenderer (320x240).

The environment keeps one World for its life and resets it to each episode's scene (``World.reset``:
the same simulation as a new world), so resets cost milliseconds, not a new simulator.

``obs_mode`` (state, rgb, rgbd, state+rgb), ``control_mode`` (block_delta, ee_delta_pos, joint_delta) and
``image_size`` choose what the agent sees and how it acts (envs/modes.py, docs/envs.md).
"""

from __future__ import annotations

import numpy as np

from ..arms import PANDA
from ..embodiment.execute import grasp_candidates
from ..embodiment.record import Recorder
from ..embodiment.sim.camera import Camera, RenderSettings
from ..embodiment.sim.primitives import Primitives
from ..embodiment.sim.world import World
from ..errors import L2PError
from ..judge import judge_for
from ..planning.problem import FRAME_STEP
from ..planning.world2d import segment_frames
from . import modes
from .checks import EnvResetNeeded, check_action
from .plan2d import Plan2DEnv

STEPS_PER_EPISODE = 600
"""The ee and joint modes' default ``max_steps``: 10 s of control at 60 Hz."""


class ArmEnv(Plan2DEnv):
    """See the module docstring; arguments as Plan2D-v0's."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 2}

    def __init__(self, *args, obs_mode: str = "state", control_mode: str = "block_delta",
                 image_size: tuple[int, int] = (128, 128), **kwargs):
        self.obs_mode, self.control_mode, self.image_size = modes.check_modes(obs_mode, control_mode, image_size)
        if self.control_mode != "block_delta" and "max_steps" not in kwargs and len(args) < 3:
            kwargs["max_steps"] = STEPS_PER_EPISODE
        super().__init__(*args, **kwargs)
        self.observation_space = modes.observation_space(self.obs_mode, self.observation_space, self.image_size)
        self.action_space = modes.action_space(self.control_mode, self.action_space, len(PANDA.arm_joints))
        self.judge = judge_for(self.bundle)
        self._world = None
        self._prims = None
        self._camera = None
        self._eye = None

    @property
    def instruction(self) -> str:
        return f"move {self.mover} {self.bundle.phrases[0] if self.bundle.phrases else self.action_name} {self.anchor}"

    def _start_episode(self) -> None:
        # Observation images do not need the arm's visual meshes: without them a 128x128 image costs 2 ms, not 20,
        # and the hand still shows (drawn from its collision shapes). render() draws the full arm.
        visuals = self.render_mode == "rgb_array"
        if self._world is None:
            self._world = World(self.scene, visuals=visuals)
        else:
            self._world.reset(self.scene)
        self._camera = Camera(self._world, RenderSettings(320, 240, renderer="tiny")) if visuals else None
        w, h = self.image_size
        self._eye = Camera(self._world, RenderSettings(w, h, renderer="tiny")) if self.obs_mode != "state" else None
        self._prims = Primitives(self._world, Recorder(self._world))  # trajectory frames at 30 fps: .recorder
        if self.control_mode != "block_delta":  # the agent grasps (or pushes) the block itself
            self.anchor_pose = self._block(self.anchor)
            self.pose = self._block(self.mover)
            self.frames = self.pose[None].copy()
            self.waypoints = [self.pose.copy()]
            return
        base = tuple(self._prims.robot.base_xyz[:2])
        # the grasp whose wrist sits nearest the middle of its range at the start (the moves are not known yet)
        offset = grasp_candidates(self.pose[None], [None], base)[0]
        self._prims.engage(self.mover, tool_yaw=float(self.pose[2] + offset))
        self.anchor_pose = self._block(self.anchor)  # where the physics settled it
        self.pose = self._block(self.mover)
        self.frames = self.pose[None].copy()
        self.waypoints = [self.pose.copy()]

    def _block(self, name: str) -> np.ndarray:
        x, y, _, yaw = self._world.pose(name)
        return np.array([x, y, yaw])

    def _anchor_now(self) -> np.ndarray:
        return self.anchor_pose if self._world is None else self._block(self.anchor)

    def _move(self, target: np.ndarray):
        try:
            self._prims.move(np.vstack([self.pose, target]))
        except L2PError as e:
            return None, {"illegal": "arm", "error": str(e)}
        return self._block(self.mover), {}

    # --- the modes ------------------------------------------------------------------------------
    def step(self, action):
        if self.control_mode == "block_delta":
            obs, reward, terminated, truncated, info = super().step(action)
            return obs, reward, terminated, truncated, info | self._judged()
        if self._no_episode is not None:
            raise EnvResetNeeded(f"Cannot call env.step() before calling env.reset(): {self._no_episode}")
        what = "dx, dy, dz, gripper" if self.control_mode == "ee_delta_pos" else "each joint's turn, gripper"
        a = check_action(action, self.action_space, what)
        self.steps += 1
        error = self._control(a)
        reached = self._block(self.mover)
        if float(np.hypot(*(reached[:2] - self.pose[:2]))) > 1e-4 or abs(reached[2] - self.pose[2]) > 1e-3:
            self.frames = np.vstack([self.frames, segment_frames(self.pose, reached, FRAME_STEP * self.block)])
            self.pose = reached
            self.waypoints.append(reached.copy())
        before, self.progress = self.progress, self._score()
        judged = self._judged()
        terminated = error is not None or judged["success"]
        truncated = not terminated and self.steps >= self.max_steps
        if terminated or truncated:
            self._no_episode = "the episode has ended (terminated or truncated)"
        info = self._info() | judged | ({} if error is None else {"illegal": "arm", "error": error})
        reward = (self.progress - before) - (self.illegal_penalty if error is not None else 0.0)
        return self._obs(), float(reward), terminated, truncated, info

    def _control(self, a: np.ndarray) -> str | None:
        """One control period of the ee or joint mode; the reason when the arm cannot do it."""
        prims, robot = self._prims, self._prims.robot
        try:
            if self.control_mode == "ee_delta_pos":
                target = prims.pose.copy()
                target[:3] += np.clip(a[:3], -1.0, 1.0) * modes.EE_STEP
                target[2] = max(float(target[2]), robot.drop + 0.002)  # the fingertips stay above the table
                q = prims.solve(target[None])[0]
            else:
                q = np.clip(prims.q + np.clip(a[:-1], -1.0, 1.0) * modes.JOINT_STEP, robot.kin.arm_lower,
                            robot.kin.arm_upper)
        except L2PError as e:
            return str(e)
        prims.step_to(q)
        self._grip(float(a[-1]) > 0.0)
        return None

    def _grip(self, close: bool) -> None:
        """Close: grasp the mover when the closed fingers are on its top; open: let go."""
        prims = self._prims
        if not close:
            prims.let_go()
        elif prims.grasp is None:
            block = self._world.pose(self.mover)
            above = prims.pose[2] - prims.grasp_height(self.mover)
            if np.hypot(*(prims.pose[:2] - block[:2])) <= self.block / 2 and -0.005 <= above <= modes.GRASP_REACH:
                prims.take(self.mover)

    def _info(self) -> dict:
        return super()._info() | {"instruction": self.instruction}

    def _judged(self) -> dict:
        verdict = self.judge.judge(self.frames, self._anchor_now(), self.block)
        return {"success": bool(verdict.success), "instruction": self.instruction}

    def _obs(self):
        state = super()._obs()
        images = None
        if self._eye is not None:
            # no shadows in observations: they double a small image's cost (docs/envs.md, "Speed")
            rgb, depth = (self._eye.render_rgbd(shadows=False) if self.obs_mode == "rgbd"
                          else (self._eye.render(shadows=False), None))
            images = {"rgb": rgb, "depth": depth}
        return modes.observe(self.obs_mode, state, images, self.instruction)

    def render(self):
        if self.render_mode != "rgb_array" or self._camera is None:
            return None
        return self._camera.render()

    def close(self) -> None:
        if self._world is not None:
            self._world.close()
            self._world = None
        super().close()
