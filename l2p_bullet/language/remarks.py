"""A remark or a statement after the command: "move the jug next to the pot, thanks a million", "...; the dish has
agar in it".

People end an instruction with words for the listener ("good lad", "that is the requirement", "it gets hot dear")
that no closing table can list, and the grammar then reads them as part of the last object's name ("no block called
'the pot thanks a million'"). Where every other reading has refused a sentence, it is read once more without its
last parts after a break (a comma, a full stop, a dash), one part at a time from the end, each dropped part a remark:
none of its words could change what the command means (:func:`is_remark`). A refusal is better than a wrong block,
so a part that names or points at an object, says how far, how fast or in what manner, corrects, negates, counts or
joins another command is never dropped. A whole sentence after the command that only states how things are
(:func:`without_statement`) may name the command's own objects, no other.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from . import lenient
from .words import NEGATIONS, PACES

BREAK = re.compile(r"\s*(?:[,;!?]+|\.+|\s[-\u2013\u2014]+)\s+")
"""Where a sentence breaks into parts: a comma, semicolon, full stop or question mark, a dash between words."""
ABOUT_IT = frozenset({"it", "its", "it's", "itself", "that", "that's", "this", "thats", "there", "they", "they're"})
"""Pointing words a remark about the object may hold ("it's only in the way", "that is the requirement"): the
command before has said which object; these add nothing to it."""
JOINS = frozenset({"then", "and", "after", "afterwards", "next", "also", "too", "again", "same", "first", "second",
                   "third", "finally", "before", "once", "when", "while", "until", "till", "as", "instead", "do",
                   "put", "move", "go", "goes", "make", "row", "line", "lift", "carry", "push"})
"""Words that join or start another command ("then", "do the same", "and the cup too"): never a remark."""
MANNER_WORDS = frozenset({"time", "easy", "care", "steady", "steadily", "speed", "rush", "delicate", "delicately",
                          "drag", "dragging", "lifting", "air", "fingers", "handle", "attention"})
"""Words of a manner or pace said in a phrase ("taking your time with it", "go easy", "don't drag it"): never a
remark."""
PAST = frozenset({"was", "were", "yesterday", "earlier"})
"""Words that make what comes before a remark a report of the past ("Yesterday the duck was next to C, I noticed"):
with the remark dropped it would read as a wish for that state."""
NEVER_IN_A_REMARK = lenient.STOPS | (lenient.POINTING - ABOUT_IT) | (lenient.EXTENT_WORDS - {"good"}) \
    | frozenset(PACES) | NEGATIONS | JOINS | MANNER_WORDS
"""Every word that could change the command (:func:`is_remark`), the scene's own aside."""
IN_THE_WAY = re.compile(r"\bin\s+(?:the|my|your|our|everyone's|every1s)\s+way\b")
"""What is said of an object in the way ("it's only in the way", "its kinda in the way"): its "way" is no extent."""
MAX_PARTS = 2
"""At most this many parts are dropped: a longer tail is more than a remark."""


def is_remark(part: str, matters: frozenset[str]) -> bool:
    """Whether ``part`` (words after a break) holds none of the words that could change the command: ``matters``
    (the scene's names and kinds, colours, the installed phrases' and verbs' words), the lenient reading's stops and
    pointing words but "it" (:data:`ABOUT_IT`), extents, paces, negations, joins and numbers."""
    words = re.findall(r"[\w']+", IN_THE_WAY.sub(" ", part.lower()))
    if not words or any(ch.isdigit() for w in words for ch in w):
        return False
    return not any(w in NEVER_IN_A_REMARK or w in matters for w in words)


def phrase_words(phrases: Iterable[str]) -> frozenset[str]:
    """The words of the installed phrases that say a place ("next", "away", "past", "beside"), not the small words
    they share with every sentence ("a", "to", "the"): a remark holding one may be asking for a place."""
    return frozenset(w for p in phrases for w in p.lower().split() if len(w) >= 4 and w not in SMALL_WORDS)


SMALL_WORDS = frozenset({"from", "with", "into", "onto", "over", "that", "this", "side", "just", "about", "them"})
"""Words of four letters or more in phrases that say no place by themselves."""


def without_remarks(sentence: str, matters: Iterable[str]) -> list[str]:
    """``sentence`` with its last one, then two parts dropped where each is a remark (:func:`is_remark`), longest
    first; empty where its last part is none. The caller reads a head only where it ends in a command, never in a
    list ("line up: lemon, lime, Granny": the last item is no remark)."""
    matters = frozenset(w.lower() for w in matters)
    cuts = [m for m in BREAK.finditer(sentence) if m.end() < len(sentence)]
    out = []
    for m in reversed(cuts[-MAX_PARTS:] if cuts else []):
        head, tail = sentence[:m.start()], sentence[m.end():]
        if not head.strip() or not is_remark(tail, matters) or PAST & set(re.findall(r"[\w']+", head.lower())):
            break
        out.append(head)
    return out


