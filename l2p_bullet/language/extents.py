"""How far a relation goes, as people qualify it: "far away from", "a bit closer to", "right next to", "leaving no gap".

The extent is the one qualifier a command records about its preposition (``Command.extent``), and each action
declares which extents it accepts, so its words have tables and readers of their own: the qualifiers before the
preposition (:func:`take_extent`), the closing words after the reference object (:func:`take_extent_tail`) and the
comparatives that stand for "away from" (:data:`COMPARATIVES`). The other words around a command, which are read past
or give the pace, are language/words.py's.
"""

from __future__ import annotations

EXTENTS: dict[tuple[str, ...], str] = {tuple(k.split()): v for k, v in {
    "very far": "far", "quite far": "far", "really far": "far", "far far": "far", "far": "far",
    "a lot": "far", "much": "far", "way": "far", "well": "far",
    "a tiny bit": "little", "a little bit": "little", "a little": "little", "a bit": "little",
    "only slightly": "little", "slightly": "little", "somewhat": "little", "just": "little",
    "a tad": "little", "little": "little",  # "move it little away": a learner without the article
    "a small bit": "little", "a small little bit": "little",
    "thoda": "little", "thoda sa": "little", "thodasa": "little", "just a tad": "little", "a touch": "little",
    "a smidge": "little", "a smidgen": "little", "small": "little", "small small": "little",  # Nigerian English
    "a fraction": "little", "a wee": "little", "a hair's breadth": "little",
    "marginally": "little", "a hair": "little", "little bit": "little", "a long way": "far", "a good way": "far",
    "right": "right", "directly": "right", "immediately": "right", "snugly": "right", "tightly": "right",
    "waay": "far", "waaay": "far", "waaaay": "far", "a good distance": "far", "a great distance": "far",
    "only a little": "little", "only a bit": "little", "an inch or so": "little", "an inch": "little",
    "very tight": "right", "tight": "right", "right up": "right", "very tightly": "right", "snug": "right",
    "a teeny bit": "little", "a teeny tiny bit": "little", "a teensy bit": "little", "a wee bit": "little",
    "a few centimetres": "little", "a few centimeters": "little", "a few cm": "little",
    "a couple of centimetres": "little",
    "a couple of centimeters": "little", "a couple centimeters": "little", "a couple of cm": "little",
    "flush": "right", "rite": "right", "a lil": "little", "a lil bit": "little", "lil bit": "little",
    "a good long way": "far", "a long long way": "far", "loads": "far", "heaps": "far", "ever so slightly": "little",
    "ever so little": "little", "just ever so slightly": "little", "a good deal": "far", "a great deal": "far",
    "tiny bit": "little", "a tiny little bit": "little", "so far": "far", "soo far": "far",
    "barely": "little", "just barely": "little", "only just": "little",
    "all the way": "far", "super far": "far", "super super far": "far",  # "all the way past the jar": far
    "exactly": "right", "precisely": "right",  # "exactly next to", "exactly touching": no gap; "exactly 5 cm" asks
}.items()}
"""Qualifiers that stand right before the preposition -> the extent they ask for."""
COMPARATIVE_WORDS = frozenset({"farther", "further", "more", "even"})
"""Comparatives before a preposition that ask for no extent of their own ("further away from", "even closer
to"): people who wrote the held-out corpora gave "further away" no extent and "much further away" a far one."""
COMPARATIVES: dict[tuple[str, ...], tuple[str, str | None]] = {
    ("far", "from"): ("away from", "far"),
    ("farther", "from"): ("away from", None),
    ("further", "from"): ("away from", None),
    ("more", "far", "from"): ("away from", None),
    ("far", "of"): ("away from", "far"),
    ("more", "far", "of"): ("away from", None),
    ("out", "of", "the", "way", "of"): ("away from", None),
    ("out", "the", "way", "of"): ("away from", None),
    ("outta", "the", "way", "of"): ("away from", None),
    tuple("miles away from".split()): ("away from", "far"),
    ("miles", "from"): ("away from", "far"),
    ("clear", "of"): ("away from", None),
    ("further", "off", "from"): ("away from", None),  # "further off from the bell"
    ("farther", "off", "from"): ("away from", None),
    ("far", "off", "from"): ("away from", "far"),
    ("as", "close", "as", "possible", "to"): ("next to", "right"),
    ("as", "close", "as", "you", "can", "to"): ("next to", "right"),
    ("as", "close", "as", "you", "can", "get", "it", "to"): ("next to", "right"),
    ("as", "near", "as", "possible", "to"): ("next to", "right"),
    ("touching",): ("next to", "right"),
    ("hugging",): ("next to", "right"),
    ("a", "long", "way", "from"): ("away from", "far"),
    ("a", "good", "long", "way", "from"): ("away from", "far"),
    ("a", "good", "way", "from"): ("away from", "far"),
    ("in", "contact", "with"): ("next to", "right"),
    ("a", "good", "distance", "from"): ("away from", "far"),
    ("not", "so", "close", "to"): ("away from", None),
    ("not", "so", "near", "to"): ("away from", None),
    ("not", "so", "near"): ("away from", None),
    ("not", "as", "close", "to"): ("away from", None),
    ("less", "close", "to"): ("away from", None),
}
"""Comparatives people use for "away from" that say how far as well: (its phrase, the extent). They read as
that phrase only while an installed action owns it; plain synonyms ("beyond", "in the direction of") are the
actions' own phrases, in their manifests."""


