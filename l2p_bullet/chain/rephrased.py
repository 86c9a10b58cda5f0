"""A command said in other words, said again the usual way before it is resolved: a carry told by where the object
goes on the way ("Take the duck in the air and put it down near the ball"), a push said as a noun ("Give the duck a
little shove toward the pot"), the object before "you" and the verb ("The ball you move closer to the cube"), "over to"
("bring the ring over to the lego"), "to" an object or an arrow to it ("move the roll to the milk", "e->c"), "to next
to", a motion said as what the object is made to do ("make the 1 turn around the 4"), a carry told as two steps
("carry the mug over to the jar and set it down beside it"), and a command with words after it that change nothing:
a reason ("..., it's gonna spill"), a comparative's yardstick said as the table now ("than it currently is"),
politeness between commas or between two words. ``chain/clauses.py`` resolves each; one that does not resolve is
no reading.
"""

from __future__ import annotations

import re

from ..language import verb_heads

_PUT_IT = r"\s+and\s+(?:set|put|place|drop|lay)\s+it(?:\s+down)?\s+"
OVER_TO_AND_PUT = re.compile(rf"\s+over\s+to\s+(?P<to>.+?){_PUT_IT}(?P<how>.+?)(?P<it>\s+it)?\s*[.!?]*\s*$",
                             re.IGNORECASE)
OVER_AND_PUT = re.compile(rf"\s+over{_PUT_IT}", re.IGNORECASE)
"""A carry told as two steps: "carry the mug over to the jar and set it down beside it" is "carry the mug beside
the jar"; "carry the jar over and set it beside the stone" is "carry the jar beside the stone", and so is
"carry the jar over to the stone and set it down beside the stone"."""
_AIR_VERBS = r"(?:take|move|bring|get|lift|translate|transport|carry|raise|hoist|grab|pick)"
_AIR = r"(?:up\s+)?(?:in|into|through|thru)\s+the\s+air"
_AND_PUT_IT = r"\s+and\s+(?:put|bring|set|place|move|carry|drop|lay|take)\s+it(?:\s+down)?\s+(?P<rest>.+)$"
_ASK = r"please|pls|now|can\s+you|could\s+you|would\s+you"
_ASKING = rf"(?:(?:{_ASK}|can\s+the\s+(?:robot|arm)|could\s+the\s+(?:robot|arm))\s+)*"
_HOW = (r"(?:,?\s+(?P<how>nice\s+and\s+(?:slow|slowly|easy|gentle|gently)"
        r"|(?:very\s+|really\s+)?(?:slowly|gently|carefully|quickly)))?,?")
IN_THE_AIR = re.compile(rf"^\s*{_ASKING}{_AIR_VERBS}\s+(?P<what>.+?)\s+{_AIR}{_HOW}{_AND_PUT_IT}", re.IGNORECASE)
AIR_FIRST = re.compile(rf"^\s*{_ASKING}{_AIR_VERBS}\s+{_AIR}\s+(?P<what>.+?){_AND_PUT_IT}", re.IGNORECASE)
"""A carry said by where the object goes on the way: "Take the duck in the air and put it down near the ball", "Take
in the air the cube and bring it near the bottle", "Carry the truck through the air, nice and slow, and set it down
next to ..." (the pace said on the way kept)."""
YOU_VERB = re.compile(r"^\s*(?P<what>.+?)(?:,\s*(?:this|that)(?:\s+one)?)?,?\s+you\s+(?:should\s+|must\s+|can\s+)?"
                      r"(?P<verb>[a-z]+)\s+(?P<rest>.+)$", re.IGNORECASE)
"""The object before "you" and the verb, as learners of English may write it: "The ball you move closer to the
yellow cube", "The small red cube, this you push to the box", "The block 1 you should move past the box"."""
TAKE_AND = re.compile(r"^\s*(?:(?:now|then|ok|okay|so)\s+)?(?:take|get)\s+(?P<what>.+?)(?:\s*,\s*|\s+and\s+|\s+)"
                      r"(?P<verb>bring|move|slide|shift|put|place|set|push|nudge|shove|carry)"
                      r"\s+(?:it|them(?:\s+both)?|both\s+of\s+them)\s+(?P<rest>.+)$",
                      re.IGNORECASE)
