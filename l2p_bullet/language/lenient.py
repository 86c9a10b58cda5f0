"""The last reading of a sentence the grammar refuses: the command's parts found among words it does not know.

People wrap a command in words of their own ("What I'm after is the rubber duck sitting on the other side of
the yellow cube", "Push with the fingers the cup around the duck"). Where every reading of the grammar
(grammar.py, chain/clauses.py) has refused a sentence, it is read once more, clause by clause, looking only for
what a command must have: one installed phrase, one object named before it and the reference objects after it,
and a verb anywhere (the manner it names) or a wish ("I'd like", "should"). The other words are read past, but
only where none of them could change the meaning, because a refusal is better than a wrong block:

- no negation or correction ("not", "don't", "instead", "sorry", "rather", "or", "if"), no number;
- no second phrase, and no two verbs of different manners;
- no word left over that describes or points at an object (a colour, a shape, an object's name, "big", "left",
  "other", "it", "both"), nor one that asks how far or how fast away from its place (an extent stands right
  before the phrase, as the grammar reads it);
- no object named that the command does not use, no "and" before the phrase, and no word a motion the five
  actions cannot make would use ("stack", "back", "rotate").

It is allowed only inside :func:`reading_past`, which ``chain/clauses.resolve_clauses`` enters for its last
try, so a sentence the grammar reads is read exactly as before.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

from ..core.scene import COLORS, Scene
from . import lexicon
from .allowance import Allowance
from .extents import EXTENTS, take_extent
from .goals import participles
from .naming import naming_words, shape_named
from .partitives import VESSELS
from .pronouns import Context
from .reference_words import (
    COLOR_SYNONYMS,
    COMPARATIVE_OF,
    DETERMINERS,
    FARTHEST,
    KIND_WORDS,
    NEAREST,
    NOUNS,
    PLACE_ADJECTIVES,
    SIZE_SUPERLATIVES,
)
from .references import try_object
from .synonyms import SIZE_WORDS, name_parts
from .words import NEGATIONS, PACES

_ALLOWED = Allowance("l2p_lenient_reading")

STOPS = NEGATIONS | frozenset({
    "isn't", "aren't", "doesn't", "won't", "can't", "cannot", "nothing", "without", "instead", "sorry", "rather",
    "actually", "except", "unless", "or", "nor", "but", "if", "wait", "oops", "correction", "mean", "meant",
    "stack", "rotate", "turn", "flip", "spin", "throw", "toss", "swap", "switch", "tip", "knock", "remove",
    "hide", "return", "back", "undo", "under", "onto", "into", "inside", "above", "below", "top", "then",
    "was", "were", "already",
    "pass", "passes", "passed", "passing", "touch", "touches", "touched", "touching", "hit", "bump", "cross",
    "avoid", "follow", "possible", "gap", "rush", "hurry", "whatever", "line", "lines", "row", "rows",
    "attention",  # "with great attention": a pace, never read past
})
"""Words that stop the reading: they may change what the rest means ("touching" asks for a tight gap, "pass it
by" for past), join a clause the sentence did not split, or ask for what the actions cannot do or a row ("arrange to
a line")."""
AMBIGUOUS_PHRASES = frozenset({"by"})
"""Phrases never read leniently: "by B" may mean beside B or past it, and the verb that tells is the word the
lenient reading would read past."""
POINTING = frozenset({
    "it", "its", "this", "that", "these", "those", "them", "they", "one", "ones", "other", "another", "same",
    "both", "either", "all", "each", "every", "two", "three", "first", "second", "third", "last", "between",
    "middle", "center", "centre", "behind", "front", "left", "right", "him", "her", "his", "em", "'em",
    "latter", "former",
}) | SIZE_WORDS | frozenset(SIZE_SUPERLATIVES) | frozenset(COMPARATIVE_OF) | frozenset(PLACE_ADJECTIVES) \
    | NEAREST | FARTHEST
"""Words that describe or point at an object: left over, they would have picked another object."""
WISHES = frozenset({
    "want", "wants", "wanted", "like", "need", "needs", "needed", "should", "must", "goal", "after", "wish",
    "would", "could", "can", "let's", "lets", "have", "has", "please", "pls", "try", "make", "aim", "target",
    "ideally", "hope", "hoping",
})
"""Words that ask for an end state when no verb says how to move ("the ball should be away from the box")."""
GENERIC_VERBS = frozenset({"move", "put", "place", "set", "position", "get", "take", "bring", "relocate",
                           "reposition", "send", "translate", "displace", "circle"})
"""Verbs that name no manner of their own: with a manner's verb in the same clause, that one decides."""
HINTS = {"fingers": "push", "finger": "push", "fingertips": "push", "air": "carry"}
"""Words that say the manner as a verb would: "with your fingers" is how a push is done, "through the air" how a
carry goes (the verb they stand for, looked up among the manners' verbs)."""
BEFORE_PHRASE = frozenset({"over", "up", "down", "be", "is", "go", "goes", "sitting", "sits", "standing", "stands",
                           "end", "ends", "lands", "somewhere", "like", "itself", "stay", "stays", "remain", "remains",
                           "sit", "stand", "lie", "circuit", "loop", "lap", "circle", "full", "complete", "whole"})
"""Words left over right before the phrase that ask no extent ("slide A over next to B", "A sitting beside B")."""
EXTENT_WORDS = frozenset(w for k in EXTENTS for w in k
                         if w not in ("a", "an", "the", "so", "or", "only", "just", "well"))
"""The words of the extents ("far", "bit", "slightly"): left over away from their place, they may ask one."""
MAX_SPAN = 7
"""Longest description tried for one object, in words."""


@dataclass(frozen=True)
class Reading:
    """What the lenient reading found: the grammar builds its Command from it."""

    verb: str
    manner: str
    mover: str
    phrase: str
    action: str
    anchors: tuple[str, ...]
    extent: str | None


reading_past = _ALLOWED.inside
"""Allow :func:`read` inside the block (the last try of a sentence refused as written)."""


def allowed() -> bool:
    """Whether :func:`read` may be tried now."""
    return _ALLOWED.now()


def read(words: list[str], scene: Scene, readings: list, verbs: list[tuple[tuple[str, ...], str, str]],
         anchors: dict[str, int], extents: dict[str, frozenset[str]], context: Context | None) -> Reading | None:
    """The command in ``words`` (a clause's words, politeness and pace taken out), or None where any rule above
    stops it. ``readings`` are the grammar's (tokens, phrase, action, implied extent), longest first; ``verbs``
    (head tokens, verb as declared, manner)."""
    low = [w.lower() for w in words]
    found = _phrases(low, readings)
    if len(found) != 1:
        return None
    start, end, phrase, action, implied = found[0]
    outside = low[:start] + low[end:]  # "not so close to" is a phrase; "not" elsewhere stops the reading
    named = {n.lower() for n in scene.names if not n.isdigit()}  # "block2" is a name; "5" may be a count as well
    stops = set(outside) & STOPS  # "tip" stops "tip it over", not "the tip box" where tip_box is on the table
    if (stops and stops - _name_words(scene)) or any(ch.isdigit() for w in outside if w not in named for ch in w):
        return None
    if phrase in AMBIGUOUS_PHRASES:
        return None
    manner_verb = _manner(low, verbs)
    if manner_verb is None:
        return None
    verb, manner = manner_verb
    before, extent = take_extent(words[:start])
    extent = extent or implied
    if extent is not None and extent not in extents.get(action, frozenset()):
        return None
    movers, unread = _read_at(before, scene, context)
    left_before = [before[i] for i in sorted(unread)]
    if _head_unread(before, unread):
        return None
    if before and left_before and left_before[-1] is before[-1] and not _asks_no_extent(before, verbs):
        return None  # an unknown word where an extent stands ("move duck rite next to K"): it may be one
    refs, left_after = _mentions(words[end:], scene, context)
    if stops & {w.lower() for w in left_before + left_after}:
        return None
    count = anchors.get(action, 1)
    if len(movers) != 1 or len(refs) != count or movers[0] in refs or len(set(refs)) != count:
        return None
    # "the triangular toy", "the cereal box" on a table with neither; "... in the middle row"
    describing = naming_words(scene) | {n.lower() for n in scene.names} | POINTING | EXTENT_WORDS | set(PACES) \
        | KIND_WORDS | GROUPED | {w for w in _name_words(scene) if len(w) > 2}  # "block" of red_block, not "i"
    if _noun_left(low, {w.lower() for w in left_before + left_after}, named):
        return None
    after = [w.lower() for w in left_after]
    if any(w.lower() in describing for w in left_before + left_after) or \
            {w.lower() for w in left_before} & {"and", "&"} or _another_said(after):
        return None  # "and" before the phrase lists objects or joins a second command; after it, one more object
    return Reading(verb, manner, movers[0], phrase, action, tuple(refs), extent)


HEAD_LINKS = frozenset({"for", "of", "with"})
"""Words that join a description's noun to what follows it ("the soap for dogs", "the bottle of oil")."""


def _head_unread(words: list[str], unread: frozenset[int]) -> bool:
    """Whether an object is named only after the noun a description is about ("the soap for dogs" names the dog
    brush only by what the soap is for): a thing WordNet knows, said after an article and left unread (``unread``:
    where the words that named no object stand), right before "for", "of" or "with" and a description that names an
    object."""
    low = [w.lower() for w in words]
    return any(low[k] in HEAD_LINKS and k - 1 in unread and k + 1 not in unread
               and DETERMINERS & set(low[max(0, k - 3):k - 1]) and _a_thing_of_its_own(low[k - 1])
               for k in range(2, len(words) - 1))


def _a_thing_of_its_own(word: str) -> bool:
    """Whether ``word`` names a thing the words after it cannot be: a noun WordNet knows, but for a word that stands
    for any object ("the thing with the red handle") and a vessel, called by what it holds ("the pot with pens")."""
    return (word.isalpha() and word not in NOUNS and word not in VESSELS and word.rstrip("s") not in VESSELS
            and lexicon.singular(word) is not None)


def _another_said(after: list[str]) -> bool:
    """Whether the words left after the phrase's objects go on to another one ("... away from the rack, and the
    centrifuge too"): "and" or "then" before an article, a thing unread that reading past would drop."""
    return any(w in ("and", "&", "then", "plus") and nxt in DETERMINERS
               for w, nxt in zip(after, after[1:], strict=False))


GROUPED = frozenset({"row", "rows", "column", "columns", "line", "lines", "corner", "corners", "edge", "edges"})
"""Words that place an object in a group or a part of the table ("the leftmost one in the middle row"): left over,
the words before them would be read without them ("the leftmost one in the middle"), another object."""


def _noun_left(low: list[str], left: set[str], named: set[str]) -> bool:
    """Whether a word left unread stands where a description's noun does: after "the" (or a size word) and a colour
    that names an object ("the orange Würfel": the fruit named "orange", or the colour of a thing the word names),
    or after "the" and a size word ("the bigger par sell")."""
    for ahead, w, after in zip(low, low[1:], low[2:], strict=False):
        if after not in left:
            continue
        if w in named and COLOR_SYNONYMS.get(w, w) in COLORS and (ahead in DETERMINERS or ahead in SIZE_WORDS):
            return True
        if w in SIZE_WORDS and ahead in DETERMINERS:
            return True
    return False


def _asks_no_extent(before: list[str], verbs: list) -> bool:
    """Whether the last word before the phrase, left over, surely asks no extent: a word of
    :data:`BEFORE_PHRASE`, a form of a manner's verb ("The beam is to be shifted toward the jar"), or the noun
    of a description that names only a colour or a size ("the white plate", "the red dice")."""
    last = before[-1].lower()
    if last in BEFORE_PHRASE or any(_inflects(last, head[0]) for head, _, _ in verbs):
        return True
    adjectives = set(COLORS) | set(COLOR_SYNONYMS) | SIZE_WORDS
    return len(before) >= 2 and before[-2].lower() in adjectives and last.isalpha()


def _phrases(low: list[str], readings: list) -> list[tuple[int, int, str, str, str | None]]:
    """Every installed phrase in ``low``, longest first and not overlapping: (start, end, phrase, action, extent)."""
    taken = [False] * len(low)
    out = []
    present = set(low)
    for toks, phrase, action, implied in readings:
        if toks and toks[0] not in present:
            continue
        n = len(toks)
        for i in range(len(low) - n + 1):
            if tuple(low[i:i + n]) == toks and not any(taken[i:i + n]):
                taken[i:i + n] = [True] * n
                out.append((i, i + n, phrase, action, implied))
    return out


def _manner(low: list[str], verbs: list[tuple[tuple[str, ...], str, str]]) -> tuple[str, str] | None:
    """(verb, manner) of the clause: the one manner its specific verbs name, a generic verb's slide, or a slide
    where a wish stands in for the verb; None for two manners, or neither verb nor wish."""
    specific: dict[str, str] = {}
    generic = None
    for head, _declared, manner in verbs:
        first = head[0]
        if any(_inflects(w, first) for w in low):
            if first in GENERIC_VERBS:
                generic = generic or (first, manner)
            else:
                specific.setdefault(manner, first)
    for word, verb in HINTS.items():
        if word in low:
            manner = next((m for head, _, m in verbs if head == (verb,)), None)
            if manner is not None:
                specific.setdefault(manner, verb)
    if len(specific) > 1:
        return None
    if specific:
        manner, verb = next(iter(specific.items()))
        return verb, manner
    if generic is not None:
        return generic
    return ("move", "slide") if set(low) & WISHES else None


def _inflects(word: str, verb: str) -> bool:
    """Whether ``word`` is ``verb`` or one of its forms ("pushed", "pushing", "carries", "slid")."""
    return word == verb or word in _forms(verb)


@functools.lru_cache(maxsize=256)
def _forms(verb: str) -> frozenset[str]:
    """The forms of ``verb`` (:func:`_inflects`), kept by the verb: every word of a clause is checked against every
    manner's verbs."""
    stem = verb[:-1] if verb.endswith("e") else verb
    forms = {verb + "s", verb + "es", stem + "ing", *participles(verb)}  # participles: the -ed forms
    if verb.endswith("y"):
        forms.add(verb[:-1] + "ies")
    return frozenset(forms)


def _name_words(scene: Scene) -> frozenset[str]:
    """The words of the scene's names, lower case ("tip" of tip_box): a stop word that is one may be naming it."""
    return frozenset(w for n in scene.names for w in name_parts(n))


def _mentions(words: list[str], scene: Scene, context: Context | None) -> tuple[list[str], list[str]]:
    """(the objects ``words`` name, in order; the words that named none): the longest description that resolves
    at each word, of at most :data:`MAX_SPAN` words."""
    found, unread = _read_at(words, scene, context)
    return found, [words[i] for i in sorted(unread)]


def _read_at(words: list[str], scene: Scene, context: Context | None) -> tuple[list[str], frozenset[int]]:
    """(the objects ``words`` name, in order; where the words that named none stand)."""
    found: list[str] = []
    left: list[int] = []
    shared = shape_named(scene)
    i = 0
    while i < len(words):
        if words[i].lower() in DETERMINERS and i + 1 < len(words) and words[i + 1].lower() in shared:
            left.extend((i, i + 1))  # "the cylinder" beside Cylinder and Cylinder (1): asked, never the name
            i += 2
            continue
        for j in range(min(len(words), i + MAX_SPAN), i, -1):
            name = try_object(" ".join(words[i:j]), scene, context)
            if name is not None:
                found.append(name)
                i = j
                break
        else:
            left.append(i)
            i += 1
    return found, frozenset(left)




__all__ = ["Reading", "allowed", "read", "reading_past"]
