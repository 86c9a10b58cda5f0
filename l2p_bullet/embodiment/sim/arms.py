"""Arms as small data descriptions, so that a second arm is a new entry, not new code.

Everything the simulator needs to know about an arm lives in an :class:`ArmSpec`: where its URDF is,
which joints move it, which link is the tool point, how its fingers close and which joint positions
seed inverse kinematics. The controller, IK and grasp code read only these fields.
"""

from __future__ import annotations

import hashlib
import math
import os
import re
import stat
import tempfile
from dataclasses import dataclass

import numpy as np

from ...core.scene import ROBOT_BASE_XY
from .urdf_check import check_urdf


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
    # forces a flip), so the wrist model of embodiment/reach.py holds.
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
    # fingertips): (parent link name, xyz in the parent's frame); :func:`arm_urdf` adds a fixed massless link
    # "l2p_tool" there, and ``tool_link`` is its index (the last joint).
    tool_frame: tuple[str, tuple[float, float, float]] | None = None
    # Joints made fixed in the loaded copy: free joints that are neither the arm's nor the fingers' (the
    # KUKA's gripper swivel and fingertip hinges would otherwise flop under gravity and pull IK off).
    fixed_joints: tuple[str, ...] = ()
    # (near, far): the horizontal distances (m) from the base between which the tool reaches the table pointing
    # down at every height a run uses (grasp to hover, any yaw the wrist allows); measured by
    # ``l2p-bullet arms --check`` (embodiment/arm_plugins.py). Where this ring does not hold the scene's workspace disk,
    # the workspace is the disk cut by the ring (core/workspace.py; before 2026-11-27 the disk was shrunk to fit).
    reach: tuple[float, float] = (0.25, 0.78)
    # Where the arm's base frame stands in the scene frame (m): off the table's near edge, facing +x. An arm
    # whose reach ring is narrower or shifted (the xArm6's is 0.17-0.67 m) stands where its ring best holds
    # the workspace disk, as a lab would mount it; the default is the Panda's (core.scene.ROBOT_BASE_XY).
    mount: tuple[float, float, float] = (ROBOT_BASE_XY[0], ROBOT_BASE_XY[1], 0.0)
    description: str = ""


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
    reach=(0.27, 0.79),  # measured (l2p-bullet arms --check, every REACH_HEIGHTS height; 0.26 m with only 0.012 and 0.19)
    payload=3.0,  # Franka's rated payload
    description="Franka Emika Panda with its hand (pybullet_data franka_panda/panda.urdf); the default",
)

def arm_urdf(spec: ArmSpec, visuals: bool = True, collisions: bool = True) -> str:
    """Path of the arm's URDF, stripped of visual and/or collision elements when they are not needed.

    Parsing the Panda's visual meshes is most of the cost of loading it (0.27 s against 0.025 s without
    them), and the IK twin needs neither visuals nor collisions (0.6 ms). The stripped copy is written
    to a cache folder (mesh paths made absolute) and reused; it is derived data, never edited. A cached
    file is only used when its content is exactly the expected text (a stale, corrupt or planted file is
    rewritten), and only from a folder this user owns and nobody else can write (:func:`_cache_dir`).
    """

    src = check_description(spec)
    if visuals and collisions and not (spec.collision_free_links or spec.tool_frame or spec.fixed_joints):
        return src
    with open(src) as f:
        text = f.read()
    if not visuals:
        text = re.sub(r"<visual\b[^>]*>.*?</visual>", "", text, flags=re.S)
    if not collisions:
        text = re.sub(r"<collision\b[^>]*>.*?</collision>", "", text, flags=re.S)
    text = _drop_collisions(text, spec.collision_free_links)
    folder = os.path.dirname(src)
    sdf = src.lower().endswith(".sdf")
    if sdf:
        text = _sdf_absolute(text, folder)
        text = _sdf_edits(text, spec)
    else:
        text = text.replace("package://", folder + "/")
        text = re.sub(r'filename="(?!/)', f'filename="{folder}/', text)
        text = _urdf_edits(text, spec)
    data = text.encode()
    digest = hashlib.sha256(data).hexdigest()[:16]
    path = os.path.join(_cache_dir(), f"{spec.name}-{digest}.{'sdf' if sdf else 'urdf'}")
    if not _holds(path, data):
        tmp = f"{path}.{os.getpid()}.tmp"
        with open(tmp, "wb") as f:
            f.write(data)
        os.replace(tmp, path)  # atomic: concurrent processes never read a half-written file
    return path


