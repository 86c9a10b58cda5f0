"""Worker processes end when the process that started them dies, however it dies.

A render or evaluation worker waits on a queue its parent feeds. When the parent is killed (SIGKILL, the
OOM killer) nothing tells the worker: its siblings hold the queue's other end too, so it never reads an
end of file, and it waits forever with its simulator's memory (about 460 MB a render worker) and the
caller's stderr (a ``subprocess.communicate`` on the command then never returns). The resource tracker
multiprocessing starts for the parent ends by itself once the last worker holding its pipe is gone.

:func:`exit_with_parent` watches the parent from a daemon thread of the worker: when the worker's
parent is no longer ``parent`` (the kernel hands an orphan to init or a subreaper) the worker exits at
once (``os._exit``: there is nobody left to report to, and no cleanup of the parent's may run twice).
Polling, not ``PR_SET_PDEATHSIG``: that one fires when the *thread* that started the worker ends, and a
pool may be started by a short-lived thread (the teach page's training thread) yet outlive it.
"""

from __future__ import annotations

import os
import threading
import time

POLL_S = 0.25
"""How often a worker looks at its parent: a killed command's workers are gone within this."""


def exit_with_parent(parent: int, poll_s: float = POLL_S) -> None:
    """End this process (exit status 1) as soon as its parent is no longer the process ``parent``."""
    if os.getppid() != parent:  # died before this worker got here
        os._exit(1)

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(poll_s)
        os._exit(1)

    threading.Thread(target=watch, daemon=True, name="exit-with-parent").start()
