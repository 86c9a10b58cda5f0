"""A CLI runner for the fuzz tests, in its own process with a hard memory limit (RLIMIT_AS).

Reads one JSON request per line on stdin: ``{"args": [...], "cwd": "..."}``; runs ``l2p-bullet ARGS``
in-process (click's CliRunner: fast, no interpreter start per example) and answers one JSON line:
exit code, output, and the type of any exception that escaped the CLI (a traceback). An allocation past
the limit raises MemoryError inside the CLI, which escapes as a traceback: the test sees it.

With ``--fork`` each request gets a worker of its own: a process forked from this one once it has started up,
whose limit is set there as a fresh worker's would be (its start-up footprint plus the margin), that answers the
one request (with its ``limit``) and ends. For the tests whose inputs must not share a worker, without a Python
started and the CLI imported for each (1.3 CPU s).
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
    if "--fork" in sys.argv[2:]:
        print(json.dumps({"ready": True, "limit": None}), file=out, flush=True)
        for line in sys.stdin:
            out.write(_forked(line, margin, lambda args: CliRunner().invoke(cli, args)) + "\n")
            out.flush()
        return
    limit = _limit(margin)
    print(json.dumps({"ready": True, "limit": limit}), file=out, flush=True)
    for line in sys.stdin:
        print(_answer(json.loads(line), lambda args: CliRunner().invoke(cli, args)), file=out, flush=True)


def _limit(margin: int) -> int:
    """Cap this process's address space at its footprint now plus ``margin``; the cap."""
    with open("/proc/self/status") as f:
        vm = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize:"))
    limit = vm + margin
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    return limit


def _answer(req: dict, invoke, **extra) -> str:
    os.chdir(req["cwd"])
    r = invoke(req["args"])
    exc = None
    if r.exception is not None and not isinstance(r.exception, SystemExit):
        exc = "".join(traceback.format_exception(r.exception))[-3000:]
    return json.dumps({"exit_code": r.exit_code, "output": r.output[-5000:], "exception": exc,
                       "peak_rss": _peak_rss(), **extra})


def _forked(line: str, margin: int, invoke) -> str:
    """The answer of a process forked for this request alone (its own limit, :func:`_limit`); a process that ends
    without answering is answered for, as an exception."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read)
        code = 1
        try:
            limit = _limit(margin)
            with os.fdopen(write, "w") as f:
                f.write(_answer(json.loads(line), invoke, limit=limit))
            code = 0
        finally:
            os._exit(code)
    os.close(write)
    with os.fdopen(read) as f:
        answer = f.read()
    _, status = os.waitpid(pid, 0)
    if answer:
        return answer
    return json.dumps({"exit_code": None, "output": "", "peak_rss": 0, "limit": 0,
                       "exception": f"the worker forked for the request ended without answering ({status})"})


def _peak_rss() -> int:
    """This process's own peak resident memory (bytes): VmHWM belongs to the address space made at exec.
    getrusage's ru_maxrss is not: Linux carries it over from the parent at fork, so a worker started by a
    pytest process that had grown to 1.9 GB reported a 1.9 GB peak whatever it did."""
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmHWM:"))


if __name__ == "__main__":
    main()

