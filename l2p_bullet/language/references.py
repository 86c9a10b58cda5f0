"""Words that name an object -> the object's name, resolved against the scene before anything moves.

People name objects many ways: by name ("A", "block A", "the duck"), colour ("the red one"), shape
("the box", "the cylinder", "the tall one"), a superlative ("the biggest one", "the block nearest the
robot", "the leftmost block"), a relation to another object ("the one left of B") or a pronoun that
points back to the previous clause ("it", "that one": its mover; "the other one": its anchor), which
language/pronouns.py reads.

Every reading is checked against the scene: a description that fits several objects is a one-line
error that lists them (a refusal beats a wrong block), and so is one that fits none. Left and right are
the robot's (the scene's +y is its left, DESIGN.md section 4), the view of a person behind it.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from ..core.scene import COLORS, ROBOT_BASE_XY, Scene, SceneObject
from ..errors import LanguageError, UnknownObjectError
from . import lexicon
from .descriptions import candidates, describe, described
from .group_places import in_group, table_sides
from .kept import SceneMemo
from .letters import marked_with, named_after_the
from .likeness import coloured_like, looks
from .naming import name_words, shape_named, spelled_name
from .numbers import number_reference
from .other_than import other_than
from .partitives import holding, name_and_kind, of_compound, partitive
from .places import (
    RANKS,
    bearing_off,
    bulk_superlative,
    comparative_of,
    distance_to,
    measure,
    one_word_comparisons,
    places_as_superlatives,
    ranked,
    relation_head,
    superlative,
)
from .pools import either_reading
from .pronouns import Context, _pronoun, named_before
from .proportions import PROPORTION_NOUNS
from .reference_words import (
    CENTRE_PHRASES,
    COLOR_SYNONYMS,
    CONJUNCTIONS,
    DETERMINERS,
    DIRECT_CONE,
    DOUBT_RATIO,
    FARTHEST,
    NAMED_AS,
    NEAREST,
    NOUNS,
    OPENINGS,
    PLACE_MEASURES,
    RELATIVES,
    ROBOT_WORDS,
    SHAPE_ADJECTIVES,
    SIDE_CONE,
    SIDE_DOUBT,
    SIDE_PHRASES,
    SIDES,
    SIZE_SUPERLATIVES,
    TABLE_WORDS,
    TIE_M,
)
from .relating import beside_as_said, describes, picks_among
from .shape_words import SHAPE_NOUNS
from .synonyms import LOOSE_NOUNS, kind_groups, kind_groups_of, scene_key
from .uses import used_for
from .words import by_word


def resolve_object(text: str, scene: Scene, role: str = "block", context: Context | None = None) -> str:
    """The name of the object ``text`` refers to; a one-line error when none or several fit. Kept per scene
    (language/kept.py): a sentence's readings ask for the same words many times."""
    return _RESOLVED.ask((text, role, context, lexicon.allowed()), scene, lambda: _resolve(text, scene, role, context))


_RESOLVED = SceneMemo(4096)
"""What :func:`resolve_object` answered, by words, role, context and the scene's objects."""


def try_object(text: str, scene: Scene, context: Context | None = None) -> str | None:
    """:func:`resolve_object`, or None where ``text`` names no one object: for readers that try several spans."""
    try:
        return resolve_object(text, scene, context=context)
    except (LanguageError, UnknownObjectError):
        return None


def measured_from(text: str, scene: Scene, context: Context | None = None) -> str | None:
    """The object a relational description measures from ("the object nearest the cylinder": the cylinder), or
    None (no relation, or one to the robot): what "it" later in the same clause means ("move the object nearest
    the cylinder away from it"), since the block moved cannot be moved away from itself."""
    words = _plain_order(text.split(), scene)
    low = tuple(w.lower() for w in words)
    head = relation_head(low)
    if head is None or head[0] in SIZE_SUPERLATIVES:
        return None
    ref = _reference_point(words[head[2]:], scene, "reference block", context)
    return ref[0] if ref is not None else None


