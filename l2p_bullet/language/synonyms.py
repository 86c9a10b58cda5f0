"""The words people use for an object besides its name: common names of its kind and size words.

An object is called by its kind: its name when the name is a word ("mug", "duck", "can"), each word of a name of
several ("coffee_mug": a mug, and coffee; "cube_b": a cube), and the words of its mesh file's stem ("duck_vhacd.obj":
a duck; "soup_can.obj": soup and a can; "tablelamp.obj": a lamp). People use the kind's everyday names too ("the
cup", "the coffee mug", "the bird", "the tin can"); such a word resolves only where exactly one object is of that
kind, never by a guess between two.
"""

from __future__ import annotations

import functools
import re
import unicodedata

from ..core.scene import COLORS, Scene, SceneObject
from . import lexicon
from .kept import SceneMemo
from .shape_words import SHAPE_NOUNS

KIND_NAMES = {
    "mug": ("cup", "cups", "teacup", "mugs", "cuppa"),
    "cup": ("mug", "mugs", "cups", "teacup", "cuppa"),
    "jar": ("jars", "canister", "container", "pot"),
    "duck": ("bird", "duckling", "ducks"),
    "can": ("tin", "tins", "soda", "coke", "cola", "pop"),
    "teddy": ("bear", "bears", "teddies", "teddybear", "plush", "plushie"),
    "bunny": ("rabbit", "rabbits", "bunnies", "hare"),
    "stone": ("rock", "rocks", "pebble", "pebbles", "stones"),
    "soccerball": ("ball", "football", "soccer", "footy", "footie", "sphere", "globe"),
    "ball": ("balls", "football", "footy", "footie", "sphere", "spheres", "globe"),
    "bottle": ("bottles", "flask"),
    "bowl": ("bowls", "dish", "container", "basin", "pot"),
    "apple": ("apples",),
    "banana": ("bananas", "nana", "nanas", "nanner"),
    "lemon": ("lemons", "citrus"),
    "lime": ("limes", "citrus"),
    "orange": ("oranges", "citrus", "tangerine", "mandarin", "clementine"),
    "bread": ("loaf", "roll", "rolls", "bun", "buns"),
    "milk": ("carton", "cartons", "milkbox"),
    "lid": ("lids", "disc", "disk", "puck", "cap"),
    "brick": ("bricks",),
    "slab": ("slabs", "board", "tile", "slate", "plate"),
    "beam": ("beams", "plank", "girder", "rod"),
    "plank": ("planks", "board", "beam"),
    "plate": ("plates", "dish", "dishes", "saucer", "saucers", "baseplate", "baseplates"),
    "torus": ("ring", "rings", "donut", "donuts", "doughnut", "doughnuts", "hoop", "hoops"),
    "ring": ("rings", "donut", "donuts", "doughnut", "doughnuts", "hoop", "hoops", "torus"),
    "donut": ("donuts", "doughnut", "doughnuts", "ring", "rings", "hoop", "hoops", "torus"),
    "doughnut": ("doughnuts", "donut", "donuts", "ring", "rings", "hoop", "hoops", "torus"),
    "lego": ("legos", "brick", "bricks"),
    "cone": ("cones", "pylon", "pylons"),
    "prism": ("prisms", "triangle", "triangles", "triangular", "toblerone", "wedge", "wedges"),
    "domino": ("dominoes", "dominos", "tile", "tiles"),
    "cereal": ("cornflakes",),
    "zucchini": ("zucchinis", "courgette", "courgettes", "marrow", "marrows", "squash"),
    "gamepad": ("gamepads", "controller", "controllers", "joystick", "joysticks", "joypad", "joypads"),
    "joypad": ("joypads", "controller", "controllers", "joystick", "joysticks", "gamepad", "gamepads"),
    "lamp": ("lamps", "light", "lights"),
    "saucer": ("saucers", "plate", "plates", "dish", "dishes"),
    "camera": ("cameras", "cam", "cams", "webcam"),
    "pingpong": ("ping-pong",),
    "jello": ("jell-o", "jelly", "gelatin", "gelatine"),
    "gelatin": ("gelatine", "jello", "jell-o", "jelly"),
    "box": ("packet", "packets", "carton", "cartons", "crate", "crates", "parcel", "parcels", "package"),
    "ketchup": ("catsup", "sauce", "bottle", "bottles"),
    "mustard": ("bottle", "bottles", "sauce", "french's", "frenchs"),
    "butter": ("packet", "packets", "pack", "packs", "stick", "sticks"),
    "bolt": ("bolts", "screw", "screws"),
    "nut": ("nuts",),
    "soup": ("soups", "campbell's", "campbells", "campbell"),
    "crate": ("crates",),
    "stirrer": ("stirrers", "stick", "sticks", "stirrer"),
    "beaker": ("beakers", "cup", "cups", "glass"),  # "glasses" are spectacles before they are two of them
    "cylinder": ("tin", "tins"),
    "shaker": ("shakers", "pot", "pots", "cellar", "cellars", "grinder", "grinders", "mill", "mills"),
    "board": ("boards",),
    "bucket": ("buckets", "pail", "pails"),
    "flask": ("flasks", "erlenmeyer", "erlenmeyers", "glass", "conical"),
    "rack": ("racks", "holder", "holders"),
    "vial": ("vials", "bottle", "bottles", "ampoule", "ampule"),
    "truck": ("trucks", "lorry", "lorries", "firetruck", "firetrucks", "engine", "vehicle"),
    "cracker": ("crackers", "cheez-it", "cheez-its", "cheezit", "cheezits", "cheese-it", "cheezit's"),
    "sugar": ("domino",),
    "meat": ("spam",),
    "chef": ("coffee",),
    "tuna": ("starkist",),
    "pudding": ("jell-o", "jello"),
    "dinosaur": ("dinosaurs", "dino", "dinos", "t-rex", "trex", "rex"),
    "cow": ("cows", "moo", "calf", "cattle"),
    "dog": ("dogs", "doggy", "doggie", "doggo", "puppy", "pup", "pooch", "terrier", "scottie", "hound"),
    "dino": ("dinos", "dinosaur", "dinosaurs", "t-rex", "trex", "rex", "dyno"),
    "doll": ("dolls", "dolly", "dollie", "princess", "barbie"),
    "car": ("cars", "racecar", "racecars", "racer", "vehicle", "motor", "auto", "automobile"),
    "boot": ("boots", "shoe", "shoes", "footwear"),
    "kettle": ("kettles", "teakettle"),
    "colander": ("colanders", "strainer", "strainers", "sieve", "sieves", "drainer", "bowl"),
    "whisk": ("whisks", "beater", "eggbeater"),
    "ladle": ("ladles", "spoon", "spoons", "scoop", "dipper"),
    "keys": ("key", "keyring", "keyrings", "keychain"),
    "wallet": ("wallets", "billfold", "purse", "pocketbook"),
    "glasses": ("specs", "spectacles", "eyeglasses", "readers"),
    "vase": ("vases", "florero", "jarron", "jarr\u00f3n"),
    "book": ("books", "novel", "paperback", "hardback", "libro"),
    "candle": ("candles", "taper", "vela"),
    "remote": ("remotes", "controller", "control", "clicker", "zapper", "pult", "mando"),
    "glass": ("tumbler", "tumblers", "cup", "cups"),
    "scanner": ("scanners", "gun", "scangun", "barcode", "scan"),
    "tape": ("dispenser", "dispensers"),
    "label": ("labels", "sticker", "stickers"),
    "tote": ("totes", "bin", "bins", "container"),
    "scalpel": ("scalpels", "blade", "knife", "lancet"),
    "forceps": ("pickups", "tweezers", "tweezer", "pincers", "tongs"),
    "syringe": ("syringes", "needle", "plunger"),
    "gauze": ("sponge", "bandage", "dressing", "swab"),
    "dish": ("dishes", "basin", "basins", "emesis"),
    "bin": ("bins", "container", "bucket"),
    "fish": ("fishes", "fishy", "fishie", "clownfish", "goldfish"),
    "barn": ("barns", "house", "farmhouse", "stable", "shed"),
    "pond": ("ponds", "water", "pool", "lake"),
    "pail": ("pails", "bucket", "buckets"),
    "pen": ("pens", "pencil", "pencils"),
    "minifig": ("minifigs", "minifigure", "minifigures", "fig", "figs"),
    "sorter": ("box", "boxes", "shapesorter", "shape-sorter"),
    "sharpie": ("sharpies", "marker", "markers", "pen", "felt-tip"),
    "starbucks": ("cup", "coffee", "latte", "coffeecup", "drink"),
    "moleskine": ("notebook", "notebooks", "journal", "notepad"),
    "airpods": ("earbuds", "earphones", "headphones"),
    "pods": ("earbuds", "earphones", "headphones"),
    "post": ("notes", "postit", "post-its", "postits", "sticky", "stickies"),
    "phone": ("phones", "telephone", "cellphone", "cell", "mobile", "smartphone", "iphone"),
    "ipad": ("tablet", "tablets"),
    "kindle": ("tablet", "e-reader", "ereader"),
    "thermos": ("flask", "bottle"),
    "nutella": ("jar",),
    "kleenex": ("tissues", "tissue"),
    "king": ("kings", "k\u00f6nig", "konig", "koenig", "kink"),
    "queen": ("queens", "lady", "dame", "dama"),
    "rook": ("rooks", "castle", "castles", "tower", "towers", "turm", "rock"),
    "knight": ("knights", "horse", "horses", "horsey", "horsie", "pony", "jumper", "springer", "night", "nite"),
    "bishop": ("bishops", "runner", "l\u00e4ufer", "laufer"),
    "pawn": ("pawns", "farmer", "bauer", "peasant", "prawn", "meeple", "meeples", "token", "tokens", "counter"),
    "die": ("dice", "d6"), "deck": ("cards", "pack", "pile", "decks"),
    "hourglass": ("hourglasses", "sandglass", "sanduhr", "clock"), "timer": ("timers", "clock"),
    # a potting bench: the words people use for its tools and pots
    "trowel": ("trowels", "scoop"), "flowerpot": ("flowerpots", "planter"), "pot": ("planter", "planters"),
    "packet": ("envelope", "sachet"), "pad": ("notepad", "notebook", "scorepad"),
    "wrench": ("wrenches", "spanner", "spanners"),
    "spanner": ("spanners", "wrench", "wrenches"),
    "mallet": ("mallets", "hammer", "hammers"),
    "hammer": ("hammers", "mallet", "mallets", "claw"),
    "screwdriver": ("screwdrivers", "driver", "drivers"),
    "drill": ("drills", "makita", "dewalt", "bosch", "ryobi", "milwaukee"),
    # a classroom: the words children and teachers use
    "crayon": ("crayons", "colours", "colors", "crayola"),
    "case": ("cases", "pouch", "bag"),
    "flat": ("flathead", "flat-head", "flatblade", "flat-blade", "slotted"),
    "phillips": ("philips", "crosshead", "cross-head", "pozi", "pozidriv"),
    "goal": ("goals", "target", "targets", "marker", "markers"),
    "target": ("targets", "goal", "goals", "marker", "markers"),
    # a bathroom shelf, an art desk, an office desk: the everyday names, the brands on them, the British words
    "toothbrush": ("toothbrushes",),
    "toothpaste": ("tube", "colgate", "crest", "sensodyne"),
    "razor": ("razors", "shaver", "gillette"),
    "shampoo": ("bottle",),
    "eraser": ("erasers", "rubber", "rubbers"),
    "sketchbook": ("sketchpad", "sketchbooks", "notebook"),
    "palette": ("palettes",),
    "notepad": ("postit", "post-it", "post-its", "postits", "stickies"),
    "stapler": ("staplers", "swingline"),
}
"""A kind (an object's word name, or its mesh file's stem) -> the everyday names people also call it by, brands among
them where a benchmark's object set is a brand's product (the YCB set: the Master Chef can is the coffee, the Cheez-It
box the crackers, Domino the sugar, Campbell's the soup, French's the mustard, Spam the potted meat)."""
FIGURES = ("minifig", "figure", "figurine", "doll", "person", "man", "woman", "boy", "girl", "soldier", "astronaut",
           "pawn", "king", "queen", "knight", "bishop", "rook", "meeple", "chessman")
