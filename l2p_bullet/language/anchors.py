"""What the words after the preposition mean in the light of the words before it: "Push the small brown cube toward
the big one" (its twin), "Move the smallest cube toward the largest one" (the largest cube), "Move the green cube next
to the red cube closest to it" and "move the object nearest the cylinder away from it" (what "it" points at in a first
clause). The grammar (grammar.py) reads the reference with them; kept apart so that each reading is one function.
"""

from __future__ import annotations

from ..core.scene import Scene
from .pronouns import Context, sized_twin
from .reference_words import SIZE_SUPERLATIVES
from .references import measured_from
from .synonyms import SIZE_WORDS
from .words import drop_frames


def twin_of(after: list[str], mover: str, before: list[str], scene: Scene) -> str | None:
    """"Push the small brown cube toward the big one": "the big one" after a mover described by its size is its twin
    of that colour and shape the size word picks (language/pronouns.py: sized_twin); None where not said so."""
    low = tuple(w.lower().strip(".,!?") for w in after)
    if mover in before or not set(w.lower() for w in before) & SIZE_WORDS:
        return None
    return sized_twin(" ".join(after), low, Context(mover, described=True), scene)


SHAPE_ONES = {"cube": "cube", "cubes": "cube", "block": "block", "blocks": "block", "box": "box", "boxes": "box",
              "cylinder": "cylinder", "cylinders": "cylinder"}


def noun_carried(after: list[str], before: list[str]) -> list[str]:
    """"Move the smallest cube toward the largest one": "one" after a size said again stands for the noun of the
    mover's description (the largest cube, not the largest object); ``after`` itself where not said so."""
    low = [w.lower().strip(".,!?") for w in after]
    if len(low) != 3 or low[0] != "the" or low[2] != "one" or not (low[1] in SIZE_WORDS or low[1] in SIZE_SUPERLATIVES):
        return after
    noun = next((SHAPE_ONES[w.lower()] for w in reversed(before) if w.lower() in SHAPE_ONES), None)
    return after if noun is None else [*after[:2], noun]


def mover_in_relation(after: list[str], mover: str) -> Context | None:
    """What "it" means inside the reference's own description in a first clause ("Move the green cube next to the red
    cube closest to it"): the block being moved; None where the reference is "it" alone (nothing to point back to)."""
    low = [w.lower().strip(".,!?") for w in after]
    return Context(mover) if len(low) > 2 and low[-1] == "it" else None


def measured_context(before: list[str], scene: Scene) -> Context | None:
    """What "it" after the preposition means in a first clause: the object the mover's description measures
    from ("move the object nearest the cylinder away from it": the cylinder), or nothing."""
    source = measured_from(" ".join(drop_frames(before)), scene)
    return Context(source) if source is not None else None
