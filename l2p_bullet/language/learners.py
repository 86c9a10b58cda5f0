"""English as learners write it, said as the grammar reads it ("Put candle at book side", "Move the remote more far
of the glass", "Separate the glass from the book", "the remote stuck to the candle", "until it touch the book", "put
the A in the side of the B", "the C passes by the D", "move it little away", "the one in middle of table", "the
block on far right").

Each form is a construction of another language said word for word in English (Chinese 在书旁边 "at book side",
Spanish "más lejos de" "more far of", "pegado a" "stuck to", Russian, Polish, Chinese and Turkish without articles
("at back", "in middle of table"), Portuguese "ao lado de" "in the side of", "passar por"
"pass by", French "approcher X de Y" "approach X of Y", "faire le tour de" "make the tour of"), or as code calls it
("obj_1.next_to(obj_2)"), read only in a sentence refused as written (``chain/clauses.resolve_clauses``), so a
sentence the grammar reads is read as before.
"""

from __future__ import annotations

import re

from ..core.scene import Scene
from . import spanish
from .reference_words import PERIPHRASTIC
from .references import try_object

_SIDE = re.compile(r"\b(?:at|to|on|by|in)\s+(?P<the>the\s+)?(?P<what>[\w-]+?)(?:'s)?\s+side\b(?!\s+of\b)",
                   re.IGNORECASE)
"""An object's side as the place: "at book side", "to the candle's side", "bring bowl to candle side"."""
_CALLED = r"next_to|away_from|closer_to|past|around|toward|towards|beside|nextto|awayfrom|closerto"


def _called(m: re.Match) -> str:
    """A command written as code calls it ("obj_1.next_to(obj_2)", "around(obj_5, obj_2)"), said in words."""
    how = {"nextto": "next to", "awayfrom": "away from", "closerto": "closer to"}.get(m.group("how").lower(),
                                                                                   m.group("how").replace("_", " "))
    return f"move {m.group('what')} {how} {m.group('to')}"


COMPARED_AS = {"big": "bigger", "small": "smaller", "large": "larger", "tall": "taller", "short": "shorter",
               "wide": "wider", "long": "longer"}
"""A size said as Romance languages compare it ("più grande", "más pequeño"): the English comparative."""

_REWRITES = (
    (re.compile(r"\bmore\s+far\s+(?:of|from)\b", re.IGNORECASE), "farther from"),
    (re.compile(r"\bmost\s+(?P<how>far|near|close)\b(?P<of>\s+of\b)?", re.IGNORECASE),  # "the one most far from you"
     lambda m: PERIPHRASTIC[("most", m.group("how").lower())]
     + ({"far": " from", "near": "", "close": " to"}[m.group("how").lower()] if m.group("of") else "")),
    (re.compile(r"\bmore\s+(?:close|near)\s+(?:of|to)\b", re.IGNORECASE), "closer to"),
    (re.compile(r"\bfar\s+of\b", re.IGNORECASE), "far from"),
    (re.compile(r"\bmore\s+(big|small|large|tall|short|wide|long)\b", re.IGNORECASE),  # "the vase more big"
     lambda m: COMPARED_AS[m.group(1).lower()]),
    (re.compile(r"\bof\s+(?:a\s+|the\s+)?(?:colou?r\s+(?P<after>[a-z]+)|(?P<before>[a-z]+)\s+colou?r)\b",
                re.IGNORECASE), lambda m: m.group("after") or m.group("before")),  # "the vase of brown colour"
    (re.compile(r"\bnear\s+of\b", re.IGNORECASE), "near"),
    (re.compile(r"\bbeside\s+(?:to|of)\b", re.IGNORECASE), "beside"),
    (re.compile(r"\b(?:in|at|on)\s+(?:the\s+)?side\s+of\b", re.IGNORECASE), "next to"),
    (re.compile(r"\b(closer|nearer)\s+of\b", re.IGNORECASE), r"\1 to"),
    (re.compile(r"\btogether\s+with\b", re.IGNORECASE), "next to"),
    (re.compile(r"\bpass(es)?\s+by\b", re.IGNORECASE), lambda m: "goes beyond" if m.group(1) else "go beyond"),
    (re.compile(r"(?<!\ba)(?<!\bvery)\s+little\s+(?=(?:away|closer|nearer|past|further|farther|towards?)\b)",
                re.IGNORECASE), " a little "),
    (re.compile(r"\bstuck\s+(?:to|on)\b", re.IGNORECASE), "right next to"),
    (re.compile(r"\buntil\s+it\s+touch\b", re.IGNORECASE), "until it touches"),
    (re.compile(r"\bso\s+close\s+to\s+(?P<what>.+?)\s+as\s+(?:you\s+)?(?:can|possible)\b", re.IGNORECASE),
     r"as close as you can to \g<what>"),
    (re.compile(r"(?<!\ba)\s+little\s+bit\b", re.IGNORECASE), " a little bit"),
    (re.compile(r"\bseparate\s+(?P<extent>(?:a\s+)?(?:bit|little)\s+)?(?P<what>.+?)\s+from\b", re.IGNORECASE),
     r"move \g<what> \g<extent>away from"),
    (re.compile(r",?\s*no\s+drag\b", re.IGNORECASE), ", don't drag it"),
    (re.compile(r"\bapproach\s+(?P<what>[^,]+?)\s+of\s+(?P<to>the\b)", re.IGNORECASE),
     r"move \g<what> closer to \g<to>"),
    (re.compile(r"\bdistance\s+(?P<what>[^,]+?)\s+from\b", re.IGNORECASE), r"move \g<what> away from"),
    (re.compile(r"\bmake\s+the\s+tour\s+of\s+(?P<anchor>[^,]+?)\s+with\s+(?P<what>[^,]+)", re.IGNORECASE),
     r"move \g<what> around \g<anchor>"),
    (re.compile(r"\b(in|on|at)\s+(?=(?:far|very)\s+(?:left|right|back|front)\b|(?:middle|centre|center|back|rear)\b"
                r"|(?:left|right)\b(?!\s+of\b))", re.IGNORECASE), r"\1 the "),
    (re.compile(r"\b(middle|centre|center|side|edge|end|corner)\s+of\s+(?=(?:table|desk|bench|tray|board|counter|shelf)\b)",
                re.IGNORECASE), r"\1 of the "),
    (re.compile(rf"(?P<what>[\w-]+)\.(?P<how>{_CALLED})\(\s*(?P<to>[\w-]+)\s*\)", re.IGNORECASE), _called),
    (re.compile(rf"\b(?P<how>{_CALLED})\(\s*(?P<what>[\w-]+)\s*,\s*(?P<to>[\w-]+)\s*\)", re.IGNORECASE), _called),
)
"""Word-for-word constructions and what they say in the grammar's English."""


def in_plain_english(sentence: str, scene: Scene) -> str:
    """``sentence`` with each learner's construction said as the grammar reads it; unchanged where it has none. An
    object's side is read as "next to" it only where the word before "side" names an object ("the other side",
    "the left side" are places of their own)."""
    def side(m: re.Match) -> str:
        said = f"the {m.group('what')}"
        return f"next to {m.group('the') or ''}{m.group('what')}" if try_object(said, scene) is not None \
            else m.group(0)

    out = _SIDE.sub(side, spanish.in_english(sentence))
    for pattern, said in _REWRITES:
        out = pattern.sub(said, out)
    return out


__all__ = ["in_plain_english"]
