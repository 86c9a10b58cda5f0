"""Objects named by numbers, as people say them: "6", "#6", "number 6", "no. 6", "object six", "cube 1" (for
Cube_01), "block one" (for block1), and a description with the number in apposition ("the red one, number 2").

A scene's names that are digits or end in digits ("1", "block1", "Cube_01", "obj3") are numbered, and so are names
that open with digits before their words ("002_master_chef_can", as the YCB object set names its files); a number said
names the object whose name ends (or so opens) with it (leading zeros aside), and a word before the number says which
where several end so ("cube 1": Cube_01, not Apple_01). A number spelled out ("six") names an object only where the
scene has that number, and never after a determiner ("the two cubes", "that one", "the two" are counts and pointers,
not names).

A description said with the number ("the small green cube, number 7") must fit the numbered object, and where it picks
another object by itself ("the big red one, number 1" with 2 the bigger red one) the line is refused, naming both: a
refusal beats a wrong block.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Callable, Iterable

from ..core.scene import Scene, SceneObject
from ..errors import L2PError, LanguageError, UnknownObjectError
from .reference_words import BLOCK_SHAPES, DETERMINERS, NOUNS
from .shape_words import SHAPE_NOUNS
from .synonyms import NAME_PART, kind_groups, kinds_of, size_codes

SPELLED = {w: n for n, w in enumerate(
    "zero one two three four five six seven eight nine ten eleven twelve thirteen fourteen fifteen sixteen seventeen "
    "eighteen nineteen twenty".split())}
"""Numbers people spell out when they dictate ("move six round four")."""
MARKERS = frozenset({"number", "no", "nr", "num", "#", "n°", "nº", "no.", "nr.", "num."})
"""Words that say the next word is a number that names an object ("number 5", "no. 6", "# 6")."""
LABELS = (NOUNS - {"one"}) | frozenset(w for w in SHAPE_NOUNS if not w.endswith("s")) | frozenset(
    {"obj", "element", "unit", "shape", "toy"})
"""Nouns said right before a number as its label ("object one", "cube no. 6"): they name a kind, never a count."""
GENERIC = frozenset({"object", "obj", "item", "thing", "piece", "part", "element", "unit", "shape", "block", "toy"})
"""Labels that fit any object ("object 4", "block 4": "block" covers any object, docs/perform.md)."""
BLOCKY = frozenset({"cube", "box", "brick", "block"})
"""Labels people give any block-shaped object, a cube or a box alike ("cube 4" for a brick-shaped box)."""
RELATION_ENDS = frozenset({"to", "of", "from", "nearest", "closest", "farthest", "furthest", "than", "and", "or",
                           "near", "by", "beside", "behind", "between", "with", "at", "in", "on", "next", "toward",
                           "towards", "under", "over", "besides", "except", "not"})
"""Words a description before "number N" cannot end with: "the cube nearest number 2" measures from number 2. The
actions' own words are not listed (the actions declare them; a description ending in one is read, and refused where
it names another object than the number)."""


def number_of(word: str) -> int | None:
    """The number a word says ("6", "06", "#6", "six"), or None."""
    low = word.lower().strip(".,;:!?")
    if low.startswith("#"):
        low = low[1:]
    if low.isdigit() and len(low) <= 4:
        return int(low)
    return SPELLED.get(low)


UNIT_SAID = {"mm": "mm", "mil": "mm", "mils": "mm", "millimeter": "mm", "millimeters": "mm", "millimetre": "mm",
             "millimetres": "mm", "cm": "cm", "centimeter": "cm", "centimeters": "cm", "centimetre": "cm",
             "centimetres": "cm", "ml": "ml", "milliliter": "ml", "milliliters": "ml", "millilitre": "ml",
             "millilitres": "ml", "in": "in", "inch": "in", "inches": "in", "v": "v", "volt": "v", "volts": "v",
             "w": "w", "watt": "w", "watts": "w", "g": "g", "gram": "g", "grams": "g", "kg": "kg", "l": "l",
             "litre": "l", "liter": "l"}
"""A measure's unit as people say it -> as a name writes it after its number ("wrench_10mm": "the 10 mil")."""


def _number_at(parts: list[str]) -> int | None:
    """Where in a name's words its number stands: last ("block1"), before a unit it measures ("wrench_10mm"), or
    first ("002_master_chef_can", as YCB names); None where it has none."""
    if parts and parts[-1].isdigit() and len(parts[-1]) <= 4:
        return len(parts) - 1
    if len(parts) > 2 and parts[-1].lower() in UNIT_SAID.values() and parts[-2].isdigit() and len(parts[-2]) <= 4:
        return len(parts) - 2
    if len(parts) > 1 and parts[0].isdigit() and len(parts[0]) <= 4:
        return 0
    return None


