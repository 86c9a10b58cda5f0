"""A chain sentence -> its clauses, each resolved to a :class:`~l2p_bullet.language.Command` up front.

"move A next to B, then slide C past A and then move D around B" is three clauses, joined by ``, then``,
``and then``, ``then``, ``after that`` or ``;``. A clause without a verb repeats the previous clause's
verb ("move A around B, then next to C"); one that starts with the preposition repeats its mover too.
Every clause is resolved against the scene before anything is planned or moved, so a typo, an unknown
colour or a block that is not in the scene in clause 3 costs milliseconds and names the clause.
"""

from __future__ import annotations

import re
from dataclasses import replace

from ..core.scene import COLORS, Scene
from ..errors import L2PError, LanguageError
from ..language import (
    MAX_SENTENCE,
    Command,
    Context,
    dangling_join,
    known_verbs,
    strip_polite,
    trailing_join,
    typos,
    verb_heads,
)
from ..language.dictated import numbers_said
from ..language.emoji import emoji_said
from ..language.learners import in_plain_english
from ..language.naming import naming_words
from ..language.numbers import codes_said
from ..language.synonyms import kind_groups
from ..pipeline import resolve
from ..plugins import once, registry
from . import apart, corrections, pointing, rephrased
from .clause import MAX_CLAUSES, Clause, named
from .completion import checks_the_steps, complete, said_again, to_the_anchor
from .composite import composite_clauses, is_composite
from .context import context_after, context_of, two_moved
from .groups import group_first, ordinals, refuse_for_the_topic
from .last_tries import read_past
from .splitting import _item_by_item, _pieces, _rows_after_commas, split_clauses, unaddressed


def is_chain(sentence: str, plugins: list | None = None) -> bool:
    """More than one clause, or a composite action's sentence ("make a row of A, B and C", whose clauses
    its recipe makes: chain/composite.py): performed as a chain of its clauses, where a lone clause is
    performed and written as a one-clause run (:func:`one_clause`)."""
    return len(split_clauses(sentence)) > 1 or is_composite(sentence, plugins)


ASIDE = re.compile(r"\s*\([^()0-9]*\)")
"""Words in brackets without a number: an aside ("the object behind the cylinder (larger x)"), read past in a
sentence refused as written; a bracket with a number may carry a distance, which must still be refused."""


def resolve_clauses(sentence: str, scene: Scene, plugins: list) -> list[Clause]:
    """:func:`read_clauses`; where the sentence is refused as written, read again with its typing slips mended
    (language/typos.py: "mvoe teh red cube") and its asides in brackets read past (:data:`ASIDE`); the first
    refusal stands where the mended sentence is refused too or there is nothing to mend, and where the lenient
    reading (language/lenient.py), tried last, refuses both. The installed plugins are read once for the sentence
    (plugins/once.py)."""
    with once.read_once():
        return _resolve_clauses(sentence, scene, plugins)


def _resolve_clauses(sentence: str, scene: Scene, plugins: list) -> list[Clause]:
    def known() -> frozenset[str]:  # every word the toolkit reads in this scene (made only where a reading needs it)
        shades = tuple(sorted({o.shade for o in scene.objects if o.shade}))  # "the mauve block" is never "move"
        return typos.vocabulary(registry.phrase_table(plugins), known_verbs(), (*COLORS, *shades)) | naming_words(scene)

    if isinstance(sentence, str):
        # "the red two by four" for brick_2x4_red, before "by" is read; "four twelve" for S-0412; "🔑 ➡️ 👛"
        sentence = rephrased.passed_by(numbers_said(codes_said(emoji_said(sentence, scene), scene), scene))
        sentence = unaddressed(sentence, "robot" in naming_words(scene))  # "Robot, take the smallest block and ..."
        if typos.RUNS.search(sentence.lower()):  # "slowwwly": the pace, not a word read past
            sentence = typos.squeezed(sentence, known())
    try:
        return read_clauses(sentence, scene, plugins)
    except L2PError:
        if not isinstance(sentence, str) or len(sentence) > MAX_SENTENCE * MAX_CLAUSES:
            raise
        words = known()
        mended = typos.mend(in_plain_english(ASIDE.sub("", sentence), scene), words, scene.names, verb_heads(),
                            kind_groups(scene))
        if mended != sentence:
            try:
                return read_clauses(mended, scene, plugins)
            except L2PError:
                pass
        read = read_past(sentence, mended, scene, plugins, words, read_clauses)
        if read is None:
            raise
        return read


