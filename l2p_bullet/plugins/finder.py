"""The one way l2p-bullet finds its plugins, for every kind: actions (and composites), arms and manners.

A plugin is an entry point of its kind's group (:data:`GROUPS`) declared by an installed distribution; the
built-ins are the entry points of the project's own distribution, found through the same groups, so a
third-party plugin is a first-class citizen. As flake8's plugin finder, in three steps, with one record
(:class:`Plugin`) and one error (:class:`~l2p_bullet.errors.FailedToLoadPlugin`) for every kind:

- :func:`find` lists every entry point of a kind without importing anything: the built-ins first, then
  the others by name and package, so machines with the same packages read them in the same order.
- :func:`load` imports one and returns what its entry point names; a failing import (even ``sys.exit``)
  is that plugin's bug, raised as ``FailedToLoadPlugin`` naming it and its package, never the end of the
  program.
- :func:`settle` applies the one rule for names: a plugin that takes a built-in's name is broken and the
  built-in kept (a package cannot change what a plain ``perform`` does by calling itself "panda"), and
  two usable plugins of one name are both broken (picking either would make one command do different
  things on different machines). A broken plugin is listed with its reason and package; the others work.

A name no plugin of a kind has is one :class:`~l2p_bullet.errors.UnknownPluginError` (kind, name, the
names known, a did-you-mean) for every kind; ``UnknownActionError`` and ``UnknownArmError`` are its own.

What an entry point names is each kind's business: an action's bundle folder is located, not imported
(``plugins/registry.py``); an arm (``plugins/arms.py``) or a manner (``manners/registry.py``) is a small
declaration, loaded. This module imports nothing of l2p_bullet but its errors, so the lowest floor that
needs plugins (the manners' verbs, read when parsing a sentence) may use it (tests/test_layout.py).
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable
from dataclasses import dataclass, field, replace
from importlib import metadata
from typing import Any

from ..errors import FailedToLoadPlugin

GROUPS = {"action": "l2p_bullet.actions", "arm": "l2p_bullet.arms", "manner": "l2p_bullet.manners"}
"""Entry-point group of each kind (a composite action is an action whose manifest says so)."""
BUILTIN = "l2p-bullet"
"""The distribution whose entry points are the built-ins."""


def name_key(name: str) -> str:
    """How names compare: ``next_to``, ``Next-To`` and ``next-to`` are one name."""
    return name.strip().lower().replace("_", "-")


@dataclass(frozen=True)
class Plugin:
    """One found plugin of any kind. ``error`` None: usable; otherwise why not (listed by the ``actions``,
    ``arms`` and ``manners`` commands). ``obj`` is what loading it gave (an arm's ArmSpec, a manner's
    MannerSpec); None for a plugin that is only located."""

    kind: str  # "action", "composite", "arm", "manner"
    name: str  # the entry point's name: what a sentence, --arm or a verb table calls it
    package: str  # the distribution that declares it ("l2p-bullet" for a built-in)
    package_version: str
    entry_point: str  # the entry point's value, "module" or "module:ATTRIBUTE"
    error: str | None = None
    obj: Any = field(default=None, compare=False, repr=False)
    dist: Any = field(default=None, compare=False, repr=False)  # its importlib.metadata Distribution

    @property
    def ok(self) -> bool:
        return self.error is None

    @property
    def builtin(self) -> bool:
        return name_key(self.package) == BUILTIN

    @property
    def module(self) -> str:
        return self.entry_point.split(":", 1)[0].strip()

    def label(self) -> str:
        return f'"{self.name}" (package {self.package} {self.package_version})'


def entry_points(kind: str) -> list[tuple[metadata.EntryPoint, str, str]]:
    """(entry point, package, package version) of every entry point of ``kind``'s group, as installed."""
    out = []
    packages: dict[int, tuple[str, str]] = {}  # a package's METADATA parsed once, not once per entry point
    for ep in metadata.entry_points(group=GROUPS["action" if kind == "composite" else kind]):
        dist = getattr(ep, "dist", None)
        if dist is None:
            out.append((ep, "unknown package", ""))
            continue
        if id(dist) not in packages:
            meta = dist.metadata
            packages[id(dist)] = (str(meta["Name"] or "unknown package"), str(meta["Version"] or ""))
        out.append((ep, *packages[id(dist)]))
    return out


def find(kind: str) -> list[Plugin]:
    """Every installed plugin of ``kind`` (a key of :data:`GROUPS`), usable or not, importing nothing: the
    built-ins first, then by name, package and entry point."""
    found = [
        Plugin(kind, ep.name, package, version, ep.value, dist=getattr(ep, "dist", None))
        for ep, package, version in entry_points(kind)
    ]
    return sorted(found, key=lambda p: (not p.builtin, name_key(p.name), p.package, p.entry_point))


def load(plugin: Plugin, attribute: str | None = None) -> Any:
    """Import ``plugin``'s module and return what its entry point names (``module:ATTRIBUTE``; ``attribute``
    when the entry point names a module alone; the module itself when neither says). Every failure is a
    :class:`FailedToLoadPlugin` naming the plugin and its package."""
    module, _, attr = plugin.entry_point.partition(":")
    try:
        obj = importlib.import_module(module.strip())
        for part in (attr.strip() or attribute or "").split("."):
            if part:
                obj = getattr(obj, part)
    except KeyboardInterrupt:  # the person at the keyboard wants to stop: that is not the plugin's bug
        raise
    except BaseException as e:  # noqa: BLE001 - sys.exit(7) or a BaseException in a plugin's import must not
        # end the program: it is the plugin's bug, reported with its name like any other
        what = f"it called sys.exit({e.code!r})" if isinstance(e, SystemExit) else f"{type(e).__name__}: {e}"
        reason = f"importing {plugin.entry_point} failed: {what}"[:500]
        raise FailedToLoadPlugin(plugin.name, plugin.package, reason, kind=plugin.kind) from None
    return obj


def settle(plugins: Iterable[Plugin]) -> list[Plugin]:
    """``plugins`` (one group's, checked by their kind) with the one rule for names applied: a plugin that
    takes a built-in's name is broken, the built-in kept; two usable plugins of one name are both broken.
    A plugin already broken for another reason keeps that reason, and blocks no usable one."""
    plugins = list(plugins)
    builtin = {name_key(p.name): p for p in plugins if p.builtin}
    out = []
    for p in plugins:
        first = builtin.get(name_key(p.name))
        if p.ok and not p.builtin and first is not None:
            p = replace(
                p,
                error=f'the name "{p.name}" is the built-in {first.kind}\'s (package {BUILTIN}), '
                f"which a plugin cannot replace; rename its entry point or uninstall {p.package}",
            )
        out.append(p)
    by_name: dict[str, list[Plugin]] = {}
    for p in out:
        if p.ok:
            by_name.setdefault(name_key(p.name), []).append(p)
    twins = {k: g for k, g in by_name.items() if len(g) > 1}
    if not twins:
        return out

    def both(p: Plugin) -> str:
        packages = " and ".join(f"{t.package} {t.package_version}" for t in twins[name_key(p.name)])
        return f'two {p.kind} plugins are both named "{p.name}" (packages {packages}); uninstall one of them'

    return [replace(p, error=both(p)) if p.ok and name_key(p.name) in twins else p for p in out]

