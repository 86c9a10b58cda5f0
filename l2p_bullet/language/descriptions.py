"""What an object is called by: its name, colour, shape, size, proportions and kind words ("the red block", "the tall
one", "the stick", "the flat square", "the rubber duck", "the football-looking thing"), resolved among the scene's
objects (the proportions are language/proportions.py's).

The leaf of the resolver (language/references.py): these readings look at the objects themselves, never at
places, relations or the clause before, so they import nothing of the resolver; a description that fits
several objects or none is a one-line error that names them.
"""

from __future__ import annotations

import re

from ..core import colours
from ..core.scene import COLORS, Scene, SceneObject
from ..errors import LanguageError, UnknownObjectError, did_you_mean
from .letters import letter_of, letters_of
from .naming import GEOMETRIC, kind_named, name_words, names_within, parts_of, shape_named, spelled_name
from .places import by_size, named_colours
from .proportions import PROFILES, PROPORTION_NOUNS, fitting, outline_sides
from .reference_words import (
    BLOCK_KINDS,
    BLOCK_SHAPES,
    BLOCK_WORDS,
    BOX_KINDS,
    COLOR_SYNONYMS,
    COLOUR_NOUNS,
    COLOUR_WORDS,
    DETERMINERS,
    FRAMING_KINDS,
    FUNCTION_WORDS,
    NEAR_COLOURS,
    NOUNS,
    ROUND_KINDS,
    SHAPE_ADJECTIVES,
    SOFT_ADJECTIVES,
    STRICT_SHAPES,
)
from .shape_words import SHAPE_NOUNS
from .synonyms import (
    BIG,
    DRINKS,
    FOODS,
    KIND_NAMES,
    KIND_SYNONYMS,
    LOOSE_NOUNS,
    SHORT,
    SIZE_WORDS,
    SMALL,
    TALL,
    abbreviated,
    is_modifier,
    kind_groups,
    kinds_of,
    own_kinds_of,
    shape_of,
    unaccented,
)


def describe(scene: Scene) -> str:
    return ", ".join(f"{o.name} ({o.shade or o.color})" for o in scene.objects)


def shades_said(words: list[str], low: tuple[str, ...], scene: Scene) -> tuple[list[str], tuple[str, ...], set[str]]:
    """``words`` and ``low`` with a shade the scene file gives an object ("gold", "light blue", "navy", "clear" and the
    words alike to it: "see-through", "glass") said as its basic colour, and the shades so said: "the gold cup" is the
    yellow cup that is gold, "the silver one" beside a grey one the silver one (:func:`candidates` keeps those)."""
    shades: dict[tuple[str, ...], tuple[str, str]] = {}
    for o in scene.objects:  # not "grey", the basic colour spelt so
        if o.shade and not o.shade.startswith("#") and o.shade.replace("grey", "gray") != o.color:
            for said_as in (o.shade, *colours.alike(o.shade)):
                shades[tuple(said_as.split())] = (o.color, o.shade)
    own = {tuple(o.shade.split()) for o in scene.objects if o.shade}
    if not shades:
        return words, low, set()
    out_w, out_l, said, i = [], [], set(), 0
    while i < len(low):
        for shade in sorted(shades, key=len, reverse=True):
            taken = len(shade) if low[i:i + len(shade)] == shade else \
                1 if len(shade) > 1 and tuple(low[i].split("-")) == shade else 0  # "light-blue", "see-through"
            if taken and (shade in own or i + taken < len(low)):  # "the magnifying glass" is no glass-clear thing
                basic, shade_of = shades[shade]
                out_w.append(basic)
                out_l.append(basic)
                said.add(shade_of)
                i += taken
                break
        else:
            out_w.append(words[i])
            out_l.append(low[i])
            i += 1
    return out_w, tuple(out_l), said


