"""A chain sentence -> its clauses' texts, before any of them is read.

Where one clause ends and the next begins is a question of the sentence's joins ("then", "after that", a full stop),
of a list told item by item ("make a row: first the cube, then the duck") that stays one clause, and of a composite's
sentence that follows a comma; none of it needs the scene, so it is kept apart from reading each clause against the
scene (chain/clauses.py).
"""

from __future__ import annotations

import re

from ..language import MAX_SENTENCE, is_courtesy, known_verbs, strip_polite, tokens
from ..language.goals import participles
from ..language.lists import GROUP
from ..language.words import STEP_LABELS
from . import pointing
from .composite import is_composite

ADDRESSED = re.compile(r"\s*(?:(?:hey|hi|hello|ok|okay|oi|yo|dear|so|now|right)\s+)?robot\s*[,:!]\s*(?=\w)",
                       re.IGNORECASE)
"""The robot addressed before the sentence ("Robot, take ...", "Okay robot, find ...")."""


def unaddressed(sentence: str, robot_named: bool) -> str:
    """``sentence`` without the robot addressed before it (:data:`ADDRESSED`), read past as a whole so that the
    sentence's own frames ("take X and move it ...") read what follows; as said where an object is called "robot"
    (``robot_named``: "robot, move next to the bucket" moves the toy robot)."""
    addressed = None if robot_named else ADDRESSED.match(sentence)
    return sentence if addressed is None else sentence[addressed.end():]


_JOINS = re.compile(r"\s*(?:;|(?<=[a-z0-9])[.!?]\s+(?=\S)|,?\s*\band\s+then\b|,?\s*\bthen\b"
                    r"|,?\s*(?:\band\s+)?\bafter\s+that\b|,?\s*(?:\band\s+)?\b(?:afterwards|thereafter)\b"
                    r"|,\s*after\s+(?=(?![a-z]+ing\b)[a-z]+\s+(?:the|it|them|a|an)\b)"
                    r"|,\s*and\s+after\b"
                    r"|,?\s*\band\s+finally\b|,\s*finally\b"
                    r"|(?:,\s*|\s+and\s+)(?:and\s+)?now\b(?=,?\s+[a-z])"
                    r"|(?:,\s*|\s+)(?:(?:and|but)\s+)?(?=(?:don't|dont|do\s+not)\s+(?:drag|lift|carry)\s+it(?:\s+(?:across|along|over)\s+the\s+\w+)?[\s.!]*$))"
                    r"\s*,?\s*", re.IGNORECASE)
"""What joins clauses: "then", "and then", "after that", "afterwards", "thereafter", ", and after", ", after" before a
verb and its object ("..., after push the brick away"), "and finally", "now" after a comma or "and" ("..., now push it
past B, and now bring it ..."), a semicolon, a full stop between two sentences ("Carry C around B. Next, move D a
bit closer to the duck."), or a manner ruled out at the sentence's end ("..., but don't drag it": chain/apart.py
reads it into the clause before)."""


def split_clauses(sentence: str) -> list[str]:
    """The clauses' texts, in order (empty pieces, e.g. a leading "then", dropped); a list told item by item after a
    colon ("make a row: first the cube, then the duck, then the cup") stays one clause, its items as a list."""
    if not isinstance(sentence, str):
        return []
    order = pointing.ORDER.search(sentence)
    if order is not None and (order.group("lead") or order.group("then")) and order.start() > 0:
        # "..., first the blue, then the red", "..., the small one first and then the big one"
        sentence = sentence[:order.start()] + re.sub(r"(?i)\b(?:and\s+)?then\b", "after", order.group(0))
    sentence = LIST_MARKS.sub(lambda m: m.group("lead"), sentence)
    sentence = _after_you(ABBREVIATED.sub(lambda m: m.group(0).replace(".", ""), sentence))
    out = []
    for part in SENTENCE_ENDS.split(sentence):  # a list told item by item is one sentence of several
        listed = _item_by_item(part)
        out.extend([listed] if listed is not None else [c for p in _pieces(part) for c in _past_courtesy(p)])
    return out


COURTESY_FIRST = re.compile(r"^(?P<courtesy>[^-\u2013\u2014:,]+?)\s*(?:[-\u2013\u2014:,]|\.{3})\s*(?P<rest>.+)$")
"""A courtesy said before the command, set off by a dash, a colon or a comma ("thanks in advance - could you ...")."""


def _past_courtesy(piece: str) -> list[str]:
    """``piece`` as a clause's text; none where it is courtesy alone ("Thanks!"), and the command alone where a
    courtesy set off before it opens it ("Thanks in advance - move A ...": no thanks is a clause, no command lost)."""
    if not is_courtesy(tokens(piece)):
        return [piece]
    m = COURTESY_FIRST.match(piece)
    if m is not None and is_courtesy(tokens(m.group("courtesy"))) and not is_courtesy(tokens(m.group("rest"))):
        return [m.group("rest")]
    return []


LIST_MARKS = re.compile(r"(?P<lead>^|[.!?;:]\s+)\s*(?:\(\d{1,2}\)|(?:(?:" + "|".join(sorted(STEP_LABELS))
                        + r")\s+)?\d{1,2}[.)])\s+(?=[a-z])", re.IGNORECASE)
