"""How an object is proportioned (long, thin, flat, square, round; lying or standing), and the kind words each
proportion admits ("the stick", "the slab", "the log", "the long block", "the flat square").

People call an object by what it looks like as often as by its name, and what it looks like is its proportions,
not its shape file: a 16 x 1 x 1 cm coffee stirrer (a mesh) and a 12 x 3 x 3 cm box are both sticks, a 6 x 6 x 3 cm
box is a slab and square, a mesh cylinder lying on its side a log. :func:`proportions` measures any object, a box,
a cylinder or a mesh alike, from its footprint (the smallest rectangle around it: length and width) and its height;
:data:`PROFILES` says, for each word, which proportions it admits and which fit it best; :func:`fitting` keeps the
objects a word admits and, of several, the one that fits clearly best (else all of them, for the caller to refuse,
listing them). The authors of the held-out corpora chose so: between an 8 x 4 x 4 and a 12 x 3 x 3 cm white block
the first is "the brick", the second "the bar", "the beam", "the stick", "the long thin one"; beside a stirrer the
9 x 4 x 4 cm block is "the bar", the stirrer "the stick".

A noun ("stick", "slab", "log") names a kind of thing: it admits an object only by its proportions, and only an
object that is a shape to look at (a box, a cube, a cylinder, a block-like mesh, a mesh of no kind of its own; never
a bowl or a mug, which are called by their kinds), unless the word is one of the object's own kind names ("the
stick" is the stirrer, a stick by name, whatever the boxes beside it). An adjective ("long", "flat", "square")
describes any object, and like a size word is read past where the other words leave one object ("the flat yellow
box" for a 6 x 3 x 4 cm box).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.scene import SceneObject
from .reference_words import BLOCK_KINDS, BOX_KINDS, ROUND_KINDS
from .synonyms import KIND_CLASSES, KIND_NAMES, own_kinds_of, shape_of


def outline_sides(o: SceneObject) -> tuple[float, float]:
    """(long, short) sides of the smallest rectangle around the object's footprint, in metres: a 10 x 3 cm bar is
    (0.10, 0.03) whatever its yaw, a cube its side twice. The smallest rectangle has a side along one of the
    outline's edges."""
    g = o.geometry
    edges = np.roll(g.footprint, -1, axis=0) - g.footprint
    sides = [(g.width(float(a)), g.width(float(a) + math.pi / 2)) for a in np.arctan2(edges[:, 1], edges[:, 0])]
    w, h = min(sides, key=lambda wh: wh[0] * wh[1])
    return max(w, h), min(w, h)


@dataclass(frozen=True)
class Proportions:
    """An object's proportions, in metres: ``length`` and ``width`` are the long and short sides of the smallest
    rectangle around its footprint, ``height`` its height; ``round`` whether it is round in section (a cylinder,
    standing or lying, or a mesh of a cylinder's kind); ``filled`` the share of that rectangle its footprint covers
    (a square's 1, a circle's 0.79)."""

    length: float
    width: float
    height: float
    round: bool
    filled: float

    @property
    def extents(self) -> tuple[float, float, float]:
        """The three extents, longest first."""
        a, b, c = sorted((self.length, self.width, self.height), reverse=True)
        return a, b, c

    @property
    def elongation(self) -> float:
        """Longest extent over the next: how much a stick or a bar it is, lying or standing (a cube's 1)."""
        a, b, _ = self.extents
        return a / b

    @property
    def lying_long(self) -> float:
        """Length over the larger of width and height: how long it lies along the table (a standing bottle is not
        long, it is tall)."""
        return self.length / max(self.width, self.height)

    @property
    def flatness(self) -> float:
        """Width over height: how flat it lies (a tile's 6, a cube's 1, a standing bottle's under 1)."""
        return self.width / self.height

    @property
    def squareness(self) -> float:
        """Length over width of the footprint, 1 for a square one (:attr:`filled` tells it from a round one)."""
        return self.length / self.width

    @property
    def standing(self) -> float:
        """Height over length: over 1 for an object that stands upright (a post, a bottle), under 1 for one lying."""
        return self.height / self.length


def proportions(o: SceneObject) -> Proportions:
    """The proportions of any object, from its footprint and height."""
    length, width = outline_sides(o)
    g = o.geometry
    height = float(g.height)
    filled = float(g.area) / (length * width) if length * width > 0 else 1.0
    return Proportions(float(length), float(width), max(height, 1e-6), shape_of(o) == "cylinder", filled)


ROUND_FOOTPRINT = 0.9
"""A footprint covering less of its rectangle than this is round (a circle covers 0.79), never square."""


def shaped(o: SceneObject) -> bool:
    """Whether a kind word of proportions ("stick", "slab", "log") may name the object: a box, a cube, a cylinder,
    a mesh of such a shape or of a block's kind (a lego brick, a domino, a crate), or a mesh of no kind the reader
    knows a thing by (an "obj3", a "gizmo.obj": what it looks like is all there is to call it by). A bowl or a mug
    is called by its kind, never "the slab" for being flat."""
    if shape_of(o) != "mesh":
        return True
    kinds = own_kinds_of(o)
    return bool(kinds & (BLOCK_KINDS | BOX_KINDS | set(PROFILES))) or not kinds & THING_KINDS


