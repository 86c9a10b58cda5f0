"""An object said by its place in a group or on the table: "the middle red block", "the second red one from the
left", "the object closest to the front edge", "the one in the middle of everything".

:func:`table_sides` rewrites the ways of saying a side of the table into the places language/references.py reads
already ("at the back of the table", "nearest the front edge": at the back, at the front; "the cube red of the
right": on the right); :func:`in_group` picks the object a place in a group names, or refuses with the candidates
where the place is not clear (a tie under a place tie, a group not in a line, an even group's middle, an ordinal
counted from no end said that names different objects from the two ends).
"""

from __future__ import annotations

import re
from collections.abc import Callable

import numpy as np

from ..core.scene import Scene, SceneObject
from ..errors import LanguageError, UnknownObjectError
from .descriptions import candidates
from .numbers import number_of
from .places import distance_to, superlative
from .pools import either_reading
from .reference_words import (
    DETERMINERS,
    DIRECTIONS,
    EDGE_WORDS,
    FARTHEST,
    GROUP_CENTRE_WORDS,
    IN_A_LINE,
    LINE_WORDS,
    MIDDLE_WORDS,
    NEAREST,
    ORDINALS,
    ROBOT_WORDS,
    SIDE_SUPERLATIVE,
    SIZE_SUPERLATIVES,
    TABLE_WORDS,
    TIE_PLACE,
    TIE_PLACE_M,
    VIEWPOINTS,
)

GENERIC = frozenset({"one", "object", "thing", "piece", "item", "ones", "objects", "things", "items", "pieces", "bit",
                     "stuff", "thingy"})
"""Nouns that name any object: a group said with only these is every object on the table."""
COORDINATE_PICKS = {"largest": max, "biggest": max, "greatest": max, "highest": max, "maximum": max, "max": max,
                    "smallest": min, "lowest": min, "least": min, "minimum": min, "min": min}
"""Superlatives of a coordinate ("the object with the largest y"): x is away from the robot, y its left."""


OPPOSITE = {"leftmost": "rightmost", "rightmost": "leftmost", "frontmost": "backmost", "backmost": "frontmost"}
SIDE_SAID = {"leftmost": ("on", "the", "left"), "rightmost": ("on", "the", "right"),
             "frontmost": ("at", "the", "front"), "backmost": ("at", "the", "back")}
"""A side of the table as the place phrase language/references.py reads (reference_words.SIDE_PHRASES)."""