def check_description(spec: ArmSpec) -> str:
    """The arm's URDF checked before PyBullet reads it (urdf_check: it crashes on two root links), named as
    the plugin gives it; called before a run folder is made, so a broken arm leaves none. Returns its path."""
    src = arm_source(spec)
    if not src.lower().endswith(".sdf"):
        check_urdf(src)
    return src


def arm_source(spec: ArmSpec) -> str:
    """Absolute path of the arm's description as given (relative paths are inside pybullet_data)."""
    import pybullet_data  # lazy: a small package of data files, imported only when an arm is loaded

    return spec.urdf if os.path.isabs(spec.urdf) else os.path.join(pybullet_data.getDataPath(), spec.urdf)


def portable_path(path: str) -> str:
    """``path`` as ArmSpec.urdf should hold it: relative to pybullet_data when inside it, else absolute."""
    import pybullet_data

    data = os.path.realpath(pybullet_data.getDataPath())
    real = os.path.realpath(path)
    return os.path.relpath(real, data) if real.startswith(data + os.sep) else real


_TOOL = "l2p_tool"
_INERTIAL = '<inertial><origin rpy="0 0 0" xyz="0 0 0"/><mass value="0.0"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>'


def _urdf_edits(text: str, spec: ArmSpec) -> str:
    """``spec.fixed_joints`` made fixed and the ``spec.tool_frame`` link added, in a URDF's text."""
    for name in spec.fixed_joints:
        text = re.sub(rf'(<joint\s+name="{re.escape(name)}"\s+type=")\w+"', r'\1fixed"', text)
    if spec.tool_frame:
        parent, (x, y, z) = spec.tool_frame
        text = text.replace("</robot>", f'<link name="{_TOOL}">{_INERTIAL}</link><joint name="{_TOOL}_joint" '
                            f'type="fixed"><parent link="{parent}"/><child link="{_TOOL}"/><origin rpy="0 0 0" '
                            f'xyz="{x} {y} {z}"/></joint></robot>')
    return text


def _sdf_absolute(text: str, folder: str) -> str:
    """Mesh URIs of an SDF made absolute (its own are relative to its folder, some with a leading slash)."""
    def fix(m: re.Match) -> str:
        uri = m.group(1).strip()
        if os.path.isabs(uri) and os.path.exists(uri):
            return m.group(0)
        return f"<uri>{os.path.join(folder, uri.lstrip('/'))}</uri>"

    return re.sub(r"<uri>(.*?)</uri>", fix, text, flags=re.S)


def _sdf_edits(text: str, spec: ArmSpec) -> str:
    """``spec.fixed_joints`` made fixed and the ``spec.tool_frame`` link added, in an SDF's text (its link
    poses are in the model's frame, so the tool's is the parent's pose composed with the offset)."""
    for name in spec.fixed_joints:
        text = re.sub(rf"(<joint\s+name=['\"]{re.escape(name)}['\"]\s+type=['\"])\w+(['\"])", r"\1fixed\2", text)
    if spec.tool_frame:
        parent, offset = spec.tool_frame
        m = re.search(rf"<link\s+name=['\"]{re.escape(parent)}['\"]>\s*<pose>(.*?)</pose>", text, flags=re.S)
        if m is None:
            raise ValueError(f'{spec.urdf} has no link "{parent}" with a pose (the tool frame\'s parent)')
        x, y, z, roll, pitch, yaw = (float(v) for v in m.group(1).split())
        p = _rpy_matrix(roll, pitch, yaw) @ np.asarray(offset, float) + np.array([x, y, z])
        link = (f"<link name='{_TOOL}'><pose>{p[0]} {p[1]} {p[2]} {roll} {pitch} {yaw}</pose><inertial><mass>0.0"
                "</mass><inertia><ixx>0.1</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0.1</iyy><iyz>0</iyz><izz>0.1</izz>"
                f"</inertia></inertial></link><joint name='{_TOOL}_joint' type='fixed'><parent>{parent}</parent>"
                f"<child>{_TOOL}</child></joint>")
        i = text.rindex("</model>")
        text = text[:i] + link + text[i:]
    return text


