"""The simulated world: one simulator (DIRECT) holding the table, the scene's blocks and an arm.

Nothing is global: every :class:`World` owns its own :class:`~.bullet.Bullet`, so two worlds (or two
tests) never see each other's bodies. The world frame is the scene frame lifted to 3-D: z = 0 is the
table top, so a block's centre height above the table is simply its z.

A world can be reused for run after run (a batch evaluator keeps one per worker process):
:meth:`World.reset` puts it in exactly the state of a new ``World(scene)``, so what a run records does
not depend on what the world did before.
"""

from __future__ import annotations

import math
from importlib import resources
from pathlib import Path

import numpy as np

from ...core.scene import COLORS, ROBOT_BASE_XY, Scene
from ...errors import SceneError
from .arms import PANDA, ArmSpec
from .bullet import Bullet
from .robot import ARM, Robot

PHYSICS_HZ = 240.0
BLOCK_URDF_SIZE = 0.05  # the side of urdf/block.urdf; other sizes load it with globalScaling
BLOCK_MASS, BLOCK_FRICTION = 0.1, 0.5  # urdf/block.urdf's: what a box, cylinder or mesh gets unless told
TABLE = "<table>"  # the table's body name (blocks go by their scene names, the arm is robot.ARM)


def urdf_path(name: str) -> str:
    """Absolute path of a URDF the project ships (inside the installed package)."""
    return str(Path(str(resources.files("l2p_bullet") / "urdf" / name)))


class World:
    """Table + blocks + arm in one DIRECT simulator. Close it (or use ``with``) when done.

    ``visuals=False`` loads the arm without its visual meshes (for runs that render nothing).
    ``egl=True`` loads PyBullet's EGL renderer plugin first: bodies loaded before it never reach it
    (their images come out empty).
    """

    def __init__(self, scene: Scene, arm: ArmSpec = PANDA, visuals: bool = True, egl: bool = False):
        self.sim = Bullet()
        self.visuals = visuals
        self.dt = 1.0 / PHYSICS_HZ
        self.robot: Robot | None = None
        try:
            self.sim.set_physics(self.dt)
            if egl:
                self.sim.load_egl()
            self.robot = Robot(self.sim, arm, base_xyz=(ROBOT_BASE_XY[0], ROBOT_BASE_XY[1], 0.0), visuals=visuals)
            self._load(scene)
        except BaseException:
            self.close()
            raise

    def _load(self, scene: Scene) -> None:
        """Table, then the blocks in scene order, then the arm at home: the same order every time, so the
        physics engine's internal order (which decides the last bits of a result) is the same too."""
        reserved = [o.name for o in scene.objects if o.name in (TABLE, ARM)]
        if reserved:
            raise SceneError(f'"{reserved[0]}" is reserved for the simulator; name the block otherwise')
        sim = self.sim
        self.scene = scene  # what the world was loaded with (a film's painters load the same)
        self.steps = 0
        sim.load_urdf(TABLE, urdf_path("table.urdf"), (0.0, 0.0, 0.0), fixed=True)
        self.sizes: dict[str, float] = {}
        self.heights: dict[str, float] = {}  # each object's top above the table, standing
        self.rests: dict[str, float] = {}  # each object's centre (of mass) above the table, standing
        for o in scene.objects:
            orn = sim.quaternion(0.0, 0.0, o.yaw)
            if o.shape == "cube":
                sim.load_urdf(o.name, urdf_path("block.urdf"), (o.xy[0], o.xy[1], o.size / 2), orn,
                              scale=o.size / BLOCK_URDF_SIZE)
                rest = o.size / 2
            else:  # its convex hull, its centre of mass at the body's origin (core/shapes.py)
                g = o.geometry
                rest = g.rest
                sim.load_convex(o.name, g.points, (o.xy[0], o.xy[1], rest), orn,
                                mass=BLOCK_MASS if o.mass is None else o.mass, faces=g.faces)
                sim.set_dynamics(o.name, friction=BLOCK_FRICTION)
            sim.set_dynamics(o.name, mass=o.mass, friction=o.friction)
            sim.set_color(o.name, COLORS[o.color])
            self.sizes[o.name] = o.size
            self.heights[o.name] = o.height
            self.rests[o.name] = rest
        self.robot.load()

    def reset(self, scene: Scene) -> None:
        """Start over with ``scene``: old blocks and any grasp gone, the new blocks in place, the arm at
        home, the step counter at zero. Afterwards the world simulates exactly like ``World(scene)`` made
        with the same arm, visuals and renderer (what a run records is byte-identical)."""
        self.sim.reset()
        self._load(scene)

    # --- state -----------------------------------------------------------------------------
    def pose(self, name: str) -> np.ndarray:
        """[x, y, z, yaw] of a block (z: its centre above the table top)."""
        pos, orn = self.sim.base_pose(name)
        x, y, z, w = orn
        yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
        return np.array([pos[0], pos[1], pos[2], yaw])

    def tilt(self, name: str) -> float:
        """Angle (radians) between the block's up axis and the world's: 0 when it sits flat."""
        _, orn = self.sim.base_pose(name)
        m = self.sim.rotation_matrix(orn)
        # m is row-major: the world z components of the block's three axes are m[6], m[7], m[8];
        # a cube may rest on any face, so take the axis closest to vertical.
        return math.acos(min(1.0, max(abs(m[6]), abs(m[7]), abs(m[8]))))

    def poses(self) -> dict[str, np.ndarray]:
        """Every block's :meth:`pose`, in scene order."""
        return {name: self.pose(name) for name in self.sizes}

    @property
    def time(self) -> float:
        return self.steps * self.dt

    def step(self) -> None:
        self.sim.step()
        self.steps += 1

    def close(self) -> None:
        """Disconnect the simulator and the arm's IK twin (idempotent)."""
        if self.robot is not None:
            self.robot.close()
        self.sim.close()

    def __enter__(self) -> World:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
