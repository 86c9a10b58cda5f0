"""A group, or one object, shown before the clauses about it: "there r two cylinders, move the short one towards the
bunny and the other one away from it", "Tip box, move past the vial", "of the 2 rectangular blocks move the one closer
to the robot next to the jar", "the stone and the teddy: move the first one ..., the second one ...".

Each reading asks chain/clauses.py's reader again for the words after the group (``read``), which is passed in so that
this module stays below it."""

from __future__ import annotations

import re
from collections.abc import Callable

from ..core.scene import Scene
from ..errors import L2PError, LanguageError, UnknownObjectError
from ..language import Command, Context, resolve_object, strip_polite, verb_heads
from ..language.numbers import apposed
from ..language.reference_words import FARTHEST, NEAREST
from ..pipeline import resolve
from . import pointing
from .clause import MAX_CLAUSES
from .rephrased import TOPIC_BARE

Read = Callable[..., list[tuple[str, Command]]]
"""chain/clauses.py's reader of a clause's text: (text, previous, scene, plugins, depth, context, pair) -> pieces."""


def group_first(text: str, previous: Command | None, scene: Scene, plugins: list, depth: int,
                context: Context | None, read: Read) -> list[tuple[str, Command]] | None:
    """"there r two cylinders, move the short one towards the bunny and the other one away from it": a group
    shown before a comma or colon, then clauses that pick among it, or one object that "it" then means (``read``:
    how a clause's text is read, chain/clauses.py)."""
    if depth >= MAX_CLAUSES:
        return None
    m = pointing.TOPIC.match(text)
    if m is None:
        return _of_group(text, previous, scene, plugins, depth, read)
    what, rest = apposed(m.group("what"), m.group("rest"))  # "the red one, number 2 - move it ..."
    group = pointing.shown(what[3:], scene, context) if what.lower().startswith("of the ") else None
    if group is not None and len(group.objects) > 1:  # "Of the two at the front, move the one on the left ..."
        what, shows = what[3:], group
    else:
        shows = pointing.shown(what, scene, context)
    if shows is None and what != m.group("what") and not {w.lower() for w in what.split()} & verb_heads():
        resolve_object(what, scene)  # a description the number contradicts is refused as such, naming both
    if shows is None or (len(shows.objects) < 2 and shows.lifted):
        return None  # one object shown is what "it" then means ("About the can: move it past Q"); lifted, a carry
    if len(shows.objects) == 2 and all(said.search(rest) for said in ORDINALS):
        # "the stone and the teddy: move the first one ..., the second one ...": "it" after them is asked about
        if re.search(r"\bit\b", rest, re.IGNORECASE):
            return None
        rest = ordinals(rest, shows)
    _same_in_apposition(what, rest, shows, scene)
    rest = _restated(what, rest, shows, scene)
    try:
        return read(rest, previous, scene, plugins, depth + 1, shows.context, shows)
    except L2PError:
        pass
    said = strip_polite(rest.split(), frozenset(scene.names))
    if len(shows.objects) != 1 or not said:
        return None
    if said[0].lower() not in verb_heads():
        said = ["move", "it", *said]  # "biggest item, away from cam", "cube by the ball, over to P": where it goes
    elif len(said) > 1 and said[1].lower() not in OBJECT_SAID:
        said = [said[0], "it", *said[1:]]  # "Tip box, move past the vial": the verb's object is the one shown
    else:
        return None
    try:
        return read(" ".join(said), previous, scene, plugins, depth + 1, shows.context, shows)
    except L2PError:
        return None


OBJECT_SAID = frozenset({"it", "that", "this", "them", "the", "one", "same"})
"""Words that open the object of a verb said after an object shown ("The cup, move it ...", "..., move the same ..."):
the verb has its object, so none is put in."""


def _same_in_apposition(what: str, rest: str, shows: pointing.Shown, scene: Scene) -> None:
    """A relation said after a description, before the verb ("The cube at the front, nearest the robot, put it ..."):
    one object said twice, so where the two name different objects the sentence is refused naming both (the relation
    alone would otherwise be what "it" means)."""
    m = pointing.TOPIC.match(rest)
    if m is None or len(shows.objects) != 1:
        return
    said = [w.lower() for w in m.group("what").split()]
    while said and said[0] in ("the", "one", "which", "that's", "is", "that"):
        said = said[1:]
    if not said or said[0] not in NEAREST | FARTHEST:
        return  # a description said again ("That flat thing, the brown one, ...") narrows the first: corrections.py
    _not_another(what, m.group("what"), pointing.shown(m.group("what"), scene, shows.context), shows)


def _not_another(what: str, said: str, again: pointing.Shown | None, shows: pointing.Shown) -> None:
    """Refuse, naming both, where ``said`` (what was said again after ``what``) shows one object other than the one
    ``what`` showed."""
    if again is not None and len(again.objects) == 1 and again.objects != shows.objects:
        raise LanguageError(f'"{what}" is {shows.objects[0]} and "{said}" is {again.objects[0]}: one object said two '
                            "ways that name different objects; say which you mean")


