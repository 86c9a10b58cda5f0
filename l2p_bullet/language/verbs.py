"""A sentence's verb -> the manner of motion it asks for, and the closing words that say so again.

Which verbs are known is not the grammar's to fix: the installed manners declare them ("carry", "lift ... and
put"), so the verb is read against their table, a gap verb's phrase taken out of the words, and the words that
only repeat the manner ("without lifting it", "through the air", "with your fingers") read past or refused where
they contradict it. Kept apart from the grammar (language/grammar.py), which reads what follows the verb.
"""

from __future__ import annotations

import functools

from ..errors import LanguageError, did_you_mean
from ..manners import registry as manners

VERBS: tuple[str, ...] = ("move", "slide", "push", "shift", "put")
"""The plain verbs of a slide; every installed manner's verbs are known too (:func:`known_verbs`)."""
OBJECT_PRONOUNS = frozenset({"it", "them", "him", "her"})
"""What may follow a manner's gap phrase: "lift A and put *it* next to B"."""
EXAMPLE = 'try for example "move A around B" or "slide the red block next to the green one"'


def known_verbs() -> list[str]:
    """Every verb a sentence may start with (its first word): the old ones first, then the manners'."""
    return list(_known_verbs(tuple(manners.verb_table())))


@functools.lru_cache(maxsize=8)
def _known_verbs(declared: tuple[str, ...]) -> tuple[str, ...]:
    """:func:`known_verbs` of the manners' verbs as declared, kept by them: every clause read asks for them."""
    out = list(VERBS)
    for v in declared:
        head = v.split("...")[0].strip()
        if head not in out:
            out.append(head)
    return tuple(out)


def verb_heads() -> frozenset[str]:
    """The known verbs' first words ("pick" of "pick up"): words that open a command, never a description. Asked
    each time, as :func:`known_verbs` is, so a manner installed later counts."""
    return frozenset(v.split()[0] for v in known_verbs())


Pattern = tuple[tuple[str, ...], tuple[str, ...], str, str]
"""(head tokens, gap tokens, verb as declared, manner)."""


def _verb_patterns() -> list[Pattern]:
    """(head tokens, gap tokens, verb as declared, manner) for every installed manner's verb, longest first;
    the old verbs no manner claims are the default manner's."""
    return list(_patterns_of(tuple(manners.verb_table().items())))


@functools.lru_cache(maxsize=8)
def _patterns_of(declared: tuple[tuple[str, str], ...]) -> tuple[Pattern, ...]:
    """:func:`_verb_patterns` of the manners' (verb, manner) pairs, kept by them: every clause read asks for them."""
    table = dict(declared)
    for v in VERBS:
        table.setdefault(v, manners.DEFAULT)
    out = []
    for v, m in table.items():
        head, _, gap = v.partition("...")
        out.append((tuple(head.lower().split()), tuple(gap.lower().split()), v, m))
    return tuple(sorted(out, key=lambda t: -len(t[0]) - len(t[1])))  # stable: a manner's own order among equals


def split_verb(words: list[str]) -> tuple[str, str, list[str]]:
    """(verb, manner, the words after the verb) of a sentence's ``words``: the manner whose verb starts them
    (a gap verb's phrase, "lift A *and put it* next to B", is taken out of the rest); a one-line error with
    did-you-mean when no manner's verb does."""
    low = [w.lower() for w in words]
    near_miss = None
    for head, gap, declared, manner in _verb_patterns():
        if tuple(low[: len(head)]) != head:
            continue
        rest = list(words[len(head):])
        if not gap:
            return " ".join(head), manner, rest
        lrest = [w.lower() for w in rest]
        at = next((i for i in range(1, len(rest) - len(gap) + 1) if _gap_at(lrest[i: i + len(gap)], gap)), None)
        if at is None:
            near_miss = near_miss or declared
            continue
        end = at + len(gap) + (1 if at + len(gap) < len(rest) and lrest[at + len(gap)] in OBJECT_PRONOUNS else 0)
        held = rest[:at][:-1] if at > 1 and lrest[at - 1] == "up" else rest[:at]  # "lift the bottle up and ..."
        return " ".join(head), manner, _over_then_side(held, rest[end:])
    if near_miss is not None:
        head, _, gap = near_miss.partition("...")
        raise LanguageError(f'"{head.strip()}" asks for "{near_miss}": say what to do with the block, as in '
                            f'"{head.strip()} A{gap} it next to B"')
    known = known_verbs()
    raise LanguageError(f'"{words[0]}" is not a verb I know (known: {", ".join(known)}).'
                        + did_you_mean(low[0], known) + f" {EXAMPLE[0].upper()}{EXAMPLE[1:]}")