"""Kinds of a little person: "the little guy", "the figure", "the lego man" is the one object of such a kind. A board
game's pieces are its men and figures ("the little red man", a German speaker's "the blue figure" for a pawn)."""
CASUAL_PERSONS = frozenset({"guy", "dude", "fella", "fellow", "chap", "bloke", "figure"})
FIGURE_WORDS = CASUAL_PERSONS | {"figurine", "person", "man", "character", "minifigure", "figures", "people", "guys"}
"""Words for a little person. They name the scene's figures where it has one; where it has none they are no kind:
"the bunny figurine" is the bunny, and the casual ones ("the little yellow guy", a chess set's "white figure") mean
any object, as "one" does."""
LOOSE_NOUNS = CASUAL_PERSONS | {"machine", "device", "gadget", "appliance", "instrument", "thingy", "thingamajig",
                                "doodad", "whatsit", "doohickey", "shape", "tool", "tools", "utensil", "utensils",
                                "implement", "gizmo", "contraption"}
"""Nouns that name any object where nothing on the table is of their kind ("the grey machine", "the little yellow
guy"): read as "one" is."""
KIND_NAMES |= {
    # French
    "bol": ("bowl", "bowls"), "tasse": ("cup", "cups", "mug", "teacup"), "cuillere": ("spoon", "spoons", "teaspoon"),
    "theiere": ("teapot", "teapots", "pot", "kettle"), "assiette": ("plate", "plates", "dish"),
    "sucrier": ("sugar", "sugarbowl"), "verre": ("glass", "glasses"), "bouteille": ("bottle", "bottles"),
    "boite": ("box", "boxes"), "balle": ("ball", "balls"),
    # Spanish
    "caja": ("box", "boxes", "crate"), "pelota": ("ball", "balls"), "bola": ("ball", "balls"),
    "taza": ("cup", "cups", "mug"), "lata": ("can", "cans", "tin"), "cubo": ("cube", "cubes"),
    "botella": ("bottle", "bottles"), "vaso": ("glass", "glasses"), "plato": ("plate", "plates", "dish"),
    "cuchara": ("spoon", "spoons"), "tetera": ("teapot", "pot"),
    # German
    "wurfel": ("cube", "cubes", "dice"), "becher": ("cup", "mug"), "kiste": ("box", "crate"), "schachtel": ("box",),
    "dose": ("can", "tin"), "flasche": ("bottle",), "teller": ("plate", "dish"), "loffel": ("spoon",),
    "schussel": ("bowl",), "kanne": ("pot", "teapot", "jug"),
    # Italian
    "tazza": ("cup", "mug"), "scatola": ("box",), "palla": ("ball",), "lattina": ("can", "tin"),
    "bottiglia": ("bottle",), "piatto": ("plate", "dish"), "cucchiaio": ("spoon",), "ciotola": ("bowl",),
    "teiera": ("teapot", "pot"), "bicchiere": ("glass", "cup"),
    # Japanese, as romaji writes it
    "koppu": ("cup", "cups", "glass", "mug"), "sara": ("plate", "plates"), "hako": ("box", "boxes"),
    "hashi": ("chopsticks", "chopstick", "sticks"), "chawan": ("bowl", "ricebowl"), "kyusu": ("teapot", "pot"),
    "yunomi": ("teacup", "cup"), "kappu": ("cup", "mug"), "bouru": ("bowl", "ball"),
}
"""Objects a scene names in French, Spanish, German, Italian or Japanese (its names without accents, as kinds are): the
English words a bilingual user also calls them by ("la tasse" is the cup, "the teapot" the théière)."""
KIND_CLASSES = {"animal": ("duck", "teddy", "bunny", "dinosaur", "dino", "cow", "dog", "fish"),
                "animals": ("duck", "teddy", "bunny", "dinosaur", "dino", "cow", "dog", "fish"),
                "toy": ("duck", "teddy", "bunny", "ball", "soccerball", "truck", "doll", "dino", "dinosaur", "brick",
                        "lego"),
                "fruit": ("apple", "lemon", "orange", "banana", "pear", "peach", "plum", "lime", "grape", "kiwi",
                          "mango", "strawberry", "cherry", "melon", "grapefruit", "apricot", "pineapple")} | {
    word: ("zucchini", "cucumber", "carrot", "eggplant", "aubergine", "potato", "broccoli")
    for word in ("vegetable", "vegetables", "veg", "veggie", "veggies")} | {
    word: ("bolt", "nut", "screw", "washer") for word in ("fastener", "fasteners", "metal", "hardware")} | {
    word: ("wrench", "spanner", "screwdriver", "hammer", "mallet", "tape", "pliers", "saw", "drill", "chisel", "file",
           "ruler", "scissors", "knife") for word in ("tool", "tools")}
