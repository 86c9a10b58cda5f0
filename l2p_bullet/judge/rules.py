"""The project's own rule-based judge of a motion: did the mover do what the action says?

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

"Steadily" allows wobbles of half a block against the running best. Every rule also gives a graded
``score`` in [0, 1] (used for the correlation with people's grades; ``success`` is the yes/no verdict).
Motions are read in the anchor's frame (mover minus anchor), so a moving anchor is handled too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..learning.demos import canonical_action

WOBBLE = 0.5
"""Blocks a 'steady' change may go back against its running best (motion-capture jitter in the human
demonstrations reaches this: at 0.3 the rule rejected 37 % of people's "closer" demonstrations)."""


@dataclass(frozen=True)
class Verdict:
    """The judge's answer: yes/no, a graded score in [0, 1] and the reason in words."""

    success: bool
    score: float
    reason: str


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
    from ..core.geometry import polygons_overlap

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


def turn(rel: np.ndarray) -> float:
    """Signed angle (radians) swept by ``rel`` (T,2) around the origin, summed frame to frame."""
    ang = np.arctan2(rel[:, 1], rel[:, 0])
    return float(np.sum(np.angle(np.exp(1j * np.diff(ang))))) if len(ang) > 1 else 0.0


def _closer(rel: np.ndarray, d: np.ndarray, *_: object) -> Verdict:
    room = max(float(d[0]) - 1.0, 0.25)
    moved = float(d[0]) - float(d[-1])
    closed = moved / room
    rise = float(np.max(d - np.minimum.accumulate(d)))
    # people also reward how far it came, not only the share of the room ("right, but too short")
    score = float(np.clip(closed, 0, 1) * np.clip(moved / 2.0, 0, 1)) * (1.0 if rise <= WOBBLE else 0.5)
    ok = closed >= 0.5 and rise <= WOBBLE
    why = f"closed {closed:.0%} of the gap (start {d[0]:.2f}, end {d[-1]:.2f} blocks), went back {rise:.2f} blocks"
    return Verdict(ok, score, why)


def _away(rel: np.ndarray, d: np.ndarray, *_: object) -> Verdict:
    gained = float(d[-1]) - float(d[0])
    drop = float(np.max(np.maximum.accumulate(d) - d))
    score = float(np.clip((gained - drop) / 6.0, 0, 1))
    ok = gained >= 1.0 and drop <= WOBBLE
    return Verdict(ok, score, f"distance grew by {gained:.2f} blocks (start {d[0]:.2f}), went back {drop:.2f} blocks")


def _next_to(rel: np.ndarray, d: np.ndarray, mover: np.ndarray, anchor: np.ndarray, size: float) -> Verdict:
    m = np.r_[rel[-1], mover[-1, 2]]
    a = np.r_[0.0, 0.0, anchor[-1, 2]]
    gap = square_gap(m, a)
    overlap = gap == 0.0 and _overlaps(m, a)
    score = 0.0 if overlap else float(1.0 - min(gap, 3.0) / 3.0)
    ok = gap <= 0.5 and not overlap
    return Verdict(ok, score, f"ends {gap:.2f} blocks from the anchor" + (" (overlapping it)" if overlap else ""))


def _overlaps(a: np.ndarray, b: np.ndarray) -> bool:
    from ..core.geometry import polygons_overlap

    return polygons_overlap(_unit_square(a), _unit_square(b), margin=-0.02)


def _past(rel: np.ndarray, d: np.ndarray, *_: object) -> Verdict:
    travel = rel[-1] - rel[0]
    length = float(np.linalg.norm(travel))
    if length < 1e-9:
        return Verdict(False, 0.0, "did not move")
    u = travel / length
    before, beyond = -float(rel[0] @ u), float(rel[-1] @ u)
    near = float(d.min())
    swept = math.degrees(abs(turn(rel)))
    crossing = min(np.clip(before / 0.5, 0, 1), np.clip(beyond / 0.5, 0, 1))
    nearness = float(np.clip(1.0 - (near - 4.0) / 8.0, 0.5, 1.0))
    straight = float(np.clip((200.0 - swept) / 40.0, 0.3, 1.0))  # more than a half-turn is circling
    score = float(crossing * nearness * straight)
    ok = before >= 0.5 and beyond >= 0.5 and near <= 4.0 and swept <= 180.0
    why = (f"started {before:.2f} blocks before and ended {beyond:.2f} beyond the anchor, "
           f"closest {near:.2f} blocks, turned {swept:.0f} deg around it")
    return Verdict(ok, score, why)


def _around(rel: np.ndarray, d: np.ndarray, *_: object) -> Verdict:
    turns = abs(turn(rel)) / (2 * math.pi)
    far = float(d.max())
    score = float(np.clip(turns, 0, 1)) * (1.0 if far <= 4.0 else 0.5)
    ok = turns >= 0.8 and far <= 4.0
    return Verdict(ok, score, f"swept {turns:.2f} of a turn around the anchor, at most {far:.2f} blocks away")


_RULES = {"closer": _closer, "away": _away, "next-to": _next_to, "past": _past, "around": _around}


def evaluate(action: str, mover: np.ndarray, anchor: np.ndarray, size: float) -> Verdict:
    """Judge a motion: ``mover`` (T,3) and ``anchor`` (T,3) or (3,) poses in metres, blocks of side ``size``.

    Frames must be dense enough that the mover turns less than half a turn around the anchor between
    two of them (``sim2d.interpolate`` gives that).
    """
    name = canonical_action(action)
    mover = np.asarray(mover, float).reshape(-1, 3)
    anchor_arr = np.asarray(anchor, float).reshape(-1, 3)
    if len(anchor_arr) == 1:
        anchor_arr = np.repeat(anchor_arr, len(mover), axis=0)
    rel, d = _relative(mover, anchor_arr, size)
    return _RULES[name](rel, d, mover, anchor_arr, size)


# --- agreement with people ---------------------------------------------------------------------
def spearman(a: np.ndarray, b: np.ndarray) -> float:
    """Spearman's rank correlation (ties get their average rank); nan when either side is constant."""

    def ranks(x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, float)
        order = np.argsort(x, kind="mergesort")
        r = np.empty(len(x))
        r[order] = np.arange(len(x), dtype=float)
        for v in np.unique(x):  # average the ranks of ties
            r[x == v] = r[x == v].mean()
        return r

    ra, rb = ranks(a), ranks(b)
    if ra.std() == 0 or rb.std() == 0:
        return float("nan")
    return float(np.corrcoef(ra, rb)[0, 1])


def graded_motion(demo: dict, step_blocks: float = 0.25) -> tuple[np.ndarray, np.ndarray, float]:
    """A graded 2-D demonstration as (mover frames, anchor pose, size): its accepted straight moves, dense."""
    from ..planning.world2d import interpolate

    start, anchor = demo["start_config"][0], demo["start_config"][1]
    size = float(start["side"])
    way = [[start["x"], start["y"], start["theta"]]]
    way += [s["to"] for s in demo["steps"] if s["accepted"] and s.get("object_index", 0) == 0]
    frames = interpolate(np.asarray(way, float), step=step_blocks * size)
    return frames, np.array([anchor["x"], anchor["y"], anchor["theta"]]), size


def demo_acceptance() -> dict[str, float]:
    """Share of the people's motion-capture demonstrations (the training data) each rule accepts."""
    from ..learning.demos import ACTIONS, load_demos

    return {a: float(np.mean([evaluate(a, d.event_mover, d.event_anchor, d.size).success for d in load_demos(a)]))
            for a in ACTIONS}


def graded_agreement() -> dict[str, float]:
    """Spearman correlation of the rule score with the people's mean grade, per action and pooled.

    Uses the 90 graded demonstrations shipped in ``data/sim`` (15 per folder; "SlideAroundDiscrete" is
    around too). Pooled = over all 90, ranks taken within the whole set.
    """
    from ..learning.demos import load_graded_demos

    rows: dict[str, tuple[list[float], list[float]]] = {}
    for demo in load_graded_demos():
        action = canonical_action(demo["action"])
        mover, anchor, size = graded_motion(demo)
        v = evaluate(action, mover, anchor, size)
        grade = float(np.mean(list(demo["scores_txt"].values())))
        for key in (action, "all"):
            rows.setdefault(key, ([], []))
            rows[key][0].append(v.score)
            rows[key][1].append(grade)
    return {k: spearman(np.array(s), np.array(g)) for k, (s, g) in rows.items()}
