"""Action bundles: a folder with ``manifest.toml`` and safetensors weights, loaded and validated.

A bundle is what an action plugin ships: its name and phrases, the feature settings and architecture
its progress model needs, how it was trained, its metrics, and a sha256 digest of every weights file.
Loading checks all of it and raises :class:`BundleError` with a message that names the file and the
problem: a missing file, a manifest from an incompatible version, a tampered weights file (digest
mismatch) or weights of the wrong shape. Weights are only ever read with safetensors: nothing is
unpickled, so a bundle from a stranger cannot run code.

torch is imported lazily (``progress_model``/``policy_tensors``) so that listing bundles stays fast.
"""

from __future__ import annotations

import hashlib
import os
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .. import __version__
from ..errors import BundleError, DataError
from ..learning.demos import ACTIONS, canonical_action
from ..progress.config import ModelConfig, expected_shapes

if TYPE_CHECKING:  # pragma: no cover
    import torch

    from ..learning.progress_net import ProgressModel

MANIFEST = "manifest.toml"
PROGRESS_FILE = "progress.safetensors"
POLICY_FILE = "policy.safetensors"
SCHEMA = 1
"""Manifest schema this code reads; a bundle with another schema is refused."""
REQUIRES = ">=0.1,<1.0"
"""l2p-bullet versions a bundle written now works with (written into ``requires``)."""
REQUIRED_KEYS = ("schema", "name", "version", "requires", "phrases", "features", "model", "weights")

PHRASES: dict[str, list[str]] = {
    "closer": ["closer to", "nearer to", "toward", "towards"],
    "away": ["away from"],
    "next-to": ["next to", "beside", "alongside"],
    "past": ["past"],
    "around": ["around", "round"],
}
DESCRIPTIONS: dict[str, str] = {
    "closer": "Slide the mover closer to the anchor.",
    "away": "Slide the mover away from the anchor.",
    "next-to": "Slide the mover until it rests next to the anchor.",
    "past": "Slide the mover past the anchor, from one side of it to the other.",
    "around": "Slide the mover around the anchor.",
}


