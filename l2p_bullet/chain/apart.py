"""What a sentence says about a clause apart from it: a pace or how far said alone ("Hurry!!", "Just a tiny bit
though."), a motion said after the end it should reach ("The jar needs to be next to the mug. Slide it over."), a
manner said apart ("Don't lift it.", "do it by carrying"). ``chain/clauses.py`` asks these where a clause does not
read as a command of its own.
"""

from __future__ import annotations

import re
from dataclasses import replace

from ..core.scene import Scene
from ..errors import L2PError, LanguageError
from ..language import Command, known_verbs, resolve_object, split_verb, strip_polite, tokens
from ..language.extents import take_extent, take_extent_tail
from ..language.words import take_pace, verb_of_gerund
from ..manners import registry as manners
from ..pipeline import resolve
from ..plugins import registry
from . import pointing
from .clause import Clause
from .completion import ONCE_MORE


def pace_alone(text: str, scene: Scene) -> str | None:
    """The pace a clause asks for when it says nothing else ("Hurry!!", "Slowly please"); None otherwise."""
    keep = frozenset(scene.names)
    try:
        words, pace = take_pace(strip_polite(tokens(text), keep), keep)
    except L2PError:
        return None
    return pace if not strip_polite(words, keep) else None


def extent_alone(text: str) -> str | None:
    """How far a clause asks when it says nothing else ("Just a tiny bit though.", "But only a little", "like actually
    touching it"); None otherwise."""
    words = [w for w in strip_polite(tokens(text)) if w.lower() not in ("though", "but", "only")]
    rest, extent = take_extent(["_", *words])
    if rest == ["_"]:
        return extent
    rest, extent = take_extent_tail(["_", *words])  # "... snug against the notebook. like actually touching it"
    return extent if rest == ["_"] else None


def extended(clause: Clause, extent: str, plugins: list) -> Clause:
    """``clause`` asked to go ``extent`` far by the sentence after it; a one-line error where its action takes no such
    extent or it asked for another."""
    command = clause.command
    accepted = registry.extent_table(plugins).get(command.action, frozenset())
    if command.extent not in (None, extent) or extent not in accepted:
        raise LanguageError(f'"{clause.text}" cannot also go a {extent} way ("{command.preposition}" takes: '
                            f"{', '.join(sorted(accepted)) or 'none'})")
    return replace(clause, command=replace(command, extent=extent))


def paced(clause: Clause, pace: str) -> Clause:
    """``clause`` at ``pace``; a clause that asks for another pace of its own is a one-line error."""
    if clause.command.pace not in (None, pace):
        raise LanguageError(f'"{clause.text}" asks for a {clause.command.pace} pace, and the sentence around it for a '
                            f"{pace} one; say one of them")
    return replace(clause, command=replace(clause.command, pace=pace))


def done_so(text: str, before: Clause) -> Clause | None:
    """The clause before, done in the manner ``text``'s verb names, where ``text`` only says to do it so ("push it
    there", "slide it over"); None for any other text or a clause before that moved something else."""
    m = pointing.DO_IT.match(" ".join(strip_polite(text.split())) or text)  # "Just slide it over."
    if m is None or before.target is not None:
        return None
    try:
        verb, manner, _ = split_verb(m.group("verb").split())
        ruled_out = split_verb([m.group("not")])[1] if m.group("not") else None  # "Carry it over, don't drag it."
    except L2PError:
        return None
    if m.group("tail") is None and _has_verb(before.text) and (
            manner == before.command.manner or not AFTERTHOUGHT.search(text)):
        return None  # "Move A past B. Then push it.": a step left unsaid; "... lift it though" is how to do it
    if ruled_out == manner:
        return None
    return replace(before, command=replace(before.command, verb=verb, manner=manner))


def wishes_done(clauses: list[Clause], scene: Scene, sentence: str) -> list[Clause]:
    """``clauses`` with a clause that only orders the end the clause before wished for ("The idea is that the globe is
    not so near to the box, move it away") read as that one move (:func:`done_as_wished`), and a verbless clause that
    only says which object the next one's "it" is ("the little one next to the globe, move it towards the apple")
    read past (:func:`topic_first`); numbered again. ``sentence``: the text they were read from."""
    out: list[Clause] = []
    for c in clauses:
        wished = (done_as_wished(out[-1], c) or topic_first(out[-1], c, scene, sentence)) if out else None
        if wished is not None:
            out[-1] = replace(wished, index=len(out))
        else:
            out.append(replace(c, index=len(out) + 1))
    return out