def _rpy_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    cr, sr, cp, sp, cy, sy = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw),
                              math.sin(yaw))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


_PRIVATE: list[str] = []


def _cache_dir() -> str:
    """``<tmp>/l2p_bullet-urdf-<uid>``, made with mode 0700; if it exists but is not a folder this user
    owns and alone can write (a link, someone else's), a private folder for this process instead."""

    uid = os.getuid() if hasattr(os, "getuid") else 0
    path = os.path.join(tempfile.gettempdir(), f"l2p_bullet-urdf-{uid}")
    try:
        os.mkdir(path, 0o700)
    except FileExistsError:
        pass
    except OSError:
        return _private_dir()
    st = os.lstat(path)
    if not stat.S_ISDIR(st.st_mode) or st.st_uid != uid or st.st_mode & 0o022:
        return _private_dir()
    return path


def _private_dir() -> str:
    if not _PRIVATE:
        _PRIVATE.append(tempfile.mkdtemp(prefix="l2p_bullet-urdf-"))
    return _PRIVATE[0]


def _holds(path: str, data: bytes) -> bool:
    """True when ``path`` is a regular file (not a link) whose bytes are exactly ``data``."""

    try:
        st = os.lstat(path)
        if not stat.S_ISREG(st.st_mode) or st.st_size != len(data):
            return False
        with open(path, "rb") as f:
            return f.read() == data
    except OSError:
        return False


def _drop_collisions(text: str, links: tuple[str, ...]) -> str:
    """The URDF ``text`` without the collision elements of the named links."""
    def strip(m: re.Match) -> str:
        return re.sub(r"<collision\b[^>]*>.*?</collision>", "", m.group(0), flags=re.S)

    for name in links:
        text = re.sub(rf"<link name=['\"]{re.escape(name)}['\"]>.*?</link>", strip, text, flags=re.S)
    return text


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
    hand_profile=(  # measured by embodiment.arm_plugins.measure_hand (tests/embodiment/test_arms.py re-measures it)
        (0.000, 0.0151, 0.0109), (0.005, 0.0191, 0.0152), (0.010, 0.0191, 0.0186), (0.015, 0.0191, 0.0203),
        (0.020, 0.0191, 0.0220), (0.025, 0.0191, 0.0237), (0.030, 0.0191, 0.0255), (0.035, 0.0191, 0.0272),
        (0.040, 0.0204, 0.0289), (0.045, 0.0205, 0.0468), (0.050, 0.0206, 0.0656), (0.055, 0.0207, 0.0677),
        (0.060, 0.0208, 0.0677), (0.065, 0.0209, 0.0677), (0.070, 0.0209, 0.0677), (0.075, 0.0311, 0.0677),
        (0.080, 0.0316, 0.0677),
    ),
    reach=(0.175, 0.675),
    mount=(-0.425, 0.0, 0.0),  # the middle of its ring: the workspace disk fits whole (radius 0.25 m)
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
    tool_frame=("base_link", (0.0, 0.024, 0.232)),
    fixed_joints=("gripper_to_arm", "left_base_tip_joint", "right_base_tip_joint"),
    gripper_opening=0.101,
    payload=7.0,  # the LBR iiwa 7's rated payload (the iiwa 14's is 14 kg; the description does not say which)
    hand_profile=(  # measured by embodiment.arm_plugins.measure_hand (tests/embodiment/test_arms.py re-measures it)
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
