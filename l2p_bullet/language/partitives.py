"""One object said by a group it is picked from, by what it is made of or by what it is beside its name, and the groups
themselves: "the smallest of the cubes", "the one nearer the robot of the two boxes" (partitives), "the bar of soap",
"the tin of soup" (a kind said with "of"), "Rex the dinosaur" (a name with its kind), "the cubes", "2 rectangular
blocks" (a plural description's objects).

The readers here ask the description reader again for a part of the words (``resolve``: language/references.py),
which is passed in so that this module stays below it."""

from __future__ import annotations

import re
from collections.abc import Callable

from ..core.scene import Scene
from ..errors import LanguageError, UnknownObjectError
from .descriptions import candidates
from .reference_words import COLOUR_WORDS, NOUNS
from .shape_words import SHAPE_NOUNS
from .synonyms import CONTAINERS as NAMED_CONTAINERS
from .synonyms import LOOSE_NOUNS, is_modifier, kind_groups

PARTITIVE = re.compile(r"^(?P<head>.+?)\s+of\s+(?:all\s+)?the\s+(?:(?P<count>two|three|four|five|[2-5])\s+)?"
                       r"(?P<group>[\w\s-]+?(?:s|es))$", re.IGNORECASE)
"""One object picked among a group said in the plural: "the smallest of the cubes", "the one nearer the robot of the
two boxes"."""
COUNTS = {"two": 2, "three": 3, "four": 4, "five": 5}


def number_said(count: str | None, otherwise: int) -> int:
    """How many a group's number word or digits say ("three", "3"); ``otherwise`` where none is said."""
    if not count:
        return otherwise
    return COUNTS.get(count.lower(), int(count) if count.isdigit() else 0)


def group_of(text: str, scene: Scene, count: str | None = None) -> tuple[str, ...] | None:
    """The objects a plural description fits ("the cubes", "2 rectangular blocks"), in the scene's order; None where
    it fits fewer than two, or not the number said."""
    words = [w for w in text.split() if w.lower() != "the"]
    if not words or not words[-1].lower().endswith("s"):
        return None
    last = words[-1].lower()
    singulars = [last[:-2]] if last.endswith(("xes", "ches")) else [last[:-1]]
    if last.endswith(("ses", "shes", "zes")):  # "the lenses", "the brushes": after "vases" and "cases" are tried
        singulars.append(last[:-2])
    for singular in singulars:
        said = [*words[:-1], singular]
        try:
            fits = candidates(text, said, tuple(w.lower() for w in said), scene)
        except (LanguageError, UnknownObjectError):
            continue
        if len(fits) >= 2 and number_said(count, len(fits)) == len(fits):
            return tuple(o.name for o in fits)
    return None


CONTAINERS = frozenset({"bar", "piece", "lump", "chunk", "cake", "block", "bit", "stick"})
"""Words for how much of a kind there is ("a bar of soap", "a stick of butter"): the kind is what the object is."""
VESSELS = frozenset({"tin", "can", "bottle", "carton", "box", "jar", "packet", "bag", "cup", "mug", "bowl", "pot",
                     "tub", "tube", "pack", "roll", "reel", "spool"}) | NAMED_CONTAINERS
"""Kinds that hold what they are named by ("the tin of soup", "the box of milk", "the dish of mints", "the roll of
green tape"): the vessel and its content both describe the object ("the soup tin")."""


def of_compound(text: str, scene: Scene, role: str, resolve: Callable[[str, Scene, str], str]) -> str | None:
    """A kind said with "of" ("the bar of soap": the soap; "the duck of rubber", as learners write "rubber duck": the
    duck; "the tin of soup": the soup tin; "the card of memory" where the scene file declares a "memory card"); None
    where ``text`` is not said so or names no one object."""
    words = text.split()
    low = [w.lower() for w in words]
    if low.count("of") != 1 or low.index("of") in (0, len(low) - 1):
        return None
    at = low.index("of")
    head, tail = low[:at], low[at + 1:]
    if head[-1] in CONTAINERS and len(tail) <= 2 and len(tail[-1]) >= 3 and tail[-1].isalpha():
        said = " ".join(["the", *tail[-1:]])
    elif all(is_modifier(w) for w in tail) or (head[-1] in VESSELS and len(tail) <= 2 and tail[-1].isalpha()) \
            or _declared(" ".join([head[-1], "of", *tail]), scene) \
            or _declared(" ".join([*tail, head[-1]]), scene):  # "the ball of twine", "the card of memory" for a
        # "memory card": the words of a kind the scene file declares, with "of" or turned about as learners write them
        said = " ".join([*head[:-1], *tail, head[-1]])  # "the controller of video games", "the tin of soup"
    else:
        return None
    try:
        return resolve(said, scene, role)
    except (LanguageError, UnknownObjectError):
        return None


