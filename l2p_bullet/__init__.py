"""l2p-bullet: teach a simulated robot arm spatial actions from human demonstrations.

Kept import-light on purpose: ``l2p-bullet --help`` must not import torch or pybullet. Importing the
package changes nothing in the process (no signal handler, no environment): the command line's start-up,
which installs :func:`interrupted_while_starting`, is :func:`l2p_bullet.launch.main`, the console script's
entry point. ``os`` is already imported by CPython's start-up, so importing it here runs no code.
"""

import os as _os


def interrupted_while_starting(signum, frame) -> None:  # noqa: ARG001 - a signal handler's signature
    """Ctrl-C before the command runs (its imports take ~0.3 s): nothing has started, so stop quietly
    (exit 130) instead of printing a KeyboardInterrupt traceback from inside an import.
    ``cli.main`` hands SIGINT back to KeyboardInterrupt once the command is about to run."""
    _os.write(2, b"interrupted\n")
    _os._exit(130)


__version__ = "0.1.0"
