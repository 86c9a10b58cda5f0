"""Where a spatial relation is seen from, and how many reference objects it names.

An action's manifest declares both (docs/perform.md, "Writing a new action")::

    frame = "viewer"     # "relative" (default), "viewer" (seen from the robot's base) or "viewer:camera"
    anchors = 2          # reference objects in the sentence: 1 (default) or 2 ("between B and C")

Why a declaration and not one feature set for all: "around", "past" or "closer to" mean the same
whichever way the table is turned, so their features are invariant to turning the whole scene and
their training set mirrors every demonstration (twice the data for free). "To the left of" as a person
at the robot says it changes meaning when the scene turns: its features must know where the viewer is,
and mirroring a demonstration would turn left into right. The five built-in actions are ``relative``.

A viewpoint is a point on the table plane, in the scene frame (metres): the robot's base, or the
camera the runs are filmed from. Left is the viewer's left looking at the anchor.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import BundleError, did_you_mean
from .scene import ROBOT_BASE_XY

RELATIVE = "relative"
VIEWER = "viewer"

VIEWPOINTS: dict[str, tuple[float, float]] = {
    "robot": ROBOT_BASE_XY,
    "camera": (0.5, -0.5),
}
"""Named viewpoints (scene frame, metres): the arm's base, and the position on the table plane of the
camera across the table facing the robot (``embodiment/sim/camera.py``'s
``robot`` camera, ``--camera robot``; a test keeps the two equal). The default camera, ``viewer``, stands
behind the robot, so its left is the ``robot`` viewpoint's left."""

MAX_ANCHORS = 2
"""Reference objects a sentence may name: one ("next to B") or two ("between B and C")."""


@dataclass(frozen=True)
class Frame:
    """A parsed ``frame`` declaration: ``kind`` is "relative" or "viewer", ``viewpoint`` a VIEWPOINTS key."""

    kind: str = RELATIVE
    viewpoint: str | None = None

    @property
    def name(self) -> str:
        """The canonical spelling ("relative", "viewer", "viewer:camera"): what manifests record."""
        if self.kind == RELATIVE:
            return RELATIVE
        return VIEWER if self.viewpoint == "robot" else f"{VIEWER}:{self.viewpoint}"

    @property
    def relative(self) -> bool:
        return self.kind == RELATIVE

    def viewpoint_xy(self) -> np.ndarray | None:
        """The viewpoint in the scene frame (metres), None for a relative frame."""
        return None if self.viewpoint is None else np.array(VIEWPOINTS[self.viewpoint], float)


def parse_frame(value: object) -> Frame:
    """Read a ``frame`` declaration; :class:`BundleError` with a suggestion when it is not one."""
    if value is None:
        return Frame()
    if not isinstance(value, str):
        raise BundleError(f'"frame" must be a string such as "relative" or "viewer", not {value!r}')
    text = value.strip().lower()
    if text == RELATIVE:
        return Frame()
    kind, _, point = text.partition(":")
    known = [RELATIVE, VIEWER] + [f"{VIEWER}:{v}" for v in VIEWPOINTS]
    if kind != VIEWER:
        raise BundleError(f'unknown frame "{value}" (known: {", ".join(known)}).' + did_you_mean(text, known))
    point = point or "robot"
    if point not in VIEWPOINTS:
        raise BundleError(f'unknown viewpoint "{point}" in frame "{value}" (known: {", ".join(known)}).'
                          + did_you_mean(text, known))
    return Frame(VIEWER, point)


def parse_anchors(value: object) -> int:
    """Read an ``anchors`` declaration (how many reference objects): 1 or 2."""
    if value is None:
        return 1
    if isinstance(value, bool) or not isinstance(value, int) or not 1 <= value <= MAX_ANCHORS:
        raise BundleError(f'"anchors" must be 1 or {MAX_ANCHORS} (reference objects in the sentence), not {value!r}')
    return int(value)


def declaration(manifest: dict) -> tuple[Frame, int]:
    """(frame, number of anchors) a manifest declares; defaults: relative, one anchor."""
    return parse_frame(manifest.get("frame")), parse_anchors(manifest.get("anchors"))


def viewer_axes(anchor_xy: np.ndarray, viewer_xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(depth, left) unit vectors (..., 2) of the viewer looking at the anchor: depth points from the
    viewer through the anchor (behind it is +depth), left is the viewer's left."""
    sight = np.asarray(anchor_xy, float)[..., :2] - np.asarray(viewer_xy, float)[..., :2]
    f = sight / np.maximum(np.linalg.norm(sight, axis=-1, keepdims=True), 1e-9)
    return f, np.stack([-f[..., 1], f[..., 0]], axis=-1)


def viewer_offset(mover_xy: np.ndarray, anchor_xy: np.ndarray, viewer_xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(lateral, depth) of the mover relative to the anchor as the viewer sees it, in the inputs' units:
    lateral > 0 is to the viewer's left, depth > 0 behind the anchor (farther from the viewer)."""
    f, left = viewer_axes(anchor_xy, viewer_xy)
    d = np.asarray(mover_xy, float)[..., :2] - np.asarray(anchor_xy, float)[..., :2]
    return np.sum(d * left, axis=-1), np.sum(d * f, axis=-1)
