"""An :class:`ArmSpec` guessed from a user's URDF (``l2p-bullet new-arm``): what can be read or measured is.

- **Fingers**: the joints named with ``--fingers``, else the movable joints whose name holds "finger". None:
  the URDF has no gripper this toolkit can use (an error).
- **Hand and chain**: the hand is the deepest link both fingers hang from; the arm's joints are the movable
  joints from the base to it, the wrist the last of them. Every movable joint below the hand belongs to the
  gripper (knuckles, mimics: PyBullet does not enforce URDF mimics, so all are held at their closed value).
- **Closed**: each leading gripper joint (one no URDF ``<mimic>`` ties to another) at the limit, lower or upper
  whatever their signs, that brings the fingertips closer, every mimic joint following its leader (a Robotiq
  2F-85's knuckles and inner fingers: a four-bar linkage); the leaders at their other limits give the gripper's
  opening (the gap between the fingertips' collision boxes, along the hand's own axes). The fingertips are the
  finger joints' deepest links (a Robotiq's pads); of more than two, the two farthest apart.
- **Tool point**: a link ``l2p_tool`` added to the hand between the closed fingertips (``--tool-link`` names an
  existing one instead); the hand's +z must point from the hand towards the fingertips (the usual convention).
- **Home, wrist model, reach, hand profile**: the home poses the tool 0.3 m above the table pointing down (of the
  IK solutions from several first guesses, the one whose joints stand highest: elbow up); the wrist model (wrist
  = offset + azimuth - yaw) is measured, with how far the wrist strays from it over the table
  (``wrist_error``: a UR's tool stands off its base joint's plane); the reach ring and the hand profile are
  measured as for the shipped arms (``arm_measure``); the arm is mounted where its ring best holds the
  workspace. IK restarts from joints drawn within their limits when its seeds fail (``ik_restarts``). A chain
  that cannot reach the table pointing down is an error.

An arm and a gripper given as separate URDFs are composed into one first (``arm_compose``).
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import replace

import numpy as np

from ..arms import ArmSpec
from ..arms.spec import IK_RESTARTS
from ..core.scene import ROBOT_BASE_XY
from ..errors import PluginError, ReachError
from . import arm_measure
from .sim.arms import arm_source

HOME_NEARER = (0.45, 0.35)
"""Distances (m, less 0.1) from the base where the home is sought when the mount's distance is out of reach."""
WRIST_STRAY = 0.6
"""The most (rad) the wrist may stray from the model over the table: a UR's, 0.1-0.4 rad (its tool stands 13 cm off
the plane of its base joint); more means the last joint does not turn the gripper about the vertical."""
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
    spec = read_arm(name, urdf, tool_link, fingers)
    spec = _home_and_wrist(spec)
    spec = _mount(spec)
    if spec.ik_restarts:
        spec = _wrist_error(spec)
    _, profile = arm_measure.measure_hand(spec)
    return replace(spec, hand_profile=profile)


def read_arm(name: str, urdf: str, tool_link: str | None = None, fingers: list[str] | None = None) -> ArmSpec:
    """What :func:`guess` reads from the URDF alone: the chain, the fingers (their mimics, closed pose and opening),
    the tool point and the wrist's limit, with the home, mount, reach and hand profile not yet measured. Separate
    because these take milliseconds and the measurements seconds to minutes (inverse kinematics over the ring)."""
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
        mimic = _mimics(src, by_name, below)
        tips = list(dict.fromkeys(_deepest(joints, f.index) for f in finger))
        if len(tips) < 2:
            raise PluginError(f"{urdf}: the finger joints {', '.join(f.name for f in finger)} all end in one link; "
                              "name the two fingers' joints with --fingers J,J")
        closed, opening, tips = _closing(sim, ARM, joints, below, tips, hand, mimic)
        bare = [t for t in tips if not len(sim.collision_vertices(ARM, t))]
        if bare:
            raise PluginError(f'{urdf}: the fingertip link "{joints[bare[0]].link}" has no collision shape (a gripper '
                              "described without its fingers): attach them, or name the fingers with --fingers J,J")
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
                   finger_mimic=tuple((j, lead, mult, off) for j, (lead, mult, off) in sorted(mimic.items())),
                   ik_restarts=IK_RESTARTS,
                   description=f"{name}: made by l2p-bullet new-arm from {os.path.basename(src)}")
    return _reindex(spec, {j.index: j.name for j in joints})


