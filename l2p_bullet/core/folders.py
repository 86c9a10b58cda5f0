"""What a folder holds, asked before a command writes into it or reads it as a run.

- :func:`check_writable`: can this process write there at all? Asked before minutes of training, so that a
  PermissionError does not come after them.
- :func:`unfinished`: did the run in a run folder finish writing? ``export`` and ``review`` skip one that did
  not (an interrupted render leaves a 0-byte frame, and people would grade half a motion).

runfolder.py makes and replaces run folders; this module only reads them.
"""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import L2PError, RunFolderError
from .runfiles import INTERRUPTED, read_json, run_folder_command, run_folder_state
from .runfolder import _parked


def unfinished(folder: Path) -> str | None:
    """Why run folder ``folder`` is no run to read (review, export), as the note that skips it; None when
    its run finished writing.

    Only a run that did not finish writing is skipped: one interrupted (Ctrl-C), one that broke off with an
    error (summary.json ``"ok": false``), one killed before it was marked finished, or one still being
    written; it may lack frames or hold a half-written image, and people would grade half a motion. A
    finished run whose verdict failed (``"success": false``) is kept: a failed attempt is still an episode
    to grade or learn from. A folder this tool did not write (no marker, no summary) is read as before."""
    state = run_folder_state(folder)
    if state == "running":
        return f"skipped {folder}: its run is still being written; wait for it to finish"
    summary = read_json(folder / "summary.json")
    failed = isinstance(summary, dict) and summary.get("ok") is False
    if not failed and state != "incomplete":
        return None
    command = run_folder_command(folder) or "perform"
    again = "perform it again" if command == "perform" else f"run `l2p-bullet {command}` again"
    stage = summary.get("failed_stage") if failed else None
    if stage == INTERRUPTED:
        return f"skipped {folder}: its run was interrupted; {again}"
    if failed:
        return f"skipped {folder}: its run failed (stage {stage or 'unknown'}); {again}"
    parked = _parked(folder)
    if parked:  # a --force run killed outright: the run it replaced waits aside, the next claim restores it
        return (f"skipped {folder}: its run did not finish; the earlier run it was replacing is in {parked[0]} "
                f"(the next l2p-bullet command into {folder} puts it back)")
    return f"skipped {folder}: its run did not finish; {again}"


def check_writable(path: str | os.PathLike, option: str = "--out", error: type[L2PError] = RunFolderError) -> None:
    """Refuse a folder this process cannot write into (or, not made yet, whose nearest existing parent it
    cannot), before any long work starts: a PermissionError after minutes of training loses them."""
    probe = Path(path)
    while not probe.exists() and not probe.is_symlink() and probe.parent != probe:
        probe = probe.parent
    if probe.exists() and not probe.is_dir():
        raise error(f"{option} {path}: {probe} exists and is not a folder; choose another {option}")
    if not os.access(probe, os.W_OK | os.X_OK):
        raise error(f"{option} {path}: cannot write into {probe} (permission denied); choose another {option}")
