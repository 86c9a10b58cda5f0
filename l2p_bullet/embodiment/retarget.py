"""Put a recorded 2-D motion (a human demonstration, a scoring input) onto the scene's blocks.

The demonstrations live in per-session table frames with 0.15 m blocks; only the mover's motion
*relative to the anchor* means anything. So each frame's mover pose is expressed in the anchor's frame
(rotated into it), divided by the block size, then multiplied by the scene's block size and placed on
the scene's anchor. The anchor's own drift in the recording (people nudge it) is thereby ignored.

Two documented fix-ups make a real human motion executable on a small table (see docs/embodiment.md):
- points outside the arm's workspace are pulled radially back onto its edge (with an arm's reach ring,
  ``core/workspace.py``, onto the nearest point of the region, which is the radial pull for the disk);
- points where the scaled mover would touch the anchor (motion-capture noise, or a person sliding the
  block along its neighbour) are pushed straight away from the anchor until ``GRIPPER_MARGIN`` clears.
Both are reported in :class:`Retargeted` so a caller can see how much of the motion was changed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.geometry import moving_average, polygons_overlap
from ..core.scene import GRIPPER_MARGIN, Scene
from ..errors import PathError
from .motion import resample_path, unwrap_yaw

SMOOTH_FRAMES = 5
"""Moving-average window (frames) against motion-capture jitter, which would otherwise be read as
tight curves and force the arm to crawl (v <= sqrt(a / kappa))."""
RESAMPLE_BLOCKS = 0.2
"""Spacing of the executed path, in block sizes."""
PUSH_STEP = 0.0005  # m per push-out step


@dataclass
class Retargeted:
    path: np.ndarray  # (N,3) mover poses in the scene frame
    clamped: int  # points pulled back into the workspace
    pushed: int  # points pushed away from the anchor
    max_fix_m: float  # the largest distance a point was moved by either fix-up


def to_anchor_frame(mover: np.ndarray, anchor: np.ndarray, size: float) -> np.ndarray:
    """Mover poses (T,3) in the anchor's frame, in block units, yaw relative to the anchor's."""
    m, a = np.asarray(mover, float), np.asarray(anchor, float)
    if a.ndim == 1:
        a = np.repeat(a[None], len(m), axis=0)
    d = m[:, :2] - a[:, :2]
    c, s = np.cos(a[:, 2]), np.sin(a[:, 2])
    rel = np.column_stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]]) / size
    return np.column_stack([rel, m[:, 2] - a[:, 2]])


def from_anchor_frame(rel: np.ndarray, anchor_pose: np.ndarray, size: float) -> np.ndarray:
    """Inverse of :func:`to_anchor_frame` onto a fixed anchor pose [x, y, yaw] with blocks of ``size``."""
    x, y, yaw = anchor_pose
    c, s = math.cos(yaw), math.sin(yaw)
    d = rel[:, :2] * size
    return np.column_stack([x + c * d[:, 0] - s * d[:, 1], y + s * d[:, 0] + c * d[:, 1], rel[:, 2] + yaw])


def smooth_path(path: np.ndarray, window: int = SMOOTH_FRAMES) -> np.ndarray:
    """Centred moving average (ends kept exactly, yaw unwrapped first)."""
    p = unwrap_yaw(path)
    if len(p) <= window or window < 2:
        return p
    out = moving_average(p, window)
    out[0], out[-1] = p[0], p[-1]
    return out


MAX_MOTION_BLOCKS = 1000.0
"""How far (block sides) a motion to replay may reach from its anchor: what ``score`` accepts too
(``progress.features.MAX_BLOCKS``); beyond it the poses are in the wrong unit, and resampling them
would ask for gigabytes before the fit clamps them into the workspace."""


def _check_numbers(mover: np.ndarray, anchor: np.ndarray, size: float) -> None:
    """Finite poses within :data:`MAX_MOTION_BLOCKS` of the anchor, checked before anything is resampled."""
    if not (np.isfinite(mover).all() and np.isfinite(anchor).all() and np.isfinite(size) and size > 0):
        raise PathError("the motion to replay holds a number that is not finite (or a block size that is not positive)")
    with np.errstate(over="ignore", invalid="ignore"):
        extent = float(np.max(np.abs(mover[:, :2] - anchor[:1, :2]))) / size
    if not extent <= MAX_MOTION_BLOCKS:
        raise PathError(
            f"the motion to replay reaches {extent:.3g} block sides from its anchor (blocks of {size:.3g} m);"
            f" at most {MAX_MOTION_BLOCKS:g}: are the poses in metres and the block size right?"
        )


def retarget(mover: np.ndarray, anchor: np.ndarray, size: float, scene: Scene, mover_name: str,
             anchor_name: str) -> Retargeted:
    """The recorded motion as an executable path of ``mover_name`` around ``anchor_name`` in ``scene``."""
    if len(mover) < 2:
        raise PathError("a motion to replay needs at least two poses")
    _check_numbers(np.asarray(mover, float), np.atleast_2d(np.asarray(anchor, float)), size)
    a_obj, m_obj = scene.get(anchor_name), scene.get(mover_name)
    if a_obj.name == m_obj.name:
        raise PathError(f'the mover and the anchor are the same block ("{mover_name}")')
    rel = to_anchor_frame(mover, anchor, size)
    path = from_anchor_frame(smooth_path(rel), a_obj.pose, m_obj.size)
    path = resample_path(path, RESAMPLE_BLOCKS * m_obj.size)
    fixed = path.copy()
    ws = scene.workspace
    centre = np.array(ws.center)
    clamped = pushed = 0
    limit = ws.radius - 1e-4
    for k in range(len(fixed)):
        if ws.ring is None:  # the disk: the radial pull, as always
            d = fixed[k, :2] - centre
            r = float(np.hypot(*d))
            if r > limit:
                fixed[k, :2] = centre + d * (limit / r)
                clamped += 1
        elif not ws.contains(fixed[k, :2], 1e-4)[0]:
            fixed[k, :2] = ws.nearest_inside(fixed[k, :2], 1e-4)[0]
            clamped += 1
        pushed += _push_out(fixed[k], m_obj, a_obj)
    fixed, inserted = _clear_segments(fixed, m_obj, a_obj)
    if ws.path_inside(fixed) is not None:  # a point pushed out again, or a move cutting the ring's hole
        raise PathError("the motion cannot be fitted into the workspace around the anchor "
                        f'"{anchor_name}"; move the anchor nearer the table centre')
    orig = motion_resample_like(path, fixed)
    max_fix = float(np.max(np.hypot(*(fixed[:, :2] - orig[:, :2]).T)))
    return Retargeted(fixed, clamped, pushed + inserted, max_fix)


def _push_out(pose: np.ndarray, m_obj, a_obj) -> bool:
    """Push ``pose`` (in place) straight away from the anchor until the footprints clear the margin."""
    anchor_fp = a_obj.footprint()
    away = pose[:2] - a_obj.pose[:2]
    n = float(np.hypot(*away))
    away = away / n if n > 1e-9 else np.array([1.0, 0.0])
    moved = False
    for _ in range(400):
        if not polygons_overlap(m_obj.footprint(pose), anchor_fp, GRIPPER_MARGIN):
            break
        pose[:2] += PUSH_STEP * away
        moved = True
    return moved


def _clear_segments(path: np.ndarray, m_obj, a_obj, rounds: int = 6) -> tuple[np.ndarray, int]:
    """Split segments whose straight sweep touches the anchor (between two clear points) and push
    their midpoints out; repeat until every segment is clear."""
    anchor_fp = a_obj.footprint()
    inserted = 0
    for _ in range(rounds):
        out, changed = [path[0]], False
        for a, b in zip(path[:-1], path[1:], strict=True):
            if any(polygons_overlap(m_obj.footprint(a + (b - a) * w), anchor_fp, GRIPPER_MARGIN * 0.5)
                   for w in (0.25, 0.5, 0.75)):
                mid = (a + b) / 2
                _push_out(mid, m_obj, a_obj)
                out.append(mid)
                inserted += 1
                changed = True
            out.append(b)
        path = np.array(out)
        if not changed:
            break
    return path, inserted


def motion_resample_like(original: np.ndarray, fixed: np.ndarray) -> np.ndarray:
    """For each fixed point, the nearest original point (to measure how far the fix-ups moved it)."""
    d = np.hypot(fixed[:, None, 0] - original[None, :, 0], fixed[:, None, 1] - original[None, :, 1])
    return original[np.argmin(d, axis=1)]