def sha256_file(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def _version_tuple(v: str) -> tuple[int, ...]:
    try:
        return tuple(int(p) for p in v.strip().split("."))
    except ValueError:
        raise BundleError(f'bad version "{v}" in a bundle\'s "requires"') from None


def version_satisfies(version: str, spec: str) -> bool:
    """True when ``version`` meets a comma-separated range like ``">=0.1,<1.0"``."""
    v = _version_tuple(version)
    for part in (p.strip() for p in spec.split(",") if p.strip()):
        for op in (">=", "<=", "==", ">", "<"):
            if part.startswith(op):
                w = _version_tuple(part[len(op):])
                n = max(len(v), len(w))
                a, b = v + (0,) * (n - len(v)), w + (0,) * (n - len(w))
                ok = {">=": a >= b, "<=": a <= b, "==": a == b, ">": a > b, "<": a < b}[op]
                if not ok:
                    return False
                break
        else:
            raise BundleError(f'cannot read the version range "{spec}" (use e.g. ">=0.1,<1.0")')
    return True


@dataclass
class Bundle:
    """A validated bundle. ``manifest`` is the parsed manifest.toml."""

    name: str
    version: str
    phrases: list[str]
    manifest: dict
    path: Path

    def weights_path(self, filename: str) -> Path:
        return self.path / filename

    def _tensors(self, filename: str) -> dict[str, torch.Tensor]:
        from safetensors import SafetensorError
        from safetensors.torch import load_file

        _check_digest(self.path, filename, self.manifest)  # the file may have changed since loading
        try:
            return load_file(self.path / filename)
        except (SafetensorError, OSError) as e:
            raise BundleError(f"{self.path / filename}: not a readable safetensors file ({e})") from None

    def progress_model(self) -> ProgressModel:
        """The ensemble, ready for batched scoring (imports torch)."""
        from ..learning.progress_net import ProgressModel
        from ..progress.features import QSRConfig

        mcfg = ModelConfig.from_dict(self.manifest["model"])
        return ProgressModel(self._tensors(PROGRESS_FILE), mcfg, QSRConfig.from_dict(self.manifest["features"]))

    def policy_tensors(self) -> dict[str, torch.Tensor] | None:
        """The planner's policy weights (``policy.safetensors``), or None when the bundle has none."""
        if POLICY_FILE not in self.manifest.get("weights", {}):
            return None
        return self._tensors(POLICY_FILE)


def _check_digest(folder: Path, filename: str, manifest: dict) -> None:
    entry = manifest.get("weights", {}).get(filename)
    if not isinstance(entry, dict) or "sha256" not in entry:
        raise BundleError(f'{folder / MANIFEST}: no [weights."{filename}"] sha256 entry')
    p = folder / filename
    if not p.is_file():
        raise BundleError(f"bundle {folder}: weights file {filename} is missing")
    if sha256_file(p) != entry["sha256"]:
        raise BundleError(f"bundle {folder}: {filename} does not match the sha256 digest in {MANIFEST} "
                          "(the file was modified or corrupted; re-train or re-install the bundle)")


def _check_shapes(folder: Path, manifest: dict) -> None:
    from safetensors import SafetensorError, safe_open

    try:
        mcfg = ModelConfig.from_dict(manifest["model"])
    except (KeyError, TypeError, ValueError) as e:
        raise BundleError(f"{folder / MANIFEST}: [model] needs integer n_features, hidden, ensemble ({e})") from None
    expected = expected_shapes(mcfg)
    try:
        with safe_open(folder / PROGRESS_FILE, framework="numpy") as f:
            got = {k: tuple(f.get_slice(k).get_shape()) for k in f.keys()}  # noqa: SIM118
    except (SafetensorError, OSError) as e:
        raise BundleError(f"{folder / PROGRESS_FILE}: not a readable safetensors file ({e})") from None
    missing = sorted(set(expected) - set(got))
    if missing:
        raise BundleError(f"{folder / PROGRESS_FILE}: missing tensors {', '.join(missing[:3])}"
                          + (" ..." if len(missing) > 3 else ""))
    for k, shape in expected.items():
        if got[k] != shape:
            raise BundleError(f"{folder / PROGRESS_FILE}: tensor {k} has shape {list(got[k])}, the manifest's "
                              f"[model] implies {list(shape)}")


def read_manifest(folder: Path) -> dict:
    p = folder / MANIFEST
    if not folder.is_dir():
        raise BundleError(f"bundle folder {folder} does not exist")
    if not p.is_file():
        raise BundleError(f"bundle {folder} has no {MANIFEST}")
    try:
        return tomllib.loads(p.read_text())
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
        raise BundleError(f"{p}: not valid TOML ({e})") from None


def load_bundle(path: str | os.PathLike) -> Bundle:
    """Read and validate a bundle folder (manifest, version, digests, tensor shapes); never unpickles."""
    folder = Path(path)
    man = read_manifest(folder)
    missing = [k for k in REQUIRED_KEYS if k not in man]
    if missing:
        raise BundleError(f"{folder / MANIFEST}: missing {', '.join(missing)}")
    if man["schema"] != SCHEMA:
        raise BundleError(f"{folder / MANIFEST}: manifest schema {man['schema']} is not supported "
                          f"(this l2p-bullet {__version__} reads schema {SCHEMA})")
    if not version_satisfies(__version__, str(man["requires"])):
        raise BundleError(f"{folder / MANIFEST}: bundle requires l2p-bullet {man['requires']}, "
                          f"this is {__version__}")
    if not isinstance(man["phrases"], list) or not all(isinstance(p, str) for p in man["phrases"]):
        raise BundleError(f"{folder / MANIFEST}: phrases must be a list of strings")
    for filename in man["weights"]:
        _check_digest(folder, filename, man)
    if PROGRESS_FILE not in man["weights"]:
        raise BundleError(f'{folder / MANIFEST}: no [weights."{PROGRESS_FILE}"] entry')
    _check_shapes(folder, man)
    return Bundle(str(man["name"]), str(man["version"]), list(man["phrases"]), man, folder)


def _write_manifest(folder: Path, manifest: dict) -> None:
    import tomli_w

    tmp = folder / (MANIFEST + ".tmp")
    tmp.write_text(tomli_w.dumps(_plain(manifest)))
    os.replace(tmp, folder / MANIFEST)


def _plain(v: Any) -> Any:
    """TOML-writable copy: tuples -> lists, numpy scalars -> floats/ints, None dropped."""
    if isinstance(v, dict):
        return {str(k): _plain(x) for k, x in v.items() if x is not None}
    if isinstance(v, list | tuple):
        return [_plain(x) for x in v]
    if hasattr(v, "item") and not isinstance(v, str | bytes):
        return v.item()
    return v


def write_weights(bundle_dir: str | os.PathLike, filename: str, tensors: dict[str, torch.Tensor],
                  section: str | None = None, settings: dict | None = None) -> Path:
    """Add or replace a weights file in a bundle and record its digest (and a manifest section).

    Used by the trainers: ``write_weights(dir, "policy.safetensors", tensors, "policy", {...})`` stores a
    planner policy that :meth:`Bundle.policy_tensors` then returns. The manifest must already exist.
    """
    from safetensors.torch import save_file

    folder = Path(bundle_dir)
    man = read_manifest(folder)
    if "/" in filename or not filename.endswith(".safetensors"):
        raise BundleError(f'weights file name "{filename}" must be a plain *.safetensors name')
    path = folder / filename
    save_file({k: v.detach().contiguous().cpu() for k, v in tensors.items()}, str(path))
    man.setdefault("weights", {})[filename] = {"sha256": sha256_file(path), "bytes": path.stat().st_size}
    if section is not None:
        man[section] = dict(settings or {})
    _write_manifest(folder, man)
    return path


def update_manifest(bundle_dir: str | os.PathLike, section: str, values: dict) -> None:
    """Merge ``values`` into one manifest section (e.g. ``metrics`` from the benchmark); weights untouched."""
    folder = Path(bundle_dir)
    man = read_manifest(folder)
    if section in ("schema", "name", "version", "requires", "weights"):
        raise BundleError(f'update_manifest does not change "{section}"')
    man[section] = {**man.get(section, {}), **values}
    _write_manifest(folder, man)


def write_progress_bundle(out_dir: str | os.PathLike, action: str, model: ProgressModel, *,
                          training: dict, metrics: dict, version: str = "1.0.0") -> Path:
    """Write (or overwrite) a bundle's manifest and progress weights, keeping any policy it already has."""
    from ..learning.progress_net import ensemble_state

    folder = Path(out_dir)
    folder.mkdir(parents=True, exist_ok=True)
    old: dict = {}
    if (folder / MANIFEST).is_file():
        try:
            old = tomllib.loads((folder / MANIFEST).read_text())
        except tomllib.TOMLDecodeError:
            old = {}
    keep_weights = {k: v for k, v in old.get("weights", {}).items()
                    if k != PROGRESS_FILE and (folder / k).is_file()}
    from ..progress.features import feature_names

    man = {
        "schema": SCHEMA, "name": action, "version": version, "requires": REQUIRES,
        # a plugin action keeps the phrases and description its scaffolded manifest declares
        "phrases": PHRASES.get(action) or old.get("phrases") or [action],
        "description": DESCRIPTIONS.get(action) or old.get("description", ""),
        "features": {**model.qsr_cfg.to_dict(), "names": feature_names(model.qsr_cfg)},
        "model": model.model_cfg.to_dict(), "training": training, "metrics": metrics,
        "weights": keep_weights,
    }
    for k, v in old.items():  # sections other stages own (e.g. [policy]) survive a re-train
        if k not in man:
            man[k] = v
    _write_manifest(folder, man)
    write_weights(folder, PROGRESS_FILE, ensemble_state(model.nets))
    return folder


def builtin_bundle_dir(action: str) -> Path:
    """Folder of a built-in action's bundle inside the installed package."""
    from importlib import resources

    canon = canonical_action(action)
    return Path(str(resources.files("l2p_bullet") / "actions" / canon.replace("-", "_")))


def resolve_action(spec: str) -> tuple[str, Path]:
    """``ACTION`` on the command line -> (canonical name, bundle folder).

    A path to a folder with a manifest is a bundle; anything else must name a built-in action. This is
    the one place the plugin registry replaces to resolve third-party actions.
    """
    p = Path(spec)
    if p.is_dir() and (p / MANIFEST).is_file():
        return str(read_manifest(p).get("name", p.name)), p
    try:
        canon = canonical_action(spec)
    except DataError as e:
        raise BundleError(f"{e} It is not a bundle folder either.") from None
    assert canon in ACTIONS
    return canon, builtin_bundle_dir(canon)