"""Words for a class of kinds ("the stuffed animal", "the veg", "the metal part"): like a kind's name, they resolve
only where exactly one object is of a kind of the class (a nut and a bolt: "the metal part" is asked)."""
KIND_SYNONYMS: dict[str, tuple[str, ...]] = {
    word: tuple(kind for kind, names in KIND_NAMES.items() if word in names)
    for word in dict.fromkeys(w for names in KIND_NAMES.values() for w in names)
} | KIND_CLASSES
"""An everyday name -> the kinds it names (an object named, or meshed as, one of those kinds)."""
KIND_MODIFIERS = frozenset({"coffee", "tea", "soda", "tin", "measuring", "glass", "rubber", "toy", "plastic", "bath",
                            "drink", "drinks",
                            "traffic", "teddy", "stuffed", "plush", "soft", "fluffy", "cuddly", "water", "cardboard",
                            "video", "game", "games", "ping", "pong", "table-tennis", "hex", "hexagonal", "desk",
                            "table", "bedside", "tomato", "sauce", "metal", "steel", "wooden", "popsicle", "swizzle",
                            "stir", "lolly", "chopping", "cutting", "bread", "test", "tube", "pipette", "lab",
                            "laboratory", "conical", "base", "lego", "fire", "race", "shipping",
                            "soup", "egg", "balloon", "kidney", "sharps", "biohazard", "emesis", "reading",
                            "tv", "flower", "leather", "tape", "label"})
