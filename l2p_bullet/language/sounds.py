"""A name as speech-to-text hears it: the English word that sounds like a name in another language ("copper" for
koppu, "hockey" for hako, "Sarah" for sara, "tease" for tasse, "sucker" for sucrier).

Words are compared by their consonants as heard (a rough phonetic key): "c" and "k" alike, "wr" as "r" ("the ranch" for
the wrench), "ph" as "f", "th" as "t", letters doubled once, vowels after the first letter and a silent "h" left out. A
word is read as a name only in a sentence refused as written (language/typos.py), only where it is no word the grammar
knows, and only where exactly one of the scene's one-word names sounds so: a refusal is better than a guess between two.
"""

from __future__ import annotations

import re

from .synonyms import unaccented

_SPELLINGS = (("wr", "r"), ("ph", "f"), ("ck", "k"), ("qu", "kw"), ("th", "t"), ("sh", "s"), ("ch", "k"), ("ce", "se"),
              ("ci", "si"), ("cy", "si"), ("c", "k"), ("q", "k"), ("x", "ks"), ("z", "s"), ("y", "i"), ("wh", "w"),
              ("ew", "u"))


def heard_key(word: str) -> str:
    """The consonants of ``word`` as heard: "hockey" and "hako" -> "hk", "copper" -> "kpr", "koppu" -> "kp"."""
    w = re.sub(r"[^a-z]", "", unaccented(word).lower())
    for spelt, heard in _SPELLINGS:
        w = w.replace(spelt, heard)
    if not w:
        return ""
    rest = re.sub(r"[aeiouh]", "", w[1:])
    return re.sub(r"(.)\1+", r"\1", w[0] + rest)


def heard_name(word: str, names: list[str], amiss: bool = False) -> str | None:
    """The one name of ``names`` (one word of letters each) that ``word`` (three letters or more) sounds like; a final
    "r" heard where the name ends in a vowel is allowed ("copper" for koppu), and an "h" the speaker dropped ("the
    art" for the heart), and with ``amiss`` one consonant heard as another or left out ("kennel" for kettle). None
    where none or several do."""
    if len(word) < 3 or not word.isalpha():
        return None
    said = heard_key(word)
    keys = {said, said[:-1] if said.endswith("r") and len(said) > 2 else said}
    if word.lower().startswith("ch"):  # "the water char" for the water jar: "ch" and "j" heard alike
        keys |= {"j" + k[1:] for k in keys}
    keys |= {k[1:] for k in keys if k[:1] in "aeiou" and len(k) > 2}  # "art" heard for heart: its vowel, no "h"
    keyed = [(n, heard_key(n)) for n in names if len(n) >= 3 and unaccented(n).isalpha() and n.lower() != word.lower()]
    fits = [n for n, key in keyed if key in keys or key.startswith("h") and key[1:] in keys]
    if not fits and amiss and len(word) >= 4:  # "the kennel" for the kettle, "the lady" for the ladle: one sound amiss
        fits = [n for n, key in keyed if len(key) >= 3 and any(one_sound_apart(k, key) for k in keys)
                and _first_vowel(n) == _first_vowel(word)]  # the stressed vowel heard right: no "bobbin" for button
    return fits[0] if len(fits) == 1 else None


def _first_vowel(word: str) -> str:
    """The first vowel after a word's first letter ("kennel": e, "button": u), or "" where there is none."""
    return next((c for c in unaccented(word).lower()[1:] if c in "aeiou"), "")


def one_sound_apart(said: str, name: str) -> bool:
    """Whether two consonant keys differ by one consonant heard as another, or one left out, past the first."""
    if said[:1] != name[:1] or said == name:
        return False
    if len(said) == len(name):
        return sum(a != b for a, b in zip(said, name, strict=True)) == 1
    short, long_ = sorted((said, name), key=len)
    return len(long_) == len(short) + 1 and any(long_[:i] + long_[i + 1:] == short for i in range(1, len(long_)))
