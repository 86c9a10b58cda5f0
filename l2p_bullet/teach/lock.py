"""One ``teach`` page per plugin folder, across processes.

Two teach servers on one plugin each read the demos file, append their demonstration and write it back:
the second write drops the first one's demonstration. A lock per process cannot see the other server, so
the plugin folder holds a lock file (:data:`LOCK_FILE`) that a teach server keeps locked (``flock``) while
it serves; a second one is refused, naming the first one's process and address. The kernel releases the
lock when the process ends however it ends, so a killed server never blocks the next one.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
from dataclasses import dataclass
from pathlib import Path

from ..errors import TeachError

LOCK_FILE = ".l2p-teach.lock"
"""In the plugin project's folder (next to pyproject.toml): who is teaching this plugin now."""


@dataclass
class TeachLock:
    """The plugin folder's lock, held until :meth:`release` (or the process ends)."""

    path: Path
    fd: int

    def release(self) -> None:
        if self.fd >= 0:
            with contextlib.suppress(OSError):
                os.ftruncate(self.fd, 0)
            os.close(self.fd)
            self.fd = -1


def claim_plugin(root: Path, url: str) -> TeachLock:
    """Lock plugin folder ``root`` for this process's teach page at ``url``; :class:`TeachError` naming
    the other server (its pid and address) when one is teaching it already."""
    path = Path(root) / LOCK_FILE
    try:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC, 0o644)
    except OSError as e:
        raise TeachError(f"cannot lock {path} (one teach page per plugin): {e.strerror or e}") from None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        other = _holder(fd)
        os.close(fd)
        who = f"pid {other.get('pid', '?')}, {other.get('url', 'address unknown')}"
        raise TeachError(f"another l2p-bullet teach ({who}) is teaching {root} already; two pages on one plugin "
                         "would overwrite each other's demonstrations: use that page, or stop it first") from None
    os.ftruncate(fd, 0)
    os.pwrite(fd, (json.dumps({"pid": os.getpid(), "url": url}) + "\n").encode(), 0)
    return TeachLock(path, fd)


def _holder(fd: int) -> dict:
    try:
        d = json.loads(os.pread(fd, 4096, 0).decode("utf-8"))
    except (OSError, ValueError):
        return {}
    return d if isinstance(d, dict) else {}