def read_clauses(sentence: str, scene: Scene, plugins: list) -> list[Clause]:
    """Every clause parsed against ``scene`` and the installed phrases; the first problem raised as a
    one-line error of its own type (LanguageError, UnknownObjectError...) that names the clause.

    A sentence of one clause is the chain of that one clause, resolved whole as ``perform`` always resolved
    it (its own words, its own errors: nothing to name a clause by); a composite's sentence is its steps. In a
    longer chain a composite may stand anywhere ("make a row of A, B and C, then move D next to C"), also after a
    comma ("move S next to P, line up the can, the tray and the teddy, then ...")."""
    texts = _rows_after_commas(split_clauses(sentence), plugins)
    if len(texts) <= 1:
        listed = texts[0] if texts and _item_by_item(sentence) is not None else sentence  # told item by item
        made = composite_clauses(listed, scene, plugins)
        if made is not None:
            return made
        try:
            command = resolve(sentence, scene, plugins)
            if isinstance(sentence, str):
                _one_command(sentence, command, scene, plugins)
            return [Clause(1, texts[0] if texts else str(sentence), command)]
        except L2PError:
            if texts and len(_pieces(sentence)) > 1:  # "Hello! Move A past B. Thanks.": the command alone
                try:
                    return [Clause(1, texts[0], resolve(texts[0], scene, plugins))]
                except L2PError:
                    pass
            text = texts[0] if texts else str(sentence)
            pieces = _other_readings(text, None, scene, plugins)
            if pieces is None:
                refuse_for_the_topic(text, scene, None, plugins)
                raise
            pieces = _set_down(pieces, None, None)  # "beside the... the colander, yes, beside the colander": once
            pieces = [p for k, p in enumerate(pieces) if k == 0 or not said_again(p[0], p[1], pieces[k - 1][1], scene)]
            return apart.wishes_done([Clause(k, piece, cmd) for k, (piece, cmd) in enumerate(pieces, start=1)], scene,
                                     str(sentence))
    said = trailing_join(sentence.rstrip(" .!?,").split())
    if said is not None:  # "move A around B, then move C past A, then": the splitter drops the empty clause
        raise dangling_join(said)
    if len(texts) > MAX_CLAUSES:
        raise LanguageError(f"the chain has {len(texts)} clauses; a chain has at most {MAX_CLAUSES}")
    clauses: list[Clause] = []
    pending: str | None = None  # a pace said alone before its clause ("Hurry!! Slide A ...")
    show: pointing.Shown | None = None  # objects the clause before showed without a command ("See E?")
    pair: pointing.Shown | None = None  # the last two objects shown, for "the other one" later on
    for i, text in enumerate(texts, start=1):
        if len(text) > MAX_SENTENCE:
            raise LanguageError(f'clause {i} is {len(text)} characters long; a clause has at most {MAX_SENTENCE}')
        made = composite_clauses(text, scene, plugins)
        if made is not None:  # a composite's steps, numbered on from the clauses before it
            clauses.extend(replace(c, index=len(clauses) + 1) for c in made)
            show = None
            continue
        previous = clauses[-1].command if clauses else None
        context = show.context if show is not None else (context_after(previous, pair) if previous else None)
        said = ordinals(text, show)
        try:
            pieces = [(text if piece == said else piece, cmd)
                      for piece, cmd in _in_order(said, i < len(texts), previous, scene, plugins, context, pair)]
        except L2PError as e:
            instead = corrections.instead_of(text) if clauses and not show else None
            meant = instead or (corrections.taken_back(text) if clauses and not show else None)
            if meant is not None:  # "Actually no, move it past the jar instead.", "no wait, closer to the jello."
                again = _in_place_of(meant, clauses[-1], scene, plugins, pair)
                if again is not None:
                    clauses[-1:] = again
                    continue
                if instead is not None:  # said as a correction for sure: its own refusal, not another reading
                    raise named(e, f'clause {i} ("{text}")') from None
            extent = apart.extent_alone(text) if clauses else None
            if extent is not None:  # "Move the tin away from the mug. Just a tiny bit though."
                clauses[-1] = apart.extended(clauses[-1], extent, plugins)
                continue
            pace = apart.pace_alone(text, scene)
            if pace is not None and (i < len(texts) or clauses):  # "Hurry!! Slide A ...", "... B. Slowly please."
                if i < len(texts):
                    pending = pace
                else:
                    clauses[-1] = apart.paced(clauses[-1], pace)
                continue
            if (i < len(texts) and pointing.about_us(text, scene)) or pointing.asks_nothing(text, scene,
                                                                                             known_verbs()):
                continue  # "We're setting up for the demo.", "Here's the situation.", "Would you see to that?"
            placed = _placed(text, show, scene, plugins)
            if placed is not None:  # "Plate. Away from the lemon.": the place where the object shown goes
                clauses.append(Clause(len(clauses) + 1, text, placed))
                show = None
                continue
            away = apart.away_from_shown(text, show, scene, plugins)
            if away is not None:  # "A and B are too close together. Fix that by moving A."
                clauses.extend(Clause(len(clauses) + 1, text, cmd) for cmd in away)
                show = None
                continue
            done = (apart.done_so(text, clauses[-1]) or apart.manner_after(text, clauses[-1])
                    or apart.confirmed(text, clauses[-1], scene)) if clauses else None
            if done is not None:  # "The jar needs to be next to the mug. Slide it over."
                clauses[-1] = done
                continue
            shows = pointing.shown(text, scene, context) if i < len(texts) else None
            if shows is not None:
                show = shows
                pair = shows if len(shows.objects) == 2 else pair
                continue
            raise named(e, f'clause {i} ("{text}")') from None
        pieces = _set_down(pieces, previous, show)
        if len(pieces) == 1 and pending is None and any(said_again(text, pieces[0][1], c.command, scene)
                                                        for c in reversed(clauses)):
            continue  # "... a lot closer to the rack? much closer": a clause before, said once more
        if clauses and checks_the_steps(text, [cmd for _, cmd in pieces], [c.command for c in clauses]):
            continue  # "Step 24: move Z past P2, then W next to it. Expected: Z beyond P2, W adjacent Z."
        if pending is not None:
            pieces = [(piece, apart.paced(Clause(0, piece, cmd), pending).command) for piece, cmd in pieces]
            pending = None
        show = two_moved([cmd for _, cmd in pieces])
        clauses.extend(Clause(len(clauses) + 1 + k, piece, cmd) for k, (piece, cmd) in enumerate(pieces))
    if not clauses:  # "Wonderful job, everyone! Look how tidy our sandpit is.": every part read past, none a move
        raise LanguageError(f'"{sentence}" asks for no move; say which object to move and where')
    clauses = apart.wishes_done(clauses, scene, sentence)
    if len(clauses) > MAX_CLAUSES:
        raise LanguageError(f"the chain has {len(clauses)} moves; a chain has at most {MAX_CLAUSES}")
    return clauses


