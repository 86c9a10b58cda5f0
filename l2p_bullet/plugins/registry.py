"""Action plugins: find them through entry points without importing them, load one only when needed.

An action plugin is any installed distribution that declares an entry point in the group
``l2p_bullet.actions``; its value names a module whose folder holds a bundle (``manifest.toml`` plus
weights). The five built-in actions register the same way in the project's own pyproject, so a
third-party action is a first-class citizen; the entry points are found, and names settled (a plugin
cannot take a built-in's name), by the one plugin finder of every kind (plugins/finder.py).

Two phases, as in flake8 and llm:

- **found** (:func:`discover`): entry points are read from installed metadata and each module's folder
  is located with the import system's finders *without executing any module* (not even the plugin's
  parent packages; plugins/folders.py), then ``manifest.toml`` is read with :mod:`tomllib`. No torch, no
  plugin code, no weights: listing actions and parsing a sentence stay fast and cannot be broken by one bad plugin.
- **loaded** (:func:`load`): only the plugin a command needs is imported and its bundle validated and
  read by :func:`l2p_bullet.plugins.bundle.load_bundle`.

A plugin that cannot be located, has no or an invalid manifest, or fails to import (even by calling
``sys.exit``) is *reported* (name, package, reason) and the others keep working. Two plugins that claim
the same phrase make that phrase ambiguous: it is left out of :func:`phrase_table`
and a sentence using it gets the :class:`PluginConflict` naming both (:func:`blocked_phrases`), since
silently picking one would make sentences mean different things on different machines; every other
phrase keeps working. The phrases of a broken plugin are blocked the same way, with its reason.

One group, two kinds: a manifest's ``kind`` is ``"action"`` (the default: a single action with a
progress model) or ``"composite"`` (an action over a list of objects, "make a row of A, B and C",
whose bundle holds a learned recipe instead of weights: l2p_bullet/composite). :func:`discover` lists
one kind at a time (actions unless asked), so nothing that reads single actions ever meets a composite.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..actions.spec import ActionSpec
from ..core.bounded import MAX_TOML_BYTES, loads_toml, read_bounded
from ..core.frames import declaration
from ..core.vocabulary import normalize_name, normalize_phrase
from ..errors import (
    BundleError,
    FailedToLoadPlugin,
    L2PError,
    PluginConflict,
    PluginError,
    UnknownActionError,
    copied,
)
from . import finder, once
from .bundle import MANIFEST, PROGRESS_FILE, load_bundle, read_manifest
from .finder import Plugin
from .folders import locate_from_files, locate_module_folder, module_folder
from .phrases import conflicts, tables  # noqa: F401 - registry.conflicts is the actions command's

if TYPE_CHECKING:  # pragma: no cover
    from .bundle import Bundle

GROUP = finder.GROUPS["action"]
KINDS = ("action", "composite")
"""What a manifest's ``kind`` may say (default "action")."""


@dataclass(frozen=True)
class PluginInfo(Plugin):
    """One found action plugin (the finder's :class:`~l2p_bullet.plugins.finder.Plugin`), with what can be
    known without importing it: its bundle folder and manifest. ``kind`` is the manifest's: "action" (the
    default: a single action with a progress model) or "composite" (:data:`KINDS`).

    ``error`` is None for a usable plugin, otherwise the reason it cannot be used (shown by
    ``l2p-bullet actions`` and by :func:`load`).
    """

    path: Path | None = None  # the bundle folder, when it could be located
    manifest: dict[str, Any] = field(default_factory=dict)

    @property
    def version(self) -> str:
        return str(self.manifest.get("version", ""))

    @property
    def phrases(self) -> tuple[str, ...]:
        raw = self.manifest.get("phrases", ())
        return tuple(normalize_phrase(p) for p in raw if isinstance(p, str)) if isinstance(raw, list) else ()

    @property
    def anchors(self) -> int:
        """Reference objects its sentences name (the manifest's ``anchors``; 1 unless declared)."""
        a = self.manifest.get("anchors", 1)
        return a if isinstance(a, int) and not isinstance(a, bool) else 1

    @property
    def extents(self) -> frozenset[str]:
        """The qualifiers its phrase takes ("far", "little", "right": the manifest's ``extents``; none unless
        declared): language/extents.EXTENTS."""
        raw = self.manifest.get("extents", [])
        return frozenset(e for e in raw if isinstance(e, str)) if isinstance(raw, list) else frozenset()

    @property
    def frame(self) -> str:
        """Where its relation is seen from (the manifest's ``frame``; "relative" unless declared)."""
        return str(self.manifest.get("frame", "relative"))

    @property
    def description(self) -> str:
        return str(self.manifest.get("description", ""))

    @property
    def metrics(self) -> dict[str, Any]:
        m = self.manifest.get("metrics", {})
        return m if isinstance(m, dict) else {}