"""Words that, just before a kind's name, make a compound people use for it ("coffee mug", "tin can", "rubber
duck", "teddy bear", "stuffed animal", "video game controller", "ping pong ball", "hex nut", "swizzle
stick", "popsicle stick"): read past there, a run of them too ("video game")."""
DRINKS = frozenset({"soda", "coke", "cola", "pop", "beer", "drink", "drinks", "fizzy", "juice"})
"""Words that say a thing holds a drink ("the soda can", "the coke"): never a food's tin or packet beside it."""
FOODS = frozenset({"soup", "ketchup", "mustard", "butter", "cereal", "bread", "jello", "gelatin", "tomato"})
"""Kinds that hold food: "the soda can" is not the soup can."""
THREAD_SIZE = re.compile(r"^m\d+(?:x\d+(?:[.,]\d+)?)?$")
"""A metric thread size before a fastener's kind ("the M8 bolt", "an m6x1.0 nut"): read past as a modifier."""


def is_modifier(word: str) -> bool:
    """Whether ``word`` (lower case) may open a compound before a kind's name (:data:`KIND_MODIFIERS`, a thread
    size)."""
    return word in KIND_MODIFIERS or THREAD_SIZE.match(word) is not None
BIG = frozenset({"big", "large", "bigger", "larger", "huge", "giant", "chunky", "bulky", "hefty"})
SMALL = frozenset({"small", "little", "tiny", "smaller", "littler", "mini", "teeny", "wee", "smol"})
TALL = frozenset({"tall", "taller"})
SHORT = frozenset({"short", "shorter", "low", "lower"})
MEDIUM = frozenset({"medium", "medium-sized", "medium-size", "mid-sized", "mid-size", "midsize", "middle-sized"})
SIZE_WORDS = BIG | SMALL | TALL | SHORT | MEDIUM
"""Size adjectives: they decide among the objects the rest of a description leaves (big/small by bulk,
tall/short by height) when the sizes differ clearly; with one object left they are read past."""
TIE_SIZE = 0.25
"""Two sizes closer than this fraction of the smaller one are a tie for "the big / small / tall one": a plain
size adjective asks for a difference a person sees at a glance (a 4 cm and a 5 cm cube, not 4.0 and 4.2 cm)."""


