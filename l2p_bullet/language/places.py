"""Objects named by where they are: superlatives ("the biggest one", "the leftmost block", "the block nearest
the robot"), relations to another object or the robot ("the one left of B", "the cube behind the blue one"),
and places on the table ("the cube in the middle", "the object on the far right", "the cube between A and C").

Every reading chooses among the objects the rest of the description allows, and a tie is ambiguous: places
that differ by under :data:`TIE_PLACE` of a side are a tie (people saw 1-1.7 cm between 4 cm blocks as one).
Called from ``references.py`` (the rest of what a description can say).
"""

from __future__ import annotations

import math

import numpy as np

from ..core.scene import COLORS, ROBOT_BASE_XY, Scene, SceneObject
from ..errors import LanguageError, UnknownObjectError
from .references import (
    BLOCK_SHAPES,
    BLOCK_WORDS,
    DETERMINERS,
    FARTHEST,
    NEAREST,
    NOUNS,
    ROBOT_WORDS,
    SHAPE_NOUNS,
    SIZE_SUPERLATIVES,
    Context,
    _colours,
    describe,
    object_pairs,
    resolve_object,
)

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
    ends = _two_references(words[at + 1:], scene, role, context)
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


def _two_references(words: list[str], scene: Scene, role: str, context: Context | None) -> tuple[str, str] | None:
    """"A and C", "the red and blue cubes" -> two different objects' names; None when ``words`` are not two."""
    return next((p for p in object_pairs(words, scene, (role, role), context) if isinstance(p, tuple) and p[0] != p[1]),
                None)


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
