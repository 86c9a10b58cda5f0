"""The arm in the world: joint control, tool pose, and inverse kinematics with failure detection.

IK runs on a kinematic twin of the arm in a second, private DIRECT client: PyBullet's IK seeds from a
body's current joints and checking a solution needs forward kinematics, and doing either on the
simulated arm would teleport it. The twin is never stepped, so it costs nothing in the physics loop.
"""

from __future__ import annotations

import math

import numpy as np

from ...errors import ReachError
from .arms import ArmSpec, arm_urdf
from .client import new_client

IK_POS_TOL = 0.002  # metres between the commanded and the reached tool point
IK_ANG_TOL = math.radians(2.0)  # tool orientation error


def down_quaternion(pb, spec: ArmSpec, yaw: float) -> tuple[float, ...]:
    """The tool pointing down, turned by ``yaw`` about the vertical."""
    return pb.getQuaternionFromEuler([spec.down_euler[0], spec.down_euler[1], yaw])


def quat_angle(a, b) -> float:
    """Angle (radians) between two unit quaternions (x, y, z, w)."""
    d = abs(float(np.dot(a, b)))
    return 2.0 * math.acos(min(1.0, d))


class Kinematics:
    """IK and FK on a private copy of the arm. ``solve`` raises :class:`ReachError` on failure."""

    def __init__(self, spec: ArmSpec, base_xyz: tuple[float, float, float]):
        self.client = new_client()
        import pybullet as pb

        self.pb, self.spec = pb, spec
        self.body = self.client.loadURDF(arm_urdf(spec, visuals=False, collisions=False), base_xyz,
                                         useFixedBase=True)
        c, b = self.client, self.body
        info = [c.getJointInfo(b, j) for j in range(c.getNumJoints(b))]
        # IK returns one value per movable joint, in joint order: remember where the arm's are.
        movable = [j for j in range(len(info)) if info[j][2] != pb.JOINT_FIXED]
        self.ik_index = [movable.index(j) for j in spec.arm_joints]
        self.lower = np.array([info[j][8] for j in movable])
        self.upper = np.array([info[j][9] for j in movable])
        self.arm_lower = self.lower[self.ik_index]
        self.arm_upper = self.upper[self.ik_index]
        self.movable = movable
        self.cid = c._client
        self.current: np.ndarray | None = None  # the twin's joints now (skips a reset when unchanged)
        self.joint_ids = list(spec.arm_joints)
        self.n_solves = 0
        for j, q in zip(spec.finger_joints, spec.finger_closed, strict=True):
            c.resetJointState(b, j, q)

    def set(self, q: np.ndarray) -> None:
        # Hot path (several calls per IK): one multi-joint call, straight to pybullet with the client id
        # (BulletClient's attribute wrapper costs a few microseconds per call).
        self.pb.resetJointStatesMultiDof(self.body, self.joint_ids, [[float(v)] for v in q], physicsClientId=self.cid)

    def fk(self, q: np.ndarray) -> tuple[np.ndarray, tuple[float, ...]]:
        """Tool position and orientation quaternion for arm joints ``q``."""
        self.set(q)
        s = self.pb.getLinkState(self.body, self.spec.tool_link, computeForwardKinematics=True,
                                 physicsClientId=self.cid)
        return np.array(s[4]), s[5]

    def _try(self, pos, orn, seed: np.ndarray, iterations: int, rounds: int, null_space: bool):
        """Damped least squares from ``seed`` (PyBullet seeds from the twin's joints), re-seeded
        ``rounds`` times. Plain DLS converges near the reach limit where the null-space variant stalls
        millimetres short; the null-space variant (pulled towards ``seed``) is the fallback when plain
        DLS ends outside a joint limit."""
        b = self.body
        extra = {}
        if null_space:
            rest = np.zeros(len(self.movable))
            rest[self.ik_index] = seed
            extra = dict(lowerLimits=self.lower.tolist(), upperLimits=self.upper.tolist(),
                         jointRanges=(self.upper - self.lower).tolist(), restPoses=rest.tolist())
        q = np.asarray(seed, float)
        err = ang = math.inf
        for _ in range(rounds):
            if self.current is None or not np.array_equal(self.current, q):
                self.set(q)
            sol = self.pb.calculateInverseKinematics(b, self.spec.tool_link, pos, orn, maxNumIterations=iterations,
                                                     residualThreshold=1e-6, physicsClientId=self.cid, **extra)
            q = np.asarray(sol)[self.ik_index]
            got, got_orn = self.fk(q)
            self.current = q
            err, ang = float(np.linalg.norm(got - pos)), quat_angle(got_orn, orn)
            if err < IK_POS_TOL * 0.25 and ang < IK_ANG_TOL * 0.25:
                break
        return q, err, ang

    def solve(self, pos, yaw: float, seed: np.ndarray, *, iterations: int = 10, rounds: int = 8,
              seeds: tuple[tuple[float, ...], ...] = ()) -> np.ndarray:
        """Joints putting the tool at ``pos`` pointing down with ``yaw``; ReachError when impossible.

        Tries ``seed`` first (the previous solution: cheap and continuous), then ``seeds``.
        A solution counts only if its forward kinematics lands within tolerance and every joint is
        inside its limits: PyBullet's IK returns its best effort without saying it failed.
        """
        self.n_solves += 1
        pos = np.asarray(pos, float)
        orn = down_quaternion(self.pb, self.spec, yaw)
        best = None
        attempts = [(seed, False, iterations)] + [(s, ns, max(iterations, 50)) for s in (seed, *seeds)
                                                  for ns in (False, True)]
        for s, null_space, its in attempts:
            q, err, ang = self._try(pos, orn, np.asarray(s, float), its, rounds, null_space)
            inside = bool(np.all(q >= self.arm_lower - 1e-6) and np.all(q <= self.arm_upper + 1e-6))
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

    def close(self) -> None:
        if self.client is not None:
            self.client.disconnect()
            self.client = None


