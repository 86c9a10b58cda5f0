"""The arm in the world: joint control, tool pose, and inverse kinematics with failure detection.

IK runs on a kinematic twin of the arm in a second, private simulator (its own :class:`~.bullet.Bullet`):
PyBullet's IK seeds from a body's current joints and checking a solution needs forward kinematics, and
doing either on the simulated arm would teleport it. The twin is never stepped, so it costs nothing in
the physics loop; the world closes it with itself.
"""

from __future__ import annotations

import math

import numpy as np

from ...arms import ArmSpec
from ...errors import ReachError
from .arms import ARM, arm_urdf, load_arm
from .bullet import Bullet

IK_POS_TOL = 0.002  # metres between the commanded and the reached tool point
IK_ANG_TOL = math.radians(2.0)  # tool orientation error


def down_quaternion(sim: Bullet, spec: ArmSpec, yaw: float) -> tuple[float, ...]:
    """The tool pointing down, turned by ``yaw`` about the vertical."""
    return sim.quaternion(spec.down_euler[0], spec.down_euler[1], yaw)


def quat_angle(a, b) -> float:
    """Angle (radians) between two unit quaternions (x, y, z, w)."""
    d = abs(float(np.dot(a, b)))
    return 2.0 * math.acos(min(1.0, d))


