"""Spanish among English words, as bilingual speakers type to the robot ("mueve el rojo next to the dado", "el verde
around la baraja", "pon la ficha azul junto a las cartas"): the Spanish verbs, places, articles and joining words said
in English, word for word ("mueve" move, "junto a" next to, "lejos del" away from the, "luego" then), with the words of
a game's table ("dado" die, "baraja" and "cartas" the cards, "ficha" a piece). Colours are read where colours are
(language/reference_words.COLOR_SYNONYMS: "rojo", "azul").

Read only in a sentence refused as written, and only where it says a Spanish verb or place: "la" and "y" alone say
nothing of the kind.
"""

from __future__ import annotations

import re

_OF_THE = r"(?:\s+(?:la|las|los|el)|l)?"  # "de la", "de las", "del", "de"
_SAID = (
    (r"\b(?:mueve|muevelo|muévelo|muevela|muévela|mover)\b", "move"),
    (r"\b(?:pon|ponlo|ponla|ponme|coloca|colocalo|colócalo|colocala|colócala)\b", "put"),
    (r"\b(?:lleva|llevalo|llévalo|llevala|llévala|llevame)\b", "take"),
    (r"\b(?:empuja|empujalo|empújalo|empujala|empújala)\b", "push"),
    (r"\b(?:levanta|levantalo|levántalo|levantala|levántala)\b", "lift"),
    (rf"\b(?:al\s+lado|junto)\s+(?:de|a){_OF_THE}\b", "next to the"),
    (rf"\bpegadito\s+a{_OF_THE}\b", "right next to the"),
    (r"\b(?:tantito|poquito|un\s+poco)\b", "a bit"),
    (rf"\b(?:mas|más)\s+cerca\s+de{_OF_THE}\b", "closer to the"),
    (rf"\bcerca\s+de{_OF_THE}\b", "near the"),
    (rf"\bmuy\s+lejos\s+de{_OF_THE}\b", "far away from the"),
    (rf"\b(?:mas|más\s+)?lejos\s+de{_OF_THE}\b", "away from the"),
    (rf"\balrededor\s+de{_OF_THE}\b", "around the"),
    (r"\bhacia\s+(?:el|la|los|las)\b", "toward the"),
    (r"\ben\s+(?:linea|línea|fila)\b", "in a line"),
    (r"\b(?:luego|despues|después|y\s+luego|y\s+despues|y\s+después)\b", "then"),
    (r"\bcon\s+cuidado\b", "carefully"),
    (r"\b(?:porfa|por\s+favor)\b", "please"),
    (r"\bgracias\b", "thanks"),
    (r"\bdado\b", "die"), (r"\b(?:cartas|baraja)\b", "cards"), (r"\bfichas?\b", "piece"),
    (r"\b(?:el|la|los|las)\b", "the"),
    (r"\by\b", "and"),
)
SAID = tuple((re.compile(pattern, re.IGNORECASE), english) for pattern, english in _SAID)
"""Spanish words and what each says in English, the longer before the shorter."""
SPANISH = re.compile(r"\b(?:mueve\w*|muével\w|pon|ponlo|ponla|ponme|coloca\w*|lleva\w*|lléval\w|empuja\w*|levanta\w*"
                     r"|al\s+lado|junto\s+a|cerca\s+de|lejos\s+de|alrededor|hacia|luego|despu[eé]s|en\s+fila"
                     r"|(?:el|la)\s+(?:rojo|roja|verde|azul|amarillo|amarilla|blanco|blanca|negro|negra|dado|baraja"
                     r"|ficha))\b",
                     re.IGNORECASE)
"""A Spanish verb, place or joining word, or an article before a colour or a game's thing: the sentence is said
partly in Spanish."""


def in_english(sentence: str) -> str:
    """``sentence`` with its Spanish said in English (module docstring); unchanged where it says no Spanish verb or
    place."""
    if not SPANISH.search(sentence):
        return sentence
    out = sentence
    for pattern, english in SAID:
        out = pattern.sub(english, out)
    return out


__all__ = ["in_english"]