def _set_down(pieces: list[tuple[str, Command]], previous: Command | None,
              show: pointing.Shown | None) -> list[tuple[str, Command]]:
    """``pieces`` with a lift shown before carried on, and "set it down ..." after a carry a carry, each piece read
    after the one before it ("carry H past F, and set it down next to C": both carried)."""
    out = []
    for piece, cmd in pieces:
        cmd = pointing.set_down(pointing.carried(cmd, show), previous, piece)
        out.append((piece, cmd))
        previous = cmd
    return out


def _in_place_of(meant: str, taken: Clause, scene: Scene, plugins: list,
                 pair: pointing.Shown | None) -> list[Clause] | None:
    """The clauses ``meant`` says in place of the clause ``taken`` back (chain/corrections.instead_of, taken_back), read
    as said after it: its verb and mover complete a place said alone, and "it" is its mover; None where it does not
    resolve."""
    try:
        pieces = _resolve_text(meant, taken.command, scene, plugins, context=context_after(taken.command, pair),
                               pair=pair)
    except L2PError:
        return None
    # "sorry, past it, past the box": the place meant, said twice, is one clause
    pieces = [p for k, p in enumerate(pieces) if k == 0 or not _same_move(p[1], pieces[k - 1][1])]
    return [Clause(taken.index + k, piece, cmd) for k, (piece, cmd) in enumerate(pieces)]


