"""Arms as small data descriptions, so that a second arm is a new entry, not new code.

Everything the simulator needs to know about an arm lives in an :class:`ArmSpec`: where its URDF is,
which joints move it, which link is the tool point, how its fingers close and which joint positions
seed inverse kinematics. The controller, IK and grasp code read only these fields.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


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
)

def arm_urdf(spec: ArmSpec, visuals: bool = True, collisions: bool = True) -> str:
    """Path of the arm's URDF, stripped of visual and/or collision elements when they are not needed.

    Parsing the Panda's visual meshes is most of the cost of loading it (0.27 s against 0.025 s without
    them), and the IK twin needs neither visuals nor collisions (0.6 ms). The stripped copy is written
    once to a cache folder (mesh paths made absolute) and reused; it is derived data, never edited.
    """
    import hashlib
    import os
    import re
    import tempfile

    import pybullet_data

    src = spec.urdf if os.path.isabs(spec.urdf) else os.path.join(pybullet_data.getDataPath(), spec.urdf)
    if visuals and collisions:
        return src
    with open(src) as f:
        text = f.read()
    if not visuals:
        text = re.sub(r"<visual>.*?</visual>", "", text, flags=re.S)
    if not collisions:
        text = re.sub(r"<collision>.*?</collision>", "", text, flags=re.S)
    folder = os.path.dirname(src)
    text = text.replace("package://", folder + "/")
    text = re.sub(r'filename="(?!/)', f'filename="{folder}/', text)
    digest = hashlib.sha256(text.encode()).hexdigest()[:16]
    cache = os.path.join(tempfile.gettempdir(), "l2p_bullet-urdf")
    os.makedirs(cache, exist_ok=True)
    path = os.path.join(cache, f"{spec.name}-{digest}.urdf")
    if not os.path.exists(path):
        tmp = f"{path}.{os.getpid()}.tmp"
        with open(tmp, "w") as f:
            f.write(text)
        os.replace(tmp, path)  # atomic: concurrent processes never read a half-written file
    return path
