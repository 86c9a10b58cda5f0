"""Replacing a file a person's work lives in (demonstrations, a manifest, weights) so that no reader and
no crash ever sees half of it, and no two writers share a temporary file.

The new content goes to a temporary file of its own (``tempfile.mkstemp`` in the same folder: a unique
name, and the same file system, so the rename is atomic), is flushed to disk (``fsync``) and only then
renamed over the old file: after a crash or a power cut the path holds the old file or the new one,
never a truncated one. Two processes saving at once each write their own temporary file; the last rename
wins, but the file is always whole (a lock, such as the teach page's, decides who may save at all).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import IO


def _umask() -> int:
    """The process's umask, read without changing it where the system says it (setting it, even for an
    instant, would apply to files other threads create meanwhile)."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_file(path: str | os.PathLike, suffix: str = ".tmp") -> Iterator[IO[bytes]]:
    """``with atomic_file(p) as f: f.write(...)``: ``p`` is replaced by what was written once the block
    ends without an error; an error leaves ``p`` as it was and removes the temporary file. ``f.name`` is
    the temporary file's path (to read back what was written, inside the block). The file gets the mode a
    plain ``open`` would give it (mkstemp's are 0600: a shared plugin must stay readable)."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=path.parent)
    try:
        os.fchmod(fd, 0o666 & ~_umask())
        os.close(fd)
        with open(tmp, "wb") as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    _sync_folder(path.parent)


def write_atomic(path: str | os.PathLike, data: bytes | str) -> Path:
    """Replace ``path`` by ``data`` (text is written as UTF-8) as :func:`atomic_file` does."""
    with atomic_file(path) as f:
        f.write(data.encode("utf-8") if isinstance(data, str) else data)
    return Path(path)


def write_atomic_with(path: str | os.PathLike, writer: Callable[[IO[bytes]], None], suffix: str = ".tmp") -> Path:
    """Replace ``path`` by what ``writer(file)`` writes (numpy's ``savez`` and the like)."""
    with atomic_file(path, suffix) as f:
        writer(f)
    return Path(path)


def _sync_folder(folder: Path) -> None:
    """Make the rename itself durable (a folder's entries are flushed like a file's data)."""
    try:
        fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    except OSError:
        return
    try:
        with contextlib.suppress(OSError):
            os.fsync(fd)
    finally:
        os.close(fd)
