"""Feedback from people's grades (and from a rule judge) as training sequences for a progress model.

Why: the training set was reshaped, change after change, until planners passed our own rules, and
each change cost agreement with people (docs/learning.md). Grades are the standard of truth, so the
motions people graded become training sequences whose progress at the motion's end is the people's
mean grade (0-10 -> 0-1), and motions people took for another action in a blind review are negatives.

Where grades come from (:func:`load_feedback`), one :class:`FeedbackItem` per graded motion:

- ``original``: the 90 graded 2-D demonstrations of the original study (``learning.agreement``);
- a review-app export, CSV or JSON lines (``data.grades.EXPORT_FIELDS``, one ``GradeRow`` per line); a reviewed
  run's motion is read from its run folder's trajectory.json, and a run whose trajectory.json no longer
  has the sha256 that was reviewed is reported, never used;
- the review app's SQLite database (``.sqlite``/``.db``), through ``l2p_bullet.data.grades.load_grades``;
- the rule judge (:func:`~l2p_bullet.learning.feedback_targets.judge_items`): planner outputs graded 10 x the judge's
  score, the original
  project's "automatic feedback".

How items become training sequences is :mod:`l2p_bullet.learning.feedback_targets`; the fine-tuning
:func:`l2p_bullet.learning.train_progress.fine_tune`. How well a model agrees with the grades, per folder
(:func:`folder_agreement`, :func:`score_items`), is what ``improve`` reports each round. Torch-free.
"""

from __future__ import annotations

import csv
import json
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..core.contracts import load_motion
from ..core.vocabulary import GRADED_FOLDERS, canonical_action, normalize_name
from ..data.grades import EXPORT_FIELDS, GradeRow, grades_text, load_grades
from ..errors import DataError, L2PError, ReviewError, UnknownActionError
from ..plugins.bundle import sha256_file
from .agreement import graded_motions, spearman

GRADE_MAX = 10.0
"""Grades run from 0 (bad) to this (good); the training target is grade / GRADE_MAX."""

ORIGINAL = "original"
"""The built-in source: the original study's graded 2-D demonstrations."""


class FeedbackError(DataError):
    """A feedback source is missing, unreadable or malformed; ``.path`` and ``.line`` say where."""

    def __init__(self, message: str, path: str = "", line: int | None = None):
        self.path, self.line = path, line
        where = f"{path}" + (f", line {line}" if line is not None else "")
        super().__init__(f"{where}: {message}" if where else message)


def _row(d: dict, path: str, line: int) -> GradeRow:
    """Validate one export row (a mapping of column -> value; CSV gives strings, JSON typed values)."""
    vals = {k: ("" if d.get(k) is None else str(d.get(k)).strip()) for k in EXPORT_FIELDS if k != "stale"}
    mode = vals["mode"].lower() or "graded"
    if mode not in ("graded", "blind"):
        raise FeedbackError(f'mode must be "graded" or "blind", not "{vals["mode"]}"', path, line)
    grade = None
    if vals["grade"]:
        try:
            grade = float(vals["grade"])
        except ValueError:
            raise FeedbackError(f'grade "{vals["grade"]}" is not a number', path, line) from None
        if not 0.0 <= grade <= GRADE_MAX:
            raise FeedbackError(f"grade {grade:g} is outside 0-{GRADE_MAX:g}", path, line)
    if not vals["action"]:
        raise FeedbackError("the row names no action", path, line)
    if not (vals["run_id"] or vals["demo_id"]):
        raise FeedbackError("the row has neither a run_id nor a demo_id", path, line)
    return GradeRow(**{**vals, "mode": mode, "grade": grade, "source": vals["source"] or "app",
                       **{k: vals[k] or None for k in ("label", "demo_id", "folder")},
                       "stale": str(d.get("stale", "")).strip().lower() in ("true", "1")})