def _resolve(text: str, scene: Scene, role: str, context: Context | None) -> str:
    words = [part for w in text.split() for part in _elided(w)]
    if not words:
        raise LanguageError(f"the sentence does not name the {role}")
    names = scene.names
    if text in names:  # an exact name first: a block may well be called "a" or "the cube"
        return text
    if len(words) > 1 and words[-1].lower() in EMPHATIC:  # "beside the goal itself", "nearer to the goal only"
        return _resolve(" ".join(words[:-1]), scene, role, context)
    numbered = number_reference(text, scene, role, resolve_object)  # "number 5", "cube 1", "the red one, #2"
    if numbered is not None:
        return numbered
    other = other_than(text, scene, role, resolve_object)  # "the cube that isn't red"
    if other is not None:
        return other
    marked = marked_with(text, scene, role, resolve_object)  # "the red one with the X on it"
    if marked is not None:
        return marked
    used = used_for(text, scene, try_object)  # "the thing you boil water in", "the one with all the holes"
    if used is not None:
        return used
    words = _plain_order(words, scene)
    low = tuple(w.lower() for w in words)
    if set(low) & CONJUNCTIONS and "between" not in low:  # "the tray and the other one closer to the can"
        raise LanguageError(f'"{text}" names more than one object; name the {role}')
    pointed = _pronoun(words, low, context, role, scene)
    if pointed is not None:
        return pointed
    if context is not None and len(context.among) > 1 and len(low) > 1 and low[0] == "the":
        try:  # "the big one", "the cube" after "There are two grey things": the one of those two
            return _resolve(text, scene.only(context.among), role, None)
        except UnknownObjectError:
            pass  # "the yellow one": none of the group, so one of the scene
    for i in range(1, len(low) - 1):
        if low[i - 1] in NOUNS and low[i:i + 1] in NAMED_AS:  # "the block called A"
            return resolve_object(" ".join(words[i + 1:]), scene, role, context)
    if len(low) > 1 and low[0] in POSSESSIVES and words[0] not in names:  # "my razor", "your mug": the razor, the mug
        words, low = ["the", *words[1:]], ("the", *low[1:])
    determined = False
    while len(low) > 1 and low[0] in DETERMINERS and words[0] not in names:
        if determined and named_after_the(low[0], names):
            break  # "the a block": no second article after "the", so the name A
        words, low, determined = words[1:], low[1:], True
    candidate = " ".join(words)
    if candidate in names:
        return candidate
    folded = [n for n in names if n.lower() == candidate.lower()]
    if len(folded) == 1 and not (determined and candidate.lower() in shape_named(scene)):
        return folded[0]  # "the cylinder" beside Cylinder and Cylinder (1) is either: described below
    apposed = name_and_kind(words, scene, role, _unremembered)
    if apposed is not None:
        return apposed
    relational = _relational(words, low, scene, role, context)
    spelled = spelled_name([w for w in text.split() if w.lower() not in DETERMINERS], scene)
    if relational is not None and spelled not in (None, relational):  # "the left block" beside left_block
        raise LanguageError(f'"{text}" is ambiguous: it is {spelled} by name, and {relational} by where it is; '
                            "name the one you mean")
    if relational is not None:
        return relational
    try:
        return described(text, words, low, scene, determined)
    except LanguageError:
        proportioned = set(low) & PROPORTION_NOUNS - {n.lower() for n in scene.names}  # "the tube": a guess
        named = named_before(text, scene, role, context, _unremembered) if determined and not proportioned else None
        named = named or partitive(text, scene, role, _unremembered)
        if named is None:
            raise
        return named
    except UnknownObjectError:
        named = partitive(text, scene, role, _unremembered) or of_compound(text, scene, role, _unremembered) \
            or holding(text, scene, role, _unremembered)
        if named is None:
            raise
        return named


def _elided(word: str) -> list[str]:
    """A French article run into its noun, apart ("l'assiette" -> "the", "assiette"); other words as they are."""
    if len(word) > 3 and word[:2].lower() in ("l'", "l\u2019") and word[2].isalpha():
        return ["the", word[2:]]
    return [word]


POSSESSIVES = frozenset({"my", "your", "our", "his", "her", "their", "ur"})
"""Whose a thing is, said where "the" would be ("my paste", "ur phone"): it names the thing as "the" does."""
EMPHATIC = frozenset({"itself", "only"})
"""Words after a reference that stress it and name nothing more."""
def _unremembered(text: str, scene: Scene, role: str) -> str:
    """:func:`_resolve` without a context, for the partitive readers that ask it again of a part of the words."""
    return _resolve(text, scene, role, None)


