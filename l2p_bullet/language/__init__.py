"""Sentence -> what to do: the grammar (grammar.py), its verb and manner (verbs.py), the words around a command
(words.py), the objects a sentence names (references.py, descriptions.py, naming.py, pronouns.py) and lists of
objects for composites (lists.py). One grammar, documented in docs/perform.md ("Sentences")."""

from .grammar import (
    MAX_SENTENCE,
    Command,
    command_words,
    dangling_join,
    manner_of_sentence,
    parse,
    phrase_tokens,
    tokens,
    trailing_join,
)
from .lists import ListCommand, parse_list, phrase_matches
from .pronouns import Context
from .references import resolve_object
from .verbs import EXAMPLE, VERBS, known_verbs, split_verb, verb_heads
from .words import is_courtesy, strip_polite

__all__ = [
    "EXAMPLE",
    "MAX_SENTENCE",
    "VERBS",
    "Command",
    "command_words",
    "dangling_join",
    "Context",
    "ListCommand",
    "is_courtesy",
    "known_verbs",
    "verb_heads",
    "manner_of_sentence",
    "parse",
    "parse_list",
    "phrase_matches",
    "phrase_tokens",
    "resolve_object",
    "split_verb",
    "strip_polite",
    "tokens",
    "trailing_join",
]
