"""An object said by what it is for or what it has: "the thing you boil water in", "the one with all the holes", "the
thing I drink from", "thing for flowers", "the cup with the handle", "the stirry thing", "the jingly things".

People who forget a thing's word say what it does. Each kind people keep on a table has the words of its uses and
parts (:data:`USES`: a kettle boils water and has a spout, a colander has holes and drains pasta); a use said with
the preposition that tells a tool from what it works on is kept as two words ("cut on" is the board, "cut with" the
knife). A description of a generic thing (or a kind) followed by what it does or has names the one object of the
scene whose kind has such a use; where several have, it is asked; where none has, the description is left to the
other readers.
"""

from __future__ import annotations

import re
from collections.abc import Callable

from ..core.scene import COLORS, Scene, SceneObject
from ..errors import LanguageError
from .reference_words import (
    COLOR_SYNONYMS,
    DETERMINERS,
    FARTHEST,
    KIND_WORDS,
    NEAREST,
    NOUNS,
    PLACE_ADJECTIVES,
)
from .shape_words import SHAPE_NOUNS
from .synonyms import KIND_NAMES, SIZE_WORDS, kinds_of

_DRINK = ("drink", "drinking", "sip", "coffee", "tea")
USES: dict[str, tuple[str, ...]] = {
    "mug": (*_DRINK, "handle"), "cup": (*_DRINK, "handle"), "teacup": (*_DRINK, "handle"), "glass": _DRINK,
    "tumbler": _DRINK, "beaker": _DRINK, "bottle": ("drink", "drinking", "sip", "water", "pour"),
    "kettle": ("boil", "boiling", "spout", "hot water", "whistle", "handle"),
    "teapot": ("tea", "pour", "spout", "brew", "handle"),
    "kyusu": ("tea", "pour", "spout", "brew"), "colander": ("hole", "drain", "strain", "pasta"),
    "whisk": ("beat", "whip", "egg", "stir", "wire", "whisking"), "ladle": ("soup", "scoop", "serve", "ladling"),
    "spoon": ("stir", "eat", "soup", "scoop"), "fork": ("eat", "prong"),
    "knife": ("cut with", "slice", "blade", "sharp"), "scalpel": ("cut with", "blade", "sharp", "incision"),
    "board": ("chop", "cut on", "chop on", "chopping"), "plate": ("eat off", "eat from", "serve", "food"),
    "bowl": ("eat out", "soup", "cereal", "mix"), "phone": ("call", "ring", "text", "calls"),
    "glasses": ("see", "read with", "eyes", "sight", "wear on"), "lamp": ("light", "glow", "shine", "bulb"),
    "wallet": ("money", "cash", "card", "pay", "leather"), "keys": ("lock", "unlock", "door", "jingle"),
    "vase": ("flower",), "book": ("read", "story", "page"), "candle": ("wax", "flame", "burn", "wick"),
    "remote": ("tv", "channel", "television", "telly"), "scanner": ("scan", "beep", "barcode"),
    "tape": ("seal", "sealing", "taping"), "label": ("label", "stick on", "address"),
    "forceps": ("grab", "pick up", "pinch", "grip"), "tweezers": ("grab", "pluck", "pinch", "grip"),
    "syringe": ("inject", "injection", "shot", "jab", "plunger"), "gauze": ("bandage", "wound", "dressing", "bleed"),
    "sharps": ("dispose", "throw", "needle"), "iron": ("press", "clothes", "ironing", "crease", "wrinkle"),
    "thimble": ("sew", "sewing", "finger"), "car": ("wheel", "drive", "vroom"),
    "truck": ("wheel", "drive", "fire", "ladder", "siren"), "hat": ("head", "brim"),
    "boot": ("foot", "feet", "walk", "lace"), "shoe": ("foot", "feet", "walk", "lace"),
    "ball": ("kick", "bounce", "throw"), "pen": ("write", "writing", "ink"), "marker": ("write", "draw", "ink"),
    "sharpie": ("write", "draw", "ink"), "pencil": ("write", "draw"), "notebook": ("write in", "note"),
    "stapler": ("staple",), "scissors": ("cut with", "snip"), "centrifuge": ("spin",),
    "rack": ("hold tube", "holds tube"), "wrench": ("bolt", "nut", "tighten", "loosen"),
    "spanner": ("bolt", "nut", "tighten", "loosen"), "screwdriver": ("screw",), "mallet": ("hit", "bang", "pound"),
    "hammer": ("hit", "bang", "nail", "pound"), "measure": ("measure", "measuring"),
    "ruler": ("measure", "measuring", "line", "lines"), "glue": ("glue", "stick on", "sticky", "gluing"),
    "crayon": ("colour", "color", "colouring", "coloring", "draw"), "paint": ("paint", "painting"),
    "teddy": ("cuddle", "hug"), "dino": ("roar", "rawr"), "dog": ("bark", "woof"), "duck": ("quack", "bath"),
}
"""A kind -> the words of its uses and parts; two words where the preposition tells a tool from what it works on."""

OPENER = re.compile(r"^(?P<head>(?:(?:the|that|a|an|this|my|your)\s+)?(?:[\w-]+\s+){0,3}?[\w-]+)\s+"
                    r"(?P<rest>(?:that|which|you|u|i|we|people|for|with|used)\b.+)$", re.IGNORECASE)
"""A description, then what the thing does or has: "the thing you ...", "thing for ...", "the one with ..."."""
PLACED = NEAREST | FARTHEST | frozenset(PLACE_ADJECTIVES) | frozenset({
    "next", "behind", "between", "moved", "middle", "centre", "center", "corner", "biggest", "smallest", "tallest",
    "than", "other"})
