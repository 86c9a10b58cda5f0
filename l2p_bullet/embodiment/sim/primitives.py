"""The paper's primitives on the simulated arm: ``engage(obj)``, ``move(path)``, ``disengage()``.

Every motion is: geometric end-effector path (motion.py) -> ruckig timing (smoothing.py) -> IK at the
control rate, all solved *before* the arm moves (so an unreachable pose raises ReachError with the world
untouched) -> physics steps with the joint targets interpolated between control samples.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ...errors import ExecutionError, ReachError
from .. import motion
from ..smoothing import NORMAL_PACE, Limits, Pace, Timed, time_parameterise
from .grasp import Grasp, attach, detach

CONTROL_HZ = 60.0
"""IK rate. Physics runs at 240 Hz with joint targets interpolated in between (IK is the costly part)."""
HOVER = 0.08  # m above the grasp height for approach and retract
APPROACH = Limits(velocity=0.3, acceleration=1.0, jerk=10.0, lateral=1.0)
DESCEND = Limits(velocity=0.1, acceleration=0.5, jerk=5.0, lateral=0.5)
SLIDE = Limits(velocity=0.1, acceleration=0.5, jerk=5.0, lateral=0.5)
SETTLE_S = 0.1  # s held still after touching the block and after letting go
MAX_TILT = math.radians(10.0)  # a held block tilting more than this means the grasp went wrong
MAX_SLIP = 0.01  # m between where the block is and where the grasp says it is
MAX_JOINT_JUMP = 0.5  # rad between neighbouring IK samples (<= 1 cm apart), beyond the yaw change: a flip


def tool_targets(block_poses: np.ndarray, yaw_offset: float, z: float,
                 offset_xy: np.ndarray = (0.0, 0.0)) -> np.ndarray:
    """Tool poses (M,4) holding a block at ``block_poses`` (M,3): tool = block + offset (block frame)."""
    c, s = np.cos(block_poses[:, 2]), np.sin(block_poses[:, 2])
    x = block_poses[:, 0] + c * offset_xy[0] - s * offset_xy[1]
    y = block_poses[:, 1] + s * offset_xy[0] + c * offset_xy[1]
    return np.column_stack([x, y, np.full(len(x), z), block_poses[:, 2] + yaw_offset])


def line_plan(start: np.ndarray, target: np.ndarray, limits: Limits, short_turn: bool = True) -> Timed:
    """A timed straight tool move; the yaw turns the short way round, or with ``short_turn`` False exactly to
    the target's yaw (the wrist then ends where that yaw puts it, on the branch the caller chose)."""
    target = np.asarray(target, float).copy()
    if short_turn:
        target[3] = start[3] + (target[3] - start[3] + math.pi) % (2 * math.pi) - math.pi
    return time_parameterise(motion.line(start, target), limits, 1.0 / CONTROL_HZ)


def slide_plan(path: np.ndarray, yaw_offset: float, z: float,
               offset_xy: np.ndarray = (0.0, 0.0), limits: Limits = SLIDE) -> list[Timed]:
    """The timed tool chunks of a slide: corners rounded or stopped at (motion.py), ruckig timing."""
    return [time_parameterise(tool_targets(ch, yaw_offset, z, offset_xy), limits, 1.0 / CONTROL_HZ)
            for ch in motion.slide_chunks(path)]


