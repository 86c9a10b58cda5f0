"""Manners found through the entry-point group ``l2p_bullet.manners`` (the built-ins register there too).

Each entry point names a module (or ``module:attribute``) whose ``MANNER`` is a :class:`MannerSpec`. Loading
one is cheap (a declaration, no simulator), so :func:`discover` loads them all, once per process. A broken
manner (fails to import, no ``MANNER``, a verb or a name another manner already claims) is reported by
:func:`broken` and left out; the others keep working, as the action registry does with its plugins. The
built-ins are read first, so of a plugin and a built-in claiming one verb or name the plugin is left out.
"""

from __future__ import annotations

import importlib
from functools import lru_cache
from importlib import metadata

from ..errors import LanguageError, PluginError, did_you_mean
from .spec import MannerSpec

GROUP = "l2p_bullet.manners"
DEFAULT = "slide"


def _package(ep: metadata.EntryPoint) -> str:
    """"name version" of the distribution that registers ``ep`` (what ``pip uninstall`` needs)."""
    dist = getattr(ep, "dist", None)
    return f'{dist.metadata["Name"]} {dist.metadata["Version"]}' if dist is not None else "unknown package"


def _builtin(ep: metadata.EntryPoint) -> bool:
    """Whether ``ep`` is registered by the l2p-bullet distribution itself."""
    dist = getattr(ep, "dist", None)
    return dist is not None and str(dist.metadata["Name"] or "").lower().replace("_", "-") == "l2p-bullet"


@lru_cache(maxsize=1)
def _found() -> tuple[tuple[MannerSpec, ...], tuple[tuple[str, str], ...], dict[str, str]]:
    good: dict[str, MannerSpec] = {}
    bad: list[tuple[str, str]] = []
    claimed: dict[str, str] = {}
    packages: dict[str, str] = {}
    # the project's own manners first: a plugin that claims a built-in's verb or name is the one left out, and
    # named with its own package (never "l2p-bullet" as the package to uninstall), whatever its name sorts as
    for ep in sorted(metadata.entry_points(group=GROUP), key=lambda e: (not _builtin(e), e.name, e.value)):
        try:
            module, _, attr = ep.value.partition(":")
            obj = getattr(importlib.import_module(module), attr or "MANNER")
        except BaseException as e:  # noqa: BLE001 - a broken plugin (even sys.exit) is reported, not fatal
            if isinstance(e, KeyboardInterrupt):
                raise
            bad.append((ep.name, f"{type(e).__name__}: {str(e)[:120]} (package {_package(ep)})"))
            continue
        if not isinstance(obj, MannerSpec):
            bad.append((ep.name, f"its MANNER is not a MannerSpec (package {_package(ep)})"))
            continue
        if obj.name in good:
            bad.append((ep.name, f'a second manner called "{obj.name}" (package {_package(ep)})'))
            continue
        twice = [v for v in obj.verbs if v in claimed]
        if twice:
            bad.append((ep.name, f'the verb "{twice[0]}" is already the manner "{claimed[twice[0]]}"\'s '
                                 f"(package {_package(ep)})"))
            continue
        good[obj.name] = obj
        packages[obj.name] = _package(ep)
        claimed.update({v: obj.name for v in obj.verbs})
    if DEFAULT not in good:  # the project itself is broken or not installed: the built-ins still work
        from . import carry, push, slide

        for m in (slide.MANNER, carry.MANNER, push.MANNER):
            good.setdefault(m.name, m)
            packages.setdefault(m.name, "l2p-bullet (built in, not installed)")
    return tuple(sorted(good.values(), key=lambda m: m.name)), tuple(bad), packages


def discover() -> list[MannerSpec]:
    """Every working manner, by name."""
    return list(_found()[0])


def broken() -> list[tuple[str, str]]:
    """(entry-point name, reason) of every manner that could not be used."""
    return list(_found()[1])


def package(name: str) -> str:
    """"name version" of the package that installed the working manner ``name``."""
    return _found()[2][get(name).name]


def get(name: str | None) -> MannerSpec:
    """The manner called ``name`` (None: the default, slide); a one-line error with did-you-mean otherwise."""
    found = {m.name: m for m in discover()}
    if name is None:
        return found[DEFAULT]
    if name not in found:
        raise PluginError(f'no manner called "{name}" (installed: {", ".join(sorted(found))}).'
                          + did_you_mean(str(name), found))
    return found[name]


def verb_table() -> dict[str, str]:
    """Verb (as the manners declare it, "pick up ... and put" included) -> manner name."""
    return {v: m.name for m in discover() for v in m.verbs}


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


def unknown_verb(verb: str) -> LanguageError:
    """The error for a sentence whose first word no manner claims."""
    verbs = sorted({v.split()[0] for v in verb_table()})
    return LanguageError(f'"{verb}" is not a verb I know (known: {", ".join(verbs)}).' + did_you_mean(verb.lower(), verbs))
