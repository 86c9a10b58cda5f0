"""Agreement with people: the graded 2-D demonstrations, and how well a judge or a model ranks them.

The original study's 90 generated 2-D demonstrations (15 per folder, ``data/sim``) were graded 0-10 by
two people who knew the action's name. They are evaluation data only, never trained on. Each becomes
one :class:`GradedMotion` (block 0 sliding along its accepted straight moves, block 1 still), in one
way for every consumer: the rule judges, the progress models, the review app's report.

Agreement is Spearman's rank correlation between a score (a judge's graded score, a model's final
progress) and the people's mean grade: ranks, because a judge or a model need not be calibrated to a
0-10 scale to order motions the way people do. Torch-free.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.vocabulary import ACTIONS, GRADED_FOLDERS
from ..data.demos import load_demos, load_graded_demos
from ..judge.rules import rule_verdict
from ..planning.world2d import interpolate

STEP_BLOCKS = 0.25
"""Frames of a graded motion are this many block sides apart along each move (the models' grid)."""


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


@dataclass
class GradedMotion:
    """One graded demonstration as a motion: ``mover`` (T,3) and ``anchor`` (T,3) in the study's metres."""

    id: str
    folder: str
    action: str
    mover: np.ndarray
    anchor: np.ndarray
    grade: float  # mean of the people's grades (0-10)
    size: float
    grades: dict[str, float]  # grader -> grade


def graded_motion(demo: dict, step_blocks: float = STEP_BLOCKS) -> GradedMotion:
    """A graded demonstration (one line of ``human_eval_2d_demos.jsonl``) as a :class:`GradedMotion`."""
    c0, c1 = demo["start_config"][0], demo["start_config"][1]
    size = float(c0["side"])
    way = [[c0["x"], c0["y"], c0["theta"]]]
    way += [s["to"] for s in demo["steps"] if s["accepted"] and s.get("object_index", 0) == 0]
    mover = interpolate(np.asarray(way, float), step=step_blocks * size)
    anchor = np.repeat(np.array([[c1["x"], c1["y"], c1["theta"]]]), len(mover), axis=0)
    grades = {k: float(v) for k, v in demo["scores_txt"].items()}
    return GradedMotion(demo["id"], demo["folder"], GRADED_FOLDERS[demo["folder"]], mover, anchor,
                        float(np.mean(list(grades.values()))), size, grades)


def graded_motions() -> list[GradedMotion]:
    """All 90 graded demonstrations, in the file's order (folder, then index)."""
    return [graded_motion(d) for d in load_graded_demos()]


def model_agreement(models: dict[str, Any], motions: list[GradedMotion] | None = None) -> dict[str, dict]:
    """Spearman(final progress, mean grade) per graded folder, with the finals and grades for the tables.

    ``models`` maps action -> anything with the scoring API's ``final_batch`` (numpy or torch).
    """
    motions = motions if motions is not None else graded_motions()
    out = {}
    for folder in GRADED_FOLDERS:
        ms = [m for m in motions if m.folder == folder]
        finals = models[GRADED_FOLDERS[folder]].final_batch([m.mover for m in ms], [m.anchor for m in ms], ms[0].size)
        grades = np.array([m.grade for m in ms])
        out[folder] = {"spearman": spearman(finals, grades), "finals": finals, "grades": grades}
    return out


def rule_agreement(motions: list[GradedMotion] | None = None) -> dict[str, float]:
    """Spearman(rule judge's score, mean grade) per action and pooled over all 90 ("all").

    "SlideAroundDiscrete" counts as around; pooled ranks are taken within the whole set.
    """
    motions = motions if motions is not None else graded_motions()
    rows: dict[str, tuple[list[float], list[float]]] = {}
    for m in motions:
        score = rule_verdict(m.action, m.mover, m.anchor, m.size).score
        for key in (m.action, "all"):
            rows.setdefault(key, ([], []))
            rows[key][0].append(score)
            rows[key][1].append(m.grade)
    return {k: spearman(np.array(s), np.array(g)) for k, (s, g) in rows.items()}


def demo_acceptance() -> dict[str, float]:
    """Share of the people's motion-capture demonstrations (the training data) each rule judge accepts."""
    return {a: float(np.mean([rule_verdict(a, d.event_mover, d.event_anchor, d.size).success for d in load_demos(a)]))
            for a in ACTIONS}
