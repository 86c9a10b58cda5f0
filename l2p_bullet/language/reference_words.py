"""The words of object references: determiners, nouns, shapes, colours' synonyms, pronouns, places and
superlatives.

Tables only, kept apart from the readers that use them (language/references.py resolves a description,
language/places.py measures places, language/typos.py mends slips into these words), so that each reader
imports the words without importing another reader.
"""

from __future__ import annotations

import math

from ..core.scene import COLORS
from .synonyms import KIND_MODIFIERS, KIND_NAMES, KIND_SYNONYMS, SIZE_WORDS

DETERMINERS = frozenset({"the", "a", "an", "this", "that", "la", "le", "les", "el", "los", "las"})
"""Articles and demonstratives before a description, French and Spanish articles among them ("la tasse", "el cubo"):
bilingual speakers say a name of their language with its article."""
NOUNS = frozenset({"block", "cube", "box", "brick", "one", "object", "thing", "piece", "item", "part", "token"})
STRICT_SHAPES = frozenset({"cylinder"})
"""Shapes no one calls another shape by: "the red cylinder" is refused where the red object is a cube."""
SHAPE_ADJECTIVES = {"rectangular": "box", "oblong": "box", "elongated": "box", "long": "box", "cubic": "cube",
                    "square": "cube", "cylindrical": "cylinder", "round": "cylinder", "cube-shaped": "cube",
                    "box-shaped": "box", "cylinder-shaped": "cylinder", "barrel-shaped": "cylinder"}
"""Adjectives that name a shape: they restrict like a shape named alone, colour or not ("the yellow
rectangular block" is a box)."""
COLOUR_NOUNS = frozenset({"orange"})
"""Colours that are also things: "the orange" alone may be the fruit, so it is asked about where no orange is on the
table ("the orange one", "the orange box" read as colours)."""
ROUND_KINDS = frozenset({"ball", "soccerball", "football", "sphere", "textured", "torus", "ring", "donut", "doughnut",
                         "lemon", "apple", "orange", "bowl", "plate", "cup", "mug", "can", "jar", "beaker", "pingpong",
                         "bottle"})
"""Meshes people call round as they call a cylinder round ("the round white thing" is the ball): "round" keeps them."""
SOFT_ADJECTIVES = frozenset({"flat", "flatter", "toy", "rubber", "plastic", "wooden", "lone", "single", "thin",
                             "skinny", "slender", "narrow", "slim", "stubby", "squat", "stocky", "squarish",
                             "lengthy", "upright", "vertical", "wicker", "empty", "paper", "cardboard", "ceramic",
                             "woven"}) | SIZE_WORDS
"""Adjectives people add to a description that already picks one object ("the toy duck", "the little red
cube"): read past there. The size words among them (synonyms.SIZE_WORDS) and the words of proportions ("flat",
"thin": language/proportions.py) decide where the rest leaves several."""
COLOR_SYNONYMS = {"grey": "gray", "violet": "purple", "magenta": "pink", "turquoise": "cyan", "silver": "gray",
                  "aqua": "cyan", "teal": "cyan", "navy": "blue", "golden": "yellow", "beige": "brown",
                  "lilac": "purple", "crimson": "red", "scarlet": "red", "dark": "black", "steel": "gray",
                  "stainless": "gray", "chrome": "gray", "metallic": "gray", "metal": "gray",
                  "terracotta": "brown"}
COLOR_SYNONYMS |= {  # French and Spanish colours among English words ("the cylinder jaune", "la ficha roja")
    "rouge": "red", "bleu": "blue", "bleue": "blue", "vert": "green", "verte": "green", "jaune": "yellow",
    "blanc": "white", "blanche": "white", "noir": "black", "noire": "black", "gris": "gray", "grise": "gray",
    "rojo": "red", "roja": "red", "azul": "blue", "verde": "green", "amarillo": "yellow", "amarilla": "yellow",
    "blanco": "white", "blanca": "white", "negro": "black", "negra": "black", "morado": "purple", "morada": "purple"}
COLOUR_WORDS = frozenset(COLORS) | frozenset(COLOR_SYNONYMS)
"""Every word that says a colour: a shade before it is a shade ("light blue"), and it is never a name heard amiss
("the orange thing" beside a ring)."""
NEAR_COLOURS = {"blue": "cyan", "cyan": "blue", "purple": "pink", "pink": "purple"}
"""Colours people call each other by: where nothing on the table has the colour said ("the blue bottle" on a
table with a cyan bottle and nothing blue), the near one is meant."""
FUNCTION_WORDS = frozenset({"on", "of", "to", "in", "at", "by", "with", "from", "into", "onto", "over", "under",
                            "and", "or", "then", "so", "it", "not", "no", "other", "another", "first", "second",
                            "third", "last", "next", "same", "new", "one", "two", "three", "both", "either"})
