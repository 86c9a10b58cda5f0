"""The built-in arms, registered in the entry-point group ``l2p_bullet.arms`` as a third-party arm is
(plugins/arms.py): the Franka Emika Panda (the default), the UFactory xArm6 and the KUKA LBR iiwa, each
with its gripper, described by pybullet_data's files and measured (``l2p-bullet arms --check``)."""

from __future__ import annotations

import math

from .spec import ArmSpec

PANDA = ArmSpec(
    name="panda",
    urdf="franka_panda/panda.urdf",
    arm_joints=(0, 1, 2, 3, 4, 5, 6),
    tool_link=11,
    finger_joints=(9, 10),
    finger_closed=(0.0, 0.0),
    home=(0.0, -0.3, 0.0, -2.2, 0.0, 1.9, math.pi / 4),
    ik_seeds=(
        (0.0, 0.3, 0.0, -2.0, 0.0, 2.3, math.pi / 4),
        (0.0, -0.5, 0.0, -2.8, 0.0, 2.3, math.pi / 4),
        (0.0, 0.6, 0.0, -1.4, 0.0, 2.0, math.pi / 4),
    ),
    wrist_joint=6,
    fingertip_links=(9, 10),
    wrist_limit=2.9671,
    swivel_joints=(2, 4),
    collision_free_links=tuple(f"panda_link{i}" for i in range(7)),
    wrist_offset=math.pi / 4,  # the hand sits at -45 deg on the flange
    hand_profile=(  # fingers alone up to 4.5 cm above their tips (their long side across the tool's x), then the hand
        (0.000, 0.0093, 0.0183), (0.005, 0.0130, 0.0199), (0.010, 0.0132, 0.0215), (0.015, 0.0135, 0.0231),
        (0.020, 0.0138, 0.0247), (0.025, 0.0140, 0.0262), (0.030, 0.0143, 0.0278), (0.035, 0.0145, 0.0293),
        (0.040, 0.0145, 0.0296), (0.045, 0.0145, 0.0299), (0.050, 0.0215, 0.1016), (0.055, 0.0228, 0.1045),
        (0.060, 0.0241, 0.1048), (0.065, 0.0253, 0.1051), (0.070, 0.0266, 0.1055), (0.075, 0.0278, 0.1058),
        (0.080, 0.0291, 0.1062),
    ),
    # measured (l2p-bullet arms --check, every REACH_HEIGHTS height; 0.26 m with only 0.012 and 0.19)
    reach=(0.27, 0.79),
    payload=3.0,  # Franka's rated payload
    description="Franka Emika Panda with its hand (pybullet_data franka_panda/panda.urdf); the default",
)

# UFactory xArm6 with its gripper. Measured on pybullet_data's xarm6_with_gripper.urdf (docs/arms.md): the
# gripper's six joints are one linkage (URDF mimics, which PyBullet does not enforce, so all six are held at
# the same value); 0.85 rad closes it, 0 opens it to 8.3 cm between the fingers' collision hulls. The tool
# point is 16 cm below the gripper base, between the closed fingertips (they reach 1.75 cm lower). Pointing
# down, wrist (joint 6) = azimuth - tool yaw exactly: the arm has no redundant joint to swivel.
XARM6 = ArmSpec(
    name="xarm6",
    urdf="xarm/xarm6_with_gripper.urdf",
    arm_joints=(1, 2, 3, 4, 5, 6),
    tool_link=14,
    finger_joints=(8, 9, 10, 11, 12, 13),
    finger_closed=(0.85,) * 6,
    home=(0.0, -0.25, -0.75, 0.0, 1.0, 0.0),
    ik_seeds=((0.0, 0.5, -1.2, 0.0, 0.7, 0.0), (0.0, 0.0, -1.4, 0.0, 1.4, 0.0), (0.0, 0.9, -1.9, 0.0, 1.0, 0.0)),
    wrist_joint=6,
    fingertip_links=(9, 12),
    wrist_limit=6.2832,
    wrist_offset=0.0,
    tool_frame=("xarm_gripper_base_link", (0.0, 0.0, 0.16)),
    gripper_opening=0.083,
    payload=5.0,  # UFactory's rated payload for the xArm6
    hand_profile=(  # measured by embodiment.arm_measure.measure_hand (tests/embodiment/test_arms.py re-measures it)
        (0.000, 0.0151, 0.0109), (0.005, 0.0191, 0.0152), (0.010, 0.0191, 0.0186), (0.015, 0.0191, 0.0203),
        (0.020, 0.0191, 0.0220), (0.025, 0.0191, 0.0237), (0.030, 0.0191, 0.0255), (0.035, 0.0191, 0.0272),
        (0.040, 0.0204, 0.0289), (0.045, 0.0205, 0.0468), (0.050, 0.0206, 0.0656), (0.055, 0.0207, 0.0677),
        (0.060, 0.0208, 0.0677), (0.065, 0.0209, 0.0677), (0.070, 0.0209, 0.0677), (0.075, 0.0311, 0.0677),
        (0.080, 0.0316, 0.0677),
    ),
    # measured (l2p-bullet arms --check) with IK's restarts and without the arm folding into itself: near its base
    # the hand reaches the table only through the base from 0.10 m in
    reach=(0.105, 0.685),
    mount=(-0.425, 0.0, 0.0),  # the workspace disk (radius 0.25 m) fits whole in its ring
    description="UFactory xArm6 with its gripper (pybullet_data xarm/xarm6_with_gripper.urdf)",
)

