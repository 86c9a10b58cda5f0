"""A composite action's sentence: a phrase and a list of objects ("make a row of A, B, C and D", "put P in a
row with Q and R", "row: duck, cup, ball"), read against the installed composites' phrases.

Single actions' sentences are grammar.py's; a list is read here so the chain can tell a composite's sentence
from a single action's before either is resolved (chain/composite.py).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from ..core.scene import Scene
from ..errors import LanguageError
from .grammar import ARROWS, MAX_SENTENCE, phrase_tokens, tokens
from .letters import in_abc_order, said_letters
from .naming import name_words
from .numbers import number_name
from .partitives import number_said
from .reference_words import CONJUNCTIONS
from .references import resolve_object, try_object
from .words import strip_polite


@dataclass(frozen=True)
class ListCommand:
    """A composite action's sentence ("make a row of A, B, C and D"): the objects in the order named."""

    action: str
    phrase: str
    objects: tuple[str, ...]
    sentence: str = ""


def parse_list(sentence: str, scene: Scene, phrases: dict[str, str]) -> ListCommand | None:
    """``[polite words] PHRASE OBJECT, OBJECT ... and OBJECT`` for the composite ``phrases`` (phrase ->
    action); None when the sentence does not start with one of them (it is then a single action's or a
    chain's). The objects are separated by commas and/or "and"; at least two, all different."""
    if not isinstance(sentence, str) or not phrases or len(sentence) > MAX_SENTENCE:
        return None
    plain = said_plainly(sentence, scene)
    if plain == sentence:
        return _parse_list(sentence, scene, phrases)
    try:
        read = _parse_list(plain, scene, phrases)
    except LanguageError:
        read = None
    return read if read is not None else _parse_list(sentence, scene, phrases)


_ROW_ADJECTIVE = r"(?:neat|nice|tidy|single|straight|long|perfect|clean|little|lil|proper|orderly|even)"
"""Words said of a row that change nothing of it ("a neat little row")."""
ROW_ADJECTIVES = re.compile(rf"\bin\s+(?:a|one)\s+(?:{_ROW_ADJECTIVE},?\s+)+(row|line)\b", re.IGNORECASE)
IN_LINE = re.compile(r"\bin\s+(row|line)\b(?!\s+with\b)", re.IGNORECASE)
IN_ONE = re.compile(r"\bin\s+(?:one|a\s+single)\s+(row|line)\b", re.IGNORECASE)
ROW_FIRST = re.compile(r"^(?P<verb>\s*(?:please\s+(?:to\s+)?)?(?:put|place|set|arrange))\s+in\s+a\s+(?P<row>row|line)"
                       r"(?:\s*,?\s*in\s+(?:this|that|the\s+following)\s+order)?\s*[:,\-\u2013\u2014]?\s+"
                       r"(?P<items>[^.;!?]+?)(?=\s*(?:,\s*(?:please|pls|plz|thanks|thank\s+you))?\s*(?:[.;!?]|$))",
                       re.IGNORECASE)
LINE_FROM = re.compile(rf"\b(?:make|form|create|build)\s+(?:a|one)\s+(?:{_ROW_ADJECTIVE},?\s+)*"
                       r"(row|line)\s+(?:from|out\s+of|outta|using|with|of)\s+", re.IGNORECASE)
"""More ways to say a row: "in one line", "in line" as learners write it (not "in line with"), "Put in one row the ball,
the mug and the tile", "Make a line from A, B and C", "Form a straight line of A, B and C", "make a line outta A, B,
C", "row pls - A, B, C"."""
WISHED_ROW = re.compile(r"^\s*(?:please\s*,?\s+)?(?:i'?d\s+like|i\s+would\s+like|i\s+want|i'?d\s+love|we'?d\s+like|"
                        r"we\s+want|i\s+need|we\s+need|can\s+i\s+have|could\s+i\s+have)\s+(?P<items>.+?)\s+"
                        r"(?:lined\s+up|in\s+(?:a|one)\s+(?:row|line))\b", re.IGNORECASE)
