"""One root error for everything a user can get wrong, and subclasses that carry their data.

The CLI catches :class:`L2PError` and prints its message on one line with a non-zero exit code;
anything else is a bug and keeps its traceback. Subclasses exist so that callers (and tests) can
tell failures apart without parsing messages; the ones a caller may want to act on carry the facts
as attributes (like flake8's ``FailedToLoadPlugin(name, exception)``): an unknown action is one
:class:`UnknownActionError` with ``.name`` and ``.known`` wherever it is raised.
"""

from __future__ import annotations

import difflib
import functools
from collections.abc import Iterable


class L2PError(Exception):
    """Root of every user-facing failure. The message must say what is wrong and, if possible, what to do."""

    exit_code = 2


class SceneError(L2PError):
    """A scene file or scene description is invalid (bad JSON, missing field, overlap, off the table...)."""


class UnknownObjectError(SceneError):
    """A sentence or path names an object that is not in the scene."""

    def __init__(self, message: str, name: str = "", known: Iterable[str] = (), word: str = ""):
        super().__init__(message)
        # ``word``: the word of the description a scene file's "kind" could give an object ("tin" of "the tin"), ""
        # where the refusal suggests a name instead; ``perform`` asks which object it is (commands/asking.py)
        self.name, self.known, self.word = name, tuple(known), word


class ReachError(L2PError):
    """The arm cannot reach a pose (inverse kinematics failed or a joint limit would be violated)."""


class ExecutionError(L2PError):
    """The physical execution went wrong (grasp lost, block tilted, constraint missing...)."""


class PathError(L2PError):
    """A 2-D path file is unreadable or malformed, or a path leaves the workspace."""


class MotionError(L2PError):
    """A motion cannot be scored: non-finite poses, or longer or wider than :data:`limit` block sides."""

    def __init__(self, message: str, extent_blocks: float = float("nan"), limit: float = float("nan")):
        super().__init__(message)
        self.extent_blocks, self.limit = extent_blocks, limit


class DataError(L2PError):
    """A demonstration file is missing, unreadable or malformed."""


class BundleError(L2PError):
    """An action bundle (manifest + weights) is missing, invalid, incompatible or tampered with."""


class PluginError(L2PError):
    """A plugin (an action, arm or manner) cannot be found or loaded, or two plugins claim the same phrase."""


class UnknownPluginError(PluginError):
    """No installed plugin of ``kind`` (action, arm, manner; built-in or not) has this name; ``known`` lists the
    names that do, and the message suggests the closest one."""

    def __init__(self, kind: str, name: str, known: Iterable[str], context: str = ""):
        self.kind, self.name, self.known = kind, name, tuple(sorted(known))
        key = name.strip().lower().replace("_", "-")
        super().__init__(f'unknown {kind} "{name}" (known: {", ".join(self.known) or "none"}).'
                         + did_you_mean(key, self.known) + (f" {context}" if context else ""))


class UnknownActionError(UnknownPluginError):
    """No installed action (built-in or plugin) has this name."""

    def __init__(self, name: str, known: Iterable[str], context: str = ""):
        super().__init__("action", name, known, context)


class FailedToLoadPlugin(PluginError):
    """A found plugin cannot be used: its bundle is broken, its import failed, it is not trained, it takes a
    built-in's name..."""

    def __init__(self, name: str, package: str, reason: str, kind: str = "action"):
        self.name, self.package, self.reason, self.kind = name, package, reason, kind
        super().__init__(f'{kind} plugin "{name}" (package {package}) cannot be used: {reason}')


class UnknownArmError(UnknownPluginError):
    """No installed arm (built-in or plugin, entry-point group ``l2p_bullet.arms``) has this name."""

    def __init__(self, name: str, known: Iterable[str]):
        super().__init__("arm", name, known, "List them with: l2p-bullet arms")


class PluginConflict(PluginError):
    """Two usable plugins claim the same action name or phrase (``claim``), so sentences are ambiguous."""

    def __init__(self, message: str, claim: str, plugins: Iterable[str]):
        super().__init__(message)
        self.claim, self.plugins = claim, tuple(plugins)


class LanguageError(L2PError):
    """A sentence could not be understood."""


class PlanError(L2PError):
    """The planner cannot produce a path (no collision-free move, unknown planner...)."""


