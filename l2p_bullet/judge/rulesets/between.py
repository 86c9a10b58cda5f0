"""The two-anchor rule "between" (plugins pick it: ``[judge] rules = "between"``): the mover ends on the
segment between the two anchors (its centre projects strictly between theirs and lies within half a block of
the line through them) without touching either. The gaps are between the objects' real outlines where one is
not a cube, unit squares where all three are (``footprints.py``)."""

from __future__ import annotations

import numpy as np

from ..base import Verdict
from ..footprints import gap as footprint_gap


def between(rel: np.ndarray, d: np.ndarray, mover: np.ndarray, anchor: np.ndarray, size: float, *,
            anchors: list[np.ndarray] | None = None, outlines: list[np.ndarray] | None = None,
            **_: object) -> Verdict:
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
    pairs = (None, None) if outlines is None else ((outlines[0], outlines[1]), (outlines[0], outlines[2]))
    gaps = (footprint_gap(m, b, size, pairs[0]), footprint_gap(m, c, size, pairs[1]))
    touching = min(gaps) <= 0.0
    seg = float(np.linalg.norm(m[:2] - (b[:2] + np.clip(t, 0, 1) * e)))
    score = float(np.clip(1.0 - seg / 2.0, 0, 1)) * (0.5 if touching else 1.0)
    ok = 0.0 < t < 1.0 and off <= 0.5 and not touching
    why = (f"ends {t:.0%} of the way from the first anchor to the second, {off:.2f} blocks off the line "
           f"between them, gaps {gaps[0]:.2f} and {gaps[1]:.2f} blocks" + (" (touching)" if touching else ""))
    return Verdict(ok, score, why)


RULES = {"between": between}
TWO_ANCHOR = ("between",)
"""Rule sets of this module that read two reference objects (``anchors=``)."""
