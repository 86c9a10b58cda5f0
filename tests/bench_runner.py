"""Run benchmark scripts, each in a process of its own forked from this one once it has imported what they import.

``tests/test_benchmarks.py`` runs every benchmark at its smallest size as a fresh process; started one by one, each
paid for Python, numpy, torch, PyBullet and the package again (about 2 CPU s of a 3-10 s smallest run). Here they
are imported once, and each benchmark runs as ``python benchmarks/bench_x.py ARGS`` would: a process of its own
(forked, so nothing one benchmark sets is seen by the next), its own working folder, ``sys.argv`` and
``sys.path[0]``, run as ``__main__`` (``multiprocessing``'s spawned workers re-import it by its file, as from a
script), its exit code its own. Usage::

    python bench_runner.py JOBS.json

where JOBS.json lists ``{"script": PATH, "args": [...], "cwd": DIR, "out": PREFIX}``; each job's output goes to
``PREFIX.stdout`` and ``PREFIX.stderr``, and this prints one JSON line per job: ``{"out": PREFIX, "returncode": N}``.
"""

from __future__ import annotations

import json
import os
import runpy
import signal
import sys
import traceback

TIMEOUT_S = 300
"""Seconds one benchmark may run (its own process is killed past it)."""


def _child(job: dict) -> int:
    os.chdir(job["cwd"])
    for fd, suffix in ((1, "stdout"), (2, "stderr")):
        out = os.open(f"{job['out']}.{suffix}", os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(out, fd)
        os.close(out)
    signal.alarm(TIMEOUT_S)
    sys.argv = [job["script"], *job["args"]]
    sys.path[0] = os.path.dirname(os.path.abspath(job["script"]))
    try:
        runpy.run_path(job["script"], run_name="__main__")
        code = 0
    except SystemExit as e:  # as the interpreter ends on it: a number is the exit code, anything else is printed
        if e.code is None or isinstance(e.code, int):
            code = e.code or 0
        else:
            print(e.code, file=sys.stderr)
            code = 1
    except BaseException:
        traceback.print_exc()
        code = 1
    sys.stdout.flush()
    sys.stderr.flush()
    return code


def main() -> None:
    jobs = json.loads(open(sys.argv[1]).read())
    import matplotlib  # noqa: F401 - what the benchmarks import, once
    import numpy  # noqa: F401
    import pybullet  # noqa: F401
    import torch  # noqa: F401

    import l2p_bullet.cli  # noqa: F401
    import l2p_bullet.pipeline  # noqa: F401

    for job in jobs:
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            code = 1
            try:
                code = _child(job)
            finally:
                os._exit(code)
        _, status = os.waitpid(pid, 0)
        print(json.dumps({"out": job["out"], "returncode": os.waitstatus_to_exitcode(status)}), flush=True)


if __name__ == "__main__":
    main()