"""A numbered step's mark where a sentence begins ("1. Move A past B. 2. Then ...", "1) Slide ...", "Step 4. Move
..."): read past, whatever the scene's objects are called, as no sentence says a block's number alone before its
verb."""
ABBREVIATED = re.compile(r"\b(?:i\.e\.|e\.g\.|(?:no|nr|num)\.(?=\s*#?\d))", re.IGNORECASE)
"""Abbreviations whose full stops end no sentence ("..., i.e. past it", "cube no. 6")."""
AFTER_YOU = re.compile(r"^\s*(?:after|once|when)\s+(?:you've|you\s+have|you're\s+done|you\s+are\s+done)\s+"
                       r"(?P<verb>[a-z]+)\s+(?P<done>[^,]+?),\s*(?P<then>.+)$", re.IGNORECASE)
"""What to do first said in the past, before the next step: "After you've moved the white cube next to the domino,
would you line up ..." is "move the white cube next to the domino, then ..."."""


def _after_you(sentence: str) -> str:
    """``sentence`` with a first step said as done (:data:`AFTER_YOU`) said as a step; ``sentence`` itself where its
    participle is no known verb's."""
    m = AFTER_YOU.match(sentence)
    if m is None:
        return sentence
    said = m.group("verb").lower()
    verb = next((v for v in known_verbs() if " " not in v and said in participles(v)), None)
    return sentence if verb is None else f"{verb} {m.group('done')}, then {m.group('then')}"


SENTENCE_ENDS = re.compile(r"(?<=[a-z0-9])[.!?]\s+(?=\S)", re.IGNORECASE)


def _item_by_item(sentence: str) -> str | None:
    """A list told item by item after a colon (:data:`ITEM_BY_ITEM`) said as one list ("make a row: A, B and C"); None
    for any other sentence, and where the items are steps (each opens with a verb)."""
    m, longest = ITEM_BY_ITEM.match(sentence), MAX_SENTENCE
    if m is None:  # "Put the three cubes in a row, big red first, then blue, then small red"
        m, longest = ITEM_AFTER_GROUP.match(sentence), MAX_ITEM_WORDS
        if m is None or not GROUP.search(m.group("head")):
            return None
    elif not (m.group("first") or GROUP.search(m.group("head")) or is_composite(m.group("head"))):
        return None  # "first the cube", "the three cubes:", "Row please: the cube, then ..." are lists
    items = [FIRST_AFTER.sub("", i) for i in ITEM_JOINS.split(m.group("items")) if i.strip(" ,.")]
    verbs = set(known_verbs())
    if len(items) < 2 or any(i.split()[0].lower() in verbs or len(i.split()) > longest for i in items):
        return None  # steps, not items
    listed = ", ".join(i.strip(" ,.") for i in items[:-1]) + " and " + items[-1].strip(" ,.!?")
    head = " ".join(strip_polite(m.group("head").split())) or m.group("head").strip()  # "Row please:"
    return f"{head}: {listed}"


ITEM_BY_ITEM = re.compile(r"^(?P<head>[^:;]+?):\s*(?P<first>first\s+)?(?P<items>(?:[^:;.!?]|[.!?](?!\s))+?)[.!?]*\s*$",
                          re.IGNORECASE)
ITEM_AFTER_GROUP = re.compile(r"^(?P<head>[^:;,]+?),\s*(?P<first>first\s+)?(?P<items>(?:[^:;.!?]|[.!?](?!\s))+?)"
                              r"[.!?]*\s*$", re.IGNORECASE)
MAX_ITEM_WORDS = 5
"""An item of a list told one by one after a comma is an object's description ("big red", "the small red one"), never
a step ("gently nudge the can away from the tray")."""
FIRST_AFTER = re.compile(r"\s+first[\s,]*$", re.IGNORECASE)
ITEM_JOINS = re.compile(r",?\s*\b(?:and\s+then|then|next|and\s+finally|finally|and\s+last(?:ly)?|last(?:ly)?)\b"
                        r"\s*,?\s*", re.IGNORECASE)
"""A list told item by item after a colon: "Please make a row: first the yellow cube, then the duck, then the red
cube", "Put the three cubes in a row: the white one, then the big red one, then the small one" (whether its head is a
composite's phrase is for the composite to say: anything else is refused as before)."""


def _pieces(sentence: str) -> list[str]:
    """The texts between the joins, courtesies ("Thanks!") included."""
    return [p.strip(" ,.") for p in _JOINS.split(sentence) if p.strip(" ,.")]


ROW_OPENING = re.compile(r",\s*(?:and\s+)?(?=(?:line|make|form|arrange|put|place|set)\b)", re.IGNORECASE)
"""A comma before what may open a composite's sentence ("..., line up the can, the tray and the teddy")."""


def _rows_after_commas(texts: list[str], plugins: list) -> list[str]:
    """``texts`` with a clause that goes on, after a comma, into a composite's sentence split in two there: the
    clause before it, and the composite (whose list holds commas of its own). A text that is a composite's
    sentence itself stays whole."""
    return [piece for text in texts for piece in _row_after_comma(text, plugins) or [text]]


def _row_after_comma(text: str, plugins: list) -> list[str] | None:
    """(the clause before, the composite's sentence) where ``text`` goes on into one after a comma; else None."""
    openings = list(ROW_OPENING.finditer(text))
    if not openings or is_composite(text, plugins):
        return None
    for m in openings:
        left, right = text[:m.start()].strip(), text[m.end():].strip()
        if left and is_composite(right, plugins):
            return [left, right]
    return None
