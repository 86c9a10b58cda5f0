"""The local backend: W worker processes, each running one task at a time and kept for the whole evaluation.

Why not ``concurrent.futures.ProcessPoolExecutor``: when one of its workers dies (a segfault in the
simulator, the OOM killer) the whole pool is broken and every pending future fails, without saying
which task killed it. Here each worker has its own pipe and the parent knows which task each one holds:
a dead worker's task becomes a row with the error, a fresh worker takes its place, the evaluation goes
on. Workers ignore SIGINT, so Ctrl-C reaches the parent alone, which stops them and keeps every row
already committed.

Workers are started with ``spawn`` (a clean interpreter: nothing of the parent's state, threads or open
files is inherited), the way Ray starts its workers too, and like Ray's each worker's numerical libraries
run one thread (``OMP_NUM_THREADS=1`` ..., unless the user set them): W workers are meant for W cores.
Measured on 2 cores: with numpy's OpenBLAS free to start a thread per core, one worker already used 1.4
cores (0.39 CPU s per 0.27 s run) and two workers reached only 1.44x one; Ray, which pins its workers to
one thread, reached 1.81x.
"""

from __future__ import annotations

import contextlib
import multiprocessing as mp
import os
import signal
from collections import deque
from collections.abc import Callable, Iterable
from multiprocessing.connection import wait

from ..core.lifeline import exit_with_parent
from .tasks import Task
from .worker import Worker, error_row

OnRow = Callable[[dict], None]

THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
"""Thread counts of numpy's BLAS (and OpenMP code) that a spawned worker reads at import."""


@contextlib.contextmanager
def _one_thread_per_worker():
    """While a worker is started: its environment says one thread (only where the user said nothing)."""
    unset = [k for k in THREAD_VARIABLES if k not in os.environ]
    for k in unset:
        os.environ[k] = "1"
    try:
        yield
    finally:
        for k in unset:
            os.environ.pop(k, None)


def _worker_main(conn, parent: int | None = None) -> None:
    """A worker process: receive a task, send its row, until told to stop (None) or the pipe closes, or
    until ``parent`` dies (in the middle of a task too: ``core/lifeline.py``)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if parent is not None:
        exit_with_parent(parent)

    worker = Worker()
    try:
        while True:
            try:
                task = conn.recv()
            except (EOFError, OSError):
                return
            if task is None:
                return
            conn.send(worker.run(task))
    finally:
        worker.close()


class _Slot:
    def __init__(self, ctx) -> None:
        self.conn, child = ctx.Pipe()
        self.proc = ctx.Process(target=_worker_main, args=(child, os.getpid()), daemon=True)
        with _one_thread_per_worker():  # spawn copies the environment at start
            self.proc.start()
        child.close()
        self.task: Task | None = None

    def stop(self, wait_s: float = 2.0) -> None:
        try:
            if self.proc.is_alive():
                self.conn.send(None)
        except (OSError, BrokenPipeError):
            pass
        self.proc.join(wait_s)
        if self.proc.is_alive():
            self.proc.terminate()
            self.proc.join(wait_s)
        self.conn.close()


def run_pool(tasks: Iterable[Task], workers: int, on_row: OnRow) -> None:
    """Run ``tasks`` on ``workers`` processes; ``on_row`` gets every row as it arrives (in finishing order)."""
    ctx = mp.get_context("spawn")
    pending = deque(tasks)
    slots = [_Slot(ctx) for _ in range(max(1, min(workers, len(pending))))] if pending else []
    try:
        while pending or any(s.task is not None for s in slots):
            for s in slots:
                if s.task is None and pending:
                    s.task = pending.popleft()
                    s.conn.send(s.task)
            busy = [s for s in slots if s.task is not None]
            ready = wait([s.conn for s in busy] + [s.proc.sentinel for s in busy])
            for i, s in enumerate(slots):
                if s.task is None or (s.conn not in ready and s.proc.sentinel not in ready):
                    continue
                row = None
                try:
                    if s.conn.poll():
                        row = s.conn.recv()
                except (EOFError, OSError):
                    row = None
                if row is None and s.proc.is_alive():
                    continue  # the sentinel fired spuriously; the answer is still coming
                if row is None:  # the worker died while running this task
                    s.proc.join(1.0)
                    row = error_row(s.task, "WorkerDied",
                                    f"the worker process died while running this task (exit code {s.proc.exitcode})")
                    s.conn.close()
                    slots[i] = _Slot(ctx)
                else:
                    s.task = None
                on_row(row)
    finally:
        for s in slots:
            s.stop()
