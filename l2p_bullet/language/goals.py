"""An end said instead of the motion, read as the motion: "I want the red block next to B", "the goal is for C to be
pushed past B", "Make sure F ends up closer to the can", "What I should like is for the saucer to be standing beside
the lamp". The mover is the description before the words that link it to where it should be; the rest is the
command's. A statement of how the table is ("The mug is next to the domino.", "Right now the ring is far from the
cone") asks for nothing and is not read so. Kept apart from language/words.py, which reads the words around a command
(politeness, pace, framing)."""

from __future__ import annotations

import functools

from ..errors import LanguageError
from . import lexicon
from .reference_words import DETERMINERS, NOUNS, PLACE_ADJECTIVES
from .shape_words import SHAPE_NOUNS
from .words import PACES, by_word, starts

GOAL_PREFIXES: tuple[tuple[str, ...], ...] = tuple(sorted((tuple(p.split()) for p in (
    "i want", "i would like", "i'd like", "i need", "have", "we need", "we want", "what i want is", "what i need is",
    "what i'd like is", "what i'm after is", "i want to see", "i'd like to see", "i would like to see",
    "the goal is to have", "the aim is to have", "the idea is to have", "the task is to have", "the goal is to get",
    "the idea is that", "the goal is that", "the plan is that", "the aim is that", "the idea is for",
    "could we end up with", "can we end up with", "let's end up with", "i'd like to end up with", "end up with",
    "goal", "want", "end state", "target", "objective", "goal state", "target state", "task", "the task",
    "result wanted", "wanted result", "what i want", "let", "wanted", "expected result", "desired result", "end result",
    "expected outcome", "desired outcome", "result", "outcome", "final state", "desired state", "expected state",
    "expected final state", "desired final state", "end goal", "final goal", "the goal is", "goal is", "the idea is",
    "i just want", "just want", "need", "i want that", "i should like", "i should like to see", "target config",
    "target configuration", "goal config", "goal configuration", "final config", "final configuration",
    "end result should be", "the end result should be", "final frame", "last frame", "end frame", "final shot",
    "i wanna see", "wanna see", "i wanna", "wanna", "wish",
)), key=len, reverse=True))
"""Openings that state the end instead of the motion: "I want the red block next to the green one" is
"put the red block next to the green one"."""
DOERS = (("the", "robot", "to"), ("the", "arm", "to"), ("you", "to"), ("robot", "to"), ("for", "you", "to"),
         ("for", "the", "robot", "to"), ("that", "you"))
"""Who is to do it, between a goal's opening and its verb ("I'd like *the robot to* move A ...")."""

POSTURES = frozenset({"sitting", "standing", "lying", "resting", "sat", "parked"})
"""How a wished-for object rests where it should be ("I want the I block sitting next to the truck"): says nothing
of the move."""


_GOALS_BY_FIRST = by_word(GOAL_PREFIXES, 0)


def goal_to_verb(words: list[str], verbs: list[str]) -> list[str]:
    """"I want the red block next to B" -> "put the red block next to B"; a known verb after the opening
    ("I want to move ...") is kept as it is."""
    low = [w.lower() for w in words]
    for pre in _GOALS_BY_FIRST.get(low[0], ()) if low else ():
        if starts(low, pre) and len(words) > len(pre):
            rest = words[len(pre):]
            for doer in DOERS:  # "I'd like the robot to move ...", "I want you to ..."
                if tuple(w.lower() for w in rest[:len(doer)]) == doer and len(rest) > len(doer):
                    rest = rest[len(doer) - (doer[-1] == "to"):]
                    break
            if rest[0].lower() == "to" and len(rest) > 1:
                return rest[1:]
            if rest[0].lower() in verbs:
                return rest
            at = next((i for i, w in enumerate(rest) if i > 1 and w.lower() in POSTURES), None)
            if at is not None and rest[at - 1].lower() not in DETERMINERS:  # "I want the I block sitting next to B"
                rest = rest[:at] + rest[at + 1:]
            return ["put", *rest]
    if low[:1] == ["keep"] and len(low) > 3 and not low[1].endswith("ing") and low[1:3] != ["it", "on"]:
        return ["put", *words[1:]]  # "Kindly keep the box beside the goal": put it there ("keep it on the table" stays)
    if low[:1] == ["make"] and "go" in low[2:]:  # "make A go around B"
        at = low.index("go", 2)
        if not set(low[1:at]) & set(verbs):  # "make you push A small go near B" says its own verb
            return ["move", *words[1:at], *words[at + 1:]]
    if low[:2] == ["make", "pass"] and len(low) > 4 and {"beyond", "side"} & set(low[3:]):
        return ["move", *words[2:]]  # "make pass the thermos beyond the apple", as French and Spanish say it
    if low[:1] == ["make"] and "pass" in low[2:]:  # "make the C pass by the D", "make A pass B": go past it
        at = low.index("pass", 2)
        if not set(low[1:at]) & set(verbs):
            return ["move", *words[1:at], "beyond", *words[at + 1 + (low[at + 1:at + 2] == ["by"]):]]
    return words


