"""The results table: one row per run, in SQLite (``results.sqlite`` in the evaluation's folder).

Why SQLite and not Parquet: an evaluation must survive Ctrl-C and killed workers with at most the runs
in flight lost, so every row is committed the moment it arrives. SQLite does exactly that (one
transaction per row, crash-safe, in the standard library) and ``--resume`` is a primary-key lookup;
a Parquet file is immutable, its footer is written when it is closed, so appending per run would
mean a file per run or rewriting the table. Readers who want Parquet or a data frame get one from
:meth:`ResultsStore.to_parquet` (pyarrow) or ``pandas.read_sql``.

Only the evaluation's own process writes (workers return rows to it), so there is one writer; and one
evaluation process per folder: :func:`only_writer` holds a lock on ``.evaluate.lock`` for the whole run,
so a second ``--resume`` of a folder that is being written is refused instead of running every
remaining task twice.
The ``meta`` table keeps the evaluation's settings: ``--resume`` runs the same evaluation again.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import sqlite3
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from ..errors import EvaluationError
from .worker import TIMING_FIELDS

DB_NAME = "results.sqlite"
LOCK_NAME = ".evaluate.lock"


@contextlib.contextmanager
def only_writer(folder: str | Path) -> Iterator[None]:
    """Hold the evaluation folder's lock (``flock``: released by the kernel when the process dies, so a
    killed evaluation never blocks the next); EvaluationError when another process holds it."""
    folder = Path(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        fd = os.open(folder / LOCK_NAME, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o644)
    except OSError as e:
        raise EvaluationError(f"cannot use {folder} for an evaluation: {e.strerror or e}") from None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(fd)
        raise EvaluationError(f"{folder} is being written by another l2p-bullet evaluate right now; wait for it to "
                              "end (or stop it) before resuming, or choose another --out") from None
    try:
        yield
    finally:
        os.close(fd)

COLUMNS: dict[str, str] = {
    "run_id": "TEXT PRIMARY KEY", "idx": "INTEGER", "scene_id": "TEXT", "scene_source": "TEXT", "seed": "INTEGER",
    "sentence": "TEXT", "action": "TEXT", "planner": "TEXT", "planner_used": "TEXT", "mode": "TEXT",
    "success": "INTEGER", "score": "REAL", "reason": "TEXT", "judge": "TEXT", "final_progress": "REAL",
    "planned_progress": "REAL", "max_deviation_m": "REAL", "anchor_displacement_m": "REAL",
    "final_error_m": "REAL", "final_gap_blocks": "REAL", "stopped": "TEXT", "plan_steps": "INTEGER",
    "judged": "TEXT", "scored": "TEXT", "timings": "TEXT", "plan_s": "REAL", "execute_s": "REAL", "total_s": "REAL",
    "wall_s": "REAL", "worker": "TEXT", "run_dir": "TEXT", "error": "TEXT", "error_type": "TEXT",
    "finished_at": "REAL", "completed": "INTEGER", "redraws": "INTEGER", "clauses": "TEXT",
    "manner": "TEXT",
}
"""Column -> SQLite type. ``judged`` (every action's judge: {action: {success, score}}) and ``scored``
(every action's learned progress: {action: value}) are JSON text: the automatic confusion matrix;
``timings`` (JSON) has perform's stages (parse, load, plan, execute, judge, total) in seconds.
A chain's row (``evaluate --chains``) adds ``completed`` (clauses done in a row), ``redraws`` and
``clauses`` (JSON: one entry per clause performed, evaluate/chains.py); a chain drawn whole
(``--chain-draw sentence``) adds ``forecast``, ``forecast_alone``, ``forecast_plans`` and ``ends_changed`` to
its ``timings``, and one refused up front has ``error_type`` "refused". ``manner``: slide, carry,
push (``evaluate --manners``); null in a table written before it."""
JSON_COLUMNS = ("judged", "scored", "timings", "clauses")


class ResultsStore:
    """Open (or create) the results table in ``folder``; use as a context manager or call :meth:`close`."""

    def __init__(self, folder: str | Path):
        self.folder = Path(folder)
        self.path = self.folder / DB_NAME
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
            self.db = sqlite3.connect(self.path)
            self.db.execute("PRAGMA journal_mode=WAL")  # a reader (a report) never blocks the writer
            self.db.execute("PRAGMA synchronous=NORMAL")  # committed rows survive a killed process
            cols = ", ".join(f"{k} {v}" for k, v in COLUMNS.items())
            self.db.execute(f"CREATE TABLE IF NOT EXISTS runs ({cols})")
            self.db.execute("CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT)")
            have = {r[1] for r in self.db.execute("PRAGMA table_info(runs)")}
            for k, v in COLUMNS.items():  # a table from an older version gets the new columns (contracts grow)
                if k not in have:
                    self.db.execute(f"ALTER TABLE runs ADD COLUMN {k} {v.replace(' PRIMARY KEY', '')}")
            self.db.commit()
        except sqlite3.DatabaseError as e:
            raise EvaluationError(f"cannot open the results table {self.path}: {e}") from None

    def __enter__(self) -> ResultsStore:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        self.db.close()

    # --- settings ------------------------------------------------------------------------------
    def get_meta(self, key: str) -> Any:
        row = self.db.execute("SELECT value FROM meta WHERE key = ?", (key,)).fetchone()
        return None if row is None else json.loads(row[0])

    def set_meta(self, key: str, value: Any) -> None:
        self.db.execute("INSERT OR REPLACE INTO meta (key, value) VALUES (?, ?)", (key, json.dumps(value)))
        self.db.commit()

    # --- rows ----------------------------------------------------------------------------------
    def add(self, row: dict[str, Any]) -> None:
        """Insert (or replace) one run's row and commit it at once."""
        values = [json.dumps(row.get(k), sort_keys=True) if k in JSON_COLUMNS and row.get(k) is not None
                  else _plain(row.get(k)) for k in COLUMNS]
        self.db.execute(f"INSERT OR REPLACE INTO runs ({', '.join(COLUMNS)}) VALUES ({', '.join('?' * len(COLUMNS))})",
                        values)
        self.db.commit()

    def recorded(self, with_errors: bool = True) -> set[str]:
        """Run ids already in the table (``with_errors=False``: only those that ran without an error)."""
        q = "SELECT run_id FROM runs" + ("" if with_errors else " WHERE error IS NULL")
        return {r[0] for r in self.db.execute(q)}

    def rows(self) -> list[dict[str, Any]]:
        """Every row, in task order, JSON columns decoded."""
        cur = self.db.execute(f"SELECT {', '.join(COLUMNS)} FROM runs ORDER BY idx, run_id")
        out = []
        for values in cur:
            row = dict(zip(COLUMNS, values, strict=True))
            for k in JSON_COLUMNS:
                if row[k] is not None:
                    row[k] = json.loads(row[k])
            out.append(row)
        return out

    def to_parquet(self, path: str | Path, exclusive: bool = False) -> Path:
        """Write the table as Parquet (JSON columns kept as JSON text); needs pyarrow. ``exclusive``: never
        overwrite a file (``evaluate --parquet``: EvaluationError if ``path`` exists)."""
        try:
            # lazy: pyarrow is an optional extra (l2p-bullet[export])
            import pyarrow as pa
            import pyarrow.parquet as pq
        except ImportError:
            from ..errors import MissingExtraError

            raise MissingExtraError("pyarrow", "export", "writing Parquet") from None
        rows = self.rows()
        data = {k: [json.dumps(r[k], sort_keys=True) if k in JSON_COLUMNS and r[k] is not None else r[k]
                    for r in rows] for k in COLUMNS}
        if not exclusive:
            pq.write_table(pa.table(data), Path(path))
            return Path(path)
        try:
            with open(path, "xb") as f:  # made here, so ours to remove if writing it fails
                try:
                    pq.write_table(pa.table(data), f)
                except BaseException:
                    os.unlink(path)
                    raise
        except FileExistsError:
            raise EvaluationError(f"--parquet {path} already exists (it is never overwritten): remove it or "
                                  "choose another --parquet path") from None
        except OSError as e:
            raise EvaluationError(f"cannot write --parquet {path}: {e.strerror or e} (the results are in "
                                  f"{self.path})") from None
        return Path(path)


def _plain(v: Any) -> Any:
    """numpy scalars and bools as the plain Python values SQLite stores."""
    if v is None or isinstance(v, str | int | float):
        return v
    if hasattr(v, "item"):
        return v.item()
    return v


def comparable(row: dict[str, Any]) -> dict[str, Any]:
    """A row without the fields that depend on the machine and the moment (timings, worker, folder)."""
    return {k: v for k, v in row.items() if k not in TIMING_FIELDS and k != "run_dir"}
