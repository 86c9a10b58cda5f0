"""What an arm is, as data: :class:`ArmSpec`, so that a second arm is a new entry, not new code.

Everything the simulator needs to know about an arm lives here: where its description (URDF or SDF) is,
which joints move it, which link is the tool point, how its fingers close and which joint positions seed
inverse kinematics; and what the planner needs: its reach ring on the table, its hand's profile beside a
block, its wrist's range, its gripper's opening. The controller, IK and grasp code (embodiment) and the
planner (planning) read only these fields; nothing here loads a simulator.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..core.scene import ROBOT_BASE_XY

IK_RESTARTS = 12
"""First guesses IK draws within the joint limits when an arm's seeds fail (``ArmSpec.ik_restarts``): enough for a
UR5e from a seed half a turn off (tests/embodiment/test_arm_compose.py); they cost nothing where a seed succeeds."""


@dataclass(frozen=True)
class ArmSpec:
    """One arm. Joint indices are PyBullet joint indices in the arm's URDF."""

    name: str
    urdf: str  # path relative to pybullet_data, or absolute
    arm_joints: tuple[int, ...]  # the joints IK drives, base to wrist
    tool_link: int  # the link whose pose the controller commands (between the closed fingertips)
    finger_joints: tuple[int, ...]
    finger_closed: tuple[float, ...]  # finger joint positions with the fingers closed
    home: tuple[float, ...]  # arm joint positions at rest, hand above the table pointing down
    ik_seeds: tuple[tuple[float, ...], ...]  # extra IK seeds: one seed alone fails near the base
    wrist_joint: int  # the joint that turns the hand about the vertical (its range bounds the yaw)
    down_euler: tuple[float, float] = (math.pi, 0.0)  # roll, pitch of the tool pointing down
    position_gain: float = 0.6  # 0.1 lags 10 mm, 0.6 lags 0.7 mm (DESIGN.md section 2)
    fingertip_links: tuple[int, ...] = ()  # links whose lowest point rests on the block's top
    wrist_limit: float = math.pi  # |wrist joint| <= this (radians): bounds the tool's yaw
    # The arm's plane: with these joints (indices into arm_joints) at zero the arm stands in the vertical
    # plane at the base joint's angle, the tool's azimuth seen from the base is the base joint's angle and
    # wrist = wrist_offset + azimuth - tool yaw. IK first guesses are put in that plane (the 7th joint's
    # freedom would otherwise let solutions drift out of it over a long motion, until a joint limit
    # forces a flip), so the wrist model of arms/reach.py holds. ``wrist_offset`` is measured, as ``new-arm``
    # measures it (embodiment.arm_measure.wrist_offset), for every arm.
    swivel_joints: tuple[int, ...] = ()
    wrist_offset: float = 0.0
    # Links loaded without collision shapes: they stay far above every block (for the Panda the base, the
    # shoulder, the upper arm and the forearm, at least 11.7 cm above the held block's top anywhere in the
    # workspace, tests/embodiment/test_robustness.py) and their meshes cost most of the arm's load time and a tenth
    # of every physics step.
    collision_free_links: tuple[str, ...] = ()
    # (depth, hx, hy): every collision shape of the hand and fingers lower than ``depth`` above the fingertips
    # lies within +-hx along the tool's x axis and +-hy across it (metres, Bullet's collision margin
    # included); what the arm puts at the height of a block taller than the one it holds. Measured by
    # Robot.hand_profile; tests/embodiment/test_robustness.py re-measures it.
    hand_profile: tuple[tuple[float, float, float], ...] = ()
    # The widest gap the open fingers leave between their inner faces (metres): an object whose narrowest
    # graspable width (at a yaw the wrist can reach) is wider cannot be grasped by this arm, and a manner
    # that closes the fingers across an object checks it. Panda: two prismatic fingers of 0-4 cm each.
    gripper_opening: float = 0.08
    # What the arm may carry (kg): its maker's rated payload. A carry refuses a heavier object up front
    # (the grasp is a constraint, which would lift anything). 1 kg when unknown: a user's arm says its own.
    payload: float = 1.0
    # A tool point the description itself lacks (the xArm's and the KUKA's have no link between their
    # fingertips): (parent link name, xyz in the parent's frame); :func:`~l2p_bullet.embodiment.sim.arms.arm_urdf` adds
    # a fixed massless link
    # "l2p_tool" there, and ``tool_link`` is its index (the last joint).
    tool_frame: tuple[str, tuple[float, float, float]] | None = None
    # Joints made fixed in the loaded copy: free joints that are neither the arm's nor the fingers' (the
    # KUKA's gripper swivel and fingertip hinges would otherwise flop under gravity and pull IK off).
    fixed_joints: tuple[str, ...] = ()
    # (near, far): the horizontal distances (m) from the base between which the tool reaches the table pointing
    # down at every height a run uses (grasp to hover, any yaw the wrist allows); measured by
    # ``l2p-bullet arms --check`` (embodiment/arm_measure.py). Where this ring does not hold the scene's workspace
    # disk, the workspace is the disk cut by the ring (core/workspace.py), which keeps all the arm reaches.
    reach: tuple[float, float] = (0.25, 0.78)
    # Where the arm's base frame stands in the scene frame (m): off the table's near edge, facing +x. An arm
    # whose reach ring is narrower or shifted (the KUKA's is 0.43-0.77 m) stands where its ring best holds
    # the workspace disk, as a lab would mount it; the default is the Panda's (core.scene.ROBOT_BASE_XY).
    mount: tuple[float, float, float] = (ROBOT_BASE_XY[0], ROBOT_BASE_XY[1], 0.0)
    description: str = ""
    # Extra first guesses IK tries when the seeds fail: joints drawn within their limits (embodiment/sim/robot.py),
    # one inverse kinematics for every arm, the built-in ones included. Their seeds succeed wherever the ring
    # measurement looked, so restarts cost only a refusal's time; an arm whose seeds miss (a UR5e from a seed
    # half a turn off) needs them. 0 turns them off.
    ik_restarts: int = IK_RESTARTS
    # How far (rad) the wrist joint strays from ``wrist_offset + azimuth - yaw`` over the reach ring, measured by
    # ``new-arm`` and for the built-in arms by tests/embodiment/test_general_ik.py (embodiment.arm_measure.wrist_stray):
    # the planner keeps the wrist this much further from its limits.
    wrist_error: float = 0.0
    # Gripper joints that follow another (URDF ``<mimic>``, which PyBullet ignores): (joint, leader, multiplier,
    # offset), joint indices. The fingers are driven together: every gripper joint's target is its leader's
    # times the multiplier plus the offset, as a four-bar linkage (the Robotiq 2F-85's) moves.
    finger_mimic: tuple[tuple[int, int, float, float], ...] = ()
    # The reach ring at each tool height alone: ((height, near, far), ...) metres, one row per height the ring is
    # measured at (embodiment/arm_measure.py: REACH_HEIGHTS), written by ``new-arm``; ``reach`` is their narrowest
    # (the greatest near, the least far). A scene is held to the rows its blocks ask for (arms/fit.py:
    # ``reach_for``), not to an 8 cm block's hover and a 2 cm block's grasp both: pointing down, a UR3e with a
    # Robotiq reaches 4 cm cubes 0.18-0.49 m from its base and every height only 0.21-0.46 m. () holds every
    # scene to ``reach``.
    reach_heights: tuple[tuple[float, float, float], ...] = ()


