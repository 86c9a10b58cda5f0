"""The installed phrases as the grammar looks for them in a sentence's words: each phrase's tokens, longest first
(the longest phrase wins), with the ways people type a phrase besides as installed (its article left out, "to"
left out, a comparative for "away from").

Every reading of every clause asks for these tables, of the same installed phrases, so each is kept by the phrase
table's items, in order (lru_cache), and callers get lists of their own.
"""

from __future__ import annotations

import functools

from ..core.vocabulary import normalize_phrase
from .extents import COMPARATIVES, TIGHT_PHRASES

TIGHT = "right"
"""The extent of a tight gap ("right next to")."""


def phrase_tokens(phrases: dict[str, str]) -> list[tuple[tuple[str, ...], str, str]]:
    """(tokens, phrase, action) sorted longest first, so the longest phrase wins."""
    return list(_tokens_of(tuple(phrases.items())))


@functools.lru_cache(maxsize=64)
def _tokens_of(phrases: tuple[tuple[str, str], ...]) -> tuple[tuple[tuple[str, ...], str, str], ...]:
    table = {normalize_phrase(p): a for p, a in phrases}
    items = [(tuple(p.split()), p, a) for p, a in table.items() if p]
    return tuple(sorted(items, key=lambda t: (-len(t[0]), -len(t[1]), t[1])))


def readings(phrases: dict[str, str]) -> list[tuple[tuple[str, ...], str, str, str | None]]:
    """(tokens, phrase, action, implied extent) for every phrase, longest first; the comparatives people
    use for "away from" ("farther from", "far from") read as its phrase when it is installed, and a phrase typed
    without its article ("to other side of") as the phrase."""
    return list(_readings_of(tuple(phrases.items())))


@functools.lru_cache(maxsize=64)
def _readings_of(phrases: tuple[tuple[str, str], ...]) -> tuple[tuple[tuple[str, ...], str, str, str | None], ...]:
    out = [(t, p, a, TIGHT if p in TIGHT_PHRASES else None) for t, p, a in _tokens_of(phrases)]
    table = {normalize_phrase(p): a for p, a in phrases}
    for toks, phrase, action, _ in list(out):  # "to other side of", "in direction of": the article left out
        bare = tuple(w for w in toks if w != "the")
        if len(bare) > 1 and bare != toks and " ".join(bare) not in table:
            out.append((bare, phrase, action, None))
    for toks, (phrase, extent) in COMPARATIVES.items():
        if phrase in table and " ".join(toks) not in table:
            out.append((toks, phrase, table[phrase], extent))
    return tuple(sorted(out, key=lambda t: (-len(t[0]), -len(t[1]), t[1])))


def without_to(phrases: dict[str, str]) -> list[tuple[tuple[str, ...], str, str, str | None]]:
    """Phrases that end in "to" typed without it ("move the ball next the cube", "push A closer the duck"): read
    after every phrase as written has failed, and never by the lenient reading, which counts phrases."""
    return list(_without_to_of(tuple(phrases.items())))


@functools.lru_cache(maxsize=64)
def _without_to_of(phrases: tuple[tuple[str, str], ...]) -> tuple[tuple[tuple[str, ...], str, str, None], ...]:
    table = {normalize_phrase(p): a for p, a in phrases}
    return tuple((toks[:-1], phrase, action, None) for toks, phrase, action in _tokens_of(phrases)
                 if len(toks) > 1 and toks[-1] == "to" and " ".join(toks[:-1]) not in table)
