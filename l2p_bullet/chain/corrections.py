"""A person correcting themselves mid-sentence: "move U toward V - no sorry, toward W", "Move the red ball - sorry, I
mean the rabbit - past the cube", "not the black cube, the white one - slide that one next to the vase".

Each correction is said again as the sentence the person meant; the caller resolves it like any other reading
(chain/clauses.py), so a correction that does not make a whole command leaves the sentence refused. Only a
correction that is said as one ("sorry", "I mean", "not X, Y") is read: a sentence that names two places or two
objects without saying which it meant is still asked about.
"""

from __future__ import annotations

import re

from ..core.scene import Scene
from ..language.naming import naming_words
from ..language.references import try_object

SORRY = re.compile(r"^(?P<before>.+?)\s*[-\u2013\u2014,]+\s*"
                   r"(?:no\s*,?\s*(?:sorry|oops|my\s+bad|wait)?|sorry|oops|my\s+bad|wait(?:\s*,?\s*no)?"
                   r"|scratch\s+that|actually(?:\s*,?\s*no)?)\s*,?\s*"
                   r"(?:i\s+mean[t]?\s+|make\s+that\s+)?(?P<right>[^-\u2013\u2014]+?)\s*"
                   r"(?:[-\u2013\u2014]+\s*(?P<after>.*?))?\s*[.!?]*\s*$", re.IGNORECASE)
"""What was said, a word of correction, what was meant, and the rest of the command after a second dash."""
NOT_THIS_BUT = re.compile(r"^\s*not\s+(?P<wrong>[^,]+?)\s*,\s*(?:it's\s+|it\s+is\s+)?(?P<right>[^-\u2013\u2014:]+?)"
                          r"(?:\s+i\s+mean[t]?)?\s*[-\u2013\u2014:]+\s*(?P<rest>.+)$", re.IGNORECASE)
"""An object ruled out before the one meant, then the command about it: "not the black cube, the white one - ..."."""


INSTEAD = re.compile(r"^\s*(?:(?:actually|no|wait|sorry|oops|hmm)\s*[,.!]*\s*)+(?P<meant>.+?)\s*,?\s+instead"
                     r"\s*[.!]*\s*$", re.IGNORECASE)
"""A clause that takes the one before back and says what was meant: "Actually no, move it past the jar instead"."""


TAKEN_BACK = re.compile(r"^\s*(?:(?:ok(?:ay)?|hmm|ugh|actually|oh)\s*[,.!]*\s*)*"
                        r"(?:(?:no+(?:\s*,?\s*(?:wait|sorry))?|wait\s*,?\s*no|sorry|oops|my\s+bad)"
                        r"\s*[,.!:\-\u2013\u2014]+\s*(?:i\s+mean[t]?\s+|make\s+that\s+)?|make\s+that\s+)"
                        r"(?P<meant>\S.*?)\s*[.!]*\s*$", re.IGNORECASE)
"""A clause that opens by taking the one before back, then says what was meant: "no wait, closer to the jello",
"wait no, put it by E", "no, the nut next to the bolt", "Oh sorry, closer to the blue can", "Actually make that around
the blue cube"."""


def instead_of(text: str) -> str | None:
    """The command an :data:`INSTEAD` clause means in place of the clause before, or None where it is not said so."""
    m = INSTEAD.match(text)
    return m.group("meant") if m is not None else None


def taken_back(text: str) -> str | None:
    """What a :data:`TAKEN_BACK` clause means in place of the clause before it, or None where it is not said so; the
    caller reads it as said after the clause it takes back ("no wait, closer to the jello": that clause's verb and
    mover; "wait no, put it by E": "it" is that clause's mover)."""
    m = TAKEN_BACK.match(text)
    return m.group("meant") if m is not None else None


APPOSITIVE = re.compile(r"^(?P<before>.+?)\s*,\s*(?P<said>(?:the|that)\s+(?:[\w-]+\s+){0,3}?one)"
                        r"(?:\s+(?:that|which)\s+[^,]+?)?\s*,\s*(?P<after>\S.*)$", re.IGNORECASE)
"""An object said again in other words right after its description ("Move the biggest box, the red one, away from
the nut", "That little lamp, the white one that stands up, push it ...")."""


TRAILING = re.compile(r"^(?P<before>.+?)\s*(?:,|\.\.+|\u2026)\s*(?P<said>(?:the|that|my)\s+[^,.]+?)"
                      r"(?:\s*,?\s*(?:i\s+mean|yeah|right))?\s*[.!?]*\s*$", re.IGNORECASE)