"""A row wished for ("I'd like the bell, the cup and the bowl lined up, please"): as "put ... in a row"."""
LISTED_THEN_LINED = re.compile(r"^\s*(?:(?:let'?s|now|ok|okay|so)\s+)*(?:(?:take|get|grab)\s+)?(?P<items>[^:;.!?]+?"
                               r"(?:,|\s+and\s+)[^:;.!?]+?)\s*(?:,|:|\s+-+|\s*[\u2013\u2014]|\s+and)\s+"
                               r"(?:(?:please|pls|now|just|then)\s+)*(?:put|place|set|arrange|line|lay|stick|row)\s+"
                               r"(?:them|em|'em)(?:\s+all)?\s+(?:up|in\s+a\s+(?:row|line))\b", re.IGNORECASE)
"""A row's objects named first, then lined up as "them" ("the bell, the cup and the bowl - line them up", "take A, B and
C and put them in a row"): as "put ... in a row"."""
ALL_IN_A_ROW = re.compile(r"\s+(?:all|both|all\s+of\s+them)"
                          r"(?=\s+(?:in\s+(?:a|one)\s+(?:row|line)|lined\s+up|up\s+in\b))", re.IGNORECASE)
""""all" (or "both") said of the list right before its row ("the whisk, the board and the colander all in a line")."""
UP_IN_A_ROW = re.compile(r"\bup\s+in\s+(?:a|one)\s+(?:row|line)\b", re.IGNORECASE)
_FOLLOWING = r"the\s+following(?:\s+\w+)?\s+(?:objects|things|items|blocks)"
"""A list announced before its colon ("the following three objects")."""
THE_FOLLOWING = re.compile(r"\s*,?\s*(?:consisting\s+of|made\s+(?:up\s+)?of|of|with)?\s+" + _FOLLOWING
                           + r"\s*,?\s*(?:in\s+(?:this|that)\s+order\s*)?:\s*", re.IGNORECASE)
FOLLOWING_ROW = re.compile(r"^(?P<verb>\s*(?:please\s+)?(?:arrange|put|place|set|line\s+up))\s+" + _FOLLOWING
                           + r"\s*,?\s*"
                           r"(?:(?:in\s+(?:a|one)\s+(?:\w+\s+)?(?:row|line)|collinearly)\s*,?\s*)?"
                           r"(?:in\s+(?:this|that|the\s+following)\s+order\s*)?:\s*(?P<items>.+?)\s*[.!]?\s*$",
                           re.IGNORECASE)
"""The objects of a row listed after a colon: "Arrange the following objects in a single row, in this order: block4,
box, block5" is "arrange block4, box, block5 in a row"."""
COLLINEAR = re.compile(r"\bcollinearly\b", re.IGNORECASE)
"""A geometer's "in a line" ("Arrange Q, crate, O collinearly")."""
GROUP = re.compile(r"\bthe\s+(?:(?P<count>two|three|four|five|[2-5])\s+)?(?P<kind>cubes|blocks|boxes|objects|things)\b",
                   re.IGNORECASE)
GROUP_ITEMS = re.compile(r"\s*(?::|\s-+|[\u2013\u2014]|,|\()\s*(?P<items>[^:;()\-\u2013\u2014]+?)"
                         r"\s*(?:-+|[\u2013\u2014]|\))?\s*$")
"""A composite's sentence said in other words: "in a neat row", "line A, B and C up in a row", "a row of the following
objects: ...", and a group named first and its items after ("Put the three cubes in a row: red, blue, black", "Line
the four cubes up - big red, small red, blue, purple -"), each item the group's noun with the words said."""


