"""The evaluation's statistics, as the 2018 study computed them (numpy only).

- mean grade: over every grade of every demo of an action (the study: the mean of the two graders' means,
  the same number when both graded every demo);
- evaluator disparity (the paper's Table 1): per demo the absolute difference between its two graders'
  grades, averaged over the demos (the study's spreadsheet: ``AVERAGE(ABS(B - C))``). With more than
  two graders a demo contributes the mean absolute difference over its pairs of graders; a run shown
  in both views is two items (the disparity is between people, not between views);
- Fleiss' kappa over the blind labels (as ``notebooks/score_3d_scene.ipynb``): P_i the share of agreeing
  rater pairs on item i, p_j the share of all labels in category j,
  kappa = (mean P_i - sum p_j^2) / (1 - sum p_j^2). Items rated by fewer than two people carry no
  agreement and are left out; items may have different numbers of raters (P_i uses its own n_i, p_j
  all labels), which reduces to Fleiss' formula when every item has the same number;
- the confusion matrix: true action x given label, each row divided by its total.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from itertools import combinations

import numpy as np


def disparity(grades_per_item: Iterable[Sequence[float]]) -> float:
    """Mean over items (with at least two grades) of the mean absolute difference between graders."""
    per_item = [float(np.mean([abs(a - b) for a, b in combinations(g, 2)])) for g in grades_per_item if len(g) >= 2]
    return float(np.mean(per_item)) if per_item else float("nan")


def fleiss_kappa(counts: np.ndarray) -> dict:
    """Fleiss' kappa of ``counts`` (items x categories: how many raters put item i in category j).

    Returns ``{"kappa", "items", "raters_per_item" (mean), "p_bar", "p_e", "p_i"}``; kappa is nan
    when fewer than two items have two or more ratings, or when every label is the same category.
    """
    c = np.asarray(counts, float)
    if c.ndim != 2:
        raise ValueError("counts must be items x categories")
    n = c.sum(axis=1)
    c, n = c[n >= 2], n[n >= 2]
    if len(c) < 2:
        return {"kappa": float("nan"), "items": int(len(c)), "raters_per_item": float(n.mean()) if len(n) else 0.0,
                "p_bar": float("nan"), "p_e": float("nan"), "p_i": []}
    p_i = ((c ** 2).sum(axis=1) - n) / (n * (n - 1))
    p_j = c.sum(axis=0) / c.sum()
    p_bar, p_e = float(p_i.mean()), float((p_j ** 2).sum())
    kappa = float("nan") if p_e >= 1.0 else (p_bar - p_e) / (1.0 - p_e)
    return {"kappa": kappa, "items": int(len(c)), "raters_per_item": float(n.mean()), "p_bar": p_bar, "p_e": p_e,
            "p_i": p_i.tolist()}


def label_confusion(pairs: Iterable[tuple[str, str]], rows: Sequence[str], cols: Sequence[str]) -> dict:
    """Counts and row-normalised shares of (true, given) pairs; labels outside rows/cols are dropped."""
    m = np.zeros((len(rows), len(cols)))
    r_ix, c_ix = {r: i for i, r in enumerate(rows)}, {c: j for j, c in enumerate(cols)}
    for true, given in pairs:
        if true in r_ix and given in c_ix:
            m[r_ix[true], c_ix[given]] += 1
    totals = m.sum(axis=1, keepdims=True)
    share = np.divide(m, totals, out=np.full_like(m, np.nan), where=totals > 0)
    return {"rows": list(rows), "cols": list(cols), "counts": m.astype(int).tolist(), "shares": share.tolist()}
