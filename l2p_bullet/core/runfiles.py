"""What a run folder holds, read and written without claiming it: the marker that makes a folder ours
(:data:`MARKER`), the files a run may write (:data:`RUN_FILES`), the state a folder is in
(:func:`run_folder_state`: the rules of ``runfolder.py`` are decided on it) and its summary.json
(:func:`write_summary`, :func:`add_to_summary`, :func:`mark_failed`). Making, locking and replacing run
folders is ``runfolder.py``'s; this module never creates or deletes a folder."""

from __future__ import annotations

import contextlib
import fcntl
import fnmatch
import json
import os
from pathlib import Path

from .contracts import dumps_json

MARKER = ".l2p-run.json"
"""The file that makes a folder a run folder of ours: which command wrote it, when, by which process."""

RUN_FILES: tuple[str, ...] = (
    MARKER, "summary.json", "trajectory.json", "plan.json", "plan.png", "video.mp4", "video.gif",
    "contact_sheet.png", "frames", "frames/*.png",
)
"""Relative paths (fnmatch patterns) a run may write. A folder holding anything else is not replaced.
A command that writes other files lists them in ``run_folder(..., files=...)``: they are recorded in
the marker, so that a later ``--force`` recognises them."""

INTERRUPTED = "interrupted"


def run_folder_state(path: Path) -> str:
    """What an existing folder is, for the rules of ``runfolder.py``: ``"missing"``, ``"empty"``, ``"running"`` (its run
    holds the lock), ``"incomplete"``, ``"finished"`` (run folders of ours) or ``"foreign"``."""
    if not path.exists() and not path.is_symlink():
        return "missing"
    if path.is_symlink() or not path.is_dir():
        return "foreign"
    entries = list(path.iterdir())
    if not entries:
        return "empty"
    marker = read_json(path / MARKER)
    summary = read_json(path / "summary.json")
    ours = isinstance(marker, dict) and marker.get("tool") == "l2p-bullet"
    plan = read_json(path / "plan.json") if not ours else None
    legacy = (isinstance(summary, dict) and summary.get("schema") == 1 and "timings_s" in summary) or (
        isinstance(plan, dict) and plan.get("schema") == 1 and "path" in plan and "planner" in plan)
    if not (ours or legacy):
        return "foreign"
    extra = tuple(marker.get("files", ())) if ours and isinstance(marker.get("files"), list) else ()
    if unknown_files(path, RUN_FILES + tuple(str(f) for f in extra)):
        return "foreign"
    if ours and locked(path / MARKER):
        return "running"
    interrupted = isinstance(summary, dict) and summary.get("failed_stage") == INTERRUPTED
    if ours:
        return "finished" if marker.get("finished") and not interrupted else "incomplete"
    return "incomplete" if interrupted else "finished"


def read_json(p: Path) -> object:
    """A run folder's JSON file (the marker, summary.json), or None when it is missing, a link, over 10 MB or not
    JSON: what lies in a folder is read to decide about it, never trusted to be ours."""
    try:
        if p.is_symlink() or not p.is_file() or p.stat().st_size > 10_000_000:
            return None
        return json.loads(p.read_text(encoding="utf-8"))
    except (OSError, ValueError, RecursionError):
        return None


def unknown_files(folder: Path, patterns: tuple[str, ...]) -> list[str]:
    """Relative paths under ``folder`` that no pattern matches (symbolic links always count)."""
    unknown = []
    for root, dirs, files in os.walk(folder):
        for name in dirs + files:
            full = Path(root) / name
            rel = full.relative_to(folder).as_posix()
            if full.is_symlink() or not any(fnmatch.fnmatchcase(rel, p) for p in patterns):
                unknown.append(rel)
    return sorted(unknown)


def locked(marker: Path) -> bool:
    """True while some process holds the marker's lock (its run is going on)."""
    try:
        fd = os.open(marker, os.O_RDONLY | os.O_NOFOLLOW)
    except OSError:
        return False
    try:
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
        return False
    except BlockingIOError:
        return True
    finally:
        os.close(fd)


def run_folder_command(path: Path) -> str | None:
    """The command that wrote run folder ``path`` (its marker's), ``None`` for a folder from before the marker."""
    marker = read_json(path / MARKER)
    return str(marker.get("command")) if isinstance(marker, dict) and marker.get("tool") == "l2p-bullet" else None


def mark_failed(folder: Path, stage: str | None, error: str) -> None:
    """Leave ``folder/summary.json`` saying the run failed (``stage`` None: keep a failure already recorded)."""
    path = folder / "summary.json"
    summary = read_json(path)
    summary = summary if isinstance(summary, dict) else {"schema": 1}
    if stage is None and summary.get("ok") is False:
        return
    summary.update({"ok": False, "failed_stage": stage or summary.get("failed_stage") or "unknown",
                    "error": error[:2000]})
    with contextlib.suppress(OSError):
        write_summary(path, summary)


def add_to_summary(folder: Path, fields: dict) -> None:
    """Add ``fields`` to ``folder/summary.json`` (made when missing), keeping what it holds."""
    summary = read_json(folder / "summary.json")
    summary = summary if isinstance(summary, dict) else {"schema": 1}
    with contextlib.suppress(OSError):
        write_summary(folder / "summary.json", {**summary, **fields})


def write_summary(path: Path, summary: dict) -> None:
    """Write a run folder's summary.json (numpy numbers and paths become plain JSON, NaN becomes null)."""
    path.write_text(dumps_json(summary, indent=1) + "\n")
