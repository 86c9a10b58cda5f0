"""Colours as scene files write them, and the basic colour a sentence calls each by.

Sentences pick objects by twelve basic colours (:data:`COLORS`: "the red block"). Scene files as people and
model packages write them say "grey", "silver", "navy", "dark green", "gold" or "#c0c0c0". Each is read here as a
**shade**: drawn in its own RGB, and called by the basic colour people call it by ("the blue cup" is the navy
one; "the silver cup" and "the grey one" are the silver one too). The shades are CSS's 148 named colours (both
spellings of grey), the common names of :data:`MORE`, "#rgb" / "#rrggbb", and any of them after a word of
lightness ("dark", "light", "pale", "bright", "deep": "light blue").

Which basic colour a shade is comes first from :data:`SAID_AS`, the words whose basic colour English speakers
agree on ("silver" is grey, "navy" blue, "beige" brown: the sentence reader reads the same words alike,
``language/reference_words.COLOR_SYNONYMS``), and otherwise from its hue, saturation and value
(:func:`basic_of`): low saturation is white, grey or black by value; a dark orange is brown; a light red is pink.
"""

from __future__ import annotations

import colorsys
import re

COLORS: dict[str, tuple[float, float, float, float]] = {
    "red": (0.85, 0.1, 0.1, 1.0),
    "green": (0.1, 0.7, 0.2, 1.0),
    "blue": (0.15, 0.3, 0.9, 1.0),
    "yellow": (0.95, 0.85, 0.1, 1.0),
    "orange": (1.0, 0.55, 0.0, 1.0),
    "purple": (0.55, 0.2, 0.75, 1.0),
    "white": (0.95, 0.95, 0.95, 1.0),
    "black": (0.1, 0.1, 0.1, 1.0),
    "gray": (0.5, 0.5, 0.5, 1.0),
    "brown": (0.55, 0.35, 0.15, 1.0),
    "pink": (1.0, 0.5, 0.7, 1.0),
    "cyan": (0.0, 0.8, 0.85, 1.0),
}
"""The basic colours a sentence may use ("the red block") and the RGBA the renderer gives them."""

CSS: dict[str, str] = {
    "aliceblue": "#f0f8ff", "antiquewhite": "#faebd7", "aqua": "#00ffff", "aquamarine": "#7fffd4",
    "azure": "#f0ffff", "beige": "#f5f5dc", "bisque": "#ffe4c4", "black": "#000000", "blanchedalmond": "#ffebcd",
    "blue": "#0000ff", "blueviolet": "#8a2be2", "brown": "#a52a2a", "burlywood": "#deb887", "cadetblue": "#5f9ea0",
    "chartreuse": "#7fff00", "chocolate": "#d2691e", "coral": "#ff7f50", "cornflowerblue": "#6495ed",
    "cornsilk": "#fff8dc", "crimson": "#dc143c", "cyan": "#00ffff", "darkblue": "#00008b", "darkcyan": "#008b8b",
    "darkgoldenrod": "#b8860b", "darkgray": "#a9a9a9", "darkgreen": "#006400", "darkgrey": "#a9a9a9",
    "darkkhaki": "#bdb76b", "darkmagenta": "#8b008b", "darkolivegreen": "#556b2f", "darkorange": "#ff8c00",
    "darkorchid": "#9932cc", "darkred": "#8b0000", "darksalmon": "#e9967a", "darkseagreen": "#8fbc8f",
    "darkslateblue": "#483d8b", "darkslategray": "#2f4f4f", "darkslategrey": "#2f4f4f", "darkturquoise": "#00ced1",
    "darkviolet": "#9400d3", "deeppink": "#ff1493", "deepskyblue": "#00bfff", "dimgray": "#696969",
    "dimgrey": "#696969", "dodgerblue": "#1e90ff", "firebrick": "#b22222", "floralwhite": "#fffaf0",
    "forestgreen": "#228b22", "fuchsia": "#ff00ff", "gainsboro": "#dcdcdc", "ghostwhite": "#f8f8ff",
    "gold": "#ffd700", "goldenrod": "#daa520", "gray": "#808080", "green": "#008000", "greenyellow": "#adff2f",
    "grey": "#808080", "honeydew": "#f0fff0", "hotpink": "#ff69b4", "indianred": "#cd5c5c", "indigo": "#4b0082",
    "ivory": "#fffff0", "khaki": "#f0e68c", "lavender": "#e6e6fa", "lavenderblush": "#fff0f5",
    "lawngreen": "#7cfc00", "lemonchiffon": "#fffacd", "lightblue": "#add8e6", "lightcoral": "#f08080",
    "lightcyan": "#e0ffff", "lightgoldenrodyellow": "#fafad2", "lightgray": "#d3d3d3", "lightgreen": "#90ee90",
    "lightgrey": "#d3d3d3", "lightpink": "#ffb6c1", "lightsalmon": "#ffa07a", "lightseagreen": "#20b2aa",
    "lightskyblue": "#87cefa", "lightslategray": "#778899", "lightslategrey": "#778899", "lightsteelblue": "#b0c4de",
    "lightyellow": "#ffffe0", "lime": "#00ff00", "limegreen": "#32cd32", "linen": "#faf0e6", "magenta": "#ff00ff",
    "maroon": "#800000", "mediumaquamarine": "#66cdaa", "mediumblue": "#0000cd", "mediumorchid": "#ba55d3",
    "mediumpurple": "#9370db", "mediumseagreen": "#3cb371", "mediumslateblue": "#7b68ee",
    "mediumspringgreen": "#00fa9a", "mediumturquoise": "#48d1cc", "mediumvioletred": "#c71585",
    "midnightblue": "#191970", "mintcream": "#f5fffa", "mistyrose": "#ffe4e1", "moccasin": "#ffe4b5",
    "navajowhite": "#ffdead", "navy": "#000080", "oldlace": "#fdf5e6", "olive": "#808000", "olivedrab": "#6b8e23",
    "orange": "#ffa500", "orangered": "#ff4500", "orchid": "#da70d6", "palegoldenrod": "#eee8aa",
    "palegreen": "#98fb98", "paleturquoise": "#afeeee", "palevioletred": "#db7093", "papayawhip": "#ffefd5",
    "peachpuff": "#ffdab9", "peru": "#cd853f", "pink": "#ffc0cb", "plum": "#dda0dd", "powderblue": "#b0e0e6",
    "purple": "#800080", "rebeccapurple": "#663399", "red": "#ff0000", "rosybrown": "#bc8f8f",
    "royalblue": "#4169e1", "saddlebrown": "#8b4513", "salmon": "#fa8072", "sandybrown": "#f4a460",
    "seagreen": "#2e8b57", "seashell": "#fff5ee", "sienna": "#a0522d", "silver": "#c0c0c0", "skyblue": "#87ceeb",
    "slateblue": "#6a5acd", "slategray": "#708090", "slategrey": "#708090", "snow": "#fffafa",
    "springgreen": "#00ff7f", "steelblue": "#4682b4", "tan": "#d2b48c", "teal": "#008080", "thistle": "#d8bfd8",
    "tomato": "#ff6347", "turquoise": "#40e0d0", "violet": "#ee82ee", "wheat": "#f5deb3", "white": "#ffffff",
    "whitesmoke": "#f5f5f5", "yellow": "#ffff00", "yellowgreen": "#9acd32",
}
"""CSS Color Module Level 4's named colours (the names scene files and web tools write)."""

