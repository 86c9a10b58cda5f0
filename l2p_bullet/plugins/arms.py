"""Arms as plugins: every arm, the built-in Panda included, is an entry point of the group ``l2p_bullet.arms``
whose value names an :class:`~l2p_bullet.arms.ArmSpec` (``module:ATTRIBUTE``), found by the one plugin finder
(plugins/finder.py).

An arm module holds data only (numpy at most), so loading every arm to list them costs milliseconds and runs
no simulator. A broken arm plugin (its import fails, it names no ArmSpec of its own name, its fields disagree,
it takes a built-in's name) is *reported* with its package and reason and the others keep working; an
unknown name is a one-line :class:`~l2p_bullet.errors.UnknownArmError` with a suggestion.
"""

from __future__ import annotations

from dataclasses import replace

from ..arms import ArmSpec, problems
from ..errors import FailedToLoadPlugin, UnknownArmError
from . import finder
from .finder import Plugin

GROUP = finder.GROUPS["arm"]
DEFAULT = "panda"


def _checked(plugin: Plugin) -> Plugin:
    """``plugin`` loaded: its ArmSpec in ``obj``, or the reason it cannot be used in ``error``."""
    try:
        spec = finder.load(plugin)
    except FailedToLoadPlugin as e:
        return replace(plugin, error=e.reason)
    if not isinstance(spec, ArmSpec) or spec.name != plugin.name:
        return replace(
            plugin, error=f'{plugin.entry_point} must be an l2p_bullet.arms.ArmSpec named "{plugin.name}"'
        )
    return replace(plugin, obj=spec, error=problems(spec))


def discover() -> list[Plugin]:
    """Every installed arm plugin, usable or not, sorted by name (the built-in first among equal names); each
    arm's module is imported (data only). A usable one's ArmSpec is its ``obj``."""
    found = finder.settle(_checked(p) for p in finder.find("arm"))
    return sorted(found, key=lambda a: (a.name, not a.builtin, a.package))


def names() -> list[str]:
    """The usable arms' names."""
    return [a.name for a in discover() if a.ok]


def get(name: str | ArmSpec | None = None) -> ArmSpec:
    """The arm called ``name`` (None: the default, the Panda); an ArmSpec is returned as it is."""
    if isinstance(name, ArmSpec):
        return name
    name = DEFAULT if name is None else name
    found = discover()
    matches = [a for a in found if finder.name_key(a.name) == finder.name_key(name)]
    if not matches:
        raise UnknownArmError(name, [a.name for a in found])
    usable = [a for a in matches if a.ok]
    if not usable:
        a = matches[0]
        raise FailedToLoadPlugin(a.name, a.package, a.error or "broken", kind="arm")
    return usable[0].obj  # settle() leaves one usable arm per name
