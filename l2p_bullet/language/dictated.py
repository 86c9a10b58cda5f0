"""Numbers as people dictate them: digit by digit ("oh four one three" for 0413) or in pairs ("four twelve" for 412,
"ten forty two" for 1042), as a sample tube's or a parcel's code is read aloud.

A run of number words is read as the number it dictates only where an object's name carries that number (the scene's
numbered names, language/numbers.py); every other run ("two cubes", "the first one", "move six round four") is left as
it was said.
"""

from __future__ import annotations

import re

from ..core.scene import Scene
from .numbers import SPELLED, numbered

DIGITS = {w: n for w, n in SPELLED.items() if n < 10} | {"oh": 0, "o": 0, "nought": 0}
"""Words for one digit, "oh" among them (as people read a zero in a code)."""
TENS = {"twenty": 20, "thirty": 30, "forty": 40, "fifty": 50, "sixty": 60, "seventy": 70, "eighty": 80, "ninety": 90}
_ANY_NUMBER = "(?:" + "|".join(sorted([*SPELLED, *DIGITS, *TENS], key=len, reverse=True)) + ")"
NUMBER_WORD = re.compile(r"\b" + _ANY_NUMBER + r"(?:[\s-]+" + _ANY_NUMBER + r")+\b", re.IGNORECASE)
"""A run of two or more number words."""


def numbers_said(sentence: str, scene: Scene) -> str:
    """``sentence`` with each run of number words that dictates a number a name carries said in digits ("move four
    twelve past ..." -> "move 412 past ..." where S-0412 is on the table); as it was where none does."""
    table = numbered(scene)
    if not table:
        return sentence

    def digits(m: re.Match) -> str:
        words = [w.lower() for w in re.split(r"[\s-]+", m.group(0))]
        for said in _readings(words):
            if int(said) in table:
                return said
        return m.group(0)

    return NUMBER_WORD.sub(digits, sentence)


def _readings(words: list[str]) -> list[str]:
    """The numbers a run of number words may dictate, the digit-by-digit reading first: "oh four one three" -> 0413;
    "four twelve" -> 412; "ten forty two" -> 1042; "twenty one" -> 21."""
    out = []
    if all(w in DIGITS for w in words):
        out.append("".join(str(DIGITS[w]) for w in words))
    parts = _groups(words)
    if parts is not None:
        out.append("".join(str(p) for p in parts))
    return out


def _groups(words: list[str]) -> list[int] | None:
    """The numbers a run of number words says one after another ("ten", "forty two" -> [10, 42]); None where a word
    cannot start or end one."""
    out: list[int] = []
    i = 0
    while i < len(words):
        w = words[i]
        if w in TENS:
            n = TENS[w]
            if i + 1 < len(words) and DIGITS.get(words[i + 1], 0) > 0:  # "forty two"; never "forty oh"
                n, i = n + DIGITS[words[i + 1]], i + 1
            out.append(n)
        elif w in SPELLED:
            out.append(SPELLED[w])
        elif w in DIGITS:
            out.append(DIGITS[w])
        else:
            return None
        i += 1
    return out
