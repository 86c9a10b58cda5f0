"""Places and measures among the scene's objects: what "nearest", "leftmost", "the biggest" and "left of B"
compare, and when two objects tie (a refusal beats a wrong block).

Pure functions of the scene's objects; resolving the words that name a reference object is
language/references.py's, which calls these.
"""

from __future__ import annotations

import math

import numpy as np

from ..core.scene import COLORS, SceneObject
from ..errors import LanguageError, UnknownObjectError
from .proportions import outline_sides
from .reference_words import (
    COLOR_SYNONYMS,
    COMPARATIVE_OF,
    CORNERS,
    DETERMINERS,
    DIRECTIONS,
    FARTHEST,
    FARTHEST_FROM,
    NEAREST,
    NOUNS,
    PERIPHRASTIC,
    PLACE_ADJECTIVES,
    SIZE_SUPERLATIVES,
    TIE,
    TIE_DISTANCE,
    TIE_DISTANCE_M,
    TIE_M,
    TIE_PLACE,
    TIE_PLACE_M,
)
from .synonyms import BIG, MEDIUM, SMALL, TALL, TIE_SIZE


def named_colours(low) -> set[str]:
    """The colours ``low`` (lower-case words) name, synonyms resolved ("grey" is gray)."""
    return {c for w in low if (c := COLOR_SYNONYMS.get(w, w)) in COLORS}


def measure(o: SceneObject, what: str) -> float:
    """A length in metres: the footprint's side (its area's square root), the long side of the footprint's
    smallest enclosing rectangle, the height, the longest extent (the length of a lying bar, the height of a standing
    bottle), y (leftness) or x (how far back from the robot)."""
    if what == "area":
        return float(o.size)
    if what == "length":
        return outline_sides(o)[0]
    if what == "height":
        return float(o.geometry.height)
    if what == "extent":
        return max(outline_sides(o)[0], float(o.geometry.height))
    if what in ("x", "y"):
        return float(o.xy[0] if what == "x" else o.xy[1])
    return toward(o, what.split("-"))


def toward(o: SceneObject, sides: list[str]) -> float:
    """How far the object's centre lies toward the sides said (metres along their direction from the table's
    centre): "left" is +y, "front" -x; toward a corner ("back", "right") as far as toward the nearer of its two sides,
    as people see it: the thing in the front left is in front and on the left, not the one far to the left that
    stands halfway back."""
    return min(float(np.dot(o.xy[:2], DIRECTIONS[s])) for s in sides)


def distance_to(o: SceneObject, xy: tuple[float, float]) -> float:
    """Centre to ``xy`` in metres: what "nearest" and "farthest" compare."""
    return float(np.hypot(o.xy[0] - xy[0], o.xy[1] - xy[1]))


def bearing_off(v: np.ndarray, direction: float) -> float:
    """The angle between ``v`` and the scene direction ``direction`` (radians from +x: the robot's left is pi/2)."""
    ang = math.atan2(float(v[1]), float(v[0]))
    return abs(math.remainder(ang - direction, 2 * math.pi))


def relation_head(low: tuple[str, ...]) -> tuple[str, int, int] | None:
    """(the relation's word, where its phrase starts, where its reference starts) or None."""
    for i, w in enumerate(low):
        if w in SIZE_SUPERLATIVES:
            return w, i, i + 1
        if w in NEAREST | FARTHEST:
            j = i + 1
            if j < len(low) and low[j] in NOUNS:  # "the closest block to the duck"
                j += 1
            if w in FARTHEST and " ".join(low[j:j + 2]) in FARTHEST_FROM:
                j += 1  # "the block farthest away from the robot": farthest from it
            if j < len(low) and low[j] in ("to", "from"):
                j += 1
            return w, i, j
        if w in ("left", "right") and i + 1 < len(low) and low[i + 1] == "of":
            start = i
            while start > 0 and low[start - 1] in ("to", "on", "the"):
                start -= 1
            return _direct(low, f"{w} of", start, i + 2)
        if w == "behind" and i > 0:
            return _direct(low, w, i, i + 1)
        if low[i:i + 2] == ("next", "to") and i > 0 and not low[i - 1][:1].isdigit():
            return "nearest", i, i + 2  # "the piece next to the boot": the nearest, as ties are told ("the white one,
            # number 2, next to 6" is a command whose mover is said twice)
        if low[i:i + 3] == ("in", "front", "of") and i > 0:
            return _direct(low, "in front of", i, i + 3)
    return None


