"""Words that name an object -> the object's name, resolved against the scene before anything moves.

People name objects many ways: by name ("A", "block A", "the duck"), colour ("the red one"), shape
("the box", "the cylinder", "the tall one"), a superlative ("the biggest one", "the block nearest the
robot", "the leftmost block"), a relation to another object ("the one left of B") or a pronoun that
points back to the previous clause ("it", "that one": its mover; "the other one": its anchor).

Every reading is checked against the scene: a description that fits several objects is a one-line
error that lists them (a refusal beats a wrong block), and so is one that fits none. Left and right are
the robot's (the scene's +y is its left, DESIGN.md section 4), the view of a person behind it.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from ..core.scene import COLORS, ROBOT_BASE_XY, Scene, SceneObject
from ..errors import LanguageError, UnknownObjectError, did_you_mean
from .synonyms import BIG, KIND_MODIFIERS, KIND_SYNONYMS, SIZE_WORDS, SMALL, TALL, TIE_SIZE, kind_groups, kind_words

DETERMINERS = frozenset({"the", "a", "an", "this", "that"})
NOUNS = frozenset({"block", "cube", "box", "brick", "one", "object", "thing", "piece", "item"})
SHAPE_NOUNS = {"cube": "cube", "cubes": "cube", "box": "box", "boxes": "box", "cylinder": "cylinder",
               "can": "cylinder", "cylinders": "cylinder"}
"""Nouns that also name a shape: alone ("the box") they pick objects of that shape; with a colour ("the red
box", "the white cube") any block-shaped object (a cube or a box: people call any block a box or a
cube), never a cylinder or a mesh."""
STRICT_SHAPES = frozenset({"cylinder"})
"""Shapes no one calls another shape by: "the red cylinder" is refused where the red object is a cube."""
SHAPE_ADJECTIVES = {"rectangular": "box", "oblong": "box", "elongated": "box", "long": "box", "cubic": "cube",
                    "square": "cube", "cylindrical": "cylinder", "round": "cylinder"}
"""Adjectives that name a shape: they restrict like a shape named alone, colour or not ("the yellow
rectangular block" is a box)."""
SOFT_ADJECTIVES = frozenset({"flat", "toy", "rubber", "plastic", "wooden", "lone", "single"}) | SIZE_WORDS
"""Adjectives people add to a description that already picks one object ("the toy duck", "the little red
cube"): read past there. The size words among them (synonyms.SIZE_WORDS) decide where the rest leaves several."""
COLOR_SYNONYMS = {"grey": "gray", "violet": "purple", "magenta": "pink", "turquoise": "cyan"}
FUNCTION_WORDS = frozenset({"on", "of", "to", "in", "at", "by", "with", "from", "into", "onto", "over", "under",
                            "and", "or", "then", "so", "it", "not", "no", "other", "another", "first", "second",
                            "third", "last", "next", "same", "new", "one", "two", "three", "both", "either"})
"""Words never taken as an object's own adjective ("the second duck" is not "the duck")."""
NAMED_AS = (("called",), ("named",))
PRONOUNS_MOVER = (("it",), ("that", "one"), ("that", "block"), ("this", "one"), ("the", "same", "block"),
                  ("the", "same", "one"), ("the", "same", "object"), ("that",))
SAME_WORDS = (("that", "same"), ("this", "same"), ("the", "same"), ("that",), ("this",))
"""Openings that, before a noun ("that same cube", "this object"), point back to the previous clause's mover."""
PRONOUNS_ANCHOR = (("the", "other", "one"), ("the", "other", "block"), ("the", "other"))
ROBOT_WORDS = (("the", "robot"), ("robot",), ("the", "arm"), ("the", "robot's", "base"), ("you",), ("yourself",),
               ("your", "base"))
"""The robot's base as a reference point; "you" is the robot, whom the sentence addresses."""
NEAREST = frozenset("nearest closest nearer closer".split())  # English words of place ("the cube closer to you")
FARTHEST = frozenset({"farthest", "furthest", "farther", "further"})
"""Comparatives read as superlatives: "the red cube nearer to you" is the nearer of the red cubes."""
OPENINGS = {("whatever", "is"): ("the", "one"), ("whichever", "is"): ("the", "one"), ("whatever's",): ("the", "one"),
            ("what", "is"): ("the", "one"), ("the", "one", "that", "is"): ("the", "one")}
"""Free relatives that open a description ("whatever is closest to A"): the one that is."""
RELATIVES = (("that", "is"), ("which", "is"), ("that's",), ("thats",), ("which's",))
"""A relative clause after a noun ("the cube that is red", "the block that's closest to E"): its words describe
the noun as if they stood before it."""
SIZE_SUPERLATIVES = {"biggest": ("area", max), "largest": ("area", max), "smallest": ("area", min),
                     "tallest": ("height", max), "highest": ("height", max), "shortest": ("height", min),
                     "lowest": ("height", min), "leftmost": ("y", max), "rightmost": ("y", min),
                     "backmost": ("x", max), "frontmost": ("x", min)}
TIE = 0.02
TIE_M = 0.002
"""Two objects whose measures (lengths) differ by less than TIE of the best or TIE_M metres are a tie:
the description is ambiguous."""
TIE_PLACE = 0.45
"""Where a superlative compares places (leftmost, nearest), two objects whose places differ by less than this
many times the smaller one's side are a tie: a person does not tell a centimetre apart between 4 cm blocks."""
CENTRE_PHRASES = (("in", "the", "middle", "of", "the", "table"), ("in", "the", "center", "of", "the", "table"),
                  ("in", "the", "centre", "of", "the", "table"), ("in", "the", "middle"), ("in", "the", "center"),
                  ("in", "the", "centre"))
"""A place on the table that names the object nearest the table's centre (the scene frame's origin)."""
SIDE_PHRASES = {("on", "the", "far", "left"): "leftmost", ("on", "the", "far", "right"): "rightmost",
                ("on", "the", "left"): "leftmost", ("on", "the", "right"): "rightmost",
                ("at", "the", "far", "left"): "leftmost", ("at", "the", "far", "right"): "rightmost",
                ("at", "the", "back"): "backmost", ("in", "the", "back"): "backmost",
                ("at", "the", "front"): "frontmost", ("in", "the", "front"): "frontmost"}
"""Places that read as a superlative ("the object on the far right" is the rightmost; "the red cube at the back"
the one farthest from the robot, along the scene's +x)."""
SIDE_CONE = math.radians(45)
""""Left of B": the object's bearing from B is within this angle of the robot's left (+y)."""
SIDES = {"left of": math.pi / 2, "right of": -math.pi / 2, "behind": 0.0, "in front of": math.pi}
"""Relations to a reference as the robot sees it -> their direction in the scene (radians from +x, away from
the robot): behind is further from the robot, in front nearer to it."""


@dataclass(frozen=True)
class Context:
    """What pronouns point back to: the previous clause's mover and anchor (None: there is none)."""

    mover: str | None = None
    anchor: str | None = None


def describe(scene: Scene) -> str:
    return ", ".join(f"{o.name} ({o.color})" for o in scene.objects)


def resolve_object(text: str, scene: Scene, role: str = "block", context: Context | None = None) -> str:
    """The name of the object ``text`` refers to; a one-line error when none or several fit."""
    return _resolve(text, scene, role, context)


def measured_from(text: str, scene: Scene, context: Context | None = None) -> str | None:
    """The object a relational description measures from ("the object nearest the cylinder": the cylinder), or
    None (no relation, or one to the robot): what "it" later in the same clause means ("move the object nearest
    the cylinder away from it"), since the block moved cannot be moved away from itself."""
    words = _plain_order(text.split(), scene)
    low = tuple(w.lower() for w in words)
    head = _head_end(low)
    if head is None or head[0] in SIZE_SUPERLATIVES:
        return None
    ref = _reference_point(words[head[2]:], scene, "reference block", context)
    return ref[0] if ref is not None else None


def _resolve(text: str, scene: Scene, role: str, context: Context | None) -> str:
    words = text.split()
    if not words:
        raise LanguageError(f"the sentence does not name the {role}")
    names = scene.names
    if text in names:  # an exact name first: a block may well be called "a" or "the cube"
        return text
    words = _plain_order(words, scene)
    low = tuple(w.lower() for w in words)
    pointed = _pronoun(words, low, context, role, scene)
    if pointed is not None:
        return pointed
    for i in range(1, len(low) - 1):
        if low[i - 1] in NOUNS and low[i:i + 1] in NAMED_AS:  # "the block called A"
            return resolve_object(" ".join(words[i + 1:]), scene, role, context)
    determined = False
    while len(low) > 1 and low[0] in DETERMINERS and words[0] not in names:
        words, low, determined = words[1:], low[1:], True
    candidate = " ".join(words)
    if candidate in names:
        return candidate
    folded = [n for n in names if n.lower() == candidate.lower()]
    if len(folded) == 1:
        return folded[0]
    relational = _relational(words, low, scene, role, context)
    if relational is not None:
        return relational
    return _described(text, words, low, scene, determined)


def _plain_order(words: list[str], scene: Scene) -> list[str]:
    """``words`` with a free relative's opening ("whatever is closest to A": the one closest to A) and a relative
    clause's "that is" ("the cube that is red": the cube red) taken out; the other readers take words in any
    order."""
    low = tuple(w.lower() for w in words)
    for opening, plain in OPENINGS.items():
        if low[:len(opening)] == opening and len(low) > len(opening):
            return list(plain) + words[len(opening):]
    nouns = NOUNS | set(SHAPE_NOUNS) | set(_name_words(scene))
    for i in range(1, len(low) - 1):
        for rel in RELATIVES:
            if low[i - 1] in nouns and low[i:i + len(rel)] == rel and i + len(rel) < len(low):
                return words[:i] + words[i + len(rel):]
    return words


def _pronoun(words: list[str], low: tuple[str, ...], context: Context | None, role: str,
             scene: Scene) -> str | None:
    said = " ".join(low)  # what the user wrote, for the error: "that same cube" reads as "it" below
    kinds = _name_words(scene)
    opening = next((o for o in SAME_WORDS if low[:len(o)] == o and len(low) == len(o) + 1), None)
    if opening is not None and (low[-1] in SHAPE_NOUNS or (low[-1] in kinds and low[-1] not in NOUNS)):
        return _that_kind(said, low[-1], context, role, scene)
    if opening is not None and low[-1] in NOUNS:
        low = ("it",)
    if low[:2] == ("the", "other") and len(low) > 2 and low not in PRONOUNS_ANCHOR:
        return _the_other(said, words[2:], context, role, scene)
    if low in PRONOUNS_MOVER or low in PRONOUNS_ANCHOR:
        if context is None or context.mover is None:
            raise _no_earlier(said, role)
        if low in PRONOUNS_MOVER:
            return context.mover
        _no_twin(said, context, scene)
        return context.anchor
    return None


def _no_earlier(said: str, role: str) -> LanguageError:
    """The error for a word that points back ("it", "that cylinder", "the other red cube") in a first clause."""
    return LanguageError(f'"{said}" ({role}) points back to an earlier clause, and there is none; name the block')


def _fits_kind(o: SceneObject, noun: str, scene: Scene) -> bool:
    """Whether ``noun`` ("cylinder", "cube", "duck") may name ``o``: a shape noun its shape (a cube or a box for
    "cube" and "box"), a kind word the object it names."""
    kinds = _name_words(scene)
    if noun in kinds:
        return kinds[noun] == o.name
    shape = SHAPE_NOUNS[noun]
    return o.shape == shape if shape in STRICT_SHAPES else o.shape in BLOCK_SHAPES


def _that_kind(said: str, noun: str, context: Context | None, role: str, scene: Scene) -> str | None:
    """"that cylinder", "this cube": the object of that kind among the previous clause's (its mover first, then
    its anchor); with none of that kind there, what "the cylinder" names in the scene (None: read on)."""
    if context is None or context.mover is None:
        if noun in _name_words(scene):
            return None  # "that duck" in a first clause: the duck
        raise _no_earlier(said, role)
    for name in (context.mover, context.anchor):
        if name is not None and name in scene.names and _fits_kind(scene.get(name), noun, scene):
            return name
    return None


def _the_other(said: str, words: list[str], context: Context | None, role: str, scene: Scene) -> str:
    """"the other red cube", "the other white object": what the rest describes, other than the previous clause's
    mover; refused unless exactly one object is left."""
    if context is None or context.mover is None:
        raise _no_earlier(said, role)
    low = tuple(w.lower() for w in words)
    fits = [o for o in _candidates(said, words, low, scene) if o.name != context.mover]
    if len(fits) != 1:
        listed = ", ".join(o.name for o in fits) or "none"
        raise LanguageError(f'"{said}" is ambiguous: other than {context.mover} it fits {listed}; '
                            "name the one you mean")
    return fits[0].name


def _no_twin(said: str, context: Context, scene: Scene) -> None:
    """Refuses "the other one" where a third object shares the colour of one of the previous clause's two: after
    "move the small red cube next to F", "the other one" may be the other red cube as well as F."""
    pair = [n for n in (context.mover, context.anchor) if n is not None and n in scene.names]
    if len(pair) < 2:
        return
    colours = {scene.get(n).color for n in pair}
    twins = [o.name for o in scene.objects if o.color in colours and o.name not in pair]
    if twins:
        raise LanguageError(f'"{said}" is ambiguous: {context.anchor} (of the previous clause) or {", ".join(twins)} '
                            f"(the other of its colour); name the one you mean")


def _described(text: str, words: list[str], low: tuple[str, ...], scene: Scene, determined: bool) -> str:
    """Colour, shape, size and name words ("the red block", "red A", "the orange duck", "the tall one", "the big
    red cube").

    "Block" covers any object ("the purple block" is the cylinder where nothing else is purple), but where the
    other words leave several and one of them is block-shaped (a cube or a box), that one is meant ("the white
    block": the cube, not the white mug); the two readings are refused where they pick different objects."""
    names = _name_words(scene)
    sizes = [w for w in low if w in SIZE_WORDS and w not in names]
    fits = _candidates(text, words, low, scene, determined)
    pools = [fits]
    blocky = [o for o in fits if o.shape in BLOCK_SHAPES]
    if set(low) & BLOCK_WORDS and 0 < len(blocky) < len(fits) and not set(low) & set(names):
        pools.append(blocky)
    readings: list[str | Exception] = []
    for pool in pools:
        try:
            readings.append(_by_size(text, pool, sizes, scene, _colours(low)))
        except (LanguageError, UnknownObjectError) as e:
            readings.append(e)
    picked = sorted({r for r in readings if isinstance(r, str)})
    if len(picked) == 1:
        return picked[0]
    if len(picked) > 1:
        raise LanguageError(f'"{text}" is ambiguous: as any object it is {readings[0]}, as a block (a cube or a '
                            f"box) {readings[1]}; name the one you mean")
    raise readings[0]


def _candidates(text: str, words: list[str], low: tuple[str, ...], scene: Scene,
                determined: bool = True) -> list[SceneObject]:
    """The objects the name, colour and shape words of a description allow (size words and "block"'s preference
    are for :func:`_described`); an unknown word is a one-line error."""
    names = _name_words(scene)
    drop = SOFT_ADJECTIVES
    heads = set(names) | set(kind_groups(scene)) | {"can", "cans"}  # "the tin can": named so or a cylinder
    kept = [(w, lw) for i, (w, lw) in enumerate(zip(words, low, strict=True))
            if lw in names or not (lw in drop or (lw in KIND_MODIFIERS and i + 1 < len(low) and low[i + 1] in heads))]
    sized = len(kept) < len(low) and any(lw in SIZE_WORDS for lw in low)
    if kept:  # "the little red cube": the other words decide
        words, low = [w for w, _ in kept], tuple(lw for _, lw in kept)
    elif not sized:
        _unknown(text, words, low, scene)
    else:
        return list(scene.objects)  # "the tall": size words alone
    colours = _colours(low)
    named = [names[w] for w in low if w in names and w not in NOUNS]
    groups = kind_groups(scene)
    kinds = [groups[w] for w in low if w in groups and w not in names]  # "the red mug" among two mugs
    shapes = {SHAPE_NOUNS[w] for w in low if w in SHAPE_NOUNS}
    shaped = {SHAPE_ADJECTIVES[w] for w in low if w in SHAPE_ADJECTIVES}
    known = (set(COLORS) | set(COLOR_SYNONYMS) | NOUNS | set(SHAPE_NOUNS) | set(SHAPE_ADJECTIVES) | BLOCK_WORDS
             | {"things", "objects", "ones"} | set(names) | set(groups))
    unknown = [w for w in low if w not in known]
    if determined and named and len(low) == 2 and unknown == [low[0]] and low[0].isalpha() \
            and low[0] not in FUNCTION_WORDS:
        unknown = []  # one adjective of its own between "the" and a name: "the rubber duck"
    if unknown or not (colours or named or kinds or shapes or shaped or sized or set(low) & (NOUNS | BLOCK_WORDS)):
        _unknown(text, words, low, scene)
    fits = list(scene.objects)
    if named:
        fits = [o for o in fits if o.name in named]
    for group in kinds:
        fits = [o for o in fits if o.name in group]
    if colours:
        fits = [o for o in fits if o.color in colours]
    if shapes and not named:
        strict = shapes & STRICT_SHAPES
        if strict:
            fits = [o for o in fits if o.shape in strict]
        elif colours:  # "the white cube", "the red box": block-shaped, never the white mug or a cylinder
            fits = [o for o in fits if o.shape in BLOCK_SHAPES]
        else:
            fits = [o for o in fits if o.shape in shapes]
    if shaped:
        fits = [o for o in fits if o.shape in shaped]
    return fits


def _by_size(text: str, pool: list[SceneObject], sizes: list[str], scene: Scene, colours: set[str]) -> str:
    """The one object of ``pool`` the size words pick (big/small by footprint, tall/short by height), each in turn
    keeping the objects within :data:`~l2p_bullet.language.synonyms.TIE_SIZE` of the extreme; with one object
    the size words are read past, with several left the description is ambiguous."""
    if len(pool) > 1:
        for word in sizes:
            height = word in TALL or word not in BIG | SMALL
            pick = max if word in BIG | TALL else min
            values = {o.name: _measure(o, "height" if height else "area") for o in pool}
            best = pick(values.values())
            tied = [o for o in pool if abs(values[o.name] - best) < TIE_SIZE * min(values[o.name], best)]
            if len(tied) > 1 and len(tied) < len(pool):
                listed = ", ".join(o.name for o in tied)
                raise LanguageError(f'"{text}" is ambiguous: {listed} are all but equally {word}; '
                                    "name the one you mean")
            pool = tied
    return _one(text, pool, scene, colours)


def _name_words(scene: Scene) -> dict[str, str]:
    """Lower-case words that name an object -> its name: the name, and for a word name its fond forms
    ("ducky", "duckie": the duck)."""
    out = {}
    for n in scene.names:
        low = n.lower()
        if len(low) >= 3 and low.isalpha():
            out[low + "y"] = out[low + "ie"] = n
    out.update(kind_words(scene))
    out.update({n.lower(): n for n in scene.names})
    return out


def _colours(low) -> set[str]:
    """The colours ``low`` (lower-case words) name, synonyms resolved ("grey" is gray)."""
    return {c for w in low if (c := COLOR_SYNONYMS.get(w, w)) in COLORS}


def _unknown(text: str, words: list[str], low: tuple[str, ...], scene: Scene) -> None:
    if len(low) == 2 and low[1] in NOUNS and low[0] not in COLORS:
        raise UnknownObjectError(f'"{text}": "{words[0]}" is not a colour I know (blocks: {describe(scene)}).'
                                 + did_you_mean(low[0], COLORS))
    choices = scene.names + [f"the {o.color} block" for o in scene.objects]
    raise UnknownObjectError(f'no block called "{text}" in the scene (blocks: {describe(scene)}).'
                             + did_you_mean(text, choices))


def _one(text: str, fits: list[SceneObject], scene: Scene, colours: set[str]) -> str:
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


def _measure(o: SceneObject, what: str) -> float:
    """A length in metres: the footprint's side (its area's square root), the height, y (leftness) or x (how far
    back from the robot)."""
    if what == "area":
        return float(o.size)
    if what == "height":
        return float(o.geometry.height)
    return float(o.xy[0] if what == "x" else o.xy[1])


def _relational(words: list[str], low: tuple[str, ...], scene: Scene, role: str,
                context: Context | None) -> str | None:
    """Superlatives and relations: None when ``words`` hold none (then colours and names are tried).

    "Block" may mean any object or only the block-shaped ones (cubes and boxes): people differ. Where the two
    readings pick different objects ("the smallest block": the cylinder, or three equal cubes), the
    description is ambiguous and refused."""
    placed = _placed(words, low, scene, role, context)
    if placed is not None:
        return placed
    head = _head_end(low)
    if head is None:
        return None
    kind, at, end = head
    rest_words = words[end:]
    if kind in SIZE_SUPERLATIVES:  # "the biggest red block": the words on both sides restrict
        if any(w.lower() not in NOUNS | set(COLORS) | set(SHAPE_NOUNS) for w in rest_words):
            return None
        described = words[:at] + rest_words
        what, pick = SIZE_SUPERLATIVES[kind]
        place = what in ("x", "y")
        return _either_reading(
            described, scene, lambda pool: _superlative(pool, lambda o: _measure(o, what), pick, kind, place)
        )
    ref = _reference_point(rest_words, scene, role, context)
    if ref is None:
        return None
    ref_name, ref_xy = ref

    def choose(pool: list[SceneObject]) -> str:
        pool = [o for o in pool if o.name != ref_name]
        if kind in SIDES:
            beside = [o for o in pool if _bearing_off(np.subtract(o.xy, ref_xy), SIDES[kind]) <= SIDE_CONE]
            if not beside:
                raise UnknownObjectError(f'nothing in the scene is {kind} {ref_name or "the robot"} as the robot '
                                         f"sees it (blocks: {describe(scene)})")
            return _superlative(beside, lambda o: _distance(o, ref_xy), min, f"{kind} of", place=True)
        return _superlative(pool, lambda o: _distance(o, ref_xy), min if kind in NEAREST else max, kind, place=True)

    return _either_reading(words[:at], scene, choose)  # "the red block nearest B": the red ones only


def _placed(words: list[str], low: tuple[str, ...], scene: Scene, role: str, context: Context | None) -> str | None:
    """Places on the table: "the cube in the middle (of the table)", "the object on the far right", "the cube
    between A and C" (nearest the middle of the two, and lying between them); None when ``words`` name none."""
    for phrase in CENTRE_PHRASES:
        if len(low) > len(phrase) and low[-len(phrase):] == phrase:
            return _either_reading(words[:-len(phrase)], scene, lambda pool: _superlative(
                pool, lambda o: _distance(o, (0.0, 0.0)), min, "in the middle", place=True))
    for phrase, kind in SIDE_PHRASES.items():
        if len(low) > len(phrase) and low[-len(phrase):] == phrase:
            what, pick = SIZE_SUPERLATIVES[kind]
            said = " ".join(phrase)
            return _either_reading(words[:-len(phrase)], scene, lambda pool, what=what, pick=pick, said=said:
                                   _superlative(pool, lambda o: _measure(o, what), pick, said, place=True))
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
        mid = tuple((a + b) / 2)
        return _superlative(inside, lambda o: _distance(o, mid), min, "between", place=True)

    return _either_reading(words[:at], scene, choose)


def two_references(words: list[str], scene: Scene, role: str, context: Context | None) -> tuple[str, str] | None:
    """"A and C", "the red and blue cubes" -> two different objects' names; None when ``words`` are not two."""
    return next((p for p in object_pairs(words, scene, (role, role), context) if isinstance(p, tuple) and p[0] != p[1]),
                None)


CONJUNCTIONS = frozenset({"and", "&"})
"""Words that join two reference objects ("between B and C", "the cube between A and C")."""


def object_pairs(words: list[str], scene: Scene, roles: tuple[str, str],
                 context: Context | None) -> Iterator[tuple[str, str] | LanguageError | UnknownObjectError]:
    """Each reading of ``words`` as two objects joined by a conjunction, split by split: the pair of names, or
    the one-line error of that split (the caller decides which split wins and which error to show)."""
    for k, w in enumerate(words):
        if w.lower() not in CONJUNCTIONS or not 0 < k < len(words) - 1:
            continue
        try:
            yield (resolve_object(" ".join(words[:k]), scene, roles[0], context),
                   resolve_object(" ".join(words[k + 1:]), scene, roles[1], context))
        except (LanguageError, UnknownObjectError) as e:
            yield e


BLOCK_WORDS = frozenset({"block", "blocks", "brick", "bricks"})
BLOCK_SHAPES = frozenset({"cube", "box"})
REFERENCE_WORDS = frozenset(SIZE_WORDS | set(KIND_SYNONYMS) | KIND_MODIFIERS | BLOCK_WORDS | NEAREST | FARTHEST
                            | {w for p in (*OPENINGS, *RELATIVES, *ROBOT_WORDS) for w in p})
"""Every word a description may hold beyond the tables above (sizes, kinds' everyday names, "whatever is",
"you"): known words, which a reader of typing slips leaves as they are."""


def _either_reading(described: list[str], scene: Scene, choose) -> str:
    """``choose`` over the objects ``described`` allows; with "block" in it, over the block-shaped ones too, and
    the description refused as ambiguous where the two readings differ."""
    pool = _pool(" ".join(described), scene)
    if not {w.lower() for w in described} & BLOCK_WORDS:
        return choose(pool)
    readings = []
    for candidates in (pool, [o for o in pool if o.shape in BLOCK_SHAPES]):
        try:
            readings.append(choose(candidates))
        except (LanguageError, UnknownObjectError) as e:
            readings.append(e)
    if isinstance(readings[0], str) and readings[0] == readings[1]:
        return readings[0]
    said = " ".join(described + ["..."])
    picks = sorted({r for r in readings if isinstance(r, str)})
    raise LanguageError(f'"{said}" is ambiguous: as any object it is {picks[0] if picks else "none"}, as a block '
                        f'(a cube or a box) {"another" if len(picks) > 1 else "not one"}; name the one you mean')


def _distance(o: SceneObject, xy: tuple[float, float]) -> float:
    """Centre to ``xy`` in metres: what "nearest" and "farthest" compare."""
    return float(np.hypot(o.xy[0] - xy[0], o.xy[1] - xy[1]))


def _head_end(low: tuple[str, ...]) -> tuple[str, int, int] | None:
    """(the relation's word, where its phrase starts, where its reference starts) or None."""
    for i, w in enumerate(low):
        if w in SIZE_SUPERLATIVES:
            return w, i, i + 1
        if w in NEAREST | FARTHEST:
            j = i + 1
            if j < len(low) and low[j] in NOUNS:  # "the closest block to the duck"
                j += 1
            if j < len(low) and low[j] in ("to", "from"):
                j += 1
            return w, i, j
        if w in ("left", "right") and i + 1 < len(low) and low[i + 1] == "of":
            start = i
            while start > 0 and low[start - 1] in ("to", "on", "the"):
                start -= 1
            return f"{w} of", start, i + 2
        if w == "behind" and i > 0:
            return w, i, i + 1
        if low[i:i + 3] == ("in", "front", "of") and i > 0:
            return "in front of", i, i + 3
    return None


def _pool(restrict: str, scene: Scene) -> list[SceneObject]:
    """The objects a relation chooses among: those that ``restrict`` ("the red block", "the") allows."""
    low = [w.lower() for w in restrict.split()]
    low = [w for w in low if w not in DETERMINERS and (w not in NOUNS or w in ("cube", "cylinder"))]
    colours = _colours(low)
    fits = list(scene.objects)
    if colours:
        fits = [o for o in fits if o.color in colours]
    shapes = {SHAPE_NOUNS[w] for w in low if w in ("cube", "cylinder")}
    if shapes:
        fits = [o for o in fits if o.shape in shapes]
    return fits


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


def _bearing_off(v: np.ndarray, direction: float) -> float:
    """The angle between ``v`` and the scene direction ``direction`` (radians from +x: the robot's left is pi/2)."""
    ang = math.atan2(float(v[1]), float(v[0]))
    return abs(math.remainder(ang - direction, 2 * math.pi))


def _superlative(pool: list[SceneObject], measure, pick, word: str, place: bool = False) -> str:
    """The one object of ``pool`` that ``pick`` (min or max) of ``measure`` chooses; ties are ambiguous. With
    ``place`` the measure is a place (metres along the table), and a tie is closer than :data:`TIE_PLACE` sides."""
    if not pool:
        raise UnknownObjectError(f'no object in the scene is the "{word}" one')
    values = {o.name: measure(o) for o in pool}
    best = pick(values.values())
    winner = next(o for o in pool if values[o.name] == best)

    def tol(o: SceneObject) -> float:
        t = max(TIE * abs(best), TIE_M)
        return max(t, TIE_PLACE * min(float(o.size), float(winner.size))) if place else t

    tied = [o.name for o in pool if abs(values[o.name] - best) <= tol(o)]
    if len(tied) > 1:
        raise LanguageError(f'"{word}" is ambiguous: {", ".join(tied)} are all but equally so; name the one you mean')
    return tied[0]
