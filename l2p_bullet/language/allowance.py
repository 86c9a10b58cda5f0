"""A reading allowed only inside a block: the last tries of a sentence every other reading refused
(chain/last_tries.py) switch one on for the readers below them, and a sentence read without it reads as before."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar


class Allowance:
    """One reading's switch, off by default, per thread and task (a ContextVar)."""

    def __init__(self, name: str) -> None:
        self._on: ContextVar[bool] = ContextVar(name, default=False)

    @contextmanager
    def inside(self) -> Iterator[None]:
        """The reading allowed inside the block."""
        token = self._on.set(True)
        try:
            yield
        finally:
            self._on.reset(token)

    def now(self) -> bool:
        """Whether the reading is allowed now."""
        return self._on.get()
