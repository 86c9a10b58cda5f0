"""Run folders: nothing a person wrote is ever deleted, and two runs never share a folder.

Every command that writes a run folder (perform, plan, replay, and whatever comes next) gets it from
:func:`run_folder` (a context manager) or :func:`prepare_run_folder`, so the rules hold everywhere:

- A new folder is made with ``mkdir`` while holding an exclusive lock on its parent folder, and gets a
  marker file (:data:`MARKER`) on which the run holds a second lock (``flock``) until it ends. Two runs
  started together into one ``--out``: one gets the folder, the other a :class:`RunFolderError`.
- An existing folder is only ever *replaced*, never emptied in place, and only when it is a run folder
  this tool wrote: it has the marker (or, from before the marker, a summary.json of ours) and nothing
  else than the files a run writes. Never the current directory or one of its parents, never a
  symbolic link, never a folder holding a file of someone else (``thesis.txt``).
- A finished run folder is only ever replaced by the command that wrote it (``export --force`` never replaces a
  perform run), and never when it is, holds or lies inside an input of the command (``inputs``).
- A finished run folder is replaced only with ``force``; an *incomplete* one (its run was interrupted
  or killed: no summary.json, or ``"failed_stage": "interrupted"``) and an empty folder are replaced
  without asking. A folder whose run is still going (its marker is locked) is never touched.
- The old folder is renamed to a hidden sibling first and deleted after the new one exists: a crash in
  between loses nothing that was not going to be replaced anyway. Under :func:`run_folder`, a *finished*
  run replaced with ``force`` is kept aside until the new run ends, and put back if the new one is
  interrupted (Ctrl-C, or SIGTERM / SIGHUP, which the command line turns into the same interruption):
  stopping a ``--force`` run half-way must not cost the run it was replacing. A run killed outright
  (SIGKILL, a power cut) cannot put it back: the next claim of the folder does, before anything else
  touches it (:func:`_restore_parked`); a run set aside is never deleted unless the run that replaced it
  finished.
- A run that ends by an exception leaves a summary.json with ``"ok": false``: ``failed_stage`` is
  ``"interrupted"`` for Ctrl-C (KeyboardInterrupt) and the stage the caller recorded otherwise.

Callers validate every option *before* asking for the folder: a typo must never cost a previous run.
Locks are POSIX ``flock`` (released by the kernel when a process dies, so a killed run never blocks
the next one). What a folder holds and which state it is in (the marker, the files a run writes, summary.json)
is read and written by ``runfiles.py``; this module makes, locks, replaces and puts back folders.
"""

from __future__ import annotations

import contextlib
import fcntl
import glob
import json
import os
import re
import shutil
import time
import uuid
from collections.abc import Iterator
from pathlib import Path

from ..errors import RunFolderError, listed
from .runfiles import (
    INTERRUPTED,
    MARKER,
    RUN_FILES,
    add_to_summary,
    mark_failed,
    run_folder_command,
    run_folder_state,
    unknown_files,
    write_summary,
)

__all__ = [  # the run folder's own names; what a folder holds (runfiles.py) is re-exported for every caller
    "INTERRUPTED", "LEGACY_COMMANDS", "MARKER", "RUN_FILES", "add_to_summary", "claim_run_folder",
    "finish_run_folder", "mark_failed", "prepare_run_folder", "run_folder", "run_folder_command", "run_folder_state",
    "write_summary",
]