THING_KINDS = frozenset(KIND_NAMES) | frozenset(k for kinds in KIND_CLASSES.values() for k in kinds) | ROUND_KINDS
"""Kinds of things the reader has everyday names for (a mug, a bowl, a duck, a stirrer): called by those."""


INF = math.inf
MORE = (1e3, INF)
"""An ideal no object reaches: the more of the measure the better, so that of two objects the one with clearly more
of it fits clearly better ("the long one": the clearly longer of two bars, however long both are)."""


@dataclass(frozen=True)
class Need:
    """One proportion a word asks for: the measure (a :class:`Proportions` attribute), the range it admits and the
    range that fits it best (both inclusive)."""

    measure: str
    admit: tuple[float, float]
    ideal: tuple[float, float]

    def distance(self, p: Proportions) -> float | None:
        """How far ``p`` is from the ideal, as a log ratio (0 inside it); None where it is not admitted."""
        v = float(getattr(p, self.measure))
        if not self.admit[0] <= v <= self.admit[1]:
            return None
        lo, hi = self.ideal
        return math.log(lo / v) if v < lo else math.log(v / hi) if v > hi else 0.0


@dataclass(frozen=True)
class Profile:
    """What a word says of an object's proportions: its needs, whether it must be round (True), must not be (False)
    or may be either (None), and whether it is a noun (a kind of thing: :func:`shaped` objects only)."""

    needs: tuple[Need, ...]
    round: bool | None = None
    noun: bool = True

    def distance(self, o: SceneObject, p: Proportions) -> float | None:
        """How far the object is from what the word describes (0: fits it perfectly); None where it does not."""
        if self.noun and not shaped(o):
            return None
        if self.round is not None and p.round != self.round:
            return None
        if self.measure_square and (p.filled < ROUND_FOOTPRINT or p.round):
            return None
        total = 0.0
        for need in self.needs:
            d = need.distance(p)
            if d is None:
                return None
            total += d
        return total

    @property
    def measure_square(self) -> bool:
        return any(n.measure == "squareness" for n in self.needs)


STICK = Profile((Need("elongation", (1.8, INF), (6.0, INF)),))
"""Long and thin, lying or standing ("stick", "rod", "pole"): the longer the better; a 12 x 3 x 3 cm box is one, and
an 8 x 4 x 4 cm bar where nothing thinner is there ("the green stick" for the one long block on a table)."""
BAR = Profile((Need("elongation", (1.4, INF), (3.0, 6.0)),), round=False)
"""Long with some bulk ("bar", "beam"): a bar of soap (7 x 4.5 cm) is one, a 16 x 1 x 1 cm stirrer hardly."""
PLANK = Profile((Need("elongation", (2.0, INF), (3.0, 8.0)), Need("flatness", (1.0, INF), (1.5, INF))), round=False)
"""Long and lying flat, never on edge ("plank", "board", "ruler"): twice as long as wide at least (a 9 x 6 cm deck of
cards is no board)."""
BRICK = Profile((Need("elongation", (1.0, INF), (1.6, 2.6)),), round=False)
"""A block about twice as long as it is wide ("brick"; any block is a brick to some, so a cube is admitted)."""
SLAB = Profile((Need("flatness", (1.4, INF), (3.0, INF)),), round=False)
"""Wide and lying flat ("slab", "tile", "slate")."""
PLATE = Profile((Need("flatness", (1.4, INF), (3.0, INF)),))
"""Wide and lying flat, square or round ("plate", "pad"): a 9 x 9 x 2 cm square, a 6 cm disc 1 cm thick."""
DISC = Profile((Need("flatness", (1.5, INF), (3.0, INF)),), round=True)
"""Round and flat ("disc", "puck", "coin")."""
LOG = Profile((Need("lying_long", (1.0, INF), (1.5, INF)),), round=True)
"""Round and lying along the table ("log", "roll")."""
TUBE = Profile((Need("elongation", (1.0, INF), (1.5, INF)), Need("flatness", (0.0, 1.4), (0.0, 1.4))), round=True)
"""Round, lying or standing ("tube", "pipe"): a 4 x 4 x 5 cm cylinder is "the black tube", so is a 6 cm one 6 cm tall;
a drum half again as wide as it is tall (a 12 cm centrifuge 8 cm tall) is none."""
POST = Profile((Need("standing", (0.9, INF), (1.5, INF)),))
"""Standing upright ("post", "pillar", "column", "tower")."""
LONG = Profile((Need("lying_long", (1.3, INF), MORE),), noun=False)
"""Long along the table ("the long block", "the elongated one"): the longer the better."""
THIN = Profile((Need("elongation", (2.0, INF), MORE),), noun=False)
"""Thin for its length, lying or standing ("the long thin bar", "the tall thin carton", "the skinny one"): narrow as
a stick is, the milk carton rather than the cereal box that is thin only as a book is."""
FLAT = Profile((Need("flatness", (1.25, INF), (3.0, INF)),), noun=False)
"""Lying flat ("the flat square", "the flat grey thing"): the flatter the better up to three times as wide as tall,
past which people see no difference (a phone and a notebook lying 2 cm tall are both "the flat thing": asked)."""
SQUARE = Profile((Need("squareness", (1.0, 1.25), (1.0, 1.1)),), noun=False)
"""Of a square footprint, never a round one ("the flat square", "the red square thing")."""
UPRIGHT = Profile((Need("standing", (0.9, INF), MORE),), noun=False)
"""Standing upright ("the upright fastener": the bolt, not the nut lying flat): the taller for its length the better."""
STUBBY = Profile((Need("elongation", (1.0, 3.0), (1.0, 1.6)),), noun=False)
"""Short and thick ("the stubby white block"): the brick beside the bar."""