def kinds_of(o: SceneObject) -> set[str]:
    """The kinds an object is called by: its name when a word of 3+ letters, its mesh file's stem's first word."""
    return set(_kinds(*_kind_key(o)))


MESH_SHAPES = {"cube": "cube", "cubes": "cube", "cuboid": "box", "box": "box", "cylinder": "cylinder"}
"""A mesh's own kind that names a shape ("cube.obj", a mesh named "cylinder"): the mesh is that shape to look at, as
pybullet's toy blocks are (a 4.8 cm mesh cube is "the red block", "the red cube", one of "the two cubes")."""


def shape_of(o: SceneObject) -> str:
    """The shape an object looks like: its own ("cube", "box", "cylinder", "mesh"), or for a mesh whose own kind is a
    shape (:data:`MESH_SHAPES`) that shape."""
    if o.shape != "mesh":
        return o.shape
    return next((MESH_SHAPES[k] for k in sorted(own_kinds_of(o)) if k in MESH_SHAPES), "mesh")


def own_kinds_of(o: SceneObject) -> set[str]:
    """The kinds an object is by itself: its name when one word (after a dataset's number: "011_banana"), its mesh
    file's words; not the words of a name of several, which say what a user calls it ("butter_box" is called a box;
    its mesh, butter, is not a block)."""
    name, mesh, kind = _kind_key(o)
    parts = name_parts(name)
    word = parts[-1] if len(parts) == 2 and parts[0].isdigit() else name if len(parts) == 1 else ""
    return set(_kinds(word, mesh, kind))


