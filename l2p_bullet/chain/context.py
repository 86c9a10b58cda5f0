"""What the next clause's pronouns point back to, from the clause before it: its mover and anchor ("it", "the other
one"), the other of a pair shown before it, or the two objects one clause moved the same way ("both of them").
chain/clauses.py reads each clause in the context this module gives it."""

from __future__ import annotations

import re

from ..language import Command, Context
from ..language.synonyms import name_parts
from . import pointing


def context_of(previous: Command | None) -> Context | None:
    """What the next clause's pronouns point back to: the previous command's mover and anchor."""
    return Context(previous.mover, previous.anchor, described=described(previous)) if previous is not None else None


def described(command: Command) -> bool:
    """Whether the command's sentence described its mover ("the small red cube") rather than naming it (as written,
    or its words apart or by their first letters: "pen 2", "p2" for pen_2)."""
    parts = name_parts(command.mover)
    spelled = r"[\s_\-]*".join(f"(?:{re.escape(p)}|{re.escape(p[0])})" if p.isalpha() and len(p) > 1 else re.escape(p)
                                for p in parts)
    return not any(re.search(rf"(?<!\w){said}(?!\w)", command.sentence, re.IGNORECASE)
                   for said in (re.escape(command.mover), spelled) if said)


def context_after(previous: Command, pair: pointing.Shown | None) -> Context:
    """The next clause's context; after a pair was shown and one of it moved, "the other one" is the other of the
    pair ("You see A and C? Move A next to B and the other one next to D")."""
    other = next((o for o in pair.objects if o != previous.mover), None) if pair is not None else None
    if other is not None and previous.mover in pair.objects:
        return Context(previous.mover, other)
    return Context(previous.mover, previous.anchor, described=described(previous))


def two_moved(commands: list[Command]) -> pointing.Shown | None:
    """After one clause that moved two objects the same way ("Move O and Q away from the lamp"), what the next
    clause's pronouns point at: "both of them" are the two moved, "it" as the block to move is either (asked), "it"
    as the reference is the block they moved from; None after any other clause."""
    if len(commands) != 2 or commands[0].mover == commands[1].mover or commands[0].anchors != commands[1].anchors:
        return None
    return pointing.Shown((commands[0].mover, commands[1].mover), other=commands[0].anchor)