@contextlib.contextmanager
def _parent_lock(parent: Path) -> Iterator[None]:
    """Serialise the creation and replacement of run folders inside ``parent`` (a few milliseconds)."""
    fd = os.open(parent, os.O_RDONLY | os.O_DIRECTORY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # closing releases the lock


class _Claim:
    """A run folder this process made, with the marker's lock held until :meth:`release`."""

    def __init__(self, path: Path, command: str, files: tuple[str, ...]):
        self.path = path
        self.fd = -1
        self.replaced: Path | None = None  # a finished run kept aside until this one ends (run_folder)
        marker = {"tool": "l2p-bullet", "command": command, "id": uuid.uuid4().hex, "pid": os.getpid(),
                  "started": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "files": list(files)}
        fd = os.open(path / MARKER, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o644)
        fcntl.flock(fd, fcntl.LOCK_EX)
        os.write(fd, (json.dumps(marker) + "\n").encode())
        self.fd = fd

    def finish(self) -> None:
        """Record in the marker that the run ended (well or with an error), so it is not "incomplete"."""
        if self.fd < 0:
            return
        try:
            with open(self.path / MARKER, encoding="utf-8") as f:
                marker = json.load(f)
            marker["finished"] = time.strftime("%Y-%m-%dT%H:%M:%S%z")
            data = (json.dumps(marker) + "\n").encode()
            os.ftruncate(self.fd, 0)
            os.pwrite(self.fd, data, 0)
        except (OSError, ValueError):
            pass

    def release(self) -> None:
        if self.fd >= 0:
            os.close(self.fd)
            self.fd = -1

    def restore_replaced(self) -> tuple[bool, str | None]:
        """Put back the finished run this one replaced (the new folder, incomplete, is deleted): (whether it is
        back, a note for the user; None when there was none to put back). Called when the new run was interrupted, while
        this run
        still holds its marker's lock and under the parent's lock, so no other run can take the folder in
        between (a claim checks both)."""
        old, self.replaced = self.replaced, None
        if old is None or not old.is_dir():
            return False, None
        with _parent_lock(self.path.parent):
            shutil.rmtree(self.path, ignore_errors=True)
            try:
                if self.path.exists() or self.path.is_symlink():
                    raise OSError("the new run's folder could not be removed")
                old.rename(self.path)
            except OSError:  # the earlier run stays aside under a name no later claim drops: say where
                kept = old.with_name(old.name.replace(".replaced-", ".kept-", 1))
                with contextlib.suppress(OSError):
                    old.rename(kept)
                    old = kept
                return False, f"the earlier run could not be put back: it is kept in {old}"
        return True, f"{self.path} holds the earlier run again (nothing was replaced)"

    def drop_replaced(self) -> None:
        """The new run ended: the run it replaced goes."""
        if self.replaced is not None:
            shutil.rmtree(self.replaced, ignore_errors=True)
            self.replaced = None


_HELD: list[_Claim] = []
"""Claims made by :func:`prepare_run_folder`: held until the process ends."""


def _describe(path: Path, state: str, option: str = "--out") -> str:
    if state == "running":
        return f"run folder {path} is being written by another l2p-bullet run right now; choose another {option}"
    if state == "finished":
        return (f"run folder {path} already holds a finished run; choose another {option}, or pass --force to "
                "replace that run (--force only ever replaces a run folder l2p-bullet wrote)")
    if path.is_symlink():
        return f"{path} is a symbolic link; give the folder itself as {option} (links are never replaced)"
    if not path.is_dir():
        return f"{path} exists and is not a folder; choose another {option}"
    names = unknown_files(path, RUN_FILES)
    return (
        f"{path} already exists and holds files l2p-bullet did not write ({listed(names)}); choose another {option} "
        "(--force never deletes them)"
    )


def _protected(path: Path) -> bool:
    """The current directory, any of its parents, the home folder and the file system's root."""
    real = path.resolve()
    cwd = Path.cwd().resolve()
    try:
        home = Path.home().resolve()
    except (RuntimeError, KeyError):
        home = None
    return real == cwd or real in cwd.parents or real == home or real == Path(real.anchor)


LEGACY_COMMANDS = ("perform", "plan", "replay", "run")
"""The commands that wrote run folders before the marker existed (and "run", a caller naming none): only
they may replace such a folder."""


def _overlap(path: Path, inputs: tuple[str | Path, ...]) -> Path | None:
    """The input that ``path`` is, holds or lies inside (compared after resolving links), if any."""
    real = path.resolve()
    for given in inputs:
        inp = Path(given).resolve()
        if real == inp or inp in real.parents or real in inp.parents:
            return Path(given)
    return None


def _check_replace(path: Path, state: str, command: str, inputs: tuple[str | Path, ...]) -> None:
    """Refuse to replace a folder of another command, or one that is, holds or lies in an input."""
    if state == "missing":
        return
    inp = _overlap(path, inputs)
    if inp is not None:
        raise RunFolderError(f"{path} is, holds or lies inside {inp}, an input of this command; nothing is "
                             "replaced (not even with --force): choose another folder for the output", path, state)
    if state != "finished":  # an interrupted run's folder holds nothing finished: replaced as before
        return
    owner = run_folder_command(path)
    if owner != command and not (owner is None and command in LEGACY_COMMANDS):
        raise RunFolderError(f"{path} holds a run of `l2p-bullet {owner or 'perform'}`, not of `{command}`; "
                             "--force only replaces a folder written by the same command: choose another folder",
                             path, state)


def claim_run_folder(out: str | Path | None, *, force: bool = False, prefix: str = "run", root: str | Path = "runs",
                     command: str = "", files: tuple[str, ...] = (), inputs: tuple[str | Path, ...] = (),
                     keep_replaced: bool = False, option: str = "--out") -> _Claim:
    """Make the run folder (the rules of the module docstring) and lock it; the caller releases the claim.

    ``inputs``: the files and folders the command reads; the run folder never is, holds or lies in one.
    ``keep_replaced``: a finished run replaced with ``force`` stays aside as the claim's ``replaced`` (the
    caller then restores or drops it) instead of being deleted at once. ``option``: how the command names
    the folder in its messages (``--out``; ``OUT`` for export's argument)."""
    if out is None:
        base = Path(root) / f"{prefix}-{time.strftime('%Y%m%d-%H%M%S')}"
        _mkdirs(base.parent)
        with _parent_lock(base.parent):
            path, n = base, 1
            while path.exists() or path.is_symlink():
                n += 1
                path = base.with_name(f"{base.name}-{n}")
            return _make(path, command or prefix, files, option)
    path = Path(out)
    if str(out).strip() == "" or path.name in ("", ".", "..") or _protected(path):
        raise RunFolderError(f'"{out}" cannot be a run folder (it is the current folder, one of its parents, '
                             f"the home folder or the root); choose a new folder name for {option}")
    _mkdirs(path.parent)
    trash = None
    with _parent_lock(path.parent):
        back = _restore_parked(path, option)
        state = run_folder_state(path)
        _check_replace(path, state, command or prefix, inputs)
        if state in ("foreign", "running") or (state == "finished" and not force):
            raise RunFolderError(_describe(path, state, option) + (f" ({back})" if back else ""), path, state)
        if state in ("empty", "incomplete", "finished"):
            trash = path.with_name(f".{path.name}.replaced-{uuid.uuid4().hex[:8]}")
            try:
                path.rename(trash)
            except OSError as e:
                raise RunFolderError(f"cannot replace run folder {path}: {e.strerror or e}") from None
        claim = _make(path, command or prefix, files, option)
    if trash is not None and keep_replaced and state == "finished":
        claim.replaced = trash
    elif trash is not None:
        shutil.rmtree(trash, ignore_errors=True)
    return claim


def _parked(path: Path) -> list[Path]:
    """The runs set aside for ``path`` by a ``--force`` run (``.NAME.replaced-XXXXXXXX``)."""
    pattern = re.compile(rf"\.{re.escape(path.name)}\.replaced-[0-9a-f]{{8}}")  # exactly this folder's, not
    return sorted(old for old in path.parent.glob(f".{glob.escape(path.name)}.replaced-*")  # ".a.replaced-x.
                  if pattern.fullmatch(old.name) and old.is_dir() and not old.is_symlink())  # replaced-..."


def _restore_parked(path: Path, option: str = "--out") -> str | None:
    """Put back the finished run that a killed ``--force`` run set aside for ``path`` (SIGKILL gives no
    chance to do it then); a note saying so, None when nothing lay aside. Called under the parent's lock,
    before the folder's state is read: what is restored is then judged like any finished run (a plain run
    refuses it, ``--force`` sets it aside again), so it is never lost to the next command.

    The killed run's own folder holds nothing finished (it is incomplete, empty or missing) and goes. A
    folder whose run is still going keeps what lies aside (its run restores or drops it). When the run
    that replaced it finished (killed between finishing and dropping it), the replacement happened as
    asked and what lies aside goes. Anything else (a folder of someone else's, two runs aside) is refused:
    a person decides which run is the one to keep."""
    parked = _parked(path)
    if not parked:
        return None
    state = run_folder_state(path)
    if state == "running":
        return None
    if state == "finished" and len(parked) == 1:
        shutil.rmtree(parked[0], ignore_errors=True)
        return None
    if state not in ("missing", "empty", "incomplete") or len(parked) > 1:
        raise RunFolderError(f"{path} has an earlier run set aside beside it ({listed([p.name for p in parked])}) by a "
                             f"--force run that was killed, and {path} holds {_what(state)}: nothing is replaced; "
                             f"move the run to keep to {path} (or elsewhere) and the other away, or choose another "
                             f"{option}", path, state)
    try:
        if state != "missing":
            shutil.rmtree(path)
        parked[0].rename(path)
    except OSError as e:
        raise RunFolderError(f"cannot put back the earlier run {parked[0]} that a killed --force run set aside: "
                             f"{e.strerror or e}; move it to {path} yourself", path, state) from None
    return f"the earlier run, set aside by a --force run that was killed, is back in {path}"


def _what(state: str) -> str:
    return {"finished": "a finished run", "foreign": "files l2p-bullet did not write",
            "incomplete": "an unfinished run", "empty": "nothing"}.get(state, "a run")


def _mkdirs(folder: Path) -> None:
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise RunFolderError(f"cannot create the folder {folder}: {e.strerror or e}") from None
    if not folder.is_dir():
        raise RunFolderError(f"{folder} is not a folder")


def _make(path: Path, command: str, files: tuple[str, ...], option: str = "--out") -> _Claim:
    try:
        path.mkdir()
        return _Claim(path, command, files)
    except FileExistsError:
        state = run_folder_state(path)
        raise RunFolderError(_describe(path, state, option), path, state) from None
    except OSError as e:
        raise RunFolderError(f"cannot create run folder {path}: {e.strerror or e}") from None


def prepare_run_folder(out: str | Path | None, force: bool = False, prefix: str = "run",
                       root: str | Path = "runs", command: str = "") -> Path:
    """Create and return a run folder (``out=None``: ``runs/<prefix>-YYYYmmdd-HHMMSS[-n]``).

    The folder stays locked until the process ends or :func:`finish_run_folder` is called. Prefer
    :func:`run_folder`, which also marks an interrupted run; this form is for callers that cannot wrap
    their work in a ``with``. A folder whose run never called ``finish_run_folder`` counts as incomplete.
    """
    claim = claim_run_folder(out, force=force, prefix=prefix, root=root, command=command)
    _HELD.append(claim)
    return claim.path


def finish_run_folder(path: Path) -> None:
    """End a :func:`prepare_run_folder` run: mark it finished and release its lock."""
    for claim in [c for c in _HELD if c.path == Path(path)]:
        claim.finish()
        claim.release()
        _HELD.remove(claim)


@contextlib.contextmanager
def run_folder(out: str | Path | None, *, force: bool = False, prefix: str = "run", root: str | Path = "runs",
               command: str = "", files: tuple[str, ...] = (), inputs: tuple[str | Path, ...] = (),
               option: str = "--out", restore_on_error: bool = False) -> Iterator[Path]:
    """``with run_folder(out, force=force, prefix="perform") as folder: ...`` -- the one way to get a run folder.

    Inside the block the folder is locked (another run cannot take or replace it). If the block ends by
    an exception, summary.json is left with ``"ok": false``: ``"failed_stage": "interrupted"`` for
    Ctrl-C; otherwise a summary the block already wrote with ``ok: false`` is kept, and a missing one is
    written naming the error. ``files``: patterns of extra files this command writes (see RUN_FILES);
    ``inputs``: what the command reads (never replaced, see :func:`claim_run_folder`). A finished run that
    ``force`` replaces is put back if the block is interrupted (the KeyboardInterrupt then carries a note
    saying so, which the command line prints); with ``restore_on_error`` also when it ends by any other
    error (a report: its earlier version rather than a failed one).
    """
    claim = claim_run_folder(out, force=force, prefix=prefix, root=root, command=command, files=files, inputs=inputs,
                             keep_replaced=True, option=option)
    try:
        yield claim.path
        claim.finish()
    except KeyboardInterrupt as e:
        back, note = claim.restore_replaced()  # before the lock is released: see restore_replaced
        if note is not None:
            e.add_note(note)
        if back:
            raise
        mark_failed(claim.path, INTERRUPTED, f"interrupted ({str(e) or 'Ctrl-C'}) before the run finished")
        raise
    except BaseException as e:
        back, note = claim.restore_replaced() if restore_on_error else (False, None)  # a report: its old one
        if note is not None:
            e.add_note(note)
        if back:
            raise
        mark_failed(claim.path, None, str(e) or type(e).__name__)
        claim.finish()
        raise
    finally:
        claim.release()
        claim.drop_replaced()


