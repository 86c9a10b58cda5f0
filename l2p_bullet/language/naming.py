"""What names an object in words: its name, the words its name is made of, the fond forms of a word name ("ducky"),
its kinds, and the names that are another's shape or kind ("Cylinder" beside "Cylinder (1)", "apple" beside
green_apple). Read by the descriptions (descriptions.py) and by every reader that must know whether a word names a
thing before it reads it as something else (a verb, a courtesy, a slip).
"""

from __future__ import annotations

import functools

from ..core.scene import COLORS, Scene
from . import lexicon
from .kept import SceneMemo
from .reference_words import COLOR_SYNONYMS, COLOUR_WORDS, NOUNS, SOFT_ADJECTIVES
from .shape_words import SHAPE_NOUNS
from .synonyms import KIND_MODIFIERS, SIZE_WORDS, kind_words_of, name_parts, scene_key, shape_of

GEOMETRIC = frozenset({"cube", "cubes", "box", "boxes", "cylinder", "cylinders", "brick", "bricks", "rectangle",
                       "rectangles"})
"""Shape nouns that name a shape as such: an object of that kind ("cube.obj") and any other of that shape are both
it. Every other shape noun is a thing's name ("can", "log", "tube", "disc"): where an object is that thing, it is
meant, not another of its shape."""



def shape_named(scene: Scene) -> frozenset[str]:
    """The names (lower case) that are a shape's own word where another object is of that shape too ("Cylinder" and
    "Cylinder (1)", as a game engine names its shapes): said alone ("move Cylinder ...") the name; with an article or
    other words ("the cylinder at the back", "the orange cylinder") the shape, as of any of them. Kept per scene:
    every description asks."""
    def read() -> frozenset[str]:
        words = [n.lower() for n in scene.names if n.lower() in GEOMETRIC]
        return frozenset(w for w in words if sum(shape_of(o) == SHAPE_NOUNS[w] or w in name_parts(o.name)
                                                 for o in scene.objects) > 1)

    return _SHAPE_NAMED.ask("shape_named", scene, read)


_SHAPE_NAMED = SceneMemo(64)


@functools.lru_cache(maxsize=256)
def parts_of(names: tuple[str, ...]) -> frozenset[str]:
    """The words the scene's names are made of ("brick" of brick_2x4_red)."""
    return frozenset(p for n in names for p in name_parts(n))


def kind_named(scene: Scene, groups: dict[str, frozenset[str]]) -> set[str]:
    """The names (lower case) of one word that are the kind of another object too ("apple" beside green_apple;
    ``groups``: the scene's :func:`~.synonyms.kind_groups`): with other words said ("the apple at the back", "the red
    apple") the kind, as of either of them; alone ("the apple") the one so named."""
    return {n.lower() for n in scene.names if len(groups.get(n.lower(), ())) > 1}


def spelled_name(words: list[str], scene: Scene) -> str | None:
    """The object whose name of several words the words spell, however the name joins them ("cube b", "Cube-B" for
    cube_b; "the coffee mug" for coffee_mug; "red cube 2" for RedCube2; "sugar_box" for 004_sugar_box; "the glasses
    cases" for glasses_case; "the box of screws" for screw_box; "bottle B", "pills B" and "B" alone, capital, for
    pill_bottle_b); None where none or several do."""
    return _spelled(tuple(words), tuple(scene.names))


@functools.lru_cache(maxsize=4096)
def _spelled(words: tuple[str, ...], names: tuple[str, ...]) -> str | None:
    """:func:`spelled_name` of the words and the scene's names, kept: a sentence's readings ask it of the same words
    many times."""
    said = name_parts(" ".join(words))
    if len(words) == 1 and len(words[0]) == 1 and words[0].isupper():  # "B" for pill_bottle_b, its label alone
        fits = [n for n in names if len(name_parts(n)) >= 2 and name_parts(n)[-1] == said[0]]
        return fits[0] if len(fits) == 1 and not any(n.lower() == said[0] for n in names) else None
    if len(said) < 2:
        return None
    plural = (*said[:-1], said[-1][:-1]) if said[-1].endswith("s") and len(said[-1]) > 3 else said
    fits = [n for n in names if {said, plural} & {name_parts(n), _unnumbered(name_parts(n))}]
    if not fits and any(p.isdigit() for p in said):  # "p2" for pen_2: a word's first letter and the number
        fits = [n for n in names if _initialled(said, name_parts(n))]
    if not fits and len(said) == 3 and said[1] == "of":  # "the box of screws", "the deck of cards": screw_box
        held = said[2][:-1] if said[2].endswith("s") else said[2]
        fits = [n for n in names if name_parts(n) in ((held, said[0]), (said[2], said[0]))]
    if not fits:  # "bottle B", "pills A" for pill_bottle_a: its label and a word or two of it
        fits = [n for n in names if _labelled(said, name_parts(n))]
    return fits[0] if len(fits) == 1 else None