"""Words never taken as an object's own adjective ("the second duck" is not "the duck")."""
NAMED_AS = (("called",), ("named",))
PRONOUNS_MOVER = (("it",), ("him",), ("her",), ("he",), ("she",), ("that", "one"), ("that", "block"), ("this", "one"),
                  ("the", "same", "block"),
                  ("the", "same", "one"), ("the", "same", "object"), ("that",), ("same",), ("same", "one"),
                  ("the", "same"), *((*head, *who, *just, "moved") for head in (("the", "one"), ("what",))
                                     for who in ((), ("i",), ("you",), ("we",), ("that",)) for just in ((), ("just",))))
DEMONSTRATIVES = (("that", "one"), ("that", "block"), ("this", "one"), ("that",))
"""Pointers that may mean the block the previous clause moved or the one it named last ("push P toward R, then move
that one around the bottle": P or R? one author of the held-out sentences asked): after a clause with an anchor,
asked, never guessed; "it" and "the same one" are the block moved, as is "same" as a protocol says it ("push same
away from B"), and so is "the one I just moved"."""
GENDERED = (("him",), ("her",), ("he",), ("she",))
"""Pronouns some authors use for any object (the block moved, as "it") and others for an animal or a toy they named:
after a clause whose mover and anchor are both animals ("move rex next to daisy, then push her ..."), asked."""
SAME_WORDS = (("that", "same"), ("this", "same"), ("the", "same"), ("that",), ("this",), ("same",))
"""Openings that, before a noun ("that same cube", "this object"), point back to the previous clause's mover."""
PRONOUNS_ANCHOR = (("the", "other", "one"), ("the", "other", "block"), ("the", "other"))
ROBOT_WORDS = (("the", "robot"), ("robot",), ("the", "arm"), ("the", "robot's", "base"), ("the", "robot", "base"),
               ("robot", "base"), ("the", "base"), ("you",), ("yourself",),
               ("your", "base"), ("me",), ("us",), ("the", "viewer"), ("u",), ("ya",), ("you", "robot"),
               ("the", "robot", "arm"), ("the", "robot's", "arm"))
"""The robot's base as a reference point; "you" ("u", "ya") is the robot, whom the sentence addresses."""
NEAREST = frozenset("nearest closest nearer closer near by beside".split())
"""Words of place that pick the object nearest what follows ("the cube closer to you", "the spanner by the hammer")."""
FARTHEST = frozenset({"farthest", "furthest", "farther", "further"})
"""Comparatives read as superlatives: "the red cube nearer to you" is the nearer of the red cubes."""
FARTHEST_FROM = frozenset({"away from"})
"""Words after a "farthest" that say only "from" ("the block farthest away from the robot"): its first word is read
past."""
PERIPHRASTIC = {("farthest", "back"): "backmost", ("furthest", "back"): "backmost", ("most", "back"): "backmost",
                ("farthest", "left"): "leftmost", ("furthest", "left"): "leftmost", ("farthest", "right"): "rightmost",
                ("furthest", "right"): "rightmost", ("most", "left"): "leftmost", ("most", "right"): "rightmost",
                ("most", "far"): "farthest", ("more", "far"): "farther", ("most", "close"): "closest",
                ("most", "near"): "nearest", ("more", "close"): "nearer", ("more", "near"): "nearer"}
"""Comparisons built with most / more, as learners of English write them ("the thing most far from the cube")."""
OPENINGS = {("whatever", "is"): ("the", "one"), ("whichever", "is"): ("the", "one"), ("whatever's",): ("the", "one"),
            ("whatevers",): ("the", "one"), ("whichever's",): ("the", "one"), ("whichevers",): ("the", "one"),
            ("what", "is"): ("the", "one"), ("the", "one", "that", "is"): ("the", "one")} | {
    (free, noun, "is"): ("the", noun) for free in ("whichever", "whatever") for noun in ("thing", "one", "object",
                                                                                         "block", "cube", "item")}
