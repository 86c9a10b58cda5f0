"""A composite action's bundle: ``manifest.toml`` (``kind = "composite"``, phrases), ``recipe.json`` (what
was learned, recipe.py) and ``demos.json`` (the demonstrations it was learned from), both files' digests
recorded under ``[weights]`` like a single action's weights, so discovery checks they are there and
loading checks they are the files that were learned."""

from __future__ import annotations

import json
from pathlib import Path

from ..core.atomic import write_atomic
from ..core.bounded import read_bounded
from ..errors import BundleError
from ..plugins.bundle import MANIFEST, _write_manifest, read_manifest, sha256_file
from ..plugins.validate import SHA256
from .recipe import MAX_DEMOS, CompositeError, Demonstration, Recipe

RECIPE_FILE = "recipe.json"
DEMOS_FILE = "demos.json"
MAX_BYTES = 20_000_000
"""Largest recipe or demos file read (a composite's are kilobytes; a larger one is not ours), and so the
largest written: a file saved past it could never be read again, and every demonstration in it is lost."""


def read_demos(folder: str | Path) -> list[Demonstration]:
    """The demonstrations in ``folder/demos.json`` (empty when there are none yet)."""
    path = Path(folder) / DEMOS_FILE
    if not path.is_file():
        return []
    return [Demonstration.from_dict(d) for d in _read(path).get("demos", [])]


def write_demos(folder: str | Path, demos: list[Demonstration]) -> Path:
    """All ``demos`` as ``folder/demos.json``, replaced atomically (``core/atomic.py``); refused
    (:class:`CompositeError`, nothing written) when the file would hold more than :func:`read_demos` and
    :func:`~.recipe.learn` accept: :data:`~.recipe.MAX_DEMOS` demonstrations, :data:`MAX_BYTES` bytes."""
    path = Path(folder) / DEMOS_FILE
    if len(demos) > MAX_DEMOS:
        raise CompositeError(f"{path} would hold {len(demos)} demonstrations; training reads at most {MAX_DEMOS}: "
                             "remove one before recording more")
    data = (json.dumps({"schema": 1, "demos": [d.to_dict() for d in demos]}, separators=(",", ":")) + "\n").encode()
    if len(data) > MAX_BYTES:
        raise CompositeError(f"{path} would be {len(data) / 2**20:.1f} MiB; it is read up to "
                             f"{MAX_BYTES / 2**20:.1f} MiB: record shorter drags, or remove a demonstration")
    write_atomic(path, data)
    return path


def write_recipe(folder: str | Path, recipe: Recipe) -> Path:
    """``recipe.json`` and the digests of it and of ``demos.json`` in the manifest (which must exist)."""
    folder = Path(folder)
    man = read_manifest(folder)
    if man.get("kind") != "composite":
        raise BundleError(f'{folder / MANIFEST} is not a composite action\'s (kind = "composite")')
    path = folder / RECIPE_FILE
    write_atomic(path, json.dumps(recipe.to_dict(), indent=1) + "\n")
    weights = {}
    for f in (RECIPE_FILE, DEMOS_FILE):
        if (folder / f).is_file():
            weights[f] = {"sha256": sha256_file(folder / f), "bytes": (folder / f).stat().st_size}
    man["weights"] = weights
    _write_manifest(folder, man)
    return path


def read_recipe(folder: str | Path) -> Recipe:
    """The recipe of the composite bundle in ``folder``, checked against the manifest's digest."""
    folder = Path(folder)
    man = read_manifest(folder)
    path = folder / RECIPE_FILE
    if not path.is_file():
        raise CompositeError(f"{folder} has no {RECIPE_FILE}: teach the composite first (l2p-bullet teach ...)")
    # both files as learned: a recipe without its digest, or beside other demonstrations, is not what was taught
    for name, hint in ((RECIPE_FILE, "teach it again"), (DEMOS_FILE, "teach it again (train on the page), or put "
                                                                     "back the demos.json it was learned from")):
        entry = (man.get("weights") or {}).get(name) if isinstance(man.get("weights"), dict) else None
        want = entry.get("sha256") if isinstance(entry, dict) else None
        if want is None and name == DEMOS_FILE and not (folder / name).is_file():
            continue  # a recipe may ship without the rows it was learned from
        if not (isinstance(want, str) and SHA256.fullmatch(want)):
            raise CompositeError(f'{folder / MANIFEST}: [weights."{name}"] records no sha256 of {name}; {hint}')
        if not (folder / name).is_file():
            raise CompositeError(f"{folder / name} is missing, though its manifest records it; {hint}")
        if sha256_file(folder / name) != want:
            raise CompositeError(f"{folder / name} is not the file its manifest records (digest differs); {hint}")
    return Recipe.from_dict(_read(path))


def _no_constant(name: str) -> float:
    raise ValueError(f"{name} is not a JSON number")


def _read(path: Path) -> dict:
    # bounded as read, not by st_size: a link to /dev/zero has size 0 and never ends
    raw = read_bounded(path, MAX_BYTES, CompositeError, str(path))
    try:
        d = json.loads(raw.decode("utf-8"), parse_constant=_no_constant)  # NaN is no angle
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError, ValueError) as e:
        raise CompositeError(f"cannot read {path}: {type(e).__name__}: {str(e)[:120]}") from None
    if not isinstance(d, dict):
        raise CompositeError(f"{path} is not a JSON object")
    return d
