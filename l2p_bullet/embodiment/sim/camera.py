"""Where the video is filmed from, how big and how often, and the renderers that draw it.

The default camera, ``auto``, is framed per run on the region the action uses, from behind the robot at the
angle where the hand hides the mover least (embodiment/sim/framing.py); its left is the robot's left, as
``viewer``'s is. ``viewer`` is the fixed camera behind the robot's right shoulder, on the side of the table that
the viewer-frame prepositions are defined from (core/frames.py: the robot's base): the robot's left is
the left of the image, so "move A to the left of B" ends with A on the left in the video, as in the
2-D view, the teach page and the rule judge. ``robot`` faces the robot from across the table (left
and right are mirrored there), ``side`` looks from the robot's right,
``top`` straight down with the robot at the bottom (the 2-D view's orientation).

Renderers: ``egl`` (the default) is PyBullet's EGL plugin, over Mesa's software driver where there is
no GPU; ``tiny`` is PyBullet's TinyRenderer (CPU). Both draw the scene lit and with shadows; their pixels
differ, but each is deterministic: the same state gives the same image in any process
(tests/embodiment/test_render_pool.py). Where EGL does not start, rendering falls back to ``tiny`` with a one-line
note (embodiment/render.py) and summary.json records the renderer used.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import asdict, dataclass, field, replace

import numpy as np

from ...errors import ExecutionError, did_you_mean

RENDERERS = ("tiny", "egl")
LIGHT_DIRECTION = (-0.2, -0.3, 1.0)  # towards the light: high above the viewer, so shadows fall away from it


@dataclass(frozen=True)
class CameraPose:
    """A pinhole camera: ``eye`` looks at ``target`` with ``up`` up; ``fov`` vertical, in degrees."""

    eye: tuple[float, float, float] = (-0.78, -0.48, 0.78)
    target: tuple[float, float, float] = (0.06, 0.02, 0.0)
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    fov: float = 42.0
    near: float = 0.05
    far: float = 4.0
    name: str = "viewer"

    def to_dict(self) -> dict:
        return asdict(self)


AUTO = CameraPose(name="auto")
"""The framed camera before a run frames it (framed_for): until then it stands where ``viewer`` does."""

CAMERAS: dict[str, CameraPose] = {
    "auto": AUTO,
    "viewer": CameraPose(),
    # fov 60, not 50:
    "robot": CameraPose(eye=(0.5, -0.5, 0.6), target=(-0.15, 0.0, 0.1), fov=60.0, far=3.0, name="robot"),
    # at 50 a 2 cm block at the 0.35 m workspace's rim near the camera falls below the frame
    "side": CameraPose(eye=(0.0, -1.0, 0.6), target=(0.0, 0.0, 0.05), fov=45.0, name="side"),
    "top": CameraPose(eye=(0.0, 0.0, 1.3), target=(0.0, 0.0, 0.0), up=(1.0, 0.0, 0.0), fov=30.0, name="top"),
}
"""Named cameras (``--camera NAME``); what each one's left and right are is in the module docstring."""

VIEWER_SIDE: dict[str, str] = {
    "auto": "behind the robot, turned to the action: its left is your left",
    "viewer": "behind the robot: its left is your left",
    "top": "above the table, the robot at the bottom: its left is your left",
    "robot": "across the table, facing the robot: its left is your right",
    "side": "at the robot's right side",
}
"""Where a person watching each camera's video stands (the review page says it)."""


@dataclass(frozen=True)
class RenderSettings:
    """What to render: image size, frames per second of simulated time, renderer, video format, camera.

    ``workers``: processes that render the recorded states (0 or 1: in this process; None: as many as
    there are cores, at most 4). ``inset``: the video shows a top view of the blocks and the path in a
    corner (embodiment/inset.py); the frames' PNGs never do.
    """

    width: int = 640
    height: int = 480
    fps: float = 15.0
    renderer: str = "egl"
    video: str = "mp4"  # "mp4" or "gif"
    camera: CameraPose = field(default_factory=lambda: AUTO)
    workers: int | None = None
    inset: bool = True

    def check(self) -> RenderSettings:
        """Self, once every field is valid; ExecutionError (one line) naming the first that is not."""
        if self.renderer not in RENDERERS:
            raise ExecutionError(f'unknown renderer "{self.renderer}" (known: {", ".join(RENDERERS)})')
        check_resolution(self.width, self.height)
        check_fps(self.fps)
        if self.video not in ("mp4", "gif"):
            raise ExecutionError(f'unknown video format "{self.video}" (known: mp4, gif)')
        return self


