"""Bundles: the shipped ones load and score; bad ones fail with clear BundleErrors; write_weights works."""

from __future__ import annotations

import shutil
import tomllib
from pathlib import Path

import numpy as np
import pytest
import tomli_w

from l2p_bullet.core.vocabulary import ACTIONS
from l2p_bullet.errors import BundleError, UnknownActionError
from l2p_bullet.plugins.bundle import (
    MANIFEST,
    POLICY_FILE,
    PROGRESS_FILE,
    builtin_bundle_dir,
    load_bundle,
    version_satisfies,
    write_weights,
)
from l2p_bullet.plugins.registry import locate


@pytest.fixture
def bundle_copy(tmp_path: Path) -> Path:
    dst = tmp_path / "around"
    shutil.copytree(builtin_bundle_dir("around"), dst)
    return dst


def _edit_manifest(folder: Path, **changes) -> None:
    man = tomllib.loads((folder / MANIFEST).read_text())
    for k, v in changes.items():
        if v is None:
            man.pop(k, None)
        else:
            man[k] = v
    (folder / MANIFEST).write_text(tomli_w.dumps(man))


@pytest.mark.parametrize("action", ACTIONS)
def test_builtin_bundles_load_and_score(action):
    b = load_bundle(builtin_bundle_dir(action))
    assert b.name == action and b.phrases and b.manifest["judge"] == {"rules": action}
    assert {"features", "model", "training", "metrics"} <= set(b.manifest)
    model = b.progress_model()
    mover = np.column_stack([np.linspace(0.4, 0.2, 20), np.zeros(20), np.zeros(20)])
    curve = model.curve(mover, np.zeros(3), 0.05)
    assert curve.shape == (20,) and np.all((curve >= 0) & (curve <= 1))


def test_resolve_action_by_name_alias_and_folder(bundle_copy):
    name, folder = locate("next_to")
    assert name == "next-to" and folder.resolve() == builtin_bundle_dir("next-to").resolve()
    assert locate(str(bundle_copy)) == ("around", bundle_copy)
    with pytest.raises(UnknownActionError) as e:
        locate("arround")
    assert e.value.name == "arround" and set(ACTIONS) <= set(e.value.known) and "Did you mean" in str(e.value)


def test_missing_folder_manifest_and_weights(tmp_path, bundle_copy):
    with pytest.raises(BundleError, match="does not exist"):
        load_bundle(tmp_path / "nope")
    (tmp_path / "empty").mkdir()
    with pytest.raises(BundleError, match="no manifest.toml"):
        load_bundle(tmp_path / "empty")
    (bundle_copy / PROGRESS_FILE).unlink()
    with pytest.raises(BundleError, match="missing"):
        load_bundle(bundle_copy)


def test_tampered_weights_are_refused(bundle_copy):
    data = bytearray((bundle_copy / PROGRESS_FILE).read_bytes())
    data[-5] ^= 0xFF
    (bundle_copy / PROGRESS_FILE).write_bytes(bytes(data))
    with pytest.raises(BundleError, match="sha256"):
        load_bundle(bundle_copy)


def test_incompatible_manifest(bundle_copy):
    _edit_manifest(bundle_copy, schema=99)
    with pytest.raises(BundleError, match="schema 99"):
        load_bundle(bundle_copy)
    _edit_manifest(bundle_copy, schema=1, requires=">=2.0")
    with pytest.raises(BundleError, match="requires l2p-bullet >=2.0"):
        load_bundle(bundle_copy)
    _edit_manifest(bundle_copy, requires=">=0.1,<1.0", phrases=None)
    with pytest.raises(BundleError, match="missing phrases"):
        load_bundle(bundle_copy)
    (bundle_copy / MANIFEST).write_text("name = [unclosed")
    with pytest.raises(BundleError, match="not valid TOML"):
        load_bundle(bundle_copy)


@pytest.mark.parametrize("value", [[], {"a": 1}, 3])
def test_a_policy_file_that_is_not_a_name_is_a_clear_error(bundle_copy, value):
    # found by tests/cli/test_fuzz.py: a list there was looked up in [weights] and raised a TypeError
    man = tomllib.loads((bundle_copy / MANIFEST).read_text())
    man["policy"]["file"] = value
    (bundle_copy / MANIFEST).write_text(tomli_w.dumps(man))
    with pytest.raises(BundleError, match=r"\[policy\] file must be a non-empty text"):
        load_bundle(bundle_copy)


def test_wrong_shape_is_refused(bundle_copy):
    man = tomllib.loads((bundle_copy / MANIFEST).read_text())
    man["model"]["hidden"] = man["model"]["hidden"] + 1
    (bundle_copy / MANIFEST).write_text(tomli_w.dumps(man))
    with pytest.raises(BundleError, match="has shape"):
        load_bundle(bundle_copy)