"""An object taken first, then moved as "it": "Now take the sugar box and bring it closer to the can" is "bring the
sugar box closer to the can" (the second verb's manner; "grab ... and put" is a carry of its own, read by the
manners); two taken and moved as "them" are each moved so ("take the glove box and the sanitizer and move them closer
to the clipboard"); the two verbs may run on without "and" ("take O move it next to Q"). Not "grab": people wrote "grab
X, put it ..." as a carry and as a slide alike, and the manners read it."""
LIFT_THEN = re.compile(r"^\s*(?:(?:now|then|ok|okay|so|first|would\s+you|could\s+you|can\s+you|please)\s+)*"
                       r"(?:lift|pick\s+up|take\s+up|raise|hoist|carry)\s+(?P<what>.+?)"
                       r"(?:\s+up)?(?:\s*(?:,|\s+and)\s+hold\s+(?:it|them)(?:\s+up)?)?"
                       r"\s*(?:,|\s+and|\s+while\s+you|)\s+(?:then\s+)?(?:bring|move|put|place|set|slide|shift|take|carry"
                       r"|leave|drop|lay|pop|land|park|plonk|stick)\s+"
                       r"(?:it|them(?:\s+both)?|both\s+of\s+them)\s+(?P<rest>.+)$", re.IGNORECASE)
"""An object lifted first, then moved as "it" or "them": "Lift the tasse, bring it next to the sucrier", "Pick up
the phone and the notebook and move them both closer to the cup" is a carry of each; so is one held up while it
moves ("pick up the file and hold it up while you move it past the towel") and one carried and then put ("Carry the
shampoo and put it beside the soap"); so is one lifted and then left, dropped or popped somewhere ("pick up the lime
and leave it next to the bottle"), also run on without "and" ("pick up the cup carry it past the pin")."""
HELD_UP = re.compile(r"^(?P<lead>\s*(?:(?:now|then|ok|okay|so|first|would\s+you|could\s+you|please)\s+)*)hold\s+"
                     r"(?:up\s+(?P<up>.+?)|(?P<what>.+?)\s+up)(?=\s*(?:,|\s+and\s|\s+while\s))", re.IGNORECASE)
"""An object held up before it moves ("Hold the flask up and carry it past the burner", "hold up nut, bring near
bracket"): lifted, as :data:`LIFT_THEN` reads it."""
TOPIC_BARE = re.compile(r"^\s*(?P<what>.+?)\s+(?P<verb>[a-z]+)\s+(?P<it>it|that|this)\s+(?P<rest>.+)$", re.IGNORECASE)
"""A topic said before the command without a comma: "okay the bowl move it closer to the blue cube" is "okay the
bowl, move it closer to the blue cube" (the verb a known one, the topic not opening with one)."""


MAKE_GO = re.compile(rf"^\s*(?:(?:{_ASK})[\s,]+)*make\s+(?P<what>.+?)"
                     r"\s+(?:go|turn|move|travel|slide|circle|loop|pass)"
                     r"\s+(?P<rest>(?:(?:a\s+)?(?:bit|little|lot|way|far|right|just|slightly)\s+)*"
                     r"(?:around|round|past|beyond|by|next|beside|closer|nearer|toward|towards|away|over)\b.*)$",
                     re.IGNORECASE)
"""A motion said as what the object is made to do: "can you make the 1 turn around the 4?" is "move the 1 around the
4"."""


GIVE_A = re.compile(r"^\s*give\s+(?P<what>.+?)\s+an?\s+(?:(?P<size>little|small|slight|tiny|wee|lil|gentle|soft|"
                    r"quick|fast)\s+)?(?P<how>push|nudge|shove|poke|tap|bump)\s+(?P<rest>.+)$", re.IGNORECASE)
GIVE_SIZES = {"little": "a bit", "small": "a bit", "slight": "a bit", "tiny": "a bit", "wee": "a bit", "lil": "a bit",
              "gentle": "gently", "soft": "gently", "quick": "quickly", "fast": "quickly"}
