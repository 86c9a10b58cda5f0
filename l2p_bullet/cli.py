"""The ``l2p-bullet`` command line.

Every command lives in ``l2p_bullet/commands/`` and imports only click at module level: torch and
pybullet are imported inside the command bodies, so ``l2p-bullet --help`` starts fast.
User errors (:class:`L2PError`, and a command's bad options) become a one-line message and exit code 2;
anything else is a bug and keeps its traceback.
"""

from __future__ import annotations

import re
import signal
import sys

import click

from . import PROGRAM, __version__, interrupted_while_starting
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
    def main(self, *args, **kwargs):
        """The interpreter's shutdown after the command is quiet too (Ctrl-C there: "interrupted", 130)."""
        try:
            return super().main(*args, **kwargs)
        finally:
            if PROGRAM and signal.getsignal(signal.SIGINT) is signal.default_int_handler:
                signal.signal(signal.SIGINT, interrupted_while_starting)

    def invoke(self, ctx: click.Context):
        try:
            # From here on Ctrl-C is a KeyboardInterrupt again (commands mark interrupted runs). Not sooner:
            # while click parses the group's options a KeyboardInterrupt would be click's "Aborted!", exit 1.
            if signal.getsignal(signal.SIGINT) is interrupted_while_starting:
                signal.signal(signal.SIGINT, signal.default_int_handler)
            return super().invoke(ctx)
        except L2PError as e:  # notes (a report put back after a failed rewrite) follow on the same line
            click.echo(f"error: {one_line('; '.join([str(e), *getattr(e, '__notes__', ())]))}", err=True)
            sys.exit(e.exit_code)
        except click.UsageError as e:  # a bad option of a command: one line too, like every other error
            where = f" (see: {e.ctx.command_path} --help)" if e.ctx is not None else ""
            click.echo(f"error: {one_line(e.format_message())}{where}", err=True)
            sys.exit(e.exit_code)
        except KeyboardInterrupt as e:
            click.echo("; ".join(["interrupted", *getattr(e, "__notes__", ())]), err=True)
            sys.exit(130)


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
    main()
