"""Starting a command the way a terminal does, so that the tests' Ctrl-C reaches it as KeyboardInterrupt."""

from __future__ import annotations

import signal


def ctrl_c_as_at_a_terminal() -> None:
    """``preexec_fn`` for the tests that send SIGINT: a child inherits an ignored SIGINT from a test run
    started in the background (a shell's ``&``, some CI runners), and Python then never raises
    KeyboardInterrupt; a person at a terminal has the default, which this restores."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
