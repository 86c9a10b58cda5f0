"""The words around a command that people add and the parser must read past or record.

People frame a command politely ("could you ...", "..., please"), say where the block should end up
instead of how to move it ("so that it is next to B", "until it is past A"), qualify the preposition
("far away from", "a bit closer to", "right next to") and the manner ("slowly", "gently"). Politeness
and framing carry no meaning for the robot and are dropped; the qualifiers are recorded on the command:

- ``pace`` (how the arm moves): slow, fast, gentle or careful; the executor turns it into ruckig's
  velocity and acceleration limits (``embodiment/smoothing.PACES``).
- ``extent`` (how far the relation goes): far, little or right; each action declares which it accepts
  (``[language] extents`` in its manifest), so "far around B" is refused rather than ignored; its words and
  their readers are language/extents.py's.

A word that is the name of an object in the scene is never dropped ("move Now next to B" moves "Now").
"""

from __future__ import annotations

from ..errors import LanguageError
from .numbers import HEARD_NUMBERS, number_of
from .reference_words import NOUNS
from .synonyms import name_parts

POLITE_PREFIXES: tuple[tuple[str, ...], ...] = tuple(sorted((tuple(p.split()) for p in (
    "would you be so kind as to", "would you be so kind and", "would you please", "could you please",
    "can you please", "i would like you to", "i'd like you to", "i want you to", "i need you to",
    "go ahead and", "please could you", "please can you", "please to", "please", "kindly", "could you", "can you",
    "would you", "will you", "could u", "can u", "pls", "plz", "let's", "lets", "try to", "now", "then", "and",
    "first", "finally", "just", "do me a favour", "do me a favor", "hey robot", "hey", "ok", "okay", "robot",
    "alright", "all right",
    "after that", "afterwards", "lastly", "next", "maybe", "also", "hello", "hi",
    "hey there", "hi there", "hello there", "good morning", "yo", "thx in advance", "thanks in advance",
    "good afternoon", "good evening", "dear robot", "chat", "ok chat", "okay chat", "chat voted",
    "you can", "you", "when you get a chance", "when you have a moment", "if you could", "if you can",
    "i would be very grateful if you could", "i would be grateful if you could", "i'd be grateful if you could",
    "for this one", "for the next one", "right", "so", "why don't you", "why dont you", "why not", "basically",
    "so basically", "ok so basically", "ok so", "it would be nice if", "it would be great if", "it'd be nice if",
    "it'd be great if", "it would be good if", "i wish", "it would be good when", "it would be nice when",
    "it would be cool if", "it'd be cool if", "it'd be good if", "your task", "your job", "here's what to do",
    "here's what i need", "here is what i need", "here's the task", "here is the task", "here's the plan",
    "here's the thing", "here is the thing", "so here's the thing", "ok here's the thing",
    "the task is simple", "the task is easy", "ideally", "two steps", "three steps", "four steps", "five steps",
    "if it's no trouble", "if it is no trouble", "if it's not too much trouble", "if you don't mind",
    "if you dont mind", "if possible", "if you would", "do me a favour and", "do me a favor and",
    "if you would be so good", "if you would be so kind", "if you'd be so kind", "would u", "would u pls",
    "it would be lovely if", "it'd be lovely if", "it would be wonderful if",
    "do the needful and", "please do the needful and", "kindly do the needful and", "request you to",
    "i request you to", "request you to kindly", "sorry to be a pain", "sorry to be a pain but",
    "sorry to bother you", "sorry to bother you but", "sorry to trouble you", "sorry to trouble you but",
    "can we", "could we", "can we please", "could we please", "request", "my request", "new request",
    "be a love and", "be a dear and", "be a star and", "be a pal and", "be a good lad and",
    "be a good boy and", "be a good girl and", "be an angel and", "be a darling and", "if it's no bother",
    "if it is no bother", "if its no bother", "get it so", "get it so that",
    "abeg", "oya", "biko", "pls po", "please po", "po", "quick favor", "quick favour", "a quick favor",
    "a quick favour", "quick question", "help me", "help us", "can you help us", "can you help me",
    "could you help us", "could you help me",
    "brother please", "brother", "sister please", "habibi", "my friend", "please if you can", "please if not difficult",
    "if not difficult", "trouble you", "trouble you please", "thank you in advance", "todo", "to do",
    "pretty please", "required end state", "required", "i'd be grateful if", "i would be grateful if",
    "i'd be grateful if you could", "i'd be grateful if you would", "thank you robot", "thanks robot",
    "ok robot", "okay robot", "alexa", "hey alexa", "siri", "hey siri", "hey google", "ok google",
)), key=len, reverse=True))
"""Words that may open a command and ask for nothing (longest first, so "hey there" goes whole)."""
VOCATIVES = ("boys and girls", "girls and boys", "kids", "children", "class", "everyone", "everybody", "friends",
             "you guys", "guys", "folks")
