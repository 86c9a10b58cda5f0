"""The training set's copies of a demonstration: how it is read (smoothed, mirrored, reflected in a
viewer's frame, against a context) and the transformations that turn it into positives and near misses.

Why a module of their own: each is a small piece of geometry on a ``(T, 3)`` motion (metres or block
units alike; ``c`` is the anchor's pose, ``size`` the block side where a distance is in blocks), and
:mod:`l2p_bullet.learning.trainset` decides which copies an action gets and how they are labelled. A
transformation that draws random numbers takes the caller's generator, so the training sets, and with
them the shipped bundles, stay reproducible from the seed.

The training set (:mod:`l2p_bullet.learning.trainset`) builds every sequence from these copies. For the
five built-in actions (relative frame, one anchor) a copy is the smoothed demonstration or its mirror
image (left and right do not change "around"). Plugin actions that declare a viewer frame or a second
anchor (:mod:`l2p_bullet.core.frames`) read their motions against a :class:`Context` (the further
anchors, the viewpoint), and a viewer frame replaces the mirror image by reflections in the viewer's
frame, some of which are negatives (``trainset``'s module docstring says which and why).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.frames import viewer_offset
from ..core.geometry import moving_average, swept_angle
from ..data.demos import Demo
from ..errors import DataError
from ..progress.features import QSRConfig


def polyline(demo_m: np.ndarray, c: np.ndarray, rng: np.random.Generator,
              tol: float = np.radians(30)) -> np.ndarray | None:
    """Replace a motion by straight moves between 0-3 of its own intermediate poses (dense frames).

    The angle swept around the anchor (at ``c``) must stay within ``tol`` of the original's: an "around"
    cut down to one straight hop would teach that a short hop is an around. None if no try keeps it.
    """
    target = swept_angle(demo_m, c)
    for _ in range(8):
        n_mid = int(rng.integers(0, 4))
        ks = np.sort(rng.choice(np.arange(1, len(demo_m) - 1), size=min(n_mid, len(demo_m) - 2), replace=False))
        way = demo_m[np.concatenate([[0], ks, [len(demo_m) - 1]]).astype(int)]
        poly = np.concatenate([np.linspace(way[i], way[i + 1], 20, endpoint=i == len(way) - 2)
                               for i in range(len(way) - 1)])
        if abs(swept_angle(poly, c) - target) < tol:
            return poly
    return None


def event_or_polyline(ev_m: np.ndarray, c: np.ndarray, rng: np.random.Generator) -> np.ndarray | None:
    """The event itself or (half the time) one of its straight-line simplifications: the base of a copy."""
    return polyline(ev_m, c, rng) if rng.random() < 0.5 else ev_m


def scaled(m: np.ndarray, centre: np.ndarray, k: float) -> np.ndarray:
    """A copy of the motion with its positions scaled by ``k`` about ``centre`` (x, y); yaw unchanged."""
    out = m.copy()
    out[:, :2] = centre[:2] + (m[:, :2] - centre[:2]) * k
    return out


def turn_about(poses: np.ndarray, centre: np.ndarray, angle: float | np.ndarray) -> np.ndarray:
    """Poses (T,3) or one pose (3,) turned about ``centre`` (x, y) by ``angle``: one angle, or one per pose."""
    p = np.array(poses, float).reshape(-1, 3)
    c, s = np.cos(angle), np.sin(angle)
    d = p[:, :2] - centre[:2]
    p[:, 0], p[:, 1] = centre[0] + c * d[:, 0] - s * d[:, 1], centre[1] + s * d[:, 0] + c * d[:, 1]
    p[:, 2] += angle
    return p.reshape(np.shape(poses))


def twist(m: np.ndarray, c: np.ndarray, angle: float) -> np.ndarray:
    """Rotate the mover about the anchor progressively (``angle`` at the start, 0 at the end, by arc
    length): distances and the end state are unchanged, so "closer"/"away"/"next to" stay what they
    were while the bearing drifts. People graded sweeping motions as good; the captures are almost radial."""
    step = np.linalg.norm(np.diff(m[:, :2], axis=0), axis=1)
    frac = np.concatenate([[0.0], np.cumsum(step)]) / max(step.sum(), 1e-9)
    return turn_about(m, c, angle * (1.0 - frac))


def detour(m: np.ndarray, c: np.ndarray, rng: np.random.Generator, size: float) -> np.ndarray | None:
    r0 = float(np.linalg.norm(m[0, :2] - c[:2])) / size
    r1 = float(np.linalg.norm(m[-1, :2] - c[:2])) / size
    lo, hi = sorted((r0, r1))
    if hi - lo < 2.0:
        return None
    # a new start between the two distances, at least 1 block short of the end's: net motion kept
    r_new = rng.uniform(lo, hi - 1.0) if r1 > r0 else rng.uniform(lo + 1.0, hi)
    b = np.arctan2(*(m[0, 1::-1] - c[1::-1])) + rng.uniform(-1.0, 1.0)
    p0 = np.array([c[0] + r_new * size * np.cos(b), c[1] + r_new * size * np.sin(b), m[0, 2]])
    return np.concatenate([np.linspace(p0, m[0], 20, endpoint=False), m])


def approach(m: np.ndarray, extra: float) -> np.ndarray:
    """The motion with a straight run-up of ``extra`` (metres) before it, along its first direction of
    travel: a start farther away that still passes the anchor as near as the person did."""
    d = m[min(len(m) - 1, max(1, len(m) // 5)), :2] - m[0, :2]
    n = float(np.linalg.norm(d))
    if n < 1e-9:
        return m
    p0 = m[0].copy()
    p0[:2] = m[0, :2] - d / n * extra
    return np.concatenate([np.linspace(p0, m[0], 20, endpoint=False), m])


def back(m: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The motion, then back along its own path for 30-100 % of its frames (net turn shrinks)."""
    k = max(2, int(len(m) * rng.uniform(0.3, 1.0)))
    return np.concatenate([m, m[-2:-k - 1:-1]])


