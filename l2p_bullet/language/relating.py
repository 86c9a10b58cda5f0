"""The words before a relation ("the spanner by the hammer", "the red one nearest A"): whether they are one
description the relation picks among, and what "by" or "beside" says of the one object they name alone.

Read by references.py's relations; ``try_object`` is how a description is read there (references.try_object, handed
in, as the other readers of parts of a description are handed the resolver).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..core.scene import COLORS, Scene
from .naming import name_words
from .pronouns import Context
from .reference_words import (
    COLOR_SYNONYMS,
    DETERMINERS,
    NOUNS,
    PLACE_ADJECTIVES,
    REFERENCE_WORDS,
    SHAPE_ADJECTIVES,
    SOFT_ADJECTIVES,
)
from .shape_words import SHAPE_NOUNS
from .synonyms import LOOSE_NOUNS, kind_groups

Reader = Callable[..., "str | None"]
"""references.try_object: (text, scene[, context]) -> the one object named, or None."""


def beside_as_said(before: list[str], after: list[str], scene: Scene, context: Context | None,
                   try_object: Reader) -> str | None:
    """The one object ``before`` names alone where it is also the object nearest the one ``after`` names ("the white
    one next to the lamp": the cup, the lamp's nearest): a relation that only says more of it. None where it is not
    the nearest (the words contradict), or ``before`` or ``after`` name no one object."""
    said = try_object(_said_alone(before), scene) if before else None
    ref = try_object(" ".join(after), scene, context) if after else None
    if said is None or ref is None or said == ref:
        return None
    at = scene.get(ref).xy
    others = [o for o in scene.objects if o.name != ref]
    nearest = min(others, key=lambda o: float(np.hypot(*np.subtract(o.xy, at))))
    return said if nearest.name == said else None


def picks_among(before: list[str], scene: Scene, try_object: Reader) -> bool:
    """Whether the words before "by" or "beside" are one description that leaves several objects, so that the
    relation picks among them ("the spanner by the hammer"); not where no words come before ("closer by the white
    brick"), where two names do ("the théière, cuillère beside the tasse") or where they name one object alone ("the
    duck right beside A"): there the words are the clause's own preposition."""
    names = {n.lower() for n in scene.names}
    if not before or len({w.lower() for w in before} & names) > 1:
        return False
    return try_object(_said_alone(before), scene) is None


def _said_alone(before: list[str]) -> str:
    """The words before a relation without the ones that only say how near ("the duck right beside A")."""
    return " ".join(w for w in before if w.lower() not in ("right", "just", "directly"))


def describes(low: tuple[str, ...], scene: Scene) -> bool:
    """Whether every word before a relation is one a description is made of (a determiner, noun, colour, shape,
    size, kind or name, or a kind several objects share): a word of another kind ("mv", "move", "of the two ... move
    the one") means the words are not one description, and the relation is not read."""
    names = name_words(scene)
    groups = kind_groups(scene)  # "the shaker nearest the cup": a kind two objects share names neither alone
    return all(w in DESCRIBING or w in names or w in groups for w in low)


DESCRIBING = (DETERMINERS | NOUNS | frozenset(COLORS) | frozenset(COLOR_SYNONYMS) | frozenset(SHAPE_NOUNS)
              | frozenset(SHAPE_ADJECTIVES) | SOFT_ADJECTIVES | REFERENCE_WORDS | frozenset(PLACE_ADJECTIVES)
              | LOOSE_NOUNS
              | frozenset({"objects", "things", "items", "pieces", "ones", "cubes", "which", "that", "is", "of", "and",
                           "sitting", "standing", "lying", "located", "placed", "resting", "positioned", "kept",
                           "directly", "right", "just"}))
"""The words a description before a relation is made of, besides the scene's own names (:func:`describes`)."""
