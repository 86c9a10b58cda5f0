"""Action bundles: a folder with ``manifest.toml`` and safetensors weights, loaded and validated.

A bundle is what an action plugin ships: its name and phrases, the feature settings and architecture
its progress model needs, how it was trained, its metrics, and a sha256 digest of every weights file.
Loading checks all of it and raises :class:`BundleError` with a message that names the file and the
problem: a missing file, a manifest from an incompatible version, a tampered weights file (digest
mismatch) or weights of the wrong shape. Weights are only ever read with safetensors: nothing is
unpickled, so a bundle from a stranger cannot run code.

Torch-free: :meth:`Bundle.progress_model` is the numpy ensemble (:mod:`l2p_bullet.progress.model`) and
:meth:`Bundle.policy_arrays` the policy's numpy arrays; the training code builds its torch twins from
the same arrays (:mod:`l2p_bullet.learning.progress_net`, :mod:`l2p_bullet.learning.policy_net`).
"""

from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from safetensors import SafetensorError
from safetensors.numpy import load, save

from .. import __version__
from ..core.atomic import write_atomic
from ..core.bounded import MAX_TOML_BYTES, loads_toml, read_bounded
from ..core.contracts import MANIFEST, POLICY_FILE, PROGRESS_FILE
from ..core.folders import check_writable
from ..core.vocabulary import ACTIONS, canonical_action, normalize_name
from ..errors import BundleError, RunFolderError, listed
from ..progress.config import ModelConfig
from ..progress.features import feature_names
from ..progress.model import NumpyProgressModel
from .validate import check_manifest, check_weights, safe_weight_name

if TYPE_CHECKING:  # pragma: no cover
    import numpy as np

    from ..progress.model import NumpyProgressModel

SCHEMA = 1
"""Manifest schema this code reads; a bundle with another schema is refused."""
REQUIRES = ">=0.1,<1.0"
"""l2p-bullet versions a bundle written now works with (written into ``requires``)."""
REQUIRED_KEYS = ("schema", "name", "version", "requires", "phrases", "features", "model", "weights")