# --- discovery --------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def _parsed(raw: bytes, label: str) -> dict[str, Any]:
    """``raw`` parsed as a manifest, kept by its bytes: every sentence read asks :func:`discover` again (a
    composite's phrases, a broken one's), and parsing the installed manifests was half of reading one. The bytes
    are read anew each time, so an edited manifest is parsed anew; a failure is never kept."""
    return loads_toml(raw, BundleError, label)


def _copied(value: Any) -> Any:
    """A parsed TOML document copied down to its leaves (tables and arrays new; strings, numbers, booleans and
    dates are immutable and shared): what ``copy.deepcopy`` gives for such a tree, without its memo and dispatch
    (a discovery of the built-in plugins 5.0 -> 4.7 ms; a sentence read discovers them once or twice)."""
    if isinstance(value, dict):
        return {k: _copied(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_copied(v) for v in value]
    return value


def _check_manifest(name: str, folder: Path) -> tuple[dict[str, Any], str | None]:
    """Read the manifest and check what discovery can check cheaply (no weights are read)."""
    path = folder / MANIFEST
    train_hint = f"train it with: l2p-bullet train {name} --demos ... --out {folder}"
    if not path.is_file():
        return {}, f"no {MANIFEST} in {folder} ({train_hint})"
    try:
        # a copy: the caller owns what it gets (a PluginInfo's manifest), the kept one stays as parsed
        manifest = _copied(_parsed(read_bounded(path, MAX_TOML_BYTES, BundleError), str(path)))
    except BundleError as e:
        return {}, str(e)
    phrases = manifest.get("phrases")
    if not (isinstance(phrases, list) and phrases and all(isinstance(p, str) and p.strip() for p in phrases)):
        return manifest, f'{path}: "phrases" must be a non-empty list of phrases such as ["next to", "beside"]'
    if manifest.get("kind", "action") not in KINDS:
        return manifest, f'{path}: "kind" must be one of {", ".join(KINDS)} (got {str(manifest.get("kind"))[:40]!r})'
    try:
        declaration(manifest)
    except BundleError as e:
        return manifest, f"{path}: {e}"
    declared = manifest.get("name")
    if declared is not None and normalize_name(str(declared)) != normalize_name(name):
        return manifest, f'{path} describes the action "{declared}" but the entry point is named "{name}"'
    weights = manifest.get("weights", {})
    composite = manifest.get("kind") == "composite"
    files = list(weights) if isinstance(weights, dict) and weights else ["recipe.json" if composite else PROGRESS_FILE]
    missing = [f for f in files if not (folder / f).is_file()]
    if missing:
        if composite:  # learned on the teach page, never by `train`
            train_hint = (f"teach it with: l2p-bullet teach {name} --plugin <its project folder>, then install it "
                          "again")
        return manifest, f"no trained weights ({', '.join(missing)} missing in {folder}; {train_hint})"
    return manifest, None


def discover(kind: str = "action") -> list[PluginInfo]:
    """Every installed plugin of ``kind`` (:data:`KINDS`), usable or not, sorted by name. Imports no plugin
    code. A plugin whose manifest cannot be read counts as an action (its error is shown with them). Read once
    while one sentence is read (plugins/once.py)."""
    found = once.kept("action plugins", _found,  # only ``kind``'s copied: a sentence asks for the composites often
                      lambda kept: [replace(p, manifest=_copied(p.manifest)) for p in kept if p.kind == kind])
    return sorted([p for p in found if p.kind == kind], key=lambda p: (p.name, p.package))


def _found() -> list[PluginInfo]:
    """Every installed action plugin, composites too, with the one rule for names applied."""
    found: list[PluginInfo] = []
    for plugin in finder.find("action"):
        base = PluginInfo(**{f.name: getattr(plugin, f.name) for f in fields(Plugin)})
        try:
            folder = locate_module_folder(base.module)
        except LookupError as e:
            folder = locate_from_files(plugin.dist, base.module)
            if folder is None:
                found.append(replace(base, error=str(e)))
                continue
        manifest, error = _check_manifest(plugin.name, folder)
        found.append(replace(base, kind=str(manifest.get("kind", "action")), path=folder, manifest=manifest,
                             error=error))
    return finder.settle(found)


def composites(plugins: list[PluginInfo] | None = None, installed: list[PluginInfo] | None = None,
               usable: bool = True) -> list[PluginInfo]:
    """The usable composite plugins (every one, usable or not, with ``usable=False``): those in ``plugins`` (a
    folder being taught, :func:`local`) first, then the installed ones of other names; ``installed`` is
    ``discover("composite")`` where the caller has it already (reading a sentence asks twice)."""
    given = [p for p in (plugins or []) if (p.ok or not usable) and p.kind == "composite"]
    names = {normalize_name(p.name) for p in given}
    pool = discover("composite") if installed is None else installed
    return given + [p for p in pool if (p.ok or not usable) and normalize_name(p.name) not in names]


def local(name: str, folder: Path) -> PluginInfo:
    """A bundle folder being authored (not installed: the teach page trains it and performs with it),
    as a plugin that :func:`load` reads without importing anything and never caches (it may be
    re-trained at any time). Pass it in the ``plugins`` list of ``perform`` instead of the installed one."""
    manifest, error = _check_manifest(name, folder)
    return PluginInfo(kind=str(manifest.get("kind", "action")), name=name, package="(not installed)",
                      package_version="", entry_point="", error=error, path=folder, manifest=manifest)


def blocked_phrases(plugins: list[PluginInfo] | None = None) -> dict[str, PluginError]:
    """Phrases no sentence may use, each with the error that says why: the phrases of plugins in a name
    conflict, phrases claimed by two plugins, and the phrases of broken plugins that no usable one owns.

    Only those phrases are blocked: a plugin that claims "past" must not stop "move A around B".
    """
    blocked = tables(discover() if plugins is None else plugins)[1]
    copies: dict[int, PluginError] = {}  # one error blocking several phrases stays one error
    return {phrase: copies.setdefault(id(e), copied(e)) for phrase, e in blocked.items()}


def phrase_table(plugins: list[PluginInfo] | None = None) -> dict[str, str]:
    """Phrase -> action name over the usable plugins, without the :func:`blocked_phrases`."""
    return dict(tables(discover() if plugins is None else plugins)[0])


def anchor_counts(plugins: list[PluginInfo] | None = None) -> dict[str, int]:
    """Action name -> how many reference objects its sentences name, over the usable plugins."""
    plugins = discover() if plugins is None else plugins
    return {p.name: p.anchors for p in plugins if p.ok and p.kind == "action"}


def extent_table(plugins: list[PluginInfo] | None = None) -> dict[str, frozenset[str]]:
    """Action name -> the extents its sentences may ask for, over the usable plugins."""
    plugins = discover() if plugins is None else plugins
    return {p.name: p.extents for p in plugins if p.ok and p.kind == "action"}


def broken(plugins: list[PluginInfo] | None = None) -> list[PluginInfo]:
    """The plugins that cannot be used, each with its reason."""
    return [p for p in (discover() if plugins is None else plugins) if not p.ok]


# --- loading ----------------------------------------------------------------------------------------
_LOADED: dict[tuple[str, str], Bundle] = {}


def find(name: str, plugins: list[PluginInfo] | None = None) -> PluginInfo:
    """The found plugin called ``name`` (``next_to`` and ``next-to`` are the same); UnknownActionError otherwise."""
    plugins = discover() if plugins is None else plugins
    key = normalize_name(name)
    matches = [p for p in plugins if normalize_name(p.name) == key]
    if not matches:
        raise UnknownActionError(name, {p.name for p in plugins}, "(no installed action plugin has that name)")
    if len(matches) > 1 and sum(m.ok for m in matches) == 1:  # a broken twin does not block a usable one
        matches = [m for m in matches if m.ok]
    if len(matches) > 1:
        raise PluginConflict(f'two action plugins are both named "{name}": '
                             + " and ".join(m.label() for m in matches) + "; uninstall one of the two packages",
                             name, [m.name for m in matches])
    return matches[0]


def load(name: str, plugins: list[PluginInfo] | None = None) -> Bundle:
    """Import plugin ``name`` and load its bundle; every failure is a :class:`FailedToLoadPlugin` naming it.

    Only this plugin's module is imported (a plugin may run code on import, for example to check its
    own requirements); the bundle itself is read by :func:`l2p_bullet.plugins.bundle.load_bundle`, which
    validates the manifest and the weights' digests and never unpickles.
    """
    info = find(name, plugins)
    if info.error is not None:
        raise FailedToLoadPlugin(info.name, info.package, info.error)
    key = (info.name, str(info.path))
    if key in _LOADED:
        return _LOADED[key]
    folder = info.path
    if info.module:  # an installed plugin (not a folder being authored, see local())
        mod = finder.load(info)
        folder = module_folder(mod) or info.path

    try:
        bundle = load_bundle(folder)
    except L2PError as e:
        raise FailedToLoadPlugin(info.name, info.package, f"invalid bundle: {e}") from None
    if info.module:
        bundle.spec = _declared_spec(info, mod)
        _LOADED[key] = bundle
    return bundle


def locate(spec: str, plugins: list[PluginInfo] | None = None) -> tuple[str, Path]:
    """``ACTION`` on the command line -> (action name, bundle folder).

    A folder with a manifest is a bundle (its manifest names the action); anything else names an
    installed action, built-in or plugin (``UnknownActionError``, ``FailedToLoadPlugin`` otherwise).
    """
    p = Path(spec)
    if p.is_dir() and (p / MANIFEST).is_file():
        return str(read_manifest(p).get("name", p.name)), p
    if p.is_dir() and ("/" in spec or spec.startswith(".")):  # a path, not an action's name
        raise BundleError(f"{spec} is not a bundle folder (no {MANIFEST} in it)")
    info = find(spec, plugins)
    if info.error is not None or info.path is None:
        raise FailedToLoadPlugin(info.name, info.package, info.error or "its bundle folder cannot be found")
    return info.name, info.path



def load_problem(name: str, plugins: list[PluginInfo] | None = None) -> str | None:
    """Load plugin ``name`` as ``perform`` would (bundle, progress model, judge, policy) and return the
    reason it fails, or None if it loads."""
    # lazy: discovery (l2p-bullet actions, parsing a sentence) stays light; only a check loads these
    from ..judge import judge_for
    from ..planning.policy import load_policy

    try:
        bundle = load(name, plugins)
        bundle.progress_model()
        judge_for(bundle)
        load_policy(bundle)
    except L2PError as e:
        return str(e)
    return None


def action_spec(name: str, plugins: list[PluginInfo] | None = None) -> ActionSpec | None:
    """The :class:`ActionSpec` an installed action's module declares as ``ACTION`` (every built-in does; a
    plugin may), or None. Only the module is imported, not the bundle: an untrained plugin has a spec too."""
    info = find(name, plugins)
    if not info.module:
        return None
    return _declared_spec(info, finder.load(info))


def _declared_spec(info: PluginInfo, mod: Any) -> ActionSpec | None:
    """The ``ACTION`` a plugin's module declares (what the action is besides its bundle), checked: an
    :class:`ActionSpec` of the same name, or nothing."""
    spec = getattr(mod, "ACTION", None)
    if spec is None:
        return None
    if not isinstance(spec, ActionSpec) or spec.name != info.name:
        raise FailedToLoadPlugin(info.name, info.package, f"{info.module}.ACTION must be an "
                                 f'l2p_bullet.actions.spec.ActionSpec named "{info.name}"')
    return spec
