"""Emoji typed for words ("🔑 ➡️ 👛", "👉 cup next to phone 🙏", "📱 🔄 round the lamp", "🐢 cup → lamp").

Each emoji is read as the words it stands for before anything else reads the sentence: an arrow as the arrow the
grammar reads for "goes" ("the mug -> around the box"), a circling arrow as "around", folded hands as "please", a
tortoise as "slowly", a dash of wind as "quickly", a tick, a heart or a smile as nothing. Any other emoji is a thing:
its Unicode name's words ("MOBILE PHONE", "KEY", "PURSE", "EYEGLASSES") are asked of the scene, all of them together
first ("GREEN APPLE"), then from the last word back (the name's own noun first), and the first that names one object
is said as "the <word>"; an emoji that names none is said as its last word, so the sentence is refused with that word,
never read past.
"""

from __future__ import annotations

import re
import unicodedata

from ..core.scene import Scene
from .references import try_object

SAID_AS = {
    "\u27a1": " -> ", "\u2192": " -> ", "\U0001f449": " ", "\u23e9": " -> ", "\u21aa": " -> ", "\u2b95": " -> ",
    "\U0001f504": " around ", "\U0001f501": " around ", "\U0001f503": " around ", "\u21bb": " around ",
    "\u21ba": " around ", "\U0001f64f": " please ", "\U0001f422": " slowly ", "\U0001f40c": " slowly ",
    "\U0001f4a8": " quickly ", "\u26a1": " quickly ", "\U0001f680": " quickly ", "\U0001f3c3": " quickly ",
    "\u2b06": " ", "\u2705": " ", "\u2714": " ", "\U0001f44d": " ", "\u2764": " ", "\U0001f60a": " ",
    "\U0001f642": " ", "\U0001f600": " ", "\U0001f601": " ", "\U0001f604": " ", "\U0001f609": " ", "\U0001f618": " ",
    "\U0001f923": " ", "\U0001f602": " ", "\u2728": " ", "\U0001f525": " ", "\U0001f4af": " ", "\U0001f440": " ",
    "+": " and ",
}
"""Emoji (and "+" between two things) that stand for a word of the command, or for nothing it needs."""
THINGS = {"\u2615": "cup", "\U0001f4a1": "lamp", "\U0001f376": "bottle", "\U0001f37a": "glass", "\U0001f964": "cup",
          "\U0001f375": "cup", "\U0001f45b": "wallet", "\U0001f45c": "bag", "\U0001f392": "bag"}
"""Emoji whose Unicode name says no word a scene calls the thing by ("HOT BEVERAGE", "ELECTRIC LIGHT BULB")."""
_JOINERS = re.compile("[\ufe0f\ufe0e\u200d]")
_SKIP_WORDS = frozenset({"with", "without", "and", "of", "face", "sign", "symbol", "black", "white", "heavy", "large",
                         "small", "medium", "emoji", "modifier", "type"})


def emoji_said(sentence: str, scene: Scene) -> str:
    """``sentence`` with each emoji in it said in words (module docstring); unchanged where it holds none."""
    if sentence.isascii():
        return sentence
    out = []
    thing_last = False  # things said one after another are a list: "👓 🔑 ☕ in a row"
    for ch in _JOINERS.sub("", sentence):
        if ch in SAID_AS:
            out.append(SAID_AS[ch])
            thing_last = False
        elif unicodedata.category(ch) == "So":
            out.append(f"{',' if thing_last else ''} {_thing(ch, scene)} ")
            thing_last = True
        else:
            out.append(ch)
            thing_last = thing_last and ch.isspace()
    said = re.sub(r"\baround\s+(a?round)\b", r"\1", "".join(out))  # "📱 🔄 round the lamp"
    return re.sub(r"\s{2,}", " ", said).strip()


def _thing(ch: str, scene: Scene) -> str:
    """The words an emoji of a thing is said as: "the <word>" for the word of its name that names one object."""
    if ch in THINGS and try_object(f"the {THINGS[ch]}", scene) is not None:
        return f"the {THINGS[ch]}"
    words = [w for w in unicodedata.name(ch, "").lower().split() if w not in _SKIP_WORDS]
    if len(words) > 1 and try_object(f"the {' '.join(words)}", scene) is not None:
        return f"the {' '.join(words)}"  # "GREEN APPLE" is the green apple, where the apple alone is the red one
    for word in reversed(words):
        if try_object(f"the {word}", scene) is not None:
            return f"the {word}"
    return f"the {words[-1]}" if words else ""


__all__ = ["emoji_said"]
