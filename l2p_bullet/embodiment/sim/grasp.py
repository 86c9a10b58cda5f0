"""The grasp: a JOINT_FIXED constraint between the tool and the block at their measured relative pose.

The closed fingers rest on the block's top (like a suction cup), so nothing of the gripper reaches down
beside the block. The constraint is created at the relative pose *measured* when the fingers touch,
never at a nominal one: a nominal pose a few millimetres off presses the block into the table (400 N,
tilted 37 degrees) or lifts it (DESIGN.md section 2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .robot import ARM

MAX_FORCE = 100.0  # N: holds a 0.1 kg block against table friction with a wide margin


@dataclass
class Grasp:
    """An active grasp. ``tool_z`` is the tool height measured at grasp time: the slide keeps it."""

    name: str
    constraint: int
    tool_z: float
    yaw_offset: float  # tool yaw minus block yaw at grasp time
    offset_xy: np.ndarray  # tool x-y minus block x-y at grasp time, in the block's frame
    tilt: float = 0.0  # the block's tilt (rad) at grasp time: a mesh may rest tilted on its feet


def attach(world, name: str) -> Grasp:
    """Fix block ``name`` to the tool where they are now."""
    robot = world.robot
    cid = world.sim.fix(ARM, robot.spec.tool_link, name, MAX_FORCE)
    t_pos, _ = robot.tool_pose()
    block = world.pose(name)
    tool_yaw = robot.tool_yaw()
    cy, sy = np.cos(block[3]), np.sin(block[3])
    d = np.array(t_pos[:2]) - block[:2]
    offset = np.array([cy * d[0] + sy * d[1], -sy * d[0] + cy * d[1]])
    return Grasp(name, cid, float(t_pos[2]), float(tool_yaw - block[3]), offset, float(world.tilt(name)))


def detach(world, grasp: Grasp) -> None:
    world.sim.remove_constraint(grasp.constraint)
