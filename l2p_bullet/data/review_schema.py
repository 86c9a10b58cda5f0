"""The review database's schema: numbered migrations, applied in order, each in one transaction.

The version is SQLite's ``PRAGMA user_version``. A database at version k gets migrations k+1..N when it
is opened; one written by a newer l2p-bullet (version > N) is refused before anything is written to
it (:class:`~l2p_bullet.errors.SchemaVersionError`). Migrations are only ever appended: a released
step is never edited, so every database goes through the same steps.

Connections: WAL journal (readers never block the writer, one file plus its -wal/-shm companions while
open), ``synchronous=FULL`` (a committed answer survives a power cut, not only a crash), foreign keys
on, and a busy timeout so concurrent writers queue instead of failing.
"""

from __future__ import annotations

import sqlite3
from pathlib import Path

from ..errors import ReviewError, SchemaVersionError

MIGRATIONS: tuple[str, ...] = (
    # 1: the review app: runs, one current answer per (run version, reviewer, mode, view), every
    #    submission in an append-only log, skips.
    """
    CREATE TABLE runs (
        run_id TEXT PRIMARY KEY,
        path TEXT NOT NULL,
        trajectory_sha256 TEXT NOT NULL,
        action TEXT NOT NULL DEFAULT '',
        sentence TEXT NOT NULL DEFAULT '',
        registered_at TEXT NOT NULL
    );
    CREATE TABLE answers (
        id INTEGER PRIMARY KEY,
        run_id TEXT NOT NULL REFERENCES runs(run_id),
        trajectory_sha256 TEXT NOT NULL,
        reviewer TEXT NOT NULL,
        mode TEXT NOT NULL CHECK (mode IN ('graded', 'blind')),
        view TEXT NOT NULL CHECK (view IN ('3d', '2d')),
        grade INTEGER CHECK (grade IS NULL OR grade BETWEEN 0 AND 10),
        label TEXT,
        comment TEXT NOT NULL DEFAULT '',
        created_at TEXT NOT NULL,
        updated_at TEXT NOT NULL,
        UNIQUE (run_id, trajectory_sha256, reviewer, mode, view)
    );
    CREATE INDEX answers_by_item ON answers (run_id, mode, view);
    CREATE TABLE answer_log (
        id INTEGER PRIMARY KEY,
        at TEXT NOT NULL,
        event TEXT NOT NULL CHECK (event IN ('answer', 'change', 'skip')),
        run_id TEXT NOT NULL,
        trajectory_sha256 TEXT NOT NULL,
        reviewer TEXT NOT NULL,
        mode TEXT NOT NULL,
        view TEXT NOT NULL,
        grade INTEGER,
        label TEXT,
        comment TEXT
    );
    CREATE TABLE skips (
        run_id TEXT NOT NULL REFERENCES runs(run_id),
        trajectory_sha256 TEXT NOT NULL,
        reviewer TEXT NOT NULL,
        mode TEXT NOT NULL,
        view TEXT NOT NULL,
        at TEXT NOT NULL,
        PRIMARY KEY (run_id, trajectory_sha256, reviewer, mode, view)
    );
    """,
    # 2: the original study's grades live next to the app's: where a run came from.
    """
    ALTER TABLE runs ADD COLUMN source TEXT NOT NULL DEFAULT 'app';
    ALTER TABLE runs ADD COLUMN demo_id TEXT;
    ALTER TABLE runs ADD COLUMN folder TEXT;
    CREATE UNIQUE INDEX runs_by_demo ON runs (source, demo_id) WHERE demo_id IS NOT NULL;
    """,
)
SCHEMA_VERSION = len(MIGRATIONS)


def connect(path: str | Path, create: bool = True) -> sqlite3.Connection:
    """An autocommit connection (transactions are explicit: ``BEGIN IMMEDIATE`` ... ``COMMIT``).

    ``create=False``: the file must exist (SQLite would otherwise make a new, empty database in its place)."""
    try:
        target = str(path) if create else f"{Path(path).resolve().as_uri()}?mode=rw"
        conn = sqlite3.connect(target, timeout=30.0, isolation_level=None, check_same_thread=False, uri=not create)
        conn.row_factory = sqlite3.Row
        conn.execute("PRAGMA busy_timeout = 30000")
        if _is_foreign(conn):  # before WAL, which would rewrite someone's file
            conn.close()
            raise _foreign(path)
        conn.execute("PRAGMA journal_mode = WAL")
        conn.execute("PRAGMA synchronous = FULL")
        conn.execute("PRAGMA foreign_keys = ON")
    except sqlite3.DatabaseError as e:
        raise ReviewError(f"{path} is not a review database SQLite can open ({e})") from None
    return conn


def version(conn: sqlite3.Connection) -> int:
    return int(conn.execute("PRAGMA user_version").fetchone()[0])


def migrate(conn: sqlite3.Connection, path: str | Path, target: int = SCHEMA_VERSION) -> int:
    """Bring the database to ``target`` (default: the newest); returns the version it was at."""
    try:
        found = version(conn)
    except sqlite3.DatabaseError as e:
        raise ReviewError(f"{path} is not a review database ({e})") from None
    if _is_foreign(conn):  # first: someone else's user_version is not a newer review schema
        raise _foreign(path)
    if found > SCHEMA_VERSION:
        raise SchemaVersionError(str(path), found, SCHEMA_VERSION)
    for n in range(found + 1, target + 1):
        try:
            conn.execute("BEGIN IMMEDIATE")
            if version(conn) >= n:  # another process migrated meanwhile
                conn.execute("ROLLBACK")
                continue
            for statement in _statements(MIGRATIONS[n - 1]):
                conn.execute(statement)
            conn.execute(f"PRAGMA user_version = {n:d}")
            conn.execute("COMMIT")
        except sqlite3.DatabaseError as e:
            if conn.in_transaction:
                conn.execute("ROLLBACK")
            raise ReviewError(f"cannot migrate review database {path} to schema {n}: {e}") from None
    return found


def _statements(script: str) -> list[str]:
    return [s.strip() for s in script.split(";") if s.strip()]


def _foreign(path: str | Path) -> ReviewError:
    return ReviewError(f"{path} is an SQLite file of something else (it has tables but no review schema); "
                       "give another --db")


def _is_foreign(conn: sqlite3.Connection) -> bool:
    """Someone else's SQLite file: tables at version 0 (a new database has none), or a ``user_version``
    without the review schema's ``runs`` table (migration 1 makes both in one transaction). Many programs set
    ``user_version`` themselves, so a version alone does not make a file ours: at 1 it would be migrated, above
    :data:`SCHEMA_VERSION` refused as a newer l2p-bullet's, and switched to WAL before either."""
    tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
    return bool(tables) if version(conn) == 0 else "runs" not in tables