IRREGULAR_PARTICIPLES = {"slide": "slid", "bring": "brought", "put": "put", "set": "set", "lay": "laid",
                         "take": "taken"}
PASSIVE_AUX = (("needs", "to", "be"), ("need", "to", "be"), ("has", "to", "be"), ("have", "to", "be"),
              ("should", "be"), ("shall", "be"), ("must", "be"), ("to", "be"), ("be",), ("is",), ("gets",),
              ("get",))
"""Words between an object and a participle that only make it passive ("for C to be moved next to B")."""


@functools.lru_cache(maxsize=256)
def participles(verb: str) -> frozenset[str]:
    """The past participles a one-word verb may take ("move": moved, "drag": dragged, "carry": carried). Kept by
    the verb: every clause read asks for every known verb's."""
    if verb in IRREGULAR_PARTICIPLES:
        return frozenset({IRREGULAR_PARTICIPLES[verb]})
    out = {verb + "ed", verb + "d", verb + verb[-1] + "ed"}
    if verb.endswith("y"):
        out.add(verb[:-1] + "ied")
    return frozenset(out)


def passive_to_verb(words: list[str], verbs: list[str], is_object) -> list[str]:
    """"I need the cylinder moved away from C", "the goal is for C to be pushed past B" -> "move the cylinder
    away from C", "push C past B": an object described before the participle of a known verb, whatever opens
    the sentence. ``is_object(text)`` says whether ``text`` names one object; the longest such description ending
    at the participle is the mover. Words that start with a known verb are returned as they are."""
    low = [w.lower() for w in words]
    if not low or low[0] in verbs:
        return words
    forms = {p: v for v in verbs if " " not in v for p in participles(v)}
    for k in range(1, len(low)):
        if low[k] not in forms:
            continue
        end = k
        for aux in PASSIVE_AUX:
            if end > len(aux) and tuple(low[end - len(aux):end]) == aux:
                end -= len(aux)
                break
        for j in range(end):
            if _names_something(words[:j]):
                return words  # "the cube by the butter moved ...": never the butter, its words dropped
            if is_object(" ".join(words[j:end])):
                if j > 2 and low[j - 1] in ("for", "of", "with") and low[j - 3] in DETERMINERS \
                        and lexicon.singular(low[j - 2]) is not None:
                    return words  # "the soap for dogs put beside ...": the soap, never what it is for
                return [forms[low[k]], *words[j:end], *words[k + 1:]]
        return words
    return words