def _placed(text: str, show: pointing.Shown | None, scene: Scene, plugins: list) -> Command | None:
    """The command a place said alone makes of the one object the clause before showed ("Plate. Away from the lemon.",
    "Red apple. Much closer to the Granny."), carried where it was picked up; None where it makes none."""
    if show is None or len(show.objects) != 1 or show.about:
        return None
    try:
        command = resolve(f"{'carry' if show.lifted else 'move'} {show.objects[0]} {text}", scene, plugins,
                          show.context)
    except L2PError:
        return None
    return replace(command, sentence=text)


def _moves_it(text: str) -> bool:
    """Whether "it" is what the clause moves: right after its verb ("then move it next to the black one", "and pick it
    up ..."), only words of a verb or "then", "now", "please" before it."""
    words = re.findall(r"[a-z']+", text.lower())
    if "it" not in words:
        return False
    i = words.index("it")
    said = {w for v in known_verbs() for w in v.split() if w != "..."}  # every word of a verb ("pick", "up")
    return 0 < i <= 4 and all(w in said or w in ("then", "and", "now", "please", "just", "so") for w in words[:i])


def _one_command(text: str, command: Command, scene: Scene, plugins: list) -> None:
    """LanguageError where the words after the clause's last comma are a command of their own whose block to move the
    reading took as its reference ("shampoo away from the edge, comb beside razor": read whole, "the edge, comb" was
    the comb): two clauses, the first of which names no object."""
    head, comma, tail = text.rpartition(",")
    if not comma or len(tail.split()) < 3:
        return
    try:
        own = resolve(tail.strip(), scene, plugins)
    except L2PError:
        return
    if own.mover in command.anchors and own.mover != command.mover:
        raise LanguageError(f'"{head.strip()}" and "{tail.strip()}" read as two commands, and "{head.strip()}" '
                            "names no block on its own; say each as a command of its own")


def _same_move(a: Command, b: Command) -> bool:
    """Whether two commands ask for the same move (mover, action, anchors, manner, pace and extent)."""
    return (a.mover, a.action, a.anchors, a.manner, a.pace, a.extent) == (b.mover, b.action, b.anchors, b.manner,
                                                                       b.pace, b.extent)


def _resolve_text(text: str, previous: Command | None, scene: Scene, plugins: list, depth: int = 0,
                  context: Context | None = None, pair: pointing.Shown | None = None) -> list[tuple[str, Command]]:
    """A clause's text -> its command; where it does not read as one clause but as two joined by "and" or a
    comma ("shove D toward A and drag E around C", "put B next to the duck and A next to E"), both; else as
    one of chain/pointing.py's readings ("do the same with C", "move them both ...")."""
    context = context or context_of(previous)
    full = complete(text, previous, scene, plugins)
    try:
        command = resolve(full, scene, plugins, context)
        _one_command(text, command, scene, plugins)
        return [(text, command)]
    except L2PError:
        if previous is not None and context == context_of(previous) and re.search(r"\bit\b", text, re.IGNORECASE):
            # "move B toward C, then past it": "it" cannot be the block being moved, so it is the other one; where
            # "it" is the block moved ("put A by B, then move it away from A"), only if the other words name their
            # block without the clause before (not "then move it next to the black one": either black one)
            try:
                other = resolve(full, scene, plugins, Context(previous.anchor, previous.mover))
                if _moves_it(text):
                    resolve(re.sub(r"\bit\b", other.mover, full, count=1, flags=re.IGNORECASE), scene, plugins)
                return [(text, other)]
            except L2PError:
                pass
        pieces = _other_readings(text, previous, scene, plugins, depth, context, pair)
        if pieces is None:
            refuse_for_the_topic(text, scene, context, plugins)
            raise
        return pieces