def dip(m: np.ndarray, c: np.ndarray, rng: np.random.Generator, size: float) -> np.ndarray:
    """The motion with an inward dip of 0.5-1.5 blocks (towards ``c``) inserted at 30-80 % of it."""
    k = int(len(m) * rng.uniform(0.3, 0.8))
    p = m[k]
    d = p[:2] - c[:2]
    r = float(np.linalg.norm(d))
    depth = min(rng.uniform(0.5, 1.5) * size, 0.6 * r)
    q = p.copy()
    q[:2] = p[:2] - d / max(r, 1e-9) * depth
    return np.concatenate([m[:k], np.linspace(p, q, 10, endpoint=False), np.linspace(q, p, 10, endpoint=False), m[k:]])


def close_circle(m: np.ndarray, c: np.ndarray, rng: np.random.Generator) -> np.ndarray | None:
    """The motion continued along a circle round ``c`` at its end's distance, in the direction it
    turned, to 0.85-1.25 turns in all; None if it already turned that far."""
    net = swept_angle(m, c)
    extra = np.sign(net) * 2 * np.pi * rng.uniform(0.85, 1.25) - net
    if np.sign(extra) != np.sign(net):
        return None
    d = m[-1, :2] - c[:2]
    r, a0 = float(np.linalg.norm(d)), float(np.arctan2(d[1], d[0]))
    phi = np.linspace(0, extra, max(10, int(abs(extra) / 0.05)) + 1)[1:]
    arc = np.column_stack([c[0] + r * np.cos(a0 + phi), c[1] + r * np.sin(a0 + phi), m[-1, 2] + phi])
    return np.concatenate([m, arc])



def smooth_poses(poses: np.ndarray, window: int) -> np.ndarray:
    """Centred moving average with edge padding (angles unwrapped first)."""
    if window <= 1 or len(poses) < 3:
        return poses
    return moving_average(poses, window)


def mirror(poses: np.ndarray) -> np.ndarray:
    out = poses.copy()
    out[:, 1] *= -1
    out[:, 2] *= -1
    return out


