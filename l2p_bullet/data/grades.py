"""People's grades of runs as plain rows: the grades export (CSV / JSON lines) and the review database.

:func:`load_grades` reads grades from a review database (read-only) or from an export into
:class:`GradeRow` dataclasses, without torch or the web stack: the feedback learner and ``improve``
read grades here, the review app's store (``review/store.py``) writes them. The contract is
docs/review.md, "The grades export" (fields are only ever added).
"""

from __future__ import annotations

import csv
import io
import json
import sqlite3
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from ..core.bounded import read_bounded
from ..errors import L2PError, ReviewError
from . import review_schema


@dataclass(frozen=True)
class GradeRow:
    """One answer, as exported (docs/review.md, "The grades export"). Fields are only ever added.

    Also what the feedback learner reads (``learning/feedback.py``): one class for the contract, every
    field with a default so that a reader of an older export (or a test) fills only what it has.
    """

    run_id: str = ""
    run_path: str = ""  # absolute folder of the run; "" for the original study's demos
    trajectory_sha256: str = ""  # of the trajectory.json the reviewer saw (original: of the demo's JSON line)
    action: str = ""  # canonical action of the run ("" if the run had none)
    sentence: str = ""
    mode: str = "graded"  # "graded" (the sentence was shown) | "blind" (it was not; the reviewer labelled it)
    reviewer: str = ""
    grade: float | None = None  # 0-10: people give whole numbers, l2p-bullet improve's rule grades may not be
    label: str | None = None  # blind mode: the action the reviewer picked, or "none"
    comment: str = ""
    view: str = ""  # "3d" (the rendered video) | "2d" (the top-down animation)
    created_at: str = ""
    updated_at: str = ""
    source: str = "app"  # "app" | "original" (the 2018 study's grades) | "rules" (l2p-bullet improve)
    demo_id: str | None = None  # original: the graded demo's id in data/sim/human_eval_2d_demos.jsonl
    folder: str | None = None  # original: its folder (SlideToward, ..., SlideAroundDiscrete)
    stale: bool = False  # the run's trajectory changed after this grade (it was graded again since)


EXPORT_FIELDS: tuple[str, ...] = tuple(f.name for f in fields(GradeRow))


GRADES_SQL = (
    "SELECT a.run_id, r.path AS run_path, a.trajectory_sha256, r.action, r.sentence, a.mode, a.reviewer, a.grade, "
    "a.label, a.comment, a.view, a.created_at, a.updated_at, r.source, r.demo_id, r.folder, "
    "a.trajectory_sha256 != r.trajectory_sha256 AS stale FROM answers a JOIN runs r ON r.run_id = a.run_id"
)


def grade_row(r: sqlite3.Row) -> GradeRow:
    """One row of ``GRADES_SQL`` as a :class:`GradeRow`."""
    d = dict(r)
    d["stale"] = bool(d["stale"])
    return GradeRow(**d)


# --- export files ------------------------------------------------------------------------------------
def write_grades(rows: list[GradeRow], out: str | Path, force: bool = False) -> int:
    out = Path(out)
    kind = out.suffix.lower()
    if kind not in (".csv", ".jsonl"):
        raise ReviewError(f"cannot export to {out}: the file name must end in .csv or .jsonl")
    if out.exists() and not force:
        raise ReviewError(f"{out} already exists; pass --force to overwrite it")
    tmp = out.with_name(out.name + ".part")
    try:
        with open(tmp, "w", newline="", encoding="utf-8") as f:
            if kind == ".csv":
                w = csv.DictWriter(f, fieldnames=EXPORT_FIELDS)
                w.writeheader()
                for row in rows:
                    w.writerow({k: _csv_cell(v) for k, v in asdict(row).items()})
            else:
                for row in rows:
                    f.write(json.dumps(asdict(row), ensure_ascii=False) + "\n")
        tmp.replace(out)
    except OSError as e:
        raise ReviewError(f"cannot write {out}: {e.strerror or e}") from None
    return len(rows)