def _labelled(said: tuple[str, ...], parts: tuple[str, ...]) -> bool:
    """Whether ``said`` is a name's label (its last word, a letter or a number) after one or more of its other words,
    in their order, each as written or with a plural's "s" ("bottle b", "pills b", "pill bottle b")."""
    if len(parts) < 3 or said[-1] != parts[-1] or not (len(parts[-1]) == 1 or parts[-1].isdigit()):
        return False
    words = iter(parts[:-1])
    return all(any(w in (p, p + "s") for p in words) for w in said[:-1])


def _initialled(said: tuple[str, ...], parts: tuple[str, ...]) -> bool:
    """Whether ``said`` is ``parts`` with one word or more of letters said by its first letter ("p", "2": pen_2)."""
    if len(said) != len(parts):
        return False
    pairs = list(zip(said, parts, strict=True))
    return any(len(a) == 1 and a.isalpha() and len(b) > 1 for a, b in pairs) \
        and all(a == b or len(a) == 1 and a.isalpha() and b.isalpha() and b[0] == a for a, b in pairs)


def _unnumbered(parts: tuple[str, ...]) -> tuple[str, ...]:
    """A name's words without the number it opens with ("002_master_chef_can": master, chef, can), as people say a
    dataset's file names; the words themselves where it opens with none."""
    return parts[1:] if len(parts) > 2 and parts[0].isdigit() else parts


def names_within(words: list[str], scene: Scene) -> list[str]:
    """The scene's names of several words that ``words`` spell whole, each somewhere in them ("the butter dish salt
    shaker": butter dish and salt shaker), in the scene's order."""
    said = name_parts(" ".join(words))
    found = []
    for n in scene.names:
        parts = name_parts(n)
        if len(parts) > 1 and any(said[i:i + len(parts)] == parts for i in range(len(said) - len(parts) + 1)):
            found.append(n)
    return found


def naming_words(scene: Scene) -> frozenset[str]:
    """Lower-case words that name or describe objects: kind words and names of 3+ letters, colours and their
    synonyms, shape nouns. Not "can" as a shape ("can you ..." asks; an object named "can" is a kind word, a can a
    mesh file or a longer name calls so is not) nor a one-letter name ("u" is "you" as typed: U is named as "U")."""
    return _naming_words_of(scene_key(scene), lexicon.allowed())


_SHAPES_SAID = frozenset(SHAPE_NOUNS) - {"can", "cans"}


@functools.lru_cache(maxsize=256)
def _naming_words_of(objects: tuple[tuple[str, str | None, str | None], ...], looked_up: bool) -> frozenset[str]:
    """:func:`naming_words` of a :func:`~.synonyms.scene_key`, kept: every reading of a sentence asks for them."""
    literal = {name.lower() for name, *_ in objects}
    kinds = frozenset(w for w in name_words_of(objects, looked_up) if len(w) >= 3
                      and (w in literal or w not in SHAPE_NOUNS))
    return kinds | COLOUR_WORDS | _SHAPES_SAID


WORDS_OF_THEIR_OWN = (SIZE_WORDS | SOFT_ADJECTIVES | NOUNS | frozenset(SHAPE_NOUNS) | frozenset(COLORS)
                      | frozenset(COLOR_SYNONYMS) | KIND_MODIFIERS)
"""Words a name's fond form may spell ("tin" + "y" is "tiny"): never read as the name."""


def name_words(scene: Scene) -> dict[str, str]:
    """Lower-case words that name an object -> its name: the name, and for a word name its fond forms
    ("ducky", "duckie": the duck)."""
    return dict(name_words_of(scene_key(scene), lexicon.allowed()))


@functools.lru_cache(maxsize=256)
def name_words_of(objects: tuple[tuple[str, str | None, str | None], ...], looked_up: bool = False) -> dict[str, str]:
    """name_words of a :func:`~.synonyms.scene_key`, kept: made once per scene, not once per word read (a caller must
    not change it; name_words hands out copies)."""
    names = [name for name, *_ in objects]
    out = {}
    for n in names:
        low = n.lower()
        if len(low) >= 3 and low.isalpha():
            out.update({fond: n for fond in (low + "y", low + "ie") if fond not in WORDS_OF_THEIR_OWN})
    out.update(kind_words_of(objects, looked_up))
    out.update({n.lower(): n for n in names})
    return out