def said_plainly(sentence: str, scene: Scene) -> str:
    """``sentence`` with a composite's sentence said in other words (the patterns above) said as a plain list is;
    ``sentence`` itself where it has none of them. :func:`parse_list` reads the plain form first, then as typed."""
    text = in_abc_order(sentence, scene)  # "put the letter blocks in ABC order in a row"
    text = UP_IN_A_ROW.sub("up", ROW_ADJECTIVES.sub(r"in a \1", IN_ONE.sub(r"in a \1", IN_LINE.sub(r"in a \1", text))))
    text = ALL_IN_A_ROW.sub("", COLLINEAR.sub("in a line", text))
    text = FOLLOWING_ROW.sub(r"\g<verb> \g<items> in a row", text, count=1)
    text = WISHED_ROW.sub(r"put \g<items> in a row", text, count=1)
    text = LISTED_THEN_LINED.sub(r"put \g<items> in a row", text, count=1)
    text = LINED_THEN_LISTED.sub(r"line up \g<items>", text, count=1)
    text = re.sub(r"(?i)\s+(?:please|pls|plz)\s*(?::|-+\s|[\u2013\u2014])\s*", ": ", text)  # "Row please: A, B, C"
    text = _count_read_past(text)
    text = ROW_FIRST.sub(r"\g<verb> \g<items> in a \g<row>", text, count=1)
    text = LINE_FROM.sub(r"make a \1 of ", text, count=1)
    text = THE_FOLLOWING.sub(" of ", text, count=1)
    text = THEM_LISTED.sub(r"\g<items>\g<mid>", text, count=1)
    group = GROUP.search(text) or COLOURED_GROUP.search(text)
    if group is None:
        return text
    extra = EXTRA.match(text, group.end())  # "the two red cubes and the green one - small red, big red, green"
    after = text[extra.end() if extra else group.end():]
    named = try_object(extra.group("named"), scene) if extra else None
    for sep in re.finditer(r"\s*(?::|\s-+\s|[\u2013\u2014]|,|\()\s*", after):
        m = GROUP_ITEMS.match(after[sep.start():])
        if m is None:
            continue
        items = [_told(i) for part in m.group("items").split(",") for i in _split_and(part) if i.strip(" .!?")]
        count = group.group("count")
        said_count = number_said(count, len(items) - bool(extra)) + bool(extra)
        long = any(len([w for w in i.split() if w.lower() != "the"]) > 3 for i in items)
        if len(items) < 2 or said_count != len(items) or long:
            return text
        noun = group.group("kind").lower().rstrip("s")
        said = [i if noun in ("object", "thing") else re.sub(r"(?i)\s+one$", f" {noun}", i)
                if i.lower().startswith("the ") else _item(i, noun, scene, named) for i in items]
        listed = ", ".join(said[:-1]) + " and " + said[-1]
        return f"{text[:group.start()]}{listed}{after[:sep.start()]}"
    return text


COUNTED_ROW = re.compile(r"\b(?P<row>row|line)\s+of\s+(?:the\s+|all\s+)?(?P<count>two|three|four|five|six|[2-6])\s*:\s*"
                         r"(?P<items>[^:;.!?]+)", re.IGNORECASE)
"""A row's count said before its list ("row of four: tray, watch case, gift box, jar")."""


def _count_read_past(text: str) -> str:
    """``text`` with :data:`COUNTED_ROW`'s count read past where the list after it has that many items (split at its
    commas and "and"s); ``text`` itself where it says another number, which is then refused as it stands."""
    m = COUNTED_ROW.search(text)
    if m is None:
        return text
    items = [i for part in m.group("items").split(",") for i in _split_and(part) if i.strip(" .!?")]
    if number_said(m.group("count"), 0) != len(items):
        return text
    return f"{text[:m.start()]}{m.group('row')} of {text[m.start('items'):]}"


LINED_THEN_LISTED = re.compile(r"^\s*(?:(?:just|ok|okay|now|so|please|pls)[\s,]+)*line\s+(?:them|em|'em)"
                               r"(?:\s+all)?\s+up(?:\s+(?:mate|dear|pls|please|now))?\s*(?:[,:;!]+|\.{2,}|\s-+)\s*(?P<items>\S.*)$",
                               re.IGNORECASE)
"""A row lined up as "them" first, then its objects listed ("line em up!! clicker, tea, hearing aid box", "line them up
dear.. teapot kettle and spoon"): as "line up" and the list."""
THEM_LISTED = re.compile(r"\b(?:them|these|those|these\s+ones|those\s+ones|em|all\s+(?:two|three|four|five|six)|"
                         r"all\s+of\s+them)\b(?P<mid>[^:;.!?]*?)"
                         r"(?:\s*,?\s*(?:in\s+(?:this|that|the\s+following)\s+order|as\s+follows|like\s+this|like\s+so))?"
                         r"\s*:\s*(?P<items>[^:;.!?]+?)\s*[.!?]*$", re.IGNORECASE)
"""A row's objects said as "them" and listed after a colon ("row them up in this order: A, B, C"): the list stands
where "them" is."""
COLOURED_GROUP = re.compile(r"\bthe\s+(?P<count>two|three|four|five|[2-5])\s+[a-z]+\s+(?P<kind>cubes|blocks|boxes)\b",
                            re.IGNORECASE)