FORMULA_START = ("=", "+", "-", "@", "\t", "\r", "'")
"""A spreadsheet runs a cell that starts with = + - @ (or a tab/CR before one) as a formula: a reviewer
named ``=HYPERLINK(...)`` must stay text. Such cells are written with a leading ``'`` (and a cell that
starts with ``'`` gets a second one), which :func:`load_grades` takes off again: the round trip is exact."""


def _csv_cell(v: object) -> object:
    if v is None:
        return ""
    return "'" + v if isinstance(v, str) and v.startswith(FORMULA_START) else v


def _csv_text(v: object) -> object:
    return v[1:] if isinstance(v, str) and v.startswith("'") else v


MAX_GRADES_BYTES = 64 * 2**20
"""The largest grades export read (about 100,000 answers, some hundred times the original study's): a bound,
because a file linked to /dev/zero was read until memory ran out (docs/perform.md, "Limits on what is read")."""


def grades_head(path: Path, error: type[L2PError] = ReviewError) -> bytes:
    """The first 16 bytes of ``path`` (enough to tell a SQLite database), read without reading the rest."""
    try:
        with open(path, "rb") as f:
            return f.read(16)
    except OSError as e:
        raise error(f"cannot read grades from {path}: {e.strerror or e}") from None


def grades_text(path: Path, error: type[L2PError] = ReviewError) -> str:
    """A grades export's text, bounded by :data:`MAX_GRADES_BYTES`; ``error`` when it is larger or not UTF-8."""
    raw = read_bounded(path, MAX_GRADES_BYTES, error, str(path))
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise error(f"{path} is not a grades export (not UTF-8 text: byte {e.start})") from None


def load_grades(path: str | Path) -> list[GradeRow]:
    """Grades from a review database or an export (.csv / .jsonl), as :class:`GradeRow` rows.

    Columns an older export lacks get their defaults; columns a newer one adds are ignored.
    """
    p = Path(path)
    if grades_head(p).startswith(b"SQLite format 3"):
        return _grades_read_only(p)
    text = grades_text(p)
    try:
        if p.suffix.lower() == ".csv":  # newline="": comments may hold line breaks
            records = [{k: _csv_text(v) for k, v in r.items()} for r in csv.DictReader(io.StringIO(text, newline=""))]
        else:
            records = [json.loads(line) for line in text.split("\n") if line.strip()]
        return [_from_record(r) for r in records]
    except (ValueError, TypeError, KeyError, csv.Error, RecursionError) as e:  # a field over csv's 128 KiB limit,
        what = "CSV" if isinstance(e, csv.Error) else type(e).__name__  # JSON nested past the recursion limit
        raise ReviewError(f"{p} is not a grades export ({what}: {str(e)[:120]})") from None


def _grades_read_only(path: Path) -> list[GradeRow]:
    """Read a database without writing to it: an older schema is migrated in a copy in memory."""
    try:
        src = sqlite3.connect(f"{path.resolve().as_uri()}?mode=ro", uri=True)
        mem = sqlite3.connect(":memory:")
        src.backup(mem)
        src.close()
    except sqlite3.DatabaseError as e:
        raise ReviewError(f"cannot read review database {path}: {e}") from None
    mem.row_factory = sqlite3.Row
    review_schema.migrate(mem, path)
    sql = GRADES_SQL + " ORDER BY a.created_at, a.id"
    try:
        return [grade_row(r) for r in mem.execute(sql).fetchall()]
    finally:
        mem.close()


def _from_record(r: dict) -> GradeRow:
    known = {f.name: f for f in fields(GradeRow)}
    d = {k: v for k, v in r.items() if k in known}
    if d.get("grade") in (None, ""):
        d["grade"] = None
    else:
        g = float(d["grade"])
        d["grade"] = int(g) if g.is_integer() else g
    for k in ("label", "demo_id", "folder"):
        if d.get(k) == "":
            d[k] = None
    if isinstance(d.get("stale"), str):
        d["stale"] = d["stale"].strip().lower() == "true"
    d.setdefault("source", "app")
    return GradeRow(**d)