def _kind_key(o: SceneObject) -> tuple[str, str | None, str | None]:
    """What an object's kinds depend on: its name, its mesh file and the kind its scene file declares (None for
    none)."""
    mesh = getattr(o, "mesh", None)
    return o.name, mesh if isinstance(mesh, str) and mesh else None, getattr(o, "kind", None) or None


SIZE_CODE = re.compile(r"(?<![a-z0-9])(\d{1,2})x(\d{1,2})(?![0-9])")
"""A size code in a name, studs by studs as a parts list writes it ("brick_2x4_red": 2x4): a kind its name gives it."""
def size_codes(name: str) -> set[str]:
    """The size codes a name holds, each both ways round ("brick_2x4_red": 2x4 and 4x2, the same brick turned)."""
    return {c for a, b in SIZE_CODE.findall(name.lower()) for c in (f"{int(a)}x{int(b)}", f"{int(b)}x{int(a)}")}


NAME_PART = re.compile(r"[A-Z]?[a-z]+|[A-Z]+(?![a-z])|\d+")
"""A word of a name as a user's file spells it: split at "_", "-", spaces, a change of case and digits
("coffee_mug", "milk-carton", "RedCube2", "obj3")."""
PLAIN_PARTS = frozenset({"obj", "object", "objects", "item", "thing", "block", "piece", "part", "model", "mesh",
                         "one"}) | SIZE_WORDS
"""Words of a name that say nothing of what the object is ("obj3", "big_block"): no kind."""
MESH_JARGON = frozenset({"vhacd", "chs", "coacd", "textured", "smooth", "visual", "vis", "collision", "col", "convex",
                         "hull", "simplified", "simple", "decomp", "lowpoly", "poly", "scaled", "final", "processed",
                         "watertight", "centered", "new", "old", "obj", "stl", "glb"})
"""Words a mesh file's stem holds about the file, not the thing ("duck_vhacd", "sphere_smooth"): no kind."""
LOOKED_UP_NOT = frozenset(SHAPE_NOUNS) | frozenset(COLORS) | PLAIN_PARTS
"""Words never looked up in WordNet (language/lexicon.py) nor given an object by it: a shape's noun and a colour
have readings of their own ("the box", "the red one"), and a plain word says nothing of what the object is."""
COMPOUND_HEADS = ("brush", "book", "paste", "box", "bowl", "cup", "pot", "pad", "jar", "lamp", "ball", "bottle", "case",
                  "board", "light", "phone", "glass", "tray", "pan", "plate", "stick", "bag", "bin", "clip", "knife",
                  "mug", "brick", "block", "cube")
"""The nouns a name written as one compound word ends with, which people say alone for it ("paintbrush", "the
brush"; "sketchbook", "the book"; "toothpaste", "my paste"), where three letters or more come before them."""


@functools.lru_cache(maxsize=4096)
def name_parts(name: str) -> tuple[str, ...]:
    """The words of a name, lower case and without accents (:data:`NAME_PART`): ("coffee", "mug"), ("cube", "b"),
    ("red", "cube", "2"), ("theiere",) for théière, as people type it without them."""
    return tuple(p.lower() for p in NAME_PART.findall(unaccented(name)))


