"""Where a plugin's module lies on disk, found without importing it (no plugin code runs, not even its parent
packages' ``__init__``): the import system's own finders walked level by level, the distribution's RECORD
as a fallback, and the folder of a module once it is imported.

Apart from the registry because this is the import system's machinery, not plugins: the registry asks it for a
folder and reads the manifest there (:func:`.registry.discover`).
"""

from __future__ import annotations

import sys
from importlib import metadata
from pathlib import Path
from typing import Any

from .bundle import MANIFEST


def _find_spec_no_import(fullname: str, path: list[str] | None):
    """Ask the meta-path finders for a spec, as the import system would, but execute nothing."""
    if fullname in sys.modules and getattr(sys.modules[fullname], "__spec__", None) is not None:
        return sys.modules[fullname].__spec__
    for meta_finder in sys.meta_path:
        find_spec = getattr(meta_finder, "find_spec", None)
        if find_spec is None:
            continue
        try:
            spec = find_spec(fullname, path)
        except (ImportError, ValueError, OSError):
            continue
        if spec is not None:
            return spec
    return None


def locate_module_folder(module: str) -> Path:
    """The folder of ``module`` (a package's directory, or the directory holding a plain module).

    Walks the dotted name level by level with the meta-path finders and each parent's search
    locations, which is what ``import`` does, minus executing the parents' ``__init__``. Raises
    :class:`LookupError` with a readable reason when the module cannot be found.
    """
    parts = module.split(".")
    if not all(p.isidentifier() for p in parts):
        raise LookupError(f'"{module}" is not a module name')
    locations: list[str] | None = None
    spec = None
    for i in range(len(parts)):
        fullname = ".".join(parts[: i + 1])
        spec = _find_spec_no_import(fullname, locations)
        if spec is None:
            raise LookupError(f"module {fullname} is not installed (no finder knows it)")
        if i < len(parts) - 1:
            if spec.submodule_search_locations is None:
                raise LookupError(f"{fullname} is a module, not a package, so it has no {parts[i + 1]}")
            locations = list(spec.submodule_search_locations)
    assert spec is not None
    if spec.submodule_search_locations is not None:  # a package (regular or namespace)
        for loc in spec.submodule_search_locations:
            if Path(loc).is_dir():
                return Path(loc)
        raise LookupError(f"package {module} has no folder on disk")
    if spec.origin and Path(spec.origin).is_file():
        return Path(spec.origin).parent
    raise LookupError(f"module {module} has no file on disk (origin {spec.origin!r})")


def locate_from_files(dist: metadata.Distribution | None, module: str) -> Path | None:
    """Fallback for installs whose files are listed in RECORD but not reachable by the finders."""
    if dist is None or not dist.files:
        return None
    parts = tuple(module.split("."))
    for f in dist.files:
        if f.parts[: len(parts)] == parts and f.name in (MANIFEST, "__init__.py") and len(f.parts) == len(parts) + 1:
            folder = Path(str(dist.locate_file(f))).parent
            if folder.is_dir():
                return folder
    return None


def module_folder(mod: Any) -> Path | None:
    """The folder of an imported module: a package's first directory on disk, else the one holding its file."""
    paths = list(getattr(mod, "__path__", []) or [])
    for p in paths:
        if Path(p).is_dir():
            return Path(p)
    f = getattr(mod, "__file__", None)
    return Path(f).parent if f else None

