"""What a clause points at beyond a plain pronoun: an object shown before the command ("See the cylinder? Move
it next to C", "Take the blue cube and slide it toward E", "the green cube - move it past B"), both objects of
the previous clause ("then move them both away from E") and the previous command again on another object
("Now do the same with the red cube").

Each reading is tried only on a clause that does not resolve as it stands (``chain/clauses.py``), so it adds
sentences the grammar understands and changes none it already did.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace

from ..core.scene import Scene
from ..errors import L2PError, LanguageError, UnknownObjectError
from ..language import Command, Context, resolve_object, split_verb
from ..language.grammar import ARROWS
from ..language.group_places import placed_group
from ..language.naming import name_words, naming_words
from ..language.numbers import number_of
from ..language.partitives import group_of
from ..language.pronouns import plural_named, said_in_plural
from ..language.reference_words import BLOCK_WORDS, KIND_WORDS, NOUNS
from ..language.references import try_object, two_references
from ..language.shape_words import SHAPE_NOUNS
from ..language.words import PACES, strip_polite
from ..pipeline import resolve
from . import again
from .goal_after import goal_after

_SHOW = (r"(?:do\s+you\s+see|you\s+see|can\s+you\s+see|(?:who|everyone|everybody)\s+(?:can\s+)?see|see|look\s+at"
         r"|watch|there's|there\s+is|here's|here\s+is|find"
         r"|(?:have\s+you\s+)?got"
         r"|take|grab|get|pick\s+up|lift|hold\s+up)")
_ASKED = r"(?:(?:now|then|so|ok|okay|first|please|and|can\s+you|could\s+you|would\s+you)\s*,?\s+)*"
SHOWN = re.compile(rf"^\s*{_ASKED}{_SHOW}\s+(?P<what>.+?)\s*\??\s*$", re.IGNORECASE)
"""A clause that only shows objects: "See the cylinder?", "Pick up the duck", "Now find the little red cube",
"Can you find the toy closest to you"."""
TOPIC = re.compile(r"^\s*(?P<what>.+?)(?:\s+[-\u2013\u2014]|\s*[:,]|\s*(?:\.\.+|\u2026))\s+(?P<rest>.+)$")
"""An object named first, then the command about it: "the green cube - move it toward the blue one", "the
teddy, put it beside the can", "Q and R: slide them both toward P"."""
STATEMENT = re.compile(r"^\s*(?P<what>.+?)\s+(?:is|are|r|looks|seems|sits|stands|lies)\b(?P<said>.*)$", re.IGNORECASE)
"""A clause that says something about objects and asks for nothing: "The white box is in the way", "The teddy
looks lonely"; what comes next points at them ("... slide it past the cylinder")."""
TOGETHER = re.compile(r"^\s*(?:(?:far|way|much|a\s+bit)\s+)?too\s+(?:close|near)\s+"
                      r"(?:together|to\s+each\s+other)\s*[.!]?\s*$", re.IGNORECASE)
"""What a statement about two objects says when it only points at them: "The mug and the jar are too close
together"."""
TOO_CLOSE = re.compile(r"^\s*(?P<what>.+?)(?:(?:\s+(?:is|are|sits|stands|sit|stand)|'s|'re)(?:\s+(?:sitting|standing))?"
                       r"|\s+(?:shouldn't|should\s+not|mustn't)\s+be)\s+(?:both\s+)?"
                       r"(?:(?:far|way|much|a\s+bit|rather|really|quite|very|so|this|that|awfully|kinda)\s+)?"
                       r"(?:(?:too\s+)?(?:close|near)(?:\s+to)?|in\s+the\s+way\s+of)\s+(?P<other>.+?)\s*[.!]?\s*$",
                       re.IGNORECASE)
"""A statement of what is wrong between two objects: "The cup is too near to the duck", "The stone is in the way
of the jar", "The white cube is rather close to the cup", "A shouldn't be so near B"; what comes next moves the first
("Move it away": from the second)."""
NOW_SAID = re.compile(r"^\s*(?:right\s+now|currently|at\s+the\s+moment|at\s+present|as\s+it\s+stands|presently)"
                      r"\s*,?\s+(?P<rest>.+)$", re.IGNORECASE)
"""A statement of how the table is now, said first: what comes next points at its subject."""
THERE = re.compile(r"^\s*(?:there\s+(?:are|r|is)\s+(?P<what>.+?)(?:\s+(?:here|there|on\s+the\s+table))?"
                   r"|of\s+(?P<of>the\s+two\s+.+?))\s*[.!]?\s*$", re.IGNORECASE)