"""Whom a teacher speaks to beside the robot ("Boys and girls, let's line up ...", "..., everyone!"): read past
before or after the command, as a courtesy is."""
POLITE_PREFIXES = tuple(sorted(POLITE_PREFIXES + tuple(tuple(v.split()) for v in VOCATIVES), key=len, reverse=True))
ADDRESSEES = frozenset({"you", "u"})
"""A polite opening that ends by addressing the robot ("can you", "can u") is read past even where a word of it
names an object: "can you push the can ..." asks the robot, whatever the can is called."""
NOT_BEFORE_TO = frozenset({"next"})
"""Openings that are part of a preposition when "to" follows them ("next to C" is a clause's preposition):
read past only before another word."""
POLITE_SUFFIXES: tuple[tuple[str, ...], ...] = tuple(sorted((tuple(p.split()) for p in (
    "please thanks", "please thank you", "thank you very much", "thank you so much", "thank you", "thanks",
    "please", "if you please", "if you would", "rn", "right now",
    "for me", "for us", "now", "would you", "could you", "will you", "can you", "ok", "okay", "too", "as well",
    "aswell",
    "and do it", "do it", "thx", "ty", "cheers", "thank u", "thanks a lot", "thanks so much", "please and thank you",
    "not the other way round", "not the other way around", "and not the other way round",
    "nothing else moved", "and nothing else", "this is what i want", "that's what i want", "that is what i want",
    "if you can", "if possible", "when you can", "dear", "please dear", "mate", "buddy", "pal", "hun", "hon",
    "sweetie", "thanks hun", "thanks hon", "i should think", "i think", "bro", "fr", "lol", "ez", "gg", "dude",
    "bitte", "danke", "thanks chef", "chef", "only", "itself", "go", "go go", "go go go",
    "pls", "plz", "pls ty", "pls thx", "tia", "many thanks", "thanks in advance", "thank you in advance",
    "much appreciated", "that would be great", "and set it down", "and put it down", "and drop it",
    "and let go", "and let go of it", "and set it down there", "and put it down there",
    "that'd be great", "that would be nice", "that would be lovely", "please and thanks",
    "shall we", "can you do that", "could you do that", "lol", "when you have a moment", "when you get a chance",
    "if you don't mind", "if you dont mind", "yeah", "ok thanks", "in one full circuit", "in a full circle",
    "in one full circle", "in one full loop", "in a full loop", "all the way", "again", "not far", "do that",
    "at the end", "in the end", "make it happen", "make it so", "would you see to that", "could you see to that",
    "see to that", "that's it", "that's all", "ta", "appreciate it", "i appreciate it", "much obliged",
    "if that's alright", "if that is alright", "if that's all right", "if that's ok", "if that's okay",
    "if that is ok", "if that is okay", "please make like that", "make like that", "please make it like that",
    "make it like that", "please do", "please do it", "please do so", "than it is now", "than it is", "than now",
    "than it was", "than at present", "than it is at present", "than at the moment", "than it is at the moment",
    "than currently", "than it is currently", "than before", "lah", "leh", "lor", "ah", "hor", "sia", "or not",
    "can or not", "ok lah", "okay lah", "thanks ah", "thank you ah", "that'd be grand", "that would be grand",
    "po", "salamat", "salamat po", "thanks po", "thank you po", "thank u po", "aye", "cheers pal",
    "onegaishimasu", "onegai shimasu", "onegai", "kudasai", "arigatou", "arigato", "arigatou gozaimasu",
    "please onegaishimasu",
    "much appreciated", "that is all", "that's all", "though", "tho",
    "that'd be grand cheers", "it's in the way", "its in the way", "it's in my way", "its in my way",
    "it is in the way", "it is in my way", "while you're there", "whilst you're there",
    "while you're at it", "whilst you're at it", "while you are at it", "whilst you are at it",
    "don't knock anything over", "don't knock anything", "don't knock anything else over",
    "without knocking anything over", "without knocking anything", "don't hit anything", "without hitting anything",
    "without touching anything else", "don't touch anything else",
    "if it's no trouble", "if it is no trouble", "if it's not too much trouble", "if it is not too much trouble",
    "if it isn't too much bother", "if it's not too much bother", "if it is not too much bother",
    "so they're together", "so they are together",
    "if its not too much trouble", "if it's no bother", "if that's ok", "if that's okay", "if thats ok",
    "thats it", "thats all", "when we're done", "when were done", "when we are done", "when you're done",
    "when youre done", "when you are done", "at the end of it",
    "inshallah", "insha'allah", "habibi", "god bless you", "god bless", "my friend", "brother", "thank", "period",
    "comma", "full stop", "thank you sir", "thanks sir", "obrigado", "obrigada", "gracias", "merci",
    "if that makes sense", "rules are rules", "heard", "thanks a lot", "thank you robot",
    "if you could sort that out", "when you get a sec", "when you have a sec",
    "ta very much", "ta love", "cheers love", "there's a good lad", "there's a dear",
    "like",
)), key=len, reverse=True))
POLITE_SUFFIXES = tuple(sorted(POLITE_SUFFIXES + tuple(tuple(v.split()) for v in VOCATIVES), key=len, reverse=True))
GERUND_PREFIXES: tuple[tuple[str, ...], ...] = (("do", "you", "mind"), ("mind",), ("keep",), ("start",),
                                                ("how", "about"), ("what", "about"), ("fix", "that", "by"),
                                                ("fix", "it", "by"), ("fix", "this", "by"), ("do", "that", "by"),
                                                ("do", "it", "by"), ("do", "this", "by"))