HOLDING = re.compile(r"^(?P<head>.+?)\s+(?:with|full\s+of|for)\s+(?:the\s+|some\s+|all\s+the\s+)?(?P<what>[a-z]{3,})"
                     r"(?:\s+in\s+(?:it|them))?$", re.IGNORECASE)
"""An object said by what it holds or is for: "the bag with the tokens (in it)", "the thingy with the sand in it",
"the notepad for the scores"."""


def holding(text: str, scene: Scene, role: str, resolve: Callable[[str, Scene, str], str]) -> str | None:
    """The one object :data:`HOLDING`'s head and what it holds (or is for) both call ("the bag with the tokens":
    token_bag, whose name or kind says tokens as well as bag); None where ``text`` is not said so, or the two words
    call no one object together."""
    m = HOLDING.match(text)
    head = m.group("head").lower().split()[-1] if m is not None else None
    if head is None or head in ("the", "a", "one"):
        return None
    what = m.group("what").lower()
    try:
        name = resolve(f"{m.group('head')} {m.group('what')}", scene, role)
    except (LanguageError, UnknownObjectError):
        return None
    groups = kind_groups(scene)
    # both words call it ("the soap for dogs" is no dog brush: nothing here is called soap), or what it has is its
    # colour ("the screwdriver with the yellow handle")
    said_head = name in groups.get(head, ()) or head in LOOSE_NOUNS or head in NOUNS or head in SHAPE_NOUNS
    return name if said_head and (name in groups.get(what, ()) or what in COLOUR_WORDS) else None


def _declared(phrase: str, scene: Scene) -> bool:
    """Whether an object's declared kind says ``phrase`` ("ball of twine", "deck of cards"): its words with "of"."""
    return any(o.kind and f" {phrase} " in f" {o.kind.lower()} " for o in scene.objects)


def partitive(text: str, scene: Scene, role: str, resolve: Callable[[str, Scene, str], str]) -> str | None:
    """The object :data:`PARTITIVE`'s head picks among its group; None where ``text`` is not said so or either part
    does not resolve."""
    m = PARTITIVE.match(text)
    group = group_of(m.group("group"), scene, m.group("count")) if m is not None else None
    if group is None:
        return None
    try:
        return resolve(m.group("head"), scene.only(group), role)
    except (LanguageError, UnknownObjectError):
        return None


def name_and_kind(words: list[str], scene: Scene, role: str, resolve: Callable[[str, Scene, str], str]) -> str | None:
    """A name said with what the object is ("Rex the dinosaur", "Max, our dog", "Daisy (the cow)"): the named object
    where the description fits it; refused, naming both, where it picks another; None where ``words`` are not said
    so."""
    if len(words) < 3 or words[1].lower().strip(",(") not in APPOSING:
        return None
    named = [n for n in scene.names if n.lower() == words[0].strip(",(").lower()]
    if len(named) != 1:
        return None
    said = " ".join(["the", *words[2:]]).strip(" ,()")
    try:
        other = resolve(said, scene, role)
    except (LanguageError, UnknownObjectError):
        other = None
    if other == named[0]:
        return other
    if other is not None:
        raise LanguageError(f'"{" ".join(words)}" names {named[0]} and calls it {said}, which is {other}; say which '
                            "you mean")
    return None


APPOSING = frozenset({"the", "our", "my", "your", "his", "her", "their"})
"""Words that open what a name is said to be, right after it ("Rex the dinosaur", "Max, our dog")."""