def read_grades(path: str | Path) -> list[GradeRow]:
    """Every row of a review export: ``.csv`` (header row), ``.jsonl`` (one object a line), or the review
    app's database (``.sqlite``/``.db``, read by ``l2p_bullet.data.grades.load_grades``)."""
    p = Path(path)
    if p.exists() and not p.is_file():  # a folder, a device (a link to /dev/zero), a pipe
        raise FeedbackError("not a regular file (expected a .csv or .jsonl export, a review .sqlite/.db)", str(p))
    if not p.is_file():
        raise FeedbackError("no such feedback file (expected a .csv or .jsonl export, a review .sqlite/.db, "
                            f'or "{ORIGINAL}")', str(p))
    suffix = p.suffix.lower()
    if suffix in (".sqlite", ".db", ".sqlite3"):
        return _read_store(p)
    text = grades_text(p, FeedbackError)  # bounded: a file linked to /dev/zero was read until memory ran out
    if suffix == ".csv":
        reader = csv.DictReader(text.splitlines())
        try:
            if not reader.fieldnames or "action" not in reader.fieldnames:
                raise FeedbackError(f"a CSV export needs a header row with the columns {', '.join(EXPORT_FIELDS)}",
                                    str(p))
            return [_row(d, str(p), i) for i, d in enumerate(reader, start=2)]
        except csv.Error as e:  # a field over csv's 128 KiB limit
            raise FeedbackError(f"not a CSV export ({e})", str(p)) from None
    if suffix in (".jsonl", ".ndjson"):
        rows = []
        for i, line in enumerate(text.splitlines(), start=1):
            if not line.strip():
                continue
            try:
                d = json.loads(line)
            except json.JSONDecodeError as e:
                raise FeedbackError(f"not valid JSON ({e.msg})", str(p), i) from None
            except (ValueError, RecursionError) as e:  # nested past the recursion limit, an integer of 5,000 digits
                raise FeedbackError(f"not valid JSON ({type(e).__name__}: {str(e)[:80]})", str(p), i) from None
            if not isinstance(d, dict):
                raise FeedbackError("each line must be a JSON object", str(p), i)
            rows.append(_row(d, str(p), i))
        return rows
    raise FeedbackError(f'unknown feedback format "{suffix}" (expected .csv, .jsonl, .sqlite or .db)', str(p))


def _read_store(p: Path) -> list[GradeRow]:
    """The review app's database, through its own reader, each row checked as an export row is."""
    try:
        rows = load_grades(p)
    except ReviewError as e:
        raise FeedbackError(str(e), str(p)) from None
    return [_row(asdict(r), str(p), i) for i, r in enumerate(rows, start=1)]


@dataclass
class FeedbackItem:
    """One motion and what people (or a judge) said of it, for the action it was performed for.

    ``mover``/``anchor`` are (T,3) poses in metres, blocks of side ``size``; ``grades`` 0-10 from graded
    reviews; ``labels`` the actions blind reviewers picked ("none" for none of them).
    """

    id: str
    action: str
    mover: np.ndarray
    anchor: np.ndarray
    size: float
    grades: list[float] = field(default_factory=list)
    labels: list[str] = field(default_factory=list)
    source: str = ""
    folder: str = ""

    @property
    def grade(self) -> float | None:
        """The mean grade, or None when nobody graded the motion."""
        return float(np.mean(self.grades)) if self.grades else None


@dataclass
class Skipped:
    """A reviewed run that was not used, and why (its trajectory changed, its folder is gone, ...)."""

    id: str
    path: str
    reason: str


def original_items() -> list[FeedbackItem]:
    """The original study's 90 graded 2-D demonstrations, one item each (grades of both people)."""
    return [FeedbackItem(m.id, m.action, m.mover, m.anchor, m.size, list(m.grades.values()), [], ORIGINAL, m.folder)
            for m in graded_motions()]


def _label(value: str) -> str:
    key = normalize_name(value)
    if key in ("", "none"):
        return "none"
    try:
        return canonical_action(value)
    except UnknownActionError:
        return key  # a plugin action's name: still "another action"


