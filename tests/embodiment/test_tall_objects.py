"""Tall objects: a push that would tip one over is refused up front with the reason, and a tall object held
is moved with softer starts and stops; a cube is neither."""

from __future__ import annotations

import pytest

from l2p_bullet.core.scene import Scene, SceneObject, shaped
from l2p_bullet.embodiment.manners import TALL_ACCELERATION, check_manner, tall_pace, tip_refusal
from l2p_bullet.embodiment.smoothing import PACES, pace
from l2p_bullet.errors import InfeasibleError
from l2p_bullet.manners import registry as manners

CUBE_B = SceneObject("B", "green", 0.04, (0.0, 0.1), 0.0)


def _scene(mover) -> Scene:
    return Scene([mover, CUBE_B, SceneObject("A", "red", 0.04, (-0.1, 0.0), 0.0)])


CEREAL = shaped("M", "yellow", (0.1, -0.08), 0.0, shape="box", dims=(0.10, 0.03, 0.15))
MILK = shaped("M", "yellow", (0.1, -0.08), 0.0, shape="cylinder", radius=0.022, height_m=0.16)


def test_a_push_that_would_tip_a_tall_narrow_object_is_refused_with_the_reason():
    """A 15 cm box 3 cm deep tipped under the push (the push stopped, 'tipped', and the run failed)."""
    why = tip_refusal(_scene(CEREAL), "M")
    assert why is not None and "tip" in why and "15 cm tall" in why and "3.0 cm wide" in why and "\n" not in why
    with pytest.raises(InfeasibleError) as e:
        check_manner(manners.get("push"), _scene(CEREAL), "M")
    assert e.value.check == "push"


def test_a_push_refused_for_tipping_before_anything_is_planned():
    from l2p_bullet.pipeline import prepare

    with pytest.raises(InfeasibleError, match="tip"):
        prepare("push M past B", _scene(CEREAL))


@pytest.mark.parametrize("mover", [MILK, SceneObject("M", "yellow", 0.06, (0.1, -0.08), 0.0),
                                   shaped("M", "yellow", (0.1, -0.08), 0.0, shape="box", dims=(0.06, 0.03, 0.03))])
def test_objects_that_slide_under_a_push_are_not_refused(mover):
    assert tip_refusal(_scene(mover), "M") is None


def test_a_tall_object_is_held_with_softer_accelerations_and_a_cube_is_not():
    normal = pace(None)
    assert tall_pace(normal, CUBE_B) is normal
    assert tall_pace(PACES["fast"], CUBE_B) is PACES["fast"]
    soft = tall_pace(normal, MILK)
    assert soft.acceleration == normal.acceleration * TALL_ACCELERATION and soft.jerk == normal.jerk * TALL_ACCELERATION
    assert soft.velocity == normal.velocity
    assert tall_pace(normal, shaped("M", "y", (0, 0), 0.0, shape="box", dims=(0.06, 0.03, 0.04))) is normal


class _Enough(Exception):
    pass


def test_a_tall_object_is_slid_with_its_softer_pace_and_a_cube_is_not(monkeypatch):
    import numpy as np

    from l2p_bullet.embodiment import execute

    seen = []

    def stop(prims, *args, **kwargs):
        seen.append(prims.pace)
        raise _Enough

    monkeypatch.setattr(execute, "_perform", stop)
    for mover in (MILK, SceneObject("M", "yellow", 0.04, (0.1, -0.08), 0.0)):
        path = np.array([[0.1, -0.08, 0.0], [0.13, -0.08, 0.0]])
        with pytest.raises(_Enough):
            execute.execute_path(_scene(mover), "M", path, out_dir=None, render=None)
    assert seen[0].acceleration == TALL_ACCELERATION and seen[1] is pace(None)


def test_a_chain_clause_holding_a_tall_object_takes_its_softer_pace(monkeypatch, tmp_path):
    from l2p_bullet.chain.run import perform_chain
    from l2p_bullet.embodiment import execute

    seen = []

    def stop(prims, *args, **kwargs):
        seen.append(prims.pace)
        raise _Enough

    monkeypatch.setattr(execute, "act", stop)
    with pytest.raises(_Enough):
        perform_chain("move M closer to B and then move A closer to B", _scene(MILK), out_dir=tmp_path / "run",
                      render=False)
    assert seen and seen[0].acceleration == TALL_ACCELERATION
