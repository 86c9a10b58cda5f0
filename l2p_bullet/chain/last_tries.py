"""The last tries of a sentence every reading has refused as typed and as mended (chain/clauses.py): each allows one
more kind of reading past words the grammar does not know, in the order that guesses least first.
"""

from __future__ import annotations

from collections.abc import Callable

from ..core.scene import COLORS, Scene
from ..errors import L2PError
from ..language import lenient, lexicon, remarks, verb_heads
from ..language.naming import naming_words
from ..language.reference_words import COLOR_SYNONYMS, NOUNS
from ..language.synonyms import SIZE_WORDS
from ..language.words import NEGATIONS
from ..plugins import registry


def read_past(sentence: str, mended: str | None, scene: Scene, plugins: list, known: frozenset[str],
              read_clauses: Callable[[str, Scene, list], list]) -> list | None:
    """The sentence's mended form (then the sentence as typed) read once more with the lenient reading allowed
    (language/lenient.py), then again with words looked up in WordNet naming objects and moving them too
    (language/lexicon.py: ``known``, the words the toolkit reads, are never looked up), then without a remark at
    its end (language/remarks.py: "..., thanks a million"), then without the adjectives no one here or in WordNet
    knows ("the cheap silver teaspoon"); None where that refuses too. ``read_clauses`` reads a
    text as chain/clauses.py does."""
    texts = dict.fromkeys(t for t in (mended, sentence) if t is not None)
    with lenient.reading_past():
        for text in texts:
            try:
                return read_clauses(text, scene, plugins)
            except L2PError:
                pass
        with lexicon.looking_up():
            # a verb looked up is read in the sentence as typed, never in its mended form: two guesses (a mended
            # name, a looked-up verb) are not layered on one sentence
            for text in dict.fromkeys((*texts, lexicon.moving_verbs_read(sentence, known, lenient.STOPS))):
                try:
                    return read_clauses(text, scene, plugins)
                except L2PError:
                    pass
            matters = naming_words(scene) | verb_heads() | remarks.phrase_words(registry.phrase_table(plugins))
            for head in (h for t in texts for h in remarks.without_remarks(t, matters)):
                for text in dict.fromkeys((head, lexicon.moving_verbs_read(head, known, lenient.STOPS))):
                    try:
                        read = read_clauses(text, scene, plugins)
                    except L2PError:
                        continue
                    if getattr(read[-1], "group", None) is None:  # a list's last item is no remark
                        return read
            nouns = naming_words(scene) | NOUNS | SIZE_WORDS
            describing = frozenset(COLORS) | frozenset(COLOR_SYNONYMS) | SIZE_WORDS
            stops = lenient.STOPS | lenient.POINTING | lenient.EXTENT_WORDS | NEGATIONS
            for text in [t for t in dict.fromkeys(lexicon.adjectives_read_past(t, known, nouns, describing, stops)
                                                  for t in texts) if t not in texts]:
                for told in dict.fromkeys((text, lexicon.moving_verbs_read(text, known, lenient.STOPS))):
                    try:
                        return read_clauses(told, scene, plugins)
                    except L2PError:
                        pass
    return None
