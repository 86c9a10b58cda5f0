"""A clause said without its verb, or without its verb and mover, completed from the clause before it.

"move A around B, then next to C" reads its second clause as "move A next to C"; "The football is too close to the
cup. Move it away." reads "Move it away" as away from the cup. A clause that opens with a verb is left as it is, and
the anchor is only filled in where the clause reads no other way (chain/clauses.py)."""

from __future__ import annotations

import re

from ..core.scene import Scene
from ..language import Command, Context, command_words, known_verbs, phrase_tokens, typos
from ..language.extents import LONGEST_FIRST
from ..manners import registry as manners
from ..plugins import registry


def complete(text: str, previous: Command | None, scene: Scene, plugins: list) -> str:
    """The clause as a full sentence: the previous verb prepended when it has none, and the previous mover
    too when it starts with a preposition ("then next to C" after "move A around B": "move A next to C")."""
    words = command_words(text, scene)[0]
    if previous is None or not words or words[0].lower() in known_verbs():
        return text
    phrases = phrase_tokens(registry.phrase_table(plugins))
    if _verb_of_its_own(words, previous, phrases):
        return text
    # "lift A and put it next to B, then around C": the gap verb needs its gap, the manner's name does not
    verb = previous.manner if gapped(previous.verb) else previous.verb

    low = tuple(w.lower() for w in words)
    raw = tuple(w.lower().strip(",.!?;") for w in text.split())
    said = next((len(k) for k in LONGEST_FIRST if raw[:len(k)] == k), 0)  # "then right next to C"
    if len(low) > 2 and low[0] == "back" and raw[0] == "back" and any(low[1:1 + len(t)] == t for t, _, _ in phrases):
        return f"{verb} {previous.mover} {' '.join(text.split()[1:])}"  # "..., then back toward the vial"
    for toks, _phrase, action in phrases:
        if said and raw[said:said + len(toks)] == toks and (raw[said + len(toks):][:1] not in SAID_AGAIN
                                                             or action != previous.action):
            # "..., tight against it" after a next-to: the clause said again, no step; "then a little past it" after
            # a closer: a step of its own
            return f"{verb} {previous.mover} {text}"
        if low[: len(toks)] == toks:
            return f"{verb} {previous.mover} {text}" if text.split()[0].lower() == low[0] else f"{verb} {text}"
    return f"{verb} {text}"


def _verb_of_its_own(words: list[str], previous: Command, phrases: list) -> bool:
    """Whether a clause opens with a verb of its own that is not known: a word before "it" that opens no phrase and is
    no slip of the verb before ("..., then park it next to the mug" is no push; "pish it" after a push is the push;
    "leave it beside C" says where that move ends)."""
    first = words[0].lower()
    return len(words) > 1 and words[1].lower() in ("it", "them") and first != "leave" \
        and not any(toks[0] == first for toks, _, _ in phrases) \
        and typos.near(first, frozenset({previous.verb.lower()})) is None


SAID_AGAIN = {("it",), ("them",), ("that",)}
"""Words a verbless clause's reference opens with when it repeats the clause before ("..., only slightly past it")."""


def gapped(verb: str) -> bool:
    """Whether ``verb`` is the head of a manner's gap verb ("lift" of "lift ... and put")."""
    return any(v.split("...")[0].strip() == verb and "..." in v for v in manners.verb_table())


BARE_END = re.compile(r"\s+(?:back\s+)?(?P<word>[a-z]+)(?:\s+again)?"
                      r"(?P<far>\s+(?:a\s+(?:little\s+)?bit|a\s+little|slightly|a\s+lot|far))?\s*[?.!]*\s*$",
                      re.IGNORECASE)
"""A clause that ends with the first word of a two-word phrase and names nothing after it ("Move it away", "bring it
back closer", "move it away a bit")."""


def to_the_anchor(text: str, context: Context | None, plugins: list) -> str | None:
    """``text`` with the phrase its last word opens and the object the clause before named as the reference ("Move it
    away" after "The football is too close to the cup": away from the cup); None where it does not end so."""
    m = BARE_END.search(text)
    if m is None or context is None or context.anchor is None:
        return None
    word = m.group("word").lower()
    table = registry.phrase_table(plugins)
    phrase = next((p for p in table if p.split()[0] == word and len(p.split()) == 2), None)
    far = m.group("far") or ""  # "move it away a bit": how far before the phrase, where the grammar reads it
    return None if phrase is None or word in table else f"{text[:m.start()]}{far} {phrase} {context.anchor}"




ONCE_MORE = re.compile(r"\b(?:again|more|even|further|farther|still|too|also|back)\b", re.IGNORECASE)
"""Words that make a verbless clause a step of its own even where it repeats the clause before ("closer again")."""


def said_again(text: str, command: Command, previous: Command | None, scene: Scene) -> bool:
    """Whether ``text``, read as ``command``, only says the clause before once more: no verb of its own and the same
    mover, action, anchors and extent ("could the 500 be a lot closer to the rack? much closer"), and the same pace
    where it says one. Such a clause asks for no second move."""
    if previous is None or ONCE_MORE.search(text):
        return False
    words = command_words(text, scene)[0]
    if not words or words[0].lower() in known_verbs():
        return False
    same = ("mover", "action", "anchors", "extent") + (("pace",) if command.pace is not None else ())
    # a state said again keeps no manner or pace of its own ("push K toward P3, fast. Expected: K closer to P3.")
    return all(getattr(command, f) == getattr(previous, f) for f in same)


OUTCOME = re.compile(r"\s*(?:expected|desired|target|goal|final)(?:\s+(?:end\s+)?(?:result|outcome|state))?\s*:",
                     re.IGNORECASE)
"""A label that says what a step should leave ("Expected: K closer to P3."): after the step, a check of it."""


def checks_the_steps(text: str, commands: list[Command], before: list[Command]) -> bool:
    """Whether ``text``, read as ``commands``, is the result the steps before it should leave, labelled so
    (:data:`OUTCOME`): each of its moves moves a mover of ``before`` as that step did (the same action and anchors).
    Such a text asks for no move; a result no step made is a move of its own."""
    return bool(OUTCOME.match(text)) and all(
        any((b.mover, b.action, b.anchors) == (c.mover, c.action, c.anchors) for b in before) for c in commands)