# KUKA LBR iiwa 7 with a WSG-50-like parallel gripper, pybullet_data's kuka_with_gripper2.sdf. The SDF's
# gripper hangs on a free revolute joint and its fingertips on free hinges: made fixed. Its fingers sit
# 2.4 cm off the gripper's axis (as the file has them), so the tool point is there, 23.2 cm out from the
# gripper base. The finger joints' limits (+-10 rad) are not physical: the opening is measured at 0.3 rad
# (pybullet's own kuka.py opens the gripper that far): 10.1 cm between the fingertips' hulls.
# Pointing down with J2, J4 at zero, wrist (J6) = pi + azimuth - tool yaw.
KUKA_IIWA = ArmSpec(
    name="kuka-iiwa",
    urdf="kuka_iiwa/kuka_with_gripper2.sdf",
    arm_joints=(0, 1, 2, 3, 4, 5, 6),
    tool_link=14,
    finger_joints=(8, 11),
    finger_closed=(0.0, 0.0),
    home=(0.0, 0.3, 0.0, -1.6, 0.0, 1.25, 1.5),
    ik_seeds=((0.0, 0.7, 0.0, -1.2, 0.0, 1.2, 1.5), (0.0, 1.1, 0.0, -0.9, 0.0, 1.1, 1.5),
              (0.0, 0.2, 0.0, -1.9, 0.0, 1.0, 1.5)),
    wrist_joint=6,
    fingertip_links=(10, 13),
    wrist_limit=3.0543,
    swivel_joints=(2, 4),
    wrist_offset=math.pi,
    # the tool point 2.4 cm off the wrist's axis strays it 0.060 rad from the model (embodiment.arm_measure.wrist_stray,
    # tests/embodiment/test_general_ik.py), and 0.02 rad for what the samples miss, as new-arm adds
    wrist_error=0.08,
    tool_frame=("base_link", (0.0, 0.024, 0.232)),
    fixed_joints=("gripper_to_arm", "left_base_tip_joint", "right_base_tip_joint"),
    gripper_opening=0.101,
    payload=7.0,  # the LBR iiwa 7's rated payload (the iiwa 14's is 14 kg; the description does not say which)
    hand_profile=(  # measured by embodiment.arm_measure.measure_hand (tests/embodiment/test_arms.py re-measures it)
        (0.000, 0.0001, 0.0001), (0.005, 0.0227, 0.0180), (0.010, 0.0259, 0.0182), (0.015, 0.0290, 0.0184),
        (0.020, 0.0319, 0.0185), (0.025, 0.0347, 0.0187), (0.030, 0.0375, 0.0189), (0.035, 0.0399, 0.0190),
        (0.040, 0.0419, 0.0192), (0.045, 0.0438, 0.0200), (0.050, 0.0445, 0.0200), (0.055, 0.0448, 0.0200),
        (0.060, 0.0451, 0.0200), (0.065, 0.0454, 0.0202), (0.070, 0.0457, 0.0205), (0.075, 0.0457, 0.0207),
        (0.080, 0.0457, 0.0210),
    ),
    reach=(0.43, 0.77),
    mount=(-0.60, 0.0, 0.0),  # the middle of its ring (a lower or higher mount shifts it, no wider): radius 0.17 m
    description="KUKA LBR iiwa with a parallel gripper (pybullet_data kuka_iiwa/kuka_with_gripper2.sdf)",
)
