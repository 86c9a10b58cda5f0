"""One place that pins torch's intra-op threads for a block of work and puts them back afterwards.

Why: the project's networks are tiny (one LSTM layer, a two-layer policy), so a second thread never
helps, and on a shared 2-core machine a spinning second thread made batch scoring 3-4x and a planner
step 5-10x slower (measured). torch is never imported here: code that has not imported it (``perform``
scores in numpy) pays nothing.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def torch_threads(n: int = 1) -> Iterator[None]:
    """Run the block with ``n`` torch threads if torch is loaded; restore the previous count after."""
    torch = sys.modules.get("torch")
    prev = torch.get_num_threads() if torch is not None else n
    if prev != n:
        torch.set_num_threads(n)
    try:
        yield
    finally:
        if prev != n:
            torch.set_num_threads(prev)
