"""Words that point back -> the object they mean: "it", "that cylinder", "the other one", "the big one", "the latter".

A pronoun or a pointing-back phrase names nothing by itself: it is read against what the clause before moved and
named (:class:`Context`), not against the scene's descriptions, and it has refusals of its own (nothing earlier to
point back to, two objects it may mean). Kept apart from the descriptions' reader (language/references.py), which
asks it first.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..core.scene import Scene, SceneObject
from ..errors import LanguageError, UnknownObjectError
from .descriptions import candidates
from .lexicon import plural
from .naming import name_words
from .places import by_size
from .proportions import PROFILES, admits
from .reference_words import (
    BLOCK_SHAPES,
    DEMONSTRATIVES,
    GENDERED,
    NOUNS,
    PRONOUNS_ANCHOR,
    PRONOUNS_MOVER,
    SAME_WORDS,
    STRICT_SHAPES,
)
from .shape_words import SHAPE_NOUNS
from .synonyms import FIGURES, KIND_CLASSES, SIZE_WORDS, kind_groups, kinds_of, name_parts, shape_of


@dataclass(frozen=True)
class Context:
    """What pronouns point back to: the previous clause's mover and anchor (None: there is none)."""

    mover: str | None = None
    anchor: str | None = None
    among: tuple[str, ...] = ()  # a group shown before ("There are two green cubes"): "the big one" is of it
    described: bool = False  # the mover was described, not named ("the small red cube"): see _twin


SAME_PLACE = frozenset({("the", "same", "one"), ("same", "one"), ("the", "same"), ("same",)})
""""The same one" where a clause says where: the object the clause before moved to, not the one it moved."""


def _pronoun(words: list[str], low: tuple[str, ...], context: Context | None, role: str,
             scene: Scene) -> str | None:
    said = " ".join(low)  # what the user wrote, for the error: "that same cube" reads as "it" below
    kinds = set(name_words(scene)) | set(kind_groups(scene))  # "the same pawn": red_pawn's kind too
    opening = next((o for o in SAME_WORDS if low[:len(o)] == o and len(low) == len(o) + 1), None)
    if opening is not None and (low[-1] in SHAPE_NOUNS or (low[-1] in kinds and low[-1] not in NOUNS)):
        return _that_kind(said, low[-1], context, role, scene)
    if low in SAME_PLACE and "reference" in role and context is not None and context.anchor is not None:
        return context.anchor  # "put A beside the lantern, then B beside the same one": the lantern again
    gendered = _by_gender(low, context, scene)
    if gendered is not None:  # "move the doll toward teddy, then move him ...": teddy
        return gendered
    asked = low in DEMONSTRATIVES or (opening in DEMONSTRATIVES and low[-1] in NOUNS) or (
        low in GENDERED and context is not None and _animals(scene, context.mover, context.anchor))
    if asked and context is not None and context.mover is not None and context.anchor not in (None, context.mover):
        raise LanguageError(f'"{said}" is ambiguous: {context.mover} (moved in the previous clause) or '
                            f'{context.anchor} (named last); name the one you mean, or say "it"')
    if opening is not None and low[-1] in NOUNS:
        low = ("it",)
    twin = sized_twin(said, low, context, scene)
    if twin is not None:
        return twin
    if low in (("the", "latter"), ("the", "former")):  # the clause before's two objects, in the order named
        if context is None or context.mover is None or context.anchor in (None, context.mover):
            raise _no_earlier(said, role)
        return context.anchor if low[1] == "latter" else context.mover
    if low[:2] == ("the", "other") and len(low) > 2 and low not in PRONOUNS_ANCHOR:
        return _the_other(said, words[2:], context, role, scene)
    if low in PRONOUNS_MOVER or low in PRONOUNS_ANCHOR:
        if context is None or context.mover is None:
            raise _no_earlier(said, role)
        if low in PRONOUNS_MOVER:
            if len(context.among) > 1 and context.mover in context.among:
                if "reference" not in role:  # "the jar n the cup r in the way, move it": either
                    raise LanguageError(f'"{said}" is ambiguous: it may be any of {", ".join(context.among)}; '
                                        "name the one you mean")
                if context.anchor is not None and context.anchor not in context.among:
                    return context.anchor  # "A and B are too close to C. Move each of them away from it": C
            return context.mover  # "move the jar away from it": the other of the two
        return _twin(said, context, scene) or context.anchor
    return None