def _over_then_side(held: list[str], after: list[str]) -> list[str]:
    """"lift Q over P and put it down on the other side": the side is P's, so the words read "Q on the other
    side of P"; any other gap sentence is returned as it is."""
    low_held, low_after = [w.lower() for w in held], [w.lower() for w in after]
    if "over" not in low_held[1:]:
        return held + after
    k = low_held.index("over", 1)
    side = low_after[1:] if low_after[:1] == ["down"] else low_after
    if len(side) == 4 and side[0] in ("on", "to") and side[1] == "the" and side[2] in ("other", "far") \
            and side[3] == "side":
        return held[:k] + after[len(after) - 4:] + ["of"] + held[k + 1:]
    return held + after


PLACING_VERBS = frozenset({"put", "place", "set", "drop", "lay", "carry", "move", "bring", "take", "lower", "stick"})
"""A gap verb's last word may be any of these: "lift A and *set* it down next to B" is "lift ... and put"."""


def _gap_at(words: list[str], gap: tuple[str, ...]) -> bool:
    """Whether ``words`` are the gap ``gap``, a placing verb standing for another at its end."""
    if tuple(words) == gap:
        return True
    return (len(words) == len(gap) and tuple(words[:-1]) == gap[:-1] and gap[-1] in PLACING_VERBS
            and words[-1] in PLACING_VERBS)


ON_THE_TABLE = tuple(tuple(p.split()) for p in (
    "without lifting it up", "without lifting it", "without lifting", "without picking it up",
    "without picking it", "keeping it on the table", "keeping it down", "maintaining contact with the table surface",
    "maintaining contact with the table", "along the table surface",
))
"""Closing words that say the object stays on the table: what a slide or a push does anyway, and what a carry
cannot do."""


IN_THE_AIR = tuple(tuple(p.split()) for p in (
    "up off the table", "off the table", "through the air", "thru the air", "in the air", "into the air",
    "up in the air",
))
"""Words that say the object is lifted: read past, wherever they stand, after a verb that lifts it."""


def _without(words: list[str], phrases: tuple[tuple[str, ...], ...]) -> list[str]:
    """``words`` without every occurrence of ``phrases`` (longest first)."""
    out, i, low = [], 0, [w.lower() for w in words]
    ordered = sorted(phrases, key=len, reverse=True)
    while i < len(words):
        hit = next((p for p in ordered if tuple(low[i:i + len(p)]) == p), None)
        if hit is None:
            out.append(words[i])
            i += 1
        else:
            i += len(hit)
    return out


WITH_FINGERS = tuple(tuple(p.split()) for p in (
    "with your fingers", "with the fingers", "with its fingers", "using your fingers", "using the fingers",
    "with your fingertips", "with the fingertips",
))
"""Words that say how a push is done: read past right after a push's verb or at its end ("Push with your fingers the
ball ...", "bump the tray toward the bear with your fingers"); after another verb they are left, and the sentence is
refused as written."""


def _on_the_table(rest: list[str], manner: str, sentence: str) -> list[str]:
    """``rest`` without closing words of :data:`ON_THE_TABLE` (or of :data:`WITH_FINGERS` after a push); a
    one-line error where the manner lifts the object ("carry A past B without lifting it" asks for two things at
    once)."""
    if manners.get(manner).airborne:  # "lift the rabbit up off the table and take it through the air past X"
        rest = _without(rest, IN_THE_AIR)
    low = tuple(w.lower() for w in rest)
    if manner == "push":
        tail = next((t for t in WITH_FINGERS if len(low) > len(t) and low[-len(t):] == t), None)
        if tail is not None:
            return _on_the_table(rest[:-len(tail)], manner, sentence)
        head = next((t for t in WITH_FINGERS if len(low) > len(t) and low[:len(t)] == t), None)
        if head is not None:  # "Push with your fingers the ball toward the tile"
            return _on_the_table(rest[len(head):], manner, sentence)
    for tail in ON_THE_TABLE:
        if len(low) > len(tail) and low[-len(tail):] == tail:
            if manners.get(manner).airborne:
                raise LanguageError(f'"{sentence.strip()}" asks to {manner} the object and to keep it on the table; '
                                    "say one of them")
            return rest[:-len(tail)]
    return rest
