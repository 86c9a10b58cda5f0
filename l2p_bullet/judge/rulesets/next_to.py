"""The rule of "next to": the mover ends adjacent: the gap between the two footprints is at most ``gap``
blocks, and they do not overlap. The footprints are the objects' real outlines where one is not a cube (a 2:1
box's long face, a carton's side), unit squares where both are (``footprints.py``)."""

from __future__ import annotations

import numpy as np

from ...actions.next_to import ACTION
from ..base import Verdict
from ..footprints import gap as footprint_gap
from ..footprints import overlap as footprint_overlap

NEXT_TO_GAP = ACTION.thresholds["gap"]
"""Largest gap (blocks) between the footprints at the end of "next to"."""


def next_to(rel: np.ndarray, d: np.ndarray, mover: np.ndarray, anchor: np.ndarray, size: float,
            *, outlines: list[np.ndarray] | None = None, **_: object) -> Verdict:
    m = np.r_[rel[-1], mover[-1, 2]]
    a = np.r_[0.0, 0.0, anchor[-1, 2]]
    gap = footprint_gap(m, a, size, outlines)
    overlap = gap == 0.0 and footprint_overlap(m, a, size, outlines)
    score = 0.0 if overlap else float(1.0 - min(gap, 3.0) / 3.0)
    ok = gap <= NEXT_TO_GAP and not overlap
    return Verdict(ok, score, f"ends {gap:.2f} blocks from the anchor" + (" (overlapping it)" if overlap else ""))


RULES = {ACTION.rules: next_to}
