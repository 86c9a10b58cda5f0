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
"""

from __future__ import annotations

import numpy as np

from ..embodiment.execute import grasp_candidates
from ..embodiment.record import Recorder
from ..embodiment.sim.camera import Camera, RenderSettings
from ..embodiment.sim.primitives import Primitives
from ..embodiment.sim.world import World
from ..errors import L2PError
from .plan2d import Plan2DEnv


class ArmEnv(Plan2DEnv):
    """See the module docstring; arguments as Plan2D-v0's."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 2}

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._world = None
        self._prims = None
        self._camera = None

    def _start_episode(self) -> None:
        visuals = self.render_mode == "rgb_array"
        if self._world is None:
            self._world = World(self.scene, visuals=visuals)
        else:
            self._world.reset(self.scene)
        self._camera = Camera(self._world, RenderSettings(320, 240, renderer="tiny")) if visuals else None
        self._prims = Primitives(self._world, Recorder(self._world))  # trajectory frames at 30 fps: .recorder
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

    def render(self):
        if self.render_mode != "rgb_array" or self._camera is None:
            return None
        return self._camera.render()

    def close(self) -> None:
        if self._world is not None:
            self._world.close()
            self._world = None
        super().close()
