"""One inverse kinematics for every arm: the built-in arms solve with the restarts and whole-turn unwrapping
``new-arm``'s arms use (no arm relies on its seeds alone), their wrist model is what the simulator measures, and
the reach ring counts only poses where the arm does not fold into itself."""

from __future__ import annotations

import math

import numpy as np
import pytest

from l2p_bullet.arms import KUKA_IIWA, PANDA, XARM6
from l2p_bullet.embodiment import arm_measure
from l2p_bullet.embodiment.sim.robot import IK_ANG_TOL, IK_POS_TOL, Kinematics
from l2p_bullet.errors import ReachError

BUILT_IN = [PANDA, XARM6, KUKA_IIWA]


def _target(spec, r: float, az: float, z: float) -> tuple[float, float, float]:
    return (spec.mount[0] + r * math.cos(az), spec.mount[1] + r * math.sin(az), z)


@pytest.mark.parametrize("spec", BUILT_IN, ids=lambda s: s.name)
def test_a_built_in_arm_reaches_its_ring_from_a_seed_half_a_turn_off(spec):
    """The executor's tolerance (IK_POS_TOL, IK_ANG_TOL) at the near edge, the middle and the far edge of the arm's
    ring, from its home with the base joint turned nearly half a turn away and no other seed: the seeds alone reach
    3-4 of these 6 poses; the restarts every one."""
    assert spec.ik_restarts > 0
    kin = Kinematics(spec, spec.mount)
    try:
        near, far = spec.reach
        for r in (near + 0.01, (near + far) / 2, far - 0.01):
            for az in (-0.5, 0.5):
                seed = np.array(spec.home, float)
                seed[0] = az - math.copysign(0.9 * math.pi, az)
                seed = np.clip(seed, kin.arm_lower, kin.arm_upper)
                yaw = spec.wrist_offset + az - 0.5
                q = kin.solve(_target(spec, r, az, 0.05), yaw, seed)
                got, orn = kin.fk(q)
                m = kin.sim.rotation_matrix(orn)
                assert np.linalg.norm(got - _target(spec, r, az, 0.05)) <= IK_POS_TOL
                assert abs(math.remainder(math.atan2(m[3], m[0]) - yaw, 2 * math.pi)) <= IK_ANG_TOL
                assert abs(m[8] + 1.0) < 1e-3  # pointing down
                assert np.all(q >= kin.arm_lower - 1e-6) and np.all(q <= kin.arm_upper + 1e-6)
    finally:
        kin.close()


def test_a_solve_that_fails_names_the_pose_and_by_how_much():
    kin = Kinematics(PANDA, PANDA.mount)
    try:
        with pytest.raises(ReachError, match=r"cannot reach \(0\.900, 0\.000, 0\.050\) pointing down with yaw 0 deg "
                                             r"\(residual [\d.]+ mm"):
            kin.solve((0.9, 0.0, 0.05), 0.0, np.array(PANDA.home))
    finally:
        kin.close()


@pytest.mark.slow
@pytest.mark.parametrize("spec", BUILT_IN, ids=lambda s: s.name)
def test_a_built_in_arm_s_wrist_model_is_measured(spec):
    """wrist = offset + azimuth - yaw: the offset and the stray a built-in arm declares are what new-arm's
    measurement gives (within 0.01 rad; the stray declared at most 0.03 rad above the measured one)."""
    assert abs(math.remainder(arm_measure.wrist_offset(spec) - spec.wrist_offset, 2 * math.pi)) < 0.01
    stray = arm_measure.wrist_stray(spec)
    assert stray is not None and stray <= spec.wrist_error + 1e-3 <= stray + 0.03, (spec.name, stray)


def test_a_pose_folded_into_the_arm_is_not_reached():
    """Pointing down 7 cm from its base the xArm6 solves within tolerance, its gripper through its own base: the
    ring measurement refuses it; 30 cm out it is clear."""
    kin = Kinematics(XARM6, XARM6.mount)
    try:
        seed = arm_measure._in_plane(XARM6, np.asarray(XARM6.home, float), 0.0, 0.0)
        q = kin.solve(_target(XARM6, 0.07, 0.0, 0.012), XARM6.wrist_offset, seed, seeds=XARM6.ik_seeds)
        assert kin.self_collision(q) is not None
        assert "link_base" in kin.self_collision(q)
        assert not arm_measure.reaches(kin, XARM6, 0.07, 0.0, 0.012, 0.0)
        assert arm_measure.reaches(kin, XARM6, 0.3, 0.0, 0.012, 0.0)
    finally:
        kin.close()


def test_the_arm_at_home_does_not_collide_with_itself():
    for spec in BUILT_IN:
        kin = Kinematics(spec, spec.mount)
        try:
            assert kin.self_collision(np.array(spec.home)) is None
        finally:
            kin.close()


def test_the_whole_turn_shortcut_answers_what_weighing_every_turn_answers():
    """A solve turns its answer by whole turns to lie nearest its seed (``Kinematics._near``); where no joint would
    turn (``_no_turn``: almost every solve of a run) it keeps the answer as it is. Both ways give the same joints, to
    the bit, for answers inside and outside the limits, next to and turns away from their seeds, and on the half-turn
    boundary, where rounding decides."""
    kin = Kinematics(XARM6, XARM6.mount)
    try:
        rng = np.random.default_rng(5)
        lo, hi = kin.arm_lower, kin.arm_upper
        turned = 0
        for case in range(3000):
            q = rng.uniform(np.maximum(lo, -7) - (case % 3) * 0.5, np.minimum(hi, 7) + (case % 3) * 0.5)
            seed = q + rng.normal(0.0, (0.1, 1.0, 3.0, 6.0)[case % 4], len(q))
            if case % 5 == 0:  # exactly half a turn from the seed: rounds to no turn (half to even)
                seed = q + np.where(rng.uniform(size=len(q)) < 0.5, math.pi, -math.pi)
            shortcut = kin._no_turn(q, seed)
            turned += not shortcut
            full = kin._near(q, seed)
            if shortcut:
                assert full.tobytes() == q.tobytes()
            # the weighing itself, without the shortcut: the same joints
            kin._no_turn = lambda q, s: False
            try:
                assert kin._near(q, seed).tobytes() == full.tobytes(), (q, seed)
            finally:
                del kin._no_turn
        assert 300 < turned < 2700  # both ways were taken
    finally:
        kin.close()