def table_sides(words: list[str]) -> list[str]:
    """``words`` with a side of the table said as an edge, an end or a part of the table, as the place it is
    ("the cube at the back of the table": at the back; "the object closest to the front edge": at the front),
    a Portuguese speaker's "of the right" / "of the middle" as "on the right" / the middle one, and a coordinate
    superlative as the place superlative ("with the largest y": leftmost)."""
    low = [w.lower() for w in words]
    for view in VIEWPOINTS:  # "furthest to the right, as the robot sees it": every side is the robot's
        if len(low) > len(view) + 2 and tuple(low[-len(view):]) == view:
            return table_sides([*words[:-len(view) - 1], words[-len(view) - 1].rstrip(",")])
    if "robot's" in low[1:-1] and low[low.index("robot's", 1) + 1] in ("left", "right"):  # "on the robot's left"
        return table_sides([w for i, w in enumerate(words) if i != low.index("robot's", 1)])
    if len(low) >= 3 and low[-3:-1] == ["of", "the"] and low[-1] in TABLE_WORDS and low[-4:-3] \
            and (low[-4] in DIRECTIONS or low[-4] in EDGE_WORDS):  # "at the back of the table"
        return table_sides(words[:-3])
    if len(low) >= 3 and low[-2] in DIRECTIONS and low[-1] in EDGE_WORDS - {"end", "side"} and low[-3] == "the":
        return table_sides(words[:-1])  # "at the front edge", "nearest the left border": the side
    for i, w in enumerate(low):
        if w not in NEAREST | FARTHEST or i == 0:
            continue
        joined = low[i + 1:i + 2]
        if w in FARTHEST and joined != ["from"] or w in NEAREST and joined == ["from"]:
            continue  # "the cube furthest to the right" is the rightmost (reference_words.SIDE_PHRASES)
        j = i + 1 + (joined in (["to"], ["from"]))
        side = low[j + 1:j + 2] if low[j:j + 1] == ["the"] else []
        rest = low[j + 2:]
        if side and side[0] in DIRECTIONS and all(r in EDGE_WORDS for r in rest) and len(rest) <= 1:
            place = SIDE_SUPERLATIVE[side[0]] if w in NEAREST else OPPOSITE[SIDE_SUPERLATIVE[side[0]]]
            return [*words[:i], *SIDE_SAID[place]]  # "the white object nearest the front": at the front
    corner = _two_sides(low)
    if corner is not None:  # "the block at the back on the right": at the back-right corner
        return [*words[:-corner[0]], "at", "the", corner[1]]
    if len(low) >= 4 and low[-3:-1] == ["of", "the"] and low[-1] in ("left", "right"):
        return [*words[:-3], "on", "the", words[-1]]  # "the cube red of the right"
    if len(low) >= 3 and low[-2:] == ["in", "front"]:
        return [*words[:-2], "at", "the", "front"]  # "the green cube in front": the one at the front
    if len(low) >= 2 and low[-1] in ("behind", "in-back") and low[-2] not in ("is", "are", "stands", "sits"):
        return [*words[:-1], "at", "the", "back"]  # "the green cube behind": the one at the back
    if len(low) >= 4 and low[-3:] == ["of", "the", "middle"] and low[0] in DETERMINERS:
        return [words[0], "middle", *words[1:-3]]  # "the red cube of the middle": the middle red cube
    if len(low) >= 6 and low[-6:-2] == ["in", "the", "middle", "of"] and low[-2] in DETERMINERS \
            and low[-1] in LINE_WORDS and low[0] in DETERMINERS:
        return [words[0], "middle", *words[1:-6]]  # "the cube in the middle of the row"
    if len(low) >= 5 and low[-4:-1] == ["with", "the", low[-2]] and low[-2] in COORDINATE_PICKS \
            and low[-1] in ("x", "y"):
        pick = COORDINATE_PICKS[low[-2]]
        word = next(k for k, (what, p) in SIZE_SUPERLATIVES.items() if what == low[-1] and p is pick)
        start = 1 if low[0] in DETERMINERS else 0
        return ["the", word, *words[start:-4]]
    return words


DEPTH_SAID = {("at", "the", "back"): "back", ("in", "the", "back"): "back", ("at", "the", "rear"): "back",
              ("at", "the", "front"): "front", ("in", "the", "front"): "front", ("in", "front"): "front"}
SIDE_SAID_AS = {("on", "the", "left"): "left", ("on", "the", "right"): "right", ("to", "the", "left"): "left",
                ("to", "the", "right"): "right", ("on", "the", "left", "side"): "left",
                ("on", "the", "right", "side"): "right", ("on", "left", "side"): "left",
                ("on", "right", "side"): "right"}
"""A depth and a side of the table said one after the other ("at the back on the right (side)", "on the left in
front"): together a corner, where either alone would leave the other out."""


def _two_sides(low: list[str]) -> tuple[int, str] | None:
    """(how many words, the corner) where ``low`` ends with a depth and a side of the table, in either order."""
    for first, second in ((DEPTH_SAID, SIDE_SAID_AS), (SIDE_SAID_AS, DEPTH_SAID)):
        for b, second_word in second.items():
            if tuple(low[len(low) - len(b):]) != b:
                continue
            rest = low[:len(low) - len(b)]
            for a, first_word in first.items():
                if len(rest) > len(a) and tuple(rest[len(rest) - len(a):]) == a:
                    depth, side = (first_word, second_word) if first is DEPTH_SAID else (second_word, first_word)
                    return len(a) + len(b), f"{depth}-{side}"
    return None


