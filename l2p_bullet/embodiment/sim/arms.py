"""An arm's description file as PyBullet loads it: stripped of what a load does not need, with the edits its
:class:`~l2p_bullet.arms.ArmSpec` asks for (a tool link, fixed joints), cached as derived data.
"""

from __future__ import annotations

import hashlib
import math
import os
import re
import stat
import tempfile

import numpy as np

from ...arms.spec import ArmSpec
from .urdf_check import check_urdf

ARM = "<arm>"  # the arm's body name, in the world's simulator and in every private copy (IK's, self-collision's)


def load_arm(sim, path: str, base_xyz) -> None:
    """Load the arm's description (a URDF, or an SDF like the KUKA's) into ``sim`` (a :class:`.bullet.Bullet`) as
    body :data:`ARM`, base fixed."""
    if path.lower().endswith(".sdf"):
        sim.load_sdf(ARM, path, tuple(base_xyz))
    else:
        sim.load_urdf(ARM, path, tuple(base_xyz), fixed=True)


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
_INERTIAL = ('<inertial><origin rpy="0 0 0" xyz="0 0 0"/><mass value="0.0"/>'
             '<inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>')


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