"""A clause that says which objects there are: "There are two green cubes"; what comes next picks among them
("... push the big one toward S and the other one away from the bunny")."""
ORDER = re.compile(r"\s*,?\s*(?:(?P<first>(?:the\s+)?[\w-]+(?:\s+[\w-]+)?)(?:\s+one)?\s+first"
                   r"(?P<then>\s*,?\s*(?:and\s+)?(?:then|after)\s+(?:the\s+)?[\w-]+(?:\s+[\w-]+)?(?:\s+one)?)?"
                   r"|first\s+(?P<lead>(?:the\s+)?[\w-]+(?:\s+[\w-]+)?)(?:\s+one)?\s*,?\s*"
                   r"(?:then|after|afterwards|and\s+then)\s+(?:the\s+)?[\w-]+(?:\s+[\w-]+)?(?:\s+one)?)\s*[.!]?\s*$",
                   re.IGNORECASE)
"""Which of two objects moved alike goes first, said at the end: ", the red one first", ", white first", ", first
the big, after the small"."""
AND_SIGNS = re.compile(r"\s+[+&]\s+|\s*,\s*(?:both|each)(?:\s+of\s+them)?\s*,\s*")
DO_IT = re.compile(r"^\s*(?P<verb>[a-z]+(?:\s+up)?)\s+it"
                   r"(?P<tail>\s+(?:over\s+)?(?:there|over|so|that\s+way|like\s+that))?"
                   r"(?:\s*,?\s*(?:but\s+)?(?:don't|dont|do\s+not)\s+(?P<not>[a-z]+)(?:\s+it)?)?"
                   r"\s*[,.!?]*\s*(?:please|pls|lol|thanks)?\s*[.!?]*\s*$", re.IGNORECASE)
"""A motion said after the end it should reach ("The jar needs to be next to the mug. Slide it over."): the clause
before, in this verb's manner; "slide it." alone only after an end said without a verb ("N right up against the bar.
slide it."), as after "Move A past B." it is a step left unsaid."""
NOT_THAT = re.compile(r"\s*,\s*(?:but\s+)?(?:don't|dont|do\s+not|never)\s+(?:carry|lift|drag|push|slide|shove)"
                      r"(?:\s+it)?\s*,\s*", re.IGNORECASE)
"""A manner ruled out between the verb and the object: "Slide, don't carry, the cylinder ..." is a slide."""
NOT_THIS = re.compile(r"\s*,\s*(?:but\s+)?not\s+(?P<other>(?:the|that|this)\s+[^,]+?)\s*,\s*", re.IGNORECASE)
"""An object ruled out after a description ("the grey cube, not the stone,"): it must be another object than the ones
the command names."""
ABOUT = re.compile(r"^\s*(?:about|regarding|as\s+for|now\s+for)\s+(?=\S)", re.IGNORECASE)
"""An opening that says which object the next words are about ("About the can: move it ...")."""
BOTH = re.compile(r"(?:\b(?:them\s+both|both\s+of\s+them|each\s+of\s+them|both|them)"
                  r"|(?<![\w'])'?em\s+both|(?<![\w'])'?em)\b", re.IGNORECASE)
"""Words for the two objects shown before: "them (both)", "each of them", and "em" as typed."""
THEM = re.compile(r"(?<![\w'])(?:them|'?em)\b", re.IGNORECASE)
BOTH_SAID = re.compile(r"\b(?:both|each|all)\b", re.IGNORECASE)
""""them" alone, and the words that make it two ("them both", "each of them")."""
LIFTING = re.compile(r"^\s*(?:pick\s+up|lift|grab|hold\s+up)\b", re.IGNORECASE)
PLACING = frozenset({"put", "place", "set", "drop", "lay"})
HOISTING = re.compile(r"^\s*(?:pick\s+up|lift|raise|hoist|hold\s+up)\b", re.IGNORECASE)
MOVING = frozenset({"move", "bring", "take"})
"""Verbs that carry on what was lifted, not grabbed: people wrote "Pick up A. Move it next to B." as a carry and "grab
A, move it next to B" as a slide."""
PLACE_WORDS = frozenset({"it", "them", "one", "ones", "left", "right", "front", "back", "behind", "middle", "both",
                         "each", "same", "far"})
OTHER_ASKS = frozenset({"again", "twice", "also", "too", "repeat", "back", "undo", "no", "not",
                        "don't", "dont", "never", "wait", "stop", "cancel", "instead", "actually", "rather", "but",
                        "except", "unless", "meant", "mean", "mistake", "wrong", "oops", "hold", "scratch", "forget",
                        "end", "order", "between", "and"})
