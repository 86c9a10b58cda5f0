"""The checks every teach recording goes through, single action (``/api/demos``) and composite row
(``/api/rows``) alike, before anything is resampled or written.

A recording comes from a browser, so it may be anything: the limits here (sample count, duration,
finite numbers, positions and yaw of a sane size) are checked on the raw samples first, because
resampling to 30 fps allocates one pose per frame (a span of a million seconds is 30 million frames) and
``np.unwrap`` overflows on yaws near the float limit. The collision check then follows the path the page
recorded, not only its poses: a block may jump several block sides between two samples (a sample 1/30 s
after the start, far away), and a pose check alone would let it pass through another block. The page
itself only refuses a pose that overlaps, so a block dragged against another sticks and, once the pointer
clears the corner, jumps across it: that straight jump cuts the corner by a few millimetres. So one jump
between two recorded samples may overlap another block by less than a quarter side (:data:`TOLERANCE`).
"""

from __future__ import annotations

import math

import numpy as np

from ..core.geometry import polygons_overlap
from ..core.scene import SceneObject
from ..errors import TeachError

MAX_SECONDS = 600.0
"""Longest recording or drag (s)."""
MAX_SAMPLES = 20000
"""Most samples in one recording or drag."""
MAX_COORD = 100.0
"""Largest |x|, |y| of a sample (m): far beyond any table, small enough that no arithmetic overflows."""
MAX_YAW = 1000.0
"""Largest |yaw| of a sample (rad): ~160 turns, more than any hand makes; bounds ``np.unwrap``'s input."""
MIN_FRAMES = 5
"""Frames (at 30 fps) a demonstrated motion lasts at least (a single action's event, a whole row): shorter
is a click, not a demonstration."""
MIN_TRAVEL = 0.5
"""Blocks the mover must travel during the event (a single action), or each moved block over its drags
(a row: a small corrective drag is welcome, a block that barely moved is not part of the row)."""
STEP = 0.25
"""Largest move of a block's corner between two checked poses, in block sides: the path between two
samples is checked, so that no jump between samples can cross another block unseen."""
TOLERANCE = 0.25
"""How far, in block sides, one jump between two recorded samples (its straight path) may overlap another
block (1 cm for 4 cm cubes); the samples themselves may not overlap one (by more than 1 mm, as the page
placed them). The rule is the overlap's depth, not where it is: a corner cut, but also one long jump
sliding along a block's whole face less than a quarter side inside it, passes. Why so much: a block
dragged against another sticks where the page refused the next pose and jumps when the pointer clears
the corner; that jump's chord cuts the corner by 2-8 mm at 0.6-1 m/s, and hugging the anchor is what
people do for "around". A jump through a block overlaps it by half a side or more. ``teach.js`` refuses
the same chords live (``TOLERANCE`` there)."""
MAX_SPEED = 3.0
"""Fastest a drag may move its block on average, path length over time span (m/s): a real quick flick
across the table is 1-2 m/s; faster is not a hand but a teleport with a token duration (0.12 m in a
microsecond), which the 30-fps track would learn as a jump."""
MAX_CHECKED = 100_000
"""Most poses one collision check looks at, so that a hostile recording costs seconds, not minutes: a
recording has at most :data:`MAX_SAMPLES` samples, and a hand's drag needs one or two poses per sample."""


class Duplicate(TeachError):
    """The very recording was already saved (409)."""


def fmt(v: float) -> str:
    """A number for a message: 3 significant digits, never a 300-digit string."""
    return f"{v:.3g}"


def checked_samples(samples: np.ndarray, what: str = "a recording") -> np.ndarray:
    """``samples`` (n, 4) rows ``[t, x, y, yaw]`` as a float array, refused (TeachError saying why) unless
    there are 2 to :data:`MAX_SAMPLES` of them, finite, within :data:`MAX_COORD` / :data:`MAX_YAW`,
    times not decreasing and spanning at most :data:`MAX_SECONDS`."""
    s = np.asarray(samples, float)
    if s.ndim != 2 or s.shape[1] != 4 or len(s) < 2:
        raise TeachError(f"{what} needs at least two samples [t, x, y, yaw]")
    if len(s) > MAX_SAMPLES:
        raise TeachError(f"{what} has {len(s)} samples; at most {MAX_SAMPLES}")
    bad = ~np.isfinite(s)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise TeachError(f"{what}: sample {i} has a {'txyw'[j].replace('w', 'yaw')} that is not a finite number")
    if np.abs(s[:, 1:3]).max() > MAX_COORD:
        raise TeachError(f"{what}: a sample lies {fmt(np.abs(s[:, 1:3]).max())} m from the table's centre "
                         f"(at most {MAX_COORD:.0f} m)")
    if np.abs(s[:, 3]).max() > MAX_YAW:
        raise TeachError(f"{what}: a yaw of {fmt(np.abs(s[:, 3]).max())} rad (at most {MAX_YAW:.0f} rad)")
    dt = np.diff(s[:, 0])
    if np.any(dt < 0):
        raise TeachError(f"{what}: sample times must not decrease")
    span = s[-1, 0] - s[0, 0]
    if not span <= MAX_SECONDS:  # also inf: 1e308 - (-1e308)
        raise TeachError(f"{what} spans {fmt(span)} s; at most {MAX_SECONDS:.0f} s")
    return s