"""A push said as a noun with its size or pace: "Give the duck a little shove toward the pot" is "shove the duck a bit
toward the pot"."""


CAREFUL_WITH = re.compile(r"^\s*(?P<how>careful|gentle|go\s+easy|easy)\s+(?:with|w/?)\s+(?P<what>[^,]+?)\s*,\s*"
                          r"(?P<rest>\S.*\bit\b.*)$", re.IGNORECASE)
CAREFUL_WITH_PACE = {"careful": "carefully", "gentle": "gently", "easy": "gently"}
"""An object shown with the care it asks for, then moved as "it": "careful w the thermometer, slide it away from the
green box", "easy with the betty, gently slide it ...": the object, then the clause at that pace."""
TO_THEN = re.compile(r"^(?P<head>.+?)\s+(?:over\s+)?to\s+(?P<rest>(?:right\s+)?(?:next|beside|alongside|near|nearer"
                     r"|closer|past|around|round|away)\b.*)$", re.IGNORECASE)
"""A "to" before the relation it leads to: "Carry the donut to next to the small cube", "move it over to right beside
B"."""
OVER_TO = re.compile(r"^(?P<head>.+?)\s+over\s+to\s+(?P<rest>\S.*)$", re.IGNORECASE)
"""A motion said by where it goes to and nothing more: "bring the ring over to the lego" brings it closer; where more
is said ("over to the other side of", "over to B and set it down beside it") those readings win first."""


_NOT_AN_OBJECT = (r"(?!(?:right|left|back|front|rear|far|near|middle|centre|center|corner|edge|side|end|top|bottom"
                  r"|other|same|table|robot|them|there|here|where)\b)")
_TAIL = (r"(?:\s+(?:quick|quickly|fast|slow|slowly|gently|carefully|now|pls|plz|please|thx|thanks|too|also|aswell"
         r"|as\s+well))*\s*[.!]*")
_PLACE_WORD_BEFORE = r"(?<!\bnext)(?<!\bclose)(?<!\bcloser)(?<!\bnear)(?<!\bnearer)(?<!\bup)(?<!\bright)"
TO_OBJECT = re.compile(rf"^(?P<head>.+?){_PLACE_WORD_BEFORE}(?:\s+to\s+(?P<rest>(?:the|a|an)\s+{_NOT_AN_OBJECT}\S.*"
                       rf"|{_NOT_AN_OBJECT}[\w-]+(?:\s+{_NOT_AN_OBJECT}[\w-]+)?{_TAIL})|\s*(?:->|-->|=>|\u2192)\s*(?P<arrow>{_NOT_AN_OBJECT}[^,;]+))$",
                       re.IGNORECASE)
"""A motion said by the object it goes to: "Move the roll to the milk", "push a to d quick", "e->c" (an arrow to an
object) bring it closer, as "over to" does; never a place ("to the corner", "to the right of"), which no action
takes. Without an article, "to" is followed by a name of one or two words ("to d", "to tip box"), so "the lego to circle
the cube" is not read so (and what follows must name an object); an arrow before a relation ("cup -> past the jar")
is read by the grammar, before this. A "to" that ends a place ("next to", "close to", "up to") is never this "to"."""


WHY = re.compile(r"(?:\s*,\s*|\s+)(?:so\s+(?:that\s+)?(?:i|i'll|i\s+can|we|my|everyone|everybody|you\s+can|he|she"
                 r"|people)\b|so\s+(?:that\s+)?(?:it|they|the\s+[a-z]+)\s+(?:can|can't|cannot|won't|wont|doesn't|doesnt"
                 r"|does\s+not|don't|dont|will)\b|because\b|cause\b|coz\b|cuz\b|since\b|before\b|b4\b|for\s+when\b"
                 r"|when\s+(?:you're|you\s+are|you've|you're\s+done|i|i'm|he|she|we)\b|that's\s+(?:where|why|how|what)\b"
                 r"|it(?:'s|s)?\s+(?:gonna|going\s+to|keeps|will|should|might|may|could|always)\b"
                 r"|my\s+\w+\s+(?:keeps|will|is|leaves|always)\b|keeping\s+it\s+off\b|as\s+far\s+as\s+it\s+will\b"
                 r"|i\.?e\.?(?:\s*,)?\s)[^.;!?]*[.!]*\s*$", re.IGNORECASE)
