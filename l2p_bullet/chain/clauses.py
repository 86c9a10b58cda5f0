"""A chain sentence -> its clauses, each resolved to a :class:`~l2p_bullet.language.Command` up front.

"move A next to B, then slide C past A and then move D around B" is three clauses, joined by ``, then``,
``and then``, ``then``, ``after that`` or ``;``. A clause without a verb repeats the previous clause's
verb ("move A around B, then next to C"); one that starts with the preposition repeats its mover too.
Every clause is resolved against the scene before anything is planned or moved, so a typo, an unknown
colour or a block that is not in the scene in clause 3 costs milliseconds and names the clause.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, replace
from typing import Any

from ..core.scene import Scene
from ..errors import L2PError, LanguageError
from ..language import (
    MAX_SENTENCE,
    TRAILING_JOINS,
    Command,
    Context,
    command_words,
    known_verbs,
    phrase_tokens,
)
from ..manners import registry as manners
from ..pipeline import resolve
from ..plugins import registry

MAX_CLAUSES = 10
"""Most clauses in one chain: past a handful of steps errors compound (CALVIN judges chains of five)."""

_JOINS = re.compile(r"\s*(?:;|,?\s*\band\s+then\b|,?\s*\bthen\b|,?\s*\bafter\s+that\b)\s*,?\s*", re.IGNORECASE)


@dataclass(frozen=True)
class Group:
    """A composite's place in a chain ("make a row of A, B and C, then ..."): its action and objects in the
    order named; the clauses it expands to carry it, so the whole is judged as a row."""

    action: str
    objects: tuple[str, ...]
    text: str


@dataclass(frozen=True)
class Clause:
    """One step of a chain: its 1-based ``index``, its own ``text`` and what it asks for."""

    index: int
    text: str
    command: Command
    target: Any = None  # a composite's place for the mover: scene -> [x, y, yaw] (chain/composite.py), or None
    group: Group | None = None  # the composite this clause is a step of, or None

    def label(self) -> str:
        """How errors and captions name the clause: 'clause 2 ("slide C past A")'."""
        return f'clause {self.index} ("{self.text}")'


def split_clauses(sentence: str) -> list[str]:
    """The clauses' texts, in order (empty pieces, e.g. a leading "then", dropped)."""
    if not isinstance(sentence, str):
        return []
    return [p.strip(" ,.") for p in _JOINS.split(sentence) if p.strip(" ,.")]


def is_chain(sentence: str, plugins: list | None = None) -> bool:
    """More than one clause, or a composite action's sentence ("make a row of A, B and C", whose clauses
    its recipe makes: chain/composite.py): ``perform`` runs it as a chain; one clause keeps today's run."""
    from .composite import is_composite  # lazy: chain/composite.py imports this module's Clause

    return len(split_clauses(sentence)) > 1 or is_composite(sentence, plugins)


def resolve_clauses(sentence: str, scene: Scene, plugins: list) -> list[Clause]:
    """Every clause parsed against ``scene`` and the installed phrases; the first problem raised as a
    one-line error of its own type (LanguageError, UnknownObjectError...) that names the clause."""
    from .composite import composite_clauses  # lazy: see is_chain

    texts = split_clauses(sentence)
    if not texts:
        raise LanguageError('the sentence is empty; try for example "move A next to B, then move C around A"')
    dangling = _dangling(sentence)
    if dangling:
        raise LanguageError(f'the sentence ends with "{dangling}" but no clause follows it; add the next clause '
                            f'("..., {dangling} move C past A") or drop "{dangling}"')
    if len(texts) > MAX_CLAUSES:
        raise LanguageError(f"the chain has {len(texts)} clauses; a chain has at most {MAX_CLAUSES}")
    clauses: list[Clause] = []
    for i, text in enumerate(texts, start=1):
        if len(text) > MAX_SENTENCE:
            raise LanguageError(f'clause {i} is {len(text)} characters long; a clause has at most {MAX_SENTENCE}')
        made = composite_clauses(text if len(texts) > 1 else sentence, scene, plugins)
        if made is not None:  # a composite's steps, numbered on from the clauses before it
            clauses.extend(replace(c, index=len(clauses) + 1) for c in made)
            continue
        full = _complete(text, clauses[-1].command if clauses else None, scene, plugins)
        previous = clauses[-1].command if clauses else None
        context = Context(previous.mover, previous.anchor) if previous is not None else None
        try:
            cmd = resolve(full, scene, plugins, context)
        except L2PError as e:
            raise _named(e, f'clause {i} ("{text}")') from None
        clauses.append(Clause(len(clauses) + 1, text, cmd))
    if len(clauses) > MAX_CLAUSES:
        raise LanguageError(f"the chain has {len(clauses)} moves; a chain has at most {MAX_CLAUSES}")
    return clauses


def _dangling(sentence: str) -> str | None:
    """The joining words a sentence ends with when no clause follows them ("move A around B, then")."""
    words = sentence.rstrip(" .!?,").split()
    for join in TRAILING_JOINS:
        if len(words) > len(join) and tuple(w.lower() for w in words[-len(join):]) == join:
            return " ".join(words[-len(join):])
    return None


def _complete(text: str, previous: Command | None, scene: Scene, plugins: list) -> str:
    """The clause as a full sentence: the previous verb prepended when it has none, and the previous mover
    too when it starts with a preposition ("then next to C" after "move A around B": "move A next to C")."""
    words = command_words(text, scene)[0]
    if previous is None or not words or words[0].lower() in known_verbs():
        return text
    # "lift A and put it next to B, then around C": the gap verb needs its gap, the manner's name does not
    verb = previous.manner if _gapped(previous.verb) else previous.verb

    low = tuple(w.lower() for w in words)
    for toks, _phrase, _action in phrase_tokens(registry.phrase_table(plugins)):
        if low[: len(toks)] == toks:
            return f"{verb} {previous.mover} {text}" if text.split()[0].lower() == low[0] else f"{verb} {text}"
    return f"{verb} {text}"


def _gapped(verb: str) -> bool:
    """Whether ``verb`` is the head of a manner's gap verb ("lift" of "lift ... and put")."""
    return any(v.split("...")[0].strip() == verb and "..." in v for v in manners.verb_table())


def _named(e: L2PError, where: str) -> L2PError:
    """``e`` (same type and attributes: an InfeasibleError keeps its ``check``) with its message prefixed."""
    e.args = (f"{where}: {e}",) + e.args[1:]
    return e
