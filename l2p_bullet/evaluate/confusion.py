"""The automatic confusion matrices (the paper's question 2, "can the actions be told apart?", without people).

Every run's executed trajectory was judged by every installed action's judge and scored by every
installed progress model (``judged`` and ``scored`` in the results table). Rows are the action that was
asked for, columns the action it is recognised as:

- judge-based: the share of runs asked as *row* that *column*'s judge accepts. Rows need not sum to
  one: a good "next to" can also be "closer" (they are partly each other), and that is the finding;
- model-based: the mean final learned progress of *column*'s model on runs asked as *row*; and the
  share of runs each model scores highest (``argmax``), a classic confusion matrix whose rows sum to one.

Runs that ended in an error have no trajectory and are left out (their number is reported).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.vocabulary import ACTIONS

TOUCHING_BLOCKS = 0.2
"""Final gap (block sizes) at or under which two blocks read as touching: 1 cm between 5 cm blocks, twice
the planner's clearance (``GRIPPER_MARGIN``)."""


@dataclass
class Confusion:
    """``asked`` (rows) x ``recognised`` (columns); ``counts`` runs per row (errors excluded)."""

    asked: list[str]
    recognised: list[str]
    judges: np.ndarray  # share accepted
    models: np.ndarray  # mean final progress
    argmax: np.ndarray  # share of runs where the column's model scores highest
    counts: np.ndarray
    errors: np.ndarray

    def to_dict(self) -> dict:
        return {"asked": self.asked, "recognised": self.recognised, "counts": self.counts.tolist(),
                "errors": self.errors.tolist(), "judges": _cells(self.judges),
                "models": _cells(self.models), "argmax": _cells(self.argmax)}


def _cells(m: np.ndarray) -> list[list[float | None]]:
    """A matrix for JSON: rounded, and None (null) for a cell no run informs."""
    return [[None if np.isnan(v) else round(float(v), 4) for v in row] for row in m]


def confusion(rows: list[dict], order: list[str] | None = None) -> Confusion:
    """The matrices from the results table's rows (see the module docstring).

    A cell no run informs is NaN, not 0: a row whose runs all ended in an error, or a column whose action
    could not judge that row's runs (a two-anchor action on one-anchor runs). Reports leave it blank.
    """
    asked = _ordered({r["action"] for r in rows}, order)
    recognised = _ordered({k for r in rows for k in (r.get("judged") or {})}, order)
    n, m = len(asked), len(recognised)
    judges, models, argmax = np.zeros((n, m)), np.zeros((n, m)), np.zeros((n, m))
    judged_n, scored_n = np.zeros((n, m), int), np.zeros((n, m), int)
    counts, errors = np.zeros(n, int), np.zeros(n, int)
    for r in rows:
        i = asked.index(r["action"])
        if r.get("error") is not None or not r.get("judged"):
            errors[i] += 1
            continue
        counts[i] += 1
        scores = np.array([float((r.get("scored") or {}).get(a, np.nan)) for a in recognised])
        for j, a in enumerate(recognised):
            if a in r["judged"]:
                judged_n[i, j] += 1
                judges[i, j] += bool(r["judged"][a].get("success"))
            if not np.isnan(scores[j]):
                scored_n[i, j] += 1
                models[i, j] += scores[j]
        if np.isfinite(scores).any():
            argmax[i, int(np.nanargmax(scores))] += 1
    with np.errstate(invalid="ignore", divide="ignore"):
        return Confusion(asked, recognised, np.where(judged_n > 0, judges / np.maximum(judged_n, 1), np.nan),
                         np.where(scored_n > 0, models / np.maximum(scored_n, 1), np.nan),
                         np.where(scored_n > 0, argmax / np.maximum(counts, 1)[:, None], np.nan), counts, errors)


def _ordered(names: set[str], order: list[str] | None) -> list[str]:
    first = [a for a in (order or list(ACTIONS)) if a in names]
    return first + sorted(names - set(first))


def touching_finding(rows: list[dict], asked: str, also: str) -> dict:
    """How many ``asked`` runs end touching the anchor and how many ``also``'s judge accepts (the actions that
    declare such a finding: ``ActionSpec.touching``).

    People graded a "closer" that ends with the blocks touching as wrong ("the blocks touched"), while
    our closer judge accepts it and the next-to judge reads it as "next to".
    """
    ok = [r for r in rows if r["action"] == asked and r.get("error") is None and r.get("judged")]
    gaps = np.array([r["final_gap_blocks"] for r in ok if r.get("final_gap_blocks") is not None], float)
    touching = [r for r in ok if r.get("final_gap_blocks") is not None and r["final_gap_blocks"] <= TOUCHING_BLOCKS]
    both = [r for r in ok if r.get("success") and r["judged"].get(also, {}).get("success")]
    return {
        "action": asked, "also": also, "runs": len(ok),
        "touching": len(touching), "touching_share": len(touching) / len(ok) if ok else float("nan"),
        "read_as_also": sum(bool(r["judged"].get(also, {}).get("success")) for r in ok),
        "success_and_also": len(both),
        "median_gap_blocks": float(np.median(gaps)) if len(gaps) else float("nan"),
        "threshold_blocks": TOUCHING_BLOCKS,
        "share_within": {str(t): float((gaps <= t).mean()) if len(gaps) else float("nan") for t in (0.2, 0.3, 0.5)},
    }
