"""``python -m l2p_bullet``: the ``l2p-bullet`` command (the console script's start-up included)."""

import sys

from .launch import main

if __name__ == "__main__":
    sys.exit(main())
