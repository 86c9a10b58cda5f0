"""The previous command again: on another object ("Now do the same with the red cube", "then same for the duck", "...,
and the black one too") or to another place ("then do it again around the red can", "same again but past B").

Read by chain/pointing.py among its readings of a clause that does not resolve as said.
"""

from __future__ import annotations

import re
from dataclasses import replace

from ..core.scene import Scene
from ..errors import LanguageError
from ..language import Command, Context, resolve_object
from ..language.references import try_object
from ..pipeline import resolve

SAME = re.compile(r"^\s*(?:(?:ok(?:ay)?|now|and|then|after)\s*,?\s*)*(?:(?:do|repeat)\s+(?:(?:the\s+)?same|that|it)"
                  r"|(?:the\s+)?same)(?:\s+thing)?(?:\s+again)?\s+(?:with|for|to)\s+(?P<what>.+?)\s*(?:too|as\s+well)?"
                  r"(?:\s*,?\s*(?:please|pls|thanks|thank\s+you))*\s*[.!]*\s*$", re.IGNORECASE)
"""The previous command again on another object: "Now do the same with the red cube", "then same for the duck", "ok
now do the same with the blue cube, thank you"."""
TOO = re.compile(r"^\s*(?:and\s+)?(?P<what>.+?)\s*,?\s+(?:too|as\s+well|also|same\s+thing|the\s+same)\s*[.!]?\s*$",
                 re.IGNORECASE)
"""The previous command again on another object, said by the object alone: "..., and the black one too"."""
AGAIN_AT = re.compile(r"^\s*(?:(?:ok(?:ay)?|now|and|then)\s*,?\s*)*(?:(?:do|repeat)\s+(?:it|that|the\s+same)\s+again"
                      r"|(?:the\s+)?same\s+again|again)\s*,?\s*(?:but\s+)?(?P<place>(?:around|round|past|beside|next\s+to"
                      r"|closer\s+to|toward|towards|away\s+from)\s+.+?)\s*[.!]*\s*$", re.IGNORECASE)
"""The previous command again to another place: "then do it again around the red can", "same again but past B"."""


def done_again(text: str, previous: Command | None, context: Context | None, scene: Scene,
               plugins: list) -> list[Command] | None:
    """The previous command again as ``text`` says (module docstring), or None where it does not say so."""
    if previous is None:
        return None
    m = SAME.match(text)
    if m is not None:
        mover = resolve_object(m.group("what"), scene, "block to do the same with", context)
        if mover in previous.anchors:
            raise LanguageError(f'"{text}": {mover} is what the previous clause moved {previous.preposition}; '
                                "name another block")
        return [replace(previous, mover=mover, sentence=text)]
    too = _again(text, previous, scene, context)
    if too is not None:
        return [too]
    m = AGAIN_AT.match(text)
    if m is not None:  # its verb, mover and pace; the place said now
        command = resolve(f"{previous.verb} {previous.mover} {m.group('place')}", scene, plugins, context)
        return [replace(command, sentence=text, pace=command.pace or previous.pace)]
    return None


def _again(text: str, previous: Command | None, scene: Scene, context: Context | None) -> Command | None:
    """The previous command again on the object ``text`` names with "too" ("..., and the black one too"); None where
    ``text`` is not said so, names no one object, or names what the previous command moved or moved it to."""
    m = TOO.match(text)
    if m is None or previous is None:
        return None
    mover = try_object(m.group("what"), scene, context)
    if mover is None or mover == previous.mover or mover in previous.anchors:
        return None
    return replace(previous, mover=mover, sentence=text)


__all__ = ["AGAIN_AT", "SAME", "TOO", "done_again"]
