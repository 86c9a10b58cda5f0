"""A fixed camera looking at the table, and its renderers.

TinyRenderer (CPU) is the default: its images are bit-identical across processes. ``egl`` uses
PyBullet's EGL plugin where it loads (see World(egl=True); other pixels); the simulator facade
(:mod:`.bullet`) hides what it prints on load and on every frame, and disconnecting the world's
simulator ends it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import ExecutionError

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
    """Renders the world as it is now. ``view`` and ``proj`` are the renderer's matrices (column-major)."""

    def __init__(self, world, settings: RenderSettings, pose: CameraPose = CameraPose()):
        if settings.renderer not in RENDERERS:
            raise ExecutionError(f'unknown renderer "{settings.renderer}" (known: {", ".join(RENDERERS)})')
        self.sim, self.settings, self.pose = world.sim, settings, pose
        self.view = self.sim.view_matrix(pose.eye, pose.target, pose.up)
        self.proj = self.sim.projection_matrix(pose.fov, settings.width / settings.height, pose.near, pose.far)
        self.hardware = settings.renderer == "egl"
        if self.hardware and not self.sim.egl:
            raise ExecutionError("the EGL renderer must be loaded with the world: World(..., egl=True)")

    def render(self) -> np.ndarray:
        """An RGB image (H, W, 3) uint8 of the world as it is now."""
        w, h = self.settings.width, self.settings.height
        rgba = self.sim.camera_image(w, h, self.view, self.proj, hardware=self.hardware)
        return np.asarray(rgba, dtype=np.uint8).reshape(h, w, 4)[:, :, :3].copy()