def items_from_rows(
    rows: Sequence[GradeRow], base: str | Path | None = None
) -> tuple[list[FeedbackItem], list[Skipped]]:
    """Group export rows by motion (``demo_id`` for the study's rows, else ``run_id``) into items.

    A run's motion is its run folder's trajectory.json (``run_path``, relative paths first against
    ``base``, the export's folder); a run whose folder or trajectory is missing, or whose trajectory.json
    no longer has the reviewed ``trajectory_sha256``, is returned in the second list instead of used.
    """

    groups: dict[str, list[GradeRow]] = {}
    for r in rows:
        key = f"demo:{r.demo_id}" if (r.source == ORIGINAL and r.demo_id) else f"run:{r.run_id or r.run_path}"
        groups.setdefault(key, []).append(r)
    originals = {it.id: it for it in original_items()} if any(k.startswith("demo:") for k in groups) else {}
    items, skipped = [], []
    for key, rs in groups.items():
        action = canonical_action(rs[0].action) if _is_builtin(rs[0].action) else normalize_name(rs[0].action)
        grades = [r.grade for r in rs if r.mode == "graded" and r.grade is not None]
        labels = [_label(r.label) for r in rs if r.mode == "blind" and r.label]
        if key.startswith("demo:"):
            demo_id = key[5:]
            if demo_id not in originals:
                skipped.append(Skipped(demo_id, "", "no graded demonstration has this demo_id"))
                continue
            o = originals[demo_id]
            items.append(FeedbackItem(o.id, o.action, o.mover, o.anchor, o.size, grades, labels, ORIGINAL, o.folder))
            continue
        run_id = key[4:]
        folder = _run_folder(rs[0].run_path, base)
        traj = folder / "trajectory.json" if folder else None
        if traj is None or not traj.is_file():
            skipped.append(Skipped(run_id, rs[0].run_path, "the run folder or its trajectory.json is missing"))
            continue
        want = {r.trajectory_sha256.lower() for r in rs if r.trajectory_sha256}
        have = sha256_file(traj)
        if want and want != {have}:
            skipped.append(Skipped(run_id, str(traj), "trajectory.json changed since it was reviewed "
                                   f"(sha256 {have[:12]}..., reviewed {', '.join(sorted(w[:12] for w in want))}...)"))
            continue
        try:
            m = load_motion(traj)
        except L2PError as e:
            skipped.append(Skipped(run_id, str(traj), f"unreadable trajectory ({e})"))
            continue
        items.append(FeedbackItem(run_id, action, m.mover, m.anchor, m.size, grades, labels, rs[0].source or "review",
                                  rs[0].folder))
    return items, skipped


def _is_builtin(name: str) -> bool:
    try:
        canonical_action(name)
    except UnknownActionError:
        return False
    return True


def _run_folder(run_path: str, base: str | Path | None) -> Path | None:
    if not run_path:
        return None
    p = Path(run_path)
    if p.is_absolute():
        return p
    for root in ([Path(base)] if base else []) + [Path.cwd()]:
        if (root / p).exists():
            return root / p
    return Path(base) / p if base else p


def load_feedback(sources: Sequence[str]) -> tuple[list[FeedbackItem], list[Skipped]]:
    """Items from every source: "original" (the built-in study grades) or an export/database path."""
    items: list[FeedbackItem] = []
    skipped: list[Skipped] = []
    for src in sources:
        if src.strip().lower() == ORIGINAL:
            items += original_items()
            continue
        got, skip = items_from_rows(read_grades(src), Path(src).parent)
        items += got
        skipped += skip
    return items, skipped


def folder_agreement(items: Sequence[FeedbackItem], finals: dict[str, float]) -> dict[str, float]:
    """Spearman(prediction, mean grade) per folder, in the order of ``GRADED_FOLDERS`` where present."""
    order = [f for f in GRADED_FOLDERS if any(it.folder == f for it in items)]
    order += sorted({it.folder for it in items} - set(order))
    out = {}
    for folder in order:
        its = [it for it in items if it.folder == folder and it.id in finals]
        out[folder] = spearman(np.array([finals[it.id] for it in its]), np.array([it.grade for it in its]))
    return out


def score_items(model: Any, items: Sequence[FeedbackItem]) -> dict[str, float]:
    """Final progress of ``model`` on each item (batched per block size)."""
    out: dict[str, float] = {}
    for size in sorted({it.size for it in items}):
        its = [it for it in items if it.size == size]
        finals = model.final_batch([it.mover for it in its], [it.anchor for it in its], size)
        out.update({it.id: float(v) for it, v in zip(its, finals, strict=True)})
    return out