"""A reason, a time or a restatement said after the command ("... away from the ketchup, it's gonna spill", "... closer
to the mug so I can reach it", "... so the baby can reach it", "... so it doesn't get bruised", "... before my kid
grabs it", "..., i.e. past it"): read past where the command before it
is whole."""


THAN_NOW = re.compile(r"\s+than\s+(?:it|they|he|she)\s+(?:(?:currently|presently)\s+)?"
                      r"(?:is|are|was|were|'s|'re|stands|sits)"
                      r"(?:\s+(?:now|right\s+now|currently|at\s+the\s+moment|at\s+present))?\s*[.!]*\s*$",
                      re.IGNORECASE)
"""A comparative's yardstick said as the table now ("farther from the white cube than it currently is"): the
comparative says it already."""
POLITE_INSIDE = re.compile(r"\s*,\s*(?:please|pls|plz|thanks|if\s+you\s+(?:would|could|can|please))\s*,\s*",
                           re.IGNORECASE)
"""Politeness said between commas inside the command ("Push the milk right next to the bottle, please, so they're
touching"), or between two words without them ("The red cube please only a little nearer to the ball."): read past."""
POLITE_BARE = re.compile(r"(?<=\w)\s+(?:please|pls|plz|kindly)\s+(?=\w)", re.IGNORECASE)


OVER_TO_SIDE = re.compile(r"^(?P<head>.+?)\s+over\s+(?P<what>(?!the\s+(?:other|far)\b).+?)\s+(?:to|on|onto)\s+the\s+"
                          r"(?P<side>other|far)\s+side(?P<tail>\s+(?:quick|quickly|slowly|gently|carefully|please|pls))?"
                          r"\s*[.!]*\s*$", re.IGNORECASE)
"""Over an object to its other side: "lift O over the bucket to the other side" is "lift O to the other side of the
bucket"."""
NOT_SO_CLOSE = re.compile(r"\b(?P<what>(?:the\s+)?[\w-]+(?:\s+[\w-]+){0,3}?)\s+"
                          r"(?:isn't|isnt|is\s+not|wasn't|was\s+not)\s+(?:so|too|as|that)\s+(?:close|near)(?:\s+(?:to|of))?\s+(?P<other>.+?)"
                          r"(?:\s+any\s*more)?\s*[.!]*\s*$", re.IGNORECASE)
"""An end said as a closeness undone: "Make it so the cylinder isn't so close to the cup any more", "It would be good
when the bread is not so near to the cereal anymore": the first away from the second."""


_CLOSING = r"(?:[\s,]+(?:bitte|danke|please|pls|thanks))?[\s.!]*$"
VERB_LAST = re.compile(rf"^\s*(?P<lead>(?:(?:gently|slowly|carefully|quickly|softly|please|bitte|first|then)[\s,]+)*)"
                       rf"(?P<rest>\S.*?)\s+(?P<verb>[a-z]+){_CLOSING}", re.IGNORECASE)
"""The verb said last, in German order: "The green cube to the orange block push", "Gently the plate through the air
to the green cube bring", "The bowl, the plate and the green cube in a row put" (a known verb, the words before it
opening with none)."""
BE_LAST = re.compile(rf"^\s*(?:(?:at|in)\s+the\s+end[\s,]+)?(?:(?:should|shall|must)\s+(?P<asked>.+?)|(?P<said>.+?)\s+"
                     rf"(?:should|shall|must)\s+(?P<where>.+?))\s+(?:be|go|stand|lie|sit){_CLOSING}", re.IGNORECASE)
"""An end state with its "be" (or "go", "stand", "lie", "sit") last: "The plate must farther from the bowl be", "At the
end should the lemon nearer to the plate be", "the green dice shall around the blue dice go": what is wished."""


PASS = re.compile(rf"^\s*(?:(?:{_ASK})[\s,]+)*pass\s+(?P<rest>.+?\s+(?:(?:just|only|slightly|a\s+bit)\s+)*"
                  r"(?:past|beyond|(?:on\s+|to\s+)?the\s+(?:other|far)\s+side\s+of)\s.+)$", re.IGNORECASE)
