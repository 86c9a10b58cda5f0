"""The last tries of a sentence every reading has refused as typed and as mended (chain/clauses.py): each allows one
more kind of reading past words the grammar does not know, in the order that guesses least first.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from ..core.scene import COLORS, Scene
from ..errors import L2PError
from ..language import lenient, lexicon, remarks, verb_heads
from ..language.naming import naming_words
from ..language.reference_words import COLOR_SYNONYMS, NOUNS
from ..language.synonyms import SIZE_WORDS
from ..language.words import NEGATIONS
from ..plugins import registry

Read = Callable[[str, Scene, list], list]
"""chain/clauses.py's reader of a whole text: (text, scene, plugins) -> its clauses."""


def read_past(sentence: str, mended: str | None, scene: Scene, plugins: list, known: frozenset[str],
              read_clauses: Read) -> list | None:
    """The sentence's mended form (then the sentence as typed) read once more with the lenient reading allowed
    (language/lenient.py), then again with words looked up in WordNet naming objects and moving them too
    (language/lexicon.py: ``known``, the words the toolkit reads, are never looked up), then without a remark at
    its end (language/remarks.py: "..., thanks a million"), then without the adjectives no one here or in WordNet
    knows ("the cheap silver teaspoon"); None where that refuses too. ``read_clauses`` reads a
    text as chain/clauses.py does."""
    texts = dict.fromkeys(t for t in (mended, sentence) if t is not None)

    def moved(text: str) -> str:
        return lexicon.moving_verbs_read(text, known, lenient.STOPS)

    def first(tried: Iterable[str], fits: Callable[[list], bool] = lambda read: True) -> list | None:
        for text in dict.fromkeys(tried):
            try:
                read = read_clauses(text, scene, plugins)
            except L2PError:
                continue
            if fits(read):
                return read
        return None

    with lenient.reading_past():
        read = first(texts)
        if read is not None:
            return read
        with lexicon.looking_up():
            # a verb looked up is read in the sentence as typed, never in its mended form: two guesses (a mended
            # name, a looked-up verb) are not layered on one sentence
            read = first((*texts, moved(sentence)))
            if read is not None:
                return read
            named = naming_words(scene)
            places, verbs = remarks.phrase_words(registry.phrase_table(plugins)), verb_heads()
            matters = named | verbs | places
            heads = (h for t in texts for h in (*remarks.without_remarks(t, matters),
                                                *remarks.without_reason(t, places, verbs),
                                                *remarks.without_statement(t, places, verbs, named)))
            read = first((told for h in heads for told in (h, moved(h))),
                         lambda read: getattr(read[-1], "group", None) is None)  # a list's last item is no remark
            if read is not None:
                return read
            nouns = named | NOUNS | SIZE_WORDS
            describing = frozenset(COLORS) | frozenset(COLOR_SYNONYMS) | SIZE_WORDS
            stops = lenient.STOPS | lenient.POINTING | lenient.EXTENT_WORDS | NEGATIONS
            plain = [t for t in dict.fromkeys(lexicon.adjectives_read_past(t, known, nouns, describing, stops)
                                              for t in texts) if t not in texts]
            return first(told for t in plain for told in (t, moved(t)))
