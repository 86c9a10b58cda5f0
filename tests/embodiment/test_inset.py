"""The video's top-view inset: where it goes, what it shows, and that the video carries it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from l2p_bullet.core.scene import COLORS, Scene, SceneObject
from l2p_bullet.embodiment.inset import InsetPainter, plan_inset
from l2p_bullet.embodiment.render import State
from l2p_bullet.embodiment.sim.camera import CameraPose

W, H = 320, 240


def _scene() -> Scene:
    return Scene([SceneObject("A", "red", 0.04, (0.05, -0.10), 0.0), SceneObject("B", "blue", 0.04, (0.0, 0.10), 0.0)])


def _state(a_xy, b_xy=(0.0, 0.10), t=0.0) -> State:
    q = (0.0, 0.0, 0.0, 1.0)
    return State(t, (), (((a_xy[0], a_xy[1], 0.02), q), ((b_xy[0], b_xy[1], 0.02), q)))


def _share(img: np.ndarray, view, xy, colour: str) -> float:
    """The share of the pixels over a 4 cm block centred at ``xy`` that show ``colour`` through the inset."""
    x, y = view.pixel(np.array(xy))[0]
    r = 0.02 * (view.side - 1) / (2 * view.half) * 0.8
    px, py = view.left + x, view.top + y
    patch = img[int(py - r):int(py + r) + 1, int(px - r):int(px + r) + 1].reshape(-1, 3).astype(float)
    want = 0.85 * np.array(COLORS[colour][:3]) * 255
    return float((np.abs(patch - want).max(axis=1) < 12).mean())


def test_the_inset_shows_each_block_in_its_colour_where_it_is_seen_from_above():
    path = np.array([[0.05, -0.10, 0.0], [0.10, 0.0, 0.0], [0.05, 0.10, 0.0]])
    states = [_state((0.05, -0.10)), _state((0.10, 0.0), t=1.0)]
    view = plan_inset(_scene(), [("A", path)], states, W, H)
    frame = np.zeros((H, W, 3), np.uint8)
    painter = InsetPainter(view)
    first, second = painter.draw(frame, states[0]), painter.draw(frame, states[1])
    # B sits on the robot's left (+y): the inset's left half, as in the 2-D view; further A (+x) is higher up
    assert view.pixel(np.array([0.0, 0.10]))[0][0] < view.side / 2 < view.pixel(np.array([0.05, -0.10]))[0][0]
    assert view.pixel(np.array([0.10, 0.0]))[0][1] < view.pixel(np.array([0.05, -0.10]))[0][1]
    assert _share(first, view, (0.05, -0.10), "red") > 0.5  # the rest: the name written on it
    assert _share(first, view, (0.0, 0.10), "blue") > 0.5
    assert _share(second, view, (0.10, 0.0), "red") > 0.5  # A has moved there
    assert _share(second, view, (0.05, -0.10), "red") == 0  # and is gone from here
    # the inset covers its square only: the rest of the frame is the image as it was
    mask = np.ones((H, W), bool)
    mask[view.top:view.top + view.side, view.left:view.left + view.side] = False
    assert not first[mask].any() and first[~mask].any()
    assert not frame.any()  # the image passed in is not modified


def test_the_inset_goes_to_the_corner_the_action_leaves_free():
    scene = _scene()
    states = [_state((0.05, -0.10))]
    below = CameraPose(eye=(-0.8, 0.0, 0.6), target=(0.0, 0.0, 0.0))  # behind the robot: the blocks mid-frame
    view = plan_inset(scene, [], states, W, H, below)
    assert view.top > H / 2  # a bottom corner: the arm comes in from the top
    # a camera aimed well to the side of the blocks puts them in the frame's bottom right: the inset avoids it
    aside = CameraPose(eye=(-0.8, 0.35, 0.25), target=(0.0, 0.25, 0.1), fov=30.0)
    view = plan_inset(scene, [], states, W, H, aside)
    from l2p_bullet.embodiment.sim.framing import project

    xy, _ = project(np.array([[0.05, -0.10, 0.02], [0.0, 0.10, 0.02]]), np.array(aside.eye),
                    np.array(aside.target), aside.fov, W / H)
    px = (xy[:, 0] + 1) / 2 * W, (1 - xy[:, 1]) / 2 * H
    inside = ((px[0] >= view.left) & (px[0] <= view.left + view.side)
              & (px[1] >= view.top) & (px[1] <= view.top + view.side))
    assert not inside.any()


def test_no_inset_in_a_frame_too_small_for_legible_names():
    assert plan_inset(_scene(), [], [_state((0.05, -0.1))], 96, 64) is None
    assert plan_inset(_scene(), [], [], W, H) is None


def test_the_window_holds_every_block_and_path_point():
    far = (0.20, 0.30)
    path = np.array([[0.05, -0.10, 0.0], [-0.15, -0.25, 0.0]])
    view = plan_inset(_scene(), [("A", path)], [_state((0.05, -0.1)), _state(far)], W, H)
    for xy in (far, (-0.15, -0.25), (0.0, 0.10)):
        x, y = view.pixel(np.array(xy))[0]
        assert 0 < x < view.side and 0 < y < view.side
    assert math.isclose(view.side, round(H * 0.3))


@pytest.mark.slow
def test_the_video_carries_the_inset_and_the_frames_do_not(tmp_path):
    """A rendered episode: the video's frames differ from the PNGs in the inset's square only."""
    import imageio.v2 as imageio

    from l2p_bullet.embodiment.execute import execute_path
    from l2p_bullet.embodiment.sim.camera import RenderSettings

    scene = _scene()
    path = np.array([[0.05, -0.10, 0.0], [0.08, -0.05, 0.0]])
    settings = RenderSettings(W, H, fps=5.0, renderer="tiny", workers=0)
    execute_path(scene, "A", path, out_dir=tmp_path, render=settings, meta={"sentence": "move A"})
    video = [f for f in imageio.get_reader(tmp_path / "video.mp4")]
    png = imageio.imread(tmp_path / "frames" / "0000.png")
    diff = np.abs(video[0][:H].astype(float) - png.astype(float)).mean(axis=2)
    cells = diff.reshape(H // 8, 8, W // 8, 8).mean(axis=(1, 3)) > 20  # 8x8 cells: past the encoder's noise
    ys, xs = np.nonzero(cells)
    side = round(H * 0.3) / 8
    assert len(ys) > 0.5 * side**2  # the inset is there
    assert xs.max() - xs.min() <= side + 1 and ys.max() - ys.min() <= side + 1  # and only there