MIN_SIDE, MAX_SIDE = 32, 3840


def framed_for(settings: RenderSettings, scene, paths, hand_rest, base) -> RenderSettings:
    """``settings`` with an ``auto`` camera framed on ``scene`` and ``paths`` ((mover, path, manner name),
    embodiment/sim/framing.py), the hand at rest at ``hand_rest``, the arm's base at ``base``; any other
    camera is kept as it is."""
    if settings.camera.name != "auto" or not paths:
        return settings
    from .framing import action_of, frame_action

    eye, target, fov = frame_action(action_of(scene, paths, hand_rest, base), settings.width / settings.height)
    return replace(settings, camera=CameraPose(eye, target, fov=fov, name="auto"))


def check_resolution(width: object, height: object) -> tuple[int, int]:
    """(width, height) when both are whole numbers of pixels a video encoder takes; else ExecutionError."""
    for name, v in (("width", width), ("height", height)):
        if isinstance(v, bool) or not isinstance(v, int) or not MIN_SIDE <= v <= MAX_SIDE:
            raise ExecutionError(f"the video {name} must be a whole number of pixels from {MIN_SIDE} to {MAX_SIDE} "
                                 f"(got {str(v)[:20]})")
    if width % 8:
        raise ExecutionError(f"the video width must be a multiple of 8 pixels, as video encoders need (got {width}; "
                             f"try {width - width % 8 or 8})")
    return width, height


def parse_resolution(text: str) -> tuple[int, int]:
    """``"640x480"`` -> (640, 480); ExecutionError with the expected form otherwise."""
    m = re.fullmatch(r"\s*(\d{1,9})\s*[xX*]\s*(\d{1,9})\s*", str(text))  # the range: check_resolution
    if not m:
        raise ExecutionError(f'a resolution is WIDTHxHEIGHT in pixels, e.g. 640x480 (got "{str(text)[:40]}")')
    return check_resolution(int(m.group(1)), int(m.group(2)))


def check_fps(fps: object) -> float:
    """Frames per second of simulated time: 1 to 60 (the physics runs at 240 Hz)."""
    if isinstance(fps, bool) or not isinstance(fps, int | float) or not math.isfinite(fps) or not 1 <= fps <= 60:
        raise ExecutionError(f"the video's frames per second must be a number from 1 to 60 (got {str(fps)[:20]})")
    return float(fps)