RESTATED = re.compile(r"^\s*(?:the\s+one|which\s+is|that\s+one)\b", re.IGNORECASE)


def _restated(what: str, rest: str, shows: pointing.Shown, scene: Scene) -> str:
    """``rest`` without a description that says the one object shown again ("the cup, the one on the left, move it
    ..."): the object is named already, and the words added name it or nothing the reader can tell. Where they name
    another object the person said two things ("the cup, the one at the back" with the cup in front): asked."""
    m = pointing.TOPIC.match(rest)
    if m is None or len(shows.objects) != 1 or not RESTATED.match(m.group("what")):
        return rest
    try:
        again = pointing.shown(m.group("what"), scene, shows.context)
    except L2PError:
        again = None
    _not_another(what, m.group("what"), again, shows)
    return m.group("rest")


def _of_group(text: str, previous: Command | None, scene: Scene, plugins: list, depth: int,
              read: Read) -> list[tuple[str, Command]] | None:
    """"of the 2 rectangular blocks move the one closer to the robot next to the jar": a group said first without a
    comma, then a clause that picks among it."""
    words = text.split()
    for i in range(3, len(words) - 2):
        group = pointing.group_said(" ".join(words[:i]), scene)
        if group is None:
            continue
        shows = pointing.Shown(group)
        try:
            return read(" ".join(words[i:]), previous, scene, plugins, depth + 1, shows.context, shows)
        except L2PError:
            return None
    return None


def ordinals(text: str, show: pointing.Shown | None) -> str:
    """``text`` with "the first one" and "the second one" said as the two objects the clause before showed ("Take the
    bar and the cup. Move the first one around the second one."); ``text`` itself where it says neither, or says "it"
    as well (which of the two it means is asked)."""
    if show is None or len(show.objects) != 2 or not any(o.search(text) for o in ORDINALS) \
            or re.search(r"\bit\b", text, re.IGNORECASE):
        return text
    return ORDINALS[1].sub(show.objects[1], ORDINALS[0].sub(show.objects[0], text))


ORDINALS = (re.compile(r"\bthe\s+first(?:\s+one)?\b", re.IGNORECASE),
            re.compile(r"\bthe\s+second(?:\s+one)?\b", re.IGNORECASE))
"""Of two objects shown together, the one named first and the one named second."""


RESUMED = re.compile(r"\b(?:it|them|that one|this one)\b", re.IGNORECASE)
"""A pointer in the command after a topic that takes the topic up again ("the red one by the lamp, move it ...")."""


def refuse_for_the_topic(text: str, scene: Scene, context: Context | None, plugins: list | None = None) -> None:
    """Raise :func:`topic_refusal`'s error where there is one (the caller then raises its own)."""
    told = topic_refusal(text, scene, context, plugins)
    if told is not None:  # "the item farthest from you, keep it ...": the topic's own reason
        raise told from None


def topic_refusal(text: str, scene: Scene, context: Context | None, plugins: list | None = None) -> L2PError | None:
    """Why "the item which is farthest from you, kindly keep it near to spoon" is refused, where no reading took it:
    the object said first, then taken up by "it", is a description that does not resolve, and its own error ("nearest"
    is ambiguous: ..., no block called ...) says more than the grammar's on the whole clause ("'the' is not a verb").
    Where the topic resolves and the command after it names an object the table does not hold ("the scale, move it
    next to the letters"), that command's error, read with "it" as the topic (given the installed ``plugins``).
    The topic may stand without a comma before a known verb and "it" ("the thing nearest the parcel move it past
    the scale": chain/rephrased.TOPIC_BARE). None where the text is no such topic, or the topic resolves and the
    command after it fails otherwise."""
    said = _topic_and_rest(text)
    if said is None or not RESUMED.search(said[1]) or not said[0].strip():
        return None
    rest = said[1]
    what = " ".join(strip_polite(said[0].split(), frozenset(scene.names))) or said[0]
    if not what.strip() or what.split()[0].lower() in verb_heads():
        return None  # "move A next to B, then push it": a command, not a topic
    try:
        name = resolve_object(what, scene, "block", context)
    except L2PError as e:
        return e
    if plugins is None:
        return None
    try:
        resolve(rest, scene, plugins, Context(name))
    except UnknownObjectError as e:
        return e
    except L2PError:
        pass
    return None


def _topic_and_rest(text: str) -> tuple[str, str] | None:
    """(the topic, the command after it) of a text said as a topic first, with a comma, dash or colon or, before a
    known verb and "it", without one; None where it is not."""
    m = pointing.TOPIC.match(text)
    if m is not None:
        return m.group("what"), m.group("rest")
    m = TOPIC_BARE.match(text)
    if m is not None and m.group("verb").lower() in verb_heads():
        return m.group("what"), f"{m.group('verb')} {m.group('it')} {m.group('rest')}"
    return None