def problems(spec: ArmSpec) -> str | None:
    """Why ``spec`` cannot drive the simulator (its fields disagree with each other), or None."""
    n = len(spec.arm_joints)
    if not n:
        return "arm_joints is empty"
    if len(spec.home) != n or any(len(s) != n for s in spec.ik_seeds):
        return f"home and every IK seed must give {n} joint values (one per arm joint)"
    if len(spec.finger_closed) != len(spec.finger_joints):
        return "finger_closed must give one value per finger joint"
    if spec.wrist_joint not in spec.arm_joints:
        return f"the wrist joint {spec.wrist_joint} is not one of the arm joints"
    if any(j not in range(n) for j in spec.swivel_joints):
        return "swivel_joints are indices into arm_joints"
    near, far = spec.reach
    if not (0.0 <= near < far and math.isfinite(far)):
        return f"reach must be (near, far) metres with 0 <= near < far (got {spec.reach})"
    if not (0.0 < spec.gripper_opening < 1.0) or not (0.0 < spec.wrist_limit <= 2 * math.pi + 1e-3):
        return "gripper_opening must be in (0, 1) m and wrist_limit in (0, 2 pi] rad"
    if spec.ik_restarts < 0 or not (0.0 <= spec.wrist_error < math.pi):
        return "ik_restarts must be >= 0 and wrist_error in [0, pi) rad"
    if any(j not in spec.finger_joints or lead not in spec.finger_joints for j, lead, _, _ in spec.finger_mimic):
        return "finger_mimic names joints that are not finger joints"
    if not (0.0 < spec.payload < 1000.0):
        return f"payload must be in (0, 1000) kg (got {spec.payload})"
    if any(len(row) != 3 or not 0.0 <= row[1] < row[2] for row in spec.reach_heights):
        return "reach_heights rows must be (height, near, far) metres with 0 <= near < far"
    return None
