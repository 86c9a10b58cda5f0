"""Objects named by one letter (alphabet blocks A, I, O, X), called as people say letters aloud.

A letter's name is a sound, and dictation writes the sound as a word ("ay", "eye", "oh", "ex"); a parent says "the
letter A", "letter eye"; a child "the oh". Most of these words are words of their own ("you" is the robot, "see" a
verb, "em" them as typed), so each is read as a letter only where the scene has that one-letter name, nothing on the
table is called by the word, and the word stands where one object is named: the whole of a reference ("toward ay"),
after "the" ("the oh") or after a noun ("block cue", "the letter eye").
"""

from __future__ import annotations

import re
from collections.abc import Callable

from ..core.scene import Scene
from ..errors import L2PError, LanguageError
from .reference_words import BLOCK_WORDS, NOUNS, SPOKEN_LETTERS, SPOKEN_ONLY_AFTER_NOUN
from .shape_words import SHAPE_NOUNS

LETTER_NOUNS = frozenset({"letter"})
"""Nouns that say the next word is a letter ("the letter O", "letter eye"): a noun before a letter's name."""
SAID_ALONE = frozenset({"ay", "bee", "sea", "gee", "eye", "kay", "oh", "ex"})
"""Spellings that are words of their own, yet name nothing else where one object is expected: the whole of a
reference ("drag the bucket toward ay", "around oh") is the letter. Not "you" (the robot), "em" (them), "are", "be",
"see", "owe", "tea" or "why", which a reference made of one word is as often a slip of the sentence around it."""
SAID_AFTER_THE = SAID_ALONE | frozenset({"be", "see", "tea", "owe", "are", "why", "em"})
"""Spellings read as the letter right after a determiner ("the oh", "the ex", "the see"): no pronoun follows
"the"; "you" never (the robot is "the robot", and "the you" no one says)."""


def letter_of(low: tuple[str, ...], determined: bool, letters: set[str], taken: set[str]) -> tuple[str, ...]:
    """``low`` (a reference's words, lower case, its determiners taken off; ``determined`` where there were some)
    with a letter said as a word at its end read as the one-letter name it spells ("block cue": block q, "the letter
    eye": one i, "the oh": o, "ay" alone: a), where ``letters`` (the scene's one-letter names, lower case) holds
    that letter and ``taken`` (the words that call an object) does not hold the word; ``low`` as it was otherwise."""
    low = _spelled(low, determined, letters, taken)
    if len(low) >= 2 and low[-2] in LETTER_NOUNS and low[-2] not in taken and low[-1] in letters:
        return (*low[:-2], "one", low[-1])  # "the letter O": the O one, a noun of every table
    return low


def _spelled(low: tuple[str, ...], determined: bool, letters: set[str], taken: set[str]) -> tuple[str, ...]:
    if not low:
        return low
    word = low[-1]
    letter = SPOKEN_LETTERS.get(word)
    if letter is None or word in taken or letter not in letters:
        return low
    before = low[-2] if len(low) >= 2 else None
    if before is not None and (before in NOUNS or before in BLOCK_WORDS or before in SHAPE_NOUNS
                               or before in LETTER_NOUNS):
        return (*low[:-1], letter)
    if len(low) == 1 and (word not in SPOKEN_ONLY_AFTER_NOUN or word in SAID_ALONE
                          or (determined and word in SAID_AFTER_THE)):
        return (letter,)
    return low


def letters_of(names: list[str]) -> set[str]:
    """The scene's one-letter names, lower case."""
    return {n.lower() for n in names if len(n) == 1 and n.isalpha()}


MARKED = re.compile(r"^(?P<head>.+?)\s+with\s+(?:the|an?)\s+(?:letter\s+|big\s+|capital\s+)?(?P<letter>[a-z]+)"
                    r"(?:\s+(?:on|printed\s+on|written\s+on|painted\s+on)\s+(?:it|its\s+side|its\s+front|top))?$",
                    re.IGNORECASE)
"""A block told by the letter on it: "the red one with the X on it", "the red block with an ex"."""


def marked_with(text: str, scene: Scene, role: str, resolve: Callable[..., str]) -> str | None:
    """The object whose one-letter name the letter after "with" is (said as written, "X", or aloud, "ex"), where the
    words before it describe that object too ("the red one with the X": X is red); None where ``text`` is not said so
    or the letter is no object's name (``resolve``: how one description is resolved, references.resolve_object). A
    letter on another colour's object than the one said is refused: the two words disagree."""
    m = MARKED.match(text)
    letters = letters_of(scene.names)
    if m is None or not letters:
        return None
    said = m.group("letter").lower()
    letter = said if len(said) == 1 else SPOKEN_LETTERS.get(said)
    if letter is None or letter not in letters:
        return None
    name = next(n for n in scene.names if n.lower() == letter)
    try:
        return resolve(m.group("head"), scene.only({name}), role)
    except L2PError:
        raise LanguageError(f'"{text}": {name} is not {m.group("head")}; name the one you mean') from None


ABC_ORDER = re.compile(r"\s*,?\s*\bin\s+(?:abc|a-b-c|a\s+b\s+c|alphabetical|alphabetic)\s+order\b", re.IGNORECASE)
LETTER_GROUP = re.compile(r"\b(?:all\s+)?(?:of\s+)?(?:the\s+)?(?:(?P<count>two|three|four|five|six|[2-9])\s+)?"
                          r"(?:letter\s+(?:blocks|cubes)|letters|alphabet\s+(?:blocks|cubes))\b", re.IGNORECASE)
"""The letter blocks put in the alphabet's order ("put all four letter blocks in ABC order in a row"): the list of
the scene's one-letter names, A to Z."""
COUNTS = {"two": 2, "three": 3, "four": 4, "five": 5, "six": 6}


def in_abc_order(sentence: str, scene: Scene) -> str:
    """``sentence`` with the letter blocks said in ABC order (:data:`LETTER_GROUP`, :data:`ABC_ORDER`) said as their
    list ("A, I, O and X"); ``sentence`` itself where it says no such thing, or a number that is not theirs."""
    order, group = ABC_ORDER.search(sentence), LETTER_GROUP.search(sentence)
    names = sorted((n for n in scene.names if len(n) == 1 and n.isalpha()), key=str.lower)
    if order is None or group is None or len(names) < 2:
        return sentence
    count = group.group("count")
    if count is not None and COUNTS.get(count.lower(), int(count) if count.isdigit() else 0) != len(names):
        return sentence
    text = sentence[:order.start()] + sentence[order.end():]
    group = LETTER_GROUP.search(text)
    return f"{text[:group.start()]}{', '.join(names[:-1])} and {names[-1]}{text[group.end():]}"


def said_letters(words: list[str], scene: Scene, taken: set[str]) -> bool:
    """Whether each of ``words`` is a letter said aloud that names one of the scene's one-letter objects ("line up ay
    eye oh and ex"), none of them a word that calls an object (``taken``): a list typed without commas."""
    letters = letters_of(scene.names)
    return bool(words) and all(SPOKEN_LETTERS.get(w.lower()) in letters and w.lower() not in taken for w in words)


def named_after_the(word: str, names: list[str]) -> bool:
    """Whether ``word`` (lower case), said right after "the", is a one-letter name, not a second article: "the a
    block", "the a one" (no one says "the a"; a scene with A means A)."""
    return len(word) == 1 and any(n.lower() == word for n in names)