def _plain_order(words: list[str], scene: Scene) -> list[str]:
    """``words`` with a colour said by a thing ("the lemon coloured cube": the yellow cube), a free relative's opening
    ("whatever is closest to A": the one closest to A) and a relative clause's "that is" ("the cube that is red":
    the cube red) taken out, a comparative among a group as its
    superlative ("the larger of the cubes": the largest cube) and a place as an adjective as its superlative
    ("the front blue cube": the frontmost blue cube); the other readers take words in any order."""
    low = [w.lower() for w in words]
    if len(low) > 4 and low[-3] in ("on", "upon") and low[-2] == "the" and low[-1] in TABLE_WORDS:
        words = words[:-3]  # "the longest tool on the bench": every object is
    words = table_sides(looks(coloured_like(words), scene))
    words = places_as_superlatives(comparative_of(one_word_comparisons(words)))
    low = tuple(w.lower() for w in words)
    for opening, plain in OPENINGS.items() if low and low[0] in _OPENING_WORDS else ():
        if low[:len(opening)] == opening and len(low) > len(opening):
            return list(plain) + words[len(opening):]
    if not _RELATIVE_WORDS.intersection(low[1:-1]):
        return words
    nouns = NOUNS | set(SHAPE_NOUNS) | set(name_words(scene)) | set(kind_groups(scene)) | LOOSE_NOUNS
    for i in range(1, len(low) - 1):
        for rel in RELATIVES:
            if low[i - 1] in nouns and low[i:i + len(rel)] == rel and i + len(rel) < len(low):
                return words[:i] + words[i + len(rel):]
    return words


_OPENING_WORDS = frozenset(opening[0] for opening in OPENINGS)
_RELATIVE_WORDS = frozenset(rel[0] for rel in RELATIVES)
"""The words an opening or a relative clause starts with: where none is said, none is looked for."""


def _relational(words: list[str], low: tuple[str, ...], scene: Scene, role: str,
                context: Context | None) -> str | None:
    """Superlatives and relations: None when ``words`` hold none (then colours and names are tried).

    "Block" may mean any object or only the block-shaped ones (cubes and boxes): people differ. Where the two
    readings pick different objects ("the smallest block": the cylinder, or three equal cubes), the
    description is ambiguous and refused."""
    placed = _placed(words, low, scene, role, context)
    if placed is not None:
        return placed
    head = relation_head(low)
    if head is None:
        return None
    kind, at, end = head
    if not describes(low[:at], scene):  # "mv orange cube closer to tube" is a command, not a description
        return None
    if at == 0 and kind in COMPARED:  # "further from the vase than it is now" says where to, it names no object
        return None
    if kind in ("by", "beside") and not picks_among(words[:at], scene, try_object):
        return beside_as_said(words[:at], words[end:], scene, context, try_object)  # "the white one by the lamp"
    rest_words = words[end:]
    rank = RANKS.get(low[at - 1], 1) if at > 0 else 1  # "the second tallest white one", "the second closest to you"
    if kind in SIZE_SUPERLATIVES:  # "the biggest red block": the words on both sides restrict
        heads = NOUNS | set(COLORS) | set(COLOR_SYNONYMS) | set(SHAPE_NOUNS) | set(kind_groups(scene)) | LOOSE_NOUNS \
            | set(SHAPE_ADJECTIVES)  # "the smallest round one"
        if any(w.lower() not in heads for w in rest_words):
            return None
        described = words[:at - (rank > 1)] + rest_words
        _one_of_a_kind_looked_up(described, scene, kind)
        what, pick = SIZE_SUPERLATIVES[kind]
        place = what in PLACE_MEASURES
        if what == "area":
            return either_reading(described, scene, ranked(rank, lambda pool: bulk_superlative(pool, pick, kind)))
        return either_reading(described, scene, ranked(
            rank, lambda pool: superlative(pool, lambda o: measure(o, what), pick, kind, place)))
    ref = _reference_point(rest_words, scene, role, context)
    if ref is None:
        return None
    ref_name, ref_xy = ref

    def choose(pool: list[SceneObject]) -> str:
        pool = [o for o in pool if o.name != ref_name]
        side = kind.removeprefix("directly ")
        if side in SIDES:
            cone = SIDE_CONE if side == kind else DIRECT_CONE
            off = {o.name: bearing_off(np.subtract(o.xy, ref_xy), SIDES[side]) for o in pool}
            beside = [o for o in pool if off[o.name] <= cone]
            half = [o for o in pool if off[o.name] <= SIDE_DOUBT]
            if not beside and side == kind and len(half) == 1 and len(pool) < len(scene.objects) - 1:
                return half[0].name  # "the blue cube behind the cylinder": of the blue cubes, the one on that side
            if not beside:
                raise UnknownObjectError(f'nothing in the scene is {kind} {ref_name or "the robot"} as the robot '
                                         f"sees it (blocks: {describe(scene)})")
            straightest = min(off[o.name] for o in beside)
            doubt = [o.name for o in pool if cone < off[o.name] <= min(SIDE_DOUBT, DOUBT_RATIO * straightest)]
            if side == kind and doubt:
                raise LanguageError(f'"{kind}" {ref_name or "the robot"} is ambiguous: {beside[0].name} is, and '
                                    f'{", ".join(doubt)} partly; name the one you mean')
            nearest = min(beside, key=lambda o: distance_to(o, ref_xy))
            if side == kind and off[nearest.name] > DIRECT_CONE and off[nearest.name] > straightest:
                raise LanguageError(f'"{kind}" {ref_name or "the robot"} is ambiguous: {nearest.name} is nearer, '
                                    f'{min(beside, key=lambda o: off[o.name]).name} more straight {kind} it; name the '
                                    "one you mean")
            return superlative(beside, lambda o: distance_to(o, ref_xy), min, f"{kind} of", distance=True)
        return superlative(pool, lambda o: distance_to(o, ref_xy), min if kind in NEAREST else max, kind,
                           distance=True)

    # "the red block nearest B": the red ones only
    return either_reading(words[:at - (rank > 1)], scene, ranked(rank, choose))