FEMININE = frozenset({"doll", "dolly", "princess", "girl", "lady", "woman", "queen", "mermaid", "ballerina", "barbie",
                      "fairy", "bride", "mom", "mum", "mother", "grandma", "sister", "aunt", "hen", "cow"})
"""Kinds people call "she" / "her" (a doll, a queen): of two objects of the clause before, the one of such a kind is
"her", and where the other is a figure or an animal, "him" is that other."""


def _by_gender(low: tuple[str, ...], context: Context | None, scene: Scene) -> str | None:
    """The one of the clause before's two objects that "him"/"he" or "her"/"she" means by the kinds' genders; None where
    the genders do not tell (neither or both are of a feminine kind)."""
    if low not in GENDERED or context is None or context.mover is None or context.anchor in (None, context.mover):
        return None
    pair = [n for n in (context.mover, context.anchor) if n in scene.names]
    female = [n for n in pair if kinds_of(scene.get(n)) & FEMININE]
    if len(pair) != 2 or len(female) != 1:
        return None
    if low[0] in ("her", "she"):
        return female[0]
    other = next(n for n in pair if n != female[0])
    return other if _animals(scene, other) or kinds_of(scene.get(other)) & set(FIGURES) else None


def _animals(scene: Scene, *names: str | None) -> bool:
    """Whether every one of ``names`` is an object of the scene of an animal's kind (a toy dog, a duck)."""
    animal = set(KIND_CLASSES["animal"])
    return all(n in scene.names and kinds_of(scene.get(n)) & animal for n in names)


def _no_earlier(said: str, role: str) -> LanguageError:
    """The error for a word that points back ("it", "that cylinder", "the other red cube") in a first clause."""
    return LanguageError(f'"{said}" ({role}) points back to an earlier clause, and there is none; name the block')


def _fits_kind(o: SceneObject, noun: str, scene: Scene) -> bool:
    """Whether ``noun`` ("cylinder", "cube", "duck", "stick") may name ``o``: a shape noun its shape (a cube or a box
    for "cube" and "box"), a kind word the object it names, a noun of proportions an object they admit."""
    kinds = name_words(scene)
    if noun in kinds:
        return kinds[noun] == o.name
    if noun in PROFILES:
        return admits(noun, o, kind_groups(scene))
    if noun not in SHAPE_NOUNS:  # a kind several objects share ("that pawn")
        return o.name in kind_groups(scene).get(noun, ())
    shape = SHAPE_NOUNS[noun]
    return shape_of(o) == shape if shape in STRICT_SHAPES else shape_of(o) in BLOCK_SHAPES


def sized_twin(said: str, low: tuple[str, ...], context: Context | None, scene: Scene) -> str | None:
    """"the big one" after a clause that moved one of two or more objects of the same colour and shape ("move the
    small red cube ..., then slide the big one ..."): the one of them the size word picks; None where it is not said
    so or picks no single one."""
    if context is None or context.mover not in scene.names or low[:1] != ("the",) or low[2:] not in ((), ("one",)) \
            or len(low) < 2 or low[1] not in SIZE_WORDS:
        return None
    was = scene.get(context.mover)
    twins = [o for o in scene.objects if o.color == was.color and o.shape == was.shape]
    if len(twins) < 2:
        return None
    try:
        picked = by_size(said, twins, [low[1]])
    except (LanguageError, UnknownObjectError):
        return None
    return picked[0].name if len(picked) == 1 else None


def _that_kind(said: str, noun: str, context: Context | None, role: str, scene: Scene) -> str | None:
    """"that cylinder", "this cube": the object of that kind among the previous clause's (its mover first, then
    its anchor; where both are blocks and only one is of the shape the noun names, that one); with none of that kind
    there, what "the cylinder" names in the scene (None: read on)."""
    if context is None or context.mover is None:
        if noun in name_words(scene):
            return None  # "that duck" in a first clause: the duck
        raise _no_earlier(said, role)
    named = [n for n in (context.mover, context.anchor) if n is not None and n in scene.names]
    fits = [n for n in named if _fits_kind(scene.get(n), noun, scene)]
    exact = [n for n in fits if shape_of(scene.get(n)) == SHAPE_NOUNS.get(noun)]
    if len(exact) == 1 and len(fits) > 1:  # "move the yellow block next to the blue cube, then push that cube"
        return exact[0]
    return fits[0] if fits else None