def _reindex(spec: ArmSpec, names: dict[int, str]) -> ArmSpec:
    """``spec`` with its joint and link indices those of the copy PyBullet loads (arm_urdf): the tool link added
    to the hand takes its place in PyBullet's depth-first order, which shifts every joint after it (a gripper
    composed on an arm whose root has another branch, as a UR's ``base`` frame is)."""
    from .sim.arms import arm_urdf
    from .sim.bullet import Bullet
    from .sim.robot import ARM, load_arm

    if spec.tool_frame is None:
        return spec
    sim = Bullet()
    try:
        load_arm(sim, arm_urdf(spec, visuals=False, collisions=False), spec.mount)
        now = {j.name: j.index for j in sim.joints(ARM)}
    finally:
        sim.close()
    to = {i: now[n] for i, n in names.items()}

    def re(seq):
        return tuple(to[i] for i in seq)

    return replace(spec, arm_joints=re(spec.arm_joints), finger_joints=re(spec.finger_joints),
                   fingertip_links=re(spec.fingertip_links), wrist_joint=to[spec.wrist_joint],
                   tool_link=now["l2p_tool_joint"],
                   finger_mimic=tuple((to[j], to[lead], m, o) for j, lead, m, o in spec.finger_mimic))


def _deepest(joints, j: int) -> int:
    """The deepest link below joint ``j`` (following its first child at each step): the fingertip."""
    while True:
        children = [c.index for c in joints if c.parent == j]
        if not children:
            return j
        j = children[0]


def _mimics(src: str, by_name, gripper: list[int]) -> dict[int, tuple[int, float, float]]:
    """The gripper joints that follow another (URDF ``<mimic>``): joint -> (leader, multiplier, offset), indices;
    a chain of mimics is followed to its first leader."""
    from .arm_compose import read_urdf

    out: dict[int, tuple[int, float, float]] = {}
    for el in read_urdf(src, "arm").findall("joint"):
        m = el.find("mimic")
        j, lead = by_name.get(el.get("name")), by_name.get(m.get("joint") if m is not None else None)
        if m is None or j is None or lead is None or j.index not in gripper or lead.index not in gripper:
            continue
        try:
            mult, off = float(m.get("multiplier", "1")), float(m.get("offset", "0"))
        except ValueError:
            raise PluginError(f'{src}: the mimic of joint "{j.name}" has a multiplier or offset that is no number') \
                from None
        out[j.index] = (lead.index, mult, off)
    for j in list(out):  # a mimic of a mimic follows the first leader
        lead, mult, off = out[j]
        for _ in range(len(out)):
            if lead not in out:
                break
            lead, m2, o2 = out[lead][0], mult * out[lead][1], mult * out[lead][2] + off
            mult, off = m2, o2
        out[j] = (lead, mult, off)
    return out


def follow(values: dict[int, float], mimic: dict[int, tuple[int, float, float]]) -> dict[int, float]:
    """``values`` of the leading gripper joints with every mimic joint set from its leader."""
    out = dict(values)
    for j, (lead, mult, off) in mimic.items():
        out[j] = mult * out[lead] + off
    return out


