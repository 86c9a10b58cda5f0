"""The ``l2p-bullet`` command line.

Every command lives in ``l2p_bullet/commands/`` and imports only click at module level: torch and
pybullet are imported inside the command bodies, so ``l2p-bullet --help`` starts fast.
User errors (:class:`L2PError`, and a command's bad options) become a one-line message and exit code 2;
anything else is a bug and keeps its traceback. The program's start-up (a quiet Ctrl-C while this module
is imported) is :mod:`.launch`'s, the console script's entry point.

SIGTERM and SIGHUP (``kill``, a closed terminal or ssh session) stop a command the way Ctrl-C does: the
command unwinds as from a KeyboardInterrupt, so a run is marked interrupted and a ``--force`` run puts
back the run it was replacing, instead of the process vanishing half-way (exit status 128 + the signal).
"""

from __future__ import annotations

import contextlib
import os
import re
import signal
import sys
import threading
from collections.abc import Iterator

import click

from . import __version__, interrupted_while_starting
from .commands import (
    actions,
    arms,
    evaluate,
    export,
    learn,
    manners,
    perform,
    plan,
    recognize,
    replay,
    review,
    teach,
)
from .errors import L2PError

STOPPING_SIGNALS = (signal.SIGTERM, signal.SIGHUP)
"""Signals that stop a command as Ctrl-C does (the run is marked interrupted, a replaced run put back)."""


class Stopped(KeyboardInterrupt):
    """A command stopped by SIGTERM or SIGHUP: unwinds as Ctrl-C does (every ``except KeyboardInterrupt``
    that marks a run interrupted or restores a replaced one runs), exits 128 + the signal's number."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


def _stop(signum, frame) -> None:  # noqa: ARG001 - a signal handler's signature
    raise Stopped(signum)


@contextlib.contextmanager
def _stopping_signals_interrupt() -> Iterator[None]:
    """While the command runs, SIGTERM and SIGHUP raise :class:`Stopped` (where they kill the process
    by default); the handlers the caller had come back after it. Only the main thread can set them."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = {s: signal.getsignal(s) for s in STOPPING_SIGNALS}
    for s, h in old.items():
        if h is signal.SIG_DFL:  # a caller that chose to ignore them (nohup) keeps its choice
            signal.signal(s, _stop)
    try:
        yield
    finally:
        for s, h in old.items():
            if h is signal.SIG_DFL:
                signal.signal(s, h)


_INVISIBLE = re.compile("[\x80-\x9f\xad\u061c\u180e\u200b-\u200f\u2028-\u202e\u2060-\u2069\ufeff\ufff9-\ufffb]")
"""Characters a terminal shows as nothing or that reorder what follows (C1 controls, zero-width and
bidirectional marks): quoted from a user's file they would hide or reverse part of a message, so an error
shows them escaped (``\\u202e``)."""


def one_line(message: str, limit: int = 1000) -> str:
    """An error message as one printable line: file contents it quotes may hold newlines or control
    characters, and an error must never scroll a terminal or fake a second line."""
    text = re.sub(r"[\x00-\x1f\x7f]", lambda m: " " if m.group() in "\n\r\t" else "?", message)
    text = _INVISIBLE.sub(lambda m: f"\\u{ord(m.group()):04x}", text)
    return text if len(text) <= limit else text[: limit - 3] + "..."


class _Group(click.Group):
    def invoke(self, ctx: click.Context):
        try:
            # From here on Ctrl-C is a KeyboardInterrupt again (commands mark interrupted runs). Not sooner:
            # while click parses the group's options a KeyboardInterrupt would be click's "Aborted!", exit 1.
            if signal.getsignal(signal.SIGINT) is interrupted_while_starting:
                signal.signal(signal.SIGINT, signal.default_int_handler)
            with _stopping_signals_interrupt():
                return super().invoke(ctx)
        except L2PError as e:  # notes (a report put back after a failed rewrite) follow on the same line
            click.echo(f"error: {one_line('; '.join([str(e), *getattr(e, '__notes__', ())]))}", err=True)
            sys.exit(e.exit_code)
        except click.UsageError as e:  # a bad option of a command: one line too, like every other error
            where = f" (see: {e.ctx.command_path} --help)" if e.ctx is not None else ""
            click.echo(f"error: {one_line(e.format_message())}{where}", err=True)
            sys.exit(e.exit_code)
        except KeyboardInterrupt as e:
            how = f"interrupted ({e})" if isinstance(e, Stopped) else "interrupted"
            click.echo("; ".join([how, *getattr(e, "__notes__", ())]), err=True)
            raise Interrupted(128 + e.signum if isinstance(e, Stopped) else 130) from None


class Interrupted(SystemExit):
    """The exit of a command stopped by Ctrl-C (or SIGTERM, SIGHUP) once it has unwound: its run marked
    interrupted, its workers stopped, its worlds closed. :func:`program` ends the process there."""


def program(prog_name: str = "l2p-bullet") -> object:
    """Run the command line as a program. After a stop the process ends at once (``os._exit``, streams
    flushed) rather than through the interpreter's shutdown: everything the command owned is already
    closed, and the interpreter's shutdown could still end the process by a signal instead of exiting 130
    (measured: a rendering perform stopped by Ctrl-C under load printed "interrupted", then died by
    SIGINT). In-process callers (tests, click's runner) call :data:`main` and get the SystemExit."""
    try:
        return main(prog_name=prog_name)
    except Interrupted as e:
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os._exit(int(e.code))


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="l2p-bullet")
def main() -> None:
    """Teach a simulated robot arm spatial actions from human demonstrations.

    \b
    Examples:
      l2p-bullet perform "move A around B"
      l2p-bullet replay --demo around:0
      l2p-bullet actions
    """


for _module in (perform, plan, replay, learn, actions, arms, manners, review, evaluate, export, teach, recognize):
    for _cmd in _module.COMMANDS:
        main.add_command(_cmd)


if __name__ == "__main__":  # pragma: no cover
    program()