_WRITTEN_LINKS = (
    "to end up", "ends up", "end up", "should end up", "needs to end up", "to be", "is", "be", "should be",
    "needs to be", "need to be", "has to be", "must be", "to go", "goes", "go", "to get", "gets", "should go",
    "sits", "lies", "to sit", "to lie", "to land", "lands", "is placed", "is put", "to stand", "stands",
    "were", "was", "ended up", "would be", "has to go", "needs to go", "must go", "would end up", "should stand",
    "should sit", "should finish", "finishes", "to finish", "should lie", "ought to be", "ought to end up",
    "must finish", "must end up",
    "should end", "end",
    "ought to go", "ought to sit",
    "wants to end up", "wants to be", "wants to go", "wants to sit",  # "the chalk box wants to end up nearer ..."
    "want to end up", "want to be", "are",  # an object named in the plural: "make sure the cards are by the pad"
    "to finish up", "finishes up", "finish up", "should finish up",
    "to be standing", "to be sitting", "to be lying", "be standing", "be sitting", "be lying", "ends up sat",
    "should be sitting", "should be standing", "should be lying", "is going to go", "is gonna go", "will go",
    "is going to end up", "is gonna end up",
    "end up sat", "ends up sitting", "end up sitting", "to end up sitting", "to find itself", "finds itself",
    "should come", "to come", "comes", "be positioned", "to be positioned", "is positioned", "be placed",
    "to be placed", "ending up", "finish", "stays", "should stay", "to stay", "were to find itself",
    "were to end up", "were to be", "went", "came", "ended", "sat", "stood", "sitting", "standing",
    "would be sitting", "would be standing", "wants to be", "wants to come", "wants to go", "wants to sit",
    "needs to come", "needs to sit", "would be sat", "is sat", "is sitting", "is standing", "is lying",
    "to finish up", "finishes up", "finish up", "finished up", "to wind up", "winds up", "wind up",
    "become", "becomes", "to become",  # "make so the cable become more close to tuner"
)
_MODALS = ("should", "shall", "must", "needs to", "need to", "has to", "have to", "ought to", "wants to", "is going to",
           "is gonna", "will", "has got to", "gotta", "got to", "is to")
_WHERE_IT_STAYS = ("end up", "be", "go", "sit", "stand", "lie", "finish", "come", "stay", "land", "end up sitting",
                   "end up sat", "be sitting", "be standing", "be lying", "be placed", "be positioned", "be put",
                   "finish up", "wind up", "become")
STATE_LINKS: tuple[tuple[str, ...], ...] = tuple(sorted(dict.fromkeys(tuple(p.split()) for p in (
    *_WRITTEN_LINKS, *(f"{modal} {stay}" for modal in _MODALS for stay in _WHERE_IT_STAYS))), key=len, reverse=True))
"""Words that link an object to where it should be ("the goal is for the duck *to end up* next to B", "make it
so that A *is* closer to C", "the red cube *needs to be* closer to the blue one"): those people wrote, and each
way of saying it must, should, has to ... with each way of saying where it stays."""
_LINKS_BY_FIRST = by_word(STATE_LINKS, 0)
"""The links by their first word (only those can match where a word stands), the longest first as above."""


def state_to_verb(words: list[str], verbs: list[str], is_object, said: list[str] | None = None) -> list[str]:
    """A sentence that states the end instead of the motion -> "move MOVER ...": the mover is the longest
    description that names one object and ends right before a linking phrase (:data:`STATE_LINKS`), whatever
    opens the sentence ("The goal is for the duck to end up next to B", "Make sure F ends up closer to the
    can"). Words that start with a known verb are returned as they are; so are words where no object stands
    before a link (the caller's error then names the first word), and a sentence ``said`` with words of how the
    table is now (:data:`NOW`)."""
    low = [w.lower() for w in words]
    if not low or low[0] in verbs or said_now([w.lower() for w in said or words]):
        return words  # "Right now the ring is far from the cone": how the table is, not how it should end
    if any(w.endswith(("'s", "\u2019s")) for w in low[1:-1]):  # "make it so the mug's not so close to the ball"
        split = _contracted(words)
        read = state_to_verb(split, verbs, is_object, _contracted(said or words))
        if read is not split:
            return read
    for k in range(1, len(low)):
        link = next((t for t in _LINKS_BY_FIRST.get(low[k], ()) if tuple(low[k:k + len(t)]) == t
                     and k + len(t) < len(low)), None)
        if link is None:
            continue
        for j in range(k):  # the mover's words end at k whichever link follows: searched once
            if _names_something(words[:j]) or _group_shown(words[:j], is_object) or (
                    "and" in low[:j] and _linked(low[:j])):
                return words  # "The cube by the butter should go ...": never the butter, its words dropped
            if is_object(" ".join(words[j:k])):
                if j > 1 and low[j - 1].strip(",.:;") in RELATING:  # not an opening's ("By the end, F ...")
                    return words  # "the toy next to the brick goes ...": the brick tells the mover, is not it
                if j == 0 and link in TELLING and [w.lower() for w in (said or words)[:k]] == low[:k]:
                    first = low[0] if low[0] in DETERMINERS else words[0]
                    mover = " ".join([first, *words[1:k]])
                    raise LanguageError(f'"{" ".join(words)}" tells how the table is and asks for nothing; say what to '
                                        f'do, as in "move {mover} {" ".join(words[k + len(link):])}"')
                if link[-1] in GOING and low[k + len(link)] == "by":
                    raise LanguageError(f'"{" ".join(words[k:k + len(link) + 1])}" may mean going past or '
                                        "staying beside; say which")
                paced = [w for w in words[:j] if w.lower() in PACES]  # "Make rapidly the cube go ...": kept
                said_verb = next((w for w in words[:j] if w.lower() in verbs), "move")  # "make you push A ... go"
                return [said_verb, *words[j:k], *words[k + len(link):], *paced]
    return words


