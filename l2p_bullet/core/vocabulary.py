"""The action vocabulary: canonical action names, the names the data uses for them, and how names and
phrases are normalised. One place, so that "next_to", "Next-To" and "SlideNext" mean the same action
in the CLI, the registry, the demonstrations and the graded data.
"""

from __future__ import annotations

import functools
import re

from ..actions import BUILTIN
from ..errors import UnknownActionError

ACTIONS: tuple[str, ...] = tuple(BUILTIN)
"""Canonical names of the built-in actions, in the order used by every table (closer, away, next-to,
past, around: ``l2p_bullet.actions.BUILTIN``, each declared in its own module)."""

SOURCE_NAMES: dict[str, str] = {a: spec.source_name for a, spec in BUILTIN.items()}
"""What the original study's data calls each built-in action (capture files, graded folders)."""

GRADED_FOLDERS: dict[str, str] = {**{src: a for a, src in SOURCE_NAMES.items()},
                                  **{f: a for a, spec in BUILTIN.items() for f in spec.graded_folders}}
"""Folder of the graded 2-D demonstrations -> the action it shows (the discrete planner's around too)."""

PLUGIN_ACTION = re.compile(r"^[a-z][a-z0-9]*(-[a-z0-9]+)*$")
"""What an action's name looks like ("left-of"); see ``l2p-bullet new-action``."""


def normalize_name(name: str) -> str:
    """An action name as compared everywhere: lower case, ``_`` read as ``-``."""
    return name.strip().lower().replace("_", "-")


@functools.lru_cache(maxsize=4096)
def normalize_phrase(phrase: str) -> str:
    """A phrase as compared everywhere: lower case, single spaces. Kept by the phrase: reading one sentence
    normalises the installed phrases thousands of times (every phrase table is built anew from the plugins)."""
    return " ".join(phrase.lower().split())


def canonical_action(name: str) -> str:
    """Map 'around', 'SlideAround' or 'next_to' to a built-in's canonical name; UnknownActionError otherwise."""
    key = normalize_name(name)
    for canon, src in SOURCE_NAMES.items():
        if key in (canon, src.lower()):
            return canon
    raise UnknownActionError(name, ACTIONS)


def action_for_files(name: str) -> str:
    """A built-in action's canonical name, else a plugin action's own name.

    Only for demonstrations given as files: a plugin author trains a new action on their own sessions;
    the shipped data only has the built-in actions.
    """
    try:
        return canonical_action(name)
    except UnknownActionError:
        if PLUGIN_ACTION.match(name):
            return name
        raise