"""Words by which a clause that names nothing still asks something ("Do that again", "No, wait"), an order ("... then
meds A and meds B at the end") or a list ("X and Y"): never read past."""


@dataclass(frozen=True)
class Shown:
    """Objects a clause showed without a command: what the next clause's pronouns point at; ``lifted`` when it
    picked them up ("Pick up the duck. Put it next to D." is a carry)."""

    objects: tuple[str, ...]
    lifted: bool = False
    hoisted: bool = False  # lifted by a word that says up (pick up, lift), not only grabbed
    about: bool = False  # the first object is the one talked about, the second where it is wrong ("too close to")
    other: str | None = None  # where two objects talked about are wrong ("A and B are too close to C"): "it" next
    crowded: bool = False  # said to be too close: moving one of them alone next moves it away from the other

    @property
    def context(self) -> Context:
        if self.other is not None:  # "Move them away from it": each of the two, from the other object
            return Context(self.objects[0], self.other, among=self.objects)
        return Context(self.objects[0], self.objects[1] if len(self.objects) > 1 else None,
                       among=() if self.about else self.objects)


OF_THE = re.compile(r"^\s*of\s+(?:all\s+)?the\s+(?:(?P<count>two|three|four|five|[2-5])\s+)?(?P<group>.+?)\s*$",
                    re.IGNORECASE)
"""A group said before what is picked among it: "Of the three cubes, ...", "of the 2 rectangular blocks move ..."."""


PLURAL_TOPIC = re.compile(r"^\s*(?:the|those|these)\s+(?:(?P<count>two|three|four|five|[2-5])\s+)?"
                          r"(?P<group>[a-z]+s)\s*$", re.IGNORECASE)
"""A group said by its kind's plural alone before the clauses about it ("the lenses, move the smaller one ...",
"Those two lenses - take the smaller one ...")."""


def group_said(text: str, scene: Scene) -> tuple[str, ...] | None:
    """The objects :data:`OF_THE` or :data:`PLURAL_TOPIC` names, or a group said by its place ("the two in front");
    None where none."""
    m = OF_THE.match(text) or PLURAL_TOPIC.match(text)
    return group_of(m.group("group"), scene, m.group("count")) if m is not None else placed_group(text, scene)


def shown(text: str, scene: Scene, context: Context | None) -> Shown | None:
    """The objects ``text`` only shows ("See the cylinder?", "You see the red and the blue cubes?"), or None."""
    now = NOW_SAID.match(text)
    text = now.group("rest") if now is not None else text
    said = [w.rstrip(":") for w in text.split()]  # "Here's the thing: the cup is ...", "Please lift the blue cup."
    kept = strip_polite(said, frozenset(scene.names))
    start = next((i for i in range(len(said) - len(kept) + 1) if said[i:i + len(kept)] == kept), 0)
    text = " ".join(text.split()[start:start + len(kept)]) if kept else text
    group = group_said(text, scene)
    if group is not None:
        return Shown(group)
    text = ABOUT.sub("", text) or text  # "About the can: move it past Q"
    m = TOO_CLOSE.match(text)
    if m is not None:
        what, other = _objects(m.group("what"), scene, context), _objects(m.group("other"), scene, context)
        if what is not None and other is not None and len(other) == 1 and other[0] not in what:
            if len(what) == 1:
                return Shown((what[0], other[0]), about=True, crowded=True)
            return Shown(what, about=True, other=other[0])  # "The teddy and the rock are both too close to it"
    m = SHOWN.match(text)
    if m is not None:
        objects = _objects(m.group("what"), scene, context) or _plural(m.group("what"), scene)
        if objects is None:
            return None
        return Shown(objects, bool(LIFTING.match(text)), hoisted=bool(HOISTING.match(text)))
    objects = _pointed_at(text, scene, context)
    told = STATEMENT.match(text)
    if told is not None and objects is None and now is not None:
        # "Right now the ring is far from the cone": how the table is; it points at the ring
        objects = _objects(told.group("what"), scene, context)
    crowded = told is not None and TOGETHER.match(told.group("said")) is not None and objects is not None \
        and len(objects) == 2
    return None if objects is None else Shown(objects, crowded=crowded)


PLURAL = re.compile(r"^\s*(?:all\s+)?(?:the|those|these)\s+(?:(?P<count>two|three|four|five|[2-5])\s+)?"
                    r"(?P<group>.+s)\s*$", re.IGNORECASE)
