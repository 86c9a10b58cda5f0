"""The objects a relation or a place chooses among: those a description before it allows ("the box at the back": the
boxes; "the red one nearest A": the red ones), read as descriptions.candidates reads a description, and the two
readings of "block" (any object, or a block to look at) compared.

Apart from places.py, whose measures descriptions.py reads too: this module reads descriptions, so it stands after
both.
"""

from __future__ import annotations

from ..core.scene import Scene, SceneObject
from ..errors import LanguageError, UnknownObjectError
from .descriptions import a_block_to_look_at, candidates
from .places import named_colours
from .proportions import PROFILES, admits
from .reference_words import (
    BLOCK_SHAPES,
    BLOCK_WORDS,
    DETERMINERS,
    DIRECTIONS,
    EDGE_WORDS,
    KIND_WORDS,
    MIDDLE_WORDS,
    NOUNS,
    SIDE_SUPERLATIVE,
)
from .shape_words import SHAPE_NOUNS
from .synonyms import KIND_NAMES, kind_groups, kinds_of, shape_of

BOX_WORDS = frozenset(KIND_NAMES["box"]) | {"box", "boxes"}
"""A box's everyday words ("carton", "parcel", "package"): boxes a code names (SKU-4471) are them."""
PLAIN_NOUNS = frozenset({"one", "ones", "thing", "things", "object", "objects", "item", "items", "piece", "part"})
"""Nouns that name no kind ("the one at the back"): every object."""
UNREAD_PLACES = frozenset(DIRECTIONS) | frozenset(SIDE_SUPERLATIVE.values()) | EDGE_WORDS - {"part"} | MIDDLE_WORDS \
    | {"behind", "corner", "corners", "row", "rows", "column", "columns"}
"""Words of a place: in a description a relation reads beside another place, left unread, they would leave the other
place to pick another object ("the one way over on the left side in the middle of the table")."""


SHAPE_SAID = {w: SHAPE_NOUNS[w] for w in ("box", "boxes", "cylinder", "cylinders", "cube", "cubes")}
"""The plain shape nouns (of :data:`~.shape_words.SHAPE_NOUNS`, not its nouns of proportions) that a relation may
choose among by shape ("the leftmost box" of three boxes, one of them a box of syringes by its kind)."""


def _shaped_alike(said: list[str], scene: Scene) -> list[SceneObject]:
    """The objects of the shape ``said`` names where it is one shape noun alone (:data:`SHAPE_SAID`), else none: a
    relation asks for one of several, so where the kind word names one object ("box" for syringe_box) and the shape
    several, it is the shape that is meant."""
    shape = SHAPE_SAID.get(said[0].lower()) if len(said) == 1 else None
    return [o for o in scene.objects if shape_of(o) == shape] if shape is not None else []


def pool_of(restrict: str, scene: Scene) -> list[SceneObject]:
    """The objects a relation chooses among: those that ``restrict`` ("the red block", "the box", "the") allows, as
    descriptions.candidates reads a description ("the box at the back" is the box farthest back, never the plate
    behind it). Where words it does not read are left ("the cube sitting"), its colour and shape words alone: "block"
    and "brick" a block to look at, never the bowl or the mug, a word of proportions ("the stick", "the long one")
    the objects it admits (language/proportions.py); an unread place word is refused (:data:`UNREAD_PLACES`)."""
    low = [w.lower() for w in restrict.split()]
    fits = list(scene.objects)
    said = [w for w in restrict.split() if w.lower() not in DETERMINERS]
    if {w.lower() for w in said} - PLAIN_NOUNS:
        try:  # the objects the description names by kind, colour, shape and proportions ("the box": a box)
            found = candidates(restrict, said, tuple(w.lower() for w in said), scene)
            if len(found) == 1:  # one object by its kind word: several of that shape are what a relation picks among
                shaped = _shaped_alike(said, scene)
                if len(shaped) > 1:
                    return shaped
            return found
        except (LanguageError, UnknownObjectError):
            said_before = low[:-1] if low[-1] == "right" else low  # "right in the middle": how near, not a side
            placed = [w for w in said_before if w in UNREAD_PLACES]
            if placed:  # "the one on the left side" before "in the middle": two places, one of them unread
                raise LanguageError(f'"{restrict}" says a place ("{placed[0]}") before another; say one place, or '
                                    "name the object") from None
            groups = kind_groups(scene)
            unread = [w for w in low if w in KIND_WORDS and w not in SHAPE_NOUNS and w not in groups]
            if unread:  # a kind nothing is: none, never the nearest of all
                if not BOX_WORDS.issuperset(unread):
                    return []
                # "the carton by the tape gun" where nothing is a carton by name: the boxes of no kind (SKU-4471)
                return [o for o in fits if shape_of(o) == "box" and not kinds_of(o) & KIND_WORDS]
    if set(low) & BLOCK_WORDS:
        fits = [o for o in fits if a_block_to_look_at(o)]
    low = [w for w in low if w not in DETERMINERS and (w not in NOUNS or w in ("cube", "cylinder"))]
    colours = named_colours(low)
    if colours:
        fits = [o for o in fits if o.color in colours]
    shapes = {SHAPE_NOUNS[w] for w in low if w in ("cube", "cylinder")}
    if shapes:
        fits = [o for o in fits if shape_of(o) in shapes]
    for word in (w for w in low if w in PROFILES and w not in {n.lower() for n in scene.names}):
        fits = [o for o in fits if admits(word, o, kind_groups(scene))]  # "the stick nearest the bowl": a stick
    return fits


def either_reading(described: list[str], scene: Scene, choose, pool: list[SceneObject] | None = None) -> str:
    """``choose`` over the objects ``described`` allows (``pool`` where the caller chose them); with "block" in it,
    over the block-shaped ones too, and the description refused as ambiguous where the two readings differ. Where the
    scene names several objects with the word said ("brick_2x4_red", "brick_2x2_blue"), the names say which are
    bricks: those alone."""
    pool = pool_of(" ".join(described), scene) if pool is None else pool
    said_blocks = {w.lower() for w in described} & BLOCK_WORDS
    if not said_blocks:
        return choose(pool)
    groups = kind_groups(scene)  # "the leftmost brick" where the names say which are bricks (brick_2x4_red ...)
    named = {n for w in said_blocks for n in groups.get(w, ())}
    if len(named) > 1 and any(o.name not in named for o in pool) and any(o.name in named for o in pool):
        return choose([o for o in pool if o.name in named])  # the names say which are bricks, not their shapes
    readings = []
    for among in (pool, [o for o in pool if shape_of(o) in BLOCK_SHAPES]):
        try:
            readings.append(choose(among))
        except (LanguageError, UnknownObjectError) as e:
            readings.append(e)
    if isinstance(readings[0], str) and readings[0] == readings[1]:
        return readings[0]
    said = " ".join(described + ["..."])
    picks = sorted({r for r in readings if isinstance(r, str)})
    if not picks:
        raise readings[0]  # neither reading picks one: why the first does not (a tie, nothing on that side)
    raise LanguageError(f'"{said}" is ambiguous: as any object it is {picks[0]}, as a block '
                        f'(a cube or a box) {"another" if len(picks) > 1 else "not one"}; name the one you mean')