MORE: dict[str, str] = {
    "clear": "#dfe8ef", "transparent": "#dfe8ef", "glass": "#dfe8ef", "bronze": "#cd7f32", "copper": "#b87333",
    "brass": "#b5a642", "chrome": "#dbe2e9", "steel": "#8a9597", "charcoal": "#36454f", "cream": "#fffdd0",
    "mint": "#98ff98", "rose": "#ff66cc", "rust": "#b7410e", "mustard": "#e1ad01", "burgundy": "#800020",
    "amber": "#ffbf00", "emerald": "#50c878", "ruby": "#e0115f", "sapphire": "#0f52ba", "jade": "#00a86b",
    "lilac": "#c8a2c8", "mauve": "#e0b0ff", "peach": "#ffcba4", "sand": "#c2b280", "ochre": "#cc7722",
    "scarlet": "#ff2400", "golden": "#ffd700", "natural": "#e3d3b4", "wood": "#c19a6b", "wooden": "#c19a6b",
}
"""Colour names people write that CSS does not name. A clear or glass object is drawn a pale grey-blue (the
renderer draws no transparency), and called white."""

SAID_AS: dict[str, str] = {
    "grey": "gray", "silver": "gray", "steel": "gray", "chrome": "gray", "charcoal": "gray", "slategray": "gray",
    "slategrey": "gray", "navy": "blue", "indigo": "purple", "violet": "purple", "lilac": "purple",
    "lavender": "purple", "mauve": "purple", "plum": "purple", "orchid": "purple", "magenta": "pink",
    "fuchsia": "pink", "salmon": "pink", "rose": "pink", "teal": "cyan", "aqua": "cyan", "turquoise": "cyan",
    "aquamarine": "cyan", "gold": "yellow", "golden": "yellow", "amber": "orange", "beige": "brown", "tan": "brown",
    "khaki": "brown", "wheat": "brown", "sand": "brown", "natural": "brown", "wood": "brown", "wooden": "brown",
    "bronze": "brown", "copper": "brown", "brass": "yellow", "rust": "brown", "ochre": "brown", "maroon": "red",
    "burgundy": "red", "crimson": "red", "scarlet": "red", "ruby": "red", "olive": "green", "lime": "green",
    "mint": "green", "emerald": "green", "jade": "green", "sapphire": "blue", "cream": "white", "ivory": "white",
    "clear": "white", "transparent": "white", "glass": "white", "coral": "orange", "peach": "orange",
    "mustard": "yellow", "chocolate": "brown", "sienna": "brown", "peru": "brown", "thistle": "purple",
    "goldenrod": "yellow",
}
"""The basic colour of shades whose hue alone would mislead (silver reads as white, navy as black, gold as orange)."""

