"""The auto camera frames every object, the path and the hand at rest, from behind the robot; the contact
sheet's panels carry their time and clause."""

from __future__ import annotations

import numpy as np
import pytest

from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.embodiment.overlay import BACKGROUND
from l2p_bullet.embodiment.record import contact_sheet
from l2p_bullet.embodiment.sim.camera import CAMERAS, RenderSettings, framed_for, parse_camera
from l2p_bullet.embodiment.sim.framing import (
    CUBE_PX,
    TIPS_HEIGHT,
    action_of,
    cube_px,
    frame_action,
    must_see,
    project,
)

REST, BASE = (-0.066, 0.0, 0.40), (-0.53, 0.0, 0.0)


def _scene() -> Scene:
    return Scene([SceneObject("A", "red", 0.05, (0.05, -0.1)), SceneObject("B", "green", 0.05, (0.0, 0.05)),
                  SceneObject("C", "blue", 0.04, (0.12, 0.14))]).validate()


@pytest.mark.parametrize("manner", ["slide", "push", "carry"])
def test_the_auto_camera_holds_every_object_the_path_and_the_hand_at_rest(manner):
    scene = _scene()
    path = np.array([[0.05, -0.1, 0.0], [0.1, 0.0, 0.0], [0.05, 0.12, 0.0], [-0.05, 0.15, 0.0]])
    action = action_of(scene, [("A", path, manner)], REST, BASE)
    eye, target, fov = frame_action(action)
    xy, depth = project(must_see(action, TIPS_HEIGHT), np.array(eye), np.array(target), fov, 4 / 3)
    assert (depth > 0).all() and np.abs(xy).max() <= 1.0  # the hand at rest: its fingertips at least
    start = action.paths[0][0]  # a block there looks bigger than from the fixed camera that takes in the whole arm
    assert cube_px(np.array(eye), start) > 1.1 * cube_px(np.array(CAMERAS["viewer"].eye), start, CAMERAS["viewer"].fov)
    centres = [(*o.xy, o.height / 2) for o in scene.objects] + [tuple(p) for p in action.paths[0]]
    xy, _ = project(np.array(centres), np.array(eye), np.array(target), fov, 4 / 3)
    assert np.abs(xy).max() < 0.95  # with room to spare: the margin
    assert eye[0] < target[0]  # from behind the robot: its left is the picture's left
    left, right = project(np.array([[0.0, 0.1, 0.0], [0.0, -0.1, 0.0]]), np.array(eye), np.array(target), fov, 4 / 3)[0]
    assert left[0] < right[0]


def test_the_auto_camera_shows_a_4_cm_cube_at_1500_px_on_the_default_scene():
    scene = Scene(_scene().objects[:2])
    path = np.array([[0.05, -0.1, 0.0], [0.06, 0.0, 0.0], [0.05, 0.12, 0.0]])
    for manner in ("push", "slide"):
        action = action_of(scene, [("A", path, manner)], REST, BASE)
        eye, target, fov = frame_action(action)
        assert cube_px(np.array(eye), action.paths[0][0], fov) >= CUBE_PX


def test_a_named_camera_keeps_its_pose_and_auto_is_the_default():
    settings = RenderSettings(camera=parse_camera("viewer"))
    assert framed_for(settings, _scene(), [("A", np.zeros((2, 3)), "slide")], REST, BASE) is settings
    assert RenderSettings().camera.name == "auto" and parse_camera("auto").name == "auto"
    framed = framed_for(RenderSettings(), _scene(), [("A", np.array([[0.05, -0.1, 0], [0.1, 0.1, 0]]), "slide")],
                        REST, BASE)
    assert framed.camera.name == "auto" and framed.camera.eye != CAMERAS["viewer"].eye


def test_contact_sheet_panels_are_captioned_with_time_and_clause():
    images = [np.full((48, 64, 3), 200, np.uint8) for _ in range(10)]
    plain = contact_sheet(images, n=4, cols=2)
    sheet = contact_sheet(images, n=4, cols=2, times=[i * 0.5 for i in range(10)],
                          captions=["1/2: push A past B"] * 5 + ["2/2: move A around B"] * 5)
    assert plain.shape == (96, 128, 3) and sheet.shape[0] > plain.shape[0]
    panel_h = sheet.shape[0] // 2
    strip = sheet[48:panel_h, :64]
    assert (strip == BACKGROUND).all(axis=2).mean() > 0.5  # a caption strip ...
    assert (strip > 150).all(axis=2).sum() > 20  # ... with text on it
    first, last = sheet[48:panel_h, :64], sheet[panel_h + 48:, 64:]
    assert not np.array_equal(first, last)  # different times and clauses, different captions


def test_a_shadow_falls_away_from_the_light_under_a_lifted_block():
    from l2p_bullet.embodiment.render import SHADOW_LIFT, shadow_at
    from l2p_bullet.embodiment.sim.camera import LIGHT_DIRECTION

    x, y, z = shadow_at((0.1, 0.0, 0.1))
    assert z == SHADOW_LIFT
    assert np.sign(x - 0.1) == -np.sign(LIGHT_DIRECTION[0]) and np.sign(y) == -np.sign(LIGHT_DIRECTION[1])


@pytest.mark.slow
def test_a_carried_block_casts_a_visible_shadow_in_the_egl_video():
    from l2p_bullet.core.scene import default_scene
    from l2p_bullet.embodiment.render import Painter, capture

    painter = Painter(default_scene(), RenderSettings(320, 240, camera=CAMERAS["viewer"]))
    try:
        if painter.renderer != "egl":
            pytest.skip("EGL does not start here")
        state = capture(painter.world)
        (pos, orn), *rest = state.bodies
        lifted = type(state)(state.t, state.joints, (((pos[0], pos[1], pos[2] + 0.07), orn), *rest))
        with_shadow = painter.draw(lifted).astype(int)
        for shadow in painter.shadows.values():
            painter.world.sim.set_base_pose(shadow, (50.0, 50.0, 50.0), (0, 0, 0, 1))
        without = painter.camera.render().astype(int)
    finally:
        painter.close()
    darker = (with_shadow.sum(axis=2) < without.sum(axis=2) - 60).sum()
    assert darker > 40  # the shadow: a patch of the table, away from the block, in shade
