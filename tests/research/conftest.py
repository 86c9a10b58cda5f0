"""research/ lives beside the package, not in it: the repository root goes on the path so its tests import it
from any working directory."""

import sys
from pathlib import Path

ROOT = str(Path(__file__).resolve().parents[2])
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)