def parse_camera(text: str) -> CameraPose:
    """A preset name (``auto``, ``viewer``, ``robot``, ``side``, ``top``) or a JSON camera, e.g.
    ``{"eye": [-0.9, 0, 0.9], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 45}`` (metres, scene frame,
    z up from the table top; ``up`` and ``fov`` optional). ExecutionError (one line) when it is neither."""
    s = str(text).strip()
    if not s.startswith("{"):
        if s.lower() in CAMERAS:
            return CAMERAS[s.lower()]
        raise ExecutionError(f'unknown camera "{s[:40]}" (known: {", ".join(CAMERAS)}, or a JSON camera '
                             '{"eye": [x, y, z], "target": [x, y, z]})' + did_you_mean(s.lower(), list(CAMERAS)))
    try:
        doc = json.loads(s)
    except ValueError as e:
        raise ExecutionError(f"the JSON camera is not valid JSON: {e}") from None
    if not isinstance(doc, dict):
        raise ExecutionError("a JSON camera is an object with eye and target")
    unknown = sorted(set(doc) - {"eye", "target", "up", "fov", "near", "far"})
    if unknown:
        raise ExecutionError(f'unknown camera field "{unknown[0]}" (known: eye, target, up, fov, near, far)')
    vec = {k: _vec3(doc, k) for k in ("eye", "target", "up") if k in doc or k != "up"}
    up = vec.get("up", (0.0, 0.0, 1.0))
    sight = np.subtract(vec["target"], vec["eye"])
    if np.linalg.norm(sight) < 1e-3:
        raise ExecutionError("the camera's eye and target must be apart")
    if np.linalg.norm(np.cross(sight / np.linalg.norm(sight), up)) < 1e-3 * max(np.linalg.norm(up), 1e-12):
        raise ExecutionError("the camera's up must not point along its line of sight")
    fov, near, far = (_number(doc, k, d) for k, d in (("fov", 45.0), ("near", 0.05), ("far", 4.0)))
    if not 5.0 <= fov <= 120.0:
        raise ExecutionError(f"the camera's fov is the vertical angle in degrees, from 5 to 120 (got {fov})")
    if not 0 < near < far <= 100:
        raise ExecutionError(f"the camera needs 0 < near < far <= 100 metres (got near {near}, far {far})")
    return CameraPose(vec["eye"], vec["target"], up, fov, near, far, name="custom")


def _vec3(doc: dict, key: str) -> tuple[float, float, float]:
    v = doc.get(key)
    if not (isinstance(v, list) and len(v) == 3 and all(_finite(x) for x in v)) or abs(max(v, key=abs)) > 100:
        raise ExecutionError(f'the camera\'s "{key}" must be three numbers [x, y, z] in metres')
    return tuple(float(x) for x in v)


def _number(doc: dict, key: str, default: float) -> float:
    v = doc.get(key, default)
    if not _finite(v):
        raise ExecutionError(f'the camera\'s "{key}" must be a number')
    return float(v)


def _finite(v: object) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)


class Camera:
    """Renders the world as it is now. ``view`` and ``proj`` are the renderer's matrices (column-major)."""

    def __init__(self, world, settings: RenderSettings, pose: CameraPose | None = None):
        if settings.renderer not in RENDERERS:
            raise ExecutionError(f'unknown renderer "{settings.renderer}" (known: {", ".join(RENDERERS)})')
        pose = settings.camera if pose is None else pose
        self.sim, self.settings, self.pose = world.sim, settings, pose
        self.view = self.sim.view_matrix(pose.eye, pose.target, pose.up)
        self.proj = self.sim.projection_matrix(pose.fov, settings.width / settings.height, pose.near, pose.far)
        self.hardware = settings.renderer == "egl"
        if self.hardware and not self.sim.egl:
            raise ExecutionError("the EGL renderer must be loaded with the world: World(..., egl=True)")

    def render_rgbd(self, shadows: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """An RGB image (H, W, 3) uint8 and the depth (H, W, 1) float32, metres from the camera."""
        rgb, depth = self._shot(shadows, depth=True)
        near, far = self.pose.near, self.pose.far
        return rgb, (far * near / (far - (far - near) * depth[..., None])).astype(np.float32)

    def render(self, shadows: bool = True) -> np.ndarray:
        """An RGB image (H, W, 3) uint8 of the world as it is now, lit, with shadows (or without: half the cost)."""
        return self._shot(shadows)[0]

    def _shot(self, shadows: bool, depth: bool = False) -> tuple[np.ndarray, np.ndarray | None]:
        """The image (H, W, 3) uint8 and, when asked, the renderer's depth buffer (H, W) in 0..1."""
        w, h = self.settings.width, self.settings.height
        out = self.sim.camera_image(w, h, self.view, self.proj, hardware=self.hardware,
                                    light=LIGHT_DIRECTION if shadows else None, depth=depth)
        rgba, buffer = out if depth else (out, None)
        rgb = np.asarray(rgba, dtype=np.uint8).reshape(h, w, 4)[:, :, :3].copy()
        return rgb, None if buffer is None else np.asarray(buffer, np.float32).reshape(h, w)
