"""Objects named by one letter (alphabet blocks A, I, O, X), called as people say letters aloud.

A letter's name is a sound, and dictation writes the sound as a word ("ay", "eye", "oh", "ex"); a parent says "the
letter A", "letter eye"; a child "the oh". Most of these words are words of their own ("you" is the robot, "see" a
verb, "em" them as typed), so each is read as a letter only where the scene has that one-letter name, nothing on the
table is called by the word, and the word stands where one object is named: the whole of a reference ("toward ay"),
after "the" ("the oh") or after a noun ("block cue", "the letter eye").
"""

from __future__ import annotations

from .reference_words import BLOCK_WORDS, NOUNS, SHAPE_NOUNS, SPOKEN_LETTERS, SPOKEN_ONLY_AFTER_NOUN

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