@dataclass(frozen=True)
class Context:
    """What a motion is read against besides its anchor, in the motion's metric frame: the further
    anchors (each a (T,3) track or one (3,) pose) and the viewpoint (2,). Only for actions that
    declare a second anchor or a viewer frame; None everywhere else."""

    more: tuple[np.ndarray, ...] = ()
    viewer: np.ndarray | None = None

    def crop(self, lo: int, hi: int | None = None) -> Context:
        """The same frames of every track as the mover's ``[lo:hi]``."""
        return Context(tuple(x[lo:hi] if x.ndim == 2 else x for x in self.more), self.viewer)

    def mirrored(self) -> Context:
        return Context(tuple(mirror(x) if x.ndim == 2 else mirror(x[None])[0] for x in self.more),
                       None if self.viewer is None else self.viewer * np.array([1.0, -1.0]))

    def at_event(self, d: Demo) -> Context:
        """Every further anchor as its mean pose over the demonstration's event (for copies of the event)."""
        return Context(tuple(x[d.start:d.end + 1].mean(axis=0) if x.ndim == 2 else x for x in self.more), self.viewer)


def demo_context(d: Demo, smooth_frames: int) -> Context:
    """A demonstration's own context: its further anchors' tracks (smoothed like the anchor's) and its viewpoint."""
    return Context(tuple(smooth_poses(x, smooth_frames) for x in d.more_anchors), d.viewer)


def reflect(poses: np.ndarray, centre: np.ndarray, angle: float) -> np.ndarray:
    """Poses (T,3) reflected across the line through ``centre`` (x, y) at ``angle`` (yaw reflected too)."""
    c2, s2 = np.cos(2 * angle), np.sin(2 * angle)
    d = poses[:, :2] - centre[:2]
    out = poses.copy()
    out[:, 0] = centre[0] + c2 * d[:, 0] + s2 * d[:, 1]
    out[:, 1] = centre[1] + s2 * d[:, 0] - c2 * d[:, 1]
    out[:, 2] = 2 * angle - poses[:, 2]
    return out


SIDE_SHARE = 0.9
"""Share of a viewer-frame action's demonstrations that must end on one side (by at least half a block)
for the other side to be "not the action" (:func:`viewer_sides`)."""


def viewer_sides(demos: list[Demo]) -> tuple[int, int]:
    """(lateral, depth): on which side of the anchor, as seen from the viewpoint, the demonstrations end.

    +1 (left / behind) or -1 (right / in front) when at least :data:`SIDE_SHARE` of them end at least half a
    block to that side; 0 when they end on both (the relation does not depend on that axis).
    """
    if not demos:
        return 0, 0
    ends = np.array([viewer_offset(d.mover[d.end, :2], d.anchor[d.end, :2], d.viewer) for d in demos]) / np.array(
        [[d.size] for d in demos])

    def side(v: np.ndarray) -> int:
        return 1 if np.mean(v >= 0.5) >= SIDE_SHARE else -1 if np.mean(v <= -0.5) >= SIDE_SHARE else 0

    return side(ends[:, 0]), side(ends[:, 1])


def mirrored_copies(d: Demo, m: np.ndarray, a: np.ndarray, ctx: Context | None, qcfg: QSRConfig,
                    sides: tuple[int, int] | None) -> list[tuple[np.ndarray, np.ndarray, Context | None, bool]]:
    """The demonstration (smoothed ``m``, ``a``) and its mirror images, each marked positive or not.

    Relative frames: the mirror image (y -> -y), a positive. Viewer frames: the reflections across the
    line of sight through the anchor and across its perpendicular, and both; positive when every axis a
    reflection flips is one the demonstrations end on both sides of (see the module docstring).
    """
    if not qcfg.viewer:
        return [(m, a, ctx, True), (mirror(m), mirror(a), None if ctx is None else ctx.mirrored(), True)]
    assert ctx is not None and ctx.viewer is not None and sides is not None
    c = a[d.start:d.end + 1].mean(axis=0)
    sight = float(np.arctan2(*(c[1::-1] - ctx.viewer[1::-1])))
    out = [(m, a, ctx, True)]
    for flip_lat, flip_dep in ((True, False), (False, True), (True, True)):
        mm, aa, more = m, a, ctx.more
        for flip, angle in ((flip_lat, sight), (flip_dep, sight + np.pi / 2)):
            if flip:
                mm, aa = reflect(mm, c, angle), reflect(aa, c, angle)
                more = tuple(reflect(x if x.ndim == 2 else x[None], c, angle).reshape(x.shape) for x in more)
        positive = not ((flip_lat and sides[0]) or (flip_dep and sides[1]))
        out.append((mm, aa, Context(more, ctx.viewer), positive))
    return out