def done_as_wished(before: Clause, after: Clause) -> Clause | None:
    """``before`` as ``after`` orders it, where ``before`` only wished for an end ("The idea is that the globe is not so
    near to the chalk box") and ``after``, with a verb, refers back to it and asks for the same move ("move it away"):
    one move, in ``after``'s manner and pace; None otherwise. A clause that says to go on ("move it further", "again")
    is a move of its own. Read from the sentences the commands were read from: two pieces of one text share it."""
    wished, said = before.command, after.command
    if not _plain(before) or not _plain(after) or _has_verb(wished.sentence) or not _has_verb(said.sentence) \
            or not IT.search(said.sentence) or ONCE_MORE.search(said.sentence):
        return None
    if (said.mover, said.action, said.anchors) != (wished.mover, wished.action, wished.anchors) \
            or said.extent not in (None, wished.extent):
        return None
    text = before.text if after.text == before.text else f"{before.text} {after.text}".strip()
    return replace(before, text=text, command=replace(said, extent=said.extent or wished.extent,
                                                      pace=said.pace or wished.pace, sentence=wished.sentence))


def topic_first(before: Clause, after: Clause, scene: Scene, sentence: str) -> Clause | None:
    """``after`` alone where ``before``, read as a command without a verb ("the little one next to the globe"), is
    only the object ``after`` then orders with "it", said first and described by where it stands ("the little one
    next to the globe, move it towards the apple"): the two parts joined by a comma alone, the first a description
    (an article first) whose words name that very object, and whose place alone names it too ("the one next to the
    globe" is the eraser: it stands there already). With "then", a full stop or a step's number between them, or
    where another object is the one so placed ("the apple next to the globe, ..."), they are two moves."""
    wished, said = before.command, after.command
    if not _plain(before) or not _plain(after) or _has_verb(wished.sentence) or not _has_verb(said.sentence) \
            or not IT.search(said.sentence) or said.mover != wished.mover \
            or f"{before.text}, {after.text}" not in sentence:
        return None
    whole = wished.sentence.strip(" .,;:!?")
    parts = re.split(rf"\s+{re.escape(wished.preposition)}\s+", whole, maxsplit=1, flags=re.IGNORECASE)
    if len(parts) != 2 or parts[0].lower().split()[:1] not in (["the"], ["that"], ["this"]):
        return None
    try:
        if resolve_object(whole, scene) != wished.mover or \
                resolve_object(f"the one {wished.preposition} {parts[1]}", scene) != wished.mover:
            return None
    except L2PError:
        return None
    return replace(after, text=f"{before.text}, {after.text}")


def _plain(clause: Clause) -> bool:
    """Whether ``clause`` is a move of its own, not a composite's step."""
    return clause.target is None and clause.group is None


IT = re.compile(r"\b(?:it|that|this one|that one)\b", re.IGNORECASE)
"""Words that point back at the object a clause before named."""


AFTERTHOUGHT = re.compile(r"\b(?:though|tho|instead|rather)\b", re.IGNORECASE)
"""Words that say a clause is how to do the one before, not a step of its own ("... Lift it though")."""


def _has_verb(text: str) -> bool:
    """Whether a clause's words start with a verb (after politeness): "N right up against the bar" has none."""
    try:
        split_verb(strip_polite(text.split()) or text.split())
    except L2PError:
        return False
    return True


NOT_LIFTED = re.compile(r"^\s*(?:and\s+)?(?:please\s+)?(?:don't|dont|do\s+not|never|no)\s+"
                        r"(?:lift|lifting|carry|carrying|pick|picking)(?:\s+it)?(?:\s+up)?(?:\s+please)?\s*[.!]*\s*$",
                        re.IGNORECASE)
NOT_DRAGGED = re.compile(r"^\s*(?:and\s+|but\s+)?(?:please\s+)?(?:don't|dont|do\s+not|never|no|without)\s+"
                         r"(?:drag|dragging|slide|sliding)(?:\s+it)?(?:\s+(?:on|along|across|over)\s+the\s+(?:table|bench|workbench|desk|surface))?"
                         r"(?:\s+please)?\s*[.!]*\s*$", re.IGNORECASE)
BY_MANNER = re.compile(r"^\s*(?:and\s+)?(?:do\s+it\s+|please\s+)?by\s+(?P<how>[a-z]+ing)(?:\s+it)?\s*[.!]*\s*$",
                       re.IGNORECASE)
