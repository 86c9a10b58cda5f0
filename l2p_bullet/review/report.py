"""``l2p-bullet report``: the evaluation's tables from the grades (the paper's Table 1 and the 3-D study).

Question 1 (graded: the action's name was shown): per action, or per folder of the original study, the
mean grade and the evaluator disparity (stats.py), and how well the installed action's learned final
progress and its judge (``judge_for(bundle)``, the rules for the built-in actions) rank the runs like
people do (Spearman with each run's mean grade). Question 2 (blind): the confusion matrix of true action
x label, row-normalised, and Fleiss' kappa over the runs labelled by two or more people. Question 3:
runs graded both as the 3-D video and as the 2-D animation, side by side.

Only grades of a run's current trajectory count; grades whose run folder disappeared or whose
trajectory.json changed since (sha256) are listed as problems, never silently scored against another
motion. Torch-free: the models are the bundles' numpy ones.

The report's text, files and folder are written by ``report_files.py``; its names are re-exported here.
"""

from __future__ import annotations

import csv
import json
from collections import defaultdict
from pathlib import Path
from typing import Any

import numpy as np

from ..core.contracts import load_motion
from ..core.vocabulary import ACTIONS, GRADED_FOLDERS
from ..errors import L2PError, ReviewError
from ..judge import judge_context, judge_for
from ..learning.agreement import graded_motions, spearman
from ..plugins import registry
from ..plugins.bundle import sha256_file
from .report_files import REPORT_FILES, REPORT_KEYS, render_text, report_folder, write_grade_report
from .stats import disparity, fleiss_kappa, label_confusion
from .store import NONE_LABEL, GradeRow

__all__ = [  # the tables' own names, and what report_files.py writes them with, which callers read from here
    "MIN_SPEARMAN", "NEEDED_COLUMNS", "REPORT_FILES", "REPORT_KEYS", "SQLITE_SUFFIXES", "blind_table",
    "build_report", "graded_table", "problems", "read_report_grades", "render_text", "report_folder",
    "views_table", "write_grade_report",
]

MIN_SPEARMAN = 3
"""Runs a Spearman needs before it is reported (fewer: n/a)."""


def _order(actions) -> list[str]:
    actions = set(actions)
    return [a for a in ACTIONS if a in actions] + sorted(actions - set(ACTIONS) - {NONE_LABEL}) + (
        [NONE_LABEL] if NONE_LABEL in actions else [])


def _f(v) -> float | None:
    return None if v is None or not np.isfinite(v) else round(float(v), 4)


class _Motions:
    """Each graded run's motion (original demo or trajectory.json), and the scores of the installed models."""

    def __init__(self):
        self._graded = None
        self._bundles: dict[str, Any] = {}
        self.notes: list[str] = []

    def motion(self, row: GradeRow):
        if row.source == "original":
            if self._graded is None:
                self._graded = {m.id: m for m in graded_motions()}
            m = self._graded.get(row.demo_id or "")
            return None if m is None else (m.mover, m.anchor, m.size)

        try:
            m = load_motion(Path(row.run_path) / "trajectory.json")
        except L2PError:
            return None
        if not m.more_anchors and m.viewer is None:
            return m.mover, m.anchor, m.size

        # a two-anchor or viewer-frame plugin's run: the model and the judge read the rest of it too
        model_kw = {"more_anchors": m.more_anchors} if m.more_anchors else {}
        model_kw |= {} if m.viewer is None else {"viewer": m.viewer}
        return m.mover, m.anchor, m.size, (model_kw, judge_context([m.anchor, *m.more_anchors], m.viewer))

    def scores(self, action: str, motion) -> tuple[float | None, float | None]:
        """(learned final progress, the judge's score) of the installed action, or None where unavailable."""
        if action not in self._bundles:
            try:
                bundle = registry.load(action)
                self._bundles[action] = (bundle.progress_model(), judge_for(bundle))
            except L2PError as e:
                self._bundles[action] = None
                self.notes.append(f"{action}: no model or judge to compare with ({e})")
        if self._bundles[action] is None:
            return None, None
        model, judge = self._bundles[action]
        mover, anchor, size, *rest = motion
        model_kw, judge_kw = rest[0] if rest else ({}, {})
        try:
            final = float(model.final(mover, anchor, size, **model_kw))
            return final, float(judge.judge(mover, anchor, size, final_progress=final, **judge_kw).score)
        except ValueError as e:  # the motion does not have what the action reads (a second anchor)
            self.notes.append(f"{action}: cannot score this run ({e})")
            return None, None