BEARING_MARGIN = np.radians(10)
"""Bearings (seen from the viewer) this far beyond every demonstration's end are "not the action"."""


def end_bearings(demos: list[Demo]) -> tuple[float, float]:
    """(centre, half-width) of the bearings at which a viewer-frame action's demonstrations end: the angle
    of the mover's end offset from the anchor, measured from the viewer's line of sight (radians)."""
    beta = np.array([np.arctan2(*viewer_offset(d.mover[d.end, :2], d.anchor[d.end, :2], d.viewer)) for d in demos])
    centre = float(np.arctan2(np.sin(beta).mean(), np.cos(beta).mean()))
    return centre, float(np.abs(np.angle(np.exp(1j * (beta - centre)))).max())


def twisted_end(d: Demo, m: np.ndarray, a: np.ndarray, ctx: Context, bearings: tuple[float, float],
                rng: np.random.Generator) -> np.ndarray | None:
    """The mover's track turned about the anchor progressively (not at all at the event's start, fully at
    its end, by arc length) so that it ends at a bearing (seen from the viewer) :data:`BEARING_MARGIN`
    or more beyond every demonstration's: the same start, the same distances, the wrong place. A near
    miss, the negative that teaches how exactly "left of" is left, and with the same starts as the
    positives, so that where a motion starts is no cue. None when the demonstrations end all round."""
    centre, half = bearings
    if half + BEARING_MARGIN >= np.pi:
        return None
    beta = float(np.arctan2(*viewer_offset(m[d.end, :2], a[d.end, :2], ctx.viewer)))
    target = centre + rng.choice([-1.0, 1.0]) * rng.uniform(half + BEARING_MARGIN, np.pi)
    turn = float(np.angle(np.exp(1j * (target - beta))))
    c = a[d.start:d.end + 1].mean(axis=0)
    step = np.linalg.norm(np.diff(m[d.start:d.end + 1, :2], axis=0), axis=1)
    frac = np.concatenate([np.zeros(d.start), np.concatenate([[0.0], np.cumsum(step)]) / max(step.sum(), 1e-9),
                           np.ones(len(m) - d.end - 1)])
    out = np.array(m, float)
    k = frac > 0  # the frames before the event stay exactly where they were
    out[k] = turn_about(m[k], c, turn * frac[k])
    return out


FAR = (1.25, 2.5)
"""Stretched near misses end this many times farther from the anchor than the farthest positive does."""


def stretched(d: Demo, m: np.ndarray, a: np.ndarray, farthest: float, rng: np.random.Generator) -> np.ndarray:
    """The mover's track stretched about the anchor so that it ends :data:`FAR` times ``farthest`` (blocks)
    from it: on the right side, but much farther than "left of" ever ended in a demonstration or a
    stretched copy of one (a planner would otherwise be free to end anywhere on that side)."""
    c = a[d.start:d.end + 1].mean(axis=0)
    r = float(np.linalg.norm(m[d.end, :2] - c[:2])) / d.size
    return scaled(m, c, rng.uniform(*FAR) * farthest / max(r, 1e-9))


def segment_coords(end: np.ndarray, b: np.ndarray, c: np.ndarray, size: float) -> tuple[float, float]:
    """(t, off) of a point relative to two anchors: t is 0 at ``b``'s centre and 1 at ``c``'s, off the
    distance from the line through them in blocks."""
    e, rel = c[:2] - b[:2], end[:2] - b[:2]
    sep2 = max(float(e @ e), 1e-12)
    return float(rel @ e) / sep2, abs(float(rel[0] * e[1] - rel[1] * e[0])) / np.sqrt(sep2) / size


@dataclass(frozen=True)
class Region:
    """Where a two-anchor action's demonstrations end relative to their anchors (:func:`segment_coords`),
    widened by a margin: ``t`` in [t_lo, t_hi], at most ``off_hi`` blocks off the line."""

    t_lo: float
    t_hi: float
    off_hi: float

    def holds(self, t: float, off: float) -> bool:
        return self.t_lo <= t <= self.t_hi and off <= self.off_hi