def _other_readings(text: str, previous: Command | None, scene: Scene, plugins: list, depth: int = 0,
                    context: Context | None = None,
                    pair: pointing.Shown | None = None) -> list[tuple[str, Command]] | None:
    """A text that does not resolve as one clause read as two joined by "and" or a comma, as a group shown and
    then clauses about it, or as one of chain/pointing.py's readings; None when none applies."""
    if len(text) > MAX_SENTENCE:
        return None  # a clause too long to read: refused as it stands, at once
    for said in [rephrased.over_and_put(text), *rephrased.in_other_words(text), *corrections.corrected(text, scene)]:
        if said != text and depth < MAX_CLAUSES:
            try:
                return [(text, c) for _, c in _resolve_text(said, previous, scene, plugins, depth + 1, context, pair)]
            except L2PError:
                pass
    pieces = _split_on_and(text, previous, scene, plugins, depth, context, pair)
    dash = apart.DASH_THEN.match(text) if pieces is None and depth < MAX_CLAUSES else None
    if dash is not None:  # "Make it so the cylinder isn't so close to the cup - move the cylinder"; "... - carry it"
        after = dash.group("after")
        pieces = _told_beside(dash.group("before"), text,
                              lambda c: apart.confirmed(after, c, scene) or apart.done_so(after, c)
                              or apart.manner_after(after, c), previous, scene, plugins, depth, context, pair)
    first = apart.NOT_DRAGGED_FIRST.match(text) if pieces is None and depth < MAX_CLAUSES else None
    if first is not None:  # "Without dragging it across the table, move A ...": as "move A ..., without dragging it"
        pieces = _told_beside(first.group("rest"), text,
                              lambda c: apart.manner_after(f"without {first.group('how')} it", c),
                              previous, scene, plugins, depth, context, pair)
    if pieces is None:
        pieces = group_first(text, previous, scene, plugins, depth, context, _resolve_text)
    full = to_the_anchor(text, context, plugins) if pieces is None else None
    if full is not None:
        try:  # "The football is too close to the cup. Move it away.": away from what the clause before named
            pieces = [(text, resolve(complete(full, previous, scene, plugins), scene, plugins, context))]
        except L2PError:
            pieces = None
    if pieces is None:  # then "Push them away" after "A and B are too close to C": each away from C
        for said in dict.fromkeys(t for t in (text, full) if t is not None):
            pieces = [(text, c) for c in pointing.pointed(said, previous, context, scene, plugins) or ()] or None
            if pieces is not None:
                break
    return pieces


FIRST_SAID = re.compile(r"[\s,]+(?:first(?:\s+of\s+all)?|to\s+(?:begin|start)\s+with)[\s.!]*$", re.IGNORECASE)
"""A clause's end that says only that it comes first ("move A next to B first, then ...")."""


def _in_order(said: str, more: bool, previous: Command | None, scene: Scene, plugins: list, context: Context | None,
              pair: pointing.Shown | None) -> list[tuple[str, Command]]:
    """The pieces of a clause's text, read as said and, where that is refused and another clause follows it
    (``more``), without a "first" at its end (:data:`FIRST_SAID`), which says only the order the clauses already
    have; the refusal as said stands where that is refused too."""
    try:
        return _resolve_text(said, previous, scene, plugins, context=context, pair=pair)
    except L2PError as refused:
        plain = FIRST_SAID.sub("", said) if more else said
        if plain == said:
            raise
        try:
            return _resolve_text(plain, previous, scene, plugins, context=context, pair=pair)
        except L2PError:
            raise refused from None