def in_group(words: list[str], low: tuple[str, ...], scene: Scene, read: Callable[[str, Scene], str]) -> str | None:
    """The object a place in a group names ("middle red block", "second red one from the left", "one in the middle
    of everything"; ``words`` without their determiner), or None where ``words`` name no such place. ``read`` resolves
    a description among some of the objects (language/references.py's reader, passed in: it calls this module)."""
    centre = _centre_of_everything(low)
    if centre is not None:
        return _nearest_centre(words[:centre], scene)
    if low and low[0] in MIDDLE_WORDS and len(low) > 1:
        return _among(words[1:], scene, lambda pool: _middle(pool, " ".join(words)))
    ordinal = _ordinal(low)
    if ordinal is not None:
        n, at, end = ordinal
        counted = _counted_from([*words[:at], *words[end:]])
        if counted is None or at > 0 and counted[1] is None:
            return None  # "one second from the left" is counted; "A first" is not an ordinal of a group
        return _among(counted[0], scene, lambda pool: _nth(pool, n, counted[1], " ".join(words)))
    return _half(words, low, scene, read)


def _ordinal(low: tuple[str, ...]) -> tuple[int, int, int] | None:
    """(the place counted: 2 for "second", -2 for "second to last"; where its words start; where they end) in
    "second red one", "second-to-last one", "the block third from the right"; None where ``low`` holds none."""
    for at, w in enumerate(low[:3]):
        joined = "-" in w
        parts = tuple(w.split("-")) if joined else low[at:at + 3]
        if parts[0] in ORDINALS and ORDINALS[parts[0]] > 0:
            for tail in (("to", "last"), ("last",)):  # "second to last", "second-last"
                if parts[1:1 + len(tail)] == tail:
                    return -ORDINALS[parts[0]], at, at + (1 if joined else 1 + len(tail))
        if w in ORDINALS and len(low) > at + 1 and (at == 0 or low[at + 1] == "from"):
            return ORDINALS[w], at, at + 1
    return None


def _centre_of_everything(low: tuple[str, ...]) -> int | None:
    """Where "in the middle of everything" / "of all the junk" / "of them all" starts in ``low``, or None."""
    for i in range(1, len(low) - 4):
        if low[i:i + 4] == ("in", "the", "middle", "of") or low[i:i + 4] == ("in", "the", "center", "of") \
                or low[i:i + 4] == ("in", "the", "centre", "of"):
            rest = low[i + 4:]
            if rest and all(w in GROUP_CENTRE_WORDS for w in rest) and rest != ("the",):
                return i
    return None


def _nearest_centre(words: list[str], scene: Scene) -> str:
    """The object of those ``words`` describe nearest the centre of all the objects on the table."""
    centre = tuple(np.mean([o.xy[:2] for o in scene.objects], axis=0))
    return _among(words, scene, lambda pool: superlative(pool, lambda o: distance_to(o, centre), min,
                                                          "in the middle of everything", distance=True))


def _counted_from(words: list[str]) -> tuple[list[str], str | None] | None:
    """(the description, the side counted from) of "red one from the left", "cube counting from the front"; the
    side None where none is said; None where "from" says something else."""
    low = [w.lower() for w in words]
    for i in range(len(low)):
        if low[i] != "from":
            continue
        rest = low[i + 1:]
        rest = rest[1:] if rest[:1] == ["the"] else rest
        if rest and rest[0] in DIRECTIONS and all(r in EDGE_WORDS for r in rest[1:]) and len(rest) <= 2:
            end = i - 1 if i > 0 and low[i - 1] in ("counting", "counted", "starting") else i
            return words[:end], rest[0]
        return None
    return words, None