REGION_MARGIN = (0.1, 0.4)
"""Margins of :class:`Region` around the demonstrations' ends: 0.1 of the anchors' separation along the
line, 0.4 block off it (about a tracker's error: a demonstration's end, not a planner's exploit)."""


def end_region(demos: list[Demo]) -> Region:
    """The :class:`Region` a two-anchor action's demonstrations end in."""
    tc = np.array([segment_coords(d.mover[d.end], d.anchor[d.end], d.more_anchors[0][d.end], d.size) for d in demos])
    return Region(float(tc[:, 0].min()) - REGION_MARGIN[0], float(tc[:, 0].max()) + REGION_MARGIN[0],
                  float(tc[:, 1].max()) + REGION_MARGIN[1])


def displaced(d: Demo, m: np.ndarray, a: np.ndarray, ctx: Context, region: Region, rng: np.random.Generator,
              tries: int = 10) -> tuple[np.ndarray, Context] | None:
    """A two-anchor demonstration with one anchor turned 10-180 degrees about the other, so that the mover
    ends where no demonstration ends (outside ``region``) without its path running through the moved
    anchor: a near miss, the negative that teaches how exact the relation is. (anchor, context) or None."""
    b, c = a[d.start:d.end + 1].mean(axis=0), ctx.more[0][d.start:d.end + 1].mean(axis=0)
    path = m[d.start:d.end + 1, :2]
    for _ in range(tries):
        angle = rng.choice([-1.0, 1.0]) * np.radians(rng.uniform(10, 180))
        first = bool(rng.random() < 0.5)
        nb, nc = (turn_about(b, c, angle), c) if first else (b, turn_about(c, b, angle))
        moved = nb if first else nc
        if np.linalg.norm(path - moved[:2], axis=1).min() / d.size < 1.1:
            continue
        if region.holds(*segment_coords(m[d.end], nb, nc, d.size)):
            continue
        if first:
            return turn_about(a, c, angle), ctx
        return a, Context((turn_about(ctx.more[0], b, angle),), ctx.viewer)
    return None


def check_demos(action: str, demos: list[Demo], qcfg: QSRConfig) -> None:
    """Every demonstration of a viewer-frame action has a viewpoint, of a two-anchor action a second anchor."""
    for d in demos:
        if qcfg.viewer and d.viewer is None:
            raise DataError(f'demonstration {d.id} has no "viewer_xy": the action "{action}" is seen from a viewer '
                            "(frame = \"viewer\"), so its demonstrations must say where the viewer was")
        if len(d.more_anchors) + 1 != qcfg.anchors:
            raise DataError(f"demonstration {d.id} has {len(d.more_anchors) + 1} reference block(s), the action "
                            f'"{action}" takes {qcfg.anchors} ("event_anchors" and "more_poses")')


def placed(end: np.ndarray, anchor: np.ndarray, size: float, qcfg: QSRConfig, sides: tuple[int, int] | None,
            rng: np.random.Generator) -> Context:
    """A context for a motion recorded without one (another action's demonstration, a still block) that makes
    it clearly not this action: a second anchor on the far side of the first from the motion's ``end``, a
    viewpoint 8-14 blocks away from which the end lies on a side ``sides`` says the action never ends on."""
    off = end[:2] - anchor[:2]
    bearing = float(np.arctan2(off[1], off[0]))
    more: tuple[np.ndarray, ...] = ()
    if qcfg.anchors > 1:
        phi = bearing + np.radians(rng.uniform(100, 260))
        r = rng.uniform(3.0, 5.0) * size
        more = (np.array([anchor[0] + r * np.cos(phi), anchor[1] + r * np.sin(phi), rng.uniform(0, np.pi / 2)]),)
    viewer = None
    if sides is not None:
        if sides[0]:  # beta: the end's bearing from the line of sight; lateral = r sin(beta), depth = r cos(beta)
            beta = -sides[0] * np.radians(rng.uniform(20, 160))
        elif sides[1]:
            beta = (np.pi if sides[1] > 0 else 0.0) + np.radians(rng.uniform(-70, 70))
        else:
            beta = rng.uniform(-np.pi, np.pi)
        alpha = bearing - beta  # direction of the line of sight
        viewer = anchor[:2] - rng.uniform(8.0, 14.0) * size * np.array([np.cos(alpha), np.sin(alpha)])
    return Context(more, viewer)
