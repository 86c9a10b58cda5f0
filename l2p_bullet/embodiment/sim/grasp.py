"""The grasp: a JOINT_FIXED constraint between the tool and the block at their measured relative pose.

The closed fingers rest on the block's top (like a suction cup), so nothing of the gripper reaches down
beside the block. The constraint is created at the relative pose *measured* when the fingers touch,
never at a nominal one: a nominal pose a few millimetres off presses the block into the table (400 N,
tilted 37 degrees) or lifts it (DESIGN.md section 2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

MAX_FORCE = 100.0  # N: holds a 0.1 kg block against table friction with a wide margin


@dataclass
class Grasp:
    """An active grasp. ``tool_z`` is the tool height measured at grasp time: the slide keeps it."""

    name: str
    body: int
    constraint: int
    tool_z: float
    yaw_offset: float  # tool yaw minus block yaw at grasp time
    offset_xy: np.ndarray  # tool x-y minus block x-y at grasp time, in the block's frame


def attach(world, name: str) -> Grasp:
    """Fix block ``name`` to the tool where they are now."""
    c, robot = world.client, world.robot
    body = world.bodies[name]
    tool = c.getLinkState(robot.body, robot.spec.tool_link, computeForwardKinematics=True)
    t_pos = tool[4]
    b_pos, b_orn = c.getBasePositionAndOrientation(body)
    # PyBullet places a constraint's parent frame relative to the link's centre of mass frame.
    com_pos, com_orn = tool[0], tool[1]
    inv_pos, inv_orn = c.invertTransform(com_pos, com_orn)
    par_pos, par_orn = c.multiplyTransforms(inv_pos, inv_orn, b_pos, b_orn)
    cid = c.createConstraint(robot.body, robot.spec.tool_link, body, -1, world.pb.JOINT_FIXED, [0, 0, 0],
                             parentFramePosition=par_pos, childFramePosition=[0, 0, 0],
                             parentFrameOrientation=par_orn, childFrameOrientation=[0, 0, 0, 1])
    c.changeConstraint(cid, maxForce=MAX_FORCE)
    block = world.pose(name)
    tool_yaw = robot.tool_yaw()
    cy, sy = np.cos(block[3]), np.sin(block[3])
    d = np.array(t_pos[:2]) - block[:2]
    offset = np.array([cy * d[0] + sy * d[1], -sy * d[0] + cy * d[1]])
    return Grasp(name, body, cid, float(t_pos[2]), float(tool_yaw - block[3]), offset)


def detach(world, grasp: Grasp) -> None:
    world.client.removeConstraint(grasp.constraint)


def constraint_count(world) -> int:
    return world.client.getNumConstraints()