@functools.lru_cache(maxsize=256)
def _numbered_of(names: tuple[str, ...]) -> dict[int, tuple[str, ...]]:
    out: dict[int, list[str]] = {}
    for name in names:
        parts = NAME_PART.findall(name)
        at = _number_at(parts)
        if at is not None:
            out.setdefault(int(parts[at]), []).append(name)
    return {k: tuple(v) for k, v in out.items()}


@functools.lru_cache(maxsize=256)
def units_said(names: tuple[str, ...]) -> frozenset[str]:
    """The words people say for the units the scene's names carry after their numbers ("mil", "millimeter" where
    wrench_10mm stands), kept per scene's names: a reference is read many times a sentence."""
    carried = {unit_of(name) for name in names} - {None}
    return frozenset(said for said, unit in UNIT_SAID.items() if unit in carried)


def unit_of(name: str) -> str | None:
    """The unit a name's number measures ("wrench_10mm": mm), or None."""
    parts = NAME_PART.findall(name)
    at = _number_at(parts)
    return parts[-1].lower() if at is not None and at == len(parts) - 2 else None


def numbered(scene: Scene) -> dict[int, tuple[str, ...]]:
    """Number -> the scene's names that end in it ("1", "block1", "Cube_01" all end in 1), in the scene's order."""
    return _numbered_of(tuple(scene.names))


def stem(name: str) -> tuple[str, ...]:
    """The words of a name besides its number, lower case ("Cube_01": cube; "obj3": obj; "1": none;
    "002_master_chef_can": master, chef, can)."""
    parts = NAME_PART.findall(name)
    at = _number_at(parts)
    if at == 0 and not parts[-1].isdigit():
        return tuple(p.lower() for p in parts[1:])
    return tuple(p.lower() for p in parts[:-1 if at is None or at == len(parts) - 1 else at])


def number_name(word: str, scene: Scene) -> str | None:
    """The one object a lone word names by its number ("4", "#4", "four" where the scene has a 4); None otherwise."""
    n = number_of(word)
    names = numbered(scene).get(n, ()) if n is not None else ()
    return names[0] if len(names) == 1 else None


def _looks(o: SceneObject) -> str:
    """An object as a person sees it: "a red cube", "a yellow cylinder"."""
    kinds = sorted(kinds_of(o)) if o.shape == "mesh" else []
    what = o.shape if o.shape in ("cube", "box", "cylinder") else (kinds[0] if kinds else "object")
    return f"{'an' if o.color[0] in 'aeiou' else 'a'} {o.color} {what}"


def number_reference(text: str, scene: Scene, role: str, resolve: Callable[..., str]) -> str | None:
    """The object ``text`` names by a number at its end ("number 5", "#5", "cube 1", "object one", "the red one,
    number 2"); None where ``text`` is no such reference or the scene numbers nothing (the other readers then read
    it). A number the scene does not have, a label that does not fit ("cylinder 2" where 2 is a cube) and a
    description that contradicts the number are one-line errors (``resolve``: how one description is resolved,
    language/references.resolve_object)."""
    table = numbered(scene)
    words = [w for w in (x.strip(",;:") for x in text.split()) if w]
    if not table or not words:
        return None
    words = _number_last(words, table, UNITS | units_said(tuple(scene.names)))
    low = [w.lower() for w in words]
    n = number_of(low[-1])
    if n is None and low[-1] in HEARD_NUMBERS and len(low) > 1 and low[-2] in _stems(table):
        n = HEARD_NUMBERS[low[-1]]  # "cube too", "cylinder won": the number as speech-to-text heard it
    if n is None:
        return None
    spelled = low[-1].lstrip("#").isalpha()
    marked = low[-1].startswith("#")
    end = len(low) - 1
    if not marked and end > 0 and low[end - 1] in MARKERS:
        marked, end = True, end - 1
    before = [w for w in low[:end] if w not in DETERMINERS]
    said = " ".join(words)
    if not before:  # "6", "the 6", "#6", "number six"; never "the two", "that one"
        if n not in table or (spelled and not marked and end > 0):
            if marked:
                raise _missing(n, table, said, scene)
            tail = _by_tail(low[-1], table)  # "the 72" for SKU-4472, as a picker says the last digits
            return tail  # None for "8": the other readers say it is no block's name
        return _the_one(table[n], n, said)
    if n not in table:
        if marked or (len(before) == 1 and before[0] in LABELS):
            raise _missing(n, table, said, scene)
        return None
    if not marked:
        if len(before) == 1 and (before[0] in LABELS | _stems(table) or before[0] in kind_groups(scene)):
            # "object one", "cube 1", "block one", "the 10mm spanner" (wrench_10mm: a spanner is a wrench)
            return _labelled(n, before[0], table[n], said, scene, resolve)
        return None  # "the cube nearest block 2", "the red 1": other readers'
    if low[end - 1] in RELATION_ENDS:
        return None
    return _apposed(n, " ".join(words[:end]), table[n], said, scene, role, resolve)


