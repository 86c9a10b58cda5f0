"""A CLI runner for the fuzz tests, in its own process with a hard memory limit (RLIMIT_AS).

Reads one JSON request per line on stdin: ``{"args": [...], "cwd": "..."}``; runs ``l2p-bullet ARGS``
in-process (click's CliRunner: fast, no interpreter start per example) and answers one JSON line:
exit code, output, and the type of any exception that escaped the CLI (a traceback). An allocation past
the limit raises MemoryError inside the CLI, which escapes as a traceback: the test sees it.
"""

from __future__ import annotations

import json
import os
import resource
import sys
import traceback


def main() -> None:
    margin = int(sys.argv[1])
    out = os.fdopen(os.dup(1), "w")  # the protocol's channel; fd 1 itself goes to /dev/null so that
    devnull = os.open(os.devnull, os.O_WRONLY)  # nothing a library prints can corrupt it
    os.dup2(devnull, 1)
    import matplotlib  # noqa: F401 - plan's plot: loaded before measuring the start-up footprint
    from click.testing import CliRunner

    from l2p_bullet.cli import main as cli
    from l2p_bullet.plugins import registry

    registry.discover()
    with open("/proc/self/status") as f:
        vm = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize:"))
    limit = vm + margin
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    print(json.dumps({"ready": True, "limit": limit}), file=out, flush=True)
    for line in sys.stdin:
        req = json.loads(line)
        os.chdir(req["cwd"])
        r = CliRunner().invoke(cli, req["args"])
        exc = None
        if r.exception is not None and not isinstance(r.exception, SystemExit):
            exc = "".join(traceback.format_exception(r.exception))[-3000:]
        peak = _peak_rss()
        print(json.dumps({"exit_code": r.exit_code, "output": r.output[-5000:], "exception": exc,
                          "peak_rss": peak}), file=out, flush=True)


def _peak_rss() -> int:
    """This process's own peak resident memory (bytes): VmHWM belongs to the address space made at exec.
    getrusage's ru_maxrss is not: Linux carries it over from the parent at fork, so a worker started by a
    pytest process that had grown to 1.9 GB reported a 1.9 GB peak whatever it did."""
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmHWM:"))


if __name__ == "__main__":
    main()