def _closing(sim, body: str, joints, gripper: list[int], tips: list[int], hand: int,
             mimic: dict[int, tuple[int, float, float]]) -> tuple[list[float], float, list[int]]:
    """(closed positions of the gripper joints, the opening in metres, the two fingertip links): each leading joint
    (one no ``<mimic>`` ties to another) at the limit that brings the fingertips closer is closed, whichever sign
    its limits have, and its mimics follow it (a Robotiq's knuckles, a four-bar's inner fingers); the gap between
    the fingertips' boxes with every leader at its other limit is the opening. Of more than two fingertip links,
    the two farthest apart open are the fingers.

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

    leaders = [j for j in gripper if j not in mimic]
    if any(
        joints[j].upper <= joints[j].lower or not math.isfinite(joints[j].upper - joints[j].lower)
        or joints[j].upper - joints[j].lower > 2 * math.pi for j in leaders
    ):
        raise PluginError("a gripper joint has no usable limits (lower < upper, less than a turn apart): the closed "
                          "and the open positions cannot be read")

    def pose(ends: dict[int, float]) -> list[float]:
        v = follow(ends, mimic)
        return [v[j] for j in gripper]

    base = sim.base_pose(body)
    hand_orn = sim.link_pose(body, hand)[1]
    inverse = (-hand_orn[0], -hand_orn[1], -hand_orn[2], hand_orn[3])
    sim.set_base_pose(body, base[0], sim.compose(((0.0, 0.0, 0.0), inverse), ((0.0, 0.0, 0.0), base[1]))[1])
    try:
        lower = {j: joints[j].lower for j in leaders}
        upper = {j: joints[j].upper for j in leaders}
        if len(tips) > 2:  # the two fingertips farthest apart with the gripper open either way
            far = []
            for ends in (lower, upper):
                sim.reset_joints(body, gripper, pose(ends))
                c = {t: np.array(sim.aabb(body, t)).mean(axis=0) for t in tips}
                far.append(max(((a, b) for a in tips for b in tips if a < b),
                                key=lambda p: float(np.linalg.norm(c[p[0]] - c[p[1]]))))
            tips = list(far[0])
        closed_at, open_at = {}, {}
        for j in leaders:  # each leader alone, the others half way: which end brings the tips together
            mid = {k: (lower[k] + upper[k]) / 2 for k in leaders}
            d_lo, d_hi = gap(pose(mid | {j: lower[j]}))[0], gap(pose(mid | {j: upper[j]}))[0]
            closed_at[j], open_at[j] = (lower[j], upper[j]) if d_lo <= d_hi else (upper[j], lower[j])
        opening = gap(pose(open_at))[1]
    finally:
        sim.set_base_pose(body, *base)
    if opening <= 0.005:
        raise PluginError(f"the fingers open only {opening * 1000:.0f} mm: no gripper this toolkit can use")
    return pose(closed_at), opening, tips[:2]


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
    """A home 0.3 m above the table pointing down, IK seeds, and the wrist model (wrist = offset + azimuth - yaw)
    measured: its offset straight ahead of the base, and how far the wrist strays from it elsewhere on the table
    (``wrist_error``, which the planner keeps from the wrist's limits: a UR's tool stands off the plane of its
    base joint, so its azimuth is not the base joint's angle)."""
    from .sim.robot import Kinematics

    kin = Kinematics(spec, spec.mount)
    try:
        n = len(spec.arm_joints)
        mid = (kin.arm_lower + kin.arm_upper) / 2
        bent = np.zeros(n)
        bent[1:4] = (-math.pi / 2, math.pi / 2, -math.pi / 2)[: max(0, min(3, n - 1))]
        starts = [np.zeros(n), np.clip(mid, -1.0, 1.0), *(np.full(n, s) * np.sign(np.arange(n) % 2 - 0.5)
                                                         for s in (0.5, 1.0)), bent, -bent]
        found = []  # (mean link height, -k, joints, yaw): the home that keeps the arm highest above the table
        first = math.hypot(*spec.mount[:2])
        for r in (first, *HOME_NEARER):  # a small arm (a UR3e) reaches only nearer its base
            x, y = spec.mount[0] + r, spec.mount[1]
            for k, s in enumerate(starts):
                for turned in (0.0, math.pi / 2, -math.pi / 2, math.pi):
                    try:
                        q = kin.solve((x - 0.1, y, 0.3), turned, s)
                    except ReachError:
                        continue
                    found.append((_link_height(kin, spec, q), -k, q, turned))
                    break
                if len(found) >= 2 and not spec.ik_restarts:
                    break
            if found or not spec.ik_restarts:
                break
        if not found:
            raise PluginError(f"the arm cannot point its gripper down {first - 0.1:.2f} m in front of its base: its "
                              "chain cannot reach the table")
        _, _, home, turned = max(found, key=lambda f: f[:2]) if spec.ik_restarts else found[0]
        wrist = spec.arm_joints.index(spec.wrist_joint)
        offset = float(home[wrist] + turned)  # straight ahead of the base (azimuth 0): wrist = offset - yaw
        offset = math.remainder(offset, 2 * math.pi)
        spec = replace(spec, home=tuple(round(float(v), 4) for v in home), wrist_offset=round(offset, 4))
        seeds = []
        for z in (0.03, 0.15):
            try:
                q = kin.solve((x, y, z), spec.wrist_offset, _in_plane(spec, home, 0.0, 0.0))
            except ReachError:
                if not spec.ik_restarts:
                    raise
                q = kin.solve((x - 0.1, y, z), spec.wrist_offset, _in_plane(spec, home, 0.0, 0.0))
            seeds.append(tuple(round(float(v), 4) for v in q))
        spec = replace(spec, ik_seeds=tuple(seeds))
        stray = 0.0
        for dr, az, yaw in ((0.25, 0.45, 0.4), (-0.2, -0.45, -0.5), (0.2, -0.3, 1.0), (-0.2, 0.3, -1.0)):
            px, py = spec.mount[0] + (r + dr) * math.cos(az), spec.mount[1] + (r + dr) * math.sin(az)
            want = spec.wrist_offset + az - yaw
            try:
                q = kin.solve((px, py, 0.05), yaw, _in_plane(spec, home, az, want), seeds=spec.ik_seeds)
            except ReachError:
                continue  # the reach test decides; the model is measured where the arm reaches
            stray = max(stray, abs(math.remainder(q[wrist] - want, 2 * math.pi)))
        if stray > WRIST_STRAY:
            raise PluginError(f"the arm's last joint strays {stray:.2f} rad from turning the gripper about the "
                              "vertical (wrist = offset + azimuth - yaw, pointing down): its wrist cannot set the "
                              "gripper's yaw")
        return replace(spec, wrist_error=round(stray + 0.02, 3) if stray > 0.05 else 0.0)
    finally:
        kin.close()


def _wrist_error(spec: ArmSpec) -> ArmSpec:
    """``spec`` with ``wrist_error`` measured over its whole reach ring (``arm_measure.wrist_stray``), 0.02 rad
    added for what the samples miss."""
    stray = arm_measure.wrist_stray(spec)
    if stray is not None:
        spec = replace(spec, wrist_error=max(spec.wrist_error, stray + 0.02))
    return replace(spec, wrist_error=round(min(spec.wrist_error, 3.0), 3))


def _link_height(kin, spec: ArmSpec, q) -> float:
    """The mean height of the arm's joint origins with joints ``q`` (the twin has no shapes): of the solutions
    for one tool pose, the elbow-up one keeps the arm above the table and the blocks."""
    from .sim.robot import ARM

    kin.set(q)
    return float(np.mean([kin.sim.link_pose(ARM, j)[0][2] for j in spec.arm_joints]))


def _mount(spec: ArmSpec) -> ArmSpec:
    """Measure the reach ring and stand the arm where it best holds the workspace disk; an error when the
    workspace left is smaller than :data:`MIN_WORKSPACE`."""
    rows = arm_measure.measure_reach_heights(spec)  # the ring at every height is the narrowest of its rows
    near, far = (max(r[1] for r in rows), min(r[2] for r in rows)) if rows else (0.0, 0.0)
    if far <= near:
        raise PluginError(f"the arm cannot reach the table pointing down {math.hypot(*spec.mount[:2]):.2f} m from its "
                          "base at every height and yaw a run uses: its chain cannot reach the table")
    centre = (near + far) / 2
    spec = replace(spec, mount=(-round(centre, 3), 0.0, 0.0), reach=(round(near, 3), round(far, 3)),
                   reach_heights=rows)
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
