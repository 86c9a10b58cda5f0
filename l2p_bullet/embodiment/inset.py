"""The video's top-view inset: the blocks, their names and the planned path, seen from straight above.

The camera looks at the table at a slant, so depth is squashed: a block carried over another reads as
touching it, a row reads as a column. A small map in a corner of every frame shows the same moment without
foreshortening, in the 2-D view's orientation (the robot at the bottom, its left on the left, as the ``top``
camera and the teach page show it). It is drawn from the frame's recorded state (embodiment/render.py's
:class:`~.render.State`: each block's pose), not rendered: a few hundred microseconds a frame with Pillow.

The map's window and its corner are chosen once per video (:func:`plan_inset`), so nothing jumps: the
window holds every block at every frame and every path; the corner is the one where the objects and paths,
projected by the run's camera, leave the picture emptiest (the arm comes in from the top, so a tie goes to
a bottom corner).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.scene import Scene

SHARE = 0.3  # the inset's side as a share of the frame's height: legible names, most of the picture free
MIN_SIDE = 48  # px: below this the names are unreadable and the video goes without the inset
MARGIN = 0.03  # m of table around the outermost block or path point
BACKGROUND = (236, 226, 205)  # a light table wood: the blocks' colours stand out on it
OPACITY = 0.85  # of the inset over the video: the scene still shows faintly through it
EDGE = (90, 80, 62)
PATH = (70, 70, 70)
DONE = (30, 110, 200)  # the mover's track so far


@dataclass(frozen=True)
class TopView:
    """Where the inset goes in the frame and what of the table it shows (fixed for a whole video)."""

    left: int  # px, the inset's top-left corner in the frame
    top: int
    side: int  # px, the inset is square
    centre: tuple[float, float]  # m, the scene point at the inset's middle
    half: float  # m, half the width of table shown
    names: tuple[str, ...]  # the scene's objects, in scene (and State) order
    outlines: tuple[np.ndarray, ...]  # each object's footprint (K, 2) at pose (0, 0, 0), m
    colours: tuple[tuple[int, int, int], ...]
    paths: tuple[np.ndarray, ...]  # each (N, 2) m: a mover's planned centre
    movers: tuple[int, ...]  # each path's mover, as an index into names

    def pixel(self, xy: np.ndarray) -> np.ndarray:
        """Scene (x, y) (M, 2) -> inset pixels (M, 2): +x up, +y to the left (the robot's left)."""
        xy = np.asarray(xy, float).reshape(-1, 2)
        s = (self.side - 1) / (2 * self.half)
        return np.stack([(self.centre[1] - xy[:, 1]) * s + self.side / 2,
                         (self.centre[0] - xy[:, 0]) * s + self.side / 2], axis=1)


def plan_inset(scene: Scene, paths, states, width: int, height: int, camera=None) -> TopView | None:
    """The inset for a video of ``states`` (render.State) whose movers follow ``paths`` ((mover name, path
    (N, >=2)) each), in a ``width`` x ``height`` frame filmed with ``camera`` (a CameraPose; None: bottom
    right). None where the frame is too small for a legible one."""
    side = int(round(height * SHARE))
    if side < MIN_SIDE or not states:
        return None
    names = tuple(o.name for o in scene.objects)
    pts = [np.asarray(p, float)[:, :2] for _, p in paths]
    centres = np.array([b[0][:2] for s in states for b in s.bodies], float).reshape(-1, 2)
    reach = max((float(np.abs(o.footprint(np.zeros(3))).max()) for o in scene.objects), default=0.0)
    every = np.concatenate([centres, *pts]) if pts else centres
    lo, hi = every.min(axis=0) - reach - MARGIN, every.max(axis=0) + reach + MARGIN
    left, top = _corner(scene, pts, width, height, side, camera)
    return TopView(left, top, side, tuple((lo + hi) / 2), float((hi - lo).max() / 2), names,
                   tuple(o.footprint(np.zeros(3)) for o in scene.objects),
                   tuple(tuple(int(255 * c) for c in o.rgba[:3])
                         for o in scene.objects),
                   tuple(pts), tuple(names.index(m) for m, _ in paths if m in names))


def _corner(scene: Scene, paths: list[np.ndarray], width: int, height: int, side: int, camera) -> tuple[int, int]:
    """The corner (left, top) of the frame whose inset-sized square holds the fewest projected objects and
    path points; bottom corners first, the arm filling the top of the picture."""
    pad = max(2, side // 16)
    corners = [(width - side - pad, height - side - pad), (pad, height - side - pad),
               (width - side - pad, pad), (pad, pad)]
    if camera is None:
        return corners[0]
    from .sim.framing import project

    pts = [np.array([o.xy[0], o.xy[1], 0.02]) for o in scene.objects]
    pts += [np.c_[p, np.full(len(p), 0.02)] for p in paths]
    xy, depth = project(np.vstack(pts), np.array(camera.eye, float), np.array(camera.target, float),
                        camera.fov, width / height)
    px = np.stack([(xy[:, 0] + 1) / 2 * width, (1 - xy[:, 1]) / 2 * height], axis=1)[depth > 0]
    margin = side * 0.15  # a block drawn at a point spreads around it

    def hidden(corner: tuple[int, int]) -> int:
        x0, y0 = corner
        inside = ((px[:, 0] > x0 - margin) & (px[:, 0] < x0 + side + margin)
                  & (px[:, 1] > y0 - margin) & (px[:, 1] < y0 + side + margin))
        return int(inside.sum())

    return min(corners, key=hidden)  # min keeps the first of equals: the preference order above


class InsetPainter:
    """Draws a :class:`TopView` onto frames: the paths once, the blocks at each frame's state."""

    def __init__(self, view: TopView):
        from PIL import Image, ImageDraw

        self.view = view
        base = Image.new("RGB", (view.side, view.side), BACKGROUND)
        draw = ImageDraw.Draw(base)
        width = max(1, view.side // 60)
        for path in view.paths:
            if len(path) > 1:
                draw.line([tuple(p) for p in view.pixel(path)], fill=PATH, width=width)
            end = view.pixel(path[-1:])[0]
            r = max(2, view.side // 40)
            draw.ellipse((end[0] - r, end[1] - r, end[0] + r, end[1] + r), outline=PATH, width=width)
        draw.rectangle((0, 0, view.side - 1, view.side - 1), outline=EDGE, width=max(1, view.side // 80))
        self.base = base
        self.font = _font(max(9, view.side // 9))
        self.track: list[list[tuple[float, float]]] = [[] for _ in view.paths]

    def draw(self, image: np.ndarray, state) -> np.ndarray:
        """``image`` (H, W, 3) uint8 with the inset showing ``state``; a new array."""
        from PIL import ImageDraw

        v = self.view
        panel = self.base.copy()
        draw = ImageDraw.Draw(panel)
        for k, i in enumerate(v.movers):  # the mover's centre so far, under the blocks
            self.track[k].append(tuple(v.pixel(np.array(state.bodies[i][0][:2]))[0]))
            if len(self.track[k]) > 1:
                draw.line(self.track[k], fill=DONE, width=max(2, v.side // 40))
        for name, outline, colour, (pos, orn) in zip(v.names, v.outlines, v.colours, state.bodies, strict=True):
            yaw = _yaw(orn)
            c, s = math.cos(yaw), math.sin(yaw)
            poly = v.pixel(outline @ np.array([[c, s], [-s, c]]) + np.asarray(pos[:2]))
            draw.polygon([tuple(p) for p in poly], fill=colour, outline=EDGE)
            x, y = v.pixel(np.asarray(pos[:2]))[0]
            ink = (0, 0, 0) if sum(colour) > 450 else (255, 255, 255)
            draw.text((x, y), name, fill=ink, font=self.font, anchor="mm")
        out = np.array(image[:, :, :3], dtype=np.uint8, copy=True)
        region = out[v.top:v.top + v.side, v.left:v.left + v.side]
        region[:] = (OPACITY * np.asarray(panel, np.float32) + (1 - OPACITY) * region).astype(np.uint8)
        return out


def _yaw(orn) -> float:
    x, y, z, w = orn
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def _font(size: int):
    from .overlay import _font as overlay_font

    return overlay_font(size)