"""A group shown by its plural ("Look at the three red blocks"): what comes next picks among it."""


def _plural(text: str, scene: Scene) -> tuple[str, ...] | None:
    """The objects a plural description shown names (:data:`PLURAL`), or None."""
    m = PLURAL.match(text)
    return group_of(m.group("group"), scene, m.group("count")) if m is not None else None


def _pointed_at(text: str, scene: Scene, context: Context | None) -> tuple[str, ...] | None:
    """The objects a clause that asks for nothing points at: a description alone ("the teddy", "ok now the box")
    or a statement about it ("The white box is in the way"); None for anything else."""
    m = WHERE.search(text)
    if m is not None:
        return _objects(m.group("what"), scene, context)
    m = THERE.match(text)
    if m is not None and not _names_a_place(m.group("what") or m.group("of")):
        return _objects(m.group("what") or m.group("of"), scene, context)
    m = STATEMENT.match(text)
    if m is not None and (not _names_a_place(m.group("said")) or TOGETHER.match(m.group("said"))):
        objects = _objects(m.group("what"), scene, context)
        if objects is not None:
            return objects
    return _objects(text, scene, context)


ABOUT_US = frozenset({"we're", "we", "we've", "i'm", "i", "i've", "it's", "this", "that's", "our", "my"})
"""Openings of a sentence that tells about the person or the occasion ("We're setting up for the demo")."""
WHERE = re.compile(r"\bwhere\s+(?P<what>.+?)\s+(?:is|are|sits|stands|lies)\b", re.IGNORECASE)
"""A clause about where an object is ("I don't like where the can is"): it points at the object."""


def about_us(text: str, scene: Scene) -> bool:
    """Whether a clause only tells about the person or the occasion: it opens so (:data:`ABOUT_US`) and no word
    of it names an object, a colour or a shape; read past between commands, as a greeting is."""
    words = [w.strip(".,;:!?\"()").lower() for w in text.split()]
    if not words or words[0] not in ABOUT_US:
        return False
    naming = naming_words(scene) | set(name_words(scene)) | set(SHAPE_NOUNS) | NOUNS | BLOCK_WORDS
    return not naming & set(words)


def asks_nothing(text: str, scene: Scene, verbs: list[str]) -> bool:
    """Whether a clause asks for nothing and points at nothing ("Here's the situation", "Would you see to that?",
    "go"): no word of it names an object, a colour, a shape, a place, a pace or a pronoun, and it does not open with
    a verb of motion (an unfinished command, "move it", is refused, not read past)."""
    words = [w.strip(".,;:!?\"()").lower() for w in strip_polite(text.split(), frozenset(scene.names))]
    words = [w for w in words if w]
    if not words or words[0] in {v.split()[0] for v in verbs} - {"get", "take"}:
        return False
    naming = naming_words(scene) | set(name_words(scene)) | set(SHAPE_NOUNS) | NOUNS | BLOCK_WORDS | PLACE_WORDS \
        | KIND_WORDS  # "then footy two": a thing said, on the table or not, is never read past
    said = {w.strip(".,;:!?\"()").lower() for w in text.split()}
    return not (naming | PACES.keys()) & set(words) and not (OTHER_ASKS | HOW_FAR) & said \
        and not _names_a_place(text) and not any(c.isdigit() for c in text) \
        and not any(number_of(w) is not None for w in words)


HOW_FAR = frozenset({"close", "far", "farther", "further", "near", "nearer", "touching", "touch", "gap",
                     "bit", "little", "lot", "slightly", "possible", "tight", "distance", "way"})
"""Words by which a clause that names nothing asks how far ("as close as possible"): never read past."""


def _names_a_place(said: str) -> bool:
    """Whether a statement's words name a relation to another object ("A is next to B"): it may be a goal
    stated badly, never only a pointer."""
    return bool(re.search(r"\b(?:to|from|of|past|beyond|around|round|away|beside|by|toward|towards|near|nearer"
                          r"|closer)\b", said, re.IGNORECASE))


def carried(command: Command, after: Shown | None) -> Command:
    """A placing command after a clause that picked its mover up is a carry ("Pick up A. Put it next to B.")."""
    if after is not None and after.lifted and command.mover in after.objects and command.manner == "slide" \
            and (command.verb.lower() in PLACING or after.hoisted and command.verb.lower() in MOVING):
        return replace(command, manner="carry")
    return command