"""Openings followed by the verb's -ing form: "do you mind moving A past B", and "would you mind ..." once its
"would you" is read past as politeness."""

_RESTS = ("is", "'s", "ends up", "goes", "sits", "lands", "ends", "lies", "rests", "stands", "gets", "moves", "comes")
FRAMES: tuple[tuple[str, ...], ...] = tuple(sorted((tuple(p.split()) for p in (
    *(f"{lead} {rest}".replace(" 's", "'s") for lead in ("so that it", "so it", "such that it", "until it")
      for rest in _RESTS),
    "so that", "so", "over so it's", "over so it is", "over", "back", "down", "up", "all", "until its", "so its",
    "so that its",
    "along the table", "across the table", "over the table", "on the table", "to be", "to end up",
    "until", "till", "untill", "til", "along",
)), key=len, reverse=True))
"""Words between the mover and the preposition that say where the mover ends, not how: dropped."""

PACES: dict[str, str] = {
    "slowly": "slow", "slow": "slow", "asap": "fast", "pronto": "fast", "hurry": "fast", "hurriedly": "fast",
    "stat": "fast",  # a clinic's "at once"
    "quickly": "fast", "quick": "fast", "fast": "fast", "rapidly": "fast", "sharpish": "fast",
    "swiftly": "fast", "handsomely": "slow",  # a sailor's "slowly and with care"
    "gently": "gentle", "softly": "gentle", "carefully": "careful", "cautiously": "careful", "careful": "careful",
    "gentle": "gentle",
    # said in Spanish among English words, as bilingual speakers do ("rapido!! move la lata ...")
    "rapido": "fast", "rápido": "fast", "rapidito": "fast", "despacio": "slow", "despacito": "slow",
    "lento": "slow", "lentamente": "slow", "suave": "gentle", "suavecito": "gentle", "suavemente": "gentle",
    "cuidadosamente": "careful",
    # in French, as francophones do ("doucement, move the sucrier ...", "vite vite! push ...")
    "doucement": "gentle", "vite": "fast", "rapidement": "fast", "lentement": "slow", "délicatement": "gentle",
    "delicatement": "gentle", "prudemment": "careful",
    # written as notes without their vowels ("gntly push F to B"), read before the verb as paces are
    "slwly": "slow", "qckly": "fast", "qkly": "fast", "gntly": "gentle", "crfly": "careful", "crfully": "careful",
    # in Scots ("go canny an lift yon black tin ...")
    "canny": "careful",
    # and in Hindi, as Hinglish speakers do ("jaldi jaldi put the phone ...")
    "jaldi": "fast", "jaldi-jaldi": "fast", "dheere": "slow", "dheere-dheere": "slow", "dhire": "slow",
}
"""Manner adverbs -> the pace they ask for."""
PACE_PHRASES: dict[tuple[str, ...], str] = {tuple(k.split()): v for k, v in {
    "and be gentle": "gentle", "be gentle": "gentle", "and be careful": "careful", "be careful": "careful",
    "and be quick": "fast", "be quick": "fast", "and go slow": "slow",
    "take your time and": "slow", "take your time": "slow",
    "take our time and": "slow", "take our time": "slow", "in a hurry": "fast", "as fast as you can": "fast",
    "hurry up": "fast", "hurry up and": "fast", "hurry and": "fast", "in a slow way": "slow", "in slow way": "slow",
    "in a careful way": "careful",
    "as quickly as you can": "fast", "with care": "careful", "with attention": "careful",
    "with much care": "careful", "with the utmost care": "careful", "with utmost care": "careful",
    "ever so slowly": "slow", "ever so gently": "gentle", "ever so carefully": "careful",
    "careful now": "careful", "gently does it": "gentle", "easy does it": "gentle", "nice and easy": "gentle",
    "real quick": "fast",
    "real quickly": "fast", "real slow": "slow", "real slowly": "slow",
    "no rush at all": "slow", "no hurry at all": "slow",
    "no rush": "slow", "no hurry": "slow", "there's no rush": "slow", "theres no rush": "slow",
    "no need to rush": "slow", "no need to hurry": "slow",
    "taking your time": "slow", "take it slow": "slow", "don't rush": "slow", "dont rush": "slow",
    "don't hurry": "slow", "dont hurry": "slow", "without rushing": "slow", "con cuidado": "careful",
    "with precaution": "careful", "sharp sharp": "fast", "tak yer time": "slow", "tak yer time an": "slow",
    "go canny": "careful", "go canny an": "careful", "dahan-dahan lang": "slow", "dahan-dahan": "slow",
    "take ur time": "slow", "take ur time and": "slow", "take yr time": "slow", "take yr time and": "slow",
    "take yer time": "slow", "take yer time and": "slow", "take yer time an": "slow",
    "on the fly": "fast", "nice and gentle": "gentle", "nice and slow": "slow", "nice and slowly": "slow",
    "taking care": "careful", "take care": "careful", "with great care": "careful",
    # a manner's noun after "with", as learners say it ("with softness move the jar ...")
    "with softness": "gentle", "with gentleness": "gentle", "with delicacy": "gentle", "with caution": "careful",
    "with speed": "fast", "with slowness": "slow",
    "at high speed": "fast", "at full speed": "fast", "at top speed": "fast", "at low speed": "slow",
}.items()}
"""Phrases that ask for a pace as a manner adverb does ("take your time and slide A ...")."""
EDGE_PACES = {"soft": "gentle"}
"""Adjectives that ask for a pace only right after the verb or at the very end ("the soft toy" describes)."""
PACE_INTENSIFIERS = frozenset({"very", "really", "quite", "extra", "super"})
"""Words that may stand before a manner adverb and add nothing the pace can express."""
NICE_AND = ("nice", "and")

