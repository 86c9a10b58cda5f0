"""Typing slips in a sentence the grammar refused ("mvoe teh red cube", "the yelow box", "the blu cylnder").

A slip is read as the known word it is one keystroke from: one letter swapped with its neighbour, left out,
added or replaced (Damerau-Levenshtein distance 1), when exactly one known word is that near. Words of three
letters are read only through a swap or a left-out letter ("teh", "blu"): a replaced letter in so short a
word is as likely another word. A word that is known, or that names an object in the scene, is never
changed.

Only a sentence that was refused as written is read again with its slips mended (``chain/clauses.py``), so
a slip can turn a refusal into an answer but never change the answer to a sentence that already read.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Iterable

from . import extents, goals, lexicon, reference_words, words
from .shape_words import SHAPE_NOUNS
from .sounds import heard_key, heard_name, one_sound_apart
from .synonyms import BIG, SMALL, name_parts

_WORD = re.compile(r"[A-Za-z]+(?:'[A-Za-z]+)?")

COMMON = frozenset("""
a an the this that these those it its them they one ones some all both each other another same to of from at
in on onto into by with without for and or but then so is are be been being was were do does did don't not
no yes me my you your we our i i'd i'm let's lets here there where what which who whatever as than up down
over under near nearer nearest far farther further away next toward towards around round past beyond close
closer beside left right front back behind middle side end top bottom edge table again too also very just
only now first second third last until while when if could would should will can may might must shall
please thanks thank mind go goes get gets make sure want like need needs task goal job keep see look there's
bit little lot much more less way little slightly real time times row rows
""".split())
"""Everyday words a sentence holds that no table of the grammar lists; known, so never mended."""
SHORTHAND = {"nxt": "next", "cyl": "cylinder", "cyls": "cylinders", "frm": "from", "n": "and", "r": "are",
             "u": "you", "ur": "your", "thru": "through", "w": "with", "abt": "about", "bc": "because",
             "obj": "object", "blk": "block", "lil": "little", "tho": "though", "bout": "about", "pls": "please",
             "plz": "please", "nr": "near", "mv": "move", "twd": "toward", "twds": "towards", "rnd": "round",
             "yel": "yellow", "wht": "white", "grn": "green", "rly": "really", "rlly": "really", "b4": "before",
             "da": "the", "dat": "that", "dis": "this", "rite": "right", "wit": "with", "ova": "over", "roe": "row"}
SHORTHAND |= {"blew": "blue", "won": "one", "b": "be", "shld": "should", "shd": "should", "shud": "should",
              "em": "them", "thx": "thanks", "thnx": "thanks", "ty": "thanks", "rn": "now", "bk": "back", "thn": "then",
              "read": "red", "buy": "by"}
SHORTHAND |= dict(pair.split("=") for pair in """
    tae=to fae=from frae=from awa=away roon=round roond=round yon=the yin=one pit=put gie=give richt=right muckle=big
    hae=have ye=you dinnae=don't tak=take ower=over wi=with oot=out doon=down aboot=about cannae=can't intae=into
    ontae=onto tek=take mek=make reet=right reight=right tha=you thee=you un=one""".split())
"""Texting shorthand, the colour speech-to-text hears as another word ("the blew block", "the read cube") and Scots
and Northern English words people type among English ones ("shift yon red cube awa fae the box", "tek t'big un past
t'twine"), read as the word each stands for in a refused sentence, as a slip is."""


def vocabulary(phrases: Iterable[str], verbs: Iterable[str], colours: Iterable[str]) -> frozenset[str]:
    """Every word the grammar knows: the installed phrases' and verbs' words, the colour names, the words of
    politeness, framing and pace (language/words.py), of extent (language/extents.py), of references
    (language/reference_words.py), and :data:`COMMON`. Kept by the phrases, verbs and colours: every sentence
    refused as typed asks for it."""
    return _vocabulary(tuple(phrases), tuple(verbs), tuple(colours))


@functools.lru_cache(maxsize=16)
def _vocabulary(phrases: tuple[str, ...], verbs: tuple[str, ...], colours: tuple[str, ...]) -> frozenset[str]:
    """:func:`vocabulary` of its words, made."""
    known: set[str] = set(COMMON)
    for text in (*phrases, *verbs, *colours):
        known.update(_WORD.findall(text.lower()))
    for table in (words.POLITE_PREFIXES, words.POLITE_SUFFIXES, words.FRAMES, words.GERUND_PREFIXES,
                  goals.GOAL_PREFIXES, goals.STATE_LINKS, tuple(extents.EXTENTS)):
        for phrase in table:
            known.update(phrase)
    known.update(words.PACES)
    known.update(extents.COMPARATIVE_WORDS)
    r = reference_words
    for table in (r.DETERMINERS, r.NOUNS, SHAPE_NOUNS, r.SHAPE_ADJECTIVES, r.SOFT_ADJECTIVES, r.COLOR_SYNONYMS,
                  r.FUNCTION_WORDS, r.NEAREST, r.FARTHEST, r.SIZE_SUPERLATIVES, r.REFERENCE_WORDS):
        known.update(table)
    return frozenset(w for w in known if w.isascii())


def near(word: str, known: frozenset[str], named: frozenset[str] = frozenset()) -> str | None:
    """The one known word ``word`` is a slip of, or None (no such word, or several that mean different things;
    "carefuly" is "careful" or "carefully", one pace either way). Of several, the one word that names an object of
    the scene (``named``) is meant: "bowel" is the bowl on the table, not a dowel."""
    if len(word) < 3 or not word.isalpha():
        return None
    lengths = (len(word) - 1, len(word), len(word) + 1)
    words_near = (k for n in lengths for k in _by_length(known).get(n, ())) if len(known) > BY_LENGTH_FROM else known
    hits = {k for k in words_near if len(k) in lengths and _one_slip(word, k)}
    if len(hits & named) == 1:
        hits &= named
    meanings = {words.PACES.get(h, reference_words.COLOR_SYNONYMS.get(h, h)) for h in hits}
    if len(meanings) != 1:  # "blu": blue or bleu, one colour either way
        return None
    return meanings.pop() if meanings <= hits else max(sorted(hits), key=len)


BY_LENGTH_FROM = 64
"""A vocabulary of more words than this is looked through by length (a sentence's vocabulary: thousands of words)."""


@functools.lru_cache(maxsize=16)
def _by_length(known: frozenset[str]) -> dict[int, tuple[str, ...]]:
    """``known``'s words by their length: a slip is within one letter of the word's length."""
    out: dict[int, list[str]] = {}
    for k in known:
        out.setdefault(len(k), []).append(k)
    return {n: tuple(ws) for n, ws in out.items()}


CLIPPED_FROM = 4
"""The fewest letters a word clipped from an object's name keeps ("loco", "steth"): three are a slip or an
abbreviation of anything ("pen", "tin")."""


def clipped(word: str, named: frozenset[str], known: frozenset[str]) -> str | None:
    """The one word of the scene's names that ``word`` is the start of, as people clip a long word ("the loco" for
    the locomotive, "the steth" for the stethoscope), at least two letters longer; None where ``word`` is a word of its
    own (the toolkit's or WordNet's: "pot" is no "potato"), is short, or starts several."""
    if len(word) < CLIPPED_FROM or not word.isalpha() or word in known:
        return None
    fits = [n for n in named if len(n) >= len(word) + 2 and n.startswith(word) and n.isalpha()]
    return fits[0] if len(fits) == 1 and lexicon.singular(word) is None else None


def unvowelled(word: str, known: frozenset[str]) -> str | None:
    """The one known word ``word`` is written as with its vowels left out, as people write notes ("psh", "gntly",
    "bsde", "scrwdrvr"): the same first letter, the same consonants as written or heard, every letter in order and no
    vowel typed but the first or the last letter. None where none or several words are so written ("thn": then, than
    or thin)."""
    if len(word) < 3 or not word.isalpha() or any(c in "aeiou" for c in word[1:-1]):
        return None  # a vowel typed inside is a word of its own ("min" is no "mini", "par" no "paper")
    said, written = heard_key(word), _consonants(word)
    hits = {k for k in known if len(k) > len(word) and k[0] == word[0] and _in_order(word, k)
            and (heard_key(k) == said or _consonants(k) == written)}
    spelt = {k for k in hits if _consonants(k) == written}  # "gntly": gently, not gentle
    hits = spelt if len(spelt) == 1 else hits
    stem = min(hits, key=len, default="")
    return stem if hits and all(h.startswith(stem) for h in hits) else None  # "push", not "pushes"


def _consonants(word: str) -> str:
    """``word``'s letters as written, without the vowels after its first letter, each letter once in a row."""
    return re.sub(r"(.)\1+", r"\1", word[0] + re.sub(r"[aeiou]", "", word[1:]))


def _in_order(word: str, known: str) -> bool:
    """Whether every letter of ``word`` stands in ``known``, in the same order."""
    letters = iter(known)
    return all(c in letters for c in word)


def _one_slip(word: str, known: str) -> bool:
    """Whether ``known`` is one keystroke from ``word`` (in a three-letter word: a swap or a left-out letter)."""
    if word == known:
        return False
    if len(word) == len(known):
        diff: list[int] = []
        for i, (a, b) in enumerate(zip(word, known, strict=True)):
            if a != b:
                diff.append(i)
                if len(diff) > 2:
                    return False
        swap = len(diff) == 2 and diff[1] == diff[0] + 1 and word[diff[0]] == known[diff[1]] \
            and word[diff[1]] == known[diff[0]]
        return swap or (len(diff) == 1 and len(word) > 3)
    if len(word) + 1 == len(known):  # a letter left out
        return _one_left_out(known, word)
    if len(word) == len(known) + 1 and len(word) > 3:  # a letter added
        return _one_left_out(word, known)
    return False


def _one_left_out(longer: str, shorter: str) -> bool:
    """Whether ``shorter`` is ``longer`` with one letter left out: where they first differ, the rest of ``longer``
    after that letter is the rest of ``shorter`` (a letter left out of a run of one letter is left out at its end)."""
    i = next((k for k, (a, b) in enumerate(zip(shorter, longer, strict=False)) if a != b), len(shorter))
    return longer[i + 1:] == shorter[i:]


def squeezed(sentence: str, known: frozenset[str]) -> str:
    """``sentence`` with each word typed with a letter three or more times for emphasis ("slowwwly", "wayyy") read as
    the known word it squeezes to, once or twice (:data:`RUNS`); other words as typed. Read before anything else: a
    pace or an extent so typed is otherwise read past, and the move made without it."""
    def fix(m: re.Match) -> str:
        return _squeezed(m.group(0).lower(), known) or m.group(0)
    return re.sub(r"[A-Za-z]+", fix, sentence) if RUNS.search(sentence.lower()) else sentence


def _squeezed(low: str, known: frozenset[str]) -> str | None:
    """The known word ``low`` (lower case) is with its held-down letters (:data:`RUNS`) typed once, else twice; None
    where it has none or neither is known."""
    return next((s for s in (RUNS.sub(r"\1", low), RUNS.sub(r"\1\1", low)) if s != low and s in known), None)


def mend(sentence: str, known: frozenset[str], names: Iterable[str], verbs: Iterable[str] = (),
         kinds: Iterable[str] = ()) -> str:
    """``sentence`` with each slip replaced by the known word it is one keystroke from (its case as typed for
    the first letter); every other character as it was. A word right after an article is never mended into one of
    ``verbs``: "for a pic" is no "pick", which would make a slide a lift."""
    verbs = frozenset(v.lower() for v in verbs)
    kinds = frozenset(kinds)
    names = list(names)
    spoken = [n for n in names if " " not in n]  # one-word names, as speech-to-text may hear them
    heard_parts = list(dict.fromkeys([*spoken, *(w for n in names for w in name_parts(n) if len(name_parts(n)) > 1
                                                  and w.isalpha() and len(w) >= 3)]))  # "the tape gone"
    keep = {n.lower() for n in names}
    parted = [name_parts(n) for n in names if len(name_parts(n)) > 1]
    named = frozenset(w for n in keep for w in _WORD.findall(n))

    def fix(m: re.Match) -> str:
        w = m.group(0)
        low = w.lower()
        if low in keep or low in named:  # "shaker" of "salt shaker" is no slip of "shakers"
            return w
        following = _next_parts(m, parted)
        heard = heard_name(low, following, amiss=True) if following and low not in kinds \
            and low not in reference_words.COLOUR_WORDS else None
        if heard is not None:  # "the water char", "the paint pit", "the glue stock": a name's next word as heard
            return heard
        if low in SHORTHAND and SHORTHAND[low] in known:
            return SHORTHAND[low]
        if low in PACE_PHRASE_WORDS:  # "with care" is no slip of "with case" beside a glasses case
            return w
        if low in known:
            if low in reference_words.KIND_WORDS and low not in kinds and low not in reference_words.COLOUR_WORDS \
                    and THE_BEFORE.search(m.string, 0, m.start()):
                # "the racer" where no racer stands and the razor sounds just so: the razor ("the orange thing" is
                # a colour, never the ring)
                return heard_name(low, heard_parts) or w
            return w
        if _dropped_g(low, verbs):  # "movin", "pushin", "puttin": a verb's -ing with its g left off
            return w + "g"
        squeezed = _squeezed(low, known)
        if squeezed is not None:  # "wayyy", "waaay", "sooo"
            return squeezed
        hit = near(low, known, named) or unvowelled(low, known | named)
        if hit not in named:  # "the calc": the calculator on the table, not a slip of "calf", which names nothing here
            hit = clipped(low, named, known) or hit
        after_article = ARTICLE_BEFORE.search(m.string, 0, m.start()) is not None
        amiss = THE_BEFORE.search(m.string, 0, m.start()) is not None
        after_subject = SUBJECT_BEFORE.search(m.string, 0, m.start()) is not None
        hyphened = "-" in m.string[max(0, m.start() - 1):m.start()] + m.string[m.end():m.end() + 1]
        heard = heard_name(low, heard_parts, amiss) if (hit is None or (after_article and hit not in named)) \
            and low not in reference_words.KIND_WORDS and not after_subject \
            and not hyphened else None  # "the banana" is no bunny, "you boil water" no bowl, "bean-shaped" no bin
        if heard is not None:  # "the copper" for koppu, "the tease" for tasse; "the art" is the heart, not "at"
            return heard
        if hit is None:
            return w
        if hit in verbs and after_article or hit in named and after_subject:
            return w  # "for a pic" is no "pick"; "the thing you boil water in" is no bowl
        # "candy dish", "the clock", "the soap": a thing of its own (a WordNet noun), no slip of the pace "canny", of
        # "block" or of "soup"; only a name on the table is near enough ("the bowel": the bowl)
        if (hit in words.PACES or hit in reference_words.KIND_WORDS or hit in reference_words.NOUNS) \
                and hit not in named and lexicon.singular(low) is not None:
            return w
        return hit.capitalize() if w[0].isupper() else hit

    said = sentence if keep & FILLER_WORDS else FILLERS.sub("", sentence)
    if not any("\u0131" in n for n in names):  # "slıde C", "lıft ıt": a Turkish keyboard's dotless i
        said = said.replace("\u0131", "i").replace("\u0130", "I")
    said = OTHER_BARE.sub(r"\1the \2", NORTHERN.sub(lambda m: NORTHERN_FOR[m.lastgroup], said))
    nouns = keep | named | set(kinds) | reference_words.COLOUR_WORDS | BIG | SMALL
    said = DEMONSTRATIVE.sub(lambda m: "the " if m.group(1).lower() in nouns else m.group(0), said)
    said = _joined(_lettered(DROPPED_LETTER.sub("", _cut_short(said, names)), names), keep | named | set(kinds), spoken)
    mended = TWO_FOR_TO.sub(r"\1 to", _WORD.sub(fix, TWO_WARDS.sub(r"to\1", said)))  # "2wards" first: no "2cards"
    mended = TWO_BEFORE_THE.sub("to ", mended)
    mended = HEARD_PACES.sub(lambda m: PACE_OF[m.group(1).lower()], HEARD.sub(_heard, mended))
    mended = HANDED.sub(r"\1-hand", mended)
    return mended if "1" in keep else ONE_FOR_ONE.sub(r"\1 one", mended)


CUT_NAME = re.compile(r"(?<![\w-])[A-Za-z0-9]+(?:_[A-Za-z0-9]+)+(?![\w-])")
"""A name written with its underscore, perhaps cut short ("tape_meas")."""


def _cut_short(sentence: str, names: list[str]) -> str:
    """``sentence`` with a name cut short as a note writes it ("tape_meas" for tape_measure) written whole: the one
    name that begins so, the cut keeping at least half of it."""
    def whole(m: re.Match) -> str:
        said = m.group(0).lower()
        fits = [n for n in names if n.lower().startswith(said) and 2 * len(said) >= len(n)]
        return fits[0] if len(fits) == 1 and m.group(0) not in names else m.group(0)

    return CUT_NAME.sub(whole, sentence)


def _next_parts(m: re.Match, parted: list[tuple[str, ...]]) -> list[str]:
    """The words that follow the word before ``m`` in the names of several words (``parted``): "pot" after "paint"."""
    before = WORD_BEFORE.search(m.string, 0, m.start())
    said = before.group(1).lower() if before is not None else None
    return [p[i + 1] for p in parted for i in range(len(p) - 1) if p[i] == said]


def _lettered(sentence: str, names: list[str]) -> str:
    """``sentence`` with a name that ends in a letter said as dictation writes it ("toad bee", "tote bee" for
    tote_B, "the pill bottle hey" for pill_bottle_a): the word before the letter heard as the name's word before its
    letter (as said, or with one sound amiss), then the letter."""
    def said(m: re.Match) -> str:
        word, letter = m.group(1), reference_words.SPOKEN_LETTERS[m.group(2).lower()]
        heard = heard_key(word)
        for n in names:
            parts = name_parts(n)
            meant = heard_key(parts[-2]) if len(parts) >= 2 else ""
            if len(parts) >= 2 and parts[-1] == letter and len(parts[-2]) >= 3 and (
                    word.lower() == parts[-2] or heard == meant or one_sound_apart(heard, meant)):
                return f"{parts[-2]} {letter.upper()}"  # "the pill bottle hey": pill_bottle_a
        return m.group(0)

    return SAID_LETTER.sub(said, sentence)


SAID_LETTER = re.compile(r"\b([A-Za-z]{3,})\s+("
                         + "|".join(sorted(reference_words.SPOKEN_LETTERS, key=len, reverse=True)) + r")\b",
                         re.IGNORECASE)
"""A word, then a letter as it is said ("toad bee")."""


def _dropped_g(low: str, verbs: frozenset[str]) -> bool:
    """Whether ``low`` is a verb's -ing form typed without its g ("movin", "slidin", "puttin", "carryin")."""
    if len(low) < 5 or not low.endswith("in"):
        return False
    stem = low[:-2]
    return bool({stem, stem + "e", stem[:-1] if len(stem) > 2 and stem[-1] == stem[-2] else stem} & verbs)


def _joined(sentence: str, named: set[str] | frozenset[str], spoken: list[str] = ()) -> str:
    """``sentence`` with a name or a kind said as two words written as one ("the note book" -> "the notebook", "the
    mini fig" -> "the minifig", "the flat head" -> "the flathead", "the sugar bowl" -> "the sugarbowl"), or heard so
    ("the cue sue" for kyusu); read only in a sentence refused as written. Two words of one name stay as said."""
    pairs = {pair for n in spoken for parts in [name_parts(n)] for pair in zip(parts, parts[1:], strict=False)}
    found = list(_WORD.finditer(sentence))
    targets = set(named) | {re.sub(r"[^a-z]", "", n) for n in named if "-" in n}  # "post it" for Post-it
    long_targets = sorted(t for t in targets if len(t) >= 6)
    said_alone = named | COMMON  # words that say something of their own: never heard as half of a name
    out, at = [], 0
    for a, b in zip(found, found[1:], strict=False):
        one = (a.group(0) + b.group(0)).lower()
        if a.start() < at or not sentence[a.end():b.start()].isspace() \
                or (a.group(0).lower(), b.group(0).lower()) in pairs:
            continue  # "the left block", "the mustard bottle": a name's own words, read as they are
        slipped = len(one) >= 6 and len(b.group(0)) > 1
        meant = one if one in targets else next((t for t in long_targets if slipped and _one_slip(one, t)), None) or (
            heard_name(one, spoken) if not {a.group(0).lower(), b.group(0).lower()} & said_alone else None)
        if meant is not None:  # "the mole skin", "the sharp e": a slip of the name run together
            out.append(sentence[at:a.start()] + meant)
            at = b.end()
    return "".join(out) + sentence[at:]


PACE_PHRASE_WORDS = frozenset(w for phrase in words.PACE_PHRASES for w in phrase)
"""The words of the pace phrases ("with care", "no rush"): never mended into another word, never a mend's target."""
NORTHERN = re.compile(r"\b(?:(?P<the>t)['\u2019](?=[a-z])|(?P<and>an)['\u2019](?=\s)|(?P<of>o)['\u2019](?=\s))",
                      re.IGNORECASE)
"""Northern English as typed: "t'" for "the" before its noun ("put t'trowel by t'pot"), "an'" for "and", "o'" for
"of" ("t'ball o' twine"), each said with its apostrophe (a word of its own without one is another word)."""
NORTHERN_FOR = {"the": "the ", "and": "and", "of": "of"}
OTHER_BARE = re.compile(r"(^\s*|[.;!?]\s+|\b(?:then|and|now)\s+)(other)\b(?=\s+[a-z])", re.IGNORECASE)
"""A clause that opens on "other" without its article, as notes are typed ("red pawn by the bag. other pawn by the
deck"): "the other"."""
DEMONSTRATIVE = re.compile(r"\b(?:these|those|them)\s+(?=([A-Za-z]+))", re.IGNORECASE)
"""A plural demonstrative before what an object is called: "those gloves" for the pair named gloves, "them cards" as
many people say "those cards". Read as "the" only before a name, a kind, a colour or a size of the table; "them" before
anything else is the pronoun."""
DROPPED_LETTER = re.compile(r"(?<=[a-z])'(?=\s)")
"""An apostrophe that marks a letter left off a word's end ("awa' fae", "o' the"): the word as typed."""
ARTICLE_BEFORE = re.compile(r"\b(?:a|an|the)\s+$", re.IGNORECASE)
"""An article right before a word: what follows names a thing, never a verb."""
SUBJECT_BEFORE = re.compile(r"\b(?:you|u|i|we|they|people)\s+$", re.IGNORECASE)
"""A subject right before a word: what follows is what someone does, never a thing's name heard amiss."""
THE_BEFORE = re.compile(r"\bthe\s+$", re.IGNORECASE)
WORD_BEFORE = re.compile(r"\b([A-Za-z]+)\s+$")
"""The word right before another (a name's first word: "water" before "char")."""
"""A thing said with "the" ("the kennel"): only such a word may be a name heard with one sound amiss."""
RUNS = re.compile(r"([a-z])\1{2,}")
"""A letter typed three or more times for emphasis ("wayyy past", "sooo slowly"): read once or twice."""
TWO_FOR_TO = re.compile(r"\b(closer|close|nearer|near|next|up|over|back|right|on|onto|according)\s+"
                        r"(?:2\b(?=\s+[a-z])|two\b(?=\s+(?:the|it|that|this|them)\b))", re.IGNORECASE)
""""2" texted for "to" after the word a preposition starts with ("closer 2 the white block", "next 2 it"); a number
elsewhere is left as typed."""
TWO_WARDS = re.compile(r"\b2(wards?)\b", re.IGNORECASE)
""""2wards" texted for "towards"."""
TWO_BEFORE_THE = re.compile(r"(?<=[a-z] )2 (?=the\b)", re.IGNORECASE)
""""2" texted for "to" before an article ("move the green cube 2 the bowl"): no number stands before "the"."""
ONE_FOR_ONE = re.compile(r"\b(red|green|blue|yellow|white|black|orange|purple|pink|grey|gray|brown|big|small|little|"
                         r"other|front|back|left|right|tall|short|last|first)\s+1\b(?!\s*(?:cm|mm|m)\b)", re.IGNORECASE)
""""1" texted for "one" after an adjective ("the blue 1", "the other 1"), where no object is named "1"."""
HEARD = re.compile(r"\b(?:(?P<passed>passed)|(?P<a_round>a\s+round))\s+(?=(?:the|it|that|this|them)\b)"
                   r"|\b(?P<a_way>a\s+way)\s+(?=from\b)", re.IGNORECASE)
"""What speech-to-text hears for a preposition ("passed the bowl", "a round the bowl", "a way from it"), read as the
preposition before an article, a pronoun or "from" ("next two the plate": :data:`TWO_FOR_TO`)."""
HEARD_AS = {"passed": "past ", "a_round": "around ", "a_way": "away "}
HANDED = re.compile(r"\b(left|right)\s+hand\b(?=\s+[a-z])", re.IGNORECASE)
""""the right hand shaker", "on the left hand side": the side as one word, as the place readers know it."""
HEARD_PACES = re.compile(r"\b(slow|quick|careful|gentle)\s+lee\b", re.IGNORECASE)
"""A pace adverb heard as two words ("slow Lee"): one word again."""
PACE_OF = {"slow": "slowly", "quick": "quickly", "careful": "carefully", "gentle": "gently"}


def _heard(m: re.Match) -> str:
    return next(HEARD_AS[group] for group, said in m.groupdict().items() if said)


FILLERS = re.compile(r"\b(?:u+m+|u+h+m*|e+r+m+|h+m+)\b[,.]*\s*", re.IGNORECASE)
"""Hesitations a speech-to-text transcript or a typist leaves anywhere ("um the ball um move it ..."): read past."""
FILLER_WORDS = frozenset({"um", "umm", "uh", "uhh", "uhm", "erm", "hmm", "hm"})
"""Fillers as a scene might name an object: where one does, the fillers stay as typed."""
