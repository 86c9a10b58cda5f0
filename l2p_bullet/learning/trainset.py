"""Training sequences for one action's progress model: positives, negatives and their labels.

Why each part is here:
- **Positives** are the action's demonstrations with their context: progress is 0 on the frames before
  the event, rises linearly with the mover's arc length to 1 at the event's end, and falls back to 0
  over ``post_decay`` blocks of further motion (the person resetting the block is not the event).
  "around" is labelled by the net turn swept round the anchor instead (``DataConfig.turn_label``);
  "away"'s dip, back-off and one detour copy by the net distance gained (``DataConfig.net_label``).
  Each is also used cropped to the event alone (a planner's path has no context), mirrored (left/right
  does not change any of the five actions), simplified into 1-4 straight moves (planners and the
  graded 2-D demonstrations move in straight lines while people slide along curves), stretched about
  the anchor, and with a drifting bearing (see :class:`DataConfig`).
- **Negatives** (label 0, penalised on the last ``negative_tail`` of their motion) teach the model
  what the action is not, so that a planner maximising it cannot cheat: the other actions'
  demonstrations (except those that are also, or begin, this action: a good "next to" is also
  "closer"), standing still, and random straight-line motions, including far jumps, that are clearly
  not even a partial instance of the action (:func:`violates`).
Everything is in block units; motion-capture jitter is smoothed before resampling.

Plugin actions that declare a viewer frame or a second anchor (:mod:`l2p_bullet.core.frames`) read
their demonstrations against more than the anchor (:class:`Context`), and the set follows the
declaration (:func:`build`; the five built-in actions take none of these branches):
- **viewer frame**: no mirroring (it would turn left into right). The demonstrations are reflected in
  the viewer's frame instead, across the line of sight through the anchor (left <-> right) and across
  the line through the anchor at right angles to it (in front <-> behind): a reflection that moves the
  ends to a side the demonstrations never end on (:func:`viewer_sides`) is a **negative** (the left-of
  model learns that right-of motions are not it), one that keeps them where they end is a positive
  (in front stays in front when left and right are swapped). Near misses are negatives too: the end
  turned (start kept) to a bearing no demonstration ends at, or stretched beyond the farthest; twisted
  copies (start turned, end kept) are positives. The other actions' demonstrations, as negatives, are
  seen from a viewpoint placed so that they end on a side this action does not.
- **two anchors**: the second anchor's track goes along; stretched copies are stretched about the
  event's end (where the relation holds) instead of about the first anchor; the other actions'
  demonstrations get a second anchor on the far side of the first from where they end (ending beside
  one anchor, away from the other, is not "between" them).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..actions import BUILTIN, ActionSpec
from ..core.geometry import swept_angle, unwrapped_bearing
from ..core.vocabulary import ACTIONS
from ..data.demos import SMOOTH_FRAMES, Demo
from ..progress.features import QSRConfig, features, resample
from . import augment
from .augment import (
    Context,
    check_demos,
    demo_context,
    displaced,
    end_bearings,
    end_region,
    mirror,
    mirrored_copies,
    placed,
    smooth_poses,
    stretched,
    twisted_end,
    viewer_sides,
)


def _per_action(option: str) -> dict:
    """A built-in training option (``actions.spec.Training``) of every built-in action that sets one."""
    return {a: getattr(s.training, option) for a, s in BUILTIN.items() if getattr(s.training, option) is not None}


def _actions_with(option: str) -> tuple[str, ...]:
    return tuple(a for a, s in BUILTIN.items() if getattr(s.training, option))


@dataclass(frozen=True)
class DataConfig:
    """How the training set is built (written to the manifest's ``[training]``). Each field says why it
    exists in one line; how each value was arrived at, with the numbers, is in docs/learning.md."""

    smooth_frames: int = SMOOTH_FRAMES
    """Moving-average window on captured poses (data.demos.SMOOTH_FRAMES): jitter would read as motion."""
    post_decay: float = 1.0
    """Blocks of further motion over which progress falls back to 0 after the event (the reset is not it)."""
    polylines_per_demo: int = 2
    """Straight-line simplifications per positive: planners and the graded demos move in straight lines."""
    scaled_per_demo: int = 2
    """Copies stretched about the anchor (not next-to): people graded starts farther than any capture's."""
    scale_range: tuple[float, float] = (0.75, 1.7)
    """Stretch factors of those copies (blocks keep their size)."""
    scale_ranges: dict = field(default_factory=lambda: _per_action("scale_range"))
    """Per-action stretch ranges: around stays near the anchor; closer must have seen closing in from 2 blocks."""
    approach: dict = field(default_factory=lambda: _per_action("approach"))
    """Actions with copies that start farther back along their first direction (blocks): far starts, near passes."""
    shortened: dict = field(default_factory=lambda: _per_action("shortened"))
    """Actions with extra copies shrunk about their own start: the same motion stopped sooner is complete."""
    twisted_per_demo: int = 2
    """Copies whose bearing drifts (``augment.twist``): people graded sweeping motions well; captures are radial."""
    twist_actions: tuple[str, ...] = field(default_factory=lambda: _actions_with("twist"))
    """The actions whose meaning a drifting bearing does not change."""
    twist_max_deg: float = 100.0
    """Largest bearing drift of a twisted copy."""
    detour_per_demo: int = 2
    """Copies of closer/away that first move the other way: the net motion is still the action."""
    turn_label: dict = field(default_factory=lambda: _per_action("turn_label"))
    """Actions labelled by the net turn swept (in these many turns): an around ends when the circle closes."""
    turn_copies: int = 2
    """Per turn-labelled demo and kind: partial crops, out-and-back copies and closed circles."""
    net_label: dict = field(default_factory=lambda: _per_action("net_label"))
    """Actions whose dip/back-off copies are labelled by net gain less this times the inward motion."""
    net_copies: int = 2
    """Per net-labelled demo and kind: copies with an inward dip, and copies that back off at the end."""
    random_negatives: int = 300
    """Random straight-line motions that clearly are not the action (:func:`violates`), labelled 0."""
    static_negatives: int = 40
    """Motions that stand still: progress must not rise for doing nothing."""
    negative_tail: float = 0.4
    """Final fraction of a negative that is penalised: another motion's start can be this one's start."""
    negative_weight: float = 1.0
    """Total weight of the negatives relative to the positives."""
    negatives: dict = field(default_factory=lambda: {a: list(s.training.negatives) for a, s in BUILTIN.items()})
    """Whose demonstrations are negatives; pairs where one is (a prefix of) the other are left out."""
    unscaled: tuple[str, ...] = field(default_factory=lambda: tuple(a for a, s in BUILTIN.items()
                                                                    if not s.training.scaled))
    """Actions without stretched copies (next-to: stretched, it would end apart)."""
    detour_actions: tuple[str, ...] = field(default_factory=lambda: _actions_with("detour"))
    """Actions with detour copies (closer, away: the net motion is still the action)."""

    def with_action(self, spec: ActionSpec | None) -> DataConfig:
        """This configuration with a plugin action's own training options (``ActionSpec.training``) added;
        the built-ins' are the defaults already. ``spec`` None: unchanged."""
        if spec is None:
            return self
        t, n = spec.training, spec.name

        def add(table: dict, value: object) -> dict:
            return table if value is None else {**table, n: value}

        return replace(
            self, negatives=add(self.negatives, list(t.negatives) if t.negatives else None),
            scale_ranges=add(self.scale_ranges, t.scale_range), approach=add(self.approach, t.approach),
            shortened=add(self.shortened, t.shortened), turn_label=add(self.turn_label, t.turn_label),
            net_label=add(self.net_label, t.net_label),
            twist_actions=self.twist_actions + ((n,) if t.twist and n not in self.twist_actions else ()),
            detour_actions=self.detour_actions + ((n,) if t.detour and n not in self.detour_actions else ()),
            unscaled=self.unscaled + ((n,) if not t.scaled and n not in self.unscaled else ()))

    def to_dict(self) -> dict:
        keys = ("smooth_frames", "post_decay", "polylines_per_demo", "scaled_per_demo", "twisted_per_demo",
                "twist_max_deg", "detour_per_demo", "turn_copies", "net_copies", "random_negatives",
                "static_negatives", "negative_tail", "negative_weight")
        d = {k: getattr(self, k) for k in keys}
        return {**d, "scale_range": list(self.scale_range), "twist_actions": list(self.twist_actions),
                "unscaled": list(self.unscaled), "detour_actions": list(self.detour_actions),
                "negatives": dict(self.negatives), "turn_label": dict(self.turn_label),
                "net_label": dict(self.net_label),
                "scale_ranges": {k: list(v) for k, v in self.scale_ranges.items()},
                "shortened": {k: list(v) for k, v in self.shortened.items()},
                "approach": {k: list(v) for k, v in self.approach.items()}}


@dataclass
class TrainingSequence:
    """One training sequence: per-frame features, targets and a weight."""

    x: np.ndarray  # (K, F) float32
    y: np.ndarray  # (K,) float32
    weight: float = 1.0
    positive: bool = False
    frame_w: np.ndarray | None = None  # (K,) relative per-frame weights (None: uniform)
    end: int = -1  # index of the event's last frame (positives), else the last frame


def _labelled(mover: np.ndarray, anchor: np.ndarray, size: float, start: float, end: float,
              qcfg: QSRConfig, dcfg: DataConfig, positive: bool, turns: float | None = None,
              net: float | None = None, ctx: Context | None = None) -> TrainingSequence:
    if ctx is None:
        rs = resample(mover, anchor, size, qcfg)
        x = features(rs.mover, rs.anchor, qcfg)
    else:
        rs = resample(mover, anchor, size, qcfg, list(ctx.more) or None)
        x = features(rs.mover, rs.anchor, qcfg, more=rs.more or None,
                     viewer=None if ctx.viewer is None else np.asarray(ctx.viewer, float)[:2] / size)
    if not positive:
        # penalise only the tail: arc length past (1 - tail) of the way from the start to the end
        s_from = rs.arc[-1] * (1.0 - dcfg.negative_tail)
        fw = (rs.arc >= s_from - 1e-9).astype(np.float32)
        return TrainingSequence(x, np.zeros(len(x), np.float32), end=len(x) - 1, frame_w=fw)
    idx = np.arange(len(rs.input_arc), dtype=float)
    s0, s1 = np.interp([start, end], idx, rs.input_arc)
    s = rs.arc
    k_end = int(np.clip(np.searchsorted(s, s1 - 1e-9), 0, len(s) - 1))
    if net is not None:  # net gain in distance, less ``net`` times the inward motion so far
        r = np.linalg.norm(rs.mover[:, :2] - rs.anchor[:, :2], axis=1)
        r0 = float(np.interp(s0, s, r))
        inward = np.concatenate([[0.0], np.cumsum(np.maximum(-np.diff(r), 0.0))])
        frac = np.clip((r - r0 - net * inward) / max(float(r.max()) - r0, 1.0), 0, 1)
    elif turns is None:
        frac = np.clip((s - s0) / max(s1 - s0, 1e-6), 0, 1)
    else:  # net turn round the anchor since the event's start, in units of ``turns`` full turns
        ang = unwrapped_bearing(rs.mover[:, :2] - rs.anchor[:, :2])
        frac = np.clip(np.abs(ang - np.interp(s0, s, ang)) / (2 * np.pi * turns), 0, 1)
    y = np.where(s <= s0, 0.0, frac)
    after = rs.times > end + 1e-9
    # the first frame at or past the end is the end (the grid rarely hits it exactly), then decay
    decay = np.clip(1.0 - np.maximum(s - s1 - qcfg.spacing, 0) / dcfg.post_decay, 0, 1)
    y = np.where(after, frac[k_end] * decay, y)
    return TrainingSequence(x, y.astype(np.float32), positive=True, end=k_end)


def violates(action: str | ActionSpec, mover: np.ndarray, anchor: np.ndarray) -> bool:
    """True when a block-unit motion is clearly not even a *partial* instance of the action, by the checks the
    action declares (``ActionSpec.training.violation``; ``action`` a built-in's name or a spec).

    Used only to label random motions as negatives; motions that pass are left out, not made positive.
    Partial instances must keep a partial progress (the planner climbs it), so the rules only reject
    motions that went the wrong way: a "closer" that ends farther, an "around" that never turned, ...
    """
    spec = BUILTIN.get(action) if isinstance(action, str) else action
    v = spec.training.violation if spec is not None else None
    if v is None:
        raise ValueError(f"{action}: the action declares no random negatives (ActionSpec.training.violation)")
    d = mover[:, :2] - anchor[:, :2]
    r = np.linalg.norm(d, axis=1)
    swept = abs(swept_angle(d))
    length = np.linalg.norm(np.diff(mover[:, :2], axis=0), axis=1).sum()
    return bool(
        (v.ends_farther is not None and r[-1] >= r[0] + v.ends_farther)
        or (v.ends_nearer is not None and r[-1] <= r[0] - v.ends_nearer)
        or (v.stays_off is not None and r[-1] > v.stays_off[0] and r[-1] >= r[0] - v.stays_off[1])
        or (v.strays is not None and r.max() > v.strays[0] and r[0] < v.strays[1])
        or (v.no_turn is not None and swept < np.radians(v.no_turn[0]) and length > v.no_turn[1])
        or (v.max_turn_deg is not None and swept > np.radians(v.max_turn_deg)))


def random_motion(rng: np.random.Generator, n_moves: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """A random 1-4 segment (or ``n_moves``) straight-line motion of the mover around a static anchor (block units)."""
    anchor = np.array([0.0, 0.0, rng.uniform(0, np.pi / 2)])
    r0, b0 = rng.uniform(1.2, 8.0), rng.uniform(-np.pi, np.pi)
    pts = [np.array([r0 * np.cos(b0), r0 * np.sin(b0), rng.uniform(0, np.pi / 2)])]
    for _ in range(int(rng.integers(1, 5)) if n_moves is None else n_moves):
        if rng.random() < 0.2:  # a far jump
            r, b = rng.uniform(6, 14), rng.uniform(-np.pi, np.pi)
        else:
            r, b = rng.uniform(1.1, 7.0), rng.uniform(-np.pi, np.pi)
        pts.append(np.array([r * np.cos(b), r * np.sin(b), pts[-1][2] + rng.normal(0, 0.3)]))
    if len(pts) == 1:
        mover = pts[0][None] + np.concatenate([np.zeros((1, 3)), rng.normal(0, 0.01, (5, 3))])
    else:
        mover = np.concatenate([np.linspace(pts[i], pts[i + 1], 30) for i in range(len(pts) - 1)])
    return mover, np.repeat(anchor[None], len(mover), axis=0)


def build(action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig, dcfg: DataConfig,
          seed: int = 0) -> list[TrainingSequence]:
    """All training sequences for ``action`` from the demonstrations of every action (train split).

    Positives first (each demonstration and its mirror image, with their copies), then the negatives,
    weighted so that together they weigh ``negative_weight`` times the positives. One random generator
    drives every draw, in this order, so a seed reproduces the set bit for bit. A viewer frame or a
    second anchor changes which mirror images are positives and how the negatives are read (module
    docstring).
    """
    rng = np.random.default_rng(seed)
    own = demos.get(action, [])
    sides = None
    if qcfg.viewer or qcfg.anchors > 1:
        check_demos(action, own, qcfg)
        sides = viewer_sides(own) if qcfg.viewer else None
    pos = [s for d in own for s in _positives(action, d, qcfg, dcfg, rng, sides)]
    neg = _negatives(action, demos, qcfg, dcfg, rng, sides)
    w = dcfg.negative_weight * len(pos) / max(len(neg), 1)
    for s in neg:
        s.weight = w
    return pos + neg


def _positives(action: str, d: Demo, qcfg: QSRConfig, dcfg: DataConfig, rng: np.random.Generator,
               sides: tuple[int, int] | None = None) -> list[TrainingSequence]:
    """A demonstration and its mirror image, each with its context, cropped to the event, and its copies."""
    turns, net = dcfg.turn_label.get(action), dcfg.net_label.get(action)
    out = []
    m, a = smooth_poses(d.mover, dcfg.smooth_frames), smooth_poses(d.anchor, dcfg.smooth_frames)
    ctx = demo_context(d, dcfg.smooth_frames) if sides is not None or qcfg.anchors > 1 else None
    for mm, aa, cx, positive in mirrored_copies(d, m, a, ctx, qcfg, sides):
        if not positive:
            continue
        out.append(_labelled(mm, aa, d.size, d.start, d.end, qcfg, dcfg, True, turns, ctx=cx))
        out.append(_labelled(mm[d.start:], aa[d.start:], d.size, 0, d.end - d.start, qcfg, dcfg, True, turns,
                             ctx=None if cx is None else cx.crop(d.start)))
        c = aa[d.start:d.end + 1].mean(axis=0)
        cc = None if cx is None else cx.at_event(d)
        about_end = qcfg.anchors > 1
        variants, net_variants = _copies(action, mm[d.start:d.end + 1], c, d.size, dcfg, rng, about_end,
                                         twist=qcfg.viewer)
        for pm in variants:
            if pm is not None:
                pa = np.repeat(c[None], len(pm), axis=0)
                out.append(_labelled(pm, pa, d.size, 0, len(pm) - 1, qcfg, dcfg, True, turns, ctx=cc))
        for pm in net_variants:
            if pm is not None:
                pa = np.repeat(c[None], len(pm), axis=0)
                out.append(_labelled(pm, pa, d.size, 0, len(pm) - 1, qcfg, dcfg, True, net=net, ctx=cc))
    return out


def _copies(action: str, ev_m: np.ndarray, c: np.ndarray, size: float, dcfg: DataConfig,
            rng: np.random.Generator, about_end: bool = False, twist: bool = False) -> tuple[list, list]:
    """The event's copies (see :class:`DataConfig`): those labelled like the event, and those labelled by
    the net distance gained (``net_label`` actions). None entries are copies that could not be made.
    ``about_end`` stretches about the event's end instead of the anchor (two-anchor actions); ``twist``
    adds twisted copies (a viewer-frame action: where the block comes from is not the relation, where
    it ends is)."""
    variants = [augment.polyline(ev_m, c, rng) for _ in range(dcfg.polylines_per_demo)]
    for _ in range(dcfg.scaled_per_demo if action not in dcfg.unscaled else 0):
        pm = augment.event_or_polyline(ev_m, c, rng)
        if pm is not None and about_end:
            lo, hi = dcfg.scale_ranges.get(action, dcfg.scale_range)
            pm = augment.scaled(pm, pm[-1], max(rng.uniform(lo, hi), 1.0))  # the same end, from farther away
        elif pm is not None:
            lo, hi = dcfg.scale_ranges.get(action, dcfg.scale_range)
            nearest = float(np.linalg.norm(pm[:, :2] - c[:2], axis=1).min()) / size
            pm = augment.scaled(pm, c, max(rng.uniform(lo, hi), min(1.0, 1.0 / max(nearest, 1e-9))))
        variants.append(pm)
    for _ in range(dcfg.scaled_per_demo if action in dcfg.shortened else 0):
        pm = augment.event_or_polyline(ev_m, c, rng)
        if pm is not None:
            pm = augment.scaled(pm, pm[0], rng.uniform(*dcfg.shortened[action]))
        variants.append(pm)
    for _ in range(dcfg.scaled_per_demo if action in dcfg.approach else 0):
        pm = augment.event_or_polyline(ev_m, c, rng)
        variants.append(None if pm is None else augment.approach(pm, rng.uniform(*dcfg.approach[action]) * size))
    for _ in range(dcfg.twisted_per_demo if action in dcfg.twist_actions or twist else 0):
        pm = augment.event_or_polyline(ev_m, c, rng)
        angle = np.radians(dcfg.twist_max_deg) * rng.uniform(-1, 1)
        variants.append(None if pm is None else augment.twist(pm, c, angle))
    for _ in range(dcfg.detour_per_demo if action in dcfg.detour_actions else 0):
        variants.append(augment.detour(ev_m, c, rng, size))
    net_variants: list = []
    if action in dcfg.net_label:  # the last detour too: coming closer first is not progress away
        net_variants, variants = variants[len(variants) - 1:], variants[:len(variants) - 1]
        for _ in range(dcfg.net_copies):
            pm = augment.event_or_polyline(ev_m, c, rng)
            if pm is None:
                continue
            net_variants.append(augment.dip(pm, c, rng, size))
            net_variants.append(augment.back(pm, rng))
    for _ in range(dcfg.turn_copies if action in dcfg.turn_label else 0):
        pm = augment.event_or_polyline(ev_m, c, rng)
        if pm is None:
            continue
        variants.append(pm[: max(2, int(len(pm) * rng.uniform(0.4, 0.6)))])
        variants.append(augment.back(pm, rng))
        variants.append(augment.close_circle(pm, c, rng))
    return variants, net_variants


NEAR_MISSES = 2
"""Near misses per positive copy of a two-anchor or viewer-frame demonstration (``augment.displaced``,
``augment.twisted_end``)."""


def _negatives(action: str, demos: dict[str, list[Demo]], qcfg: QSRConfig, dcfg: DataConfig,
               rng: np.random.Generator, sides: tuple[int, int] | None = None) -> list[TrainingSequence]:
    """The other actions' demonstrations (with context and cropped, both mirror images), random motions
    that :func:`violates` the action, and motions that stand still. A viewer-frame action adds its own
    demonstrations' reflections that end on the wrong side (:func:`~l2p_bullet.learning.augment.mirrored_copies`)."""
    general = sides is not None or qcfg.anchors > 1
    neg: list[TrainingSequence] = []
    for other in dcfg.negatives.get(action, [o for o in ACTIONS if o != action]):
        for d in demos.get(other, []):
            m, a = smooth_poses(d.mover, dcfg.smooth_frames), smooth_poses(d.anchor, dcfg.smooth_frames)
            for mm, aa in ((m, a), (mirror(m), mirror(a))):
                cx = placed(mm[d.end], aa[d.end], d.size, qcfg, sides, rng) if general else None
                neg.append(_labelled(mm[: d.end + 1], aa[: d.end + 1], d.size, 0, 0, qcfg, dcfg, False, ctx=cx))
                neg.append(_labelled(mm[d.start:d.end + 1], aa[d.start:d.end + 1], d.size, 0, 0, qcfg, dcfg, False,
                                     ctx=cx))
    if qcfg.anchors > 1:
        region = end_region(demos.get(action, []))
        for d in demos.get(action, []):
            m, a = smooth_poses(d.mover, dcfg.smooth_frames), smooth_poses(d.anchor, dcfg.smooth_frames)
            for mm, aa, cx, _ in mirrored_copies(d, m, a, demo_context(d, dcfg.smooth_frames), qcfg, sides):
                for _ in range(NEAR_MISSES):
                    miss = displaced(d, mm, aa, cx, region, rng)
                    if miss is not None:
                        neg.append(_labelled(mm[: d.end + 1], miss[0][: d.end + 1], d.size, 0, 0, qcfg, dcfg, False,
                                             ctx=miss[1].crop(0, d.end + 1)))
                        neg.append(_labelled(mm[d.start:d.end + 1], miss[0][d.start:d.end + 1], d.size, 0, 0, qcfg,
                                             dcfg, False, ctx=miss[1].crop(d.start, d.end + 1)))
    if sides is not None:
        own = demos.get(action, [])
        bearings = end_bearings(own)
        farthest = max(float(np.linalg.norm(d.mover[d.end, :2] - d.anchor[d.end, :2])) / d.size for d in own) * max(
            dcfg.scale_ranges.get(action, dcfg.scale_range))
        for d in own:
            m, a = smooth_poses(d.mover, dcfg.smooth_frames), smooth_poses(d.anchor, dcfg.smooth_frames)
            for mm, aa, cx, positive in mirrored_copies(d, m, a, demo_context(d, dcfg.smooth_frames), qcfg, sides):
                wrong = [(mm, cx)] if not positive else (
                    [(twisted_end(d, mm, aa, cx, bearings, rng), cx) for _ in range(NEAR_MISSES)]
                    + [(stretched(d, mm, aa, farthest, rng), cx)])
                for wm, x in wrong:
                    if wm is None:
                        continue
                    neg.append(_labelled(wm[: d.end + 1], aa[: d.end + 1], d.size, 0, 0, qcfg, dcfg, False,
                                         ctx=x.crop(0, d.end + 1)))
                    neg.append(_labelled(wm[d.start:d.end + 1], aa[d.start:d.end + 1], d.size, 0, 0, qcfg, dcfg,
                                         False, ctx=x.crop(d.start, d.end + 1)))
    n_rand = tries = 0
    while n_rand < dcfg.random_negatives and tries < 20 * dcfg.random_negatives:
        tries += 1
        mover, anchor = random_motion(rng)
        if violates(action, mover, anchor):
            neg.append(_labelled(mover, anchor, 1.0, 0, 0, qcfg, dcfg, False))
            n_rand += 1
    for _ in range(dcfg.static_negatives):
        mover, anchor = random_motion(rng, n_moves=0)
        cx = placed(mover[-1], anchor[-1], 1.0, qcfg, (0, 0) if sides else None, rng) if general else None
        neg.append(_labelled(mover, anchor, 1.0, 0, 0, qcfg, dcfg, False, ctx=cx))
    return neg


def demo_sequence(d: Demo, qcfg: QSRConfig, dcfg: DataConfig) -> TrainingSequence:
    """A demonstration with its whole context, labelled as a positive (for held-out MSE)."""
    m, a = smooth_poses(d.mover, dcfg.smooth_frames), smooth_poses(d.anchor, dcfg.smooth_frames)
    ctx = demo_context(d, dcfg.smooth_frames) if qcfg.viewer or qcfg.anchors > 1 else None
    return _labelled(m, a, d.size, d.start, d.end, qcfg, dcfg, True, ctx=ctx)