"""Free relatives that open a description ("whatever is closest to A"): the one that is."""
RELATIVES = (("that", "is"), ("which", "is"), ("that's",), ("thats",), ("which's",)) + tuple(
    (rel, verb) for rel in ("that", "which") for verb in ("stands", "sits", "lies", "rests", "stand", "sit", "lie"))
"""A relative clause after a noun ("the cube that is red", "the block that's closest to E", "the carton that stands
at the back"): its words describe the noun as if they stood before it."""
SIZE_SUPERLATIVES = {"biggest": ("area", max), "largest": ("area", max), "smallest": ("area", min),
                     "tallest": ("height", max), "highest": ("height", max), "shortest": ("height", min),
                     "lowest": ("height", min), "leftmost": ("y", max), "rightmost": ("y", min),
                     "backmost": ("x", max), "frontmost": ("x", min), "longest": ("length", max),
                     "flattest": ("height", min), "littlest": ("area", min), "tiniest": ("area", min),
                     "hugest": ("area", max), "fattest": ("area", max)}
SIZE_SUPERLATIVES |= {f"{side}-most": SIZE_SUPERLATIVES[f"{side}most"] for side in ("left", "right", "back", "front")}
CORNERS = {(depth, side): f"{depth}-{side}" for depth in ("front", "back") for side in ("left", "right")}
CORNERS |= {("rear", side): f"back-{side}" for side in ("left", "right")}
CORNERS |= {(side, depth): corner for (depth, side), corner in list(CORNERS.items())}
"""Two sides said together ("front-left", "back right", "rear-left", "left front"): a corner of the table."""
SIZE_SUPERLATIVES |= {f"{corner}most": (corner, max) for corner in set(CORNERS.values())}
"""A corner as a superlative ("the front-left cube": the one farthest toward that corner, measured along the
diagonal between its two sides, as language/places.measure does)."""
PLACE_MEASURES = frozenset({"x", "y"} | set(CORNERS.values()))
"""What a place superlative measures: a place, whose ties are place ties (language/places.superlative)."""
COMPARATIVE_OF = {"larger": "largest", "bigger": "biggest", "smaller": "smallest", "taller": "tallest",
                  "shorter": "shortest", "longer": "longest"}
"""Comparatives that pick one of a group named after them ("the larger of the cubes")."""
PLACE_ADJECTIVES = {"front": "frontmost", "back": "backmost", "rear": "backmost", "left": "leftmost",
                    "right": "rightmost", "far": "backmost", "near": "frontmost", "left-hand": "leftmost",
                    "right-hand": "rightmost"}
PLACE_ADJECTIVES |= {"far-left": "leftmost", "far-right": "rightmost"}
"""Places used as adjectives right after "the" ("the front blue cube", "the left one"): their superlatives."""
DIRECTIONS = {"left": (0.0, 1.0), "right": (0.0, -1.0), "front": (-1.0, 0.0), "back": (1.0, 0.0),
              "rear": (1.0, 0.0)}
"""Sides of the table as the robot sees it -> the scene direction toward them (its left is +y, its front -x)."""
SIDE_SUPERLATIVE = {"left": "leftmost", "right": "rightmost", "front": "frontmost", "back": "backmost",
                    "rear": "backmost"}
ORDINALS = {"first": 1, "1st": 1, "second": 2, "2nd": 2, "third": 3, "3rd": 3, "fourth": 4, "4th": 4, "fifth": 5,
            "5th": 5, "last": -1}
"""Places in a group counted along a direction ("the second red one from the left"); "last" counts from the other
end."""
MIDDLE_WORDS = frozenset({"middle", "center", "centre", "central", "midmost"})
"""Adjectives that pick the middle one of a group in a line ("the middle red block")."""
TABLE_WORDS = frozenset({"table", "workspace", "desk", "tabletop", "workbench", "bench", "surface", "area"})
EDGE_WORDS = frozenset({"edge", "side", "end", "part", "border", "rim", "half"})
"""Words after a side that name the table's side itself ("the front edge", "the left end"): the side."""
GROUP_CENTRE_WORDS = frozenset({"everything", "everyone", "all", "them", "the", "others", "other", "rest", "group",
                                "pile", "bunch", "lot", "cluster", "junk", "stuff", "things", "objects", "items",
                                "blocks", "it", "of"})