DIRECTLY = frozenset({"directly", "straight", "right", "just", "exactly", "immediately"})
"""Words before a side relation that narrow it: "the object directly behind B" lies on B's line to the back."""


def _direct(low: tuple[str, ...], kind: str, start: int, end: int) -> tuple[str, int, int]:
    """(``kind``, start, end), or ("directly " + kind, start - 1, end) where a word of :data:`DIRECTLY` precedes."""
    if start > 1 and low[start - 1] in DIRECTLY:
        return f"directly {kind}", start - 1, end
    return kind, start, end


def bulk_superlative(pool: list[SceneObject], pick, word: str) -> str:
    """"The biggest / smallest": the object whose bulk (the volume of the box around it: its footprint's
    rectangle times its height) is the extreme, where no other's is within :data:`TIE_SIZE` of it
    (:func:`seen_size`). A long flat bar and a tall thin can are judged by the space they take, as people judged
    them (a duck wider than a tall cylinder is the bigger; a cylinder, a teddy and a cube within a fifth of each
    other are a tie)."""
    if not pool:
        raise UnknownObjectError(f'no object in the scene is the "{word}" one')
    tied = [o.name for o in outlined(size_tied(pool, seen_size(pool), pick, seen_tie(pool)), pick)]
    if len(tied) > 1:
        raise LanguageError(f'"{word}" is ambiguous: {", ".join(tied)} are all but equally so; name the one you mean')
    return tied[0]


def size_tied(pool: list[SceneObject], size, pick, tie: float = TIE_SIZE) -> list[SceneObject]:
    """The objects of ``pool`` whose ``size`` is within ``tie`` (a fraction) of the extreme ``pick`` (min or max)
    chooses: sizes a person does not tell apart at a glance."""
    values = {o.name: size(o) for o in pool}
    best = pick(values.values())
    return [o for o in pool if _alike(values[o.name], best, tie)]


def outlined(tied: list[SceneObject], pick) -> list[SceneObject]:
    """Objects of one shape tied by their side, told apart by their outline seen from above: the one that ``pick``
    (max or min) makes the extreme in both its longest side and its footprint's side (the root of its area), clearly
    apart from each other in one of them ("the bigger spanner": 18 against 15 cm long, as flat as the other; a 4x4
    plate beside a 1x4 brick of its length); where the outlines are alike, by their height ("the big lens": 7 cm
    tall against 5, as wide as the other); ``tied`` itself where neither tells them apart or the outline says
    otherwise than the bulk."""
    if len(tied) < 2 or len({o.shape for o in tied}) > 1:
        return tied
    seen = {o.name: (max(outline_sides(o)), (outline_sides(o)[0] * outline_sides(o)[1]) ** 0.5) for o in tied}
    best = pick(tied, key=lambda o: (seen[o.name][0], seen[o.name][1]))
    for o in tied:
        if o is best:
            continue
        for b, v in zip(seen[best.name], seen[o.name], strict=True):
            if pick(b, v) != b and not _alike(b, v, TIE_SIDE):
                return tied  # the outline says the other way: a tie stays a tie
        if all(_alike(b, v, TIE_SIDE) for b, v in zip(seen[best.name], seen[o.name], strict=True)):
            return _by_height(tied, pick, seen)
    return [best]


def _by_height(tied: list[SceneObject], pick, seen: dict[str, tuple[float, float]]) -> list[SceneObject]:
    """Objects whose outlines (``seen``) are alike told apart by their height: the one ``pick`` makes the extreme,
    clearly apart from every other (:data:`TIE_SIDE`) and not the other way in its outline (a wider, lower shaker
    beside a tall bottle is a tie); ``tied`` itself otherwise."""
    height = {o.name: float(o.geometry.height) for o in tied}
    best = pick(tied, key=lambda o: height[o.name])
    for o in tied:
        if o is best:
            continue
        if _alike(height[o.name], height[best.name], TIE_SIDE) or any(
                pick(b, v) != b for b, v in zip(seen[best.name], seen[o.name], strict=True)):
            return tied
    return [best]


def _alike(a: float, b: float, tie: float = TIE_SIZE) -> bool:
    """Whether two sizes are closer than ``tie`` of the smaller: a person does not tell them apart."""
    return abs(a - b) < tie * min(a, b)


