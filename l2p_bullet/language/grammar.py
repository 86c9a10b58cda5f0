"""Sentence -> :class:`Command`, from the phrases the installed action plugins declare.

The grammar is deliberately small and predictable: ``[polite words] VERB MOVER PREPOSITION ANCHOR``,
for example "move A around B" or "Please slide the red block around the green one.", and for an action
that declares two reference objects (``anchors = 2``) ``... PREPOSITION ANCHOR and ANCHOR``, as in
"put A between B and C". Prepositions
are not hard-coded: they are the phrases of the installed manifests (``phrases`` maps each phrase to
its action), so installing a plugin teaches the parser a new preposition. When several phrases match,
the longest wins ("to the left of" over "left of", "closer to" over "to").

Around that core people add words: politeness and framing ("could you ...", "so that it is"), which
are dropped, and qualifiers of the manner ("slowly") and of the preposition ("far away from"), which
the command records (``pace``, ``extent``: language/words.py). Objects are named, described or pointed
back to (language/references.py). Every failure is a :class:`LanguageError` (or :class:`UnknownObjectError`) that says
which
words were not understood and suggests the closest known ones, because the person typing the sentence
cannot see the grammar.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass, replace

from ..core.scene import Scene
from ..core.vocabulary import normalize_phrase
from ..errors import LanguageError, UnknownObjectError, did_you_mean
from ..manners import registry as manners
from . import lenient
from .anchors import measured_context, mover_in_relation, noun_carried, twin_of
from .extents import take_extent, take_extent_first, take_extent_tail
from .goals import goal_to_verb, passive_to_verb, said_now, state_to_verb
from .group_places import GENERIC
from .naming import naming_words
from .phrase_readings import TIGHT, phrase_tokens, readings, without_to
from .pronouns import Context
from .reference_words import BLOCK_WORDS, DETERMINERS, SHAPE_ADJECTIVES
from .references import POSSESSIVES, object_pairs, resolve_object, try_object
from .synonyms import kind_groups
from .verbs import EXAMPLE, IN_THE_AIR, _on_the_table, _verb_patterns, _without, known_verbs, split_verb, verb_heads
from .words import (
    by_gerund,
    drop_frames,
    gerund_to_verb,
    skip_to_verb,
    strip_polite,
    take_pace,
)

MAX_SENTENCE = 200
"""Longest sentence read, in characters: a command is a few words; a longer text is refused at once
(parsing is quadratic in the words, and an error must not echo kilobytes back)."""


@dataclass(frozen=True)
class Command:
    """What a sentence asks for: ``mover`` and ``anchor`` are object names, ``action`` the plugin name.

    ``anchors`` lists every reference object in the sentence's order; ``anchor`` is the first (the only
    one for a one-anchor action: "move A next to B").
    """

    verb: str
    mover: str
    preposition: str
    action: str
    anchor: str
    sentence: str = ""
    anchors: tuple[str, ...] = ()
    manner: str = "slide"  # the manner of motion the verb asks for (l2p_bullet/manners)
    pace: str | None = None  # "slowly", "gently"...: language/words.PACES (None: the manner's own pace)
    extent: str | None = None  # "far away", "a bit closer", "right next to": language/extents.EXTENTS
    manner_why: str | None = None  # why ``manner`` is not the verb's own (pipeline.feasible_as); None: it is

    def __post_init__(self) -> None:
        if not self.anchors:
            object.__setattr__(self, "anchors", (self.anchor,))
        elif self.anchors[0] != self.anchor:
            raise ValueError(f"anchors {self.anchors} must start with the anchor {self.anchor!r}")

    @property
    def more_anchors(self) -> tuple[str, ...]:
        """The reference objects after the first (a two-anchor action's second)."""
        return self.anchors[1:]


ARROWS = frozenset({"->", "-->", "=>", "=", "\u2192", "-", "--", "\u2013", "\u2014"})
"""Arrows typed for "goes" ("the mug -> around the box") and lone dashes: read past, leaving a command without its
verb."""


REPEATED = frozenset({"very", "really", "super", "so", "much"})
"""Intensifiers people double for emphasis ("very very far from"): the second says nothing the first did not."""


def tokens(sentence: str) -> list[str]:
    """Words without surrounding punctuation ("one." -> "one") and arrows, a doubled intensifier once
    (:data:`REPEATED`); apostrophes inside words are kept."""
    words = [w.strip(".,;:!?\"()[]") for w in sentence.split() if w not in ARROWS]
    out: list[str] = []
    for w in words:
        if w and not (out and w.lower() in REPEATED and out[-1].lower() == w.lower()):
            out.append(w)
    return out


def parse(sentence: str, scene: Scene, phrases: dict[str, str], anchors: dict[str, int] | None = None, *,
          extents: dict[str, frozenset[str]] | None = None, context: Context | None = None) -> Command:
    """Parse ``sentence`` against the objects of ``scene`` and the installed ``phrases`` (phrase -> action).

    ``anchors`` says how many reference objects each action's sentences name (action -> 1 or 2; 1 when
    not listed): a two-anchor action reads "B and C" after its phrase. ``extents`` says which qualifiers
    ("far", "a bit", "right": language/extents.EXTENTS) each action accepts (none when not listed);
    ``context`` is what pronouns ("it", "the other one") point back to: the previous clause. Where the
    grammar refuses it inside :func:`lenient.reading_past`, the lenient reading is tried (language/lenient.py).
    """
    try:
        return _parse(sentence, scene, phrases, anchors, extents=extents, context=context)
    except (LanguageError, UnknownObjectError):
        if not lenient.allowed() or not isinstance(sentence, str) or len(sentence) > MAX_SENTENCE:
            raise
        keep = frozenset(scene.names)  # the words as typed: no verb made from a statement ("A was next to B")
        said = tokens(sentence)
        if said_now([w.lower() for w in said]):  # "Right now A is far from B": how it is, not a wish
            raise
        words, pace = take_pace(strip_polite(said, keep), keep)
        found = lenient.read(words, scene, readings(phrases), [(h, d, m) for h, _, d, m in _verb_patterns()],
                             anchors or {}, extents or {}, context)
        if found is None:
            raise
        return Command(found.verb, found.mover, found.phrase, found.action, found.anchors[0], sentence.strip(),
                       found.anchors, found.manner, pace, found.extent)


RELATIVE_ENDS = frozenset({("whatever", "is"), ("whatever's",), ("whatevers",), ("whichever", "is"),
                           ("what", "is"), ("what's",), ("that", "is"), ("that's",), ("which", "is"), ("who", "is")})
"""Words that end a description with a place of its own ("the one that is next to B", "whatever's by the cup"): the
phrase after them is never the command's preposition."""

ARTICLES = frozenset({"the", "this", "that", "these", "those"})


def _adjective_here(low: list[str], i: int) -> bool:
    """Whether the one-word phrase at ``low[i]``, a shape word too ("round"), stands as an adjective: after an article
    ("the round block") or before a noun that names any object (:data:`~.group_places.GENERIC`: "the littlest round
    one"). "Take the mat round the teapot" and "move A round B" (never "a", which may be a block's name) keep their
    preposition."""
    return (i > 0 and low[i - 1] in ARTICLES) or (i + 1 < len(low) and low[i + 1] in GENERIC)


def _parse(sentence: str, scene: Scene, phrases: dict[str, str], anchors: dict[str, int] | None = None, *,
           extents: dict[str, frozenset[str]] | None = None, context: Context | None = None) -> Command:
    """:func:`parse` as the grammar reads a sentence."""
    if not isinstance(sentence, str) or not sentence.strip():
        raise LanguageError(f"the sentence is empty; {EXAMPLE}")
    if len(sentence) > MAX_SENTENCE:
        raise LanguageError(f"the sentence is {len(sentence)} characters long; a command has at most {MAX_SENTENCE} "
                            f'("{sentence[:30].strip()}..."); {EXAMPLE}')
    if not phrases:
        raise LanguageError("no action plugins are installed, so no preposition is known (see: l2p-bullet actions)")
    words, pace = command_words(sentence, scene)
    if not words:
        raise LanguageError(f'"{sentence.strip()}" asks for nothing; {EXAMPLE}')
    try:
        verb, manner, rest = split_verb(words)
    except LanguageError as no_verb:
        if not _verbless(words, phrases):
            raise
        try:  # "duck closer to ball": a note of the end wanted, the verb left out
            cmd = _parse(f"move {' '.join(words)}", scene, phrases, anchors, extents=extents, context=context)
            return replace(cmd, pace=cmd.pace or pace, sentence=sentence.strip())
        except (LanguageError, UnknownObjectError) as verbless:
            raise (verbless if _mover_said(words, scene, phrases, context) else no_verb) from None
    if manner == manners.DEFAULT and verb.lower() in NEUTRAL_VERBS and _without(rest, IN_THE_AIR) != rest:
        manner = "carry"  # "Move the small red cube through the air away from the bar": a carry
    rest = _on_the_table(rest, manner, sentence)
    if not rest:
        raise LanguageError(f'"{sentence.strip()}" does not say what to {verb}; {EXAMPLE}')
    low = [w.lower() for w in rest]
    # The longest phrase wins; among its positions the first that names two objects. If no phrase
    # gives a valid reading, the error of the longest phrase's first reading is the most useful one.
    first_error: Exception | None = None
    present = set(low)  # a phrase none of whose first words is said is passed over in the order the loop tries them
    for toks, phrase, action, implied in readings(phrases) + without_to(phrases):
        if toks and toks[0] not in present:
            continue
        n = len(toks)
        for i in range(0, len(low) - n + 1):
            if tuple(low[i : i + n]) != toks:
                continue
            if tuple(low[max(0, i - 2):i]) in RELATIVE_ENDS or tuple(low[max(0, i - 1):i]) in RELATIVE_ENDS:
                continue  # "to whatever is next to the pincushion": a description's place, not the command's
            if n == 1 and low[i] in SHAPE_ADJECTIVES and _adjective_here(low, i):
                continue  # "the littlest round one": "round" describes, it is not "around"
            try:
                lead = rest[:i - 1] if implied and i > 1 and low[i - 1] in INTENSIFIERS else rest[:i]
                before, said, mover = _mover(lead, scene, context)  # "really far from": far, as "far from"
                extent = said or implied
                after, closing = take_extent_tail(rest[i + n:])
                if closing is not None and extent not in (None, closing):
                    raise LanguageError(f'"{sentence.strip()}" asks for a {extent} and a {closing} extent; say one')
                said, extent = said or closing, extent or closing
                twin = twin_of(after, mover, before, scene)
                refs = (twin,) if twin is not None else _references(
                    noun_carried(after, before), scene, phrase, (anchors or {}).get(action, 1),
                    context or measured_context(before, scene) or mover_in_relation(after, mover))
            except (LanguageError, UnknownObjectError) as e:
                first_error = first_error or e
                continue
            if context is not None and _it_again(after, context, mover) and (
                    mover in refs or (TOO_END.search(sentence) and refs[0] == context.mover)):
                # "bring it away from it": the second "it" is the other one; "then W next to it too": W as well
                refs = (context.anchor, *refs[1:])
            if mover in refs:
                first_error = first_error or LanguageError(
                    f'the block to move and the reference block are both "{mover}": '
                    f"a block cannot be moved {phrase} itself")
                continue
            accepted = (extents or {}).get(action, frozenset())
            if said is None and implied == TIGHT and TIGHT not in accepted:
                extent = None  # "against" of an action without a tight gap: the phrase alone asks for none
            if extent is not None and extent not in accepted:
                said = " ".join(rest[len(before):i])
                asked, said = (f"{said} {phrase}", said) if said else (" ".join(rest[i + n + len(after):]),) * 2
                raise LanguageError(f'"{asked}" asks for a {extent} extent, which "{phrase}" does not have '
                                    f"(it takes: {', '.join(sorted(accepted)) or 'none'}); drop \"{said}\"")
            return Command(verb, mover, phrase, action, refs[0], sentence.strip(), refs, manner, pace, extent)
    middle = _unplaced_words(rest, scene)
    if first_error is not None and (middle is None or _contains_phrase(middle, phrases)):
        raise first_error
    raise _unknown_preposition(rest, middle, phrases, verb)


INTENSIFIERS = frozenset({"really", "very", "super", "so", "quite", "extra"})
"""Words before a phrase that says how far itself ("really far from", "very far away from"): read past."""
NEUTRAL_VERBS = frozenset({"move", "take", "bring", "get", "shift", "put", "place", "transport", "translate"})
"""Verbs that say nothing of how: with words that lift the object ("through the air") they are a carry."""

TOO_END = re.compile(r"\b(?:too|as\s*well|also)\s*[.!?]*\s*$", re.IGNORECASE)
"""A clause that ends by saying it repeats the clause before for another mover ("then W next to it too")."""


def _it_again(words: list[str], context: Context | None, mover: str) -> bool:
    """Whether the reference is "it" again after "it" moved ("The cup is too near to the duck. Bring it away from
    it."; "slide the rock toward the cup, then shove it past it"): the other object of the clause before."""
    return context is not None and context.anchor not in (None, mover) and [w.lower() for w in words] == ["it"]


def _verbless(words: list[str], phrases: dict[str, str]) -> bool:
    """Whether ``words`` read as a command with its verb left out, as notes are typed ("W closer to stone", "cup
    just a touch closer to duck"): an installed phrase after at least one word, no word that says something
    is or should be so ("the cup is next to the box" states, it does not ask), and no verb later on."""
    low = [w.lower() for w in words]
    if set(low) & {"is", "are", "was", "were", "be", "should", "must", "isn't", "aren't", "not"}:
        return False
    if set(low[1:]) & verb_heads():
        return False  # "Of the two small cubes, move the one ...": the verb is there, after an opening
    return bool(_phrase_starts(low, phrases))


def _phrase_starts(low: list[str], phrases: dict[str, str]) -> list[int]:
    """Where an installed phrase starts in the lower-case words ``low``, after at least one word."""
    return [i for i in range(1, len(low)) for t, _, _, _ in readings(phrases) if tuple(low[i:i + len(t)]) == t]


def _mover_said(words: list[str], scene: Scene, phrases: dict[str, str], context: Context | None) -> bool:
    """Whether the words of a verbless command before its first phrase are its mover: they name an object, with or
    without an extent ("bottle past the wedge", "the bottle a bit past the wedge"), or are one word that is no slip of
    a verb ("tin next to the wedge"). Then what its reading refused (the unknown "wedge", "tin") is the reason to
    give, not that "bottle" or "tin" is no verb."""
    low = [w.lower() for w in words]
    starts = _phrase_starts(low, phrases)
    if not starts:
        return False
    before = words[:min(starts)]
    if len(before) == 1:
        return not did_you_mean(low[0], known_verbs())
    plain = take_extent(before)[0]
    return any(try_object(" ".join(drop_frames(said)), scene, context) is not None
               for said in (before, plain) if said) or _a_description(plain)


VERBLESS_DESCRIPTION = 4
"""Most words after its article a verbless command's unknown mover may have and still be read as a description ("the
blue digger next to the red pot"): a longer run of words before the phrase says more than which object."""
SAYS_WHAT_IS = frozenset({"goes", "go", "belongs", "needs", "need", "should", "shall", "will", "would", "has", "have",
                          "gets", "ends", "stays", "sits", "wants", "want", "must", "can", "could", "moves", "is",
                          "are", "been", "being", "i", "it", "you", "we", "they", "he", "she", "me"})
"""Words that make the words before a phrase a clause of their own ("the blue digger goes next to ...", "the
pastillero i want it more far of ..."), no description."""


def _a_description(before: list[str]) -> bool:
    """Whether ``before`` reads as a description of an object the scene does not know: an article, a demonstrative or
    a possessive, then at most :data:`VERBLESS_DESCRIPTION` words, none of :data:`SAYS_WHAT_IS` ("the blue digger",
    "my amber vial", "that red tin")."""
    low = [w.lower() for w in before]
    return 2 <= len(low) <= VERBLESS_DESCRIPTION + 1 and (low[0] in DETERMINERS or low[0] in POSSESSIVES) \
        and not SAYS_WHAT_IS & set(low) and all(w.isalpha() for w in low)


def _mover(words: list[str], scene: Scene, context: Context | None) -> tuple[list[str], str | None, str]:
    """(the mover's words, the extent before the preposition, the mover's name): the qualifiers at the end are
    an extent ("A a bit closer to"), unless the mover's description needs them ("the one on the far right")."""
    before, extent = take_extent(words)
    if extent is None:
        first, extent = take_extent_first(before)
        before = first if extent is not None else before
    try:
        return before, extent, resolve_object(" ".join(drop_frames(before)), scene, "block to move", context)
    except (LanguageError, UnknownObjectError):
        if extent is None:
            raise
        whole = try_object(" ".join(drop_frames(words)), scene, context)
        if whole is None:
            raise
        return words, None, whole


def command_words(text: str, scene: Scene) -> tuple[list[str], str | None]:
    """The words of the command itself (politeness, a goal's or a gerund's opening and manner adverbs
    taken out) and the pace the adverbs ask for; a word that names an object always stays."""
    keep = frozenset(scene.names)
    verbs = known_verbs()
    heads = _first_words(tuple(verbs))
    said = tokens(text)
    words = gerund_to_verb(strip_polite(said, keep), verbs)
    is_object = lambda t: try_object(t, scene) is not None  # noqa: E731
    words = goal_to_verb(state_to_verb(passive_to_verb(words, verbs, is_object), verbs, is_object, said), verbs)
    words, pace = take_pace(words, keep)
    named = naming_words(scene)  # "Of the two blue cubes, push ...", "of the 2 rectangular blocks move ...": an
    # opening about objects is not skipped
    groups = kind_groups(scene)
    naming = keep | frozenset(w for w in words if (low := w.lower()) in named or low in BLOCK_WORDS
                              or low in SHAPE_ADJECTIVES or _plural_of(low, groups))
    return by_gerund(strip_polite(skip_to_verb(words, heads, naming), keep), verbs), pace


def _plural_of(word: str, groups: dict) -> bool:
    """Whether ``word`` is the plural of a kind several objects share (``groups``: "lenses" where two lenses stand,
    "dishes"): an opening that names a group ("the lenses, move the smaller one ...") is kept, never skipped as words
    about nothing before the verb (the smaller one of all would be moved)."""
    return len(word) > 3 and word.endswith("s") and (len(groups.get(word[:-1], ())) > 1
                                                    or word.endswith("es") and len(groups.get(word[:-2], ())) > 1)


@functools.lru_cache(maxsize=8)
def _first_words(verbs: tuple[str, ...]) -> list[str]:
    """The verbs' first words, sorted: where a command's own words start. Kept by the verbs (every reading asks)."""
    return sorted({v.split()[0] for v in verbs})


def manner_of_sentence(sentence: object) -> str:
    """The manner a recorded sentence's verb asks for ("carry A past B": carry); slide when there is no
    sentence or its verb is no installed manner's (a replayed plan does what its sentence said)."""
    if not isinstance(sentence, str) or len(sentence) > MAX_SENTENCE:
        return "slide"
    words = strip_polite(tokens(sentence))
    try:
        return split_verb(words)[1] if words else "slide"
    except LanguageError:
        return "slide"


def _references(words: list[str], scene: Scene, phrase: str, count: int,
                context: Context | None = None) -> tuple[str, ...]:
    """The ``count`` reference objects named by ``words`` (after the preposition)."""
    role = f'reference block after "{phrase}"'
    if count == 1:
        _one_reference(words, scene, phrase)
        return (resolve_object(" ".join(words), scene, role, context),)
    first_error: Exception | None = None
    for pair in object_pairs(words, scene, (f"first {role}", f"second {role}"), context):
        if not isinstance(pair, tuple):
            first_error = first_error or pair
            continue
        if pair[0] == pair[1]:
            raise LanguageError(f'the two reference blocks are both "{pair[0]}": "{phrase}" needs two different '
                                "blocks")
        return pair
    if first_error is not None:
        raise first_error
    raise LanguageError(f'"{phrase}" needs two reference blocks, as in "move A {phrase} B and C"'
                        + (f' (got "{" ".join(words)}")' if words else ""))


TRAILING_JOINS = (("and", "then"), ("after", "that"), ("then",), ("and",))
"""Words that join a next clause (chain/clauses.py), left at a sentence's end with no clause after them."""


def trailing_join(words: list[str]) -> str | None:
    """The joining words (:data:`TRAILING_JOINS`) that ``words`` end with after something else, or None."""
    low = tuple(w.lower() for w in words)
    for join in TRAILING_JOINS:
        if len(low) > len(join) and low[-len(join):] == join:
            return " ".join(words[-len(join):])
    return None


def dangling_join(said: str) -> LanguageError:
    """The error for a sentence that ends with the joining words ``said`` and no clause after them."""
    return LanguageError(f'the sentence ends with "{said}" but no clause follows it; add the next clause '
                         f'("..., {said} move C past A") or drop "{said}"')


def _one_reference(words: list[str], scene: Scene, phrase: str) -> None:
    """Two slips that would otherwise read as 'no block called "B then"': a sentence that ends with a
    joining word and no clause after it ("move A around B, then"), and two blocks after a one-block
    preposition ("move A around B and C")."""
    said = trailing_join(words)
    if said is not None and try_object(" ".join(words[: -len(said.split())]), scene) is not None:
        raise dangling_join(said)
    if _try_pair(words, scene):
        raise LanguageError(f'"{phrase}" takes one reference block, but "{" ".join(words)}" names two; name one, '
                            f'as in "move A {phrase} B"')


def _try_pair(words: list[str], scene: Scene) -> bool:
    """Whether ``words`` read as "OBJECT and OBJECT"."""
    try:
        _references(words, scene, "", 2)
    except (LanguageError, UnknownObjectError):
        return False
    return True


def _contains_phrase(text: str, phrases: dict[str, str]) -> bool:
    low = tuple(text.lower().split())
    return any(low[i : i + len(t)] == t for t, _, _ in phrase_tokens(phrases) for i in range(len(low)))


def _unplaced_words(rest: list[str], scene: Scene) -> str | None:
    """The words between the longest object description at the start and one at the end, if any."""
    for i in range(len(rest) - 1, 0, -1):
        if try_object(" ".join(rest[:i]), scene) is None:
            continue
        for j in range(i + 1, len(rest)):
            if try_object(" ".join(rest[j:]), scene) is not None or _try_pair(rest[j:], scene):
                return " ".join(rest[i:j])
    return None


def _unknown_preposition(rest: list[str], middle: str | None, phrases: dict[str, str], verb: str) -> LanguageError:
    """Say which words sit where a preposition should be, and which prepositions are installed: each action's first
    phrase, and how many other ways to say them there are (a list of every phrase would run past an error's one line,
    cutting off what follows it; `l2p-bullet actions` lists them all)."""
    known = sorted({normalize_phrase(p) for p in phrases})
    first: dict[str, str] = {}
    for phrase, action in phrases.items():
        first.setdefault(action, normalize_phrase(phrase))
    shown = sorted(set(first.values()))
    others = len(known) - len(shown)
    listing = f"installed: {', '.join(shown)}" + (f", and {others} other ways to say them (l2p-bullet actions lists "
                                                  "every phrase)" if others > 0 else "")
    if middle is None:
        if len(rest) >= 2:
            return LanguageError(f'cannot find a preposition in "{" ".join(rest)}" ({listing}); {EXAMPLE}')
        return LanguageError(f"the sentence does not say where to {verb} the block: no preposition ({listing})")
    return LanguageError(f'"{middle}" is not a preposition I know ({listing}).' + did_you_mean(middle.lower(), known))