def unaccented(text: str) -> str:
    """``text`` with its letters' accents taken off ("théière" -> "theiere", "König" -> "Konig"), and "ß" written
    "ss" as German does without it ("Gießkanne" -> "Giesskanne": one word, not "Gie" and "kanne")."""
    if text.isascii():
        return text
    return "".join(c for c in unicodedata.normalize("NFKD", text.replace("ß", "ss")) if not unicodedata.combining(c))


@functools.lru_cache(maxsize=4096)
def _kinds(name: str, mesh: str | None, kind: str | None = None) -> tuple[str, ...]:
    """The kinds an object is called by. A name of one word is its kind; of several, each of its words that says
    what the object is ("butter_box": butter and a box; never a colour, a size or "obj"). A mesh file's stem's words
    are kinds too, and a known kind a stem ends with ("tablelamp": a lamp); so are the words of the kind the scene
    file declares ("kind": "toy cow" for a toy named Daisy: a cow, and a toy). Kept by its words: every description
    read asks it of every object."""
    out: list[str] = [p for p in name_parts(kind or "") if len(p) >= 3 and p.isalpha() and p not in PLAIN_PARTS]
    # a declared word with accents is called as written too ("the théière", "the Gießkanne"), as a one-word name is
    out.extend(w for w in re.split(r"[ '-]", (kind or "").lower()) if len(w) >= 3 and w.isalpha() and not w.isascii())
    out.extend(sorted(size_codes(name)))  # "the red 2x4" (brick_2x4_red)
    low = name.lower()
    parts = name_parts(name)
    if len(parts) > 1:
        out.extend(p for p in parts if len(p) >= 3 and p.isalpha() and p not in PLAIN_PARTS and p not in COLORS)
        if len(parts) == 2 and parts[1].isalpha() and len(parts[1]) >= 3 and parts[0] not in COLORS \
                and parts[0].isalpha() and len(parts[0]) >= 3 and not parts[0].endswith("s"):
            out.append(parts[0] + "s")  # "the screws" for screw_box: what a box of them is called by
    elif len(low) >= 3 and low.isalpha():
        out.extend(dict.fromkeys((low, unaccented(low))))
    out.extend(h for p in parts if p.isalpha() for h in COMPOUND_HEADS if p.endswith(h) and len(p) - len(h) >= 3)
    if mesh is not None:
        for part in name_parts(mesh_stem(mesh)):
            if len(part) >= 3 and part.isalpha() and part not in MESH_JARGON and part not in PLAIN_PARTS:
                out.append(part)
                out.extend(k for k in KIND_NAMES if part.endswith(k) and len(part) - len(k) >= 3)
    return tuple(dict.fromkeys(out))


def mesh_stem(mesh: str) -> str:
    """A mesh file's name without its folders and extensions ("meshes/duck_vhacd.obj" -> "duck_vhacd")."""
    return re.split(r"[/:\\]", mesh)[-1].split(".")[0]


@functools.lru_cache(maxsize=256)
def abbreviations(names: tuple[str, ...]) -> frozenset[str]:
    """The letters of names written as capital codes ("CENT-2", "RACK-A": cent, rack), lower case: a word that starts
    with them ("the centrifuge") names that object, as a lab's inventory shortens its equipment's names. Kept per
    scene's names: every description asks."""
    return frozenset(part.lower() for name in names for part in CAPITAL_CODE.findall(unaccented(name)))


CAPITAL_CODE = re.compile(r"(?<![A-Za-z])[A-Z]{3,}(?![a-z])")


def abbreviated(word: str, scene: Scene) -> str | None:
    """The one capital code's letters ``word`` (lower case, five letters or more) starts with, or None."""
    if len(word) < 5 or not word.isalpha():
        return None
    fits = [a for a in abbreviations(tuple(scene.names)) if word.startswith(a) and word != a]
    return fits[0] if len(fits) == 1 else None


def scene_key(scene: Scene) -> tuple[tuple[str, str | None, str | None], ...]:
    """Each object's (name, mesh file, declared kind): all that the words for a scene's objects depend on (a key to
    keep them by). Kept by the objects themselves (language/kept.py): reading one sentence asks it hundreds of times
    of the same objects."""
    return _SCENE_KEYS.ask("scene_key", scene, lambda: tuple(_kind_key(o) for o in scene.objects))


_SCENE_KEYS = SceneMemo(256)