COMPARED = frozenset(w for w in NEAREST | FARTHEST if w.endswith("er"))
"""Comparatives that describe an object only after words that name it ("the cube nearer to you")."""


def _one_of_a_kind_looked_up(described: list[str], scene: Scene, word: str) -> None:
    """Refuse a superlative over a kind WordNet gave one object alone ("the tallest chessman" where the pawn is a
    chessman by its first sense and the king and queen are not, theirs being monarchs): a superlative says there are
    several of the kind, so the look-up has missed the others, and picking the one it found would be a guess."""
    if not lexicon.allowed():
        return
    key = scene_key(scene)
    looked, own = kind_groups_of(key, True), kind_groups_of(key)  # the kept answers, only read here
    for w in (w.lower() for w in described):
        if w in looked and w not in own and len(looked[w]) == 1:
            raise LanguageError(f'"{word}" asks which of several, and "{w}" names one object here '
                                f"({next(iter(looked[w]))}); name the one you mean")


BETWEEN_DOUBT = 2.0
"""Two objects lie "between" A and B alike where the second is off the line A-B by less than this many times the
first's offset (plus a place tie): 4.9 and 8.1 cm off a 30 cm line is asked, 0.4 and 10 cm is not."""


def _off_line(o: SceneObject, a: np.ndarray, span: np.ndarray, length: float) -> float:
    """How far the object's centre is from the line through ``a`` along ``span`` (metres)."""
    d = np.asarray(o.xy) - a
    return abs(float(span[0] * d[1] - span[1] * d[0])) / length


_CENTRE_BY_LAST = by_word(CENTRE_PHRASES, -1)
_SIDES_BY_LAST = by_word(tuple(SIDE_PHRASES), -1)
"""The place phrases by their last word, each in the table's order: only those can end a description."""


def _placed(words: list[str], low: tuple[str, ...], scene: Scene, role: str, context: Context | None) -> str | None:
    """Places on the table: "the cube in the middle (of the table)", "the object on the far right", "the cube
    between A and C" (nearest the middle of the two, and lying between them), a place in a group (the middle
    one, the second from the left: language/group_places.py); None when ``words`` name none."""
    grouped = in_group(words, low, scene, resolve_object)
    if grouped is not None:
        return grouped
    last = low[-1] if low else ""
    for phrase in _CENTRE_BY_LAST.get(last, ()):
        if len(low) > len(phrase) and low[-len(phrase):] == phrase:
            return either_reading(words[:-len(phrase)], scene, lambda pool: superlative(
                pool, lambda o: distance_to(o, (0.0, 0.0)), min, "in the middle", place=True))
    for phrase in _SIDES_BY_LAST.get(last, ()):
        if len(low) > len(phrase) and low[-len(phrase):] == phrase:
            if relation_head(low[:-len(phrase)]) is not None:
                continue  # "the thing in front of the red cube on the right": the side picks the red cube
            what, pick = SIZE_SUPERLATIVES[SIDE_PHRASES[phrase]]
            said = " ".join(phrase)
            before = words[:-len(phrase)]
            if len(before) > 1 and before[-1].lower() in ("more", "most"):
                before = before[:-1]  # "the pawn (which stands) more at the back": the one farthest back
            return either_reading(before, scene, lambda pool, what=what, pick=pick, said=said:
                                   superlative(pool, lambda o: measure(o, what), pick, said, place=True))
    if "between" not in low[1:]:
        return None
    at = low.index("between", 1)
    ends = two_references(words[at + 1:], scene, role, context)
    if ends is None:
        return None
    a, b = (np.asarray(scene.get(n).xy, float) for n in ends)
    span = b - a
    length = float(np.linalg.norm(span))

    def choose(pool: list[SceneObject]) -> str:
        inside = []
        for o in pool:
            if o.name in ends or length < 1e-9:
                continue
            d = np.asarray(o.xy) - a
            t = float(d @ span) / length ** 2
            off = abs(float(span[0] * d[1] - span[1] * d[0])) / length
            if 0.0 < t < 1.0 and off < 0.5 * length:
                inside.append(o)
        if not inside:
            raise UnknownObjectError(f"nothing in the scene lies between {ends[0]} and {ends[1]} "
                                     f"(blocks: {describe(scene)})")
        off_line = {o.name: _off_line(o, a, span, length) for o in inside}
        ranked = sorted(inside, key=lambda o: off_line[o.name])
        if len(ranked) > 1 and off_line[ranked[1].name] < BETWEEN_DOUBT * off_line[ranked[0].name] + TIE_M:
            raise LanguageError(f'"between {ends[0]} and {ends[1]}" is ambiguous: {ranked[0].name} and '
                                f"{ranked[1].name} both lie near the line between them; name the one you mean")
        return ranked[0].name

    return either_reading(words[:at], scene, choose)