def _told_beside(said: str, text: str, tell, previous: Command | None, scene: Scene, plugins: list, depth: int,
                 context: Context | None, pair: pointing.Shown | None) -> list[tuple[str, Command]] | None:
    """``said`` read as one clause, then changed by ``tell`` (a chain/apart reading of the words said beside it, given
    that clause): the one piece of ``text``, or None where ``said`` is not one clause or ``tell`` does not apply."""
    try:
        read = _resolve_text(said, previous, scene, plugins, depth + 1, context, pair)
    except L2PError:
        return None
    told = tell(Clause(1, text, read[0][1])) if len(read) == 1 else None
    return [(text, told.command)] if told is not None else None


COLOUR_LAST = re.compile(r"\b(?:" + "|".join(COLORS) + r")$", re.IGNORECASE)
COLOURED_MANY = re.compile(r"(?:" + "|".join(COLORS) + r")\s+(?:[a-z]+\s+)?[a-z]+s\b", re.IGNORECASE)
"""Two colours before one plural noun ("the red and blue blocks"): the "and" joins the colours."""
_AND_OR_COMMA = re.compile(r",\s*(?:and\s+)?|\s+and\s+", re.IGNORECASE)


def _split_on_and(text: str, previous: Command | None, scene: Scene, plugins: list, depth: int = 0,
                  context: Context | None = None,
                  pair: pointing.Shown | None = None) -> list[tuple[str, Command]] | None:
    """The first split of ``text`` at an "and" or a comma into clauses that each resolve (the later ones may
    leave out the verb, or the verb and the mover: :func:`_complete`); None when there is none. Only tried on a
    text that does not resolve as one clause, so "lift A and put it next to B" and "between B and C" stay whole."""
    if depth >= MAX_CLAUSES:
        return None
    topic = pointing.TOPIC.match(text)
    if topic is not None and pointing.group_said(
            " ".join(strip_polite(topic.group("what").split(), frozenset(scene.names))), scene) is not None:
        return None  # "the two in front, move the red one ... and the other one ...": the group's (chain/groups.py)
    context = context or context_of(previous)
    for m in _AND_OR_COMMA.finditer(text):
        left, right = text[:m.start()].strip(" ,"), text[m.end():].strip(" ,")
        if not left or not right or "," not in m.group(0) and COLOUR_LAST.search(left) and COLOURED_MANY.match(right):
            continue  # "by the red and blue blocks": one group of two colours, not two clauses
        first = _first_said(left, previous, scene, plugins, context)
        if first is None:
            continue
        try:
            rest = _resolve_text(right, first, scene, plugins, depth + 1, context_after(first, pair), pair)
        except L2PError:
            continue
        then = rest[0][1]
        if (then.mover, then.anchors) == (first.mover, first.anchors) and then.action != first.action:
            continue  # "closer to the mug and away from the mug": two ends at once, not two steps
        return [(left, first), *rest]
    return None


def _first_said(text: str, previous: Command | None, scene: Scene, plugins: list,
                context: Context | None) -> Command | None:
    """The first clause of a split: ``text`` as it stands, else said the usual way (chain/rephrased.py: "b->g fast,
    nudge E past F"); None where neither resolves."""
    for said in (text, *rephrased.in_other_words(text)):
        try:
            return resolve(complete(said, previous, scene, plugins), scene, plugins, context)
        except L2PError:
            continue
    return None


def one_clause(clauses: list[Clause]) -> bool:
    """Whether ``clauses`` is a lone clause of a plain sentence (no composite's target): it is performed,
    planned and written as a one-clause run (the run folder's one-clause layout, DESIGN.md section 4)."""
    return len(clauses) == 1 and clauses[0].target is None
