"""Creating PyBullet clients without the C library's chatter on stdout and stderr.

PyBullet prints "pybullet build time" on import and "argv[0]=" on connect straight to the C-level
file descriptors, and the EGL plugin prints more. Printed into the middle of a command's
output (or a JSON answer) that breaks things, so every client is made inside :func:`quiet_stdout`.
"""

from __future__ import annotations

import contextlib
import os
import sys


def _flush_c_stdio() -> None:
    try:
        import ctypes

        ctypes.CDLL(None).fflush(None)
    except (OSError, AttributeError):  # pragma: no cover - no libc: nothing buffered we can reach
        pass


@contextlib.contextmanager
def quiet_stdout():
    """Send file descriptors 1 and 2 to /dev/null for the duration (Python's streams flushed first).

    Only ever wraps an import or a connect: nothing a user needs to see is printed there.
    """
    fds = [1, 2]  # the C library writes to the descriptors, whatever Python's sys.stdout is now
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (AttributeError, ValueError):  # pragma: no cover - a closed or odd stream
            pass
    saved = [os.dup(fd) for fd in fds]
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        for fd in fds:
            os.dup2(devnull, fd)
        yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        _flush_c_stdio()  # C stdio buffers what it printed; flush it while it still goes nowhere
        for fd, keep in zip(fds, saved, strict=True):
            os.dup2(keep, fd)
            os.close(keep)
        os.close(devnull)


def new_client():
    """A fresh DIRECT ``BulletClient`` with pybullet_data on its search path."""
    with quiet_stdout():
        import pybullet as pb
        import pybullet_data
        from pybullet_utils import bullet_client

        client = bullet_client.BulletClient(connection_mode=pb.DIRECT)
    client.setAdditionalSearchPath(pybullet_data.getDataPath())
    return client