class Kinematics:
    """IK and FK on a private copy of the arm. ``solve`` raises :class:`ReachError` on failure."""

    def __init__(self, spec: ArmSpec, base_xyz: tuple[float, float, float]):
        self.sim, self.spec = Bullet(), spec
        self.base_xyz = tuple(float(v) for v in base_xyz)
        self.base_xy = self.base_xyz[:2]
        self._shapes = None  # the copy with collision shapes (self_collision), loaded when first asked
        try:
            load_arm(self.sim, arm_urdf(spec, visuals=False, collisions=False), base_xyz)
        except BaseException:
            self.sim.close()
            raise
        info = self.sim.joints(ARM)
        # IK returns one value per movable joint, in joint order: remember where the arm's are.
        movable = [j.index for j in info if j.movable]
        self.ik_index = [movable.index(j) for j in spec.arm_joints]
        self.lower = np.array([info[j].lower for j in movable])
        self.upper = np.array([info[j].upper for j in movable])
        self.arm_lower = self.lower[self.ik_index]
        self.arm_upper = self.upper[self.ik_index]
        self.movable = movable
        # the limits as _inside and _near compare with them, made once (a solve runs thousands of times a run)
        self._lo_list, self._hi_list = self.arm_lower.tolist(), self.arm_upper.tolist()
        self._inside_bounds = [(lo - 1e-6, hi + 1e-6) for lo, hi in zip(self._lo_list, self._hi_list, strict=True)]
        self.current: np.ndarray | None = None  # the twin's joints now (skips a reset when unchanged)
        self.joint_ids = list(spec.arm_joints)
        self.sim.reset_joints(ARM, spec.finger_joints, spec.finger_closed)

    def set(self, q: np.ndarray) -> None:
        self.sim.reset_joints(ARM, self.joint_ids, q)

    def fk(self, q: np.ndarray) -> tuple[np.ndarray, tuple[float, ...]]:
        """Tool position and orientation quaternion for arm joints ``q``."""
        self.set(q)
        pos, orn = self.sim.link_pose(ARM, self.spec.tool_link)
        return np.array(pos), orn

    def _try(self, pos, orn, seed: np.ndarray, iterations: int, rounds: int, null_space: bool):
        """Damped least squares from ``seed`` (PyBullet seeds from the twin's joints), re-seeded
        ``rounds`` times. Plain DLS converges near the reach limit where the null-space variant stalls
        millimetres short; the null-space variant (pulled towards ``seed``) is the fallback when plain
        DLS ends outside a joint limit."""
        extra = {}
        if null_space:
            rest = np.zeros(len(self.movable))
            rest[self.ik_index] = seed
            extra = dict(lower=self.lower.tolist(), upper=self.upper.tolist(), rest=rest.tolist())
        q = np.asarray(seed, float)
        err = ang = math.inf
        for _ in range(rounds):
            # after the first pass the twin stands at the last answer, the very array q is (no comparison)
            if self.current is not q and (self.current is None or not np.array_equal(self.current, q)):
                self.set(q)
            sol = self.sim.inverse_kinematics(ARM, self.spec.tool_link, pos, orn, iterations=iterations,
                                              threshold=1e-6, **extra)
            q = np.asarray(sol)[self.ik_index]
            got, got_orn = self.fk(q)
            self.current = q
            d = got - pos
            err, ang = float(math.sqrt(d.dot(d))), quat_angle(got_orn, orn)  # np.linalg.norm's own sum
            if err < IK_POS_TOL * 0.25 and ang < IK_ANG_TOL * 0.25:
                break
        return q, err, ang

    def solve(self, pos, yaw: float, seed: np.ndarray, *, iterations: int = 10, rounds: int = 8,
              seeds: tuple[tuple[float, ...], ...] = ()) -> np.ndarray:
        """Joints putting the tool at ``pos`` pointing down with ``yaw``; ReachError when impossible.

        Tries ``seed`` first (the previous solution: cheap and continuous), then ``seeds``, then the arm's
        restarts (:meth:`_attempts`), each answer turned by whole turns to lie nearest ``seed``.
        A solution counts only if its forward kinematics lands within tolerance and every joint is
        inside its limits: PyBullet's IK returns its best effort without saying it failed.
        """
        pos = np.asarray(pos, float)
        orn = down_quaternion(self.sim, self.spec, yaw)
        seed = np.asarray(seed, float)
        best = None
        for q, err, ang in self._attempts(pos, orn, seed, seeds, iterations, rounds):
            q = self._near(q, seed)
            inside = self._inside(q)
            if err <= IK_POS_TOL and ang <= IK_ANG_TOL and inside:
                return q
            if best is None or err < best[1]:
                best = (q, err, ang, inside)
        q, err, ang, inside = best
        why = (f"residual {err * 1000:.1f} mm, {math.degrees(ang):.1f} deg" if inside
               else "a joint limit would be violated")
        raise ReachError(
            f"the arm cannot reach ({pos[0]:.3f}, {pos[1]:.3f}, {pos[2]:.3f}) pointing down with yaw "
            f"{math.degrees(yaw):.0f} deg ({why}); keep paths inside the workspace"
        )

    def _attempts(self, pos, orn, seed: np.ndarray, seeds, iterations: int, rounds: int):
        """The answers :meth:`solve` weighs, (joints, position error, angle error) each, cheapest first and made
        only when the one before failed: ``seed`` with ``iterations``, then ``seed`` and each of ``seeds`` with
        more iterations, plain and null-space; then the restarts (:meth:`_restarts`), null-space first (it keeps a
        far first guess within the joint limits), finished by plain damped least squares when it stalls
        millimetres short."""
        its = max(iterations, 50)
        yield self._try(pos, orn, seed, iterations, rounds, False)
        for s in (seed, *seeds):
            for null_space in (False, True):
                yield self._try(pos, orn, np.asarray(s, float), its, rounds, null_space)
        for s in self._restarts(pos, seed):
            q, err, ang = self._try(pos, orn, s, its, rounds, True)
            if IK_POS_TOL < err < 10 * IK_POS_TOL:
                q, err, ang = self._try(pos, orn, q, its, rounds, False)
            yield q, err, ang

    def _inside(self, q: np.ndarray) -> bool:
        """Whether every arm joint of ``q`` is within its limits (PyBullet's IK may return one outside)."""
        return all(lo <= v <= hi for v, (lo, hi) in zip(q.tolist(), self._inside_bounds, strict=True))

    def _restarts(self, pos, seed: np.ndarray) -> list[np.ndarray]:
        """First guesses when the seeds fail (``ArmSpec.ik_restarts`` of them): the seed with its base joint turned
        towards ``pos``, then joints drawn within their limits (clipped to a half turn either side, where a chain's
        useful poses lie) from a generator seeded alike every time, so that a solve is repeatable."""
        n = self.spec.ik_restarts
        if not n:
            return []
        turned = np.array(seed, float)
        turned[0] = math.atan2(pos[1] - self.base_xy[1], pos[0] - self.base_xy[0])
        lo, hi = np.maximum(self.arm_lower, -math.pi), np.minimum(self.arm_upper, math.pi)
        rng = np.random.default_rng(0)
        return [turned, *(rng.uniform(lo, hi) for _ in range(n - 1))]

    def _near(self, q: np.ndarray, seed: np.ndarray) -> np.ndarray:
        """``q`` with each joint turned by whole turns to lie nearest ``seed`` inside its limits: the same pose (a
        restart, drawn anywhere, lands a full turn off as often as not, and a UR's joints turn +-2 turns), and the
        motion from the seed (the previous solution) stays continuous instead of jumping a turn."""
        if self._no_turn(q, seed):  # almost always (an answer next to its seed, inside the limits): q as it is
            return q.copy()
        out = q.copy()
        for k in (np.round((seed - q) / (2 * math.pi)), np.round((np.clip(q, self.arm_lower, self.arm_upper) - q)
                                                                 / (2 * math.pi))):
            cand = q + k * 2 * math.pi
            ok = (cand >= self.arm_lower - 1e-6) & (cand <= self.arm_upper + 1e-6)
            out = np.where(ok & ((out < self.arm_lower - 1e-6) | (out > self.arm_upper + 1e-6)
                                 | (np.abs(cand - seed) < np.abs(out - seed))), cand, out)
        return out

    def _no_turn(self, q: np.ndarray, seed: np.ndarray) -> bool:
        """Whether :meth:`_near` turns no joint: both its whole-turn counts round to 0 for every joint (the same
        float steps as its numpy arrays; NaN is not 0), so every candidate it weighs is ``q`` itself. In plain
        floats: a solve makes thousands of these seven-element checks, where numpy's per-call cost is the cost."""
        two_pi = 2 * math.pi
        for v, s, lo, hi in zip(q.tolist(), seed.tolist(), self._lo_list, self._hi_list, strict=True):
            if not (abs((s - v) / two_pi) <= 0.5 and abs((min(max(v, lo), hi) - v) / two_pi) <= 0.5):
                return False
        return True

    def self_collision(self, q: np.ndarray) -> tuple[str, str] | None:
        """The two links of the arm that joints ``q`` put into each other, or None (:class:`.SelfCollision`, on a
        copy with every collision shape, loaded on the first call: IK itself never needs it)."""
        if self._shapes is None:
            from .self_collision import SelfCollision

            self._shapes = SelfCollision(self.spec, self.base_xyz)
        return self._shapes.overlap(q)

    def close(self) -> None:
        if self._shapes is not None:
            self._shapes.close()
        self.sim.close()


