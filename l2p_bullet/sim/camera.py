"""A fixed camera looking at the table, its renderers, and the pinhole model that predicts pixels.

TinyRenderer (CPU) is the default: its images are bit-identical across processes. ``egl`` loads
PyBullet's EGL plugin where it exists (faster, but other pixels); loading it prints to the C-level
streams, which :func:`~l2p_bullet.sim.client.quiet_stdout` hides.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ExecutionError
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
    eye: tuple[float, float, float] = (0.55, -0.55, 0.6)
    target: tuple[float, float, float] = (-0.05, 0.0, 0.0)
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
        self.plugin = None
        if settings.renderer == "egl":
            self._load_egl()

    def _load_egl(self) -> None:
        import importlib.util

        spec = importlib.util.find_spec("eglRenderer")
        with quiet_stdout():
            plugin = self.world.client.loadPlugin(spec.origin, "_eglRendererPlugin") if spec else -1
        if plugin < 0:
            raise ExecutionError("the EGL renderer plugin does not load here; use --renderer tiny")
        self.plugin = plugin
        self.renderer = self.world.pb.ER_BULLET_HARDWARE_OPENGL

    def render(self) -> np.ndarray:
        """An RGB image (H, W, 3) uint8 of the world as it is now."""
        w, h = self.settings.width, self.settings.height
        _, _, rgba, _, _ = self.world.client.getCameraImage(
            w, h, self.view, self.proj, renderer=self.renderer, shadow=0,
            flags=self.world.pb.ER_NO_SEGMENTATION_MASK,
        )
        return np.asarray(rgba, dtype=np.uint8).reshape(h, w, 4)[:, :, :3].copy()

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

    def close(self) -> None:
        if self.plugin is not None and self.world.client is not None:
            self.world.client.unloadPlugin(self.plugin)
            self.plugin = None