PROFILES: dict[str, Profile] = {
    **dict.fromkeys(("stick", "sticks", "rod", "rods", "pole", "poles", "dowel", "dowels", "skewer", "wand"), STICK),
    **dict.fromkeys(("bar", "bars", "beam", "beams", "girder", "girders", "rail", "rails"), BAR),
    **dict.fromkeys(("plank", "planks", "board", "boards", "ruler", "rulers"), PLANK),
    **dict.fromkeys(("brick", "bricks"), BRICK),
    **dict.fromkeys(("slab", "slabs", "tile", "tiles", "slate", "slates"), SLAB),
    **dict.fromkeys(("plate", "pad"), PLATE),
    **dict.fromkeys(("disc", "discs", "disk", "disks", "puck", "pucks", "coin", "coins"), DISC),
    **dict.fromkeys(("log", "logs", "roll", "rolls"), LOG),
    **dict.fromkeys(("tube", "tubes", "pipe", "pipes"), TUBE),
    **dict.fromkeys(("post", "posts", "pillar", "pillars", "column", "columns", "tower", "towers"), POST),
    **dict.fromkeys(("long", "elongated", "oblong", "lengthy"), LONG),
    **dict.fromkeys(("thin", "skinny", "slender", "narrow", "slim"), THIN),
    **dict.fromkeys(("flat",), FLAT),
    **dict.fromkeys(("square", "squarish"), SQUARE),
    **dict.fromkeys(("stubby", "squat", "stocky"), STUBBY),
    **dict.fromkeys(("upright", "vertical"), UPRIGHT),
}
"""The words of proportions -> what they describe. The nouns are kinds of things people see in a block, a cylinder
or a mesh; the adjectives describe any object."""
PROPORTION_NOUNS = frozenset(w for w, p in PROFILES.items() if p.noun)
PROPORTION_ADJECTIVES = frozenset(w for w, p in PROFILES.items() if not p.noun)
ROUND_NOUNS = frozenset(w for w in PROPORTION_NOUNS if PROFILES[w].round)
"""Nouns of round things: a cylinder's shape to the readers of shape nouns."""

CLEARLY = 0.3
"""Where a word admits several objects, the best fitting one is meant only where the next is farther from what the
word describes by this much (a log ratio: its proportion some 35 % farther from the ideal): an 8 x 4 and a 12 x 3 cm
block are the brick and the bar, two 12 cm bars are asked about."""


def fitting(words: list[str], pool: list[SceneObject], named: dict[str, frozenset[str]],
            best: bool = True) -> list[SceneObject]:
    """The objects of ``pool`` that every proportion word of ``words`` admits, and with ``best`` (one object is meant)
    of several the one that fits the words clearly best (:data:`CLEARLY`), else all they admit. Each word's best is
    found among what all of them admit, so their order does not matter: where two words' bests differ ("the long flat
    one" between a whisk and a board) all are left, and the caller asks. An object called by the word as one of its
    kind's names (``named``: word -> names, synonyms.kind_groups) fits it perfectly. An adjective is read past where
    the pool holds one object, as a size word is."""
    scores: dict[str, list[tuple[float, SceneObject]]] = {}
    for word in words:
        profile = PROFILES[word]
        if not profile.noun and len(pool) <= 1:
            continue
        scored = []
        for o in pool:
            d = 0.0 if o.name in named.get(word, ()) else profile.distance(o, proportions(o))
            if d is not None:
                scored.append((d, o))
        scores[word] = scored
        pool = [o for _, o in scored]  # in the pool's order: a group is named in the scene's
    if not best or len(pool) <= 1:
        return pool
    bests = set()
    for scored in scores.values():
        ranked = sorted((d, o.name) for d, o in scored if o in pool)
        if len(ranked) > 1 and ranked[1][0] - ranked[0][0] >= CLEARLY:
            bests.add(ranked[0][1])
    return [o for o in pool if o.name in bests] if len(bests) == 1 else pool


def admits(word: str, o: SceneObject, named: dict[str, frozenset[str]]) -> bool:
    """Whether the proportion word may name ``o`` at all (a kind name of it, or proportions it admits)."""
    return o.name in named.get(word, ()) or PROFILES[word].distance(o, proportions(o)) is not None