class InfeasibleError(L2PError):
    """The arm cannot do what is asked in this scene, found before anything is planned or moved.

    ``check`` names the check that failed ("grasp", "boxed-in", "room-around", "far-around", "blocked-around",
    "room-away", "room-closer",
    "no-motion" (after the search: a plan that leaves the mover where it is);
    docs/perform.md says what each means), ``details`` carries its numbers.
    """

    def __init__(self, check: str, message: str, details: dict | None = None):
        super().__init__(message)
        self.check, self.details = check, dict(details or {})


class UnknownPlannerError(PlanError):
    """A planner name that does not exist; ``.known`` lists the ones that do."""

    def __init__(self, name: str, known: Iterable[str], where: str = ""):
        self.name, self.known = name, tuple(known)
        super().__init__(f'{where}unknown planner "{name}" (known: {", ".join(self.known)}).'
                         + did_you_mean(name.strip().lower(), self.known))


class TeachError(L2PError):
    """A demonstration recorded on the teach page cannot be saved, or the teach app cannot start."""


class RunFolderError(L2PError):
    """A run folder cannot be made: it exists (``state``: finished, running, foreign...) or cannot be written."""

    def __init__(self, message: str, path: object = None, state: str = ""):
        super().__init__(message)
        self.path, self.state = path, state


class ReviewError(L2PError):
    """The review app cannot use a database, a run folder or a grades file, or a request to it is wrong."""


class SchemaVersionError(ReviewError):
    """A review database with a schema this l2p-bullet does not know (``found`` > ``supported``)."""

    def __init__(self, path: str, found: int, supported: int):
        self.path, self.found, self.supported = path, found, supported
        super().__init__(f"review database {path} has schema version {found}, but this l2p-bullet knows "
                         f"versions up to {supported}: it was written by a newer l2p-bullet; upgrade to use it "
                         "(nothing was changed in it)")


class EvaluationError(L2PError):
    """An evaluation cannot start or go on: a bad scene set, a results table from another evaluation..."""


class MissingExtraError(L2PError):
    """An optional dependency is not installed; ``.package`` is what is missing, ``.extra`` the extra
    that installs it (``pip install 'l2p-bullet[<extra>]'``)."""

    def __init__(self, package: str, extra: str, purpose: str):
        self.package, self.extra = package, extra
        super().__init__(f"{purpose} needs {package}, which is not installed: pip install 'l2p-bullet[{extra}]'")


def listed(names: list[str], most: int = 3) -> str:
    """The first ``most`` names, comma-separated, and " ..." when there are more: how a message names the
    files (or plugins) it is about without printing hundreds."""
    return ", ".join(names[:most]) + (" ..." if len(names) > most else "")


def plural(n: int, noun: str) -> str:
    """``1 episode``, ``2 episodes``: counts in messages people read ("1 graded runs" before)."""
    return f"{n} {noun}{'' if n == 1 else 's'}"


def sizes(n: int, limit: int) -> tuple[str, str]:
    """A size and its limit as two texts precise enough to differ ("16.21 MiB", "16 MiB"): rounded alike,
    a file 3 % over its limit read "17 MB is more than the 17 MB"."""
    if n >= 2**20 and limit >= 2**20:
        for digits in range(0, 4):
            a, b = f"{n / 2**20:.{digits}f}", f"{limit / 2**20:.{digits}f}"
            if a != b:
                return f"{a} MiB", f"{b} MiB"
    return f"{n:,} bytes", f"{limit:,} bytes"


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """Return ' Did you mean "x"?' for the closest choice, or '' when nothing is close.

    Used by every "unknown X" error so that the suggestion reads the same everywhere.
    """
    choices = tuple(choices)
    try:
        return _closest(word, choices)
    except TypeError:  # a word or choice that cannot be kept (unhashable): asked as it is
        return _closest.__wrapped__(word, choices)


@functools.lru_cache(maxsize=1024)
def _closest(word: str, choices: tuple[str, ...]) -> str:
    """:func:`did_you_mean`, kept by the word and the choices: a sentence's readings try the same words against the
    same scene many times, and each refusal asks for its suggestion (difflib's ratios are the cost)."""
    close = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return f' Did you mean "{close[0]}"?' if close else ""


def copied(error: L2PError) -> L2PError:
    """A new exception of ``error``'s type with its arguments and attributes (not its traceback or context), made
    without calling ``__init__`` (whose parameters differ between errors): how a kept refusal is raised again,
    as reading the words anew would raise a new one."""
    copy = BaseException.__new__(type(error))
    copy.args = error.args
    copy.__dict__.update(error.__dict__)
    copy.__cause__, copy.__suppress_context__ = error.__cause__, error.__suppress_context__
    return copy