REASON = re.compile(r"[\s,;.!?-]+(?:because|bc|b/c|cos|coz|cuz|'cause|since|so that|so)\s+(?=\S)", re.IGNORECASE)
"""Where a reason or a purpose after the command starts ("... closer to the scissors bc the baby keeps grabbing it",
"... beside the pattern so i can follow the chart")."""
REASON_STOPS = NEGATIONS | frozenset({"then", "and", "also", "too", "again", "first", "next", "instead", "touch",
                                      "touches", "touching", "touched", "tuching", "gap", "apart", "far", "farther",
                                      "further", "tight", "snug", "space", "room"})
"""Words in a reason that may be another step, a negation or how far ("so then push it", "so they're touching"): such
a part is kept, and the sentence refused as before. The installed phrases' words ("closer", "near"), the verbs, the
extents and the paces are kept too (:func:`without_reason`)."""


def without_reason(sentence: str, places: Iterable[str], verbs: Iterable[str]) -> list[str]:
    """``sentence`` up to where its first reason or purpose starts (:data:`REASON`): none where there is none, where
    fewer than three words come before it, or where the reason holds one of ``places`` (the installed phrases' words:
    "so it ends up next to B" says where), of ``verbs``, an extent, a pace or one of :data:`REASON_STOPS`. The reason
    explains the move; it never changes it."""
    m = REASON.search(sentence)
    if m is None:
        return []
    head, tail = sentence[:m.start()], sentence[m.end():]
    if len(head.split()) < 3:
        return []
    words = set(re.findall(r"[\w']+", tail.lower()))
    keep = frozenset(w.lower() for w in places) | frozenset(v.lower() for v in verbs) | lenient.EXTENT_WORDS \
        | REASON_STOPS | frozenset(PACES)
    return [] if words & keep else [head]


SENTENCE_BREAK = re.compile(r"(?:(?<=[\w)'\"])[.!?]+|;|\s[-\u2013\u2014]+)\s+(?=\S)")
"""Where a sentence ends and another starts: a full stop, a question or exclamation mark, a semicolon, a dash."""
STATING = frozenset({"is", "are", "isn't", "aren't", "has", "have", "may", "might", "will", "would", "can", "could",
                     "should", "must", "keeps", "keep", "stays", "cracks", "breaks", "melt", "melts", "spills",
                     "gets", "it's", "that's", "there's", "they're", "we're", "i'm", "we've", "i've"})
"""Words by which a sentence states what is, may be or should be ("the dish has agar in it", "it is tall and may fall
over", "specs should be within reach"): a statement said after the command, not another command."""
UNSURE = re.compile(r"\b(?:(?:i'?m|i\s+am|im)\s+)?not\s+(?:sure|certain)\b")
"""A doubt said of a statement ("it might be glass, I'm not sure"): its "not" negates no step."""
EXPECTED = re.compile(r"^\s*(?:expected|expect|expected\s+result|result|outcome)\s*:", re.IGNORECASE)
"""A step's expected outcome, as a test plan writes it after the step ("Expected: distance W-P3 decreased.")."""


def without_statement(sentence: str, places: Iterable[str], verbs: Iterable[str], named: Iterable[str]) -> list[str]:
    """``sentence`` without its last sentence where that only states something about the scene (a word of
    :data:`STATING`, and none of ``places``, ``verbs``, an extent, a pace, a join, a manner's word, a negation or
    the past: "Bring the beaker to the petri dish; the dish has agar in it.") or gives the step's expected outcome
    (:data:`EXPECTED`); none where it does neither or nothing comes before it. It may name only objects the command
    names in the same words (``named``: the words that name the scene's objects): "..., it is the brush that
    matters" may say which object was meant, and is kept."""
    cuts = list(SENTENCE_BREAK.finditer(sentence))
    if not cuts:
        return []
    last = cuts[-1]
    head, tail = sentence[:last.start()], sentence[last.end():]
    if len(head.split()) < 3:
        return []
    words = set(re.findall(r"[\w']+", UNSURE.sub(" ", tail.lower())))
    unsaid = frozenset(w.lower() for w in named) - set(re.findall(r"[\w']+", head.lower()))
    if EXPECTED.match(tail):
        return [] if words & unsaid else [head]
    keep = frozenset(w.lower() for w in places) | frozenset(v.lower() for v in verbs) | lenient.EXTENT_WORDS \
        | REASON_STOPS | frozenset(PACES) | JOINS | MANNER_WORDS | PAST | (lenient.STOPS - {"if"}) | unsaid
    return [head] if words & STATING and not words & keep else []