def sha256_file(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def read_weights(folder: Path, filename: str, manifest: dict) -> bytes:
    """The bytes of a bundle's weights file, after checking them against the manifest's sha256.

    Read once and checked in memory: the file may have changed since the bundle was loaded, and a
    check followed by a second read would leave a window in which it could change again.
    """
    weights = manifest.get("weights", {})
    entry = weights.get(filename) if isinstance(weights, dict) else None
    if not isinstance(entry, dict) or "sha256" not in entry:
        raise BundleError(f'{folder / MANIFEST}: no [weights."{filename}"] sha256 entry')
    p = safe_weight_name(folder, filename)
    try:
        with open(p, "rb") as f:
            size = _checked_size(folder, filename, os.fstat(f.fileno()), entry, f.read(8))
            f.seek(0)
            data = f.read(size + 1)
    except FileNotFoundError:
        raise BundleError(f"bundle {folder}: weights file {filename} is missing") from None
    except OSError as e:
        raise BundleError(f"bundle {folder}: cannot read {filename} ({e.strerror or e})") from None
    if len(data) != size:
        raise BundleError(f"bundle {folder}: {filename} changed while it was read")
    if hashlib.sha256(data).hexdigest() != entry["sha256"]:
        raise BundleError(f"bundle {folder}: {filename} does not match the sha256 digest in {MANIFEST} "
                          "(the file was modified or corrupted; re-train or re-install the bundle)")
    return data


MAX_WEIGHTS_BYTES = 512 * 2**20
"""A weights file larger than this is not one of ours (the built-ins are 22 KB and 190 KB)."""


def _checked_size(folder: Path, filename: str, st: os.stat_result, entry: dict, head: bytes) -> int:
    """The file's size, once it is known to be what the manifest and the safetensors header say, so that
    a 16 GiB sparse file (or a device) is refused before it is read, not after."""
    import stat

    where = f"bundle {folder}: {filename}"
    if not stat.S_ISREG(st.st_mode):
        raise BundleError(f"{where} is not a regular file")
    declared = entry.get("bytes")
    if isinstance(declared, int) and not isinstance(declared, bool) and declared != st.st_size:
        raise BundleError(f"{where} is {st.st_size} bytes but {MANIFEST} says {declared} (modified or corrupted; "
                          "re-train or re-install the bundle)")
    if st.st_size > MAX_WEIGHTS_BYTES:
        raise BundleError(f"{where} is {st.st_size / 2**20:.0f} MiB; weights files are at most "
                          f"{MAX_WEIGHTS_BYTES // 2**20} MiB")
    if len(head) < 8 or int.from_bytes(head, "little") > st.st_size - 8:
        raise BundleError(f"{where}: not a safetensors file (its header does not fit in the file)")
    return st.st_size


def read_arrays(folder: Path, filename: str, manifest: dict) -> dict[str, np.ndarray]:
    """A weights file's tensors as numpy arrays (digest checked, safetensors only: nothing unpickled)."""

    data = read_weights(folder, filename, manifest)
    try:
        return load(data)
    except (SafetensorError, OSError, ValueError) as e:
        raise BundleError(f"{folder / filename}: not a readable safetensors file ({e})") from None


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


_MODELS: dict[tuple[str, str, str], Any] = {}
"""Numpy progress models by (bundle folder, weights digest, feature and model settings): the planner, the
recorder and a benchmark performing many sentences all share one, read and checked once per process."""


@dataclass
class Bundle:
    """A validated bundle. ``manifest`` is the parsed manifest.toml."""

    name: str
    version: str
    phrases: list[str]
    manifest: dict
    path: Path
    spec: Any = None
    """The :class:`~l2p_bullet.actions.spec.ActionSpec` its module declares as ``ACTION`` (the built-ins do;
    a plugin may), set by the registry; None for a bundle read from a folder."""

    def arrays(self, filename: str) -> dict[str, np.ndarray]:
        """A weights file's tensors as numpy arrays (the digest is checked again: the file may have changed)."""
        return read_arrays(self.path, filename, self.manifest)

    def progress_model(self) -> NumpyProgressModel:
        """The progress ensemble for batched scoring, in numpy (no torch), built once per process."""

        key = (str(self.path), str(self.manifest["weights"][PROGRESS_FILE].get("sha256", "")),
               json.dumps([self.manifest["features"], self.manifest["model"]], sort_keys=True, default=str))
        if key not in _MODELS:
            _MODELS[key] = NumpyProgressModel.from_bundle(self)
        return _MODELS[key]

    def policy_arrays(self) -> dict[str, np.ndarray] | None:
        """The planner's policy weights (``policy.safetensors``) as arrays, or None when the bundle has none."""
        if POLICY_FILE not in self.manifest.get("weights", {}):
            return None
        return self.arrays(POLICY_FILE)


def read_manifest(folder: Path) -> dict:
    p = folder / MANIFEST
    if not folder.is_dir():
        raise BundleError(f"bundle folder {folder} does not exist")
    if not p.is_file():
        raise BundleError(f"bundle {folder} has no {MANIFEST}")
    return loads_toml(read_bounded(p, MAX_TOML_BYTES, BundleError), BundleError, str(p))


def load_bundle(path: str | os.PathLike) -> Bundle:
    """Read and validate a bundle folder; never unpickles.

    The manifest's fields by type and range, the version range, every weights file's digest, and every
    tensor's shape, dtype and finiteness (:mod:`l2p_bullet.plugins.validate`): a bundle that loads can
    be planned and scored with, and never yields NaN.
    """
    folder = Path(path)
    man = read_manifest(folder)
    missing = [k for k in REQUIRED_KEYS if k not in man]
    if missing:
        raise BundleError(f"{folder / MANIFEST}: missing {', '.join(missing)}")
    if man["schema"] != SCHEMA or isinstance(man["schema"], bool):
        raise BundleError(f"{folder / MANIFEST}: manifest schema {str(man['schema'])[:20]} is not supported "
                          f"(this l2p-bullet {__version__} reads schema {SCHEMA})")
    if not isinstance(man["requires"], str) or not version_satisfies(__version__, man["requires"]):
        raise BundleError(f"{folder / MANIFEST}: bundle requires l2p-bullet {str(man['requires'])[:40]}, "
                          f"this is {__version__}")
    check_manifest(folder, man)
    for filename in man["weights"]:
        check_weights(folder, filename, read_arrays(folder, filename, man), man)
    return Bundle(str(man["name"]), str(man["version"]), list(man["phrases"]), man, folder)


def _write_manifest(folder: Path, manifest: dict) -> None:
    """Write ``manifest`` as the bundle's manifest.toml, keeping what the author wrote around it.

    The file on disk is edited, not regenerated (tomlkit): comments, key order and formatting of every
    value that does not change survive a re-train, so a scaffolded plugin's notes and version stay.
    Written to a temporary file and renamed: a reader never sees half a manifest.
    """
    # lazy: tomlkit only when a manifest is written (training), not when plugins are listed or loaded
    import tomlkit
    from tomlkit.exceptions import TOMLKitError

    path = folder / MANIFEST
    try:
        read_manifest(folder)  # bounded size and nesting first: tomlkit recurses like tomllib
        doc = tomlkit.parse(path.read_text(encoding="utf-8"))
    except (BundleError, OSError, UnicodeDecodeError, TOMLKitError, RecursionError):
        doc = tomlkit.document()
    _merge_into(doc, _plain(manifest))
    write_atomic(path, tomlkit.dumps(doc))


def _merge_into(table: Any, values: dict) -> None:
    """Make the tomlkit ``table`` hold exactly ``values``, touching only the entries that differ."""
    for k in [k for k in table if k not in values]:
        del table[k]
    for k, v in values.items():
        if k in table and isinstance(v, dict) and hasattr(table[k], "unwrap") and isinstance(table[k].unwrap(), dict):
            _merge_into(table[k], v)
        elif k not in table or _unwrapped(table[k]) != v:
            table[k] = v


def _unwrapped(item: Any) -> Any:
    return item.unwrap() if hasattr(item, "unwrap") else item


def _plain(v: Any) -> Any:
    """TOML-writable copy: tuples -> lists, numpy scalars -> floats/ints, None dropped."""
    if isinstance(v, dict):
        return {str(k): _plain(x) for k, x in v.items() if x is not None}
    if isinstance(v, list | tuple):
        return [_plain(x) for x in v]
    if hasattr(v, "item") and not isinstance(v, str | bytes):
        return v.item()
    return v


def write_weights(bundle_dir: str | os.PathLike, filename: str, arrays: dict[str, np.ndarray],
                  section: str | None = None, settings: dict | None = None) -> Path:
    """Add or replace a weights file in a bundle and record its digest (and a manifest section).

    Used by the trainers: ``write_weights(dir, "policy.safetensors", arrays, "policy", {...})`` stores a
    planner policy that :meth:`Bundle.policy_arrays` then returns. The manifest must already exist.
    Arrays are numpy (a torch tensor's ``.numpy()``): the file is byte-identical to torch's writer.
    """
    folder = Path(bundle_dir)
    man = read_manifest(folder)
    if not filename.endswith(".safetensors"):
        raise BundleError(f'weights file name "{filename}" must be a plain *.safetensors name')
    path = safe_weight_name(folder, filename)
    # safetensors' save_file creates the file 0600 (its temporary file's mode): weights to install and
    # share must follow the umask like every other file (0644 typically). Written to a
    # temporary file and renamed, as the manifest is: a reader never sees half a weights file.
    write_atomic(path, save({k: np.ascontiguousarray(v) for k, v in arrays.items()}))
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


def write_progress_bundle(out_dir: str | os.PathLike, action: str, arrays: dict[str, np.ndarray],
                          model_cfg: ModelConfig, qsr_cfg: Any, *, training: dict, metrics: dict,
                          version: str | None = None) -> Path:
    """Write (or overwrite) a bundle's manifest and progress weights, keeping any policy it already has.

    The phrases and description come from the manifest already in ``out_dir`` (a scaffolded plugin's),
    else, for a built-in action, from its shipped manifest: manifests declare phrases, nothing else does.
    The version is ``version``, else the one already in ``out_dir`` (the author's), else 1.0.0; the
    manifest's comments survive (:func:`_write_manifest`).
    """
    folder = Path(out_dir)
    folder.mkdir(parents=True, exist_ok=True)
    old: dict = {}
    if (folder / MANIFEST).is_file():
        try:
            old = read_manifest(folder)
        except BundleError:
            old = {}
    shipped = read_manifest(builtin_bundle_dir(action)) if action in ACTIONS else {}
    keep_weights = {k: v for k, v in old.get("weights", {}).items()
                    if k != PROGRESS_FILE and (folder / k).is_file()}
    man = {
        "schema": SCHEMA, "name": action, "version": version or str(old.get("version") or "1.0.0"),
        "requires": REQUIRES,
        "phrases": shipped.get("phrases") or old.get("phrases") or [action],
        "description": shipped.get("description") or old.get("description", ""),
        # the declaration the model was trained for (left out at the defaults unless the author wrote it)
        "frame": qsr_cfg.frame if qsr_cfg.frame != "relative" or "frame" in old else None,
        "anchors": qsr_cfg.anchors if qsr_cfg.anchors != 1 or "anchors" in old else None,
        "features": {**qsr_cfg.to_dict(), "names": feature_names(qsr_cfg)},
        "model": model_cfg.to_dict(), "training": training, "metrics": metrics,
        "weights": keep_weights,
    }
    for k, v in old.items():  # sections other stages own (e.g. [policy]) survive a re-train
        if k not in man:
            man[k] = v
    if "judge" in shipped and "judge" not in man:  # a built-in trained into a new folder keeps its judge
        man["judge"] = shipped["judge"]
    _write_manifest(folder, man)
    write_weights(folder, PROGRESS_FILE, arrays)
    return folder


def check_bundle_target(out: Path, name: str, force: bool) -> None:
    """Where ``l2p-bullet train`` may write ``name``'s bundle: a new or empty folder, or a folder whose
    manifest.toml is a bundle manifest of ``name`` (a scaffolded plugin's template, or a bundle trained
    before: replaced only with ``force``). Anything else is someone's folder (notes, a run folder, another
    project's manifest.toml): refused even with ``force``, before training, so nothing of theirs is touched."""
    if out.is_symlink() or (out.exists() and not out.is_dir()):
        raise RunFolderError(f"{out} is not a folder (or is a symbolic link); choose another --out")
    check_writable(out)
    entries = sorted(p.name for p in out.iterdir()) if out.is_dir() else []
    if not entries:
        return
    try:
        man: dict | None = read_manifest(out)
    except BundleError:
        man = None
    if not (man and man.get("schema") == SCHEMA and isinstance(man.get("name"), str) and "phrases" in man):
        raise RunFolderError(
            f"{out} already exists and holds files that are not an action bundle's ({listed(entries)}); "
            "choose another --out (--force only replaces a bundle l2p-bullet wrote)"
        )
    if normalize_name(str(man["name"])) != normalize_name(name):
        raise RunFolderError(f'{out} holds the bundle of the action "{man["name"]}", not of "{name}"; '
                             "choose another --out")
    if (out / PROGRESS_FILE).exists() and not force:
        raise RunFolderError(f"{out} already holds a trained bundle of {name}; pass --force to replace its "
                             "manifest and progress weights (its other files are kept)")


def builtin_bundle_dir(action: str) -> Path:
    """Folder of a built-in action's bundle inside the installed package."""
    canon = canonical_action(action)
    return Path(str(resources.files("l2p_bullet") / "actions" / canon.replace("-", "_")))