def test_write_weights_adds_a_policy(bundle_copy):
    # start from a bundle without a policy (the shipped ones have one since the planning issue)
    man = tomllib.loads((bundle_copy / MANIFEST).read_text())
    man["weights"].pop(POLICY_FILE, None)
    man.pop("policy", None)
    (bundle_copy / MANIFEST).write_text(tomli_w.dumps(man))
    (bundle_copy / POLICY_FILE).unlink(missing_ok=True)
    assert load_bundle(bundle_copy).policy_arrays() is None
    from l2p_bullet.planning.policy import FEATURES

    h = 8
    arrays = {"body.0.weight": np.zeros((h, FEATURES), np.float32), "body.0.bias": np.zeros(h, np.float32),
              "body.2.weight": np.zeros((h, h), np.float32), "body.2.bias": np.zeros(h, np.float32),
              "mean.weight": np.arange(3.0 * h, dtype=np.float32).reshape(3, h), "mean.bias": np.zeros(3, np.float32),
              "log_std.weight": np.zeros((3, h), np.float32), "log_std.bias": np.zeros(3, np.float32)}
    write_weights(bundle_copy, POLICY_FILE, arrays, "policy", {"planner": "reinforce", "steps": 20})
    b = load_bundle(bundle_copy)
    assert b.manifest["policy"] == {"planner": "reinforce", "steps": 20}
    got = b.policy_arrays()
    assert set(got) == set(arrays) and np.array_equal(got["mean.weight"], arrays["mean.weight"])
    # tampering with the policy is caught too, and the progress weights are untouched
    (bundle_copy / POLICY_FILE).write_bytes(b"junk")
    with pytest.raises(BundleError, match=POLICY_FILE):
        load_bundle(bundle_copy)


def test_weights_are_never_unpickled(bundle_copy):
    """A pickle renamed to .safetensors with a matching digest still fails as a safetensors file."""
    import hashlib
    import pickle

    (bundle_copy / PROGRESS_FILE).write_bytes(pickle.dumps({"x": 1}))
    man = tomllib.loads((bundle_copy / MANIFEST).read_text())
    man["weights"][PROGRESS_FILE]["sha256"] = hashlib.sha256((bundle_copy / PROGRESS_FILE).read_bytes()).hexdigest()
    (bundle_copy / MANIFEST).write_text(tomli_w.dumps(man))
    with pytest.raises(BundleError, match="safetensors"):
        load_bundle(bundle_copy)


def test_version_ranges():
    assert version_satisfies("0.1.0", ">=0.1,<1.0")
    assert not version_satisfies("1.0.0", ">=0.1,<1.0")
    assert version_satisfies("0.1.0", "==0.1")
    with pytest.raises(BundleError, match=r'cannot read the version range "~0\.1" \(use e\.g\. ">=0\.1,<1\.0"\)'):
        version_satisfies("0.1.0", "~0.1")


def test_update_manifest_merges_a_section_and_keeps_the_bundle_valid(bundle_copy):
    from l2p_bullet.plugins.bundle import update_manifest

    update_manifest(bundle_copy, "metrics", {"graded_spearman": 0.5})
    b = load_bundle(bundle_copy)
    assert b.manifest["metrics"]["graded_spearman"] == 0.5
    assert "train_loss" in b.manifest["metrics"]  # merged, not replaced
    with pytest.raises(BundleError, match="weights"):
        update_manifest(bundle_copy, "weights", {})


@pytest.mark.parametrize("action", ["closer", "past"])
def test_retraining_a_bundle_in_place_keeps_its_planner_threshold(tmp_path, action):
    """``make bundles`` re-trains each built-in into its own folder; the planner thresholds chosen on chain
    starts (docs/planning.md) live in the manifest's ``[policy]`` and must survive that."""
    from l2p_bullet.planning import THRESHOLD
    from l2p_bullet.plugins.bundle import write_progress_bundle
    from l2p_bullet.progress.config import ModelConfig
    from l2p_bullet.progress.features import QSRConfig

    folder = tmp_path / action
    shutil.copytree(builtin_bundle_dir(action), folder)
    shipped = load_bundle(folder)
    threshold = shipped.manifest["policy"]["threshold"]
    assert threshold > THRESHOLD  # closer 0.97, past 0.99: above the planners' default
    write_progress_bundle(
        folder,
        action,
        shipped.arrays(PROGRESS_FILE),
        ModelConfig.from_dict(shipped.manifest["model"]),
        QSRConfig.from_dict(shipped.manifest["features"]),
        training={"seed": 0},
        metrics={},
    )
    again = load_bundle(folder)
    assert again.manifest["policy"]["threshold"] == threshold and again.manifest["policy"]["file"] == POLICY_FILE