NEGATIONS = frozenset({"don't", "dont", "not", "never", "no"})
"""Words that, just before a verb, say not to do it ("don't carry it, just push A past B")."""


def starts(low: list[str], words: tuple[str, ...]) -> bool:
    return tuple(low[: len(words)]) == words


def by_word(table: tuple[tuple[str, ...], ...], at: int) -> dict[str, tuple[tuple[str, ...], ...]]:
    """The table's entries by their word at ``at`` (0: the first, -1: the last), each list in the table's order: only
    those can match where a command starts or ends with that word (the first match is the one taken)."""
    out: dict[str, list[tuple[str, ...]]] = {}
    for entry in table:
        out.setdefault(entry[at], []).append(entry)
    return {k: tuple(v) for k, v in out.items()}


_PREFIXES_BY_FIRST = by_word(POLITE_PREFIXES, 0)
_PACES_BY_FIRST = by_word(tuple(PACE_PHRASES), 0)
_SUFFIXES_BY_LAST = by_word(POLITE_SUFFIXES, -1)


def strip_polite(words: list[str], keep: frozenset[str] = frozenset()) -> list[str]:
    """``words`` without the politeness around the command; a word in ``keep`` (an object's name) stays."""
    changed = True
    while changed and words:
        changed = False
        low = [w.lower() for w in words]
        if len(low) > 2 and low[0] in STEP_LABELS and words[0] not in keep and number_of(low[1]) is not None:
            words, changed = words[2:], True  # "Step 1: move 7 ...": the step's number names no object
            continue
        for pre in _PREFIXES_BY_FIRST.get(low[0], ()):
            if starts(low, pre) and (not set(words[: len(pre)]) & keep or set(pre) & ADDRESSEES) and not (
                    pre[-1] in NOT_BEFORE_TO and low[len(pre):len(pre) + 1] == ["to"]):
                words, changed = words[len(pre):], True
                break
        low = [w.lower() for w in words]
        for suf in _SUFFIXES_BY_LAST.get(low[-1], ()) if low else ():
            if len(low) > len(suf) and tuple(low[-len(suf):]) == suf and not set(words[-len(suf):]) & keep and not (
                    len(suf) == 1 and (low[-2] in NOUN_OPENERS or _numbers_name(low[-2], suf[0], keep))):
                words, changed = words[: -len(suf)], True
                break
    return words