def _by_tail(said: str, table: dict[int, tuple[str, ...]]) -> str | None:
    """The one object whose number of three digits or more ends in ``said`` (two digits or more, fewer than its own):
    "the 72" for SKU-4472 beside SKU-4471. None where none or several do."""
    if not said.isdigit() or len(said) < 2:
        return None
    fits = [names for n, names in table.items() if len(str(n)) >= 3 and len(str(n)) > len(said)
            and str(n).endswith(said)]
    return fits[0][0] if len(fits) == 1 and len(fits[0]) == 1 else None


UNITS = frozenset({"ml", "l", "cl", "dl", "ul", "\u00b5l", "g", "kg", "mg", "oz", "lb"})
"""Units of what an object holds or weighs, said after a number that names it ("the 500 ml beaker" for beaker_500,
"the 250ml"). Lengths are not among them: "the 5 cm cube" is a size (descriptions.said_measure), not block5."""
MEASURED = re.compile(r"^(?P<n>\d{1,4})(?P<unit>[a-z\u00b5]{1,2})$", re.IGNORECASE)
"""A number with its unit written on it ("250ml", "500mL")."""


def _number_last(words: list[str], table: dict[int, tuple[str, ...]], units: frozenset[str]) -> list[str]:
    """``words`` with a number said before its noun moved after it: "the 500 ml beaker" -> "the beaker 500", "250
    beaker" -> "beaker 250", "the 250ml" -> "the 250", "the 500 ml one" -> "the 500", where the scene numbers an object
    so (beaker_500); ``words`` as they are where no number the scene has opens them after a determiner. ``units``:
    the units said after such a number (:data:`UNITS`, and those the scene's names carry)."""
    low = [w.lower() for w in words]
    i = next((k for k, w in enumerate(low) if w not in DETERMINERS), len(low))
    glued = MEASURED.match(low[i]) if i < len(low) else None
    if i >= len(low) - 1 and glued is None:
        return words
    said = glued.group("n") if glued is not None and glued.group("unit").lower() in units else low[i]
    after = low[i + 1] if i + 1 < len(low) and glued is None else None
    if after in units and number_of(said) is not None:  # "the ten millimeter wrench"
        said = str(number_of(said))
    if not said.isdigit() or int(said) not in table:
        return words
    j = i + 1 + (after in units)
    return [*words[:i], *(w for w in words[j:] if w.lower() != "one"), said]


def _stems(table: dict[int, tuple[str, ...]]) -> set[str]:
    return {w for names in table.values() for name in names for w in stem(name) if w.isalpha()}


def _missing(n: int, table: dict[int, tuple[str, ...]], said: str, scene: Scene) -> UnknownObjectError:
    """The error for a number said that no object of the scene has."""
    return UnknownObjectError(f'nothing in the scene is numbered {n} ("{said}"; numbered: '
                              f'{", ".join(str(k) for k in sorted(table))})', said, scene.names)


def _the_one(names: tuple[str, ...], n: int, said: str) -> str:
    """The one of ``names`` (objects numbered ``n`` the words fit); several are asked about."""
    if len(names) > 1:
        raise LanguageError(f'"{said}" is ambiguous: {len(names)} objects are numbered {n} ({", ".join(names)}); '
                            "name the one you mean")
    return names[0]


def _labelled(n: int, label: str, names: tuple[str, ...], said: str, scene: Scene,
              resolve: Callable[..., str]) -> str:
    """The one of ``names`` (the objects numbered so) that ``label`` fits ("cube 1": Cube_01 of those numbered 1)."""
    fits = tuple(m for m in names if _label_fits(label, scene.get(m), scene, resolve))
    if not fits:
        raise UnknownObjectError(f'nothing in the scene is "{said}": {names[0]} is {_looks(scene.get(names[0]))}, '
                                 f"not a {label}" if len(names) == 1 else
                                 f'nothing in the scene is "{said}" (numbered so: {", ".join(names)})',
                                 said, scene.names)
    return _the_one(fits, n, said)