def _spearman(x: list, y: list) -> float | None:
    pairs = [(a, b) for a, b in zip(x, y, strict=True) if a is not None and b is not None]
    if len(pairs) < MIN_SPEARMAN:
        return None
    return _f(spearman(np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])))


def _group(row: GradeRow) -> str:
    if row.source == "original" and row.folder:
        return f"{GRADED_FOLDERS.get(row.folder, row.action)} ({row.folder})"
    return row.action or "(no action)"


def problems(rows: list[GradeRow]) -> tuple[list[GradeRow], list[dict]]:
    """(rows whose run is still the one graded, problems: runs gone or changed since graded)."""
    status: dict[tuple[str, str], str | None] = {}
    for r in rows:
        k = (r.run_path, r.trajectory_sha256)
        if r.source != "app" or k in status:
            continue
        try:
            now = sha256_file(Path(r.run_path) / "trajectory.json")
            status[k] = None if now == r.trajectory_sha256 else "changed since graded"
        except OSError:
            status[k] = "run folder disappeared"
    good = [r for r in rows if not r.stale and (r.source != "app" or status[(r.run_path, r.trajectory_sha256)] is None)]
    out: dict[tuple[str, str], dict] = {}
    for r in rows:
        why = "graded again after it changed (stale)" if r.stale else (
            status.get((r.run_path, r.trajectory_sha256)) if r.source == "app" else None)
        if why:
            d = out.setdefault(
                (r.run_id, why), {"run_id": r.run_id, "run_path": r.run_path, "problem": why, "answers": 0}
            )
            d["answers"] += 1
    return good, list(out.values())


def graded_table(rows: list[GradeRow], motions: _Motions) -> list[dict]:
    """Table 1 (+ agreement) per group, from the graded-mode rows of one source."""
    by_group: dict[str, dict[str, list[GradeRow]]] = defaultdict(lambda: defaultdict(list))
    for r in rows:
        if r.grade is not None:
            by_group[_group(r)][r.run_id].append(r)
    table = []
    def order(g: str) -> tuple:
        action = next(iter(by_group[g].values()))[0].action
        return (ACTIONS.index(action) if action in ACTIONS else len(ACTIONS), g)

    for g in sorted(by_group, key=order):
        runs = by_group[g]
        all_grades = [r.grade for rs in runs.values() for r in rs]
        means, finals, judged = [], [], []
        for rs in runs.values():
            means.append(float(np.mean([r.grade for r in rs])))
            m = motions.motion(rs[0])
            f, j = motions.scores(rs[0].action, m) if m is not None and rs[0].action else (None, None)
            finals.append(f)
            judged.append(j)
        per_item: dict[tuple[str, str], list[int]] = defaultdict(list)  # between graders, within one view
        for rs in runs.values():
            for r in rs:
                per_item[(r.run_id, r.view)].append(r.grade)
        table.append({
            "group": g, "action": next(iter(runs.values()))[0].action, "runs": len(runs), "grades": len(all_grades),
            "reviewers": len({r.reviewer for rs in runs.values() for r in rs}),
            "views": "+".join(sorted({r.view for rs in runs.values() for r in rs}, reverse=True)),
            "mean_grade": _f(np.mean(all_grades)), "disparity": _f(disparity(per_item.values())),
            "spearman_final_progress": _spearman(finals, means), "spearman_judge": _spearman(judged, means),
            "_points": {"mean": means, "final": finals, "judge": judged},
        })
    return table


def blind_table(rows: list[GradeRow]) -> dict | None:
    rows = [r for r in rows if r.label]
    if not rows:
        return None
    true = _order({r.action for r in rows})
    given = _order({r.label for r in rows} | set(true) | {NONE_LABEL})
    conf = label_confusion([(r.action, r.label) for r in rows], true, given)
    items: dict[tuple[str, str], list[str]] = defaultdict(list)
    for r in rows:
        items[(r.run_id, r.view)].append(r.label)
    counts = np.array([[labels.count(c) for c in given] for labels in items.values()])
    k = fleiss_kappa(counts)
    k.pop("p_i")
    correct = [r.label == r.action for r in rows]
    return {"confusion": conf, "fleiss": {kk: _f(v) if isinstance(v, float) else v for kk, v in k.items()},
            "labels": len(rows), "items": len(items), "accuracy": _f(np.mean(correct)),
            "mean_grade": _f(np.mean([r.grade for r in rows if r.grade is not None] or [np.nan]))}