def set_down(command: Command, previous: Command | None, text: str) -> Command:
    """Setting down what the clause before carried is the end of that carry ("carry A around B, then set it down
    next to F"): a placing verb with "down", or drop / lay, on the carried object."""
    if previous is None or previous.manner != "carry" or command.mover != previous.mover or command.manner != "slide":
        return command
    verb = command.verb.lower()
    if verb in ("drop", "lay") or (verb in PLACING and re.search(r"\bdown\b", text, re.IGNORECASE)):
        return replace(command, manner="carry")
    return command


def pointed(text: str, previous: Command | None, context: Context | None, scene: Scene,
            plugins: list) -> list[Command] | None:
    """The commands of a clause read by one of the module's readings, or None when none applies."""
    repeated = again.done_again(text, previous, context, scene, plugins)
    if repeated is not None:
        return repeated
    m = NOT_THIS.search(text)
    if m is not None:  # "Push the grey cube, not the stone, toward the jar": the stone is not what moves
        try:
            other = resolve_object(m.group("other"), scene, "block not meant", context)
            command = resolve(f"{text[:m.start()]} {text[m.end():]}", scene, plugins, context)
        except L2PError:
            command = None
        if command is not None and other not in (command.mover, *command.anchors):
            return [replace(command, sentence=text)]
    if NOT_THAT.search(text):
        try:
            return [resolve(NOT_THAT.sub(" ", text, count=1), scene, plugins, context)]
        except L2PError:
            pass
    reached = goal_after(text, scene, plugins, context)
    if reached is not None:
        return reached
    m = ORDER.search(text)
    first = m.group("first") or m.group("lead") if m is not None and m.start() > 0 else None
    text = text[:m.start()] if first is not None else text
    for what, rest, lifting in _splits(text):
        objects = _pointed_at(what, scene, context)
        if objects is None:
            continue
        told = Shown(objects).context
        if len(objects) == 1 and context is not None and len(context.among) == 2 and objects[0] in context.among:
            # "There are two brown cubes. Take the bigger one and move it past the other one."
            told = Context(objects[0], next(o for o in context.among if o != objects[0]))
        commands = _each(rest, told, objects, scene, plugins)
        if commands is not None:
            shown = Shown(objects, lifting, hoisted=lifting and bool(HOISTING.match(text)))
            return _ordered([carried(c, shown) for c in commands], first, scene)
    if context is not None and len(context.among) == 2 and BOTH.search(text):  # "See A and C? Move them ..."
        commands = _each(text, context, context.among, scene, plugins)
        if commands is not None:
            return _ordered(commands, first, scene)
    if previous is not None and THEM.search(text) and not BOTH_SAID.search(text) \
            and _called_plural(previous.mover, previous) != _called_plural(previous.anchor, previous):
        # "slide the keys past the wallet, then bring em back ...": them are the keys; "move the soup away from the
        # scissors, then push the box back toward them": the scissors; "pick up crayons put em by ruler then move
        # them ...": the box of crayons
        them = previous.mover if _called_plural(previous.mover, previous) else previous.anchor
        try:
            return [resolve(THEM.sub("it" if them == previous.mover else them, text), scene, plugins, context)]
        except L2PError:
            pass
    if previous is not None and BOTH.search(text):
        pair = (previous.mover, previous.anchor)
        return _ordered(_each(text, Context(*pair), pair, scene, plugins), first, scene)
    return _ordered(_two_movers(text, context, scene, plugins), first, scene)


def _called_plural(name: str, command: Command) -> bool:
    """Whether the object ``name`` of ``command`` is one thing people call by a plural: by its name ("the keys") or
    as the clause called it ("the crayons" for the crayon box)."""
    return plural_named(name) or said_in_plural(name, command.sentence)


GOES = frozenset({"go", "goes"})


def _two_movers(text: str, context: Context | None, scene: Scene, plugins: list) -> list[Command] | None:
    """One command per object where two objects stand where the mover does ("Move both the blue cube and the red
    cube closer to the mug", "white cube + small yellow cube -> both around lid"), in the order named; None where
    ``text`` does not read so. A note without its verb is a slide, as a one-object note is."""
    words = [w for w in AND_SIGNS.sub(lambda m: " and " if m.group().strip() in "+&" else " ", text).split()
             if w not in ARROWS]
    if len(words) < 4:
        return None
    try:
        verb, _, rest = split_verb(words)
    except LanguageError:
        verb, rest = "move", words
    for j in range(2, len(rest) - 1):
        pair = _objects(" ".join(rest[:j]), scene, context)
        if (pair is None or len(pair) != 2) and rest[0].lower() == "both":  # "both the red cube and ..."
            pair = _objects(" ".join(rest[1:j]), scene, context)
        if pair is None or len(pair) != 2:
            continue
        tail = rest[j + 1:] if rest[j].lower() == "both" else rest[j:]
        tail = tail[1:] if tail and tail[0].lower() in GOES else tail  # "Both green cubes go next to the duck"
        try:
            return [resolve(f"{verb} {name} {' '.join(tail)}", scene, plugins, context) for name in pair]
        except L2PError:
            continue
    return None


