"""A Ctrl-C while the ruckig extension initialises waits until it has loaded (raised inside the
extension's initialisation it killed a rendering perform by SIGSEGV instead of exiting 130)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

PROGRAM = """
import os, signal, sys
signal.signal(signal.SIGINT, signal.default_int_handler)
assert "ruckig" not in sys.modules

def ctrl_c_as_the_import_starts(event, args):
    if event == "import" and args[0] == "ruckig":
        os.kill(os.getpid(), signal.SIGINT)

sys.addaudithook(ctrl_c_as_the_import_starts)
from l2p_bullet.embodiment import smoothing
import numpy as np
try:
    smoothing.time_parameterise(np.array([[0.0, 0.0, 0.0, 0.0], [0.1, 0.0, 0.0, 0.0]]), smoothing.Limits(), 1 / 240)
    print("not interrupted")
except KeyboardInterrupt:
    print("interrupted once loaded:", "ruckig" in sys.modules)
"""


def test_ctrl_c_during_the_ruckig_import_is_raised_once_it_has_loaded():
    p = subprocess.run([sys.executable, "-c", PROGRAM], capture_output=True, text=True, timeout=60,
                       env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert p.stdout == "interrupted once loaded: True\n", p.stdout + p.stderr