def described(text: str, words: list[str], low: tuple[str, ...], scene: Scene, determined: bool) -> str:
    """Colour, shape, size and name words ("the red block", "red A", "the orange duck", "the tall one", "the big
    red cube").

    "Block" covers any object ("the purple block" is the cylinder where nothing else is purple), but where the
    other words leave several and one of them is block-shaped (a cube or a box), that one is meant ("the white
    block": the cube, not the white mug); the two readings are refused where they pick different objects."""
    spelled = spelled_name(words, scene)
    within = names_within(words, scene)
    if len(within) > 1:  # "the butter dish salt shaker": two names run together, as a list without its commas says
        raise LanguageError(f'"{text}" names more than one object ({", ".join(within)}); name the one you mean')
    said = set(low)
    if (said & BIG and said & SMALL) or (said & TALL and said & SHORT):
        # "big pot small pot": two objects said as a list without its commas, never one that is both
        raise LanguageError(f'"{text}" says two sizes of one object; name the one you mean')
    if spelled is not None:  # "the red cube" is red_cube by name, and asked where another red cube fits too
        sizes = [w for w in low if w in SIZE_WORDS]  # "the small box" is small_box where it is the smaller box
        try:
            fits = by_size(text, candidates(text, words, low, scene, determined, best=True), sizes)
            others = [o.name for o in fits if o.name != spelled]
        except (LanguageError, UnknownObjectError):
            others = []
        if not others:
            return spelled
        raise LanguageError(f'"{text}" is ambiguous: it is {spelled} by name, and {", ".join(others)} fits it too; '
                            "name the one you mean")
    names = name_words(scene)
    sizes = [w for w in low if w in SIZE_WORDS and w not in names]
    words, low, measure = said_measure(words, low)
    fits = candidates(text, words, low, scene, determined, best=True)
    if measure is not None:  # "the 5 cm cube": the objects whose longest side is about that long
        fits = [o for o in fits if abs(max(*outline_sides(o), o.geometry.height) - measure)
                <= max(MEASURE_TOLERANCE * measure, MEASURE_TOLERANCE_M)]
    if set(low) & BLOCK_WORDS:  # "the blue block" is no ball, no truck: a thing of another kind is no block
        fits = [o for o in fits if not _other_than_block(o)]
    pools = [fits]
    blocky = [o for o in fits if shape_of(o) in BLOCK_SHAPES]
    spoken = set(low) - colours_said(low, scene) - (NOUNS | BLOCK_WORDS)  # "the orange block" is no name said
    if set(low) & BLOCK_WORDS and 0 < len(blocky) < len(fits) and not spoken & set(names):
        pools.append(blocky)
    readings: list[str | Exception] = []
    for pool in pools:
        try:
            readings.append(one_of(text, by_size(text, pool, sizes), scene, named_colours(low)))
        except (LanguageError, UnknownObjectError) as e:
            readings.append(e)
    picked = sorted({r for r in readings if isinstance(r, str)})
    if len(picked) == 1:
        return picked[0]
    if len(picked) > 1:
        raise LanguageError(f'"{text}" is ambiguous: as any object it is {readings[0]}, as a block (a cube or a '
                            f"box) {readings[1]}; name the one you mean")
    raise readings[0]


NOT_BLOCKS = frozenset({"ball", "soccerball", "football", "sphere", "pingpong", "teddy", "duck", "bunny", "dog", "cow",
                        "dinosaur", "dino", "fish", "doll", "minifig", "truck", "car", "mug", "cup", "glass", "bottle",
                        "bowl", "plate", "apple", "banana", "lemon", "lime", "orange", "vase", "lamp", "kettle",
                        "teapot"})
"""Kinds people never call a block: a ball, an animal, a doll, a vehicle, a cup or a fruit. "Block" covers any other
object, of a kind or none ("the purple block" is the cylinder named C, "the yellow block" the wedge)."""


def _other_than_block(o: SceneObject) -> bool:
    """Whether ``o`` is of a kind of :data:`NOT_BLOCKS` and of no block's kind (a brick, a box)."""
    kinds = kinds_of(o)
    return bool(kinds & NOT_BLOCKS) and not kinds & (BLOCK_KINDS | GEOMETRIC)


MEASURE = re.compile(r"^(?P<n>\d+(?:[.,]\d+)?)-?(?P<unit>cm|mm|centimet(?:er|re)s?|millimet(?:er|re)s?)$")
UNITS = {"c": 0.01, "m": 0.001}
MEASURE_TOLERANCE = 0.15
MEASURE_TOLERANCE_M = 0.004
"""A size said in centimetres or millimetres ("the 5 cm cube", "the 6cm one") fits an object whose longest side is
within 15 % (at least 4 mm) of it: a 4 cm and a 5 cm cube are told apart, a 3.5 and a 4 cm one are asked about."""


def said_measure(words: list[str], low: tuple[str, ...]) -> tuple[list[str], tuple[str, ...], float | None]:
    """``words`` and ``low`` without a size said in centimetres or millimetres ("5 cm", "6cm", "50-mm"), and that
    size in metres; None where none is said."""
    for i in range(len(low)):
        for n in (2, 1):
            m = MEASURE.match("".join(low[i:i + n])) if i + n <= len(low) else None
            if m is not None:
                size = float(m.group("n").replace(",", ".")) * UNITS[m.group("unit")[0]]
                return words[:i] + words[i + n:], low[:i] + low[i + n:], size
    return words, low, None