RELATING = frozenset({"to", "toward", "towards", "near", "nearer", "by", "beside", "nearest", "closest", "farthest",
                      "furthest", "of", "from", "behind", "than", "with", "between", "at", "on", "in", "beyond",
                      "round"})
"""Words after which an object is told *by* another ("the toy next to the brick goes ...", "carton nearest the scanner
goes ..."): the object after them is the other one, never the mover, whose own words the reader does not know."""


def _linked(low: list[str]) -> bool:
    """Whether the words before a mover hold a link of their own ("the goal is the sharp e ends up next to the cup and
    the phone ends up ..."): an end stated before, never to be dropped."""
    return any(tuple(low[i:i + len(t)]) == t for i in range(1, len(low)) for t in _LINKS_BY_FIRST.get(low[i], ())
               if len(t) > 1 or t[0] not in ("is", "be", "end", "finish", "go"))


def _group_shown(words: list[str], is_object) -> bool:
    """Whether ``words`` (those before the mover) name two objects ("Daisy and Max both need moving: Daisy goes
    ..."): what follows picks among them ("the other one" is the other of the two), which a reading of the end alone
    loses."""
    named = {w.strip(",.:;!?") for w in words if len(w.strip(",.:;!?")) > 1 and is_object(w.strip(",.:;!?"))}
    return len(named) >= 2


def _contracted(words: list[str]) -> list[str]:
    """``words`` with "X's" said for "X is" ("the mug's not so close") as two words."""
    return [part for w in words
            for part in ((w[:-2], "is") if w.lower().endswith(("'s", "\u2019s")) and len(w) > 2 else (w,))]


def _names_something(words: list[str]) -> bool:
    """Whether words before a mover's description name a thing ("cube", "one", "block"): the description that follows
    is then not the whole mover, so it is not taken for it."""
    low = [w.lower().strip(",.:;!?") for w in words]
    if low[-1:] and low[-1] in PLACE_ADJECTIVES and low[-2:-1] and low[-2] in DETERMINERS | set(PLACE_ADJECTIVES):
        return True  # "the front left thing goes ...": "the front" is the thing's own words, never dropped
    return bool(set(low) & (NOUNS | SHAPE_WORDS)) or any(  # "the can closest to the red cube goes ...": the can
        a in DETERMINERS and w in ("can", "cans") for a, w in zip(low, low[1:], strict=False))


NOW = (("right", "now"), ("currently",), ("at", "the", "moment"), ("at", "present"), ("presently",),
       ("as", "it", "stands"), ("as", "of", "now"), ("at", "this", "point"), ("still",))
"""Words that tell how the table is now, not how it should end: a statement with them is no goal."""


def said_now(low: list[str]) -> bool:
    return any(tuple(low[i:i + len(n)]) == n for n in NOW for i in range(len(low)))


TELLING = frozenset({("is",), ("'s",), ("are",), ("sits",), ("lies",), ("stands",), ("rests",), ("was",), ("were",)})
"""Links that, with nothing before the object ("The mug is next to the domino."), tell how the table is: a goal
needs words that ask ("I want", "the goal is", "should be", "make it so")."""


GOING = frozenset({"go", "goes", "went", "pass", "passes"})
"""Links of motion: "go by B" may mean past B or beside B (people differ), so it is asked, never guessed; "pass by B" is
asked here too, then read as past where the sentence is read again (language/learners.py: every author meant past)."""


SHAPE_WORDS = frozenset(SHAPE_NOUNS) - {"can", "cans"}  # "can we make it so ...": asks, names nothing
