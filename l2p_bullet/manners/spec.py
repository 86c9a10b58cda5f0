"""What a manner of motion is, in one place: :class:`MannerSpec`, declared by each manner's module as ``MANNER``.

The paper's second extension: "slide A around B" and "carry A around B" follow the same learned path in
different ways. A manner declares the verbs that ask for it and which of the embodiment's motions performs
it (``motion``: slide, carry or push, the algorithms in ``embodiment/manners.py``), whether the planner must
keep the mover's path clear of the other objects (``airborne`` False) and the physical signature its rule
judge checks (``signature``, the rules in ``judge/manners.py``). A third-party manner is a module with its
own ``MANNER`` (its own verbs, one of the motions) registered in the entry-point group ``l2p_bullet.manners``,
as the built-ins are in the project's pyproject.

Pure declarations on the lowest floor above ``errors``: every stage may read them.
"""

from __future__ import annotations

from dataclasses import dataclass

MOTIONS = ("slide", "carry", "push")
"""The embodiment's motions a manner may name (``embodiment/manners.py``)."""
SIGNATURES = ("on-table", "lifted", "no-grasp")
"""The physical signatures a manner's rule judge may check (``judge/manners.py``)."""


@dataclass(frozen=True)
class MannerSpec:
    """One manner of motion.

    ``verbs``: the words that start a sentence asking for it: one word ("carry"), a phrase ("pick up"),
    or a phrase with a gap for the mover ("lift ... and put": "lift A and put it next to B").
    ``default``: the manner of a verb no manner claims (one manner may say so: slide).
    ``loose``: the verbs among ``verbs`` that say where the block goes and not how ("move", "put"); ``over``:
    the airborne manner a loose verb's block is carried in where the other objects leave this manner no way
    round ("move A around B" with C in the way: slide has none, so A is carried over C). A verb that says how
    ("slide", "drag") keeps its manner and is refused.
    """

    name: str
    verbs: tuple[str, ...]
    motion: str
    signature: str
    description: str = ""
    airborne: bool = False  # the block passes above the other objects: the planner tests only where it is set down
    default: bool = False
    loose: tuple[str, ...] = ()
    over: str | None = None

    def __post_init__(self) -> None:
        if self.motion not in MOTIONS:
            raise ValueError(f'manner "{self.name}": motion must be one of {", ".join(MOTIONS)} (got {self.motion!r})')
        if self.signature not in SIGNATURES:
            raise ValueError(f'manner "{self.name}": signature must be one of {", ".join(SIGNATURES)} '
                             f"(got {self.signature!r})")
        if not self.verbs or not all(isinstance(v, str) and v.strip() for v in self.verbs):
            raise ValueError(f'manner "{self.name}" declares no verbs')
        stray = [v for v in self.loose if v not in self.verbs]
        if stray:
            raise ValueError(f'manner "{self.name}": its loose verbs must be among its verbs (not {", ".join(stray)})')
