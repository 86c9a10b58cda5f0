"""The review store: runs, answers and their history in one SQLite file, and the grades as plain rows.

Every write is one ``BEGIN IMMEDIATE`` ... ``COMMIT`` transaction that ends before the caller returns
(the web app answers a reviewer only after that), so an answer survives a crash or a restart of the
server. An answer is keyed by (run, trajectory sha256, reviewer, mode, view): two reviewers never share
a row, and a changed run is graded as a new version, never by overwriting the grades of the old one.
Every submission is also appended to ``answer_log``; nothing is ever deleted.

:class:`GradeRow`, :func:`load_grades` and :func:`write_grades` (the grades as plain rows, read from a
database or an export) live in :mod:`l2p_bullet.data.grades`, a floor the learners may import too.
"""

from __future__ import annotations

import contextlib
import sqlite3
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

from ..data import review_schema as schema
from ..data.grades import (  # noqa: F401  (re-exported: the review app's names for the grades contract)
    EXPORT_FIELDS,
    GRADES_SQL,
    GradeRow,
    grade_row,
    load_grades,
    write_grades,
)
from ..errors import ReviewError
from .runs import RunInfo

MODES = ("graded", "blind")
NONE_LABEL = "none"
"""The blind-mode label for "none of these actions"."""


def now() -> str:
    """UTC time stamp with milliseconds, ISO 8601 (sorts as text)."""
    return datetime.now(UTC).isoformat(timespec="milliseconds").replace("+00:00", "Z")


@dataclass(frozen=True)
class Answer:
    """What a reviewer submits for one run in one mode and view."""

    run_id: str
    reviewer: str
    mode: str
    view: str
    grade: int | None
    label: str | None = None
    comment: str = ""


class DatabaseUnavailable(ReviewError):
    """The database file went away, was replaced or became read-only while the app was serving (503)."""


class AnswerConflict(ReviewError):
    """The run changed on disk, or this reviewer's answer was changed elsewhere since it was read."""

    def __init__(self, message: str, reason: str):
        super().__init__(message)
        self.reason = reason  # "changed" | "missing" | "answered" | "stale-edit"


@dataclass(frozen=True)
class Registration:
    new: list[RunInfo]
    known: list[RunInfo]
    changed: list[tuple[RunInfo, str, int]]  # run now, sha it was registered with, answers for that sha


