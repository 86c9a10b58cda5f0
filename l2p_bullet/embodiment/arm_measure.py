"""An arm measured in PyBullet: its joints' names, its reach ring and hand profile (``l2p-bullet arms --check``,
``new-arm``) compared with what its :class:`~l2p_bullet.arms.ArmSpec` declares.

The spec is data (``l2p_bullet/arms``); these functions load the arm's description in the simulator to
measure what a spec declares, so a user's arm and a shipped one are held to the same test.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..arms import ArmSpec, fit_workspace
from ..core.scene import Workspace


def joint_names(spec: ArmSpec) -> list[str]:
    """The names of the arm's movable joints, in index order: what each trajectory frame's ``arm`` lists."""
    from .sim.robot import ARM, Kinematics

    kin = Kinematics(spec, spec.mount)
    try:
        return [j.name for j in kin.sim.joints(ARM) if j.movable]
    finally:
        kin.close()


def robot_type(spec: ArmSpec) -> str:
    """A robot type for datasets (LeRobot's ``robot_type``): the folder of the arm's description, "_sim"
    ("franka_panda_sim", "xarm_sim", "kuka_iiwa_sim")."""
    import os

    return f"{os.path.basename(os.path.dirname(spec.urdf)) or spec.name}_sim"


# --- measuring an arm (l2p-bullet arms --check, new-arm) -------------------------------------------------
PROFILE_DEPTHS = tuple(round(0.005 * i, 3) for i in range(17))
"""The depths (m above the fingertips) of a measured hand profile: 0 to 8 cm, the tallest block's side."""
REACH_HEIGHTS = (*(round(0.012 + 0.02 * k, 3) for k in range(9)), 0.19)
"""Tool heights the reach test asks for: from a 2 cm block's grasp (0.012 m) to an 8 cm block's top plus the hover
(0.19 m), every 2 cm between. Why the heights between: pointing down near its base, an arm can reach both ends of
the vertical line it rises along and not its middle. The Panda at 0.26 m from its base reaches 0.012 and 0.19 m
but not 0.082-0.162 m, at any wrist angle; with only the two ends tested its ring's near edge was 0.26 m, and
``bench_objects.py`` (seeds 977038 "around" and 977064 "past") planned paths there that execution
could not lift (ReachError before anything moved). With the heights between, it is 0.27 m."""


def _in_plane(spec: ArmSpec, q: np.ndarray, az: float, wrist: float) -> np.ndarray:
    """A first guess in the arm's vertical plane at azimuth ``az`` (as Primitives.in_plane)."""
    out = np.array(q, float)
    out[0] = az
    out[list(spec.swivel_joints)] = 0.0
    out[spec.arm_joints.index(spec.wrist_joint)] = wrist
    return out


def reaches(kin, spec: ArmSpec, r: float, az: float, z: float, wrist: float) -> bool:
    """Whether the tool reaches the point ``r`` m from the base at azimuth ``az``, height ``z``, pointing down with
    the wrist at ``wrist`` (rad), from the arm's home and IK seeds put in its plane, without the arm folding into
    itself (``Kinematics.self_collision``: near its base an arm reaches the table only through its own base)."""
    from ..errors import ReachError

    base_xy = spec.mount[:2]
    x, y = base_xy[0] + r * math.cos(az), base_xy[1] + r * math.sin(az)
    yaw = spec.wrist_offset + az - wrist
    seeds = [_in_plane(spec, np.asarray(s, float), az, wrist) for s in (spec.home, *spec.ik_seeds)]
    try:
        q = kin.solve((x, y, z), yaw, seeds[0], seeds=tuple(tuple(s) for s in seeds[1:]))
    except ReachError:
        return False
    return kin.self_collision(q) is None


def wrist_turns(spec: ArmSpec) -> tuple[float, float, float]:
    """The wrist angles every reach test asks for: 0 and 1 rad either side (less for a narrow wrist)."""
    turn = min(1.0, spec.wrist_limit - 0.3)
    return (0.0, -turn, turn)


def unreached(kin, spec: ArmSpec, points: np.ndarray) -> list[list[float]]:
    """The points (K,2; scene frame) the tool does not reach pointing down at every :data:`REACH_HEIGHTS` with the
    wrist at every :func:`wrist_turns` angle, rounded to 0.1 mm."""
    base = np.asarray(spec.mount[:2], float)
    wrists = wrist_turns(spec)
    out = []
    for p in np.asarray(points, float).reshape(-1, 2):
        r, az = float(np.hypot(*(p - base))), float(math.atan2(p[1] - base[1], p[0] - base[0]))
        if not all(reaches(kin, spec, r, az, z, w) for z in REACH_HEIGHTS for w in wrists):
            out.append([round(float(p[0]), 4), round(float(p[1]), 4)])
    return out


def measure_reach(spec: ArmSpec, step: float = 0.01) -> tuple[float, float]:
    """(near, far): the ring of distances from the base (around its distance to the scene's centre) at which the tool
    reaches every test pose: azimuths 0 and +-0.5 rad (the workspace disk spans +-0.49), heights
    :data:`REACH_HEIGHTS`, the wrist joint at 0 and 1 rad either side (less for a narrow wrist).
    (0, 0) when the centre itself is out of reach."""
    from .sim.robot import Kinematics

    kin = Kinematics(spec, spec.mount)
    wrists = wrist_turns(spec)

    def ok(r: float) -> bool:
        return all(reaches(kin, spec, r, az, z, w) for az in (0.0, -0.5, 0.5) for z in REACH_HEIGHTS
                   for w in wrists)

    try:
        mid = float(math.hypot(*spec.mount[:2]))
        if not ok(mid):  # a smaller or larger arm than the mount expects: start where it reaches, if anywhere
            mid = next((r for r in (0.4, 0.3, 0.65, 0.25, 0.8) if ok(r)), None)
            if mid is None:
                return (0.0, 0.0)
        near = far = mid
        while near - step > 0.05 and ok(near - step):
            near -= step
        while far + step < 1.5 and ok(far + step):
            far += step
        return (round(near, 3), round(far, 3))
    finally:
        kin.close()


def measure_reach_heights(spec: ArmSpec, step: float = 0.01) -> tuple[tuple[float, float, float], ...]:
    """Per height of :data:`REACH_HEIGHTS`, (height, near, far): the ring :func:`measure_reach` walks, at that height
    alone (the same start, steps and test poses): the greatest near and the least far over the rows are its ring;
    () when the centre itself is out of reach. Why: a scene of 4 cm cubes needs the tool at 3-15 cm only
    (``arms/fit.py: reach_for``), and an arm's ring at every height can be much narrower than there (a UR3e's)."""
    from .sim.robot import Kinematics

    kin = Kinematics(spec, spec.mount)
    wrists = wrist_turns(spec)

    def ok(r: float, zs: tuple[float, ...]) -> bool:
        return all(reaches(kin, spec, r, az, z, w) for az in (0.0, -0.5, 0.5) for z in zs for w in wrists)

    try:
        mid = float(math.hypot(*spec.mount[:2]))
        if not ok(mid, REACH_HEIGHTS):
            mid = next((r for r in (0.4, 0.3, 0.65, 0.25, 0.8) if ok(r, REACH_HEIGHTS)), None)
            if mid is None:
                return ()
        rows = []
        for z in REACH_HEIGHTS:
            near = far = mid
            while near - step > 0.05 and ok(near - step, (z,)):
                near -= step
            while far + step < 1.5 and ok(far + step, (z,)):
                far += step
            rows.append((z, round(near, 3), round(far, 3)))
        return tuple(rows)
    finally:
        kin.close()


FLIPPED = 1.5
"""A wrist further than this (rad) from the model is on another branch of the IK (elbow or wrist flipped), not
strayed: a tool off the base joint's plane by d strays asin(d / r) < pi / 2."""


def wrist_offset(spec: ArmSpec) -> float:
    """The wrist model's offset measured (wrist = offset + azimuth - yaw pointing down), in (-pi, pi]: the tool where
    the arm's home puts it (pointing down, in the arm's plane), the yaw read there, solved again pointing exactly
    down; nothing taken from the offset the spec declares."""
    from .sim.robot import Kinematics

    kin = Kinematics(spec, spec.mount)
    try:
        home = np.asarray(spec.home, float)
        pos, orn = kin.fk(home)
        m = kin.sim.rotation_matrix(orn)
        yaw = math.atan2(m[3], m[0])
        q = kin.solve(pos, yaw, home, seeds=spec.ik_seeds)
        az = math.atan2(pos[1] - spec.mount[1], pos[0] - spec.mount[0])
        return math.remainder(float(q[spec.arm_joints.index(spec.wrist_joint)]) - az + yaw, 2 * math.pi)
    finally:
        kin.close()


def wrist_stray(spec: ArmSpec) -> float | None:
    """How far (rad) the wrist joint strays from the model (``wrist_offset + azimuth - yaw``) over the reach ring: its
    near edge, middle and far edge, azimuths 0 and +-0.5 rad, the wrist at :func:`wrist_turns` (as the ring is
    measured: a yaw the wrist cannot turn to in the plane would be answered on another branch), 5 cm above the
    table; None when the arm reaches none of these. A tool off the base joint's plane strays most near the base (a
    UR3e's, 13 cm off, by a radian 15 cm from its base); answers on another branch (more than :data:`FLIPPED`) do
    not count."""
    from ..errors import ReachError
    from .sim.robot import Kinematics

    near, far = spec.reach
    kin = Kinematics(spec, spec.mount)
    stray = None
    try:
        wrist = spec.arm_joints.index(spec.wrist_joint)
        for r in (near, (near + far) / 2, far):
            for az in (-0.5, 0.0, 0.5):
                for want in wrist_turns(spec):
                    yaw = spec.wrist_offset + az - want
                    px, py = spec.mount[0] + r * math.cos(az), spec.mount[1] + r * math.sin(az)
                    try:
                        q = kin.solve((px, py, 0.05), yaw, _in_plane(spec, np.asarray(spec.home, float), az, want),
                                      seeds=spec.ik_seeds)
                    except ReachError:
                        continue
                    off = abs(math.remainder(q[wrist] - want, 2 * math.pi))
                    if off < FLIPPED:  # more is the solver on another branch (seeded runs stay on theirs)
                        stray = off if stray is None else max(stray, off)
        return stray
    finally:
        kin.close()


def measure_hand(spec: ArmSpec) -> tuple[float, tuple[tuple[float, float, float], ...]]:
    """(fingertip drop below the tool point, hand profile) measured on the arm's collision shapes with the tool
    pointing down above the workspace's centre (Robot.hand_profile), at :data:`PROFILE_DEPTHS`."""
    from ..core.scene import Scene
    from .sim.world import World

    with World(Scene([]), arm=spec, visuals=False) as world:
        robot = world.robot
        x = spec.mount[0] + math.hypot(*spec.mount[:2])  # straight ahead of the base, the wrist at 0
        q = robot.kin.solve([x, spec.mount[1], 0.02 + robot.drop], spec.wrist_offset,
                            _in_plane(spec, np.asarray(spec.home, float), 0.0, 0.0), seeds=spec.ik_seeds)
        robot.reset(q)
        prof = robot.hand_profile(PROFILE_DEPTHS)
        return round(robot.drop, 4), tuple((d, round(hx + 5e-5, 4), round(hy + 5e-5, 4)) for d, hx, hy in prof)


def region_probes(ws: Workspace, margin: float = 0.005, n: int = 72) -> np.ndarray:
    """Points (K,2) the reach test asks for inside the workspace: ``margin`` in from its boundary, ``n`` along each
    of its arcs and its corners, and its centre when inside."""
    pts = [arc[np.linspace(0, len(arc) - 1, max(2, n * len(arc) // 360)).astype(int)] for arc in ws.outline(360)]
    pts = np.concatenate([*pts, np.array([ws.center])]) if pts else np.array([ws.center])
    return np.unique(np.round(ws.nearest_inside(pts, margin), 4), axis=0)


def region_unreached(spec: ArmSpec, ws: Workspace) -> list[list[float]]:
    """The points of :func:`region_probes` the tool does not reach pointing down at every :data:`REACH_HEIGHTS`
    with the wrist at 0 and turned either way as ``measure_reach`` turns it (what that walks along three
    azimuths, here over the region itself, whose wider azimuths the three do not cover)."""
    from .sim.robot import Kinematics

    kin = Kinematics(spec, spec.mount)
    try:
        return unreached(kin, spec, region_probes(ws))
    finally:
        kin.close()


def check(spec: ArmSpec) -> dict:
    """``l2p-bullet arms --check`` for one arm: load it with its collision shapes (missing meshes fail here),
    measure its reach ring and hand profile, and compare them with what its spec declares. ``ok`` False when
    the measured ring does not hold the workspace the spec promises (the largest disk about the centre, and
    for a ring-cut workspace the ring itself and every probe point of the region, :func:`region_unreached`) or
    the stored profile is narrower than the measured one (the planner would let the hand hit a block)."""
    from ..errors import L2PError

    out: dict = {"name": spec.name, "declared_reach_m": list(spec.reach)}
    try:
        drop, profile = measure_hand(spec)
        near, far = measure_reach(spec)
    except (L2PError, OSError, ValueError) as e:
        return out | {"ok": False, "error": f"cannot load or move the arm: {e}"[:300]}
    promised = fit_workspace(Workspace(), spec)
    measured = fit_workspace(Workspace(), replace(spec, reach=(near, far)))
    unreached = region_unreached(spec, promised) if promised.ring is not None else []
    stored = dict((d, (hx, hy)) for d, hx, hy in spec.hand_profile)
    short = max((max(mx - stored[d][0], my - stored[d][1]) for d, mx, my in profile if d in stored), default=0.0)
    out |= {"measured_reach_m": [near, far], "workspace_radius_m": round(promised.inner_radius, 4),
            "measured_workspace_radius_m": round(measured.inner_radius, 4), "fingertip_drop_m": drop,
            "profile_short_by_m": round(max(short, 0.0), 4),
            "workspace": promised.to_dict(), "workspace_area_m2": round(promised.area(), 4),
            "measured_workspace": measured.to_dict(), "measured_workspace_area_m2": round(measured.area(), 4),
            "region_points_unreached": unreached}
    problems_found = []
    if measured.inner_radius + 0.011 < promised.inner_radius:
        problems_found.append(f"it reaches only {near:.2f}-{far:.2f} m from its base: a workspace of radius "
                              f"{round(measured.inner_radius, 4)} m, not the {round(promised.inner_radius, 4)} m its "
                              "reach promises")
    elif promised.ring is not None and (near > spec.reach[0] + 0.011 or far < spec.reach[1] - 0.011):
        problems_found.append(
            f"it reaches only {near:.2f}-{far:.2f} m from its base, not the "
            f"{spec.reach[0]:.2f}-{spec.reach[1]:.2f} m its spec declares (its workspace is cut to that ring)"
        )
    if unreached:
        problems_found.append(f"it does not reach {len(unreached)} point(s) of its workspace, e.g. "
                              f"({unreached[0][0]:.3f}, {unreached[0][1]:.3f})")
    if not spec.hand_profile:
        problems_found.append("its spec has no hand profile (the planner would not see the hand beside a block)")
    elif short > 0.002:
        problems_found.append(f"its stored hand profile is {short * 1000:.1f} mm narrower than measured")
    return out | {"ok": not problems_found, "error": "; ".join(problems_found) or None}
