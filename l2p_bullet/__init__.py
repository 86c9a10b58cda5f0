"""l2p-bullet: teach a simulated robot arm spatial actions from human demonstrations.

Kept import-light on purpose: ``l2p-bullet --help`` must not import torch or pybullet.

The first lines install the start-up Ctrl-C handler, before anything else runs: ``_signal`` is CPython's
built-in C module (no Python code runs to import it), while ``import signal`` executes ``signal.py`` and
its enum conversion, several milliseconds in which a Ctrl-C would raise a KeyboardInterrupt traceback. ``os`` and ``sys`` are already imported by CPython's start-up, so importing them runs no code either.
"""

import _signal
import os as _os
import sys as _sys


def interrupted_while_starting(signum, frame) -> None:  # noqa: ARG001 - a signal handler's signature
    """Ctrl-C before the command runs (its imports take ~0.3 s): nothing has started, so stop quietly
    (exit 130) instead of printing a KeyboardInterrupt traceback from inside an import.
    ``cli.main`` hands SIGINT back to KeyboardInterrupt once the command is about to run."""
    _os.write(2, b"interrupted\n")
    _os._exit(130)


def _is_program() -> bool:
    """True when this process is the ``l2p-bullet`` command (the console script or ``python -m
    l2p_bullet.cli``), not a test or a library importing the package."""
    if _os.path.basename(_sys.argv[0]) == "l2p-bullet":
        return True
    argv = list(getattr(_sys, "orig_argv", ()))
    return any(a == "-m" and b == "l2p_bullet.cli" for a, b in zip(argv, argv[1:], strict=False))


PROGRAM = _is_program()
if PROGRAM and _signal.getsignal(_signal.SIGINT) is _signal.default_int_handler:
    _signal.signal(_signal.SIGINT, interrupted_while_starting)

__version__ = "0.1.0"