class Primitives:
    """Drives ``world.robot``; ``recorder()`` is called after every physics step and its ``grasped``
    attribute follows the grasp (see record.Recorder)."""

    def __init__(self, world, recorder):
        self.world, self.robot, self.recorder = world, world.robot, recorder
        self.q = self.robot.joints()
        pos, _ = self.robot.tool_pose()
        self.pose = np.array([pos[0], pos[1], pos[2], self.robot.tool_yaw()])  # last commanded tool pose
        self.grasp: Grasp | None = None
        self.pace: Pace = NORMAL_PACE  # the clause's manner adverb ("slowly"): scales every motion's limits
        self.steps_per_control = max(1, round(1.0 / (CONTROL_HZ * world.dt)))
        self.timed: list[tuple[str, Timed]] = []  # every timed chunk, for the summary
        self.ik_solves = 0
        # per stage, what the last pre-flight check solved: (joints it started from, samples, joints);
        # the run reuses or is seeded by them (see _solve_stage)
        self._preflight: dict[str, tuple[np.ndarray, np.ndarray, np.ndarray]] = {}

    # --- the control loop --------------------------------------------------------------------
    def solve(self, poses: np.ndarray, max_jump: float = MAX_JOINT_JUMP, guide: np.ndarray | None = None) -> np.ndarray:
        """Joint targets (K,7) for tool poses (K,4), each solved from a first guess next to the answer:
        the previous solution moved on by the last step (the arm moves smoothly: from there damped least
        squares converges in one round of 10 iterations, from the previous solution alone it needed 2-3),
        or ``guide[k]``, a solution for nearly the same pose, when given. The previous solution itself is
        the next seed, then the arm's other IK seeds.

        A solution from another seed may sit on another branch, so a joint jump larger than ``max_jump``
        between neighbouring samples (the arm flipping over mid-motion) is a ReachError (after one more
        try from the previous solution); the wrist's share of the yaw change does not count as a jump.
        """
        kin, out, q = self.robot.kin, np.empty((len(poses), len(self.q))), self.q
        extra = self.robot.spec.ik_seeds
        wrist = self.robot.spec.arm_joints.index(self.robot.spec.wrist_joint)
        before = q

        def jump_to(q_new: np.ndarray, k: int) -> float:
            step = np.abs(q_new - prev)
            turn = abs(float(poses[k][3] - poses[k - 1][3])) if k > 0 else 0.0
            step[wrist] = max(0.0, step[wrist] - turn)  # the wrist follows the yaw: only its excess counts
            return float(step.max()) if k > 0 else 0.0

        for k, p in enumerate(poses):
            prev = q
            if guide is not None:
                first = guide[k]
            else:  # the arm moves smoothly: the last step repeated is the better first guess, in the arm's plane
                first = self.in_plane(2 * prev - before if k > 0 else prev, p)
            q = kin.solve(p[:3], p[3], first, seeds=(tuple(prev), *extra))
            jump = jump_to(q, k)
            if jump > max_jump:  # the guess led elsewhere: start from where the arm is
                q = kin.solve(p[:3], p[3], prev, seeds=extra)
                jump = jump_to(q, k)
            before = prev
            if jump > max_jump:
                raise ReachError(
                    f"the arm would have to flip its configuration to reach ({p[0]:.3f}, {p[1]:.3f}) with "
                    f"yaw {math.degrees(p[3]):.0f} deg (a {jump:.1f} rad joint jump); keep the path in the "
                    "middle of the workspace or turn the block less")
            out[k] = q
        self.ik_solves += len(poses)
        return out

    def run(self, timed: Timed, stage: str, joints: np.ndarray | None = None) -> None:
        """Track a timed tool path: IK at the control rate first (unless given), then the physics steps."""
        if joints is None:
            joints = self._solve_stage(stage, self._control_samples(timed))
        self.timed.append((stage, timed))
        for q in joints:
            self._period(q)
        self.pose = timed.poses[-1].copy()

    def _period(self, q: np.ndarray, on_step: Callable[[], None] | None = None) -> None:
        """One control period: the joint targets go from the last commanded ``self.q`` to ``q`` over the physics
        steps in between (the recorder sees each), then ``q`` is the commanded position. ``on_step`` runs after
        each physics step, before the recorder (the push notes where the hand touches the block there)."""
        prev, n = self.q, self.steps_per_control
        for i in range(1, n + 1):
            self.robot.command(prev + (q - prev) * (i / n))
            self.world.step()
            if on_step is not None:
                on_step()
            self.recorder()
        self.q = q

    def step_to(self, q: np.ndarray) -> None:
        """One control period to the joints ``q`` (a learner's low-level command, envs/arm.py); the tool pose
        commanded next starts from where the tool then is."""
        self._period(q)
        pos, _ = self.robot.tool_pose()
        self.pose = np.array([pos[0], pos[1], pos[2], self.robot.tool_yaw()])

    def take(self, name: str) -> Grasp:
        """Fix block ``name`` to the tool where both are now (the grasp by constraint)."""
        self.grasp = attach(self.world, name)
        self.recorder.grasped = name
        return self.grasp

    def let_go(self) -> None:
        """Remove the grasp's constraint, if any."""
        if self.grasp is not None:
            detach(self.world, self.grasp)
            self.grasp = None
            self.recorder.grasped = None

    def in_plane(self, q: np.ndarray, pose: np.ndarray) -> np.ndarray:
        """``q`` moved into the arm's vertical plane through ``pose`` (ArmSpec.swivel_joints): base joint at
        the pose's azimuth, swivel joints at zero, wrist at the yaw's value there. A first guess only."""
        spec = self.robot.spec
        if not spec.swivel_joints:
            return q
        out = np.array(q, float)
        az = math.atan2(pose[1] - self.robot.base_xyz[1], pose[0] - self.robot.base_xyz[0])
        out[0] = az
        out[list(spec.swivel_joints)] = 0.0
        w = spec.arm_joints.index(spec.wrist_joint)
        wrist = spec.wrist_offset + az - pose[3]
        out[w] = wrist + 2 * math.pi * round((q[w] - wrist) / (2 * math.pi))  # the branch the wrist is on
        return out

    def _solve_stage(self, stage: str, samples: np.ndarray) -> np.ndarray:
        """IK for a stage's samples, using what the pre-flight check solved for the same stage: the very
        joints when the arm starts where the check did and the samples are the same (approach, descent:
        solving again would give the same numbers), as seeds when only the grasp's measured pose moved
        the samples a fraction of a millimetre (slide, retract, rest), nothing otherwise."""
        start, pre_samples, pre_joints = self._preflight.pop(stage, (None, None, None))
        if pre_samples is not None and pre_samples.shape == samples.shape:
            if np.array_equal(start, self.q) and np.array_equal(pre_samples, samples):
                self.ik_solves += len(samples)
                return pre_joints.copy()
            return self.solve(samples, guide=pre_joints)
        return self.solve(samples)

    def _control_samples(self, timed: Timed) -> np.ndarray:
        """The samples the arm is sent to: all but the first, which is where the tool already is
        (chunks are timed at the control period, see go and move)."""
        return timed.poses[1:] if len(timed.poses) > 1 else timed.poses

    def hold(self, seconds: float) -> None:
        for _ in range(max(1, round(seconds / self.world.dt))):
            self.robot.command(self.q)
            self.world.step()
            self.recorder()

    def go(self, target: np.ndarray, limits: Limits, stage: str, short_turn: bool = True) -> None:
        """Straight tool move from the last commanded pose to ``target`` ([x, y, z, yaw])."""
        self.run(line_plan(self.pose, target, self.pace.apply(limits), short_turn), stage)

    # --- the primitives ----------------------------------------------------------------------
    def grasp_height(self, name: str, tool_yaw: float = 0.0) -> float:
        """Tool height with the closed fingertips just touching the block's top (a mesh's: where the hand,
        turned to ``tool_yaw``, comes to rest on it, ``World.fingertip_height``)."""
        return self.world.fingertip_height(name, tool_yaw) + self.robot.drop

    def grasp_poses(self, name: str, yaw_offset: float = 0.0,
                    tool_yaw: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Tool poses above block ``name`` and with the fingertips on its top: the tool's yaw is the block's
        plus ``yaw_offset``, or ``tool_yaw`` exactly when given (an unwrapped value: it picks the wrist's branch)."""
        block = self.world.pose(name)
        yaw = block[3] + yaw_offset if tool_yaw is None else float(tool_yaw)
        z = self.grasp_height(name, yaw)
        down = np.array([block[0], block[1], z, yaw])
        return down + [0.0, 0.0, HOVER, 0.0], down

    def engage(self, name: str, yaw_offset: float = 0.0, tool_yaw: float | None = None) -> Grasp:
        """Approach ``name`` from above, descend until the closed fingers rest on its top, fix it.

        ``yaw_offset`` (a multiple of 90 deg) is the tool's yaw relative to the block's; or ``tool_yaw`` the
        tool's yaw itself, turned to exactly (not the short way), which decides where the wrist starts the
        slide: choose it with :func:`l2p_bullet.arms.reach.wrist_offsets` (execute.py does) so the wrist
        stays inside its range while sliding.
        """
        if self.grasp is not None:
            raise ExecutionError(f'already holding "{self.grasp.name}"; disengage first')
        above, down = self.grasp_poses(name, yaw_offset, tool_yaw)
        self.go(above, APPROACH, "approach", short_turn=tool_yaw is None)
        self.go(down, DESCEND, "descend")
        self.hold(SETTLE_S)
        return self.take(name)

    def tool_targets(self, block_poses: np.ndarray) -> np.ndarray:
        """Tool poses (M,4) that put the held block at ``block_poses`` (M,3), at the locked height."""
        g = self.grasp
        return tool_targets(block_poses, g.yaw_offset, g.tool_z, g.offset_xy)

    def slide_joints(self, timed: list[Timed]) -> list[np.ndarray]:
        """IK for every control sample of a whole slide, continuous across its chunks, per chunk."""
        samples = [self._control_samples(t) for t in timed]
        if not samples:
            return []
        joints = self._solve_stage("slide", np.concatenate(samples))
        return np.split(joints, np.cumsum([len(s) for s in samples])[:-1])

    def check_engage_and_slide(self, name: str, path: np.ndarray, tool_yaw: float,
                               rest: np.ndarray | None = None, lift: float = 0.0) -> None:
        """Solve the IK of the approach, descent, slide, retract and return to ``rest`` exactly as
        :meth:`engage`, :meth:`move` and :meth:`disengage` will (same chunks, timing and seeds, nominal
        grasp height) without moving anything, so an unreachable pose is a ReachError now rather than
        halfway through. The arm's state is kept. ``lift`` > 0: the carry's lift, path in the air and
        lowering (:meth:`carry`) instead of the slide."""
        saved_q, saved_pose = self.q.copy(), self.pose.copy()
        self._preflight = {}
        solved = {}
        try:
            above, down = self.grasp_poses(name, tool_yaw=tool_yaw)
            solved["approach"] = self._check_line(above, APPROACH, short_turn=False)
            solved["descend"] = self._check_line(down, DESCEND)
            offset = tool_yaw - float(self.world.pose(name)[3])
            if lift > 0:
                solved["lift"] = self._check_line(down + [0.0, 0.0, lift, 0.0], DESCEND)
            p = self._continued(path, offset)
            timed = slide_plan(p, offset, float(down[2]) + lift, limits=self.pace.apply(SLIDE))
            if timed:
                samples = np.concatenate([self._control_samples(t) for t in timed])
                joints = self.solve(samples)
                solved["slide"] = (self.q, samples, joints)
                self.q, self.pose = joints[-1], timed[-1].poses[-1].copy()
            if lift > 0:
                solved["lower"] = self._check_line(self.pose - [0.0, 0.0, lift, 0.0], DESCEND)
            up = self.pose + [0.0, 0.0, HOVER, 0.0]
            solved["retract"] = self._check_line(up, DESCEND)
            if rest is not None:
                solved["rest"] = self._check_line(rest, APPROACH, short_turn=False)
            self._preflight = solved  # every stage reachable: the run may use them
        finally:
            self.q, self.pose = saved_q, saved_pose

    def _check_line(self, target: np.ndarray, limits: Limits,
                    short_turn: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        timed = line_plan(self.pose, target, self.pace.apply(limits), short_turn)
        start, samples = self.q, self._control_samples(timed)
        joints = self.solve(samples)
        self.q, self.pose = joints[-1], timed.poses[-1].copy()
        return start, samples, joints

    def _continued(self, path: np.ndarray, yaw_offset: float) -> np.ndarray:
        """The cleaned path with its yaw shifted by whole turns so that the tool's yaw (block yaw +
        ``yaw_offset``) continues from where the tool is, without a turn."""
        p = motion.clean_path(path)
        p[:, 2] += 2 * math.pi * round((self.pose[3] - yaw_offset - p[0, 2]) / (2 * math.pi))
        return p

    def move(self, path: np.ndarray) -> None:
        """Slide the held block along ``path`` (N,3) on the table, the grasp height locked."""
        if self.grasp is None:
            raise ExecutionError("move() needs a grasped block: engage(obj) first")
        g = self.grasp
        timed = slide_plan(self._continued(path, g.yaw_offset), g.yaw_offset, g.tool_z, g.offset_xy,
                           self.pace.apply(SLIDE))
        for t, joints in zip(timed, self.slide_joints(timed), strict=True):  # all IK before moving
            self.run(t, "slide", joints)
            self.check_grasp()

    def carry(self, path: np.ndarray, lift: float) -> None:
        """Lift the held block ``lift`` metres straight up, carry it along ``path`` (N,3) at that height,
        lower it onto the table at the path's end (the grasp height locked, as a slide's)."""
        if self.grasp is None:
            raise ExecutionError("carry() needs a grasped block: engage(obj) first")
        g = self.grasp
        self.go(self.pose + [0.0, 0.0, lift, 0.0], DESCEND, "lift")  # the pre-flight check's joints reused
        self.check_grasp(lift)
        timed = slide_plan(self._continued(path, g.yaw_offset), g.yaw_offset, g.tool_z + lift, g.offset_xy,
                           self.pace.apply(SLIDE))
        for t, joints in zip(timed, self.slide_joints(timed), strict=True):  # all IK before moving
            self.run(t, "slide", joints)
            self.check_grasp(lift)
        down = self.pose - [0.0, 0.0, lift, 0.0]
        self.go(down, DESCEND, "lower")
        self.hold(SETTLE_S)

    def check_grasp(self, lift: float = 0.0) -> None:
        g = self.grasp
        if g is None:
            return
        if self.world.tilt(g.name) - g.tilt > MAX_TILT:  # from how it rested when grasped
            raise ExecutionError(
                f'block "{g.name}" tilted {math.degrees(self.world.tilt(g.name) - g.tilt):.0f} deg while held')
        pos, _ = self.robot.tool_pose()
        block = self.world.pose(g.name)
        want = self.tool_targets(block[None, [0, 1, 3]])[0] + [0.0, 0.0, lift, 0.0]
        if np.hypot(*(want[:2] - pos[:2])) > MAX_SLIP:
            raise ExecutionError(f'block "{g.name}" slipped out of the grasp')

    def disengage(self, rest: np.ndarray | None = None) -> None:
        """Remove the constraint, let go, retract straight up, then return to the rest pose."""
        self.let_go()
        self.hold(SETTLE_S)
        up = self.pose.copy()
        up[2] += HOVER
        self.go(up, DESCEND, "retract")
        if rest is not None:  # back to the rest pose's own yaw, so the wrist unwinds to where it started
            self.go(rest, APPROACH, "rest", short_turn=False)