def _colour_of_compound(word: str) -> str:
    """A colour said with a shade before it ("lime-green", "sky-blue", "dark-red"): the colour; else ``word``."""
    head, _, last = word.rpartition("-")
    return last if head and (last in COLORS or last in COLOR_SYNONYMS) else word


def candidates(text: str, words: list[str], low: tuple[str, ...], scene: Scene,
                determined: bool = True, best: bool = False) -> list[SceneObject]:
    """The objects the name, colour, shape and proportion words of a description allow (size words and "block"'s
    preference are for :func:`described`); an unknown word is a one-line error. ``best``: a word of proportions
    keeps the one object it fits clearly best, as a description of one object means ("the stick": the stirrer, not
    the 9 cm bar); else every object it admits, as a group does ("the sticks", "the other stick", "the second stick
    from the left")."""
    names = name_words(scene)
    groups = kind_groups(scene)
    plain = any(w in COLORS or w == "grey" for w in low)  # a basic colour said by its own name
    words, low, shades = shades_said(words, low, scene)  # "the gold cup", "the light blue block" on a table saying so
    low = tuple(_colour_of_compound(w) for w in low)  # "the lime-green block", "the sky-blue one"
    if not all(w.isascii() for w in low):  # "the Gießkanne", "the théière" where the file writes them without
        plain = tuple(w if w in groups or w in names or unaccented(w) not in groups and unaccented(w) not in names
                      else unaccented(w) for w in low)
        if plain != low:
            low, words = plain, list(plain)
    if any(w not in groups and w not in names and abbreviated(w, scene) for w in low):  # "the centrifuge": CENT-2
        low = tuple(w if w in groups or w in names else abbreviated(w, scene) or w for w in low)
        words = list(low)
    if any(w in LOOSE_NOUNS and w not in groups for w in low):  # "the little yellow guy", no figure: any object
        low = tuple("one" if w in LOOSE_NOUNS and w not in groups else w for w in low)
        words = [w if w.lower() not in LOOSE_NOUNS or w.lower() in groups else "one" for w in words]
    low = letter_of(low, determined, letters_of(scene.names), set(names) | set(groups))
    low = _shades_apart(low)
    said = [w for w in low if w not in DETERMINERS]
    drink = bool(set(low) & DRINKS)
    as_colour = colours_said(low, scene)  # "the orange block": the colour, not the fruit named "orange"
    if as_colour:
        names = {w: n for w, n in names.items() if w not in as_colour}
    if len(said) == 1 and said[0] in COLOUR_NOUNS and said[0] not in names:
        raise UnknownObjectError(f'"{text}" may be a colour or the fruit, and no {said[0]} fruit is on the table; '
                                 f'say "the {said[0]} one" or name it')
    drop = SOFT_ADJECTIVES
    # "can" as a word of "soup_can.obj" is a kind, not a name; "the orange cylinder" beside one named Cylinder a shape
    group = len(said) > 1 or not best  # a pool a relation chooses among ("the apple at the back") is a group
    literal = {n.lower() for n in scene.names} - (shape_named(scene) if determined or group else set())
    shared = kind_named(scene, groups) if group else set()  # "the apple at the back" beside green_apple: either
    modifiers = [i for i, lw in enumerate(low) if lw not in names and is_modifier(lw)]
    heads = set(names) | set(groups) | PROPORTION_NOUNS | {"can", "cans"} if modifiers else set()  # "the tin can"
    compound = {i for i in modifiers if _before_head(low, i, heads)}
    # "the stick", "the flat square"; not "tube" in "the tube rack", which says what the rack holds
    proportioned = [w for i, w in enumerate(low) if w in PROFILES and w not in literal and i not in compound
                    and (not best or w not in groups or w in NOUNS and w not in parts_of(tuple(scene.names)))]
    # "the tower": the rook in a chess set, not any tall thing; "the brick" where names say which are bricks; a group or
    # a relation's pool still takes every object the word admits ("the stick nearest the bowl")
    kept = [(w, lw) for i, (w, lw) in enumerate(zip(words, low, strict=True))
            if lw in names or (lw in groups and lw in PROFILES) or not (lw in drop or i in compound)]
    sized = len(kept) < len(low) and any(lw in SIZE_WORDS or lw in PROFILES for lw in low)
    if kept:  # "the little red cube": the other words decide
        words, low = [w for w, _ in kept], tuple(lw for _, lw in kept)
    elif not sized:
        unknown_object(text, words, low, scene)
    else:
        return fitting(proportioned, list(scene.objects), groups, best)  # "the tall", "the flat": alone
    colours = named_colours(low)
    named = [names[w] for w in low if w in names and w not in NOUNS and w not in shared
             and (w in literal or w not in SHAPE_NOUNS or best and w in PROFILES and w in groups)]  # "the tower"
    kinds = [groups[w] for w in low if w in groups and (w not in names or w in shared) and w not in SHAPE_NOUNS  # mugs
             and w not in as_colour]
    either = [(w, groups[w], SHAPE_NOUNS[w]) for w in low if w in groups and (w not in literal or w in NOUNS)
              and w in SHAPE_NOUNS and w not in PROFILES]  # "the big cube": the mesh named "cube" or another cube
    shapes = {SHAPE_NOUNS[w] for w in low if w in SHAPE_NOUNS and w not in groups and w not in PROFILES}
    shaped = {SHAPE_ADJECTIVES[w] for w in low if w in SHAPE_ADJECTIVES and w not in PROFILES}
    unknown = [w for w in low if w not in DESCRIPTION_WORDS and w not in names and w not in groups]
    if determined and named and len(low) == 2 and unknown == [low[0]] and low[0].isalpha() \
            and low[0] not in FUNCTION_WORDS and (low[0] not in KIND_SYNONYMS or low[0] in FRAMING_KINDS):
        # "the triangular toy" is another kind; "the goal: 6 ..." heads a wish
        unknown = []  # one adjective of its own between "the" and a name: "the rubber duck"
    if named and len(low) >= 2 and unknown == [low[-1]] and low[-2] in names \
            and (low[-1] in KIND_SYNONYMS or low[-1] in KIND_NAMES):
        unknown = []  # a name said before the noun for what it is: "the Starbucks cup", "the Sharpie marker"
    if unknown or not (colours or named or kinds or either or shapes or shaped or sized or proportioned
                       or set(low) & (NOUNS | BLOCK_WORDS)):
        unknown_object(text, words, low, scene)
    fits = list(scene.objects)
    if named:
        fits = [o for o in fits if o.name in named]
    for group in kinds:
        fits = [o for o in fits if o.name in group]
    for word, group, shape in either:  # "the red brick": a lego brick, or a brick-shaped block
        if word not in GEOMETRIC and any(o.name in group and (not colours or o.color in colours) for o in fits):
            # "the can": the soda can, not a plain cylinder beside it; "the gold box" is the box-shaped gold watch
            # case where no object named a box is gold
            fits = [o for o in fits if o.name in group]
            continue
        if word in ("box", "boxes") and not colours and any(o.name in group for o in fits) \
                and not any(o.name not in group and _another_box(o) for o in fits):
            fits = [o for o in fits if o.name in group]  # "the box": big_box, not one of the cubes beside it
            continue
        fits = [o for o in fits if o.name in group or shape_of(o) == shape
                or (word in ("box", "boxes") and kinds_of(o) & BOX_KINDS)]  # "the box": any box mesh too
        if word in ("box", "boxes"):  # "the big box": a parcel, not the tote beside it; "the gold box" the case
            boxy = [o for o in fits if _boxy(o)]
            fits = boxy if boxy and (not colours or any(o.color in colours for o in boxy)) else fits
    if colours:
        if not any(o.color in colours for o in scene.objects):
            colours = {NEAR_COLOURS.get(c, c) for c in colours}
        fits = [o for o in fits if o.color in colours]
    if shapes and not named:
        strict = shapes & STRICT_SHAPES
        if strict:
            fits = [o for o in fits if shape_of(o) in strict]
        elif colours:  # "the white cube", "the red box": block-shaped, never the white mug or a cylinder
            fits = [o for o in fits if shape_of(o) in BLOCK_SHAPES or ("box" in shapes and kinds_of(o) & BOX_KINDS)]
            if len(fits) > 1 and "cube" in shapes:  # "the blue cube" beside a long blue beam is the cube-like one
                kept = [o for o in fits if _cube_like(o)]
                fits = kept if len(kept) == 1 else fits
        else:  # "the box": a box, or a mesh that is one ("the cereal box"); a parcel, not the tote beside it; "the
            # cube": a box as long as it is wide and tall too
            fits = [o for o in fits if shape_of(o) in shapes or ("box" in shapes and kinds_of(o) & BOX_KINDS)
                    or ("cube" in shapes and shape_of(o) == "box" and _cube_like(o, CUBE_SAID))]
            if "box" in shapes:
                fits = [o for o in fits if _boxy(o)] or fits
    if shaped:
        fits = [o for o in fits if shape_of(o) in shaped or ("round" in low and kinds_of(o) & ROUND_KINDS)]
    if set(low) & BLOCK_WORDS and not named and not kinds:  # "the big green block": the cube, never the bottle
        fits = [o for o in fits if a_block_to_look_at(o)]
        if not shaped and not proportioned:  # "the yellow block": the cube, not the truck
            fits = [o for o in fits if not a_thing_by_name(o)] or fits
    if drink and len(fits) > 1:  # "the soda can" beside a soup can
        fits = [o for o in fits if not own_kinds_of(o) & FOODS] or fits
    if shades:  # "the silver cube" beside a grey one: the one the scene file calls silver
        fits = [o for o in fits if o.shade in shades] or fits
    elif plain and best and len(fits) > 1:  # "the grey box" beside a silver one: the one the file calls grey
        fits = [o for o in fits if _plain_colour(o)] or fits
    return fitting(proportioned, fits, groups, best)  # "the stick", "the long white one": by proportions


