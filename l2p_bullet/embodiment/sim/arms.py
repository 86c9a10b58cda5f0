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
    to a cache folder (mesh paths made absolute) and reused; it is derived data, never edited. A cached
    file is only used when its content is exactly the expected text (a stale, corrupt or planted file is
    rewritten), and only from a folder this user owns and nobody else can write (:func:`_cache_dir`).
    """
    import hashlib
    import os
    import re

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
    data = text.encode()
    digest = hashlib.sha256(data).hexdigest()[:16]
    path = os.path.join(_cache_dir(), f"{spec.name}-{digest}.urdf")
    if not _holds(path, data):
        tmp = f"{path}.{os.getpid()}.tmp"
        with open(tmp, "wb") as f:
            f.write(data)
        os.replace(tmp, path)  # atomic: concurrent processes never read a half-written file
    return path


_PRIVATE: list[str] = []


def _cache_dir() -> str:
    """``<tmp>/l2p_bullet-urdf-<uid>``, made with mode 0700; if it exists but is not a folder this user
    owns and alone can write (a link, someone else's), a private folder for this process instead."""
    import os
    import stat
    import tempfile

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
    import tempfile

    if not _PRIVATE:
        _PRIVATE.append(tempfile.mkdtemp(prefix="l2p_bullet-urdf-"))
    return _PRIVATE[0]


def _holds(path: str, data: bytes) -> bool:
    """True when ``path`` is a regular file (not a link) whose bytes are exactly ``data``."""
    import os
    import stat

    try:
        st = os.lstat(path)
        if not stat.S_ISREG(st.st_mode) or st.st_size != len(data):
            return False
        with open(path, "rb") as f:
            return f.read() == data
    except OSError:
        return False