NOUN_OPENERS = frozenset({"the", "a", "an", "this", "that", "my", "your", "our", "his", "her", "little", "big", "small",
                          "tiny", "wee", "old", "young"})
"""Words a noun follows: a sign-off word after one is the noun it names ("away from the little dude", "next to the
chef"), never read past as the courtesy it is after a command ("next to B, dude")."""
def _numbers_name(stem: str, word: str, names: frozenset[str]) -> bool:
    """Whether ``word`` is a number as speech-to-text hears it that, after ``stem``, names an object ("closer to cube
    too" for Cube (2)): then no courtesy ("too") to read past."""
    n = HEARD_NUMBERS.get(word)
    return n is not None and any(name_parts(name) == (stem, str(n)) for name in names)


STEP_LABELS = frozenset({"step", "test", "task", "stage", "phase", "trial", "case", "instruction", "command",
                         "exercise", "example", "scenario"})
"""Words that number a step before its instruction ("Step 1: move 7 ...", "Test 4: lift 5 ..."): the label and its
number are read past, whatever the scene's objects are called ("1" may name a block; "Step 1" never does)."""


_COURTESIES_BY_FIRST = by_word(POLITE_PREFIXES + POLITE_SUFFIXES, 0)


def is_courtesy(words: list[str]) -> bool:
    """Whether ``words`` are politeness alone ("Thank you!", "Cheers", "Hello"): a sentence of its own between
    commands that asks for nothing."""
    low = [w.lower() for w in words]
    if low[:2] == ["thank", "you"] or low[:1] == ["thanks"]:
        return True  # "Thank you for the help before.", "Thank you ever so much."
    if {"again", "twice"} & set(low) and {"do", "repeat", "same", "that", "it"} & set(low):
        return False  # "Then do that again" asks for the move once more: never read past
    while low:
        for pre in _COURTESIES_BY_FIRST.get(low[0], ()):
            if starts(low, pre):
                low = low[len(pre):]
                break
        else:
            return False
    return bool(words)