""""Pass the cup just beyond the green cube", "can you pass the red cube on the other side of the soup can": a move
past it."""
PASS_BY = re.compile(r"(?P<lead>^|[,;.]\s*|\b(?:and|then|after|please|to)\s+)pass\s+(?P<what>[^,;.]+?)\s+by\b",
                     re.IGNORECASE)
""""Pass the E by the C", "pass the one in the back by the cylinder": a move past it, as every author who wrote it
meant (a person passes by what they go past; "go by B" may be past or beside B, and is asked)."""


def passed_by(sentence: str) -> str:
    """``sentence`` with each :data:`PASS_BY` said as the grammar reads it ("move the E past the C"), before it is read:
    read as written, "pass" would be taken for a word of the object's description and "by" for beside."""
    return PASS_BY.sub(r"\g<lead>move \g<what> past", sentence)
NOT_DRAGGED_THEN = re.compile(r"^\s*(?:don't|dont|do\s+not)\s+(?:drag|slide)\s+(?P<what>[^,]+?)\s*,\s*"
                              r"(?P<verb>lift|pick\s+up|carry|raise)\s+it\b(?P<rest>.+)$", re.IGNORECASE)
"""A carry told by the slide it is not: "Don't drag the bowl, lift it and set it by the plate" is "lift the bowl and set
it by the plate"."""


POSTPOSITIONS = dict(zip("near beside next around round past away closer toward towards".split(),
                         ("near", "beside", "next to", "round", "round", "beyond", "away from", "closer to", "toward",
                          "towards"), strict=True))
"""A place said after its object, as Korean, Japanese and Turkish say it ("A to B near move", "C near put") -> the words
the grammar reads before the object (words, not actions: the installed phrases decide what they ask for)."""
GO_FIRST = re.compile(r"^\s*(?P<what>.+?)\s+(?:go|goes|should\s+go|must\s+go)\s+(?P<rest>(?:to|around|round|past|beyond"
                      r"|near|beside|next\s+to|closer|toward|towards|away)\b.+)$", re.IGNORECASE)
"""An object that goes somewhere, said with nothing before it: "biggest one go around the middle one" is "move the
biggest one around the middle one" ("goes by" may be past or beside: not read)."""


def _verb_last(text: str) -> list[str]:
    """:data:`VERB_LAST`'s, :data:`BE_LAST`'s and :data:`GO_FIRST`'s sentences said the usual way, a place said after
    its object (:data:`POSTPOSITIONS`) said before it; [] for any other."""
    m = BE_LAST.match(text)
    if m is not None:
        return [f"I want {m.group('asked') or m.group('said') + ' ' + m.group('where')}"]
    heads = verb_heads()
    m = GO_FIRST.match(text)
    if m is not None and m.group("what").split()[0].lower() not in heads | {"it", "that", "this", "then"}:
        return [f"move {m.group('what')} {m.group('rest')}"]
    m = VERB_LAST.match(text)
    verb = m.group("verb").lower() if m is not None else ""
    verb = "move" if verb in ("go", "goes") else verb
    if m is None or verb not in heads or m.group("rest").split()[0].lower() in heads:
        return []
    rest = m.group("rest").split()
    said = POSTPOSITIONS.get(rest[-1].lower()) if len(rest) >= 3 else None
    if said is None:
        return [f"{m.group('lead')}{verb} {m.group('rest')}"]
    body = rest[:-1]  # "A to B near": the object before "to" or "from" moves; else each way of cutting the words
    cut = next((k for k, w in enumerate(body) if w.lower() in ("to", "from") and 0 < k < len(body) - 1), None)
    cuts = [(body[:cut], body[cut + 1:])] if cut is not None else [(body[:k], body[k:]) for k in range(1, len(body))]
    return [f"{m.group('lead')}{verb} {' '.join(what)} {said} {' '.join(where)}" for what, where in cuts]


