"""The rule judges of the five built-in actions: did the mover do what the action says?

Why rules and not the learned model: the planner maximises the learned progress model, so judging its
paths with the same model would only measure how well the planner exploits it. These rules are written
from the meaning of the words, in **units of block size** (the original evaluator used absolute
thresholds, which broke as soon as the blocks changed size, and its "next to" rule was wrong):

- closer:  the centre distance shrinks steadily and closes at least half of the room there was
           (room = start distance - 1 block, the distance at which two squares touch face to face);
           the score also grows with the distance covered (people graded short moves down);
- away:    the centre distance grows steadily, by at least one block (score: the growth less the
           largest step back);
- next-to: the mover ends adjacent: the gap between the two footprints is at most half a block (and
           they do not overlap);
- past:    the mover crosses from one side of the anchor to the other along its overall direction of
           travel (starting at least half a block before it and ending at least half a block beyond it),
           passes near it (closest centre distance at most 4 blocks) and does not circle it (turns at
           most half a turn around it: more is going around);
- around:  the mover sweeps nearly a full turn around the anchor (at least 0.8 turn) while staying near
           it (centre distance at most 4 blocks).

For plugin actions (a manifest's ``[judge] rules = "..."``):

- between:     a two-anchor rule: the mover ends on the segment between the two anchors (its centre
               projects strictly between theirs and lies within half a block of the line through them)
               without touching either;
- left-of, right-of, in-front-of, behind: viewer-frame rules: the mover ends on that side of the anchor
               as the viewer sees it (its offset from the anchor within 45 degrees of the viewer's left,
               right, towards the viewer, away from it), near it (centre distance at most 4 blocks) and
               not overlapping it. The viewer is the ``viewer`` keyword, the robot's base by default.

The numbers above are declared by each built-in action (``l2p_bullet/actions/<name>/__init__.py``,
``ActionSpec.thresholds``) and read here once, as the constants below.

"Steadily" allows wobbles of half a block against the running best. Every rule also gives a graded
``score`` in [0, 1] (used for the correlation with people's grades; ``success`` is the yes/no verdict).
Motions are read in the anchor's frame (mover minus anchor), so a moving anchor is handled too.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ..actions import BUILTIN
from ..core.frames import VIEWPOINTS, viewer_offset
from ..core.geometry import polygons_overlap, swept_angle
from ..core.vocabulary import canonical_action
from ..errors import UnknownActionError
from .base import Verdict

WOBBLE = 0.5
"""Blocks a 'steady' change may go back against its running best (motion-capture jitter in the human
demonstrations reaches this: at 0.3 the rule rejected 37 % of people's "closer" demonstrations)."""
# The built-in actions' thresholds, declared by each action (l2p_bullet/actions/<name>/__init__.py):
CLOSER_SHARE = BUILTIN["closer"].thresholds["share"]
"""Share of the room there was (:func:`closer_room`) that "closer" must close."""
AWAY_GAIN = BUILTIN["away"].thresholds["gain"]
"""Blocks the centre distance must grow by for "away"."""
NEXT_TO_GAP = BUILTIN["next-to"].thresholds["gap"]
"""Largest gap (blocks) between the footprints at the end of "next to"."""
PAST_MARGIN = BUILTIN["past"].thresholds["margin"]
"""Blocks "past" must start before the anchor and end beyond it (along its direction of travel)."""
PAST_NEAR = BUILTIN["past"].thresholds["near"]
"""Largest closest centre distance (blocks) of "past"."""
PAST_MAX_TURN_DEG = BUILTIN["past"].thresholds["max_turn_deg"]
"""Most degrees "past" may turn around the anchor (more is going around)."""
AROUND_TURNS = BUILTIN["around"].thresholds["turns"]
"""Share of a full turn around the anchor that "around" must sweep."""
AROUND_NEAR = BUILTIN["around"].thresholds["near"]
"""Largest centre distance (blocks) of "around"."""
NEAR = 4.0
"""Largest centre distance (blocks) at which the viewer-frame sides (plugins' rule sets) still count as near."""


def _unit_square(pose: np.ndarray) -> np.ndarray:
    x, y, t = pose
    c, s = math.cos(t), math.sin(t)
    corners = np.array([[0.5, 0.5], [-0.5, 0.5], [-0.5, -0.5], [0.5, -0.5]])
    return corners @ np.array([[c, s], [-s, c]]) + np.array([x, y])


def _point_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = np.clip(((p - a) @ ab) / max(float(ab @ ab), 1e-12), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=-1)


def square_gap(a: np.ndarray, b: np.ndarray) -> float:
    """Gap between two unit squares at poses a, b (block units); 0 when they touch or overlap."""
    pa, pb = _unit_square(a), _unit_square(b)
    if polygons_overlap(pa, pb):
        return 0.0
    d = [float(_point_segment(p, q[i], q[(i + 1) % 4]).min()) for p, q in ((pa, pb), (pb, pa)) for i in range(4)]
    return min(d)


def _relative(mover: np.ndarray, anchor: np.ndarray, size: float) -> tuple[np.ndarray, np.ndarray]:
    mover = np.asarray(mover, float).reshape(-1, 3)
    anchor = np.asarray(anchor, float).reshape(-1, 3)
    if len(anchor) == 1:
        anchor = np.repeat(anchor, len(mover), axis=0)
    rel = (mover[:, :2] - anchor[:, :2]) / size
    return rel, np.linalg.norm(rel, axis=1)


def closer_room(start: float) -> float:
    """The room "closer" has, in blocks, from a start distance of ``start`` blocks: the distance to where two
    squares touch face to face (1 block), at least a quarter block (planning/feasibility.py reads it too)."""
    return max(start - 1.0, 0.25)


def _closer(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    room = closer_room(float(d[0]))
    moved = float(d[0]) - float(d[-1])
    closed = moved / room
    rise = float(np.max(d - np.minimum.accumulate(d)))
    # people also reward how far it came, not only the share of the room ("right, but too short")
    score = float(np.clip(closed, 0, 1) * np.clip(moved / 2.0, 0, 1)) * (1.0 if rise <= WOBBLE else 0.5)
    ok = closed >= CLOSER_SHARE and rise <= WOBBLE
    why = f"closed {closed:.0%} of the gap (start {d[0]:.2f}, end {d[-1]:.2f} blocks), went back {rise:.2f} blocks"
    return Verdict(ok, score, why)


def _away(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    gained = float(d[-1]) - float(d[0])
    drop = float(np.max(np.maximum.accumulate(d) - d))
    score = float(np.clip((gained - drop) / 6.0, 0, 1))
    ok = gained >= AWAY_GAIN and drop <= WOBBLE
    return Verdict(ok, score, f"distance grew by {gained:.2f} blocks (start {d[0]:.2f}), went back {drop:.2f} blocks")


def _next_to(rel: np.ndarray, d: np.ndarray, mover: np.ndarray, anchor: np.ndarray, size: float,
             **_: object) -> Verdict:
    m = np.r_[rel[-1], mover[-1, 2]]
    a = np.r_[0.0, 0.0, anchor[-1, 2]]
    gap = square_gap(m, a)
    overlap = gap == 0.0 and _overlaps(m, a)
    score = 0.0 if overlap else float(1.0 - min(gap, 3.0) / 3.0)
    ok = gap <= NEXT_TO_GAP and not overlap
    return Verdict(ok, score, f"ends {gap:.2f} blocks from the anchor" + (" (overlapping it)" if overlap else ""))


def _overlaps(a: np.ndarray, b: np.ndarray) -> bool:
    return polygons_overlap(_unit_square(a), _unit_square(b), margin=-0.02)


def _past(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    travel = rel[-1] - rel[0]
    length = float(np.linalg.norm(travel))
    if length < 1e-9:
        return Verdict(False, 0.0, "did not move")
    u = travel / length
    before, beyond = -float(rel[0] @ u), float(rel[-1] @ u)
    near = float(d.min())
    swept = math.degrees(abs(swept_angle(rel)))
    crossing = min(np.clip(before / PAST_MARGIN, 0, 1), np.clip(beyond / PAST_MARGIN, 0, 1))
    nearness = float(np.clip(1.0 - (near - PAST_NEAR) / 8.0, 0.5, 1.0))
    straight = float(np.clip((200.0 - swept) / 40.0, 0.3, 1.0))  # more than a half-turn is circling
    score = float(crossing * nearness * straight)
    ok = before >= PAST_MARGIN and beyond >= PAST_MARGIN and near <= PAST_NEAR and swept <= PAST_MAX_TURN_DEG
    why = (f"started {before:.2f} blocks before and ended {beyond:.2f} beyond the anchor, "
           f"closest {near:.2f} blocks, turned {swept:.0f} deg around it")
    return Verdict(ok, score, why)


def _around(rel: np.ndarray, d: np.ndarray, *_: object, **__: object) -> Verdict:
    turns = abs(swept_angle(rel)) / (2 * math.pi)
    far = float(d.max())
    score = float(np.clip(turns, 0, 1)) * (1.0 if far <= AROUND_NEAR else 0.5)
    ok = turns >= AROUND_TURNS and far <= AROUND_NEAR
    return Verdict(ok, score, f"swept {turns:.2f} of a turn around the anchor, at most {far:.2f} blocks away")


def _between(rel: np.ndarray, d: np.ndarray, mover: np.ndarray, anchor: np.ndarray, size: float, *,
             anchors: list[np.ndarray] | None = None, **_: object) -> Verdict:
    if anchors is None or len(anchors) != 2:
        raise ValueError('the rule "between" needs the two reference objects (anchors=[B, C])')
    m = np.r_[mover[-1, :2] / size, mover[-1, 2]]
    b, c = (np.asarray(a, float).reshape(-1, 3)[-1] for a in anchors)
    b, c = np.r_[b[:2] / size, b[2]], np.r_[c[:2] / size, c[2]]
    e = c[:2] - b[:2]
    sep = max(float(np.linalg.norm(e)), 1e-9)
    t = float((m[:2] - b[:2]) @ e) / sep**2
    w = m[:2] - b[:2]
    off = abs(float(e[0] * w[1] - e[1] * w[0])) / sep
    gaps = (square_gap(m, b), square_gap(m, c))
    touching = min(gaps) <= 0.0
    seg = float(np.linalg.norm(m[:2] - (b[:2] + np.clip(t, 0, 1) * e)))
    score = float(np.clip(1.0 - seg / 2.0, 0, 1)) * (0.5 if touching else 1.0)
    ok = 0.0 < t < 1.0 and off <= 0.5 and not touching
    why = (f"ends {t:.0%} of the way from the first anchor to the second, {off:.2f} blocks off the line "
           f"between them, gaps {gaps[0]:.2f} and {gaps[1]:.2f} blocks" + (" (touching)" if touching else ""))
    return Verdict(ok, score, why)


SIDES: dict[str, tuple[float, float, str]] = {
    "left-of": (1.0, 0.0, "left of"), "right-of": (-1.0, 0.0, "right of"),
    "in-front-of": (0.0, -1.0, "in front of"), "behind": (0.0, 1.0, "behind"),
}
"""Viewer-frame rules: the direction (lateral, depth) of the side, in the viewer's frame, and its words."""


def _side(name: str) -> Callable[..., Verdict]:
    """The viewer-frame rule for one side of the anchor (see the module docstring)."""
    lat_dir, dep_dir, words = SIDES[name]

    def rule(rel: np.ndarray, d: np.ndarray, mover: np.ndarray, anchor: np.ndarray, size: float, *,
             viewer: np.ndarray | None = None, **_: object) -> Verdict:
        v = np.asarray(VIEWPOINTS["robot"] if viewer is None else viewer, float)
        lat, dep = viewer_offset(mover[-1, :2] / size, anchor[-1, :2] / size, v[:2] / size)
        r = max(float(np.hypot(lat, dep)), 1e-9)
        along = (lat * lat_dir + dep * dep_dir) / r  # cosine of the angle from the side's direction
        overlap = _overlaps(np.r_[rel[-1], mover[-1, 2]], np.r_[0.0, 0.0, anchor[-1, 2]])
        score = float(np.clip(along, 0, 1)) * (1.0 if r <= NEAR else 0.5) * (0.0 if overlap else 1.0)
        ok = along >= math.cos(math.radians(45)) - 1e-9 and r <= NEAR and not overlap
        why = (f"ends {math.degrees(math.acos(float(np.clip(along, -1, 1)))):.0f} deg from straight {words} the "
               f"anchor as the viewer sees it ({lat:+.2f} blocks to its left, {dep:+.2f} behind), "
               f"{r:.2f} blocks away" + (" (overlapping it)" if overlap else ""))
        return Verdict(ok, score, why)

    return rule


RULES: dict[str, Callable[..., Verdict]] = {
    "closer": _closer, "away": _away, "next-to": _next_to, "past": _past, "around": _around,
    "between": _between, **{name: _side(name) for name in SIDES},
}
"""Rule sets by name; a bundle's manifest picks one with ``[judge] rules = "<name>"``."""

TWO_ANCHOR_RULES = ("between",)
"""Rule sets that read two reference objects (``anchors=``)."""


def rule_verdict(action: str, mover: np.ndarray, anchor: np.ndarray, size: float, *,
                 anchors: list[np.ndarray] | None = None, viewer: np.ndarray | None = None) -> Verdict:
    """Judge a motion by the rules named ``action``: ``mover`` (T,3) and ``anchor`` (T,3) or (3,) poses in
    metres, blocks of side ``size``; ``anchors`` every reference object of a two-anchor rule, ``viewer``
    the viewpoint (2,) of a viewer-frame rule (default: the robot's base, scene frame).

    Frames must be dense enough that the mover turns less than half a turn around the anchor between
    two of them (``planning.world2d.interpolate`` gives that).
    """
    if action in RULES:
        name = action
    else:
        try:
            name = canonical_action(action)
        except UnknownActionError:
            raise UnknownActionError(action, RULES, "(no rule judge has that name)") from None
    mover = np.asarray(mover, float).reshape(-1, 3)
    anchor_arr = np.asarray(anchor, float).reshape(-1, 3)
    if len(anchor_arr) == 1:
        anchor_arr = np.repeat(anchor_arr, len(mover), axis=0)
    rel, d = _relative(mover, anchor_arr, size)
    context = {k: v for k, v in (("anchors", anchors), ("viewer", viewer)) if v is not None}
    return RULES[name](rel, d, mover, anchor_arr, size, **context)


class RuleJudge:
    """The :class:`~l2p_bullet.judge.base.Judge` over one of :data:`RULES` (the progress model is not asked)."""

    name = "rules"

    def __init__(self, rules: str):
        if rules not in RULES:
            raise UnknownActionError(rules, RULES, "(no rule judge has that name)")
        self.rules = rules

    def judge(self, mover: np.ndarray, anchor: np.ndarray, size: float, *,
              final_progress: float | None = None, anchors: list[np.ndarray] | None = None,
              viewer: np.ndarray | None = None) -> Verdict:
        return rule_verdict(self.rules, mover, anchor, size, anchors=anchors, viewer=viewer)