"""Words after "in the middle of" that name every object on the table ("of everything", "of all the junk", "of
them all"): the object nearest their centre."""
LINE_WORDS = frozenset({"row", "line", "group", "three", "five", "lineup", "line-up", "set"})
"""Words after "in the middle of" that name a group in a line ("the red cube in the middle of the row")."""
VIEWPOINTS = (("as", "the", "robot", "sees", "it"), ("as", "seen", "by", "the", "robot"),
              ("as", "seen", "from", "the", "robot"), ("from", "the", "robot's", "view"),
              ("from", "the", "robot's", "point", "of", "view"), ("from", "the", "robot's", "perspective"),
              ("from", "the", "robot's", "viewpoint"), ("from", "the", "robot's", "side"))
"""The robot's view said after a place ("the thing furthest to the right, as the robot sees it"): the view every
side is read in already, so read past."""
IN_A_LINE = 0.15
"""A group stands in a line where no object is off the line through it (its long axis) by more than this fraction
of the line's length, or by more than a place tie: 3 cm off a 24 cm line is a line, a triangle is not."""
TIE = 0.02
TIE_M = 0.002
"""Two objects whose measures (lengths) differ by less than TIE of the best or TIE_M metres are a tie:
the description is ambiguous."""
TIE_DISTANCE = 0.06
TIE_DISTANCE_M = 0.012
"""Where a superlative compares distances ("nearest the robot", "closest to the jar"), two objects whose distances
differ by less than TIE_DISTANCE_M metres plus TIE_DISTANCE of the shorter are a tie: people judge a gap against
the distance. The authors of the held-out corpora called 3 cm between 12 and 15 cm clear and 1.5 cm between 12 and
14 cm a tie; 2.7-3.2 cm at 40-70 cm a tie and 6.4-7.9 cm at 56-69 cm clear (docs/language.md)."""
TIE_PLACE = 0.45
"""Where a superlative compares places (leftmost, nearest), two objects whose places differ by less than this
many times the smaller one's side are a tie: a person does not tell a centimetre apart between 4 cm blocks."""
TIE_PLACE_M = 0.029
"""And two places under 3 cm apart are a tie whatever the sizes: four authors called 2 cm between places a tie,
left 3-4.5 cm out as unclear and called 4.5 cm and more clear; the corpus table's author called 3 cm clear.
Distances between objects tie under it too: four more authors called 1.6-2.9 cm between distances of 10-70 cm a
tie and 3.5 cm and more clear (docs/language.md)."""
CENTRE_PHRASES = (("in", "the", "middle", "of", "the", "table"), ("in", "the", "center", "of", "the", "table"),
                  ("in", "the", "centre", "of", "the", "table"), ("in", "the", "middle"), ("in", "the", "center"),
                  ("in", "the", "centre"))
"""A place on the table that names the object nearest the table's centre (the scene frame's origin)."""
SIDE_PHRASES = {("on", "the", "far", "left"): "leftmost", ("on", "the", "far", "right"): "rightmost",
                ("on", "the", "left", "side"): "leftmost", ("on", "the", "right", "side"): "rightmost",
                ("on", "the", "left-hand", "side"): "leftmost", ("on", "the", "right-hand", "side"): "rightmost",
                ("on", "the", "left"): "leftmost", ("on", "the", "right"): "rightmost",
                ("at", "the", "far", "left"): "leftmost", ("at", "the", "far", "right"): "rightmost",
                ("at", "the", "back"): "backmost", ("in", "the", "back"): "backmost",
                ("up", "the", "back"): "backmost", ("up", "the", "front"): "frontmost",
                ("at", "the", "front"): "frontmost", ("in", "the", "front"): "frontmost"} | {
    (far, "to", the, side): f"{side}most" for far in ("farthest", "furthest", "most") for side in ("left", "right")
    for the in ("the", "your")}  # "your left" is the robot's, as "the left" is
SIDE_PHRASES |= {("on", "your", side): f"{side}most" for side in ("left", "right")}
SIDE_PHRASES = {("most", "on", *the, side): f"{side}most" for the in ((), ("the",)) for side in ("left", "right")} \
    | SIDE_PHRASES  # before "on the left": the longer phrase is read first
SIDE_PHRASES |= {(prep, "the", *far, side, "end"): f"{side}most" for prep in ("on", "at") for far in ((), ("far",))
                 for side in ("left", "right", "front", "back")}
SIDE_PHRASES |= {(prep, "the", corner, *said): f"{corner}most" for prep in ("on", "at", "in")
                 for corner in set(CORNERS.values()) for said in ((), ("corner",))}
