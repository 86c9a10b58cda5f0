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


def trained_plugin(root: Path, name: str, phrase: str, options: list[str], epochs: int = 4) -> Path:
    """A plugin as docs/perform.md makes one: ``l2p-bullet new-action NAME --phrase PHRASE OPTIONS`` in
    ``root``, generated demonstrations (``learning.synthetic``), ``l2p-bullet train`` into its package
    (one small LSTM: this tests the path, not the model), and a ``*.dist-info`` next to the package in
    ``root/site`` so that, on ``sys.path``, it is an installed distribution. Returns that site folder."""
    from click.testing import CliRunner

    from l2p_bullet.cli import main
    from l2p_bullet.learning.synthetic import write_sessions

    module = f"l2p_{name.replace('-', '_')}"
    r = CliRunner().invoke(main, ["new-action", name, "--phrase", phrase, *options, "--out", str(root / f"l2p-{name}")])
    assert r.exit_code == 0, r.output
    pkg = root / f"l2p-{name}"
    files = write_sessions(pkg / "demos", name, sessions=1, events=12, seed=0)
    r = CliRunner().invoke(main, ["train", name, "--demos", *map(str, files), "--out", str(pkg / module),
                                  "--ensemble", "1", "--epochs", str(epochs)])
    assert r.exit_code == 0, r.output
    site = root / "site"
    shutil.copytree(pkg / module, site / module)
    make_dist(site, f"l2p-{name}", {name: module})
    return site