NOT_DRAGGED_FIRST = re.compile(r"^\s*without\s+(?P<how>dragging|sliding)\s+it"
                               r"(?:\s+(?:on|along|across|over)\s+the\s+(?:table|bench|workbench|desk|surface))?"
                               r"\s*,\s*(?P<rest>.+)$", re.IGNORECASE)
"""A manner said apart after its clause: "Don't lift it." keeps a slide a slide; "don't drag it" makes a slide a
carry (the one way to move a block without dragging it), as "do it by carrying" does, and as "Without dragging it,"
before the clause does (:data:`NOT_DRAGGED_FIRST`)."""


def manner_after(text: str, before: Clause) -> Clause | None:
    """The clause before in the manner ``text`` says apart (:data:`NOT_LIFTED`, :data:`BY_MANNER`); None for any other
    text, or where it rules out the manner the clause before asked for."""
    if before.target is not None:
        return None
    if NOT_LIFTED.match(text):
        return before if before.command.manner == "slide" else None
    if NOT_DRAGGED.match(text):
        if before.command.manner == "carry" or (before.command.manner == "slide" and not _dragged(before)):
            return replace(before, command=replace(before.command, verb="carry", manner="carry"))
        if before.command.manner == "push":
            return before
        raise LanguageError(f'"{before.text}" drags the block and "{text.strip()}" asks not to; say "carry" or '
                            '"lift" to have it lifted')
    m = BY_MANNER.match(text)
    if m is None:
        return None
    verb = verb_of_gerund(m.group("how").lower(), known_verbs())
    if verb is None:
        return None
    try:
        verb, manner, _ = split_verb([verb])
    except L2PError:
        return None
    return replace(before, command=replace(before.command, verb=verb, manner=manner))


def _dragged(clause: Clause) -> bool:
    """Whether the clause's own verb says to drag or slide (then "don't drag it" contradicts it)."""
    return clause.command.verb.lower() in ("drag", "slide")


def away_from_shown(text: str, show: pointing.Shown | None, scene: Scene, plugins: list) -> list[Command] | None:
    """"The mug and the domino are too close together. Fix that by moving the mug.": a clause that only moves one of
    two objects said to be too close moves it away from the other; None where it does not read so."""
    if show is None or not show.crowded or len(show.objects) != 2:
        return None
    read = []
    for other in show.objects:
        try:
            cmd = resolve(f"{text.rstrip(' .!?')} away from {other}", scene, plugins, None)
        except L2PError:
            continue
        if cmd.mover in show.objects and cmd.mover != other:
            read.append(replace(cmd, sentence=text))
    return read if len(read) == 1 else None


CONFIRM = re.compile(r"^\s*(?:and\s+)?(?:so\s+)?(?:please\s+)?(?:just\s+)?(?P<verb>[a-z]+)\s+(?P<what>.+?)"
                     r"(?:\s*,?\s+(?:but\s+)?not\s+(?P<not>.+?)|\s+only|\s*,?\s+(?:and\s+)?leave\s+(?P<leave>.+?)"
                     r"(?:\s+(?:where\s+it\s+is|alone|be))?)?\s*[.!]*\s*$", re.IGNORECASE)
"""A clause that only says which of the two objects the clause before named is to move: "Move the box, not the cube.",
"Move obj4 only.", "move the cylinder"."""
DASH_THEN = re.compile(r"^(?P<before>.+?)\s+[-\u2013\u2014]+\s+(?P<after>[a-z]+\s+.+)$", re.IGNORECASE)
"""An end said, a dash, then which object moves: "Make it so the cylinder isn't so close to the cup - move the
cylinder"."""


def confirmed(text: str, before: Clause, scene: Scene) -> Clause | None:
    """The clause before, where ``text`` (:data:`CONFIRM`) names its mover as the one to move (and its reference, if
    at all, as the one not to), in the manner the verb names where it names one; None for any other text."""
    m = CONFIRM.match(text)
    if m is None or before.target is not None:
        return None
    cmd = before.command
    named = scene.only((cmd.mover, *cmd.anchors))
    try:  # "the cube" is the cube of the two the clause before named
        verb, manner, rest = split_verb([m.group("verb")])
        what = resolve_object(m.group("what"), named, "block to move")
        kept = m.group("not") or m.group("leave")
        other = resolve_object(kept, named, "block to leave") if kept else None
    except L2PError:
        return None
    if rest or what != cmd.mover or (other is not None and other not in cmd.anchors):
        return None
    if manner != manners.DEFAULT:  # "Push the box, not the cube": how, as well as which
        cmd = replace(cmd, verb=verb, manner=manner)
    return replace(before, command=cmd)