def _among(described: list[str], scene: Scene, choose) -> str | None:
    """``choose`` over the objects ``described`` fits (every object where it says only "one", "thing"), both ways
    where it says "block" (language/pools.either_reading); None where ``described`` is no plain description
    ("one of the three red blocks": the reader of a group said after "of" takes it)."""
    said = [w for w in described if w.lower() not in DETERMINERS]
    if all(w.lower() in GENERIC for w in said):
        pool = list(scene.objects)
    else:
        try:
            pool = candidates(" ".join(said), said, tuple(w.lower() for w in said), scene)
        except (LanguageError, UnknownObjectError):
            return None
    return either_reading(described, scene, choose, pool)


def _tie(a: SceneObject, b: SceneObject) -> float:
    """Two places closer than this are a tie (language/places.superlative's place tie)."""
    return max(TIE_PLACE_M, TIE_PLACE * min(float(a.size), float(b.size)))


def _line(pool: list[SceneObject], said: str, why: str) -> tuple[list[SceneObject], np.ndarray]:
    """The group in its order along the line it stands in, and the line's direction; refused where it stands in
    no line (a triangle, a cluster)."""
    xy = np.array([o.xy[:2] for o in pool], float)
    centred = xy - xy.mean(axis=0)
    axis = np.linalg.svd(centred)[2][0]
    along = centred @ axis
    off = np.abs(centred @ np.array([-axis[1], axis[0]]))
    span = float(along.max() - along.min())
    if float(off.max()) > max(TIE_PLACE_M, IN_A_LINE * span):
        listed = ", ".join(o.name for o in pool)
        raise LanguageError(f'"{said}" is ambiguous: {listed} stand in no line, so {why}; name the one you mean')
    order = np.argsort(along)
    return [pool[k] for k in order], axis


def _clear(ordered: list[SceneObject], k: int, along, said: str) -> SceneObject:
    """The ``k``-th of ``ordered``, refused where a neighbour's place ties with its own."""
    pick = ordered[k]
    tied = [o for o in ordered[max(k - 1, 0):k + 2]
            if o is not pick and abs(along(o) - along(pick)) < _tie(o, pick)]
    if tied:
        listed = ", ".join(o.name for o in [pick, *tied])
        raise LanguageError(f'"{said}" is ambiguous: {listed} stand all but side by side; name the one you mean')
    return pick