DESCRIPTION_WORDS = (frozenset(COLORS) | frozenset(COLOR_SYNONYMS) | NOUNS | frozenset(SHAPE_NOUNS)
                     | frozenset(SHAPE_ADJECTIVES) | BLOCK_WORDS | frozenset({"things", "objects", "ones"}))
"""The words of a description that every table knows (:func:`candidates`); a scene's names and kinds are known too."""


def _boxy(o: SceneObject) -> bool:
    """Whether "box" may name ``o`` among other block-shaped things: no thing with a name of its own (a tote, a star),
    or one whose kind is a box's (the butter box, a carton)."""
    return not a_thing_by_name(o) or bool(kinds_of(o) & BOX_KINDS)


def _another_box(o: SceneObject) -> bool:
    """Whether people would call ``o`` a box beside one named so: one "box" may name (:func:`_boxy`) that is of a box's
    kind (a carton, a crate) or a block but no cube, and not a thing named as its own kind (a banana or scissors
    modelled as a box are no box beside the cracker box)."""
    return _boxy(o) and (bool(kinds_of(o) & BOX_KINDS) or shape_of(o) in BLOCK_SHAPES and not _cube_like(o)
                         and not a_thing_by_name(o))


def a_block_to_look_at(o: SceneObject) -> bool:
    """Whether "block" and "brick" may name ``o``: a cube, a box or a cylinder, or a mesh of a block's kind (a lego
    brick, a crate), never the bowl, the mug or the bottle."""
    return shape_of(o) != "mesh" or bool(own_kinds_of(o) & BLOCK_KINDS)