def kind_groups(scene: Scene) -> dict[str, frozenset[str]]:
    """Lower-case words that call objects by their kind -> the names of every object of that kind ("mug": both
    mugs): a noun that restricts a description ("the red mug") and alone fits them all."""
    return dict(kind_groups_of(scene_key(scene), lexicon.allowed()))


@functools.lru_cache(maxsize=256)
def kind_groups_of(objects: tuple[tuple[str, str | None, str | None], ...],
                   looked_up: bool = False) -> dict[str, frozenset[str]]:
    """kind_groups of a :func:`scene_key`, kept: made once per scene, not once per word looked up (reading one
    sentence asks for it hundreds of times). Kept answers are shared: a caller must not change one (kind_groups
    hands out copies). ``looked_up``: with the words WordNet relates to each kind (language/lexicon.py), where no
    table here gives the word an object."""
    by_kind: dict[str, set[str]] = {}
    for name, mesh, kind in objects:
        for k in _kinds(name, mesh, kind):
            by_kind.setdefault(k, set()).add(name)
    out = {k: frozenset(v) for k, v in by_kind.items()}
    own = dict(out)  # a word calls the objects of its kinds, never those another word called ("post-its": the
    # notepad's, not the Moleskine called a notepad)
    held = {name: set(parts[:-1]) for name, *_ in objects for parts in [name_parts(name)] if parts[-1:] and
            parts[-1] in CONTAINERS}
    for word, kinds in [*KIND_SYNONYMS.items(), *((w, FIGURES) for w in FIGURE_WORDS)]:
        named = frozenset().union(*(own[k] for k in kinds if k in own))
        if word in KIND_CLASSES:  # "the metal thing" is no screw_box: what a box holds is not what it is
            named = frozenset(n for n in named if not any(k in held.get(n, ()) for k in kinds))
        if named and word not in out:
            out[word] = named
    if looked_up:
        heads = tuple((name, tuple(sorted(_heads(name, mesh, kind)))) for name, mesh, kind in objects)
        for word, names in lexicon.groups_of(heads, LOOKED_UP_NOT, frozenset(KIND_NAMES)).items():
            out.setdefault(word, names)
        for name, *_ in objects:  # "the nappies" for diaper_pack: a package called by what it holds
            parts = name_parts(name)
            if len(parts) == 2 and parts[1] in PACKAGES and parts[0].isalpha() and parts[0] not in LOOKED_UP_NOT:
                for word in lexicon.same_as(parts[0]) - LOOKED_UP_NOT:
                    out.setdefault(word, frozenset({name}))
    return out


PACKAGES = frozenset({"pack", "packet", "box", "carton", "bag", "sack", "jar", "tub", "tin", "case", "crate"})
"""What a name's last word may call a package of what its first word names ("diaper_pack", "egg_carton")."""


def _heads(name: str, mesh: str | None, kind: str | None) -> set[str]:
    """The words that say what an object is, as a noun phrase's last word does: of its declared kind, its name and
    its mesh file's stem, the last word of three letters or more ("coffee_cup": a cup, not coffee)."""
    heads = set()
    for text in (kind or "", name, mesh_stem(mesh) if mesh else ""):
        words = [p for p in name_parts(text) if len(p) >= 3 and p.isalpha() and p not in MESH_JARGON]
        if words:
            heads.add(words[-1])
    return heads


CONTAINERS = frozenset({"box", "jar", "bin", "bag", "dish", "tray", "tin", "pot", "bowl", "cup", "holder", "rack",
                        "case", "tub", "crate", "basket", "bottle", "carton"})
"""The last word of a name that says the object holds what the words before it name ("screw_box", "soap_dish")."""


def kind_words(scene: Scene) -> dict[str, str]:
    """Lower-case words that call exactly one object by its kind -> its name: "duck" (the mesh's kind), "cup"
    (a mug's everyday name). A kind that two objects share names neither (the description is then refused)."""
    return dict(kind_words_of(scene_key(scene), lexicon.allowed()))


@functools.lru_cache(maxsize=256)
def kind_words_of(objects: tuple[tuple[str, str | None, str | None], ...], looked_up: bool = False) -> dict[str, str]:
    """kind_words of a :func:`scene_key`, kept as :func:`kind_groups_of` (a caller must not change it)."""
    return {w: next(iter(names)) for w, names in kind_groups_of(objects, looked_up).items() if len(names) == 1}