"""A group said with one word more ("the two red cubes"): each item told after it says that word itself."""
EXTRA = re.compile(r"\s+and\s+(?P<named>the\s+[\w-]+(?:\s+(?!in\b|into\b)[\w-]+)?)(?=\s|$|[,:;(])", re.IGNORECASE)
"""One more object named after a group ("the two blue cubes and the lemon"): its item is told among the group's."""


def _told(item: str) -> str:
    """An item told in order ("then the small one", "big blue one first") without its order words."""
    item = re.sub(r"(?i)^(?:and\s+)?(?:then|next|finally|last(?:ly)?|first)\s+", "", item.strip(" .!?"))
    item = re.sub(r"(?i)\s+(?:first|last|next)$", "", item)
    return f"the {item}" if item.lower().endswith(" one") and not item.lower().startswith("the ") else item


def _item(said: str, noun: str, scene: Scene, named: str | None) -> str:
    """An item told after a group ("small red", "lemon") as a description: with the group's noun, or as said where
    that is ``named``, the one object named after the group ("the two blue cubes and the lemon - small blue, lemon")."""
    with_noun = f"the {said} {noun}"
    if named is not None and try_object(with_noun, scene) is None and try_object(f"the {said}", scene) == named:
        return f"the {said}"
    return with_noun


def _parse_list(sentence: str, scene: Scene, phrases: dict[str, str]) -> ListCommand | None:
    """:func:`parse_list` of the sentence as it is said."""
    sentence = IN_ORDER.sub("", re.sub(r"(?i)\bw/\s*", "with ", sentence))
    raw = [w for w in sentence.split() if w.strip(".,;:!?\"()[]") and w not in ARROWS]
    words = tokens(sentence)
    kept = strip_polite(list(words))
    start = next((i for i in range(len(words) - len(kept) + 1) if words[i:i + len(kept)] == kept), 0)
    low = [w.lower() for w in kept]
    for toks, phrase, action in phrase_tokens(phrases):
        if not phrase_matches(low, toks):
            continue
        head, tail = _head_tail(toks)
        joined = _joined_at(low, head, tail)
        if joined is not None and not tail and _with_itself(raw[start + len(head): start + len(kept)],
                                                            joined - len(head), scene):
            joined = None  # "make a row of O, I and the red block with the X": "with" describes the last one
        if joined is None:
            rest = " ".join(raw[start + len(head): start + len(kept) - len(tail)])
        else:  # "put P in a row with Q and R": the block before the tail leads the list
            rest = " ".join(raw[start + len(head): start + joined]) + ", " + " ".join(
                raw[start + joined + len(tail) + 1: start + len(kept)])
        items = [i.strip(" .;:!?\"()[]") for part in rest.split(",") for i in _split_and(part)]
        items = [i for i in items if i]
        if items:  # "line up the mug, the jar and the stone in a row": the row said again at the end
            items[-1] = ROW_AGAIN.sub("", items[-1]).strip() or items[-1]
        named, taken = {n.lower() for n in scene.names}, set(name_words(scene))
        loose = [i.split() if len(i.split()) > 1 and (all(w.lower() in named or number_name(w, scene)
                                                          for w in i.split()) or said_letters(i.split(), scene, taken))
                 else [i] for i in items]  # "line up c b a", "line up U V W and stone", "four six and seven": names
        # without commas, and "line up ay eye oh and ex": letters said aloud
        items = [part for group in loose for w in group for part in _by_article(w, scene)]
        if len(items) < 2:
            raise LanguageError(f'"{phrase}" needs a list of at least two blocks, as in "{phrase} A, B and C"'
                                + (f' (got "{rest}")' if rest else ""))
        names = tuple(resolve_object(i, scene, role=f'block {k + 1} after "{phrase}"') for k, i in enumerate(items))
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise LanguageError(f'the list after "{phrase}" names {", ".join(twice)} more than once')
        return ListCommand(action, phrase, names, sentence.strip())
    return None