BLOCKISH = BLOCK_KINDS | BLOCK_WORDS | frozenset(SHAPE_NOUNS) | PROPORTION_NOUNS | frozenset({"cube", "cubes"})
"""Kinds a block may be named by and still be a block ("brick", "slab", "beam", "tile")."""


def a_thing_by_name(o: SceneObject) -> bool:
    """Whether ``o`` is named as a thing of its own kind that is no block ("truck", "tray", "scanner"): among
    several that "block" fits, the plain blocks are meant ("the yellow block" beside a yellow toy truck is the
    cube); alone it is still the block ("the yellow block" where the wedge is the only yellow thing), and a shape said
    is a shape seen ("the rectangular block" is the brick or the bar of soap, as one author asked)."""
    kinds = own_kinds_of(o)
    return bool(kinds) and not kinds & BLOCKISH


def _plain_colour(o: SceneObject) -> bool:
    """Whether the scene file gives ``o`` its basic colour by that colour's own name ("gray", "grey"), not a shade."""
    return o.shade is None or o.shade.replace("grey", "gray") == o.color


def _shades_apart(low: tuple[str, ...]) -> tuple[str, ...]:
    """``low`` with "light" before a colour ("the light blue block") read as a shade, a word no table knows (so
    refused, lamp or none), never as the lamp "light" names alone."""
    return tuple("light-shade" if w == "light" and i + 1 < len(low) and low[i + 1] in COLOUR_WORDS else w
                 for i, w in enumerate(low))