def _label_fits(label: str, o: SceneObject, scene: Scene, resolve: Callable[..., str]) -> bool:
    """Whether an object may be called ``label`` before its number: any object an "object", the block-shaped ones a
    "cube" or a "brick" alike, an object its name's own word ("cube" for Cube_01), else as the description says."""
    if label in GENERIC or label in stem(o.name) or (label in BLOCKY and o.shape in BLOCK_SHAPES):
        return True
    try:
        return resolve(f"the {label}", scene.only([o.name])) == o.name
    except L2PError:
        return False


def _apposed(n: int, description: str, names: tuple[str, ...], said: str, scene: Scene, role: str,
             resolve: Callable[..., str]) -> str:
    """The one of ``names`` (the objects numbered ``n``) that ``description`` fits ("the red one, number 2"); refused
    where it fits none of them or picks another object by itself."""
    fits = _fits(description, names, scene, role, resolve)
    if not fits:
        if len(names) > 1:
            raise UnknownObjectError(f'nothing numbered {n} is "{description}" ({", ".join(names)})', said,
                                     scene.names)
        raise UnknownObjectError(f'"{description}" and number {n} name different objects: {names[0]} is '
                                 f"{_looks(scene.get(names[0]))}{_elsewhere(description, scene, role, resolve)}; "
                                 "say which you mean", said, scene.names)
    name = _the_one(tuple(fits), n, said)
    try:
        alone = resolve(description, scene, role)
    except L2PError:
        return name  # "the red one" fits two objects: the number says which
    if alone != name:
        raise LanguageError(f'"{description}" and number {n} name different objects: "{description}" is {alone}, '
                            f"{name} is {_looks(scene.get(name))}; say which you mean")
    return name


def _fits(description: str, names: Iterable[str], scene: Scene, role: str, resolve: Callable[..., str]) -> list[str]:
    """Those of ``names`` that ``description`` fits, each asked alone (as if the only object on the table)."""
    fits = []
    for name in names:
        try:
            if resolve(description, scene.only([name]), role) == name:
                fits.append(name)
        except L2PError:
            pass
    return fits


def _elsewhere(description: str, scene: Scene, role: str, resolve: Callable[..., str]) -> str:
    """", and "the blue one" is 3" (or "fits 3, 4") where the description fits other objects; "" where it fits
    none."""
    fits = _fits(description, scene.names, scene, role, resolve)
    if not fits:
        return ""
    return f', and "{description}" {"is" if len(fits) == 1 else "fits"} {", ".join(fits)}'


APPOSED = re.compile(r"^(?P<number>(?:(?:number|no\.?|nr\.?|num\.?)\s+|#\s*)\w+)(?:\s+[-\u2013\u2014]|\s*[:,])\s+"
                     r"(?P<rest>.+)$", re.IGNORECASE)
"""A number in apposition after a topic's description: "the red one, number 2 - move it closer to 1"."""


def apposed(what: str, rest: str) -> tuple[str, str]:
    """A topic said before a comma and what follows it, with a number said in apposition after the comma taken into
    the topic ("the red one" + "number 2 - move it ..." -> "the red one number 2" + "move it ..."); as they are
    where ``rest`` opens with no such number."""
    m = APPOSED.match(rest)
    if m is None or number_of(m.group("number").split()[-1]) is None:
        return what, rest
    return f"{what} {m.group('number')}", m.group("rest")


HEARD_NUMBERS = {"won": 1, "to": 2, "too": 2, "tree": 3, "for": 4, "fore": 4, "ate": 8}
"""Words speech-to-text writes for a number said in a size code ("the blue to buy to": the blue two by two)."""
_NUMBER_SAID = r"(\d{1,2}|" + "|".join([*SPELLED, *HEARD_NUMBERS]) + r")"
CODE_SAID = re.compile(r"\b" + _NUMBER_SAID + r"\s*(?:x|\u00d7|by|buy|bye)\s*" + _NUMBER_SAID + r"\b",
                       re.IGNORECASE)
"""A size code as people say or type it: "2x4", "2 x 4", "2 by 4", "two by four", and as speech-to-text hears it
("to buy to", "one by for"); read as a code only where a name holds it."""


def _said(word: str) -> int | None:
    return HEARD_NUMBERS.get(word.lower(), number_of(word))


def codes_said(sentence: str, scene: Scene) -> str:
    """``sentence`` with each size code said as the scene's names write it ("the red two by four" -> "the red 2x4"),
    where some name holds that code; as it is otherwise (so "by" stays the preposition it is everywhere else)."""
    codes = {c for n in scene.names for c in size_codes(n)}
    if not codes:
        return sentence

    def code(m: re.Match) -> str:
        said = f"{_said(m.group(1))}x{_said(m.group(2))}"
        return said if said in codes else m.group(0)

    return CODE_SAID.sub(code, sentence)
