"""Rendering: frames are not blank and the blocks appear where the camera model projects them."""

from __future__ import annotations

import os

import numpy as np
import pytest

from l2p_bullet.core.scene import Scene, SceneObject, default_scene
from l2p_bullet.embodiment.sim.camera import Camera, RenderSettings
from l2p_bullet.embodiment.sim.world import World
from l2p_bullet.errors import ExecutionError


def _is(colour: str, px: np.ndarray) -> bool:
    r, g, b = (int(v) for v in px)
    return (r > 120 and g < 70 and b < 70) if colour == "red" else (g > 100 and r < 80 and b < 90)


def project(cam: Camera, points: np.ndarray) -> np.ndarray:
    """Pixel (column, row) of world points (K,3): the pinhole model, from the matrices the renderer uses."""
    view = np.asarray(cam.view).reshape(4, 4).T  # PyBullet's matrices are column-major
    proj = np.asarray(cam.proj).reshape(4, 4).T
    p = np.column_stack([np.asarray(points, float), np.ones(len(points))])
    clip = (proj @ view @ p.T).T
    ndc = clip[:, :3] / clip[:, 3:4]
    col = (ndc[:, 0] + 1.0) * 0.5 * cam.settings.width
    row = (1.0 - ndc[:, 1]) * 0.5 * cam.settings.height
    return np.column_stack([col, row])


def _window(img: np.ndarray, col: float, row: float, half: int = 2) -> np.ndarray:
    c, r = int(round(col)), int(round(row))
    return img[r - half : r + half + 1, c - half : c + half + 1].reshape(-1, 3)


SCENE = Scene([SceneObject("A", "red", 0.05, (0.1, -0.12), 0.4), SceneObject("B", "green", 0.05, (-0.1, 0.1))])


@pytest.fixture(scope="module")
def rendered():
    world = World(SCENE.validate())
    cam = Camera(world, RenderSettings(width=320, height=240, renderer="tiny"))
    img = cam.render()
    yield world, cam, img
    world.close()


def test_frame_is_not_blank(rendered):
    _, _, img = rendered
    assert img.shape == (240, 320, 3) and img.dtype == np.uint8
    assert img.std() > 20 and len(np.unique(img.reshape(-1, 3), axis=0)) > 50


def test_blocks_appear_where_the_camera_model_says(rendered):
    world, cam, img = rendered
    for name, colour in (("A", "red"), ("B", "green")):
        x, y, z, _ = world.pose(name)
        top = project(cam, np.array([[x, y, z + 0.025]]))[0]  # the centre of the block's top face
        assert all(_is(colour, px) for px in _window(img, *top)), f"{name} not {colour} at {top}"
        other = "green" if colour == "red" else "red"
        assert not any(_is(other, px) for px in _window(img, *top))
    # the table between them is neither
    mid = project(cam, np.array([[0.0, 0.0, 0.0]]))[0]
    assert not any(_is("red", px) or _is("green", px) for px in _window(img, *mid))


def test_rendering_is_deterministic(rendered):
    _, cam, img = rendered
    assert np.array_equal(cam.render(), img)


def test_a_reset_world_renders_like_a_new_one(rendered):
    """Blocks of the scene before a reset leave no trace in the images (the renderer is reset too)."""
    _, cam, img = rendered
    with World(default_scene()) as world:
        before = Camera(world, cam.settings).render()
        world.reset(SCENE)
        assert np.array_equal(Camera(world, cam.settings).render(), img)
        assert not np.array_equal(before, img)


def test_unknown_renderer_is_a_clear_error(rendered):
    world, _, _ = rendered
    with pytest.raises(ExecutionError, match='unknown renderer "vulkan"'):
        Camera(world, RenderSettings(renderer="vulkan"))


def test_egl_renders_the_same_scene_or_says_why(capfd):
    try:
        world = World(SCENE, visuals=True, egl=True)
    except ExecutionError as e:  # where the plugin does not load, a clear message
        assert str(e) == "the EGL renderer plugin does not load here; use --renderer tiny", e
        # CI (CI=true) installs EGL: there a plugin that does not load is a failure, never a quiet pass
        # (as tests/conftest.py does for Chromium); elsewhere the rendering half is reported as skipped
        if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
            pytest.fail(f"EGL is installed in CI but did not load: {e}")
        pytest.skip(f"EGL does not load here: {e}")
    try:
        cam = Camera(world, RenderSettings(width=320, height=240, renderer="egl"))
        img = cam.render()
        assert img.std() > 20
        for name, colour in (("A", "red"), ("B", "green")):
            x, y, z, _ = world.pose(name)
            top = project(cam, np.array([[x, y, z + 0.025]]))[0]
            assert sum(_is(colour, px) for px in _window(img, *top)) >= 20  # other pixels than Tiny's
        world.reset(default_scene())
        world.reset(SCENE)  # bodies loaded after a reset still reach the plugin
        assert np.array_equal(cam.render(), img)
    finally:
        world.close()
    out, err = capfd.readouterr()
    assert out == "" and err == ""  # the plugin's C-level chatter is hidden