IN_ORDER = re.compile(r",?\s*in\s+(?:(?:(?:precisely|exactly|just|strictly)\s+)?(?:that|this|the\s+same|the\s+given)"
                      r"\s+order|the\s+order\s+(?:i(?:'ve|\s+have)?\s+"
                      r"(?:named|said|gave|given|listed|wrote|written|mentioned)(?:\s+them)?|given|named|listed))"
                      r"(?:\s*,?\s*(?:please|pls|plz|thanks|thank\s+you|thx|ty|grazie|obrigado|danke))*"
                      r"\s*[\-\u2013\u2014]*\s*(?=[.!?]*\s*$)", re.IGNORECASE)
""", in that order" after a list ("in that order please", "in the order I have named them"): the order named is the
order anyway."""
ROW_AGAIN = re.compile(r"\s+in\s+(?:a|one|a\s+single)\s+(?:row|line)\s*$", re.IGNORECASE)


def _with_itself(said: list[str], at: int, scene: Scene) -> bool:
    """Whether the last item before "with" (``said[at]``), with the words after it, names one object ("the red block
    with the X"): "with" then describes it, and joins no more of the list."""
    before = re.split(r",|\band\b|&", " ".join(said[:at]), flags=re.IGNORECASE)[-1].strip()
    item = f"{before} {' '.join(said[at:])}".strip(" .;:!?\"()[]")
    return bool(before) and try_object(item, scene) is not None


def _head_tail(toks: tuple[str, ...]) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """A composite's phrase around its list: "make a row of" is all head; "arrange ... in a row" has a tail."""
    if "..." not in toks:
        return toks, ()
    at = toks.index("...")
    return toks[:at], toks[at + 1:]


def phrase_matches(low: list[str] | tuple[str, ...], toks: tuple[str, ...]) -> bool:
    """Whether the lower-case words ``low`` are a composite's sentence of phrase ``toks``: they start with it, or,
    for a phrase with a gap for the list ("put ... in a row"), start with its head and end with its tail."""
    head, tail = _head_tail(toks)
    if tuple(low[:len(head)]) != head:
        return False
    return not tail or (len(low) > len(head) + len(tail) and tuple(low[len(low) - len(tail):]) == tail) \
        or _joined_at(low, head, tail) is not None


def _joined_at(low: list[str] | tuple[str, ...], head: tuple[str, ...], tail: tuple[str, ...]) -> int | None:
    """Where a gap phrase's tail is followed by "with" and more of the list ("put P in a row with Q and R",
    "line A up with B"): the tail's index in ``low``; None where the sentence has no such join."""
    for i in range(len(head) + 1, len(low) - len(tail) - 1):
        if tuple(low[i:i + len(tail)]) == tail and low[i + len(tail)] == "with":
            return i
    return None


def _names_run(words: list[str], scene: Scene) -> list[str] | None:
    """The scene's names that ``words`` are, one after another, each name perhaps after "the" ("the butter dish salt
    shaker": butter dish, salt shaker); None where the words are anything else or only one name."""
    names = sorted(((tuple(n.lower().split()), n) for n in scene.names), key=lambda t: -len(t[0]))
    low = [w.lower() for w in words]
    out, i = [], 0
    while i < len(low):
        i += low[i] == "the" and i + 1 < len(low)
        hit = next(((toks, n) for toks, n in names if tuple(low[i:i + len(toks)]) == toks), None)
        if hit is None:
            return None
        out.append(hit[1])
        i += len(hit[0])
    return out if len(out) > 1 else None


def _by_article(item: str, scene: Scene) -> list[str]:
    """"the ball the lid" -> "the ball", "the lid": a list typed without commas, split where each "the" opens an
    object, or where names of several words follow one another ("butter dish salt shaker"); the item as it is where it
    names one object or the pieces do not each name one."""
    words = item.split()
    starts = [k for k, w in enumerate(words) if w.lower() == "the"]
    if len(starts) >= 2 and starts[0] == 0 and try_object(item, scene) is None:  # each "the" first: "the orange
        pieces = [" ".join(words[a:b]) for a, b in zip(starts, [*starts[1:], len(words)], strict=True)]  # block"
        if all(try_object(p, scene) is not None for p in pieces):  # is one object, not the orange and the block
            return pieces
    run = _names_run(words, scene)
    return run if run is not None else [item]


def _split_and(text: str) -> list[str]:
    words = text.split()
    out, cur = [], []
    for w in words:
        if w.lower() in CONJUNCTIONS:
            out.append(" ".join(cur))
            cur = []
        else:
            cur.append(w)
    return [*out, " ".join(cur)]