def two_references(words: list[str], scene: Scene, role: str, context: Context | None) -> tuple[str, str] | None:
    """"A and C", "the red and blue cubes", "the two blue cubes" -> two different objects' names; None when
    ``words`` are not two."""
    group = _the_two(words, scene)
    if group is not None:
        return group
    return next((p for p in object_pairs(words, scene, (role, role), context) if isinstance(p, tuple) and p[0] != p[1]),
                None)


def _the_two(words: list[str], scene: Scene) -> tuple[str, str] | None:
    """"the two blue cubes", "both red blocks": the two objects the plural description fits, in the scene's
    order; None where it is no such phrase or fits another number."""
    low = [w.lower() for w in words]
    for opening in (("the", "two"), ("both", "the"), ("both",), ("two",), ("2",)):
        if tuple(low[:len(opening)]) == opening and len(low) > len(opening) and low[-1].endswith("s"):
            rest = [*words[len(opening):-1], words[-1][:-1]]
            try:
                fits = candidates(" ".join(rest), rest, tuple(w.lower() for w in rest), scene)
            except (LanguageError, UnknownObjectError):
                return None
            return (fits[0].name, fits[1].name) if len(fits) == 2 else None
    return None


def object_pairs(words: list[str], scene: Scene, roles: tuple[str, str],
                 context: Context | None) -> Iterator[tuple[str, str] | LanguageError | UnknownObjectError]:
    """Each reading of ``words`` as two objects joined by a conjunction, split by split: the pair of names, or
    the one-line error of that split (the caller decides which split wins and which error to show)."""
    for k, w in enumerate(words):
        if w.lower() not in CONJUNCTIONS or not 0 < k < len(words) - 1:
            continue
        try:
            yield (resolve_object(" ".join(words[:k]), scene, roles[0], context),
                   resolve_object(" ".join(_one_as(words[k + 1:], words[:k])), scene, roles[1], context))
        except (LanguageError, UnknownObjectError) as e:
            yield e


def _one_as(second: list[str], first: list[str]) -> list[str]:
    """"the one on the right" after "the blue cube on the left": "one" stands for the first's noun with its
    adjectives ("the blue cube on the right"); ``second`` as it is where it does not open with "the one" or the
    first names no noun."""
    low = [w.lower() for w in first]
    if [w.lower() for w in second[:2]] != ["the", "one"] or len(second) < 3:
        return second
    noun = next((i for i, w in enumerate(low) if w in NOUNS | set(SHAPE_NOUNS) and w != "one"), None)
    return second if noun is None else [*first[:noun + 1], *second[2:]]


def _reference_point(words: list[str], scene: Scene, role: str,
                     context: Context | None) -> tuple[str | None, tuple[float, float]] | None:
    low = tuple(w.lower() for w in words)
    if not low:
        return None
    if low in ROBOT_WORDS:
        return None, (float(ROBOT_BASE_XY[0]), float(ROBOT_BASE_XY[1]))
    try:
        name = resolve_object(" ".join(words), scene, role, context)
    except (LanguageError, UnknownObjectError):
        return None
    return name, tuple(scene.get(name).xy)

