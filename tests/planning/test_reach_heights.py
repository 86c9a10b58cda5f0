"""The reach ring per tool height (``ArmSpec.reach_heights``, arms/fit.py: ``reach_for``): a scene is held to the
rows its blocks ask for, so "around" next to the rim of a narrow ring (a UR3e's) plans with the room the arm
reaches for those blocks, where the ring at every height (an 8 cm block's hover, a 2 cm block's grasp) left too
little for any way round."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from l2p_bullet.arms import PANDA, fit_scene
from l2p_bullet.arms.fit import TOOL_SPAN, reach_for
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.embodiment.arm_measure import REACH_HEIGHTS
from l2p_bullet.errors import InfeasibleError
from l2p_bullet.planning import sweep

# what new-arm measures for airo-models' UR3e + Robotiq 2F-85 (1 cm steps): every height reaches 0.21-0.46 m from
# the base, the heights a 4 cm cube asks for (3.2-15.2 cm) 0.18-0.49 m
UR3E_ROWS = ((0.012, 0.21, 0.54), (0.032, 0.18, 0.54), (0.052, 0.17, 0.53), (0.072, 0.18, 0.53), (0.092, 0.18, 0.52),
             (0.112, 0.17, 0.51), (0.132, 0.16, 0.5), (0.152, 0.15, 0.49), (0.172, 0.15, 0.48), (0.19, 0.15, 0.46))
NARROW = replace(PANDA, reach=(0.21, 0.46), mount=(-0.335, 0.0, 0.0), reach_heights=UR3E_ROWS)


def test_the_ring_s_test_heights_are_the_tool_span_of_the_blocks_they_were_chosen_for():
    assert REACH_HEIGHTS[0] == pytest.approx(0.02 + TOOL_SPAN[0]) and REACH_HEIGHTS[-1] == pytest.approx(
        0.08 + TOOL_SPAN[1])
    assert tuple(z for z, _, _ in UR3E_ROWS) == REACH_HEIGHTS


@pytest.mark.parametrize(("heights", "ring"), [
    ((0.04,), (0.18, 0.49)),  # 3.2-15 cm: the rows 0.032-0.152
    ((0.04, 0.04), (0.18, 0.49)),
    ((0.02, 0.08), (0.21, 0.46)),  # the 2-8 cm blocks the ring was measured for: the ring itself
    ((0.1,), (0.21, 0.46)),  # beyond the rows: the ring
    ((), (0.21, 0.46)),
])
def test_a_scene_is_held_to_the_rows_its_blocks_ask_for(heights, ring):
    assert reach_for(NARROW, heights) == ring
    assert reach_for(replace(NARROW, reach_heights=()), heights) == (0.21, 0.46)


def _scene(spec) -> Scene:
    """bench_arms.py's seed 220005 on the UR3e + Robotiq: the anchor 4.3 cm in from the ring's far edge, the mover
    4.7 blocks away on its inward side."""
    return fit_scene(Scene([SceneObject("A", "red", 0.04, (-0.1096, 0.0555), 3.1171),
                            SceneObject("B", "green", 0.04, (0.079, 0.0515), -0.5492)]).validate(), spec)


def test_around_next_to_a_narrow_ring_s_rim_plans_in_the_room_its_blocks_have():
    from l2p_bullet.judge.rules import rule_verdict
    from l2p_bullet.planning import plan
    from l2p_bullet.planning.world2d import interpolate
    from l2p_bullet.plugins import registry

    with pytest.raises(InfeasibleError) as e:  # held to every height: no way round fits
        sweep.blocked_around(_scene(replace(NARROW, reach_heights=())), "A", "B")
    assert e.value.check == "blocked-around"
    scene = _scene(NARROW)
    assert scene.workspace.ring == (-0.335, 0.0, 0.18, 0.49)
    sweep.room_around(scene, "A", "B")
    sweep.blocked_around(scene, "A", "B")
    p = plan(scene, "A", "B", registry.load("around"), seed=220005, arm=NARROW)
    assert scene.workspace.contains(p.path[:, :2]).all()
    frames = interpolate(p.path, 0.002)
    v = rule_verdict("around", frames, np.array(scene.get("B").pose), 0.04)
    assert v.success, v.reason
