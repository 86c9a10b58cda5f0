"""The ``l2p-bullet`` console script's entry point: the command line's start-up, then :mod:`.cli`.

Ctrl-C in the first ~0.3 s (click and the commands being imported) must stop quietly ("interrupted",
exit 130), not print a KeyboardInterrupt traceback from inside an import. So :func:`main` installs that
handler before it imports anything heavy, and this module imports only ``_signal`` (CPython's built-in C
module: no Python code runs to import it, while ``import signal`` executes ``signal.py`` and its enum
conversion, several milliseconds in which a Ctrl-C raised a traceback), ``sys`` (already imported by
CPython's start-up) and the package (import-light: the handler itself is defined there). Importing it, or the package,
installs nothing: only running the program
does, so a test or a library that imports ``l2p_bullet`` keeps its own Ctrl-C.
"""

import _signal
import sys as _sys

from . import interrupted_while_starting


def main() -> object:
    """Run the command line as the ``l2p-bullet`` program (the console script calls this)."""
    if _signal.getsignal(_signal.SIGINT) is _signal.default_int_handler:
        _signal.signal(_signal.SIGINT, interrupted_while_starting)
    try:
        from .cli import program

        return program("l2p-bullet")
    finally:
        # the interpreter's shutdown after the command is quiet too (Ctrl-C there: "interrupted", 130)
        if _signal.getsignal(_signal.SIGINT) is _signal.default_int_handler:
            _signal.signal(_signal.SIGINT, interrupted_while_starting)


if __name__ == "__main__":  # pragma: no cover
    _sys.exit(main())
