"""Asking, at the terminal, which object a word means: what ``perform`` and ``plan`` do where a sentence calls an
object by a word the scene does not know ("move the tin next to the lime" on a bar whose shaker is called "shaker").

People call things by their own words (a bartender's "tin" is the shaker), and no table of words can hold everyone's.
The person who typed the word can say at once which object it is: the command asks, reads the sentence again with
that word given to the object (its ``kind``, each of whose words calls it: docs/perform.md), and, once the sentence
reads, offers to keep the words in the scene file, so that the next sentence reads them without asking. Nothing is
written without a yes; the run itself records the scene as read, words included (plan.json's ``scene``).
"""

from __future__ import annotations

import json
import sys
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

import click

from ..core.atomic import atomic_file
from ..errors import L2PError, LanguageError, SceneError, UnknownObjectError
from .common import mesh_dirs

if TYPE_CHECKING:
    from ..core.scene import Scene

MAX_ASKED = 5
"""Most words asked for one sentence: a sentence with more words no object has is refused as it stands."""
MAX_DESCRIPTION = 4
"""Most words of a description asked about ("the tin", "her majesty", "the little metal cup"): a longer one is mostly
a sentence read wrong ("a hook by accident when they reach"), and a question about its last word would puzzle. On
the 108 development corpora (tests/language, `benchmarks/bench_asked.py --longest N`), each word more let in asks
about more lines for fewer readings: up to 3 words 626 lines asked, 294 then read right; the 4th word 188 more, 34
right (18 %); the 5th 141 more, 11 (8 %); any length 623 more than 4, 37 (6 %). Four keeps the words that help at
least one question in six (docs/language.md)."""

Prompt = Callable[..., str]
Confirm = Callable[..., bool]


def asking_by_default(as_json: bool) -> bool:
    """Ask only a person: stdin and stderr at a terminal, and not ``--json`` (a script reads the refusal there)."""
    return not as_json and all(s is not None and s.isatty() for s in (sys.stdin, sys.stderr))


ask_option = click.option(
    "--ask/--no-ask", default=None,
    help="Where the sentence calls an object by a word the scene does not know, ask which object it is, and offer to "
         "keep the word in the scene file (default: ask at a terminal, never with --json).")
"""``perform``'s and ``plan``'s option: whether to ask (None: :func:`asking_by_default`)."""


def scene_asked(sentence: str, scene: Scene, scene_path: str | None, ask: bool | None, as_json: bool) -> Scene:
    """The scene a command reads ``sentence`` on: ``scene`` itself, or, where it asks (``ask``, or by default at a
    terminal), with the words the person gave for objects, which are then offered for the file ``scene_path``."""
    if not (asking_by_default(as_json) if ask is None else ask):
        return scene
    from ..plugins import registry

    scene, taught = ask_words(sentence, scene, registry.discover())
    if taught and scene_path is not None:
        keep_words(scene_path, taught)
    return scene


def with_word(scene: Scene, name: str, word: str) -> Scene:
    """``scene`` with ``word`` added to the ``kind`` of the object ``name`` (a kind it had is kept: "toy cow tin")."""
    objects = [replace(o, kind=_kind_with(o.kind, word)) if o.name == name else o for o in scene.objects]
    return type(scene)(objects, scene.table, scene.workspace)


def _kind_with(kind: str | None, word: str) -> str:
    return f"{kind} {word}" if kind and word not in kind.lower().split() else kind or word


def ask_words(sentence: str, scene: Scene, plugins: list, *, prompt: Prompt = click.prompt,
              confirm: Confirm = click.confirm) -> tuple[Scene, dict[str, str]]:
    """``scene`` with the words the person said for the objects the sentence calls by unknown words, and those words
    (word -> object). A refusal for anything else, or a word that cannot be a kind, is left for ``perform`` to
    report; Enter instead of a name refuses the sentence with the reason it was refused for. Where a word was
    answered, the sentence as then read is shown and goes on only on a yes: an answer can bring to light a word
    read wrong beside it ("the crisps next to the pad", "pad" read as the napkin where its author meant the game
    pad), which a refusal had hidden."""
    from ..chain.clauses import resolve_clauses

    taught: dict[str, str] = {}
    while True:
        try:
            clauses = resolve_clauses(sentence, scene, plugins)
        except UnknownObjectError as e:
            word = word_to_ask(e, scene, taught)
            if not word:
                raise
            click.echo(_reason(e), err=True)  # the word is asked for, not taught
            name = _which(word, scene, prompt)
            if name is None:
                raise
            scene = with_word(scene, name, word)
            taught[word] = name
            continue
        except L2PError:  # refused for another reason: the command reads it again and says why
            return scene, taught
        if taught and not confirm(f"Read with your words as: {read_as(clauses)}. Go on?", default=True, err=True):
            raise LanguageError(f'stopped: "{sentence}" read as {read_as(clauses)} is not what was meant; nothing '
                                "was performed or written")
        return scene, taught