"""An object said once more at the end, after a comma or dots ("... next to the box, the cardboard box", "... toward
the green block... the middle one I mean")."""


def said_again(text: str, scene: Scene) -> list[str]:
    """``text`` without an :data:`APPOSITIVE` or a :data:`TRAILING` description that fits the object the words before
    it end with (it only says it again); none where there is none, or it fits another object (the person then
    contradicts themselves: asked)."""
    out = []
    for pattern in (APPOSITIVE, TRAILING):
        m = pattern.match(text)
        if m is None:
            continue
        words = m.group("before").split()
        after = m.groupdict().get("after")
        for start in range(len(words)):  # the longest object description the words before end with
            meant = try_object(" ".join(words[start:]), scene)
            if meant is not None:
                alone = try_object(m.group("said"), scene.only((meant,))) == meant
                if after is not None:  # said before the rest: it fits the object said before it
                    fits = alone
                else:  # said last: it fits that object, and on the whole table names no other
                    whole = try_object(m.group("said"), scene)
                    fits = whole == meant or (alone and whole is None)
                if fits:
                    out.extend([f"{m.group('before')} {after}", f"{m.group('before')}, {after}"]
                               if after is not None else [m.group("before")])
                break
    return out


def corrected(text: str, scene: Scene) -> list[str]:
    """``text`` as the person meant it, where they corrected themselves in it or said an object again in other words;
    none where they did not."""
    out = said_again(text, scene)
    m = NOT_THIS_BUT.match(text)
    if m is not None:
        wrong, right = try_object(m.group("wrong"), scene), try_object(m.group("right"), scene)
        if wrong is not None and right is not None and wrong != right:
            out.append(f"{m.group('right')} - {m.group('rest')}")
    m = SORRY.match(text)
    if m is not None:
        right = MEANT_LAST.sub("", m.group("right"))  # "wait, closer to the cup i mean"
        out.extend(_meant(m.group("before"), right, m.group("after") or "", scene))
    m = MEANT_BETWEEN.match(text)
    if m is not None and try_object(m.group("right"), scene) is not None:  # "push A, sorry, the red can, past B"
        out.extend(_meant(m.group("before"), m.group("right"), m.group("after"), scene))
    elif m is not None:  # "slide the blue block past, I mean around, the box"
        out.extend(_said_between(m.group("before"), m.group("right"), m.group("after"), scene))
    return out


MEANT_LAST = re.compile(r"\s*,?\s+i\s+mean[t]?\s*$", re.IGNORECASE)
""""I mean" after what was meant ("..., closer to the cup i mean"): read past."""
MEANT_BETWEEN = re.compile(r"^(?P<before>.+?)\s*,\s*(?:(?:i\s+mean|no|sorry|scratch\s+that|actually|or\s+rather|rather)"
                           r"\s*,?\s*)+?\s(?P<right>[^,]+?)\s*,\s*(?P<after>[^,]+?)\s*[.!?]*\s*$", re.IGNORECASE)
"""A word or two said, then corrected between commas, and the rest of the command: "slide the blue block past, I mean
around, the box", "move the can near the front, sorry I mean the one at the back, around the cube"."""


def _said_between(before: str, right: str, after: str, scene: Scene) -> list[str]:
    """The sentence with what was meant (``right``) in place of the last words said before the correction that name
    no object (at most three: "past" in "slide the blue block past"), then the rest; none where the words before end
    with an object (that is what :func:`_meant` corrects)."""
    words = before.split()
    naming = naming_words(scene) | {n.lower() for n in scene.names}
    tail = 0
    while tail < min(3, len(words) - 1) and words[-1 - tail].lower() not in naming:
        tail += 1
    if tail == 0 or len(right.split()) > 4:
        return []
    return [" ".join([*words[:-tail], right, after])]


def _meant(before: str, right: str, after: str, scene: Scene) -> list[str]:
    """The sentence with what was meant in place of what was said: a place said again from its first word ("toward
    W" for the last "toward V"), or an object for the object the words before the correction end with."""
    words, said = before.split(), right.split()
    head = said[0].lower()
    at = max((i for i, w in enumerate(words) if w.lower() == head), default=None)
    if at is not None and not after:  # "move U toward V - no sorry, toward W"
        return [" ".join([*words[:at], *said])]
    meant = try_object(right, scene)
    if meant is None:
        return []
    for start in range(len(words) - 1, 0, -1):  # the longest object description the words before end with
        if try_object(" ".join(words[start:]), scene) is not None and (
                start == 1 or try_object(" ".join(words[start - 1:]), scene) is None):
            return [" ".join([*words[:start], right, after]).strip()]
    return []