class Robot:
    """The simulated arm: position control of its joints at high gain, fingers held closed.

    It lives in ``sim`` (the world's simulator) as body :data:`ARM`; :meth:`load` puts it there (the
    world calls it after the blocks, on creation and on every reset), while its IK twin stays.
    """

    def __init__(self, sim: Bullet, spec: ArmSpec, base_xyz: tuple[float, float, float], visuals: bool = True):
        self.sim, self.spec, self.visuals = sim, spec, visuals
        self.base_xyz = np.array(base_xyz, float)
        self.kin = Kinematics(spec, base_xyz)
        self.joint_ids = list(spec.arm_joints)
        self.gains = [spec.position_gain] * len(self.joint_ids)

    def load(self) -> None:
        """Load the arm at home into the simulator. Without rendering the visual meshes are dead weight
        (most of the load time): physics is the same."""
        load_arm(self.sim, arm_urdf(self.spec, visuals=self.visuals), self.base_xyz.tolist())
        info = self.sim.joints(ARM)
        self.forces = [info[j].max_force for j in self.spec.arm_joints]
        self.reset(np.array(self.spec.home))
        self.drop = self.fingertip_drop()
        self.closed_gap = self._fingertip_gap()  # with the fingers closed (reset closes them)

    def reset(self, q: np.ndarray) -> None:
        """Teleport the arm to joints ``q`` (fingers closed) and hold it there."""
        self.sim.reset_joints(ARM, self.spec.arm_joints, q)
        self.sim.reset_joints(ARM, self.spec.finger_joints, self.spec.finger_closed)
        self.command(np.asarray(q, float))
        self.sim.control_joints(ARM, list(self.spec.finger_joints), list(self.spec.finger_closed),
                                [20.0] * len(self.spec.finger_joints))

    def fingertip_drop(self) -> float:
        """How far the fingertips reach below the tool point (metres), measured on the collision shapes
        with the tool pointing down (the home pose does; the kinematic twin has no shapes)."""
        pos, _ = self.tool_pose()
        low = min(self.sim.aabb(ARM, link)[0][2] for link in self.spec.fingertip_links)
        return float(pos[2] - low)

    def hand_profile(self, depths: tuple[float, ...]) -> list[tuple[float, float, float]]:
        """Measure what the arm puts at block height: for each depth ``d``, the half extents (hx, hy) in the
        tool frame (x along the tool's yaw) of every collision shape of the arm lower than ``d`` above the
        fingertips, Bullet's collision margin included. The arm must point down; only the links from the wrist
        on count (the hand turns with the tool's yaw; the rest of the arm stays high above the blocks).

        The shapes are convex hulls of the meshes: a hull's part below a height is the hull of its
        vertices below it and of the points where the hull's vertex pairs cross that height.
        """
        pos, _ = self.tool_pose()
        yaw = self.tool_yaw()
        c, s = math.cos(-yaw), math.sin(-yaw)
        rot = np.array([[c, -s], [s, c]])
        floor = pos[2] - self.drop  # the fingertips' lowest point
        links = []
        for link in range(self.spec.wrist_joint, len(self.sim.joints(ARM))):
            v = self.sim.collision_vertices(ARM, link)
            if not len(v):
                continue
            lo = np.asarray(self.sim.aabb(ARM, link)[0])
            # the bounding box's slack below a shape turned about z only
            margin = max(float(v[:, 2].min() - lo[2]), 0.0)
            rel = np.column_stack([(v[:, :2] - pos[:2]) @ rot.T, v[:, 2] - floor])
            links.append((rel, margin))
        out = []
        for d in depths:
            hx = hy = 0.0
            for rel, m in links:
                cut = d + m  # a margin-grown shape reaches m below its hull
                below, above = rel[rel[:, 2] <= cut], rel[rel[:, 2] > cut]
                if not len(below):
                    continue
                wide = np.abs(below[:, :2]).max(axis=0)
                hx, hy = max(hx, float(wide[0]) + m), max(hy, float(wide[1]) + m)
                if len(above):
                    hx = max(hx, _widest_crossing(below, above, cut, 0, float(wide[0])) + m)
                    hy = max(hy, _widest_crossing(below, above, cut, 1, float(wide[1])) + m)
            out.append((float(d), hx, hy))
        return out

    def drive_fingers(self, targets: dict[int, float]) -> None:
        """Drive the gripper joints to ``targets`` (joint index -> position) with every mimic joint
        (``ArmSpec.finger_mimic``) following its leader: PyBullet ignores a URDF's ``<mimic>``, and a linkage
        whose joints are driven apart tears (a Robotiq's inner fingers would swing free of its knuckles)."""
        goal = {j: float(v) for j, v in zip(self.spec.finger_joints, self.spec.finger_closed, strict=True)}
        goal.update({int(j): float(v) for j, v in targets.items()})
        for j, lead, mult, off in self.spec.finger_mimic:
            goal[j] = mult * goal[lead] + off
        joints = list(self.spec.finger_joints)
        self.sim.control_joints(ARM, joints, [goal[j] for j in joints], [20.0] * len(joints))

    def command(self, q: np.ndarray) -> None:
        """Set the arm's joint targets (the motors track them during the next physics steps)."""
        self.sim.control_joints(ARM, self.joint_ids, q.tolist(), self.forces, self.gains)

    def finger_opening(self) -> float:
        """How far the fingers are open now (m; 0 closed): the fingertip links' distance beyond the one they
        have closed. Measured on the links, not read off the joints, so that it means the same for every arm
        (the Panda's fingers slide, the xArm's turn on a linkage: a joint value in radians is no width)."""
        return round(max(0.0, self._fingertip_gap() - self.closed_gap), 9) + 0.0

    def _fingertip_gap(self) -> float:
        tips = [np.array(self.sim.link_pose(ARM, link)[0]) for link in self.spec.fingertip_links]
        return float(np.linalg.norm(tips[0] - tips[-1])) if len(tips) > 1 else 0.0

    def joints(self) -> np.ndarray:
        return self.sim.joint_positions(ARM, self.spec.arm_joints)

    def tool_pose(self) -> tuple[np.ndarray, tuple[float, ...]]:
        pos, orn = self.sim.link_pose(ARM, self.spec.tool_link)
        return np.array(pos), orn

    def tool_yaw(self) -> float:
        _, orn = self.tool_pose()
        m = self.sim.rotation_matrix(orn)
        return math.atan2(m[3], m[0])  # the tool's x axis projected on the table

    def close(self) -> None:
        """Disconnect the IK twin (the world's simulator is the world's to close)."""
        self.kin.close()


CROSSING_SLACK = 1e-12
"""Metres by which a crossing point's computed coordinate may exceed both of its ends' (rounding: about 1e-16)."""


def _widest_crossing(below: np.ndarray, above: np.ndarray, cut: float, axis: int, widest: float) -> float:
    """The largest ``|coordinate axis|`` of the points where the segments from each vertex of ``below`` to each of
    ``above`` cross the height ``cut``; ``-inf`` where none of them can be wider than ``widest``. Why only the
    vertices above that stick out past ``widest``: a crossing lies between its two ends, so a pair whose ends are
    both within ``widest`` (less :data:`CROSSING_SLACK`) crosses within it, and the hull's vertex pairs (millions on
    a meshed hand) need not all be formed. The pairs kept are computed as every pair would be, so the maximum is
    the same number."""
    above = above[np.abs(above[:, axis]) > widest - CROSSING_SLACK]
    if not len(above):
        return -math.inf
    t = (cut - below[:, None, 2]) / (above[None, :, 2] - below[:, None, 2])
    return float(np.abs(below[:, None, axis] + t * (above[None, :, axis] - below[:, None, axis])).max())
