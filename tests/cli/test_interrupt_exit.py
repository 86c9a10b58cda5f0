"""A command stopped by Ctrl-C ends the process once it has unwound, without the interpreter's shutdown
(whose teardown of the simulator, the EGL driver and a pool's threads could end it by a signal instead)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

PROGRAM = """
import atexit, sys
atexit.register(lambda: print("the interpreter's shutdown ran", file=sys.stderr))
from l2p_bullet import cli

@cli.main.command("stopped")
def stopped():
    print("half-way", flush=False)  # buffered: the exit must still flush it
    raise {error}

sys.argv = ["l2p-bullet", "stopped"]
cli.program()
"""


@pytest.mark.parametrize(("error", "code", "says"), [("KeyboardInterrupt", 130, "interrupted\n"),
                                                     ("cli.Stopped(15)", 143, "interrupted (SIGTERM)\n")])
def test_a_stopped_command_exits_at_once_with_its_status(error, code, says):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    p = subprocess.run([sys.executable, "-c", PROGRAM.format(error=error)], capture_output=True, text=True,
                       env=env, timeout=60)
    assert (p.returncode, p.stdout, p.stderr) == (code, "half-way\n", says)


def test_in_process_callers_still_get_the_exit_status():
    from click.testing import CliRunner

    from l2p_bullet import cli

    @cli.main.command("stopped-in-process")
    def stopped():
        raise KeyboardInterrupt

    try:
        r = CliRunner().invoke(cli.main, ["stopped-in-process"])
    finally:
        cli.main.commands.pop("stopped-in-process")
    assert r.exit_code == 130 and "interrupted" in r.output
