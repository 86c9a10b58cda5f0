"""Cleaning motion-capture tracks: drop glyph detections that teleport, re-interpolate the gaps.

Why: the capture pipeline sometimes detects a block's glyph far from the block (the data README's
"known glitch": SlideAround Session2's Shell at x = -1.87 m, 2.5 m from where the block is a frame
earlier), and then linearly interpolates every unobserved frame towards that one detection. The
result is a straight excursion of up to 2.6 m in and out of a demonstration, which a progress model
takes for what people do: before this cleaning, 3 of the 40 "around" demonstrations went farther than
7 blocks from the anchor, and the around model let plans loop wide of it.

The rule is physical, not statistical: a block slid or carried by hand does not move faster than
``max_speed``. Consecutive detections that would need more (plus ``tolerance`` for detection jitter)
split the track into runs; a run shorter than ``min_run`` frames lies between two impossible jumps, so
it is the glitch, not the long runs either side. Its detections are dropped and every frame that is
not a kept detection is interpolated linearly between the kept ones, as the original pipeline did
(frames before the first or after the last kept detection copy the nearest one).

The teach page's samples are the other kind of track: poses at irregular instants (a mouse event and a
timer), turned into the captures' 30 fps by :func:`page_track`, for single actions and rows alike.
"""

from __future__ import annotations

import numpy as np


def page_samples(samples: np.ndarray) -> np.ndarray:
    """The rows of ``samples`` (n, 4 ``[t, x, y, yaw]``, times not decreasing) that :func:`page_track`
    is resampled from: of several samples at one instant (a mouse event and the timer) only the last
    holds. A check of the saved path must follow exactly these: a detour among samples that share an
    instant would pass it while the saved track cuts straight through. A recording at a single instant
    keeps its first and last sample."""
    keep = np.r_[np.diff(samples[:, 0]) > 0, True]
    return samples[keep] if keep.sum() >= 2 else samples[[0, -1]]


def page_track(samples: np.ndarray, fps: float = 30.0) -> np.ndarray:
    """The page's ``samples`` (n, 4 ``[t, x, y, yaw]``, times not decreasing) as poses (m, 3) at ``fps``
    from the first sample's instant, yaw unwrapped, at least two.

    The frames run to the first at or after the last sample, which holds the last sample's pose: the
    track ends where the page left the block. (Frames only up to the last sample would
    drop up to 1/fps s of a drag's end, so a fast drag's last frame would fall short of where it was put.)"""
    s = np.asarray(samples, float)
    kept = page_samples(np.column_stack([s[:, 0] - s[0, 0], s[:, 1:3], np.unwrap(s[:, 3])]))  # yaw over them all
    t = kept[:, 0]
    if t[-1] <= 0:  # a recording at a single instant: its first and last pose
        return kept[:, 1:]
    # at least one frame after the first: a span under 1e-9 frame periods (two instants 1e-12 s apart) rounds
    # to 0 frames, and the track would be the first sample alone
    grid = np.arange(max(1, int(np.ceil(t[-1] * fps - 1e-9))) + 1) / fps
    return np.column_stack([np.interp(grid, t, kept[:, i]) for i in (1, 2, 3)])


def teleporting(pose: np.ndarray, observed: np.ndarray, fps: float = 30.0, max_speed: float = 2.0,
                tolerance: float = 0.05, min_run: int = 8) -> np.ndarray:
    """Boolean mask of the observed frames whose detection is a glitch (see the module docstring).

    ``pose`` is (T, 2+) in metres, ``observed`` (T,) bool. Runs are re-formed after each removal, so a
    glitch of several detections in a row is removed whole; the longest run is never removed.
    """
    obs = np.flatnonzero(np.asarray(observed, bool))
    bad = np.zeros(len(pose), bool)
    while len(obs) > 1:
        gap = np.linalg.norm(np.diff(pose[obs, :2], axis=0), axis=1)
        allowed = max_speed * np.diff(obs) / fps + tolerance
        cuts = np.flatnonzero(gap > allowed) + 1
        if not len(cuts):
            break
        runs = np.split(np.arange(len(obs)), cuts)
        lengths = np.array([len(r) for r in runs])
        short = [r for r in runs if len(r) < min_run]
        if not short or lengths.max() < min_run:
            break
        drop = np.concatenate(short)
        bad[obs[drop]] = True
        obs = np.delete(obs, drop)
    return bad


def clean_track(pose: np.ndarray, observed: np.ndarray | None, fps: float = 30.0) -> tuple[np.ndarray, int]:
    """The track with glitch detections removed and every unobserved frame re-interpolated.

    Returns the cleaned (T, 3) poses and how many detections were dropped. Without ``observed`` flags
    (a user's own captures may lack them) every frame counts as a detection. Theta is interpolated
    linearly without wrap-around, as in the original pipeline (blocks are squares: theta in [0, pi/2)).
    """
    pose = np.asarray(pose, float)
    observed = np.ones(len(pose), bool) if observed is None else np.asarray(observed, bool)
    bad = teleporting(pose, observed, fps)
    keep = np.flatnonzero(observed & ~bad)
    if not bad.any() or len(keep) < 2:
        return pose, 0
    t = np.arange(len(pose))
    out = np.column_stack([np.interp(t, keep, pose[keep, k]) for k in range(pose.shape[1])])
    # frames the pipeline interpolated between two good detections are kept bit for bit
    untouched = _between_untouched(bad, observed)
    out[untouched] = pose[untouched]
    return out, int(bad.sum())


def _between_untouched(bad: np.ndarray, observed: np.ndarray) -> np.ndarray:
    """Frames whose value does not depend on a dropped detection: kept detections, and unobserved
    frames whose nearest detections on both sides (the pipeline's interpolation ends) were kept."""
    obs = np.flatnonzero(observed)
    t = np.arange(len(bad))
    prev_i = np.searchsorted(obs, t, side="right") - 1
    next_i = np.searchsorted(obs, t, side="left")
    prev_bad = np.where(prev_i >= 0, bad[obs[np.clip(prev_i, 0, len(obs) - 1)]], False)
    next_bad = np.where(next_i < len(obs), bad[obs[np.clip(next_i, 0, len(obs) - 1)]], False)
    return ~(prev_bad | next_bad)
