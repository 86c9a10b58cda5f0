"""Installed-looking action plugins for tests: a ``*.dist-info`` folder with METADATA and
entry_points.txt next to the plugin's package, in a folder the test puts on sys.path. For
importlib.metadata (and so for the registry) these are real installed distributions."""

from __future__ import annotations

import json
import shutil
import tomllib
from pathlib import Path

import tomli_w

from l2p_bullet.plugins.bundle import MANIFEST, builtin_bundle_dir


def make_dist(root: Path, dist: str, entry_points: dict[str, str]) -> None:
    info = root / f"{dist.replace('-', '_')}-0.3.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 0.3\n")
    lines = "\n".join(f"{k} = {v}" for k, v in entry_points.items())
    (info / "entry_points.txt").write_text(f"[l2p_bullet.actions]\n{lines}\n")


def make_bundle(folder: Path, name: str, phrases: list[str], init: str = "", weights: bool = True,
                manifest: str | None = None) -> None:
    folder.mkdir(parents=True)
    (folder / "__init__.py").write_text(init)
    if manifest is None:
        manifest = (f'schema = 1\nname = "{name}"\nversion = "1.2.0"\nphrases = {json.dumps(phrases)}\n'
                    '[metrics]\nfinal_progress = 0.91\n')
    (folder / "manifest.toml").write_text(manifest)
    if weights:
        (folder / "progress.safetensors").write_bytes(b"not read at discovery")


def copy_builtin_as_plugin(root: Path, builtin: str, name: str, phrases: list[str], dist: str = "l2p-test-plugin",
                           module: str | None = None, **manifest_changes: object) -> Path:
    """A plugin package ``root/<module>`` whose bundle is a copy of a built-in's trained bundle, renamed
    ``name`` with ``phrases`` and no ``[judge]`` (a plugin without rules of its own): real weights, so
    it plans, performs and scores like a third-party action would."""
    module = module or "l2p_test_" + name.replace("-", "_")
    folder = root / module
    shutil.copytree(builtin_bundle_dir(builtin), folder)
    man = tomllib.loads((folder / MANIFEST).read_text())
    man.update(name=name, phrases=phrases)
    man.pop("judge", None)
    for k, v in manifest_changes.items():
        if v is None:
            man.pop(k, None)
        else:
            man[k] = v
    (folder / MANIFEST).write_text(tomli_w.dumps(man))
    (folder / "__init__.py").write_text("")
    make_dist(root, dist, {name: module})
    return folder