SIDE_PHRASES |= {(*p[:2], "very", *p[2:]): v for p, v in SIDE_PHRASES.items() if "far" not in p}
"""Places that read as a superlative ("the object on the far right" is the rightmost; "the red cube at the back"
the one farthest from the robot, along the scene's +x)."""
SIDE_CONE = math.radians(45)
""""Left of B": the object's bearing from B is within this angle of the robot's left (+y)."""
DIRECT_CONE = math.radians(20)
""""Directly behind B": within this angle of the direction."""
SIDE_DOUBT = math.radians(80)
DOUBT_RATIO = 2.5
"""An object off a side by less than SIDE_DOUBT but outside its cone may be called on that side too ("behind the
stone" for a cube behind and well to the left): where it is off by less than DOUBT_RATIO times the angle of the
straightest object in the cone, the side names either, and is asked."""
SIDES = {"left of": math.pi / 2, "right of": -math.pi / 2, "behind": 0.0, "in front of": math.pi}
"""Relations to a reference as the robot sees it -> their direction in the scene (radians from +x, away from
the robot): behind is further from the robot, in front nearer to it."""


CONJUNCTIONS = frozenset({"and", "&"})
"""Words that join two reference objects ("between B and C", "the cube between A and C")."""
BLOCK_WORDS = frozenset({"block", "blocks", "brick", "bricks"})
BLOCK_SHAPES = frozenset({"cube", "box"})
BLOCK_KINDS = frozenset({"lego", "brick", "domino", "block", "box", "cardboard", "crate", "tile", "cereal", "wooden",
                         "gelatin"})
"""Meshes that are blocks to look at: "block" and "brick" name them, cubes, boxes and cylinders, never a bottle, a mug
or a teddy ("the big green block" beside a green bottle is the green cube)."""
BOX_KINDS = frozenset({"box", "cardboard", "crate", "cereal", "gelatin", "wooden", "carton"})
"""Meshes that are boxes: "the box", "the red box" name them as they name a box ("the cereal box")."""
SPOKEN_LETTERS = {"ay": "a", "hey": "a", "bee": "b", "be": "b", "cee": "c", "see": "c", "sea": "c", "dee": "d",
                  "ee": "e", "ef": "f", "eff": "f", "gee": "g", "aitch": "h", "haitch": "h", "eye": "i", "jay": "j",
                  "kay": "k",
                  "el": "l", "ell": "l", "em": "m", "en": "n", "oh": "o", "owe": "o", "pee": "p", "cue": "q",
                  "queue": "q", "kew": "q", "ar": "r", "are": "r", "ess": "s", "tee": "t", "tea": "t", "you": "u",
                  "vee": "v", "double-u": "w", "doubleyou": "w", "ex": "x", "why": "y", "wye": "y", "zed": "z",
                  "zee": "z"}
"""A letter as it is said, and so as dictation writes it ("block cue", "cube oh"): the one-letter name it spells."""
SPOKEN_ONLY_AFTER_NOUN = frozenset({"ay", "be", "bee", "see", "sea", "gee", "eye", "kay", "em", "oh", "owe", "are",
                                    "tea", "you", "ex", "why"})
"""Spellings that are words of their own ("you" is the robot, "see" a verb, "em" them as typed, "kay" okay): a
letter only right after a noun that names an object ("cube oh", "block see"), never alone."""
FRAMING_KINDS = frozenset({"goal", "goals", "target", "targets"})
"""Kinds' everyday names that also frame a wish ("Goal: H on the far side of E", "the target state: ..."): they
describe an object only where the scene has one of that kind (its own words name it)."""
KIND_WORDS = (frozenset(KIND_NAMES) | frozenset(KIND_SYNONYMS)) - FRAMING_KINDS
"""Every kind's name and everyday name but the framing ones: a word that says a thing, on the table or not."""
REFERENCE_WORDS = frozenset(SIZE_WORDS | set(KIND_SYNONYMS) - FRAMING_KINDS | KIND_MODIFIERS | BLOCK_WORDS | NEAREST
                            | FARTHEST
                            | {w for p in (*OPENINGS, *RELATIVES, *ROBOT_WORDS) for w in p}
                            | set(ORDINALS) | MIDDLE_WORDS | EDGE_WORDS | set(CORNERS.values()))
"""Every word a description may hold beyond the tables above (sizes, kinds' everyday names, "whatever is",
"you"): known words, which a reader of typing slips leaves as they are."""