def _before_head(low: tuple[str, ...], i: int, heads: set[str]) -> bool:
    """Whether the words after ``low[i]`` are more modifiers, then a kind's name ("video game controller")."""
    j = i + 1
    while j < len(low) and is_modifier(low[j]) and low[j] not in heads:
        j += 1
    return j < len(low) and low[j] in heads


CUBE_LIKE = 1.5
"""Longest side over shortest side up to which a block looks like a cube: "the blue cube" is the blue cube, not a
14 x 3 x 3 cm beam of the same colour (a careful author named them apart); where only one block has the colour, any
block is its cube, as the earlier authors called boxes cubes."""
CUBE_SAID = 1.2
"""Longest side over shortest side up to which a box is "the cube" said alone (no colour): a 5 cm cube is, a 6 x 4 x 4
cm box beside two cubes is not."""


def _cube_like(o: SceneObject, ratio: float = CUBE_LIKE) -> bool:
    g = o.geometry
    sides = [float(v) for v in (*outline_sides(o), g.height)]
    return max(sides) <= ratio * min(sides)


def colours_said(low: tuple[str, ...], scene: Scene) -> set[str]:
    """The words of ``low`` that name an object and a colour and stand before a noun, said as the colour: "the
    orange block" is the orange-coloured block beside an orange (the fruit) named "orange", and "the orange thing"
    is either; "the orange" alone stays the fruit."""
    names = name_words(scene)
    if not any(w in names for w in low[:-1]):
        return set()
    heads = NOUNS | BLOCK_WORDS | set(SHAPE_NOUNS) | set(kind_groups(scene)) | set(PROFILES)
    return {w for w, after in zip(low, low[1:], strict=False)
            if w in names and COLOR_SYNONYMS.get(w, w) in COLORS and after in heads
            and COLOR_SYNONYMS.get(after, after) not in COLORS}  # "the red blue and green cubes": a list


def unknown_object(text: str, words: list[str], low: tuple[str, ...], scene: Scene) -> None:
    if len(low) == 2 and low[1] in NOUNS and low[0] not in COLORS:  # "the sanger box": a colour, or a word of one's own
        suggested = did_you_mean(low[0], COLORS)
        raise UnknownObjectError(f'"{text}": "{words[0]}" is not a colour I know (blocks: {describe(scene)}).'
                                 + suggested, text, scene.names, "" if suggested else own_word(low[:1]))
    choices = scene.names + [f"the {o.color} block" for o in scene.objects]
    suggested = did_you_mean(text, choices)
    word = "" if suggested else own_word(low)
    raise UnknownObjectError(f'no block called "{text}" in the scene (blocks: {describe(scene)}).'
                             + (suggested or _own_word_hint(word)), text, scene.names, word)


def own_word(low: tuple[str, ...]) -> str:
    """The word of a description that a scene file's ``kind`` would give an object: its last word of letters, three
    or more ("the tin": "tin"; "the sanger box": said of "sanger" alone); "" where it has none."""
    return next((w for w in reversed(low) if len(w) >= 3 and w.isalpha()), "")


OWN_WORD_HINT = " To call an object"
"""How the hint of :func:`_own_word_hint` starts: what a refusal says after its reason (``perform`` asks for the word
instead, and shows the reason alone: commands/asking.py)."""


def _own_word_hint(word: str) -> str:
    """How to call an object by a word of one's own: the scene file's ``kind`` (each of its words calls the object),
    with ``word`` as the example ("the tin": "kind": "tin")."""
    said = f' "{word}", give it "kind": "{word}"' if word else ' by a word of your own, give it a "kind" (such as ' \
        '"kind": "toy cow")'
    return f"{OWN_WORD_HINT}{said} in the scene file."


def one_of(text: str, fits: list[SceneObject], scene: Scene, colours: set[str]) -> str:
    if len(fits) == 1:
        return fits[0].name
    if not fits:
        if colours and not any(o.color in colours for o in scene.objects):
            colour = sorted(colours)[0]
            raise UnknownObjectError(f"there is no {colour} block in the scene (blocks: {describe(scene)})."
                                     + did_you_mean(colour, sorted({o.color for o in scene.objects})))
        raise UnknownObjectError(f'nothing in the scene is "{text}" (blocks: {describe(scene)})')
    listed = ", ".join(o.name for o in fits)
    if colours and len(colours) == 1 and all(o.color in colours for o in fits):
        raise LanguageError(f'"{text}" is ambiguous: {len(fits)} {next(iter(colours))} blocks ({listed}); '
                            "name the one you mean")
    raise LanguageError(f'"{text}" is ambiguous: it fits {len(fits)} objects ({listed}); name the one you mean')
