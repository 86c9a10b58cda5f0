"""Words for a thing that no table of the toolkit lists, looked up in WordNet: the last try of a refused sentence.

People call an object by words no kind table (synonyms.py) can foresee: a trade's word ("the Erlenmeyer", "the
Bunsen"), a more general one ("the specs" for goggles, "the vessel" for a mug) or a more particular one ("the
beer mug"). Each author of a held-out corpus brings new ones, so a table grown one word at a time falls behind the
next author. WordNet (Princeton's lexical database, nouns of physical things, shipped as ``data/wordnet/``) relates
words by meaning: a word of a synset an object's kind is (its first :data:`OBJECT_SENSES` senses), of a synset up
to :data:`UP` levels above one (more general) or :data:`DOWN` below (more particular), names that object.

Only inside :func:`looking_up`, which ``chain/clauses.resolve_clauses`` enters once every other reading has refused
a sentence, and only for words no table of the toolkit already gives an object: a sentence read without it is read
exactly as before. Outside it, :func:`singular` only tells the slip mender (typos.py) that a word is a thing's name
("candy", no slip of the pace "canny"; "calc", not a word, may be the calculator clipped). A word that so names two
objects names neither (the description is refused, as any kind two objects share).
"""

from __future__ import annotations

import functools
import gzip
import json
from importlib import resources

from .allowance import Allowance

_ALLOWED = Allowance("l2p_lexicon_reading")

OBJECT_SENSES = 2
"""A kind word's senses, most used first, that say what an object on a table is: those among its first two that are
things, or else its first that is ("mug", whose first senses are a mugful and a face): "can" is a tin can, not a
toilet (its sixth sense), whose other words ("pot", "throne") would then name the can."""
UP = 1
"""Levels of more general words that name an object (goggles -> spectacles, "the specs"); two would reach words that
name nearly anything ("instrumentality", "device", "component"). None above a kind whose senses among things are all
rare ones, where the first is a guess: a stamp is first a stamp mill's pestle, a machine, and "the franking machine"
is no rubber stamp."""
DOWN = 2
"""Levels of more particular words that name an object (burner -> gas burner -> Bunsen burner, "the Bunsen")."""
MIN_LETTERS = 3
"""Shorter words are not looked up: two letters are an abbreviation or a slip more often than a thing's name."""


looking_up = _ALLOWED.inside
"""Allow the words looked up here inside the block (the last try of a sentence refused as written)."""


def allowed() -> bool:
    """Whether words looked up in WordNet may name objects now."""
    return _ALLOWED.now()


@functools.lru_cache(maxsize=1)
def _document() -> dict:
    """The shipped slice of WordNet as stored (read once, on the first look-up)."""
    with resources.files("l2p_bullet.data").joinpath("wordnet/words.json.gz").open("rb") as fh:
        return json.loads(gzip.decompress(fh.read()))


@functools.lru_cache(maxsize=1)
def _nouns() -> dict:
    """The nouns, with the inverse relations made once (about 0.2 s, on the first look-up)."""
    doc = _document()
    hyponyms: list[list[int]] = [[] for _ in doc["hypernyms"]]
    for child, parents in enumerate(doc["hypernyms"]):
        for parent in parents:
            hyponyms[parent].append(child)
    words: list[list[str]] = [[] for _ in doc["hypernyms"]]
    for lemma, senses in doc["lemmas"].items():
        if " " not in lemma and "-" not in lemma and lemma.isalpha() and len(lemma) >= MIN_LETTERS:
            for synset, _rank in senses:
                words[synset].append(lemma)
    eponyms: list[list[str]] = [[] for _ in doc["hypernyms"]]
    for word, synsets in doc["eponyms"].items():
        for synset in synsets:
            eponyms[synset].append(word)
    return {"lemmas": doc["lemmas"], "up": doc["hypernyms"], "down": hyponyms, "words": words, "eponyms": eponyms,
            "plurals": doc["plurals"]}


def singular(word: str) -> str | None:
    """The WordNet lemma ``word`` (lower case) is, or the plural of; None where it is none."""
    nouns = _nouns()
    lemmas = nouns["lemmas"]
    if word in lemmas:
        return word
    if word in nouns["plurals"]:
        return nouns["plurals"][word]
    for cut, add in (("ies", "y"), ("es", ""), ("s", "")):
        if word.endswith(cut) and word[: -len(cut)] + add in lemmas:
            return word[: -len(cut)] + add
    return None


@functools.lru_cache(maxsize=4096)
def words_for(kind: str, kinds_of_their_own: frozenset[str] = frozenset()) -> frozenset[str]:
    """Lower-case words, each with its plural, that name a thing of ``kind`` (a word an object is called by): each
    word whose own first sense among things is one of the related synsets, so that a rare sense never names an object
    ("keyboard" is a rack for keys only in its second sense); and each word of the kind's own senses, which WordNet
    gives as its synonyms whatever else they first mean ("engine" for the locomotive, "cork" for a fishing float),
    but for ``kinds_of_their_own``: words that name a thing of their own that people look for ("phone" is a telephone
    before it is a headphone, and a table without one has no phone)."""
    lemma = singular(kind.lower())
    if lemma is None:
        return frozenset()
    nouns = _nouns()
    common = [s for s, rank in nouns["lemmas"][lemma] if rank <= OBJECT_SENSES]
    senses = common or [nouns["lemmas"][lemma][0][0]]
    related = set(senses)
    for step, levels in (("up", UP if common else 0), ("down", DOWN)):
        front = set(senses)
        for _ in range(levels):
            front = {n for s in front for n in nouns[step][s]} - related
            related |= front
    out = set()
    for s in related:
        for word in nouns["words"][s]:
            if s in senses and word not in kinds_of_their_own or nouns["lemmas"][word][0][0] in related:
                out.update((word, plural(word)) if not word.endswith("s") or word.endswith("ss") else (word,))
        out.update(nouns["eponyms"][s])
    return frozenset(out)