TIE_SIDE = 0.2
"""Two objects of one shape whose sides differ by less than this fraction of the smaller are a tie for "the biggest",
"the small one": a 3.5 and a 4 cm cube are (an author who compared them said so), a 5.5 cm cube beside two of 4.5 cm
is clearly the biggest (an author said so), as a 4 and a 5 cm cube are told apart."""


def seen_tie(pool: list[SceneObject]) -> float:
    """The tie for what :func:`seen_size` compares among ``pool``: :data:`TIE_SIDE` of a side where the objects are of
    one shape, :data:`TIE_SIZE` of a bulk where they are not."""
    return TIE_SIDE if len({o.shape for o in pool}) == 1 else TIE_SIZE


def seen_size(pool: list[SceneObject]):
    """What "big" and "small" compare among ``pool``: objects of one shape by their side (the bulk's cube root:
    a 3.5 and a 4 cm cube are a tie, as an author who compared them said), objects of different shapes by
    their bulk (a wide duck is bigger than a tall thin cylinder of three quarters its bulk, as two authors
    said; a 3 cm cube is smaller than a 4 cm-wide cylinder)."""
    if len({o.shape for o in pool}) == 1:
        return lambda o: bulk(o) ** (1 / 3)
    return bulk


def bulk(o: SceneObject) -> float:
    """The volume of the box around the object, in cubic metres: how much space it seems to take."""
    long, short = outline_sides(o)
    return long * short * float(o.geometry.height)


def superlative(pool: list[SceneObject], measure, pick, word: str, place: bool = False,
                distance: bool = False) -> str:
    """The one object of ``pool`` that ``pick`` (min or max) of ``measure`` chooses; ties are ambiguous. With
    ``place`` the measure is a place (metres along the table), and a tie is closer than :data:`TIE_PLACE` sides or
    :data:`TIE_PLACE_M`;
    with ``distance`` it is a distance, and a tie is also within :data:`TIE_DISTANCE` of it (and, as for places,
    under :data:`TIE_PLACE_M`)."""
    if not pool:
        raise UnknownObjectError(f'no object in the scene is the "{word}" one')
    values = {o.name: measure(o) for o in pool}
    best = pick(values.values())
    winner = next(o for o in pool if values[o.name] == best)

    def tol(o: SceneObject) -> float:
        t = max(TIE * abs(best), TIE_M)
        if distance:
            t = max(t, TIE_DISTANCE_M + TIE_DISTANCE * abs(best))
        if place or distance:
            t = max(t, TIE_PLACE_M)
        return max(t, TIE_PLACE * min(float(o.size), float(winner.size))) if place or distance else t

    tied = [o.name for o in pool if abs(values[o.name] - best) <= tol(o)]
    if len(tied) > 1:
        raise LanguageError(f'"{word}" is ambiguous: {", ".join(tied)} are all but equally so; name the one you mean')
    return tied[0]


def comparative_of(words: list[str]) -> list[str]:
    """"the larger of the cubes" -> "the largest cube"; other words as they are."""
    low = [w.lower() for w in words]
    if len(low) >= 5 and low[0] == "the" and low[1] in COMPARATIVE_OF and low[2:4] == ["of", "the"] \
            and low[-1].endswith("s"):
        skip = 5 if low[4:5] == ["two"] and len(low) > 5 else 4  # "the larger of the two red cubes"
        return ["the", COMPARATIVE_OF[low[1]], *words[skip:-1], words[-1][:-1]]
    return words


def places_as_superlatives(words: list[str]) -> list[str]:
    """"the front blue cube", "the left one" -> "the frontmost blue cube", "the leftmost one": a place word right
    after the determiner, before the rest of the description (never "the left of", "the back side")."""
    words = _corners_joined(words)
    low = [w.lower() for w in words]
    if len(low) >= 3 and low[0] in DETERMINERS and low[1] in CORNER_WORDS and low[2] not in ("of", "corner"):
        return [words[0], f"{low[1]}most", *words[2:]]  # "the back-right thing": the one farthest that way
    if len(low) >= 2 and low[0] in CORNER_WORDS and low[1] not in ("of", "corner"):
        return ["the", f"{low[0]}most", *words[1:]]
    if len(low) >= 4 and low[0] in DETERMINERS and low[1] == "far" and low[2] in ("left", "right") \
            and low[3] not in ("of", "side", "edge", "end"):  # "the far right one": the rightmost
        return [words[0], f"{low[2]}most", *words[3:]]
    if len(low) >= 3 and low[0] in DETERMINERS and low[1] in PLACE_ADJECTIVES and low[2] not in ("of", "side", "edge"):
        return [words[0], PLACE_ADJECTIVES[low[1]], *words[2:]]
    if len(low) >= 2 and low[0] in PLACE_ADJECTIVES and low[1] not in ("of", "side", "edge", "to", "from") \
            and low[0] not in ("far", "near"):  # "front white cube", typed without its article
        return ["the", PLACE_ADJECTIVES[low[0]], *words[1:]]
    return words