"""Words of where a thing is or what was done with it: a description with them is no use said."""
LINKING = frozenset({"to", "of", "at", "on", "in", "from", "with", "for", "and", "or", "n", "&", "plus", "goes", "go",
                     "is", "that", "until", "till", "til", "so", "they", "it", "them", "then", "but", "when", "if",
                     "very", "really", "only", "any", "many", "nearly", "slightly", "early", "lovely"})
"""Words that join a description to more than its noun: a use said before the noun is a few words, never these."""
GENERIC = frozenset({"thing", "things", "one", "ones", "thingy", "stuff", "whatsit", "object", "item", "tool"})
THING_NOUNS = KIND_WORDS | NOUNS | frozenset(SHAPE_NOUNS)
"""Nouns a use said as an adjective may stand before ("the holey bowl"): words for things."""
_Y_FORM = re.compile(r"^(?P<stem>[a-z]+?)(?P<double>[a-z])?\2?(?:ey|y|ly)$")


def used_for(text: str, scene: Scene, try_object: Callable[[str, Scene], str | None]) -> str | None:
    """The object ``text`` names by its use or a part (module docstring); None where it is not said so or no object's
    kind has that use. Refused where several have. ``try_object``: how a description is read
    (language/references.try_object), to tell a noun that names a thing of its own."""
    m = OPENER.match(text.strip())
    if m is not None:
        head, said = m.group("head").lower().split(), _words(m.group("rest"))
        if set(said) & PLACED:  # "the one that is nearest the tea": a place, read by the place readers
            return None
    else:  # "the stirry thing", "the holey bowl", "the hot water thing": a use said before the noun
        words = [w for w in text.lower().split() if w not in DETERMINERS]
        used = [w for w in words[:-1] if w not in SIZE_WORDS and COLOR_SYNONYMS.get(w, w) not in COLORS]
        if not used or len(words) > 4 or set(words) & (PLACED | LINKING) or not (
                words[-1] in GENERIC or (len(words[-2]) >= 5 and _Y_FORM.match(words[-2])
                                         and words[-1].rstrip("s") in THING_NOUNS)):
            return None
        head, said = words, [s for w in used for s in _stems(w)]
    pool = _pool(head, scene)
    fits = [o for o in pool if _has(o, said, m is None)]
    if not fits and m is None and try_object(f"the {head[-1]}", scene) is None:
        # "the holey bowl" is the colander where no bowl is on the table: the use says more than the noun
        fits = [o for o in _pool([*head[:-1], "thing"], scene) if _has(o, said, True)]
    if not fits:
        return None
    if len(fits) > 1:
        raise LanguageError(f'"{text}" is ambiguous: it fits {len(fits)} objects ({", ".join(o.name for o in fits)}); '
                            "name the one you mean")
    return fits[0].name


def _words(rest: str) -> list[str]:
    """The words of what a thing is said to do, each as said and without a plural's or a verb's ending."""
    out = []
    for w in re.findall(r"[a-z]+", rest.lower()):
        out.append(w)
        for end in ("es", "s", "ing", "ed"):
            if w.endswith(end) and len(w) - len(end) >= 3:
                out.append(w[: -len(end)])
    return out


def _stems(word: str) -> list[str]:
    """What an adjective made of a word says: "stirry" -> stir, "holey" -> hole, "jingly" -> jingle, "spoony" ->
    spoon, "cutting" -> cut."""
    if word.endswith("ing") and len(word) > 5:  # "the cutting thing": cut; "the measuring one": measure
        stem = word[:-3]
        return list(dict.fromkeys([word, stem, stem + "e", stem[:-1] if stem[-1] == stem[-2] else stem]))
    m = _Y_FORM.match(word)
    if m is None:
        return [word, word[:-1]] if word.endswith("s") and len(word) > 4 else [word]
    stem = m.group("stem") + (m.group("double") or "")
    return list(dict.fromkeys([word, stem, stem + "e", m.group("stem"), word[:-1], word[:-1] + "e", word[:-2],
                               word[:-2] + "e"]))


def _pool(head: list[str], scene: Scene) -> list[SceneObject]:
    """The objects the description before the use may name: by its colour words and, unless its noun is a generic
    one, by its noun as a kind ("the cup with the handle": the cups)."""
    colours = {COLOR_SYNONYMS.get(w, w) for w in head} & set(COLORS)
    pool = [o for o in scene.objects if not colours or o.color in colours]
    noun = head[-1]
    if noun in GENERIC:
        return pool
    return [o for o in pool if noun in kinds_of(o) or any(noun in KIND_NAMES.get(k, ()) for k in kinds_of(o))]


def _has(o: SceneObject, said: list[str], named: bool = False) -> bool:
    """Whether a use or a part of one of ``o``'s kinds is among the words ``said`` (a use of two words, in order);
    with ``named`` (a use said before the noun), also the kind's own word ("the spoony thing": a spoon, the ladle)."""
    joined = " ".join(said)
    for kind in kinds_of(o):
        if named and (kind in said or set(said) & set(KIND_NAMES.get(kind, ()))):
            return True
        for use in USES.get(kind, ()):
            if named and " " in use and use.split()[0] in said:  # "the cutting thing": what it cuts with
                return True
            if (" " in use and re.search(rf"\b{use.split()[0]}\w*\s+(?:\w+\s+)?{use.split()[1]}\b", joined)) or (
                    " " not in use and use in said):
                return True
    return False


__all__ = ["USES", "used_for"]
