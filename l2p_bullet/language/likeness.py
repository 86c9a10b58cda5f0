"""What a description says an object looks like, said as the words the other readers know: a thing's colour ("the
lemon coloured cube": the yellow cube), a kind named with "-looking" or "-like" ("the duck-like one": the duck), an
apple's variety ("the Granny Smith": the green apple). The words are read before the description itself
(language/references.py)."""

from __future__ import annotations

from ..core.scene import Scene
from .naming import name_words
from .shape_words import SHAPE_NOUNS


def looks(words: list[str], scene: Scene) -> list[str]:
    """"the football-looking thing", "the duck-like one": the kind or shape named before the suffix."""
    if not any("-" in w for w in words):
        return list(words)
    nouns = set(SHAPE_NOUNS) | set(name_words(scene))
    out = []
    for w in words:
        stem, _, suffix = w.lower().rpartition("-")
        out.append(stem if suffix in ("looking", "like", "shaped") and stem in nouns else w)
    return out


THING_COLOURS = {"lemon": "yellow", "banana": "yellow", "sunflower": "yellow", "butter": "yellow", "grass": "green",
                 "leaf": "green", "lime": "green", "sky": "blue", "ocean": "blue", "tomato": "red", "cherry": "red",
                 "strawberry": "red", "blood": "red", "snow": "white", "coal": "black", "chocolate": "brown"}
"""Things whose colour names a colour ("the lemon coloured cube", "the grass-colored one"): that colour."""
_COLOURED = ("coloured", "colored", "colour", "color")


VARIETIES = {("granny", "smith"): "green", ("golden", "delicious"): "yellow", ("red", "delicious"): "red",
             ("bramley",): "green", ("gala",): "red", ("fuji",): "red", ("honeycrisp",): "red"}
"""Apples by variety, each of one colour ("the Granny Smith": the green apple)."""


_VARIETY_WORDS = frozenset(variety[0] for variety in VARIETIES)


def coloured_like(words: list[str]) -> list[str]:
    """"the lemon coloured cube", "the banana-colored one" -> "the yellow cube", "the yellow one"; "the Granny Smith
    (apple)" -> "the green apple"."""
    words = _varieties(words)
    out: list[str] = []
    for w in words:
        low = w.lower()
        thing, _, suffix = low.rpartition("-")
        if thing in THING_COLOURS and suffix in _COLOURED:
            out.append(THING_COLOURS[thing])
        elif low in _COLOURED and out and out[-1].lower() in THING_COLOURS:
            out[-1] = THING_COLOURS[out[-1].lower()]
        else:
            out.append(w)
    return out


def _varieties(words: list[str]) -> list[str]:
    """``words`` with an apple's variety said as its colour and "apple" (:data:`VARIETIES`)."""
    low = [w.lower() for w in words]
    if not _VARIETY_WORDS.intersection(low):
        return words
    for variety, colour in VARIETIES.items():
        for i in range(len(low) - len(variety) + 1):
            if tuple(low[i:i + len(variety)]) == variety:
                apple = [] if low[i + len(variety):i + len(variety) + 1] in (["apple"], ["apples"]) else ["apple"]
                return [*words[:i], colour, *apple, *words[i + len(variety):]]
    return words