def skip_to_verb(words: list[str], verbs: list[str], keep: frozenset[str] = frozenset()) -> list[str]:
    """The words from the first known verb on, when what comes before it is not the command's own (:func:`_own_words`)
    and the verb is not negated: "Sorry to bother you, but could you drag B past C", "Your task is to push ...",
    "Don't carry it, just push A past B". ``verbs`` are the verbs' first words."""
    low = [w.lower() for w in words]
    if not low or low[0] in verbs:
        return words
    told = low[0] in STATEMENT_OPENINGS or low[0] in {"this", "that", "here", "it"} and low[1:2] == ["is"]
    for i, w in enumerate(low):
        if _own_words(words[:i], keep, told):
            return words
        noun = i + 1 < len(low) and low[i + 1] in NOUN_USE  # "your next move is to lift ..."
        if w in verbs and not noun and not (set(low[max(0, i - 2):i]) & NEGATIONS
                                            and "just" not in low[max(0, i - 1):i]):
            # "Without dragging it, move A ...", "With much care, lift A ...": the words before ask for a carry or
            # a pace, which reading past would lose
            before = {x.strip(",.:;!?") for x in low[:i]}
            kept = _not_dragged(low[:i]) or before & SKIP_NEVER or (before & FAR_BEFORE and before <= FAR_BEFORE | {
                "a", "just", "little", "very", "tiny"})
            return words if kept else words[i:]
    return words


SKIP_NEVER = frozenset(PACES) | {"care", "attention"}
"""Words that, before the verb, ask how to move: never read past as a preamble."""
FAR_BEFORE = frozenset({"bit", "tad", "smidge", "smidgen", "thoda", "sa", "slightly"})
"""Words of how far said alone before the verb ("Thoda sa move the pen holder towards the phone", "A bit, move ..."):
not read past as a preamble, as the extent would be lost."""


def _not_dragged(low: list[str]) -> bool:
    """Whether ``low`` says "without dragging" or "without sliding" (chain/apart.py reads it as a carry)."""
    return any(w == "without" and low[i + 1:i + 2] in (["dragging"], ["sliding"]) for i, w in enumerate(low))


def _own_words(before: list[str], keep: frozenset[str], told: bool) -> bool:
    """Whether words before the verb belong to the command: an object's name or a description ("the other one, put it
    ...": a topic; but "yeah that one", and a noun in a sentence that tells about the command, "this is the important
    part"), or an arrow ("b->g fast, nudge E past F": a command of its own)."""
    said = {x.strip(",.:;!?") for x in before}
    lowered = {x.lower() for x in said}
    if said & keep or any(a in x for x in said for a in ("->", "=>", "\u2192")):
        return True
    nouns = lowered & (NOUNS | {n + "s" for n in NOUNS} | GROUP_COUNTS)  # "the two at the front, move the one ..."
    return bool(nouns) and not told and not (nouns == {"one"} and {"that", "this"} & lowered)


GROUP_COUNTS = frozenset({"two", "three", "four", "both"})
"""Counts that, before the verb, say a group the command picks from ("Of the two at the front, move the one on the
left ..."): the command's own words, never read past."""


STATEMENT_OPENINGS = frozenset({"this's", "that's", "here's", "it's", "thats", "heres"})
"""Openings of a sentence about the command, not about an object ("that's the plan, now move ..."): read past."""
NOUN_USE = frozenset({"is", "was", "will", "should", "would", "must"})
"""Words after which a verb's word is a noun ("your next move is to lift A ...")."""


def gerund_to_verb(words: list[str], verbs: list[str]) -> list[str]:
    """"would you mind moving A past B" -> "move A past B" (the -ing form of a known verb)."""
    low = [w.lower() for w in words]
    for pre in GERUND_PREFIXES:
        if starts(low, pre) and len(words) > len(pre):
            verb = verb_of_gerund(low[len(pre)], verbs)
            if verb is not None:  # "... lifting A and placing it next to B": both verbs as commands
                rest = words[len(pre) + 1:]
                return [verb, *(verb_of_gerund(w.lower(), verbs) or w if k and rest[k - 1].lower() == "and" else w
                                for k, w in enumerate(rest))]
    return words