def in_other_words(text: str) -> list[str]:
    """``text`` said the usual way, where it is said one of :data:`IN_THE_AIR`'s, :data:`AIR_FIRST`'s,
    :data:`GIVE_A`'s, :data:`YOU_VERB`'s, :data:`LIFT_THEN`'s, :data:`TO_THEN`'s, :data:`OVER_TO`'s,
    :data:`OVER_TO_SIDE`'s or :data:`TO_OBJECT`'s ways, or with :data:`THAN_NOW`, :data:`POLITE_INSIDE` or :data:`WHY`
    words; the caller resolves each (one that does not resolve is no reading)."""
    out = []
    m = IN_THE_AIR.match(text) or AIR_FIRST.match(text)
    if m is not None:
        out.append(" ".join(w for w in ("carry", m.group("what"), m.groupdict().get("how"), m.group("rest")) if w))
    m = GIVE_A.match(text)
    if m is not None:
        said = GIVE_SIZES.get((m.group("size") or "").lower(), "")
        out.append(" ".join(w for w in (m.group("how"), m.group("what"), said, m.group("rest")) if w))
    out += _said(MAKE_GO, r"move \g<what> \g<rest>", text) + _said(YOU_VERB, r"\g<verb> \g<what> \g<rest>", text)
    held = HELD_UP.sub(lambda m: f"{m.group('lead')}lift {m.group('up') or m.group('what')}", text, count=1)
    out += _said(TAKE_AND, r"\g<verb> \g<what> \g<rest>", text) + _said(LIFT_THEN, r"carry \g<what> \g<rest>", held)
    m = TOPIC_BARE.match(text)
    if m is not None and "," not in m.group("what") and m.group("verb").lower() in verb_heads() \
            and m.group("what").split()[0].lower() not in verb_heads():
        out.append(f"{m.group('what')}, {m.group('verb')} {m.group('it')} {m.group('rest')}")
    m = CAREFUL_WITH.match(text)
    if m is not None:  # "careful w the thermometer, slide it away from ...": the thermometer, carefully slid
        out.append(f"{m.group('what')}, {CAREFUL_WITH_PACE[m.group('how').lower().split()[-1]]} {m.group('rest')}")
    to_then = TO_THEN.match(text)
    if to_then is not None:
        out.append(f"{to_then.group('head')} {to_then.group('rest')}")
    m = (OVER_TO.match(text) or TO_OBJECT.match(text)) if to_then is None else None
    if m is not None:  # "over to" first, then "to" an object
        out.append(f"{m.group('head')} toward {m.group('rest') or m.group('arrow')}")
    m = OVER_TO_SIDE.match(text)
    if m is not None:
        out.append(f"{m.group('head')} to the {m.group('side')} side of {m.group('what')}{m.group('tail') or ''}")
    m = THAN_NOW.search(text)
    if m is not None:
        out.append(text[:m.start()])
    if POLITE_INSIDE.search(text):
        out.append(POLITE_INSIDE.sub(" ", text))
    elif POLITE_BARE.search(text):
        out.append(POLITE_BARE.sub(" ", text))
    m = WHY.search(text)
    if m is not None and m.start() > 0:
        out.append(text[:m.start()])
    m = NOT_SO_CLOSE.search(text)
    if m is not None:
        out.append(f"{text[:m.start()]}{m.group('what')} is away from {m.group('other')}")
    out += _said(PASS, r"move \g<rest>", text) + _said(NOT_DRAGGED_THEN, r"\g<verb> \g<what>\g<rest>", text)
    return out + _verb_last(text)


def _said(pattern: re.Pattern, template: str, text: str) -> list[str]:
    """``text`` said again by ``template`` (the groups ``pattern`` matched put in), or [] where it does not match."""
    m = pattern.match(text)
    return [] if m is None else [m.expand(template)]


def over_and_put(text: str) -> str:
    """``text`` with a carry told as two steps (:data:`OVER_TO_AND_PUT`) said as one; else ``text`` itself."""
    m = OVER_TO_AND_PUT.search(text)
    if m is not None:  # "... beside it": beside what it was carried over to; "... beside the red cube": that
        return f"{text[:m.start()]} {m.group('how')}" + (f" {m.group('to')}" if m.group("it") else "")
    return OVER_AND_PUT.sub(" ", text, count=1)