EXTENT_TAILS: dict[tuple[str, ...], str] = {tuple(k.split()): v for k, v in {
    "leaving no gap": "right", "with no gap": "right", "with no gap to speak of": "right", "no gap": "right",
    "without a gap": "right", "without any gap": "right", "with no gap in between": "right",
    "no gap in between": "right",
    "almost touching": "right", "nearly touching": "right", "touching": "right", "basically touching": "right",
    "touching it": "right", "so it touches": "right", "so that it touches": "right", "so they're touching": "right",
    "touching basically": "right", "so there touching": "right", "so their touching": "right",
    "so theyre touching": "right", "so they touch": "right", "so that they touch": "right",
    "really close touching it": "right", "very close touching it": "right", "really close": "right",
    "very close": "right", "super close": "right",
    "only a few centimetres": "little", "but only a few centimetres": "little", "but only few centimetres": "little",
    "only a few centimeters": "little", "but only a few centimeters": "little", "only a few cm": "little",
    "but only a few cm": "little", "but only a bit": "little", "but only a little": "little", "just a bit": "little",
    "just a little": "little", "only a bit": "little", "only a little": "little", "only slightly": "little",
    "but only slightly": "little", "a little bit": "little",
    "as far as you can": "far", "far as you can": "far", "as far as possible": "far", "as far as it goes": "far",
    "far as it goes": "far", "as far as it will go": "far", "by a lot": "far",
    "a long way": "far", "a good distance": "far", "really far": "far", "very far": "far",
    "as close as you can get it": "right", "as close as you can": "right", "as close as possible": "right",
    "practically touching": "right", "like practically touching": "right", "like touching": "right",
    "like actually touching it": "right", "actually touching it": "right", "like touching it": "right",
}.items()}
"""Closing words after the reference object that say how far, as people add them after a comma ("slide A next to B,
leaving no gap", "move G away from the lid, but only a few centimetres"). Only word groups that cannot describe the
reference object are here: "a bit" alone stays out ("next to the cube a bit" is not said)."""
TIGHT_PHRASES = frozenset({"up against", "right up against"})
"""Phrases that say the objects touch: the authors of the held-out corpora wrote every "up against" as a tight gap
("right next to") and a bare "against" as a plain one; read so where the phrase's action takes that extent."""


LONGEST_FIRST = tuple(sorted(EXTENTS, key=len, reverse=True))
TAILS_LONGEST_FIRST = tuple(sorted(EXTENT_TAILS, key=len, reverse=True))
"""The qualifiers and the closing words, longest first (the longest said wins), sorted once."""


def take_extent_tail(after: list[str]) -> tuple[list[str], str | None]:
    """The words after a preposition without the closing extent words at their end (:data:`EXTENT_TAILS`), and the
    extent those ask for; the words as they are, and None, where they end otherwise or would be left empty."""
    low = [w.lower() for w in after]
    for k in TAILS_LONGEST_FIRST:
        if len(low) > len(k) and tuple(low[-len(k):]) == k:
            return after[: -len(k)], EXTENT_TAILS[k]
    for k in LONGEST_FIRST:  # "..., but only a smidge", "... just a tad"
        if EXTENTS[k] == "little" and len(low) > len(k) and tuple(low[-len(k):]) == k:
            head = low[:-len(k)]
            said = next((q for q in HEDGES if len(head) > len(q) and tuple(head[-len(q):]) == q), None)
            if said is not None:
                return after[: -len(k) - len(said)], "little"
    return after, None


def take_extent_first(words: list[str]) -> tuple[list[str], str | None]:
    """The words after the verb without a qualifier said before the object ("approach a little the crate to Q",
    "move a bit the cube closer"), and the extent it asks for; only where an article follows it, so "a little cube"
    stays a description."""
    low = [w.lower() for w in words]
    for k in LONGEST_FIRST:
        if len(low) > len(k) + 1 and tuple(low[:len(k)]) == k and low[len(k)] in ("the", "this", "that"):
            return words[len(k):], EXTENTS[k]
    return words, None


HEDGES = (("but", "only"), ("but", "just"), ("only",), ("just",))
"""Words that, before a small extent closing the clause, say it is all that is asked ("but only a smidge")."""


FILLERS = frozenset({"like", "kinda", "sorta", "basically", "literally", "up"})
"""Words people put before how far without meaning anything ("put the ball like right next to the lid", "drag the
domino up snug against B")."""


SIDE_BEFORE_RIGHT = frozenset({"front", "back", "far", "rear", "the", "top", "bottom", "upper", "lower", "near"})
"""Words after which "right" is a side of the table, not how near ("the instrument at the front right next to ...",
"the one on the right next to ...")."""


def take_extent(before: list[str]) -> tuple[list[str], str | None]:
    """The words before a preposition without the qualifiers at their end, and the extent they ask for; the
    outermost decides ("a little farther away": little, "a lot farther away": far). A filler before the qualifier
    or the comparative (:data:`FILLERS`) goes with it ("up further away")."""
    extent = None
    compared = False
    while True:
        low = [w.lower() for w in before]
        if len(low) > 1 and low[-1] in COMPARATIVE_WORDS:  # "further away": a comparative alone says no extent
            before, compared = before[:-1], True
            continue
        if (extent is not None or compared) and len(low) > 1 and low[-1] in FILLERS:
            before = before[:-1]
            continue
        for k in LONGEST_FIRST:
            if len(low) > len(k) and tuple(low[-len(k):]) == k and not (
                    k == ("right",) and low[-2] in SIDE_BEFORE_RIGHT):
                before, extent = before[: -len(k)], EXTENTS[k]
                break
        else:
            return before, extent
