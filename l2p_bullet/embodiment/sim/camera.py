"""A fixed camera looking at the table, its renderers, and the pinhole model that predicts pixels.

TinyRenderer (CPU) is the default: its images are bit-identical across processes. ``egl`` uses
PyBullet's EGL plugin where it loads (see World(egl=True); other pixels); it prints to the C-level
streams on load and on every frame, which :func:`~l2p_bullet.embodiment.sim.client.quiet_stdout` hides. It is never
unloaded explicitly (unloading segfaulted here): disconnecting the world's client ends it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import ExecutionError
from .client import quiet_stdout

RENDERERS = ("tiny", "egl")


@dataclass(frozen=True)
class RenderSettings:
    """What to render: image size, frames per second of simulated time, renderer, video format."""

    width: int = 320
    height: int = 240
    fps: float = 10.0
    renderer: str = "tiny"
    video: str = "mp4"  # "mp4" or "gif"


@dataclass(frozen=True)
class CameraPose:
    """Front right of the table, looking back at the arm: the workspace fills the lower image."""

    eye: tuple[float, float, float] = (0.5, -0.5, 0.6)
    target: tuple[float, float, float] = (-0.15, 0.0, 0.1)
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    fov: float = 50.0
    near: float = 0.05
    far: float = 3.0


class Camera:
    """Renders the world's client; :meth:`project` says where a world point lands in the image."""

    def __init__(self, world, settings: RenderSettings, pose: CameraPose = CameraPose()):
        if settings.renderer not in RENDERERS:
            raise ExecutionError(f'unknown renderer "{settings.renderer}" (known: {", ".join(RENDERERS)})')
        self.world, self.settings, self.pose = world, settings, pose
        c = world.client
        self.view = c.computeViewMatrix(pose.eye, pose.target, pose.up)
        self.proj = c.computeProjectionMatrixFOV(pose.fov, settings.width / settings.height, pose.near, pose.far)
        self.renderer = world.pb.ER_TINY_RENDERER
        if settings.renderer == "egl":
            if world.egl_plugin is None:
                raise ExecutionError("the EGL renderer must be loaded with the world: World(..., egl=True)")
            self.renderer = world.pb.ER_BULLET_HARDWARE_OPENGL

    def render(self) -> np.ndarray:
        """An RGB image (H, W, 3) uint8 of the world as it is now."""
        w, h = self.settings.width, self.settings.height
        if self.renderer == self.world.pb.ER_TINY_RENDERER:
            rgba = self._grab(w, h)
        else:
            with quiet_stdout():  # the EGL plugin prints on every frame
                rgba = self._grab(w, h)
        return np.asarray(rgba, dtype=np.uint8).reshape(h, w, 4)[:, :, :3].copy()

    def _grab(self, w: int, h: int):
        return self.world.client.getCameraImage(
            w, h, self.view, self.proj, renderer=self.renderer, shadow=0,
            flags=self.world.pb.ER_NO_SEGMENTATION_MASK,
        )[2]

    def project(self, points: np.ndarray) -> np.ndarray:
        """Pixel (column, row) of world points (K,3), with the matrices the renderer uses."""
        view = np.asarray(self.view).reshape(4, 4).T  # PyBullet's matrices are column-major
        proj = np.asarray(self.proj).reshape(4, 4).T
        p = np.column_stack([np.asarray(points, float), np.ones(len(points))])
        clip = (proj @ view @ p.T).T
        ndc = clip[:, :3] / clip[:, 3:4]
        col = (ndc[:, 0] + 1.0) * 0.5 * self.settings.width
        row = (1.0 - ndc[:, 1]) * 0.5 * self.settings.height
        return np.column_stack([col, row])