def verb_of_gerund(word: str, verbs: list[str]) -> str | None:
    """The known one-word verb whose -ing form ``word`` is ("moving": move, "dragging": drag), or None."""
    return next((v for v in verbs if " " not in v and word in (v + "ing", v[:-1] + "ing", v + v[-1] + "ing")), None)


def by_gerund(words: list[str], verbs: list[str]) -> list[str]:
    """"move C toward A by pushing it" -> "push C toward A": a closing "by" + the -ing form of a known verb names
    the manner; the sentence's own verb is then replaced."""
    low = [w.lower() for w in words]
    for tail in (2, 3):
        if len(low) <= tail + 1 or low[-tail] != "by" or (tail == 3 and low[-1] not in ("it", "them")):
            continue
        verb = verb_of_gerund(low[-tail + 1], verbs)
        if verb is not None:
            return [verb, *words[1:-tail]]
    return words


NOT_A_PACE_AFTER = frozenset({"favor", "favour", "question", "request", "thing", "note", "check", "one"})
"""Nouns after which a pace word asks for no pace: "Quick favor - can you ...", "quick question"."""


def take_pace(words: list[str], keep: frozenset[str] = frozenset()) -> tuple[list[str], str | None]:
    """``words`` without their manner adverbs, and the one pace they ask for (None: none asked).
    Two different paces ("slowly and quickly") are a one-line error: the arm cannot do both."""
    out: list[str] = []
    paces: list[str] = []
    i = 0
    low = [w.lower() for w in words]
    while i < len(words):
        w = low[i]
        phrase = next((k for k in _PACES_BY_FIRST.get(w, ()) if tuple(low[i:i + len(k)]) == k), None)
        if phrase is not None and not set(words[i:i + len(phrase)]) & keep:
            paces.append(PACE_PHRASES[phrase])
            i += len(phrase)
            if out and out[-1].lower() == "and" and i >= len(words):  # "push A past B, and take your time"
                out.pop()
            continue
        if words[i] not in keep and w in EDGE_PACES and i in (1, len(words) - 1):
            paces.append(EDGE_PACES[w])  # "Push soft the duck ...", "... toward the pot, soft"
            i += 1
            continue
        if words[i] not in keep and w in PACES and not (i + 1 < len(low) and low[i + 1] in NOT_A_PACE_AFTER):
            paces.append(PACES[w])
            while out and out[-1].lower() in PACE_INTENSIFIERS:
                out.pop()
            if tuple(x.lower() for x in out[-2:]) == NICE_AND:
                del out[-2:]
            if out and out[-1].lower() in ("and", "but") and (paces[:-1] or i + 1 >= len(words)):
                out.pop()  # "... toward the tile, but slowly"
            i += 1
            continue
        out.append(words[i])
        i += 1
    distinct = sorted(set(paces))
    if len(distinct) > 1:
        said = " and ".join(w for w in low if w in PACES)
        raise LanguageError(f'"{said}" asks for {len(distinct)} different paces ({", ".join(distinct)}); '
                            "say one of them")
    return out, (distinct[0] if distinct else None)


def drop_frames(before: list[str]) -> list[str]:
    """The mover's words without the framing that follows them ("A so that it is" -> "A")."""
    low = [w.lower() for w in before]
    for f in FRAMES:
        n = len(f)
        said = low[:-n - 1] if len(low) > n + 1 and low[-n - 1] in ("very", "far") else low[:-n]  # "at the very back"
        if len(low) > n and tuple(low[-n:]) == f and said[-2:] not in (["at", "the"], ["in", "the"]) \
                and low[-n - 1] not in ("farthest", "furthest", "most"):
            return drop_frames(before[:-n])  # "the cube at the back", "farthest back": a place, not a frame
    return before