CORNER_WORDS = frozenset(CORNERS.values())


def _corners_joined(words: list[str]) -> list[str]:
    """``words`` with two sides said together as one corner word ("front left", "rear-left", "left front":
    "front-left"), where the pair is said before the noun or ends a place ("at the back right")."""
    out: list[str] = []
    for w in words:
        low = w.lower()
        pair = tuple(low.split("-")) if "-" in low else ((out[-1].lower(), low) if out else None)
        if pair in CORNERS:
            if "-" not in low:
                out.pop()
            out.append(CORNERS[pair])
        else:
            out.append(w)
    return out


LENGTHWISE = frozenset({"short", "shorter"})
"""Size words that measure an object along its length, lying or standing: between an 8 cm and a 12 cm bar lying
down "the short one" is the 8 cm one though it is the taller; of two standing cylinders, the lower. "Low" is height."""


def by_size(text: str, pool: list[SceneObject], sizes: list[str]) -> list[SceneObject]:
    """The objects of ``pool`` the size words keep (big/small by bulk, as "the biggest" compares; tall/low by
    height, short by length: :data:`LENGTHWISE`), each in turn keeping the objects within
    :data:`~l2p_bullet.language.synonyms.TIE_SIZE` of the extreme; with one object the size words are read past. A
    size word that splits the pool into tied objects and the rest is a one-line error naming the tied ones."""
    if len(pool) > 1:
        for word in sizes:
            if word in MEDIUM:
                pool = [_medium(text, pool)]
                continue
            seen = word in BIG | SMALL
            along = "extent" if word in LENGTHWISE else "height"
            size = seen_size(pool) if seen else (lambda o, along=along: measure(o, along))
            pick = max if word in BIG | TALL else min
            tied = size_tied(pool, size, pick, seen_tie(pool) if seen else TIE_SIZE)
            tied = outlined(tied, pick) if seen else tied
            if len(tied) > 1 and len(tied) < len(pool):
                listed = ", ".join(o.name for o in tied)
                raise LanguageError(f'"{text}" is ambiguous: {listed} are all but equally {word}; '
                                    "name the one you mean")
            pool = tied
    return pool


def _medium(text: str, pool: list[SceneObject]) -> SceneObject:
    """"The medium-sized cube": the middle one of three by bulk, each clearly apart from the other two."""
    if len(pool) != 3:
        listed = ", ".join(o.name for o in pool)
        raise LanguageError(f'"{text}" is ambiguous: "medium" picks the middle of three, and it fits {listed}; '
                            "name the one you mean")
    small, middle, big = sorted(pool, key=bulk)
    for a, b in ((small, middle), (middle, big)):
        if _alike(bulk(a), bulk(b)):
            raise LanguageError(f'"{text}" is ambiguous: {a.name} and {b.name} are all but equally big; '
                                "name the one you mean")
    return middle


def one_word_comparisons(words: list[str]) -> list[str]:
    """"most far" as "farthest", "more close" as "closer": :data:`PERIPHRASTIC`."""
    out: list[str] = []
    for w in words:
        pair = (out[-1].lower(), w.lower()) if out else None
        if pair in PERIPHRASTIC:
            out[-1] = PERIPHRASTIC[pair]
        else:
            out.append(w)
    return out


RANKS = {"second": 2, "2nd": 2, "third": 3, "3rd": 3}
"""Ordinals before a superlative ("the second tallest"): the one after that many others, each clearly so."""


def ranked(rank: int, choose):
    """``choose`` (one object of a pool, ties refused) made to pick the ``rank``-th: the first ``rank`` - 1 picks are
    taken out, each of them as clearly first as a superlative's one must be."""
    def pick(pool: list[SceneObject]) -> str:
        for _ in range(rank - 1):
            first = choose(pool)
            pool = [o for o in pool if o.name != first]
        return choose(pool)
    return pick
