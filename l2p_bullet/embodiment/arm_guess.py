"""An :class:`ArmSpec` guessed from a user's URDF (``l2p-bullet new-arm``): what can be read or measured is.

- **Fingers**: the joints named with ``--fingers``, else the movable joints whose name holds "finger". None:
  the URDF has no gripper this toolkit can use (an error).
- **Hand and chain**: the hand is the deepest link both fingers hang from; the arm's joints are the movable
  joints from the base to it, the wrist the last of them. Every movable joint below the hand belongs to the
  gripper (knuckles, mimics: PyBullet does not enforce URDF mimics, so all are held at their closed value).
- **Closed**: all gripper joints at their lower or at their upper limit, whichever brings the fingertips (the
  finger joints' deepest links) closer; the other gives the gripper's opening (the gap between the fingertips'
  collision boxes, along the hand's own axes).
- **Tool point**: a link ``l2p_tool`` added to the hand between the closed fingertips (``--tool-link`` names an
  existing one instead); the hand's +z must point from the hand towards the fingertips (the usual convention).
- **Home, wrist model, reach, hand profile**: the home poses the tool 0.3 m above the table pointing down; the
  wrist model (wrist = offset + azimuth - yaw) is measured and checked on a few poses; the reach ring and the
  hand profile are measured as for the shipped arms (``arm_measure``); the arm is mounted where its ring best
  holds the workspace. A chain that cannot reach the table pointing down is an error.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import replace

import numpy as np

from ..arms import ArmSpec
from ..core.scene import ROBOT_BASE_XY
from ..errors import PluginError, ReachError
from . import arm_measure
from .sim.arms import arm_source

MIN_WORKSPACE = 0.08
"""The smallest workspace radius (m) an arm must reach to be of use: two 4 cm blocks 1.4 sides apart."""


def missing_meshes(path: str) -> list[str]:
    """The mesh files a URDF names that do not exist (``package://`` and relative names resolved against its
    folder, as :func:`~l2p_bullet.embodiment.sim.arms.arm_urdf` does)."""
    folder = os.path.dirname(os.path.abspath(path))
    with open(path, encoding="utf-8", errors="replace") as f:
        text = f.read()
    out = []
    for name in re.findall(r'<mesh\s+[^>]*filename="([^"]+)"', text):
        p = name.replace("package://", folder + "/") if name.startswith("package://") else name
        p = p if os.path.isabs(p) else os.path.join(folder, p)
        if not os.path.isfile(p) and name not in out:
            out.append(name)
    return out


def guess(name: str, urdf: str, tool_link: str | None = None, fingers: list[str] | None = None) -> ArmSpec:
    """The arm in ``urdf`` as an ArmSpec named ``name``, every field guessed or measured (module docstring);
    PluginError with one line saying what is wrong when it cannot be used."""
    from .sim.bullet import Bullet
    from .sim.robot import ARM

    if not urdf.lower().endswith(".urdf"):
        raise PluginError(f"new-arm reads URDF files (got {urdf}); describe an SDF arm by hand (an ArmSpec, see "
                          "l2p_bullet/arms/builtin.py)")
    src = os.path.abspath(urdf)
    if not os.path.isfile(src):
        raise PluginError(f"{urdf}: no such file")
    missing = missing_meshes(src)
    if missing:
        raise PluginError(f"{urdf} names {len(missing)} mesh file(s) that do not exist (first: {missing[0]}); "
                          "put them where the URDF says")
    base = ArmSpec(name=name, urdf=src, arm_joints=(0,), tool_link=0, finger_joints=(), finger_closed=(),
                   home=(0.0,), ik_seeds=(), wrist_joint=0)
    sim = Bullet()
    try:
        sim.load_urdf(ARM, src, (ROBOT_BASE_XY[0], ROBOT_BASE_XY[1], 0.0), fixed=True)
        joints = sim.joints(ARM)
        by_name = {j.name: j for j in joints}
        movable = [j for j in joints if j.movable]
        if fingers:
            unknown = [f for f in fingers if f not in by_name or not by_name[f].movable]
            if unknown:
                raise PluginError(f'{urdf} has no movable joint "{unknown[0]}" (movable: '
                                  f'{", ".join(j.name for j in movable)})')
            finger = [by_name[f] for f in fingers]
        else:
            finger = [j for j in movable if "finger" in j.name.lower()]
        if len(finger) < 2:
            raise PluginError(f"{urdf} has no gripper this toolkit can use: no two movable finger joints (names with "
                              '"finger"); name them with --fingers J,J')

        def ancestors(j: int) -> list[int]:  # the joints from j up to the base, j first
            out = []
            while j >= 0:
                out.append(j)
                j = joints[j].parent
            return out

        chains = [ancestors(f.index) for f in finger]
        common = [j for j in chains[0] if all(j in c for c in chains[1:])]
        hand = common[0] if common else -1  # the joint whose link both fingers hang from
        if hand < 0:
            raise PluginError(f"{urdf}: the finger joints {', '.join(f.name for f in finger)} hang from no common "
                              "link (they are not one gripper)")
        arm = [j for j in reversed(ancestors(hand)) if joints[j].movable]
        if len(arm) < 5:
            raise PluginError(f"{urdf}: only {len(arm)} movable joint(s) lead to the gripper; an arm needs at least "
                              "5 to put it anywhere on the table pointing down")
        below = [j.index for j in movable if j.index not in arm and hand in ancestors(j.index)]
        tips = [_deepest(joints, f.index) for f in finger]
        closed, opening = _closing(sim, ARM, joints, below, tips, hand)
        tool, frame = _tool(sim, ARM, joints, hand, tips, below, closed, tool_link)
        wrist = arm[-1]
        lo, hi = joints[wrist].lower, joints[wrist].upper
        wrist_limit = min(abs(lo), abs(hi), 2 * math.pi) if hi > lo else math.pi
    finally:
        sim.close()
    spec = replace(base, arm_joints=tuple(arm), tool_link=tool, finger_joints=tuple(below),
                   finger_closed=tuple(closed), home=(0.0,) * len(arm), wrist_joint=wrist,
                   fingertip_links=tuple(tips), wrist_limit=round(wrist_limit, 4), tool_frame=frame,
                   swivel_joints=(2, 4) if len(arm) == 7 else (), gripper_opening=round(opening, 4),
                   description=f"{name}: made by l2p-bullet new-arm from {os.path.basename(src)}")
    spec = _home_and_wrist(spec)
    spec = _mount(spec)
    _, profile = arm_measure.measure_hand(spec)
    return replace(spec, hand_profile=profile)


def _deepest(joints, j: int) -> int:
    """The deepest link below joint ``j`` (following its first child at each step): the fingertip."""
    while True:
        children = [c.index for c in joints if c.parent == j]
        if not children:
            return j
        j = children[0]


def _closing(sim, body: str, joints, gripper: list[int], tips: list[int], hand: int) -> tuple[list[float], float]:
    """(closed positions of the gripper joints, the opening in metres): all at the limit that brings the
    fingertips closer is closed; the gap between the fingertips' boxes at the other is the opening.

    The boxes are measured along the hand's own axes: the body is turned so that the hand's frame is the
    world's while they are read (a hand turned on its flange, as the Panda's is by 45 degrees, would open
    along a diagonal of world-aligned boxes, which overlap there), then turned back."""
    def gap(values: list[float]) -> tuple[float, float]:
        sim.reset_joints(body, gripper, values)
        boxes = [np.array(sim.aabb(body, t)) for t in tips[:2]]
        centres = [b.mean(axis=0) for b in boxes]
        axis = int(np.argmax(np.abs(centres[1] - centres[0])))
        left, right = sorted(boxes, key=lambda b: b.mean(axis=0)[axis])
        return float(np.linalg.norm(centres[1] - centres[0])), float(right[0][axis] - left[1][axis])

    lower = [joints[j].lower for j in gripper]
    upper = [joints[j].upper for j in gripper]
    if any(
        hi <= lo or not math.isfinite(hi - lo) or hi - lo > 2 * math.pi for lo, hi in zip(lower, upper, strict=True)
    ):
        raise PluginError("a gripper joint has no usable limits (lower < upper, less than a turn apart): the closed "
                          "and the open positions cannot be read")
    base = sim.base_pose(body)
    hand_orn = sim.link_pose(body, hand)[1]
    inverse = (-hand_orn[0], -hand_orn[1], -hand_orn[2], hand_orn[3])
    sim.set_base_pose(body, base[0], sim.compose(((0.0, 0.0, 0.0), inverse), ((0.0, 0.0, 0.0), base[1]))[1])
    try:
        (d_lo, gap_lo), (d_hi, gap_hi) = gap(lower), gap(upper)
    finally:
        sim.set_base_pose(body, *base)
    closed, opening = (lower, gap_hi) if d_lo < d_hi else (upper, gap_lo)
    if opening <= 0.005:
        raise PluginError(f"the fingers open only {opening * 1000:.0f} mm: no gripper this toolkit can use")
    return closed, opening


def _tool(sim, body: str, joints, hand: int, tips: list[int], gripper: list[int], closed: list[float],
          tool_link: str | None) -> tuple[int, tuple[str, tuple[float, float, float]] | None]:
    """(tool link index, tool frame to add or None): ``tool_link`` if named, else a link added between the
    closed fingertips' centres, in the hand's frame (the hand's +z must point towards them)."""
    if tool_link is not None:
        names = {j.link: j.index for j in joints}
        if tool_link not in names:
            raise PluginError(f'the URDF has no link "{tool_link}" (--tool-link)')
        return names[tool_link], None
    sim.reset_joints(body, gripper, closed)
    pos, orn = sim.link_pose(body, hand)
    r = np.array(sim.rotation_matrix(orn)).reshape(3, 3)
    mid = np.mean([np.array(sim.aabb(body, t)).mean(axis=0) for t in tips[:2]], axis=0)
    local = r.T @ (mid - np.array(pos))
    if local[2] < 0.5 * np.linalg.norm(local):
        raise PluginError("the hand's +z axis does not point towards the fingertips; name the tool point's link "
                          "with --tool-link")
    return len(joints), (joints[hand].link, tuple(round(float(v), 4) for v in local))


def _in_plane(spec: ArmSpec, q, az: float, wrist: float) -> np.ndarray:
    return arm_measure._in_plane(spec, np.asarray(q, float), az, wrist)


def _home_and_wrist(spec: ArmSpec) -> ArmSpec:
    """A home 0.3 m above the table pointing down, IK seeds, and the measured wrist model (wrist = offset +
    azimuth - yaw, checked on a few poses: a model that does not hold is an error)."""
    from .sim.robot import Kinematics

    kin = Kinematics(spec, spec.mount)
    try:
        n = len(spec.arm_joints)
        mid = (kin.arm_lower + kin.arm_upper) / 2
        starts = [np.zeros(n), np.clip(mid, -1.0, 1.0), *(np.full(n, s) * np.sign(np.arange(n) % 2 - 0.5)
                                                         for s in (0.5, 1.0))]
        r = math.hypot(*spec.mount[:2])
        x, y = spec.mount[0] + r, spec.mount[1]
        home, turned = None, 0.0
        for s in starts:
            for turned in (0.0, math.pi / 2, -math.pi / 2, math.pi):
                try:
                    home = kin.solve((x - 0.1, y, 0.3), turned, s)
                    break
                except ReachError:
                    continue
            if home is not None:
                break
        if home is None:
            raise PluginError(f"the arm cannot point its gripper down {r - 0.1:.2f} m in front of its base: its chain "
                              "cannot reach the table")
        wrist = spec.arm_joints.index(spec.wrist_joint)
        offset = float(home[wrist] + turned)  # straight ahead of the base (azimuth 0): wrist = offset - yaw
        offset = math.remainder(offset, 2 * math.pi)
        spec = replace(spec, home=tuple(round(float(v), 4) for v in home), wrist_offset=round(offset, 4))
        seeds = []
        for z in (0.03, 0.15):
            q = kin.solve((x, y, z), spec.wrist_offset, _in_plane(spec, home, 0.0, 0.0))
            seeds.append(tuple(round(float(v), 4) for v in q))
        spec = replace(spec, ik_seeds=tuple(seeds))
        for px, py, yaw in ((x + 0.08, y + 0.1, 0.4), (x - 0.05, y - 0.12, -0.5)):
            az = math.atan2(py - spec.mount[1], px - spec.mount[0])
            want = spec.wrist_offset + az - yaw
            try:
                q = kin.solve((px, py, 0.05), yaw, _in_plane(spec, home, az, want), seeds=spec.ik_seeds)
            except ReachError:
                continue  # the reach test decides; the model is checked where the arm reaches
            if abs(math.remainder(q[wrist] - want, 2 * math.pi)) > 0.05:
                raise PluginError("the arm's wrist does not follow the model this toolkit plans with (wrist = offset + "
                                  "azimuth - yaw, pointing down): its last joint does not turn the gripper about the "
                                  "vertical")
        return spec
    finally:
        kin.close()


def _mount(spec: ArmSpec) -> ArmSpec:
    """Measure the reach ring and stand the arm where it best holds the workspace disk; an error when the
    workspace left is smaller than :data:`MIN_WORKSPACE`."""
    near, far = arm_measure.measure_reach(spec)
    if far <= near:
        raise PluginError(f"the arm cannot reach the table pointing down {math.hypot(*spec.mount[:2]):.2f} m from its "
                          "base at every height and yaw a run uses: its chain cannot reach the table")
    centre = (near + far) / 2
    spec = replace(spec, mount=(-round(centre, 3), 0.0, 0.0), reach=(round(near, 3), round(far, 3)))
    radius = min(0.25, spec.reach[1] + spec.mount[0], -spec.mount[0] - spec.reach[0])
    if radius < MIN_WORKSPACE:
        raise PluginError(f"the arm reaches the table only {near:.2f}-{far:.2f} m from its base: a workspace of "
                          f"{radius * 100:.0f} cm radius, too small for two blocks; its chain cannot reach the table")
    return spec


def spec_source(spec: ArmSpec) -> str:
    """Python source of ``spec`` as the ArmSpec(...) call a plugin's module declares."""
    fields = {k: getattr(spec, k) for k in spec.__dataclass_fields__}
    lines = [f"    {k}={v!r}," for k, v in fields.items() if k != "urdf"]
    return "ArmSpec(\n    urdf=URDF,\n" + "\n".join(lines) + "\n)"


__all__ = ["guess", "missing_meshes", "spec_source", "arm_source"]