@functools.lru_cache(maxsize=4096)
def same_as(word: str) -> frozenset[str]:
    """Lower-case words, each with its plural, that WordNet gives the same first sense among things as ``word``
    ("nappy" for "diaper"): what a package of them is called by the thing it holds ("the nappies": diaper_pack),
    never a more general word ("cloth") nor a kind of it."""
    lemma = singular(word.lower())
    if lemma is None:
        return frozenset()
    nouns = _nouns()
    first = nouns["lemmas"][lemma][0][0]
    out = set()
    for w in nouns["words"][first]:
        if nouns["lemmas"][w][0][0] == first:
            out.update((w, plural(w)) if not w.endswith("s") or w.endswith("ss") else (w,))
    return frozenset(out)


@functools.lru_cache(maxsize=256)
def groups_of(heads: tuple[tuple[str, tuple[str, ...]], ...], excluded: frozenset[str],
              kinds_of_their_own: frozenset[str] = frozenset()) -> dict[str, frozenset[str]]:
    """Words WordNet relates to the objects' kinds -> the names of the objects of those kinds. ``heads``: each
    object's name and the words that say what it is (synonyms.py gives them); ``excluded``: words with readings of
    their own (a shape's noun, a colour, a word that says nothing of the object), never looked up nor given;
    ``kinds_of_their_own``: as :func:`words_for` takes them."""
    by_word: dict[str, set[str]] = {}
    for name, kinds in heads:
        for k in kinds:
            if k in excluded:
                continue
            for word in words_for(k, kinds_of_their_own):
                if word not in excluded:
                    by_word.setdefault(word, set()).add(name)
    return {w: frozenset(n) for w, n in by_word.items()}


def plural(word: str) -> str:
    """The regular plural of a noun ("box" -> "boxes", "battery" -> "batteries", "mug" -> "mugs")."""
    if word.endswith(("s", "x", "z", "ch", "sh")):
        return word + "es"
    if word.endswith("y") and word[-2:-1] not in "aeiou":
        return word[:-1] + "ies"
    return word + "s"


@functools.lru_cache(maxsize=1)
def motion_verbs() -> frozenset[str]:
    """One-word verbs whose first sense in WordNet changes where a thing is ("zoom", "park", "scoot", "run")."""
    return frozenset(_document()["motion_verbs"])


def moving_verbs_read(text: str, known: frozenset[str], stops: frozenset[str]) -> str:
    """``text`` with each word the toolkit does not know (``known``, lower case) that WordNet's first sense says moves a
    thing written as "move" ("zoom the truck round the cone", "park the red car by the garage"), but for ``stops``,
    words that ask for what the actions cannot do ("throw", "toss")."""
    verbs = motion_verbs()

    def read(word: str) -> str:
        low = word.lower()
        return "move" if low in verbs and low not in known and low not in stops else word

    return " ".join(read(w) for w in text.split(" "))


BEFORE_ADJECTIVE = frozenset({"the", "a", "an", "my", "your", "our", "his", "her", "their", "this", "that", "these",
                              "those", "ur", "da", "teh"})
"""Words after which an unknown word may be an adjective of the description that follows ("the cheap silver spoon")."""


def adjectives_read_past(text: str, known: frozenset[str], nouns: frozenset[str], describing: frozenset[str],
                         stops: frozenset[str]) -> str:
    """``text`` without the words that stand between an article (or a described word) and a noun of the scene
    (``nouns``: its names, kinds, colours, sizes, "thing", "one") that the toolkit does not know (``known``) and that
    WordNet does not know as a thing ("the cheap silver teaspoon", "my lovely old kettle"): said of the object, they
    cannot pick another. Only after an article or a word that describes (``describing``: colours, sizes), never a
    word of ``stops`` (a relation, a negation: "the cube between tray and can"); a noun the scene lacks is kept."""
    words = text.split(" ")
    low = [w.lower().strip(",.;:!?") for w in words]

    def adjective(i: int) -> bool:
        w = low[i]
        return (w.isalpha() and len(w) >= 3 and w not in known and w not in nouns and w not in stops
                and singular(w) is None and w not in motion_verbs())

    keep = [True] * len(words)
    for i in range(1, len(words)):
        if not adjective(i) or words[i - 1][-1:] in ",.;:!?":
            continue
        before = low[i - 1] in BEFORE_ADJECTIVE or low[i - 1] in describing
        j = i + 1
        while j < len(words) and adjective(j) and words[j - 1][-1:] not in ",.;:!?":
            j += 1
        if before and j < len(words) and low[j] in nouns and words[j - 1][-1:] not in ",.;:!?":
            for k in range(i, j):
                keep[k] = False
    return " ".join(w for w, k in zip(words, keep, strict=True) if k)
