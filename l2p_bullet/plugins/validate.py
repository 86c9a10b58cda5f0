"""Everything a bundle declares, checked before any of it is used: a manifest is input from a stranger.

:func:`check_manifest` checks the type and range of every field the code reads (``spacing = "wide"``,
``ensemble = 0``, ``[features]`` that no longer match ``[model]``, weight files outside the bundle
folder); :func:`check_progress_arrays` and :func:`check_policy_arrays` check every tensor's name, shape,
dtype and that it is finite (NaN weights would give NaN verdicts). Each failure is a
:class:`BundleError` naming the file and the field, raised by
:func:`l2p_bullet.plugins.bundle.load_bundle`, so ``actions --check`` sees what ``perform`` would.
Sections nobody reads for computing (``[training]``, ``[metrics]``) need only be tables.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

import numpy as np

from ..core.frames import declaration
from ..errors import BundleError
from ..planning import PLANNERS
from ..planning.policy import FEATURES
from ..progress.config import ModelConfig, expected_shapes
from ..progress.features import QSRConfig, feature_names

SHA256 = re.compile(r"[0-9a-f]{64}")
NAME = re.compile(r"[a-z][a-z0-9_-]{0,63}")
LIMITS = {
    "spacing": (0.01, 10.0), "cd_sectors": (1, 64), "moving_eps": (0.0, 10.0), "max_distance": (0.1, 1000.0),
    "hidden": (1, 1024), "ensemble": (1, 64), "policy_hidden": (1, 1024),
}


def _is_int(v: object) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _is_num(v: object) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)


class _Checker:
    def __init__(self, folder: Path):
        self.where = folder / "manifest.toml"

    def fail(self, field: str, what: str) -> BundleError:
        return BundleError(f"{self.where}: {field} {what}" if field else f"{self.where}: {what}")

    def table(self, man: dict, key: str, required: bool = True) -> dict:
        v = man.get(key)
        if v is None and not required:
            return {}
        if not isinstance(v, dict):
            raise self.fail(f"[{key}]", "must be a table" if v is not None else "is missing")
        return v

    def text(self, d: dict, key: str, field: str, max_len: int = 200, required: bool = True) -> str | None:
        v = d.get(key)
        if v is None and not required:
            return None
        if not isinstance(v, str) or not v.strip() or len(v) > max_len:
            raise self.fail(field, f"must be a non-empty text of at most {max_len} characters")
        return v

    def number(self, d: dict, key: str, field: str, lo: float, hi: float, integer: bool = False) -> float:
        v = d.get(key)
        ok = _is_int(v) if integer else _is_num(v)
        if not ok or not lo <= v <= hi:
            kind = "an integer" if integer else "a number"
            raise self.fail(field, f"must be {kind} from {lo:g} to {hi:g} (got {str(v)[:30]!s})")
        return v


def safe_weight_name(folder: Path, name: object) -> Path:
    """The path of a weights file named in the manifest, which must be a plain file name inside ``folder``:
    no absolute path, no ``..``, no folder, no link leading out of the bundle."""
    if not isinstance(name, str) or not name or name != Path(name).name or name in (".", "..") or "\\" in name:
        raise BundleError(f'{folder / "manifest.toml"}: weights file "{str(name)[:80]}" must be a plain file name '
                          "in the bundle folder (no absolute path, no folder, no ..)")
    path = folder / name
    try:
        inside = path.resolve().is_relative_to(folder.resolve())
    except OSError:
        inside = False
    if not inside:
        raise BundleError(f"{folder / 'manifest.toml'}: weights file {name} leads out of the bundle folder")
    return path


def check_manifest(folder: Path, man: dict) -> None:
    """Every field the code reads, by type and range (module docstring); BundleError on the first problem."""
    c = _Checker(folder)
    if not _is_int(man.get("schema")):
        raise c.fail("schema", "must be an integer")
    name = c.text(man, "name", "name", 64)
    if not NAME.fullmatch(name):
        raise c.fail("name", f'"{name}" must be lower-case letters, digits and hyphens, e.g. "left-of"')
    c.text(man, "version", "version", 40)
    c.text(man, "requires", "requires", 80)
    phrases = man.get("phrases")
    if not (isinstance(phrases, list) and 0 < len(phrases) <= 32
            and all(isinstance(p, str) and p.strip() and len(p) <= 60 for p in phrases)):
        raise c.fail("phrases", "must be a list of 1 to 32 phrases of at most 60 characters")
    if not isinstance(man.get("description", ""), str) or len(man.get("description", "")) > 500:
        raise c.fail("description", "must be a text of at most 500 characters")

    try:
        frame, anchors = declaration(man)
    except BundleError as e:
        raise c.fail("", str(e).strip()) from None
    feats = c.table(man, "features")
    c.number(feats, "spacing", "[features] spacing", *LIMITS["spacing"])
    c.number(feats, "cd_sectors", "[features] cd_sectors", *LIMITS["cd_sectors"], integer=True)
    c.number(feats, "moving_eps", "[features] moving_eps", *LIMITS["moving_eps"])
    c.number(feats, "max_distance", "[features] max_distance", *LIMITS["max_distance"])
    edges = feats.get("qdc_edges")
    if not (isinstance(edges, list) and 0 < len(edges) <= 16 and all(_is_num(e) and e > 0 for e in edges)
            and all(a < b for a, b in zip(edges, edges[1:], strict=False))):
        raise c.fail("[features] qdc_edges", "must be 1 to 16 increasing positive numbers (block sides)")
    try:
        qsr = QSRConfig.from_dict(feats)
    except BundleError as e:
        raise c.fail("[features]", str(e)) from None
    if (qsr.frame, qsr.anchors) != (frame.name, anchors):
        raise c.fail("", f'declares frame = "{frame.name}", anchors = {anchors} but its progress model was trained '
                         f'with frame "{qsr.frame}", {qsr.anchors} anchor(s): re-train it (l2p-bullet train ... '
                         "--out this folder)")
    names = feature_names(qsr)
    if "names" in feats and feats["names"] != names:
        raise c.fail("[features] names", "do not match the features these settings compute (re-train the bundle)")

    model = c.table(man, "model")
    if model.get("arch", "lstm") != "lstm":
        raise c.fail("[model] arch", f'"{str(model.get("arch"))[:30]}" is not known (known: lstm)')
    n = c.number(model, "n_features", "[model] n_features", 1, 10_000, integer=True)
    if n != len(names):
        raise c.fail(
            "[model] n_features", f"is {n} but [features] computes {len(names)} features (re-train the bundle)"
        )
    c.number(model, "hidden", "[model] hidden", *LIMITS["hidden"], integer=True)
    c.number(model, "ensemble", "[model] ensemble", *LIMITS["ensemble"], integer=True)

    weights = c.table(man, "weights")
    if "progress.safetensors" not in weights:
        raise c.fail("[weights]", 'has no "progress.safetensors" entry')
    for fname, entry in weights.items():
        safe_weight_name(folder, fname)
        if not isinstance(entry, dict) or not isinstance(entry.get("sha256"), str) \
                or not SHA256.fullmatch(entry["sha256"]):
            raise c.fail(f'[weights."{fname}"]', "needs sha256 = 64 lower-case hex digits")
        if "bytes" in entry and not (_is_int(entry["bytes"]) and entry["bytes"] >= 0):
            raise c.fail(f'[weights."{fname}"] bytes', "must be a non-negative integer")

    policy = c.table(man, "policy", required=False)
    if policy:
        _check_policy_section(c, policy, weights)
    judge = man.get("judge")
    if judge is not None and not isinstance(judge, dict):
        raise c.fail("[judge]", "must be a table")
    for key in ("training", "metrics"):
        c.table(man, key, required=False)


def _check_policy_section(c: _Checker, policy: dict, weights: dict) -> None:
    if "planner" in policy and (not isinstance(policy["planner"], str) or policy["planner"] not in PLANNERS
                                or policy["planner"] == "default"):
        raise c.fail("[policy] planner", f"must be one of {', '.join(p for p in PLANNERS if p != 'default')}")
    if "threshold" in policy:
        c.number(policy, "threshold", "[policy] threshold", 0.0, 1.0)
    if "features" in policy and policy["features"] != FEATURES:
        raise c.fail("[policy] features", f"must be {FEATURES} (what the planner computes)")
    file = c.text(policy, "file", "[policy] file", required=False)
    if file is not None and file not in weights:
        raise c.fail("[policy] file", "names a file without a [weights] entry")


def _check_arrays(where: Path, arrays: dict[str, np.ndarray], expected: dict[str, tuple[int, ...]]) -> None:
    missing = sorted(set(expected) - set(arrays))
    if missing:
        raise BundleError(f"{where}: missing tensors {', '.join(missing[:3])}" + (" ..." if len(missing) > 3 else ""))
    for k, shape in expected.items():
        a = arrays[k]
        if tuple(a.shape) != shape:
            raise BundleError(f"{where}: tensor {k} has shape {list(a.shape)}, expected {list(shape)}")
        if a.dtype.kind != "f":
            raise BundleError(f"{where}: tensor {k} holds {a.dtype} values, expected floating point")
        if not np.all(np.isfinite(a)):
            raise BundleError(f"{where}: tensor {k} contains NaN or infinite values")


def check_progress_arrays(where: Path, arrays: dict[str, np.ndarray], model: dict) -> None:
    """The progress ensemble's tensors: every one the manifest's ``[model]`` implies, of its shape, finite."""
    _check_arrays(where, arrays, expected_shapes(ModelConfig.from_dict(model)))


def check_policy_arrays(where: Path, arrays: dict[str, np.ndarray]) -> None:
    """The move policy's tensors (``planning/policy.py``'s MLP): their shapes agree with each other and with
    the planner's feature count, and they are finite."""
    bias = arrays.get("body.0.bias")
    if bias is None or bias.ndim != 1 or not LIMITS["policy_hidden"][0] <= len(bias) <= LIMITS["policy_hidden"][1]:
        raise BundleError(f"{where}: the policy needs a 1-d tensor body.0.bias of its hidden size")
    h = len(bias)
    expected = {"body.0.weight": (h, FEATURES), "body.0.bias": (h,), "body.2.weight": (h, h), "body.2.bias": (h,),
                "mean.weight": (3, h), "mean.bias": (3,), "log_std.weight": (3, h), "log_std.bias": (3,)}
    _check_arrays(where, arrays, expected)


def check_weights(folder: Path, filename: str, arrays: dict[str, np.ndarray], man: dict[str, Any]) -> None:
    """Dispatch on the file: progress weights, policy weights; other files only need finite float tensors."""
    where = folder / filename
    if filename == "progress.safetensors":
        check_progress_arrays(where, arrays, man["model"])
    elif filename == "policy.safetensors" or filename == man.get("policy", {}).get("file"):
        check_policy_arrays(where, arrays)
    else:
        _check_arrays(where, arrays, {k: tuple(a.shape) for k, a in arrays.items()})
