"""One clause of a chain: the record every module of the chain passes around, and how errors name it.

Kept apart from clauses.py (which splits a sentence into clauses) so that composite.py, which makes a
composite's clauses, and clauses.py, which asks composite.py first, both build on it without importing
each other.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..errors import L2PError
from ..language import Command

MAX_CLAUSES = 10
"""Most clauses in one chain: past a handful of steps errors compound (CALVIN judges chains of five)."""


@dataclass(frozen=True)
class Group:
    """A composite's place in a chain ("make a row of A, B and C, then ..."): its action and objects in the
    order named; the clauses it expands to carry it, so the whole is judged as a row."""

    action: str
    objects: tuple[str, ...]
    text: str


@dataclass(frozen=True)
class Clause:
    """One step of a chain: its 1-based ``index``, its own ``text`` and what it asks for."""

    index: int
    text: str
    command: Command
    target: Any = None  # a composite's place for the mover: scene -> [x, y, yaw] (chain/composite.py), or None
    group: Group | None = None  # the composite this clause is a step of, or None

    def label(self) -> str:
        """How errors and captions name the clause: 'clause 2 ("slide C past A")'."""
        return f'clause {self.index} ("{self.text}")'


def named(e: L2PError, where: str, after: str = "") -> L2PError:
    """``e`` (same type and attributes: an InfeasibleError keeps its ``check``) with its message prefixed
    (and ``after`` appended)."""
    e.args = (f"{where}: {e}{after}",) + e.args[1:]
    return e