def _ordered(commands: list[Command] | None, first: str | None, scene: Scene) -> list[Command] | None:
    """``commands`` with the one whose mover ``first`` describes (:data:`ORDER`) first; None where ``first`` is said
    and does not pick one of two movers."""
    if commands is None or first is None:
        return commands
    movers = tuple(c.mover for c in commands)
    if len(commands) != 2 or movers[0] == movers[1]:
        return None
    among = Context(movers[0], movers[1], among=movers)
    bare = re.sub(r"(?i)^the\s+", "", first)
    for said in (f"the {bare} one", f"the {bare}"):
        pick = try_object(said, scene, among)
        if pick in movers:
            return commands if pick == movers[0] else commands[::-1]
    return None


def _splits(text: str) -> list[tuple[str, str, bool]]:
    """(the objects' words, the command's words, whether they were picked up) for every way ``text`` reads as
    objects shown and then a command: at each "and" after a showing verb, and at a dash or colon."""
    out = []
    m = SHOWN.match(text)
    if m is not None:
        what = m.group("what")
        for j in re.finditer(r"\s*,\s*(?:and\s+|then\s+)?|\s+and\s+(?:then\s+)?", what):
            out.append((what[:j.start()], what[j.end():], bool(LIFTING.match(text))))
    m = TOPIC.match(text)
    while m is not None and not strip_polite(m.group("what").split(), frozenset()):  # "Please, the vase, move it ..."
        m = TOPIC.match(m.group("rest"))
    if m is not None:
        out.append((m.group("what"), m.group("rest"), False))
    return out


PLACE_BEFORE = re.compile(r"\b(?:to|from|around|round|past|beyond|beside|by|near|toward|towards|between)\s+$",
                          re.IGNORECASE)
"""The last word of a place, right before "them both": what follows is where, not what moves."""


def _each(text: str, context: Context, objects: tuple[str, ...], scene: Scene,
          plugins: list) -> list[Command] | None:
    """``text`` resolved with ``context``; where it says "them (both)" and ``objects`` are two, once per object. None
    where "them both" is the place ("then the green cube next to them both"): one move is made by one object, never
    once beside each."""
    both = BOTH.search(text)
    if both is not None and PLACE_BEFORE.search(text, 0, both.start()):
        return None
    if len(objects) == 2 and both:
        try:
            return [resolve(BOTH.sub(name, text, count=1), scene, plugins, context) for name in objects]
        except L2PError:
            return None
    if len(objects) == 1 and plural_named(objects[0]) and not BOTH_SAID.search(text):
        text = THEM.sub("it", text, count=1)  # "the shears, move them around the box": the one pair of shears
    try:
        return [resolve(text, scene, plugins, context)]
    except L2PError:
        return None


def _objects(text: str, scene: Scene, context: Context | None) -> tuple[str, ...] | None:
    """One object ("the cylinder") or two ("the red and the blue cubes", "B and E") that ``text`` names; politeness
    around them is read past ("ok now the box")."""
    text = " ".join(strip_polite(text.split(), frozenset(scene.names))) or text
    try:
        return (resolve_object(text, scene, "block", context),)
    except (LanguageError, UnknownObjectError):
        pass
    words = text.split()
    pair = two_references(words, scene, "block", context)
    if pair is None and len(words) >= 4 and words[-1].lower().rstrip("s") in ("cube", "block", "object", "one"):
        noun = words[-1].rstrip("sS")  # "the red and the blue cubes": each colour with the noun
        split = [w.lower() for w in words].index("and") if "and" in (w.lower() for w in words) else -1
        if split > 0:
            first = " ".join([*words[:split], noun])
            second = " ".join([*words[split + 1:-1], noun])
            try:
                pair = (resolve_object(first, scene, "block", context), resolve_object(second, scene, "block", context))
            except (LanguageError, UnknownObjectError):
                pair = None
    return pair if pair is not None and pair[0] != pair[1] else None
