"""Ordered probes: variants of each held-out event whose order is fixed by a rule, not by a grade.

The grade-free suite (``research/generalise.py``) holds complete, good demonstrations, and
the shipped recipe passes most of it while agreeing with people at 0.02 (away) and 0.17 (next-to) on
the study's graded motions nobody chose a setting on (issue 25). Those graded motions are planner
output that went too short, too far, or undid part of the action. This module makes such motions from
every held-out event, by known amounts, and says in which order any model must score them. Each order
follows from what the action means (:data:`CHAINS` says why for each); none was read off a grade.

Every variant is a few straight moves (a planner's motion) and is scored twice: as those straight
moves, and with its waypoints snapped to the discrete planner's rings (:func:`generalise.ring_cells`).
The study's square grid is left out: its cells are 2.4 blocks apart and none is beside the anchor,
coarser than the distances the probes differ by. A chain ``[a, b, c]`` is ordered for an event when
``a`` scores below ``b`` and ``b`` below ``c``, each by at least :data:`MARGIN`; pairs that snap to the
same motion are not counted.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from . import generalise as g

MARGIN = 0.05
"""How much lower the lesser variant of a pair must score (final progress)."""

SHORT = (0.3, 0.6)
"""The shortened variants stop at these fractions of the event's arc length."""

ARCS = (90, 180, 270, 360)
"""around's arcs, in degrees round the anchor."""

STRAYS = tuple(reversed(g.DISTANCES[-2:]))
"""Where around's "strays" chain puts its middle corner, in blocks from the anchor: the discrete planner's
two outer rings (``planning.proposals.DISTANCES``); the rule judge's ``near`` is 4."""

CHAINS: dict[str, dict[str, str]] = {
    "closer": {
        "shortened": "stopped at 30 % / 60 % of its path / whole: the block ends less near than it could, "
                     "so less of 'closer' was done",
        "undone": "goes to its end then all the way / half way back to its start distance / stays: closer "
                  "is judged by where the block ends, and coming back undoes the approach",
    },
    "away": {
        "shortened": "stopped at 30 % / 60 % / whole: the block ends less far away",
        "undone": "goes out to its end then all the way / half way back to its start / stays: away is "
                  "judged by where the block ends, and coming back undoes it",
    },
    "next-to": {
        "shortened": "stopped at 30 % / 60 % / whole: a block stopped on the way ends apart from the anchor",
        "overshot": "goes on from its end 4 / 2 / 0 blocks straight out from the anchor: next-to means "
                    "ending beside the anchor, and a block that overshoots its place there ends apart from it",
    },
    "past": {
        "shortened": "stopped at 30 % / 60 % / whole: a pass stopped early has not gone by the anchor",
        "undone": "goes to its end then back to its start / stays: a block brought back to where it began "
                  "has not ended past anything",
    },
    "around": {
        "shortened": "stopped at 30 % / 60 % / whole: less of the way round",
        "arcs": "arcs of 90 / 180 / 270 / 360 degrees at the event's start distance, in its direction: "
                "around means a circle, and a partial arc is a partial circle; the more of it, the more "
                "of the action",
        "strays": "its own path through 5 poses with the middle one pushed straight out to 6.5 / 5 blocks "
                  "from the anchor (the planner's two outer rings) / as it is: around means going round near "
                  "the anchor, and a corner out on a far ring is a detour away from it, the farther the "
                  "less of an around",
    },
}
"""Action -> chain name -> the chain, lowest first, and why people would grade it in that order."""


def _rot(v: np.ndarray, a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def chains(e: g.Event) -> dict[str, list[np.ndarray]]:
    """The event's chains (:data:`CHAINS`) as waypoint arrays (n, 3), lowest first."""
    m, c, size = e.mover, e.anchor, e.size
    p0, p1 = m[0], m[-1]
    whole = g.waypoints(m, 3)
    out = {"shortened": [g.waypoints(g.cut(m, f), 3) for f in SHORT] + [whole]}
    if e.action in ("closer", "away"):
        half = p1 + 0.5 * (p0 - p1)
        out["undone"] = [np.vstack([whole, p0]), np.vstack([whole, half]), whole]
    elif e.action == "past":
        out["undone"] = [np.vstack([whole, p0]), whole]
    elif e.action == "next-to":
        u = (p1 - c)[:2] / max(float(np.linalg.norm((p1 - c)[:2])), 1e-9)
        over = []
        for k in (4.0, 2.0):
            q = p1.copy()
            q[:2] = p1[:2] + u * k * size
            over.append(np.vstack([whole, q]))
        out["overshot"] = over + [whole]
    elif e.action == "around":
        d0 = p0[:2] - c[:2]
        sign = 1.0 if g.swept_angle(m, c) >= 0 else -1.0
        arcs = []
        for deg in ARCS:
            steps = deg // 45
            pts = [p0.copy() for _ in range(steps + 1)]
            for i, p in enumerate(pts):
                p[:2] = c[:2] + _rot(d0, sign * np.deg2rad(45 * i))
            arcs.append(np.array(pts))
        out["arcs"] = arcs
        way = g.waypoints(m, 4)
        out["strays"] = [g.pushed_out(way, 2, c, far, size) for far in STRAYS] + [way]
    return out


def _as_domain(way: np.ndarray, e: g.Event, kind: str) -> np.ndarray:
    if kind == "rings":
        way = g._snap(way, g.ring_cells(e.anchor, e.size))
    return g.straight_moves(way, 0.25 * e.size)


DOMAINS = ("straight", "rings")


def ordered(model, evs: list[g.Event], finals: Callable | None = None) -> dict[str, float]:
    """Share of pairs in order, per chain of the events' action (both domains pooled), and ``all``
    (the mean over the chains).

    ``finals(model, motions, events)`` scores motions; by default :func:`generalise._finals`.
    """
    finals = finals or g._finals
    if not evs:
        return {}
    per = [chains(e) for e in evs]
    hits: dict[str, list[bool]] = {}
    for name in per[0]:
        for kind in DOMAINS:
            motions = [[_as_domain(w, e, kind) for w in ch[name]] for e, ch in zip(evs, per, strict=True)]
            n = len(motions[0])
            scores = np.stack([finals(model, [ms[j] for ms in motions], evs) for j in range(n)], axis=1)
            for ms, sc in zip(motions, scores, strict=True):
                for j in range(n - 1):
                    a, b = ms[j], ms[j + 1]
                    if a.shape == b.shape and np.allclose(a, b):
                        continue
                    hits.setdefault(name, []).append(bool(sc[j] < sc[j + 1] - MARGIN))
    out = {k: float(np.mean(v)) for k, v in hits.items()}
    out["all"] = float(np.mean(list(out.values())))  # each chain counts the same, however many pairs
    return out
