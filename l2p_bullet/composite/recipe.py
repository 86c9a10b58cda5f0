"""A composite action's recipe, learned from demonstrations of whole rows (not written by hand).

A demonstration (recorded on the teach page, :class:`Demonstration`) is a scene of 2-3 blocks, the
blocks in the order the sentence names them ("make a row of A, B and C") and the drags the person made,
one :class:`Segment` per dragged block. Learning (:func:`learn`) does, per demonstration:

1. replays the segments in order and asks recognition (``recognition.py``) which installed
   action each one shows, of which block against which ("B moved next to A: 0.97");
2. fits a line to the blocks' final centres (the row's axis, total least squares).

What generalises across the demonstrations becomes the recipe (each a majority or a median, with the
share of demonstrations or segments that agree, so a reader sees how firm it is):

- ``action``: the single action every segment is performed with (the one recognised most often);
- ``anchor``: which block each new block moves relative to: ``previous`` (the block that joined the row
  just before it; the first mover's is the block that stays) or ``first`` (always the block that stays).
  2-block rows cannot tell the two apart: only 3-block demonstrations vote;
- ``stays``: the position in the named list of the block that is not moved (the row grows from it);
- ``order``: ``named`` when the other blocks are moved in the order the sentence names them;
- ``spacing``: the median gap between neighbours along the axis, in block sides;
- ``monotone``: each new block lands beyond the previous one (the row grows at one end, never between);
- ``axis_offset_deg``: the axis' angle to the staying block's faces (median, folded into [-45, 45));
- ``aligned``: moved blocks end turned like the staying block (within ``ALIGNED_DEG``, median).

Assumed, not learned: that a composite of this kind is a row (a straight line is fitted; curves would
need another fit), that the table has room for it, and that the axis' direction among the staying
block's faces may be chosen freely at perform time (the demonstrations point every which way).
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from ..core.scene import Scene
from ..data.tracking import page_track
from ..errors import L2PError
from ..recognition import Tracks, recognize

ALIGNED_DEG = 10.0
"""Median turn between a moved block and the staying block (mod 90 degrees) below which rows are aligned."""

FPS = 30.0
"""Frames per second the drags are resampled to before recognition (the captures' rate)."""

MAX_DEMOS = 50
MAX_SEGMENTS = 8


class CompositeError(L2PError):
    """A demonstration or a recipe that cannot be used."""


@dataclass
class Segment:
    """One drag: ``block`` and its samples ``[t, x, y, yaw]`` (seconds, metres, radians; scene frame)."""

    block: str
    samples: list[list[float]]

    def track(self) -> np.ndarray:
        """The drag resampled to :data:`FPS` as poses (n, 3), yaw unwrapped, ending where the drag left
        the block (:func:`~l2p_bullet.data.tracking.page_track`)."""
        return page_track(np.asarray(self.samples, float), FPS)


@dataclass
class Demonstration:
    """A whole composite shown once: the scene (``Scene.to_dict``), the named order, the drags."""

    scene: dict[str, Any]
    names: list[str]
    segments: list[Segment]
    seed: int | None = None

    @classmethod
    def from_dict(cls, d: dict) -> Demonstration:
        try:
            segs = [Segment(str(s["block"]), [[float(v) for v in row] for row in s["samples"]]) for s in d["segments"]]
            demo = cls(dict(d["scene"]), [str(n) for n in d["names"]], segs, d.get("seed"))
        except (KeyError, TypeError, ValueError) as e:
            raise CompositeError(f"not a composite demonstration ({type(e).__name__}: {e})") from None
        demo.check()
        return demo

    def to_dict(self) -> dict:
        return asdict(self)

    def check(self) -> None:
        """What :func:`learn` relies on: named blocks in the scene, drags of named blocks, 2 samples each."""
        scene = Scene.from_dict(self.scene)
        if not 2 <= len(self.names) <= MAX_SEGMENTS + 1 or len(set(self.names)) != len(self.names):
            raise CompositeError(f"a demonstration names 2 to {MAX_SEGMENTS + 1} different blocks (got {self.names})")
        missing = [n for n in self.names if n not in scene.names]
        if missing:
            raise CompositeError(f"the demonstration names blocks not in its scene: {', '.join(missing)}")
        if not 1 <= len(self.segments) <= MAX_SEGMENTS:
            raise CompositeError(f"a demonstration has 1 to {MAX_SEGMENTS} drags (got {len(self.segments)})")
        for k, s in enumerate(self.segments, 1):
            a = np.asarray(s.samples, float)
            if s.block not in self.names:
                raise CompositeError(f"drag {k} moves block {s.block}, which the sentence does not name")
            if a.ndim != 2 or a.shape[1] != 4 or len(a) < 2 or not np.all(np.isfinite(a)):
                raise CompositeError(f"drag {k} needs at least two finite samples [t, x, y, yaw]")
            if np.any(np.diff(a[:, 0]) < 0):
                raise CompositeError(f"drag {k}: sample times must not decrease")


@dataclass
class Recipe:
    """What was learned (see the module docstring); ``evidence`` says how firmly, ``readings`` per segment."""

    action: str
    anchor: str  # "previous" | "first"
    stays: int
    order: str  # "named"
    spacing: float  # block sides
    monotone: bool
    axis_offset_deg: float
    aligned: bool
    demos: int
    evidence: dict[str, Any] = field(default_factory=dict)
    readings: list[dict[str, Any]] = field(default_factory=list)

    def to_dict(self) -> dict:
        return {"schema": 1, **asdict(self)}

    @classmethod
    def from_dict(cls, d: dict) -> Recipe:
        try:
            for key in ("monotone", "aligned"):  # bool("no") is True: a recipe says true or false
                if not isinstance(d[key], bool):
                    raise TypeError(f'"{key}" must be true or false (got {str(d[key])[:30]})')
            for key in ("stays", "demos"):
                if isinstance(d[key], bool) or not isinstance(d[key], int):
                    raise TypeError(f'"{key}" must be a whole number (got {str(d[key])[:30]})')
            for key in ("spacing", "axis_offset_deg"):
                if isinstance(d[key], bool) or not isinstance(d[key], int | float) or not math.isfinite(d[key]):
                    raise ValueError(f'"{key}" must be a finite number (got {str(d[key])[:30]})')
            r = cls(str(d["action"]), str(d["anchor"]), int(d["stays"]), str(d["order"]), float(d["spacing"]),
                    bool(d["monotone"]), float(d["axis_offset_deg"]), bool(d["aligned"]), int(d["demos"]),
                    dict(d.get("evidence", {})), list(d.get("readings", [])))
        except (KeyError, TypeError, ValueError) as e:
            raise CompositeError(f"not a composite recipe ({type(e).__name__}: {e})") from None
        if (r.anchor not in ("previous", "first") or r.order != "named" or not 0 <= r.spacing <= 5 or r.stays != 0
                or not -180 <= r.axis_offset_deg <= 180):
            raise CompositeError(f"a recipe this version cannot perform: anchor={r.anchor}, order={r.order}, "
                                 f"stays={r.stays}, spacing={r.spacing}, axis_offset_deg={r.axis_offset_deg}")
        return r


def fit_line(xy: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(centre, unit direction, perpendicular residuals) of the total-least-squares line through ``xy``."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    c = xy.mean(0)
    _, _, vt = np.linalg.svd(xy - c)
    u = vt[0]
    return c, u, (xy - c) @ np.array([-u[1], u[0]])


def row_gaps(xy: np.ndarray, sizes: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Along the fitted line of the centres ``xy`` (in their order): (gaps in sides between neighbours,
    |offsets| from the line in sides, along-axis coordinates). A gap is the distance between neighbours'
    centres along the axis less one side (cubes turned like the row: face to face)."""
    c, u, off = fit_line(xy)
    along = (np.asarray(xy, float) - c) @ u
    side = float(np.mean(sizes))
    order = np.argsort(along)
    gaps = (np.diff(along[order]) - side) / side
    return gaps, np.abs(off) / side, along


def _fold(deg: float) -> float:
    """An angle folded into [-45, 45) (the faces of a square repeat every 90 degrees)."""
    return (deg + 45.0) % 90.0 - 45.0


def learn(demos: list[Demonstration], recognisers: list) -> Recipe:
    """The recipe the demonstrations share (module docstring); ``recognisers`` from
    ``recognition.recognisers()`` (the installed single actions)."""
    if not demos:
        raise CompositeError("no demonstrations to learn from: record some rows on the teach page first")
    if len(demos) > MAX_DEMOS:
        raise CompositeError(f"at most {MAX_DEMOS} demonstrations (got {len(demos)})")
    readings: list[dict[str, Any]] = []
    relations = []  # (recognition, mover, previous block, first block) of every 3rd, 4th... drag
    votes: Counter[str] = Counter()
    anchor_votes: Counter[str] = Counter()
    stays: Counter[int] = Counter()
    named_order, monotone = 0, 0
    gaps_all: list[float] = []
    offsets, turns = [], []
    for d, demo in enumerate(demos):
        scene = Scene.from_dict(demo.scene)
        poses = {o.name: o.pose.copy() for o in scene.objects}
        sizes = {o.name: o.size for o in scene.objects}
        moved: list[str] = []
        for s in demo.segments:
            track = s.track()
            tracks = {n: (track if n == s.block else np.repeat(p[None], len(track), 0)) for n, p in poses.items()}
            rec = recognize(Tracks(tracks, sizes, f"demonstration {d + 1}"), recognisers)
            best = next((r for r in rec.readings if r.mover == s.block), rec.best)
            staying = [n for n in demo.names if n not in {x.block for x in demo.segments}]
            first = staying[0] if staying else None
            previous = moved[-1] if moved else first
            readings.append({"demo": d, **best.to_dict()})
            votes[best.action] += 1
            if previous != first and previous is not None:  # only a 3rd block tells the relations apart
                relations.append((rec, s.block, previous, first))
            poses[s.block] = track[-1]
            if s.block not in moved:
                moved.append(s.block)
        still = [i for i, n in enumerate(demo.names) if n not in moved]
        stays[still[0] if len(still) == 1 else -1] += 1
        named_order += int(moved == demo.names[1:])
        xy = np.array([poses[n][:2] for n in demo.names])
        gaps, _, along = row_gaps(xy, np.array([sizes[n] for n in demo.names]))
        gaps_all += gaps.tolist()
        monotone += int(np.all(np.diff(along) > 0) or np.all(np.diff(along) < 0))
        _, u, _ = fit_line(xy)
        base = poses[demo.names[0]]
        offsets.append(_fold(math.degrees(math.atan2(u[1], u[0]) - base[2])))
        turns += [abs(_fold(math.degrees(poses[n][2] - base[2]))) for n in moved]
    action, n_action = votes.most_common(1)[0]
    for rec, mover, previous, first in relations:  # under the learned action: relative to which block?
        finals = {r.anchors[0]: r.final for r in rec.readings if r.action == action and r.mover == mover}
        anchor_votes["previous" if finals.get(previous, 0) >= finals.get(first, 0) else "first"] += 1
    anchor = "previous" if anchor_votes["previous"] >= anchor_votes["first"] else "first"
    stay, n_stay = stays.most_common(1)[0]
    if stay != 0:
        raise CompositeError("in most demonstrations the first named block was not the one left in place "
                             f"(stayed: {dict(stays)}); this version grows rows from the first named block")
    n = len(demos)
    return Recipe(
        action=action,
        anchor=anchor,
        stays=stay,
        order="named" if named_order * 2 > n else "any",
        spacing=round(float(np.median(gaps_all)), 4),
        monotone=monotone * 2 > n,
        axis_offset_deg=round(float(np.median(offsets)), 2),
        aligned=bool(np.median(turns) < ALIGNED_DEG) if turns else True,
        demos=n,
        evidence={
            "segments": len(readings),
            "action_share": round(n_action / max(len(readings), 1), 4),
            "actions": dict(votes),
            "anchor_votes": dict(anchor_votes),
            "stays_share": round(n_stay / n, 4),
            "named_order_share": round(named_order / n, 4),
            "monotone_share": round(monotone / n, 4),
            "gaps_sides": [round(g, 4) for g in gaps_all],
            "axis_offsets_deg": [round(o, 2) for o in offsets],
            "turns_deg_median": round(float(np.median(turns)), 2) if turns else 0.0,
        },
        readings=readings,
    )
