"""Which installed phrases a sentence may use: the phrase table, and the phrases blocked with the error that says
why (two plugins claiming one name or phrase, a broken plugin's phrases): plugins/registry.py's
``phrase_table`` and ``blocked_phrases``, made from a list of found plugins.

Every clause of every reading asks for both, of the same plugins, so :func:`tables` keeps them by what they are
made of (:func:`_claims`); the registry hands out copies.
"""

from __future__ import annotations

from typing import Protocol

from ..core.vocabulary import normalize_name
from ..errors import FailedToLoadPlugin, PluginConflict, PluginError


class PluginInfo(Protocol):
    """What the tables read of a found action plugin (plugins/registry.py's ``PluginInfo``)."""

    name: str
    package: str
    package_version: str
    kind: str
    error: str | None

    @property
    def ok(self) -> bool: ...

    @property
    def phrases(self) -> tuple[str, ...]: ...

    def label(self) -> str: ...


def conflicts(plugins: list[PluginInfo]) -> list[PluginConflict]:
    """Every name or phrase claimed by two usable plugins (empty when all is well)."""
    out: list[PluginConflict] = []
    usable = [p for p in plugins if p.ok]
    by_name: dict[str, list[PluginInfo]] = {}
    for p in usable:
        by_name.setdefault(normalize_name(p.name), []).append(p)
    for group in by_name.values():
        if len(group) > 1:
            out.append(PluginConflict(f'two action plugins are both named "{group[0].name}": '
                                      + " and ".join(p.label() for p in group) + "; uninstall one of the packages",
                                      group[0].name, [p.name for p in group]))
    by_phrase: dict[str, list[PluginInfo]] = {}
    for p in usable:
        for phrase in dict.fromkeys(p.phrases):
            by_phrase.setdefault(phrase, []).append(p)
    for phrase, group in by_phrase.items():
        if len({normalize_name(p.name) for p in group}) > 1:
            out.append(PluginConflict(
                f'the phrase "{phrase}" is claimed by several action plugins: '
                + " and ".join(p.label() for p in group)
                + "; uninstall one of the packages or remove the phrase from one manifest",
                phrase, [p.name for p in group]))
    return out


_TABLES: dict[tuple, tuple[dict[str, str], dict[str, PluginError]]] = {}
"""(phrase table, blocked phrases) by :func:`_claims`: every clause read asks for both, of the same plugins."""


def tables(plugins: list[PluginInfo]) -> tuple[dict[str, str], dict[str, PluginError]]:
    """(the registry's ``phrase_table``, its ``blocked_phrases``) of ``plugins``, kept by what they are made of
    (:func:`_claims`); callers hand out copies. Plugins that cannot be keyed are read each time."""
    try:
        key = _claims(plugins)
        kept = _TABLES.get(key)
    except (AttributeError, TypeError):
        key, kept = None, None
    if kept is None:
        blocked = _blocked(plugins)
        table = {phrase: p.name for p in plugins if p.ok and p.kind == "action" for phrase in p.phrases
                 if phrase not in blocked}
        kept = (table, blocked)
        if key is not None:
            if len(_TABLES) >= 64:
                _TABLES.clear()
            _TABLES[key] = kept
    return kept


def _claims(plugins: list[PluginInfo]) -> tuple:
    """All that the phrase tables and their errors depend on, per plugin, in order (a key to keep them by): the
    phrases as the manifest writes them, which say what ``phrases`` reads from them, without reading them."""
    return tuple((p.name, p.package, p.package_version, p.kind, p.error, _written(p.manifest.get("phrases")))
                 for p in plugins)


def _written(raw: object) -> tuple:
    """A manifest's ``phrases`` as a key: the list's items, or nothing for anything else (which reads as none)."""
    return tuple(raw) if isinstance(raw, list) else ()


def _blocked(plugins: list[PluginInfo]) -> dict[str, PluginError]:
    """The registry's ``blocked_phrases`` of ``plugins``, read."""
    out: dict[str, PluginError] = {}
    for c in conflicts(plugins):
        if all(normalize_name(n) == normalize_name(c.claim) for n in c.plugins):
            for p in plugins:  # a name conflict: every phrase of every plugin of that name
                if p.ok and normalize_name(p.name) == normalize_name(c.claim):
                    for phrase in p.phrases:
                        out.setdefault(phrase, c)
        else:
            out.setdefault(c.claim, c)
    owned = {phrase for p in plugins if p.ok for phrase in p.phrases}
    for p in plugins:
        if not p.ok:
            for phrase in p.phrases:
                if phrase not in owned:
                    out.setdefault(phrase, FailedToLoadPlugin(p.name, p.package, p.error or "broken"))
    return out
