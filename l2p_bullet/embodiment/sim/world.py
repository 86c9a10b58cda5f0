"""The simulated world: one PyBullet client (DIRECT) holding the table, the scene's blocks and an arm.

Nothing is global: every :class:`World` owns its own ``BulletClient``, so two worlds (or two tests)
never see each other's bodies. The world frame is the scene frame lifted to 3-D: z = 0 is the table top,
so a block's centre height above the table is simply its z.
"""

from __future__ import annotations

import math
from importlib import resources
from pathlib import Path

import numpy as np

from ...core.scene import COLORS, ROBOT_BASE_XY, Scene
from .arms import PANDA, ArmSpec
from .client import new_client, quiet_stdout

PHYSICS_HZ = 240.0
BLOCK_URDF_SIZE = 0.05  # the side of urdf/block.urdf; other sizes load it with globalScaling


def urdf_path(name: str) -> str:
    """Absolute path of a URDF the project ships (inside the installed package)."""
    return str(Path(str(resources.files("l2p_bullet") / "urdf" / name)))


def load_egl(client) -> int:
    """Load the EGL renderer plugin into ``client``; ExecutionError where it does not load."""
    import importlib.util

    from ...errors import ExecutionError

    spec = importlib.util.find_spec("eglRenderer")
    with quiet_stdout():
        plugin = client.loadPlugin(spec.origin, "_eglRendererPlugin") if spec and spec.origin else -1
    if plugin < 0:
        raise ExecutionError("the EGL renderer plugin does not load here; use --renderer tiny")
    return plugin


class World:
    """Table + blocks + arm in one DIRECT PyBullet client. Close it (or use ``with``) when done.

    ``visuals=False`` loads the arm without its visual meshes (for runs that render nothing).
    ``egl=True`` loads PyBullet's EGL renderer plugin first: bodies loaded before it never reach it
    (their images come out empty).
    """

    def __init__(self, scene: Scene, arm: ArmSpec = PANDA, visuals: bool = True, egl: bool = False):
        self.client = new_client()
        import pybullet as pb

        self.pb = pb
        self.scene = scene
        c = self.client
        self.cid = c._client  # hot paths call pybullet directly with it (no wrapper per call)
        c.setGravity(0, 0, -9.81)
        c.setTimeStep(1.0 / PHYSICS_HZ)
        self.dt = 1.0 / PHYSICS_HZ
        self.egl_plugin = load_egl(c) if egl else None
        self.steps = 0
        self.table = c.loadURDF(urdf_path("table.urdf"), [0, 0, 0], useFixedBase=True)
        self.bodies: dict[str, int] = {}
        self.sizes: dict[str, float] = {}
        for o in scene.objects:
            body = c.loadURDF(
                urdf_path("block.urdf"),
                [o.xy[0], o.xy[1], o.size / 2],
                c.getQuaternionFromEuler([0, 0, o.yaw]),
                globalScaling=o.size / BLOCK_URDF_SIZE,
            )
            c.changeVisualShape(body, -1, rgbaColor=COLORS[o.color])
            self.bodies[o.name] = body
            self.sizes[o.name] = o.size
        from .robot import Robot  # local: robot imports world's constants

        self.robot = Robot(self, arm, base_xyz=(ROBOT_BASE_XY[0], ROBOT_BASE_XY[1], 0.0), visuals=visuals)

    # --- state -----------------------------------------------------------------------------
    def pose(self, name: str) -> np.ndarray:
        """[x, y, z, yaw] of a block (z: its centre above the table top)."""
        pos, orn = self.pb.getBasePositionAndOrientation(self.bodies[name], physicsClientId=self.cid)
        x, y, z, w = orn
        yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
        return np.array([pos[0], pos[1], pos[2], yaw])

    def tilt(self, name: str) -> float:
        """Angle (radians) between the block's up axis and the world's: 0 when it sits flat."""
        _, orn = self.client.getBasePositionAndOrientation(self.bodies[name])
        m = self.client.getMatrixFromQuaternion(orn)
        # m is row-major: the world z components of the block's three axes are m[6], m[7], m[8];
        # a cube may rest on any face, so take the axis closest to vertical.
        return math.acos(min(1.0, max(abs(m[6]), abs(m[7]), abs(m[8]))))

    def poses(self) -> dict[str, np.ndarray]:
        return {name: self.pose(name) for name in self.bodies}

    @property
    def time(self) -> float:
        return self.steps * self.dt

    def step(self) -> None:
        self.pb.stepSimulation(physicsClientId=self.cid)
        self.steps += 1

    def close(self) -> None:
        if self.client is not None:
            with quiet_stdout():  # the EGL plugin says goodbye on the C-level stdout
                self.client.disconnect()
            self.client = None

    def __enter__(self) -> World:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