def travel(track: np.ndarray, size: float) -> float:
    """Path length of ``track`` (n, 3 poses) in block sides."""
    return float(np.linalg.norm(np.diff(track[:, :2], axis=0), axis=1).sum()) / size


def swept(track: np.ndarray, size: float) -> tuple[np.ndarray, np.ndarray]:
    """(poses (m, 3), index (m,)): ``track`` with each step from pose k-1 to k subdivided so that no
    corner of a block of side ``size`` moves more than :data:`STEP` sides between two poses (each pose
    labelled with the index k it leads to). TeachError when that would be more than :data:`MAX_CHECKED`."""
    d = np.diff(track, axis=0)
    corner = np.hypot(d[:, 0], d[:, 1]) + np.abs(d[:, 2]) * size * math.sqrt(0.5)
    parts = np.maximum(1, np.ceil(corner / (STEP * size))).astype(np.int64)
    if parts.sum() > MAX_CHECKED:
        raise TeachError(f"the block moves too fast to be checked ({fmt(travel(track, size))} blocks in "
                         f"{len(track)} samples): slide it more slowly")
    step = np.repeat(np.arange(len(d)), parts)  # the step each pose is on
    first = np.repeat(np.cumsum(parts) - parts, parts)
    f = (np.arange(len(step)) - first + 1) / parts[step]
    poses = np.vstack([track[:1], track[step] + f[:, None] * d[step]])
    return poses, np.r_[0, step + 1]


def first_collision(mover: SceneObject, path: np.ndarray, others: list[tuple[SceneObject, np.ndarray]]
                    ) -> tuple[int, str] | None:
    """(index, name) where ``mover`` following ``path`` (n, 3 poses as the page placed the block, yaw
    unwrapped) first passes through one of ``others`` (each an object and its pose then), or None: a pose
    of ``path`` that overlaps one by more than 1 mm (index: that pose), or a straight move between two
    poses (:func:`swept`) that overlaps one deeper than :data:`TOLERANCE` (index: the pose it leads to).

    Only the samples get the full footprint: the 30-fps frames, and the swept moves, lie between them,
    where a jump across a corner the page allowed cuts it by millimetres (:data:`TOLERANCE`). ``path``
    must be the samples the track is built from (:func:`~l2p_bullet.data.tracking.page_samples`), else a detour among
    samples
    the track drops is checked instead of the path saved."""
    poses, steps = swept(path, mover.size)
    first: tuple[int, str] | None = None
    for other, pose in others:
        foot = other.footprint(pose)
        reach = (mover.size + other.size) * math.sqrt(0.5)
        tol = TOLERANCE * min(mover.size, other.size)
        for at, label, margin in ((path, np.arange(len(path)), -0.001), (poses, steps, -tol)):
            near = np.flatnonzero(np.hypot(*(at[:, :2] - pose[:2]).T) < reach)
            for i in near[label[near] < (first[0] if first else len(path))]:
                if polygons_overlap(mover.footprint(at[i]), foot, margin=margin):
                    first = int(label[i]), other.name
                    break
    return first


def same_demonstration(old: list[np.ndarray], events: np.ndarray, new: list[np.ndarray], start: int,
                       end: int) -> int | None:
    """Which demonstration of a demos file (tracks ``old``, ``events`` (n, 2) start/end frames) is ``new``
    (tracks with the event at frames ``start``..``end``) all over again, or None: the same recording
    posted twice, or with its times shifted, is resampled to the very same frames."""
    n = len(new[0])
    for i, (s, e) in enumerate(np.asarray(events, int)):
        lo = s - start
        if e - s != end - start or lo < 0 or lo + n > len(old[0]):
            continue
        if all(np.allclose(o[lo:lo + n], t, rtol=0, atol=1e-5) for o, t in zip(old, new, strict=True)):
            return i
    return None