def _the_other(said: str, words: list[str], context: Context | None, role: str, scene: Scene) -> str:
    """"the other red cube", "the other white object": what the rest describes, other than the previous clause's
    mover; refused unless exactly one object is left."""
    if context is None or context.mover is None:
        raise _no_earlier(said, role)
    low = tuple(w.lower() for w in words)
    fits = [o for o in candidates(said, words, low, scene) if o.name != context.mover]
    if len(fits) != 1:
        listed = ", ".join(o.name for o in fits) or "none"
        raise LanguageError(f'"{said}" is ambiguous: other than {context.mover} it fits {listed}; '
                            "name the one you mean")
    return fits[0].name


def _twin(said: str, context: Context, scene: Scene) -> str | None:
    """"The other one" where a third object shares the colour of one of the previous clause's two: after "move
    the small red cube next to F" it is the other red cube, as the authors who wrote so meant it, when the mover
    was described and that cube is its only twin of colour and shape (an object of the anchor's colour is not
    "the other" of the mover's kind); where the mover was named ("move B next to
    F") or twins are several, the anchor and the twins are both readings, and the user is asked. None: no
    twin, the anchor is meant."""
    pair = [n for n in (context.mover, context.anchor) if n is not None and n in scene.names]
    if len(pair) < 2:
        return None
    colours = {scene.get(n).color for n in pair}
    twins = [o.name for o in scene.objects if o.color in colours and o.name not in pair]
    if not twins:
        return None
    mover = scene.get(pair[0])
    alike = [n for n in twins if scene.get(n).color == mover.color and scene.get(n).shape == mover.shape]
    if context.described and len(alike) == 1:
        return alike[0]
    raise LanguageError(f'"{said}" is ambiguous: {context.anchor} (of the previous clause) or {", ".join(twins)} '
                        f"(the other of its colour); name the one you mean")


def named_before(text: str, scene: Scene, role: str, context: Context | None, resolve) -> str | None:
    """"The blue cup is in the way of the yellow cube. Slide it away from the cube": a definite description that
    fits several objects of the scene but one of the clause before's is that one; None otherwise (``resolve``: how a
    description is read without a context, language/references.py)."""
    if context is None:
        return None
    before = [n for n in dict.fromkeys((context.mover, context.anchor)) if n is not None and n in scene.names]
    if len(before) < 2:
        return None
    try:
        chosen = resolve(text, scene.only(before), role)
    except (LanguageError, UnknownObjectError):
        return None
    if {w.lower() for w in text.split()} & SIZE_WORDS:  # "the tall white one" is tall among the scene's
        for other in scene.names:
            try:
                if other not in before and resolve(text, scene.only([*before, other]), role) == other:
                    return None  # the king is the taller: not the knight the clause before moved
            except (LanguageError, UnknownObjectError):
                continue
    return chosen


PLURALIA = frozenset({"glasses", "spectacles", "specs", "scissors", "forceps", "tongs", "pliers", "tweezers", "keys",
                      "headphones", "earphones", "earbuds", "chopsticks", "binoculars", "clippers", "shears"})
"""Things named in the plural though each is one object: "them" is the one ("slide the keys past the wallet, then bring
em back")."""
SINGULAR_IN_S = frozenset({"lens", "bus", "gas", "canvas", "atlas", "chess", "iris", "cactus", "octopus", "walrus",
                           "citrus", "hummus", "bonus", "series", "species", "axis", "basis", "mars", "texas"})


def plural_named(name: str | None) -> bool:
    """Whether the object ``name`` is called by a plural noun ("keys", "forceps", "AirPods", "dominoes")."""
    parts = name_parts(name) if name else []
    last = parts[-1].lower() if parts else ""
    return last in PLURALIA or (len(last) > 3 and last.isalpha() and last.endswith("s")
                                and not last.endswith(("ss", "us", "is")) and last not in SINGULAR_IN_S)


def said_in_plural(name: str, sentence: str) -> bool:
    """Whether ``sentence`` calls the object ``name`` by the plural of a word of its name, as people call a box of
    crayons "the crayons" or a jar of treats "the treats": "them" may then be that one object."""
    said = {w.strip(",.;:!?'\"").lower() for w in sentence.split()}
    return any(p.isalpha() and len(p) > 2 and plural(p.lower()) in said for p in name_parts(name))