def views_table(rows: list[GradeRow]) -> list[dict]:
    """Runs graded in both views: per action the mean grade of each and their rank agreement."""
    per: dict[str, dict[str, dict[str, list[int]]]] = defaultdict(lambda: defaultdict(lambda: defaultdict(list)))
    for r in rows:
        if r.grade is not None and r.source == "app":
            per[r.action][r.run_id][r.view].append(r.grade)
    out = []
    for action in _order(per):
        both = {rid: v for rid, v in per[action].items() if v.get("2d") and v.get("3d")}
        if not both:
            continue
        m2 = [float(np.mean(v["2d"])) for v in both.values()]
        m3 = [float(np.mean(v["3d"])) for v in both.values()]
        out.append({"action": action, "runs": len(both), "mean_2d": _f(np.mean(m2)), "mean_3d": _f(np.mean(m3)),
                    "mean_3d_minus_2d": _f(np.mean(np.subtract(m3, m2))), "spearman_2d_3d": _spearman(m2, m3),
                    "_points": {"2d": m2, "3d": m3}})
    return out


def build_report(rows: list[GradeRow], source: str = "") -> dict:
    good, probs = problems(rows)
    motions = _Motions()
    graded = [r for r in good if r.mode == "graded"]
    rep = {
        "source": source,
        "answers": len(rows), "reviewers": len({r.reviewer for r in rows}),
        "graded": {
            "original": graded_table([r for r in graded if r.source == "original"], motions),
            "app": graded_table([r for r in graded if r.source != "original"], motions),
        },
        "blind": blind_table([r for r in good if r.mode == "blind"]),
        "views": views_table(graded),
        "problems": probs,
    }
    rep["notes"] = list(motions.notes)
    if any(r.source == "original" for r in rows):
        rep["notes"].append("the original 3-D study's per-rater labels are not shipped, so its blind confusion matrix "
                            "and Fleiss' kappa (0.5087) are not in this database (docs/review.md: what this code "
                            "reproduces from them)")
    return rep


SQLITE_SUFFIXES = (".sqlite", ".db", ".sqlite3")
NEEDED_COLUMNS = ("action", "mode", "grade")
"""Columns without which a file is not a grades export (``l2p-bullet review --export`` writes them all)."""


def read_report_grades(path: Path) -> list[GradeRow]:
    """The answers ``l2p-bullet report`` tabulates, refusing (one line, ``ReviewError``) a file that is not a
    review database or grades export, and one with no answers: a report of 0 answers, or of a CSV of
    something else read with every column defaulted, would be nonsense printed with exit status 0."""
    from ..data.grades import grades_head
    from .store import load_grades

    sqlite = grades_head(path).startswith(b"SQLite format 3")  # not read_bytes: a link to /dev/zero never ends
    if not sqlite and path.suffix.lower() in SQLITE_SUFFIXES:
        raise ReviewError(f"{path} is not a review database SQLite can open (file is not a database)")
    if not sqlite:
        _check_export(path)
    rows = load_grades(path)
    if not rows:
        raise ReviewError(f"{path} holds no answers: grade runs with l2p-bullet review RUNS, or import the original "
                          "study with l2p-bullet review --import-original")
    return rows


def _check_export(path: Path) -> None:
    """A grades export (.csv with a header row, else JSON lines) names the columns that reviews have."""
    from ..data.grades import grades_text

    text = grades_text(path)
    if path.suffix.lower() == ".csv":
        try:
            header = next(csv.reader(text.splitlines()[:1]), [])
        except csv.Error as e:  # a header cell over csv's 128 KiB field limit
            raise ReviewError(f"{path} is not a grades export (CSV: {e})") from None
        records = [dict.fromkeys(header)] if header else []
    else:
        try:
            records = [json.loads(line) for line in text.splitlines() if line.strip()]
        except (ValueError, RecursionError) as e:
            raise ReviewError(
                f"{path} is not a grades export (not JSON lines: {type(e).__name__}: {str(e)[:120]})"
            ) from None
    if not records:
        raise ReviewError(f"{path} holds no answers (an empty file): export the grades with l2p-bullet review --export")
    for r in records:
        missing = [c for c in NEEDED_COLUMNS if not isinstance(r, dict) or c not in r]
        if missing:
            raise ReviewError(f"{path} is not a grades export: no {', '.join(missing)} "
                              f"{'column' if len(missing) == 1 else 'columns'} (l2p-bullet review --export writes "
                              "them; see docs/review.md)")