def word_to_ask(e: UnknownObjectError, scene: Scene, taught: dict[str, str], longest: int = MAX_DESCRIPTION) -> str:
    """The word of ``e``'s description to ask about, or "" for none: its own word (``e.word``, "tin" of "the tin"), or,
    where that word was answered already and the description still names nothing ("the tablet strip" once "strip"
    calls the blister pack), its last word before it that no object is called by ("tablet"). Never a word a name was
    suggested for instead (``e.word`` empty), one a kind cannot hold, past :data:`MAX_ASKED` words, or in a
    description longer than ``longest`` words (:data:`MAX_DESCRIPTION`; benchmarks/bench_asked.py tries others)."""
    if not e.word or len(taught) >= MAX_ASKED or len(e.name.split()) > longest:
        return ""
    if e.word not in taught:
        return e.word if fits_a_kind(e.word) else ""
    from ..language.naming import naming_words
    from ..language.reference_words import DETERMINERS

    known = naming_words(scene) | DETERMINERS | set(taught)
    return next((w for w in reversed(e.name.lower().split()) if len(w) >= 3 and w not in known and fits_a_kind(w)),
                "")


def read_as(clauses: list) -> str:
    """The clauses as read, one line: "slide shaker next-to lime; row of lime, bottle, jigger" (manner, mover, action,
    anchors, and pace and extent where said): what a person checks before an answer of theirs is performed."""
    items: list[str] = []
    for c in clauses:
        group = getattr(c, "group", None)
        if group is not None:
            item = f"{group.action} of {', '.join(group.objects)}"
            if not items or items[-1] != item:
                items.append(item)
            continue
        cmd = c.command
        said = [f"{cmd.manner} {cmd.mover} {cmd.action} {' and '.join(cmd.anchors)}",
                *(f"{f}={getattr(cmd, f)}" for f in ("pace", "extent") if getattr(cmd, f, None))]
        items.append(" ".join(said))
    return "; ".join(items)


def _reason(e: L2PError) -> str:
    """A refusal without its hint on giving an object a word of one's own (the words are asked for here instead)."""
    from ..language.descriptions import OWN_WORD_HINT

    return str(e).split(OWN_WORD_HINT)[0]


def fits_a_kind(word: str) -> bool:
    """Whether ``word`` may stand in a scene file's ``kind`` (words of letters: "tin", not "thing2" or "SM58")."""
    from ..core.scene import KIND, MAX_NAME

    return bool(KIND.match(word)) and len(word) <= MAX_NAME


def _which(word: str, scene: Scene, prompt: Prompt) -> str | None:
    """The object the person names for ``word``: by its name (any case) or as a sentence describes one ("the green
    one", "the tall can"); None for Enter. A description that fits none or several is asked again, with why."""
    from ..language.references import resolve_object

    names = scene.names
    by_lower = {n.lower(): n for n in names}
    while True:
        said = prompt(f'Which object is "{word}"? ({", ".join(names)}, or say it as you would, "the green one"; '
                      "Enter to stop)", default="", show_default=False, err=True).strip()
        if not said:
            return None
        if said.lower() in by_lower:
            return by_lower[said.lower()]
        try:
            return resolve_object(said, scene)
        except L2PError as e:
            click.echo(f"{_reason(e)} Say one of: {', '.join(names)}", err=True)


def keep_words(scene_path: str, taught: dict[str, str], confirm: Confirm = click.confirm) -> bool:
    """Offer to add ``taught`` to the objects' kinds in the scene file; written (whole, then moved into place) only
    on a yes, and only where the file still reads as a scene with those objects. Whether it was written."""
    from ..core.scene import load_scene

    said = ", ".join(f'"{w}" for {n}' for w, n in taught.items())
    if not confirm(f"Keep {said} in {scene_path} (each object's \"kind\"), so the next sentence reads them?",
                   default=False, err=True):
        return False
    path = Path(scene_path).resolve()  # a link to the scene file stays a link: the file it names is rewritten
    try:
        raw = json.loads(path.read_text(encoding="utf-8"))
        objects = {o["name"]: o for o in raw["objects"]}
        for word, name in taught.items():
            objects[name]["kind"] = _kind_with(objects[name].get("kind"), word)
        with atomic_file(path, suffix=".json") as f:  # replaced only where the block ends without an error
            f.write((json.dumps(raw, indent=2, ensure_ascii=False) + "\n").encode("utf-8"))
            f.flush()
            load_scene(f.name, mesh_dirs())  # it must read back as a scene (a kind too long is refused here)
    except (OSError, ValueError, KeyError, TypeError, SceneError) as e:
        click.echo(f"not kept: {path} could not be written as a scene with these words ({e})", err=True)
        return False
    click.echo(f"kept in {path}", err=True)
    return True