ALIKE: tuple[frozenset[str], ...] = (frozenset({"clear", "transparent", "glass", "see through", "seethrough"}),)
"""Shades said in each other's words ("the see-through jar" is the clear one)."""

LIGHTNESS: dict[str, float] = {"dark": 0.6, "deep": 0.7, "light": 1.45, "pale": 1.6, "bright": 1.15}
"""A word of lightness before a colour, and how it scales the colour's value (lighter ones also take saturation
out: see :func:`rgb`)."""

_HEX = re.compile(r"#(?:[0-9a-f]{3}|[0-9a-f]{6})")


def rgb(shade: str) -> tuple[float, float, float] | None:
    """The RGB (0-1) of ``shade`` (a basic colour, a named one, "#rrggbb", or either after a word of lightness), or
    None when it is not a colour."""
    s = " ".join(shade.lower().replace("-", " ").replace("_", " ").split())
    if s in COLORS:
        return COLORS[s][:3]
    if _HEX.fullmatch(s):
        digits = s[1:] if len(s) == 7 else "".join(c * 2 for c in s[1:])
        return tuple(int(digits[i:i + 2], 16) / 255 for i in (0, 2, 4))
    joined = s.replace(" ", "")
    for table in (CSS, MORE):
        if joined in table:
            return rgb(table[joined])
    word, _, rest = s.partition(" ")
    head, _, last = s.rpartition(" ")
    if head and word not in LIGHTNESS and (base := rgb(last)) is not None:  # "navy blue", "baby blue", "brick red"
        return rgb(head) or base
    if word in LIGHTNESS and rest and (base := rgb(rest)) is not None:
        h, sat, v = colorsys.rgb_to_hsv(*base)
        k = LIGHTNESS[word]
        if k > 1:  # lighter: towards white, less saturated
            sat, v = sat / k, min(1.0, v * k if v < 0.5 else v + (1 - v) * (k - 1))
        else:
            v *= k
        return colorsys.hsv_to_rgb(h, sat, v)
    return None


def basic_of(shade: str) -> str | None:
    """The basic colour (a key of :data:`COLORS`) a sentence calls ``shade`` by, or None when it is not a colour."""
    s = " ".join(shade.lower().replace("-", " ").replace("_", " ").split())
    if s in COLORS:
        return s
    colour = rgb(s)
    if colour is None:
        return None
    joined = s.replace(" ", "")
    if joined in SAID_AS:
        return SAID_AS[joined]
    if " " in s and joined not in CSS:  # "light blue", "navy blue": the colour said last
        return basic_of(s.rpartition(" ")[2])
    for name in sorted(COLORS, key=len, reverse=True):  # "skyblue", "forestgreen", "hotpink": the colour it ends on
        if joined.endswith(name):
            return name
    for name in sorted(SAID_AS, key=len, reverse=True):  # "darksalmon", "mediumturquoise": the named colour it ends on
        if joined.endswith(name):
            return SAID_AS[name]
    return by_hue(colour)


def by_hue(colour: tuple[float, float, float]) -> str:
    """The basic colour of an RGB, by hue, saturation and value."""
    h, s, v = colorsys.rgb_to_hsv(*colour)
    deg = h * 360
    if s < 0.18 or v < 0.15:
        return "white" if v > 0.85 and s < 0.18 else "black" if v < 0.3 else "gray"
    if 15 <= deg < 45:
        return "brown" if v < 0.7 or s < 0.45 else "orange"
    if 45 <= deg < 70:
        return "brown" if v < 0.55 else "yellow"
    if 70 <= deg < 165:
        return "green"
    if 165 <= deg < 200:
        return "cyan"
    if 200 <= deg < 255:
        return "blue"
    if 255 <= deg < 290:
        return "purple"
    if 290 <= deg < 345:
        return "pink"
    return "pink" if s < 0.5 and v > 0.8 else "red"


def read(colour: str) -> tuple[str, str | None]:
    """(basic colour, shade) of a scene file's ``color``: the shade None for a basic colour, else the colour as
    written (lower case, its spaces single). ValueError when it is not a colour."""
    s = " ".join(colour.lower().split())
    basic = basic_of(s)
    if basic is None:
        raise ValueError(s)
    return basic, None if s == basic else s


def rgba(basic: str, shade: str | None = None) -> tuple[float, float, float, float]:
    """What the renderer draws an object of ``basic`` colour and ``shade`` in."""
    colour = rgb(shade) if shade else None
    return (*colour, 1.0) if colour is not None else COLORS.get(basic, COLORS["gray"])


def alike(shade: str) -> frozenset[str]:
    """The other words that say ``shade`` (:data:`ALIKE`)."""
    return next((group - {shade} for group in ALIKE if shade in group), frozenset())


def names() -> list[str]:
    """Every colour name a scene file may write (for "did you mean")."""
    return [*COLORS, *CSS, *MORE]
