"""The evaluation folder (``evaluate --out``): what evaluate writes there, and the checks made before it writes.

An evaluation folder is not a run folder (core/runfolder.py): it grows over several calls (``--resume``,
``--report``) instead of being replaced, so it has no marker. The project's rules hold nonetheless:

- nothing is written into an existing folder that holds files evaluate did not write (a perform run, a
  person's ``notes.txt``): a new evaluation needs a new folder, an empty one, or one of ours;
- every option is checked before the folder is made, so a typo leaves nothing behind;
- an evaluation is the settings stored in ``results.sqlite``: a table without them (a start that failed
  before storing them) holds no evaluation, and the next start reuses the folder;
- ``--parquet`` never overwrites a file, and its folder is checked before the evaluation runs (not after).
"""

from __future__ import annotations

import contextlib
import fnmatch
import importlib.util
import json
import os
import sqlite3
import tempfile
from pathlib import Path

from ..errors import EvaluationError, MissingExtraError, listed
from .results import DB_NAME, LOCK_NAME

EVALUATION_FILES: tuple[str, ...] = (
    DB_NAME, f"{DB_NAME}-wal", f"{DB_NAME}-shm", f"{DB_NAME}-journal", LOCK_NAME, "runs",
    "report.json", "confusion_judges.png", "confusion_models.png", "clauses.jsonl", "*.parquet",
)
"""The top-level names (fnmatch patterns) evaluate writes in its folder: the results table (and SQLite's
side files), the lock, ``runs/`` (kept run folders), the reports (report.py, chains.py) and a Parquet
copy a user put beside them. Anything else belongs to someone else."""


def foreign_files(folder: Path) -> list[str]:
    """Names in ``folder`` that evaluate did not write (symbolic links always count), sorted."""
    return sorted(p.name for p in folder.iterdir()
                  if p.is_symlink() or not any(fnmatch.fnmatchcase(p.name, pat) for pat in EVALUATION_FILES)
                  or (p.name == "runs" and not p.is_dir()))


def stored_settings(folder: Path) -> dict | None:
    """The settings of the evaluation in ``folder``; None when it holds none. Reads only (creates nothing)."""
    path = folder / DB_NAME
    if not path.exists():
        return None
    if not path.is_file():
        raise EvaluationError(f"{path} is not a results table (not a file); choose another --out")
    try:
        db = sqlite3.connect(path, timeout=10)
        try:
            row = db.execute("SELECT value FROM meta WHERE key = 'config'").fetchone()
        finally:
            db.close()
    except sqlite3.OperationalError as e:
        if "no such table" in str(e):  # an empty file, or a start that stopped before making its tables
            return None
        raise EvaluationError(f"cannot read the results table {path}: {e}") from None
    except sqlite3.DatabaseError as e:
        raise EvaluationError(f"cannot read the results table {path}: {e}") from None
    try:
        value = None if row is None else json.loads(row[0])
    except (TypeError, ValueError):
        raise EvaluationError(f"cannot read the results table {path}: its stored settings are not JSON") from None
    return value if isinstance(value, dict) else None


def check_out_folder(folder: Path, *, resume: bool) -> dict | None:
    """Before anything is written: ``resume`` needs an evaluation in ``folder`` (its settings are returned);
    a new one needs a folder that is missing, empty, or holds nothing but evaluate's files and no settings."""
    if folder.exists() and not folder.is_dir():
        raise EvaluationError(f"{folder} exists and is not a folder; choose another --out")
    stored = stored_settings(folder) if folder.is_dir() else None
    if resume:
        if stored is None:
            raise EvaluationError(f"nothing to resume in {folder}: it holds no evaluation to resume (no "
                                  f"{DB_NAME} with settings); start one without --resume")
        return stored
    if stored is not None:
        raise EvaluationError(f"{folder} already holds an evaluation: pass --resume to continue it, or choose "
                              "another --out")
    if folder.is_dir():
        names = foreign_files(folder)
        if names:
            raise EvaluationError(
                f"{folder} already exists and holds files l2p-bullet did not write ({listed(names)}); "
                "choose another --out"
            )
    return None


def check_parquet_path(path: str | Path, folder: Path) -> Path:
    """Refuse a ``--parquet`` path that exists or cannot be written, before the evaluation runs.

    Its folder must exist and take a file (tried with a temporary file, removed at once: permissions
    alone say nothing for root or a read-only file system), unless it is the evaluation folder itself,
    which evaluate makes. pyarrow must be installed."""
    p = Path(path)
    if p.exists() or p.is_symlink():
        raise EvaluationError(f"--parquet {p} already exists (it is never overwritten): remove it or choose "
                              "another --parquet path")
    parent = p.parent
    if importlib.util.find_spec("pyarrow") is None:
        raise MissingExtraError("pyarrow", "export", "writing Parquet (--parquet)")
    if not parent.exists() and os.path.abspath(parent) == os.path.abspath(folder):
        return p
    if not parent.is_dir():
        raise EvaluationError(f"cannot write --parquet {p}: the folder {parent} does not exist; create it or "
                              "choose another --parquet path")
    try:
        fd, probe = tempfile.mkstemp(prefix=".l2p-parquet-", dir=parent)
    except OSError as e:
        raise EvaluationError(f"cannot write --parquet {p} in {parent}: {e.strerror or e}; choose another "
                              "--parquet path") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)
    return p
