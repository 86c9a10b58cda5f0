"""Manners found through the entry-point group ``l2p_bullet.manners`` by the one plugin finder
(plugins/finder.py); the built-ins register there too.

Each entry point names a module (or ``module:attribute``) whose ``MANNER`` is a :class:`MannerSpec` of the
entry point's name. Loading one is cheap (a declaration, no simulator), so :func:`discover` loads them all,
once per process. A broken manner (fails to import, no ``MANNER`` of its name, a built-in's name, or a verb
another manner already claims) is reported by :func:`broken` and left out; the others keep working. The
built-ins are read first, so of a plugin and a built-in claiming one verb or name the plugin is left out,
named with its own package (never "l2p-bullet" as the package to uninstall).
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache

from ..errors import FailedToLoadPlugin, UnknownPluginError
from ..plugins.finder import GROUPS, Plugin, find, load, settle
from .spec import MannerSpec

GROUP = GROUPS["manner"]
DEFAULT = "slide"


def _checked(plugin: Plugin) -> Plugin:
    """``plugin`` loaded: its MannerSpec in ``obj``, or the reason it cannot be used in ``error``."""
    try:
        obj = load(plugin, "MANNER")
    except FailedToLoadPlugin as e:
        return replace(plugin, error=e.reason)
    if not isinstance(obj, MannerSpec) or obj.name != plugin.name:
        return replace(plugin, error=f'its MANNER is not a MannerSpec named "{plugin.name}"')
    return replace(plugin, obj=obj)


@lru_cache(maxsize=1)
def _found() -> tuple[tuple[Plugin, ...], tuple[Plugin, ...]]:
    """(usable manners by name, broken ones in the order read)."""
    good: dict[str, Plugin] = {}
    bad: list[Plugin] = []
    claimed: dict[str, str] = {}
    for p in settle(_checked(p) for p in find("manner")):  # the built-ins first
        if p.ok:
            twice = [v for v in p.obj.verbs if v in claimed]
            if twice:
                p = replace(p, error=f'the verb "{twice[0]}" is already the manner "{claimed[twice[0]]}"\'s')
        if not p.ok:
            bad.append(p)
            continue
        good[p.name] = p
        claimed.update({v: p.name for v in p.obj.verbs})
    if DEFAULT not in good:  # the project itself is broken or not installed: the built-ins still work
        from . import carry, push, slide

        for m in (slide.MANNER, carry.MANNER, push.MANNER):
            good.setdefault(m.name, Plugin("manner", m.name, "l2p-bullet (built in, not installed)", "",
                                           f"l2p_bullet.manners.{m.name}", obj=m))
    return tuple(sorted(good.values(), key=lambda p: p.name)), tuple(bad)


def discover() -> list[MannerSpec]:
    """Every working manner, by name."""
    return [p.obj for p in _found()[0]]


def broken() -> list[Plugin]:
    """Every manner that could not be used, with its reason and package."""
    return list(_found()[1])


def package(name: str) -> str:
    """"name version" of the package that installed the working manner ``name``."""
    p = next(p for p in _found()[0] if p.name == get(name).name)
    return f"{p.package} {p.package_version}".strip()


def get(name: str | None) -> MannerSpec:
    """The manner called ``name`` (None: the default, slide); a one-line error with did-you-mean otherwise."""
    found = {m.name: m for m in discover()}
    if name is None:
        return found[DEFAULT]
    if name not in found:
        raise UnknownPluginError("manner", str(name), found, "List them with: l2p-bullet manners")
    return found[name]


def verb_table() -> dict[str, str]:
    """Verb (as the manners declare it, "pick up ... and put" included) -> manner name."""
    return dict(_verbs_of(tuple((m.name, tuple(m.verbs)) for m in discover())))


@lru_cache(maxsize=8)
def _verbs_of(declared: tuple[tuple[str, tuple[str, ...]], ...]) -> dict[str, str]:
    """:func:`verb_table` of the manners' (name, verbs), kept by them: every clause read asks for it (callers get a
    copy)."""
    return {v: name for name, verbs in declared for v in verbs}


def sentence_verb(name: str) -> str:
    """The verb a generated sentence uses for manner ``name`` ("move" for the default manner, as sentences
    were written before manners; else the manner's first one-word verb)."""
    if name == DEFAULT:
        return "move"
    return next((v for v in get(name).verbs if "..." not in v and " " not in v), get(name).verbs[0])


def check_names(names: list[str]) -> list[str]:
    """``names`` if every one is a manner (``evaluate --manners``), else a one-line error."""
    for n in names:
        get(n)
    return names