class Store:
    """A review database file (created and migrated on open)."""

    def __init__(self, path: str | Path):
        self.path = Path(path)
        if self.path.exists() and self.path.is_dir():
            raise ReviewError(f"--db {self.path} is a folder; give a file name, e.g. {self.path / 'reviews.sqlite'}")
        if not self.path.parent.is_dir():
            raise ReviewError(f"cannot create review database {self.path}: folder {self.path.parent} does not exist")
        self._identity: tuple[int, int] | None = None
        conn = schema.connect(self.path)  # the one place a database is created
        try:
            self.migrated_from = schema.migrate(conn, self.path)
        finally:
            conn.close()
        st = self.path.stat()
        self._identity = (st.st_dev, st.st_ino)

    @contextmanager
    def connect(self) -> Iterator:
        """A connection to *this* database file: if it was moved, deleted or replaced since it was opened,
        :class:`DatabaseUnavailable` (never a fresh empty database created silently in its place)."""
        try:
            st = self.path.stat()
        except OSError:
            raise DatabaseUnavailable(
                f"the review database {self.path} was moved or deleted while the server was "
                "running; nothing can be saved: put it back, or restart l2p-bullet review"
            ) from None
        if self._identity is not None and (st.st_dev, st.st_ino) != self._identity:
            raise DatabaseUnavailable(f"the review database {self.path} was replaced by another file while the server "
                                      "was running; nothing is saved to it: restart l2p-bullet review")
        conn = schema.connect(self.path, create=False)
        try:
            yield conn
        except sqlite3.DatabaseError as e:  # made read-only, disk full, removed under an open connection
            raise DatabaseUnavailable(f"the review database {self.path} cannot be used ({e}): was it made read-only "
                                      "or moved while the server was running? Nothing was saved") from None
        finally:
            conn.close()

    @contextmanager
    def transaction(self) -> Iterator:
        """One write transaction, committed when the block ends (rolled back on an exception)."""
        with self.connect() as conn:
            conn.execute("BEGIN IMMEDIATE")
            try:
                yield conn
            except BaseException:
                with contextlib.suppress(sqlite3.DatabaseError):
                    conn.execute("ROLLBACK")
                raise
            conn.execute("COMMIT")

    # --- runs ---------------------------------------------------------------------------------
    def register_runs(self, runs: list[RunInfo], accept_changed: bool = False) -> Registration:
        """Record runs first seen; report those whose trajectory differs from the registered one.

        A changed run keeps its registered sha256 (its grades stay attached to what was graded) unless
        ``accept_changed``: then the new trajectory is registered and graded as a new version.
        """
        new, known, changed = [], [], []
        with self.transaction() as conn:
            for run in runs:
                row = conn.execute("SELECT trajectory_sha256 FROM runs WHERE run_id = ?", (run.run_id,)).fetchone()
                if row is None:
                    conn.execute("INSERT INTO runs (run_id, path, trajectory_sha256, action, sentence, registered_at)"
                                 " VALUES (?, ?, ?, ?, ?, ?)",
                                 (run.run_id, str(run.path), run.trajectory_sha256, run.action, run.sentence, now()))
                    new.append(run)
                elif row[0] == run.trajectory_sha256:
                    known.append(run)
                else:
                    n = conn.execute("SELECT count(*) FROM answers WHERE run_id = ? AND trajectory_sha256 = ?",
                                     (run.run_id, row[0])).fetchone()[0]
                    changed.append((run, row[0], n))
                    if accept_changed:
                        conn.execute("UPDATE runs SET trajectory_sha256 = ?, action = ?, sentence = ? WHERE run_id = ?",
                                     (run.trajectory_sha256, run.action, run.sentence, run.run_id))
        return Registration(new, known, changed)

    def registered_sha(self, run_id: str) -> str | None:
        with self.connect() as conn:
            row = conn.execute("SELECT trajectory_sha256 FROM runs WHERE run_id = ?", (run_id,)).fetchone()
        return None if row is None else row[0]

    # --- answers --------------------------------------------------------------------------------
    def save_answer(self, a: Answer, sha: str, replaces: str | None = None) -> GradeRow:
        """Insert or change ``a`` for the run version ``sha``, log it, commit; return the stored row.

        ``replaces`` is the ``updated_at`` of the answer the reviewer is changing; a first answer has
        None. A mismatch (the answer was made or changed in another window meanwhile) is an
        :class:`AnswerConflict` and nothing is written.
        """
        if a.mode not in MODES:
            raise ReviewError(f'unknown mode "{a.mode}" (known: {", ".join(MODES)})')
        t = now()
        with self.transaction() as conn:
            reg = conn.execute("SELECT trajectory_sha256 FROM runs WHERE run_id = ?", (a.run_id,)).fetchone()
            if reg is None:
                raise ReviewError(f'unknown run "{a.run_id}"')
            if reg[0] != sha:
                raise AnswerConflict(f"run {a.run_id} changed since it was registered: not graded", "changed")
            key = (a.run_id, sha, a.reviewer, a.mode, a.view)
            old = conn.execute("SELECT updated_at FROM answers WHERE run_id = ? AND trajectory_sha256 = ? AND "
                               "reviewer = ? AND mode = ? AND view = ?", key).fetchone()
            if (old[0] if old else None) != replaces:
                if old is None:
                    raise AnswerConflict("the answer you are changing no longer exists; reload the page", "stale-edit")
                raise AnswerConflict(
                    f"{a.reviewer} already answered this run at {old[0]} (in another window?); "
                    "reload to see and change that answer",
                    "answered" if replaces is None else "stale-edit",
                )
            if old is None:
                conn.execute(
                    "INSERT INTO answers (run_id, trajectory_sha256, reviewer, mode, view, grade, label, comment,"
                    " created_at, updated_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                    (*key, a.grade, a.label, a.comment, t, t),
                )
            else:
                conn.execute(
                    "UPDATE answers SET grade = ?, label = ?, comment = ?, updated_at = ? WHERE run_id = ? AND "
                    "trajectory_sha256 = ? AND reviewer = ? AND mode = ? AND view = ?",
                    (a.grade, a.label, a.comment, t, *key),
                )
            conn.execute("DELETE FROM skips WHERE run_id = ? AND trajectory_sha256 = ? AND reviewer = ? AND mode = ? "
                         "AND view = ?", key)
            self._log(conn, "answer" if old is None else "change", t, key, a)
            row = conn.execute(GRADES_SQL + " WHERE a.run_id = ? AND a.trajectory_sha256 = ? AND a.reviewer = ? AND "
                               "a.mode = ? AND a.view = ?", key).fetchone()
        return grade_row(row)

    def skip(self, run_id: str, sha: str, reviewer: str, mode: str, view: str) -> None:
        t = now()
        key = (run_id, sha, reviewer, mode, view)
        with self.transaction() as conn:
            conn.execute("INSERT OR REPLACE INTO skips (run_id, trajectory_sha256, reviewer, mode, view, at) "
                         "VALUES (?, ?, ?, ?, ?, ?)", (*key, t))
            self._log(conn, "skip", t, key, None)

    @staticmethod
    def _log(conn, event: str, t: str, key: tuple, a: Answer | None) -> None:
        conn.execute("INSERT INTO answer_log (at, event, run_id, trajectory_sha256, reviewer, mode, view, grade, "
                     "label, comment) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                     (t, event, *key, a and a.grade, a and a.label, a and a.comment))

    def counts(self, mode: str) -> dict[tuple[str, str], int]:
        """(run_id, view) -> answers for the run's registered trajectory in ``mode``, all reviewers."""
        with self.connect() as conn:
            rows = conn.execute("SELECT a.run_id, a.view, count(*) FROM answers a JOIN runs r ON r.run_id = a.run_id "
                                "AND r.trajectory_sha256 = a.trajectory_sha256 WHERE a.mode = ? "
                                "GROUP BY a.run_id, a.view", (mode,)).fetchall()
        return {(r[0], r[1]): r[2] for r in rows}

    def skips(self, reviewer: str, mode: str) -> dict[tuple[str, str], str]:
        """(run_id, view) -> when ``reviewer`` skipped it (current run versions only)."""
        with self.connect() as conn:
            rows = conn.execute("SELECT s.run_id, s.view, s.at FROM skips s JOIN runs r ON r.run_id = s.run_id AND "
                                "r.trajectory_sha256 = s.trajectory_sha256 WHERE s.reviewer = ? AND s.mode = ?",
                                (reviewer, mode)).fetchall()
        return {(r[0], r[1]): r[2] for r in rows}

    def grades(self, reviewer: str | None = None, mode: str | None = None) -> list[GradeRow]:
        """All answers (or one reviewer's in one mode), oldest first."""
        where, args = [], []
        if reviewer is not None:
            where.append("a.reviewer = ?")
            args.append(reviewer)
        if mode is not None:
            where.append("a.mode = ?")
            args.append(mode)
        sql = GRADES_SQL + (" WHERE " + " AND ".join(where) if where else "") + " ORDER BY a.created_at, a.id"
        with self.connect() as conn:
            return [grade_row(r) for r in conn.execute(sql, args).fetchall()]

    def log(self) -> list[dict]:
        with self.connect() as conn:
            return [dict(r) for r in conn.execute("SELECT * FROM answer_log ORDER BY id").fetchall()]

    def app_runs(self) -> list[dict]:
        """The registered app runs (path, sha256 registered) with how many answers each has."""
        with self.connect() as conn:
            return [dict(r) for r in conn.execute(
                "SELECT r.run_id, r.path, r.trajectory_sha256, r.action, count(a.id) AS answers FROM runs r "
                "LEFT JOIN answers a ON a.run_id = r.run_id AND a.trajectory_sha256 = r.trajectory_sha256 "
                "WHERE r.source = 'app' GROUP BY r.run_id ORDER BY r.run_id").fetchall()]

    def export(self, out: str | Path, force: bool = False) -> int:
        """Write every answer to ``out`` (.csv or .jsonl); returns the number of rows."""
        return write_grades(self.grades(), out, force=force)
