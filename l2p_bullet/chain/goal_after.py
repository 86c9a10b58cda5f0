"""A motion and then where it should end, said in one clause: "slide A toward B until it is beside it", "Keep pushing
the bear toward the plank until they're side by side". The end said after "until" / "so that" is the clause's goal,
in the motion's manner and pace; kept apart from the readings of objects shown or pointed at (chain/pointing.py).
"""

from __future__ import annotations

import re
from dataclasses import replace

from ..core.scene import Scene
from ..errors import L2PError
from ..language import Command, Context
from ..pipeline import resolve

_RESTS = r"(?:'s|s|\s+is|\s+ends\s+up|\s+ends|\s+lands|\s+sits|\s+gets|\s+lies|\s+rests|\s+stands|\s+moves|\s+goes)"
GOAL_AFTER = re.compile(rf"^(?P<head>.+?)\s+(?:so\s+(?:that\s+)?it{_RESTS}|(?:until|till|til|'til)\s+it{_RESTS}"
                        r"|(?:until|till|til|'til)\s+(?:they're|theyre|they\s+are|the\s+two(?:\s+of\s+them)?\s+are"
                        r"|both(?:\s+of\s+them)?\s+are)(?=\s+(?:side|next|beside|touching|nearer|closer))"
                        r"|(?:until|till|til|'til)\s+(?:they|the\s+two(?:\s+of\s+them)?|both(?:\s+of\s+them)?)(?=\s+touch\b)"
                        r"|(?:until|till|til|'til)\s+it(?=\s+touches\b))"
                        r"\s+(?P<goal>.+)$", re.IGNORECASE)
"""A motion and then where it should end: "slide A toward B until it is beside it" asks for "next to B"."""
TOUCHING = re.compile(r"^\s*(?:right\s+)?(?:touching|touches|against)\s+(?=\S)", re.IGNORECASE)
"""A goal said as touching ("until it is touching the prism"): right next to it."""
SIDE_BY_SIDE = re.compile(r"^\s*(?:side\s+by\s+side|next\s+to\s+each\s+other|beside\s+each\s+other)\s*[.!]*\s*$",
                          re.IGNORECASE)
"""Two objects said to end together ("until they're side by side"): the mover next to the block it moved toward."""


POLITE_AFTER = re.compile(r"\s*,\s*(?:if\s+you\s+(?:would|could|can|don't\s+mind|please)|please|thanks|thank\s+you)"
                          r"\s*[.!]*\s*$", re.IGNORECASE)


def _goal_said(goal: str) -> str:
    """The end a GOAL_AFTER clause names, said as a preposition and its block (politeness after it read past: "...
    until the two of them are touching, if you would"; how it rests too: "until it's sitting beside it")."""
    goal = re.sub(r"(?i)^\s*(?:sitting|standing|lying|resting|sat|stood)\s+", "", POLITE_AFTER.sub("", goal))
    if re.fullmatch(r"\s*(?:touching|touch|touches)(?:\s+(?:each\s+other|it))?\s*[.!]*\s*", goal, re.IGNORECASE):
        return "right next to it"  # "until they're touching"
    if re.fullmatch(r"\s*(?:nearer|closer)(?:\s+to)?\s+(?:each\s+other|together)\s*[.!]*\s*", goal, re.IGNORECASE):
        return "closer to it"  # "until they're nearer each other"
    return SIDE_BY_SIDE.sub("next to it", TOUCHING.sub("right next to ", goal))


def goal_after(text: str, scene: Scene, plugins: list, context: Context | None) -> list[Command] | None:
    """The clause's command where ``text`` is a motion and then its end (:data:`GOAL_AFTER`); None where it is not
    said so or does not resolve."""
    m = GOAL_AFTER.match(text)
    if m is None:
        return None
    try:
        head = resolve(m.group("head"), scene, plugins, context)
        goal = resolve(f"{head.verb} {head.mover} {_goal_said(m.group('goal'))}", scene,
                       plugins, Context(head.anchor, head.mover))  # "beside it": the block it moved toward
    except L2PError:
        goal = None
    if goal is not None:
        return [replace(goal, manner=head.manner, pace=head.pace or goal.pace, sentence=text)]
    try:  # "Slide the teacup over until it is touching the prism": the motion names no place of its own
        said = re.sub(r"(?i)\s+over$", "", m.group("head"))
        return [replace(resolve(f"{said} {_goal_said(m.group('goal'))}", scene, plugins,
                                context), sentence=text)]
    except L2PError:
        pass
    return None