class Robot:
    """The simulated arm: position control of its joints at high gain, fingers held closed."""

    def __init__(self, world, spec: ArmSpec, base_xyz: tuple[float, float, float], visuals: bool = True):
        self.world, self.spec = world, spec
        c = world.client
        # Without rendering the visual meshes are dead weight (most of the load time): physics is the same.
        self.body = c.loadURDF(arm_urdf(spec, visuals=visuals), base_xyz, useFixedBase=True)
        self.base_xyz = np.array(base_xyz, float)
        self.kin = Kinematics(spec, base_xyz)
        self.forces = [c.getJointInfo(self.body, j)[10] for j in spec.arm_joints]
        self.joint_ids = list(spec.arm_joints)
        self.gains = [spec.position_gain] * len(self.joint_ids)
        self.reset(np.array(spec.home))
        self.drop = self.fingertip_drop()

    def reset(self, q: np.ndarray) -> None:
        c = self.world.client
        for j, v in zip(self.spec.arm_joints, q, strict=True):
            c.resetJointState(self.body, j, float(v))
        for j, v in zip(self.spec.finger_joints, self.spec.finger_closed, strict=True):
            c.resetJointState(self.body, j, v)
        self.command(np.asarray(q, float))
        c.setJointMotorControlArray(
            self.body, list(self.spec.finger_joints), self.world.pb.POSITION_CONTROL,
            targetPositions=list(self.spec.finger_closed), forces=[20.0] * len(self.spec.finger_joints),
        )

    def fingertip_drop(self) -> float:
        """How far the fingertips reach below the tool point (metres), measured on the collision shapes
        with the tool pointing down (the home pose does; the kinematic twin has no shapes)."""
        pos, _ = self.tool_pose()
        c = self.world.client
        low = min(c.getAABB(self.body, link)[0][2] for link in self.spec.fingertip_links)
        return float(pos[2] - low)

    def command(self, q: np.ndarray) -> None:
        """Set the arm's joint targets (the motors track them during the next physics steps)."""
        self.world.pb.setJointMotorControlArray(
            self.body, self.joint_ids, self.world.pb.POSITION_CONTROL, targetPositions=q.tolist(),
            forces=self.forces, positionGains=self.gains, physicsClientId=self.world.cid,
        )

    def joints(self) -> np.ndarray:
        states = self.world.client.getJointStates(self.body, list(self.spec.arm_joints))
        return np.array([s[0] for s in states])

    def tool_pose(self) -> tuple[np.ndarray, tuple[float, ...]]:
        s = self.world.pb.getLinkState(self.body, self.spec.tool_link, computeForwardKinematics=True,
                                       physicsClientId=self.world.cid)
        return np.array(s[4]), s[5]

    def tool_yaw(self) -> float:
        _, orn = self.tool_pose()
        m = self.world.client.getMatrixFromQuaternion(orn)
        return math.atan2(m[3], m[0])  # the tool's x axis projected on the table

    def close(self) -> None:
        self.kin.close()