def _middle(pool: list[SceneObject], said: str) -> str:
    """The middle one of an odd group of three or more in a line: as many of the others on either side of it."""
    if not pool:
        raise UnknownObjectError(f'no object in the scene is the "{said}"')
    if len(pool) < 3 or len(pool) % 2 == 0:
        listed = ", ".join(o.name for o in pool)
        raise LanguageError(f'"{said}" is ambiguous: "middle" picks the one between the others of an odd group, '
                            f"and it fits {listed}; name the one you mean")
    ordered, axis = _line(pool, said, "none is between the others")
    return _clear(ordered, len(ordered) // 2, lambda o: float(np.dot(o.xy[:2], axis)), said).name


def _nth(pool: list[SceneObject], n: int, side: str | None, said: str) -> str:
    """The ``n``-th of the group counted from ``side`` (``n`` -1: the last). Counted from no side said, the group
    must stand in a line and the place name one object counted from either end (the second of three: the middle
    one); else the reading depends on where the speaker stands, and is asked."""
    k = n - 1 if n > 0 else len(pool) + n
    if not 0 <= k < len(pool):
        raise UnknownObjectError(f'"{said}": only {len(pool)} such objects are on the table '
                                 f'({", ".join(o.name for o in pool) or "none"})')
    if side is not None:
        u = np.asarray(DIRECTIONS[side])
        ordered = sorted(pool, key=lambda o: -float(np.dot(o.xy[:2], u)))
        return _clear(ordered, k, lambda o: float(np.dot(o.xy[:2], u)), said).name
    ordered, axis = _line(pool, said, "they have no order without a side to count from")
    along = lambda o: float(np.dot(o.xy[:2], axis))  # noqa: E731
    one, other = _clear(ordered, k, along, said), _clear(ordered[::-1], k, along, said)
    if one is not other:
        ends = ("left", "right") if abs(axis[1]) >= abs(axis[0]) else ("front", "back")
        a, b = (one, other) if np.dot(one.xy[:2], DIRECTIONS[ends[0]]) > np.dot(other.xy[:2],
                                                                              DIRECTIONS[ends[0]]) else (other, one)
        raise LanguageError(f'"{said}" is ambiguous: counted from the {ends[0]} it is {a.name}, from the {ends[1]} '
                            f"{b.name}; say from which end")
    return one.name


def _half(words: list[str], low: tuple[str, ...], scene: Scene, read: Callable[[str, Scene], str]) -> str | None:
    """"The thing nearest the robot on the right side": the robot is on no side, so the side is the half of the
    table the object is in; refused where an object within a place tie of the table's centre line changes the
    pick. None where ``words`` are not so said."""
    n = 4 if low[-1:] in (("side",), ("half",)) else 3
    if len(low) <= n or low[-n:-n + 2] != ("on", "the") or low[-n + 2] not in ("left", "right"):
        return None
    head = low[:-n]
    at = next((i for i, w in enumerate(head) if w in NEAREST | FARTHEST), None)
    if at is None:
        return None
    ref = head[at + 1:]
    if ref[:1] in (("to",), ("from",)):
        ref = ref[1:]
    if ref not in ROBOT_WORDS:
        return None
    sign = DIRECTIONS[low[-n + 2]][1]
    picks = []
    for margin in (TIE_PLACE_M, -TIE_PLACE_M):  # the objects clearly on that side, then those not clearly off it
        half = [o.name for o in scene.objects if sign * float(o.xy[1]) > margin]
        if not half:
            raise UnknownObjectError(f'nothing in the scene is on the {low[-n + 2]} side of the table')
        picks.append(read(" ".join(words[:-n]), scene.only(half)))
    if picks[0] != picks[1]:
        raise LanguageError(f'"{" ".join(words)}" is ambiguous: {picks[0]} or {picks[1]} (near the table\'s centre '
                            "line); name the one you mean")
    return picks[0]


PLACED_GROUP = re.compile(r"^\s*(?:the|those|these)\s+(?P<count>two|three|four|[2-4])\s+(?P<noun>[a-z]+s\s+)?"
                          r"(?:(?:in|at|on)\s+(?:the\s+)?)?(?P<side>front|back|rear|left|right)(?:\s+side)?\s*$",
                          re.IGNORECASE)
"""A group said by how many and where ("the two in front", "the three cubes on the left", "those two at the back")."""


def placed_group(text: str, scene: Scene) -> tuple[str, ...] | None:
    """The objects a :data:`PLACED_GROUP` names: the ``count`` farthest toward that side (of the noun's kind, where one
    is said), in the scene's order; None where ``text`` is no such group or the next object stands within a place tie
    of the last one counted (which two are "the two in front" is then unclear)."""
    m = PLACED_GROUP.match(text)
    if m is None:
        return None
    pool = list(scene.objects)
    if m.group("noun") and m.group("noun").strip().lower() not in ("ones", "things", "objects", "items", "pieces"):
        noun = m.group("noun").strip().lower()
        singular = noun[:-2] if noun.endswith(("xes", "ches")) else noun[:-1]
        try:
            pool = candidates(singular, [singular], (singular,), scene)
        except (LanguageError, UnknownObjectError):
            return None
    n = number_of(m.group("count"))
    if len(pool) <= n:
        return None
    toward = np.array(DIRECTIONS[m.group("side").lower()])
    along = sorted(pool, key=lambda o: -float(np.dot(o.xy, toward)))
    last, nxt = (float(np.dot(o.xy, toward)) for o in along[n - 1:n + 1])
    if last - nxt < max(TIE_PLACE_M, TIE_PLACE * min(float(along[n - 1].size), float(along[n].size))):
        return None
    chosen = {o.name for o in along[:n]}
    return tuple(o.name for o in scene.objects if o.name in chosen)
