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
"""

from __future__ import annotations

import contextlib
import csv
import json
from collections import defaultdict
from collections.abc import Iterator
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
from .plots import plot_all
from .stats import disparity, fleiss_kappa, label_confusion
from .store import NONE_LABEL, GradeRow

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


# --- output ----------------------------------------------------------------------------------------
def _fmt(v, digits: int = 2) -> str:
    if v is None:
        return "n/a"
    return f"{v:.{digits}f}" if isinstance(v, float) else str(v)


def _md(header: list[str], rows: list[list]) -> str:
    lines = [
        "| " + " | ".join(header) + " |",
        "|" + "|".join("---" if i == 0 else "---:" for i in range(len(header))) + "|",
    ]
    lines += ["| " + " | ".join(_fmt(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def render_text(rep: dict) -> str:
    out = [f"Review report: {rep['source']}: {rep['answers']} answers from {rep['reviewers']} reviewers"]
    head = ["action", "runs", "grades", "view", "mean grade", "disparity", "Spearman final progress",
            "Spearman judge"]
    for key, title in (("original", "the original study (imported, 2-D, two graders who knew the action)"),
                       ("app", "runs graded here (the sentence shown)")):
        t = rep["graded"][key]
        if t:
            out += ["", f"Question 1, grades: {title}", _md(head, [
                [r["group"], r["runs"], r["grades"], r["views"], r["mean_grade"], r["disparity"],
                 r["spearman_final_progress"], r["spearman_judge"]] for r in t])]
    b = rep["blind"]
    if b:
        c = b["confusion"]
        out += ["", f"Question 2, blind labels: {b['labels']} labels of {b['items']} runs; share of each row's labels",
                _md(["true \\ label"] + c["cols"] + ["n"],
                    [[r] + [float(v) if np.isfinite(v) else None for v in s] + [sum(n)]
                     for r, s, n in zip(c["rows"], c["shares"], c["counts"], strict=True)]),
                f"Fleiss' kappa {_fmt(b['fleiss']['kappa'], 3)} over {b['fleiss']['items']} runs labelled by two or "
                f"more people ({_fmt(b['fleiss']['raters_per_item'], 1)} each on average); "
                f"labels matching the run's action: {_fmt(b['accuracy'])}"]
    if rep["views"]:
        out += ["", "Question 3, the same runs graded as the 3-D video and as the 2-D animation",
                _md(["action", "runs", "mean 2-D", "mean 3-D", "3-D minus 2-D", "Spearman 2-D vs 3-D"],
                    [[v["action"], v["runs"], v["mean_2d"], v["mean_3d"], v["mean_3d_minus_2d"], v["spearman_2d_3d"]]
                     for v in rep["views"]])]
    if rep["problems"]:
        out += ["", "Not counted (the run is not the one that was graded):"]
        out += [f"  {p['run_id']}: {p['problem']} ({p['answers']} answers) {p['run_path']}" for p in rep["problems"]]
    if rep["notes"]:
        out += [""] + [f"note: {n}" for n in rep["notes"]]
    return "\n".join(out)


def _public(rep: dict) -> dict:
    """The report without the plotting points (what --json prints and report.json holds)."""
    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if not k.startswith("_")}
        if isinstance(x, list):
            return [strip(v) for v in x]
        return x
    return strip(rep)


REPORT_FILES: tuple[str, ...] = ("report.md", "report.json", "table1_original.csv", "table1_app.csv", "confusion.csv",
                                 "table1.png", "agreement.png", "confusion.png", "views.png")
"""What :func:`write_grade_report` writes: recorded in the report folder's marker, so that ``--force``
recognises them (and only them) later."""
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


@contextlib.contextmanager
def report_folder(folder: Path, db: Path) -> Iterator[Path]:
    """``with report_folder(out, db) as folder:`` the folder for a report, by the run-folder rules
    (:func:`~l2p_bullet.core.runfolder.run_folder`): a new or empty folder, or one holding an earlier report of
    this command and nothing else, which is replaced (a report is made again after every grading session:
    asking for ``--force`` each time would only teach people to type it); never a folder with a person's
    files (their own ``report.md``), a run folder of another command, or one that is or holds the grades file.
    The earlier report stays aside until the new one is written, and comes back if writing it fails. A
    folder without the marker (an older version's) that holds only report files is taken as an earlier report."""
    from ..core.runfolder import run_folder

    _adopt_old_report(folder)
    with run_folder(folder, force=True, command="report", files=REPORT_FILES, inputs=(db,),
                    restore_on_error=True) as out:
        yield out


def _adopt_old_report(folder: Path) -> None:
    """Mark a report folder written before the marker existed as report's, so the rules above replace it (the
    earlier report is kept aside until the new one is written). Only a folder of report files whose
    report.json is a report's (the keys :func:`build_report` always writes): a person's own report.md and
    report.json are never taken for one. Any other folder is left as it is, and refused there if not ours."""
    from ..core.runfolder import MARKER

    if not folder.is_dir() or folder.is_symlink() or (folder / MARKER).exists():
        return
    entries = list(folder.iterdir())
    if not ({"report.md", "report.json"} <= {p.name for p in entries}
            and all(p.is_file() and not p.is_symlink() and p.name in REPORT_FILES for p in entries)):
        return
    try:
        written = json.loads((folder / "report.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return
    if not (isinstance(written, dict) and REPORT_KEYS <= set(written)):
        return
    try:
        (folder / MARKER).write_text(json.dumps({"tool": "l2p-bullet", "command": "report",
                                                 "files": list(REPORT_FILES), "finished": "before the marker"}) + "\n")
    except OSError as e:
        raise ReviewError(f"cannot write the report into {folder}: {e.strerror or e}") from None


REPORT_KEYS = frozenset({"source", "answers", "reviewers", "graded", "blind", "views", "problems"})
"""Keys every report.json that ``report`` wrote has (:func:`build_report`): how an earlier report is told apart."""


def write_grade_report(rep: dict, folder: Path) -> list[Path]:
    """report.md, report.json, table CSVs and PNG plots into ``folder``; returns the files written."""

    try:
        folder.mkdir(parents=True, exist_ok=True)
        files = [folder / "report.md", folder / "report.json"]
        files[0].write_text(render_text(rep) + "\n", encoding="utf-8")
        files[1].write_text(json.dumps(_public(rep), indent=1, default=str) + "\n", encoding="utf-8")
        for key in ("original", "app"):
            t = _public(rep["graded"][key])
            if t:
                p = folder / f"table1_{key}.csv"
                with open(p, "w", newline="", encoding="utf-8") as f:
                    w = csv.DictWriter(f, fieldnames=list(t[0]))
                    w.writeheader()
                    w.writerows(t)
                files.append(p)
        if rep["blind"]:
            p = folder / "confusion.csv"
            c = rep["blind"]["confusion"]
            with open(p, "w", newline="", encoding="utf-8") as f:
                w = csv.writer(f)
                w.writerow(["true_label", *c["cols"], "n"])
                for r, s, n in zip(c["rows"], c["shares"], c["counts"], strict=True):
                    w.writerow([r, *[f"{v:.3f}" for v in s], sum(n)])
            files.append(p)
        files += plot_all(rep, folder)
    except OSError as e:
        raise ReviewError(f"cannot write the report into {folder}: {e.strerror or e}") from None
    return files
