"""What train, train-policy, improve and review --import-original say and leave behind: Ctrl-C ends in one
line with a hint and removes (or never writes) a copy that would look finished, progress lines give a
total and an ETA, the last lines say what to run next, and counts are pluralised. Tiny settings: each
test runs in a few seconds on 2 cores."""

from __future__ import annotations

import hashlib
import re
import shlex
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

import l2p_bullet.learning.improve as improve_mod
import l2p_bullet.learning.train_policy as train_policy_mod
import l2p_bullet.learning.train_progress as train_progress_mod
from l2p_bullet.cli import main
from l2p_bullet.commands.learn import _improve_command
from l2p_bullet.errors import BundleError
from l2p_bullet.learning.feedback_targets import FeedbackConfig
from l2p_bullet.plugins.bundle import builtin_bundle_dir

TINY_POLICY = ("--iterations", "2", "--episodes", "2")


def cli(*args: str):
    return CliRunner().invoke(main, list(args))


def last_line(result) -> str:
    return result.output.strip().splitlines()[-1]


def digests(folder: Path) -> dict[str, str]:
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def interrupt(*_a, **_k):
    raise KeyboardInterrupt


# --- train-policy ----------------------------------------------------------------------------------
def test_train_policy_interrupted_removes_its_copy_and_the_same_command_then_works(tmp_path, monkeypatch):
    out = tmp_path / "pol"
    with monkeypatch.context() as m:
        m.setattr(train_policy_mod, "rollout", interrupt)  # Ctrl-C in the first training step
        r = cli("train-policy", "around", *TINY_POLICY, "--out", str(out))
    assert r.exit_code == 130 and last_line(r) == "interrupted; nothing was written", r.output
    assert not out.exists()  # the untrained copy is gone: it looked finished and blocked this --out
    r = cli("train-policy", "around", *TINY_POLICY, "--out", str(out))
    assert r.exit_code == 0, r.output
    assert (out / "policy.safetensors").is_file()
    assert re.search(r"^around policy: iter    1  final progress [0-9.]+ \[#+\] 2/2 iterations .* ETA 0s$",
                     r.output, re.M), r.output
    assert last_line(r).startswith(f"next: l2p-bullet score {out} MOTION or l2p-bullet recognize MOTION --action {out}")


def test_train_policy_failure_removes_its_copy(tmp_path, monkeypatch):
    def fail(*_a, **_k):
        raise BundleError("the model could not be read")

    monkeypatch.setattr(train_policy_mod, "rollout", fail)
    r = cli("train-policy", "around", *TINY_POLICY, "--out", str(tmp_path / "pol"))
    assert r.exit_code == 2 and "could not be read" in r.output, r.output
    assert not (tmp_path / "pol").exists()


def test_train_policy_interrupted_in_place_leaves_the_bundle_and_says_so(tmp_path, monkeypatch):
    bundle = tmp_path / "around"
    shutil.copytree(builtin_bundle_dir("around"), bundle, ignore=shutil.ignore_patterns("__pycache__"))
    before = digests(bundle)
    monkeypatch.setattr(train_policy_mod, "rollout", interrupt)
    r = cli("train-policy", "around", *TINY_POLICY, "--bundle", str(bundle))
    assert r.exit_code == 130 and last_line(r) == f"interrupted; the bundle in {bundle} is unchanged", r.output
    assert digests(bundle) == before


# --- train -----------------------------------------------------------------------------------------
def test_train_says_what_to_run_next(tmp_path):
    from l2p_bullet.data.demos import session_files

    out = tmp_path / "closer"
    r = cli("train", "closer", "--demos", str(session_files("closer")[0]), "--ensemble", "1", "--epochs", "1",
            "--out", str(out))
    assert r.exit_code == 0, r.output
    lines = r.output.strip().splitlines()
    assert lines[-2].startswith(f"wrote {out} (") and lines[-2].endswith(" sequences)"), r.output
    assert lines[-1] == (f"next: l2p-bullet train-policy closer --bundle {out} (its move policy), then "
                         f"l2p-bullet score {out} MOTION or l2p-bullet recognize MOTION --action {out}")


# --- improve ---------------------------------------------------------------------------------------
@pytest.mark.slow
def test_improve_interrupted_while_fine_tuning_leaves_no_bundle_and_says_how_to_go_on(tmp_path, monkeypatch):
    out = tmp_path / "imp"
    rd = out / "round-1"
    seen = {}

    def stopped(*_a, **_k):
        seen["bundle"], seen["part"] = (rd / "bundle").exists(), (rd / "bundle.part").is_dir()
        raise KeyboardInterrupt

    monkeypatch.setattr(improve_mod, "FeedbackConfig", lambda: FeedbackConfig(epochs=1))  # tiny
    with monkeypatch.context() as m:
        m.setattr(train_progress_mod, "train_action", stopped)
        r = cli("improve", "past", "--rounds", "1", "--scenes", "1", "--out", str(out))
    assert r.exit_code == 130, r.output
    again = f"l2p-bullet improve past --rounds 1 --scenes 1 --out {out}"
    assert last_line(r) == f"interrupted; finished rounds are kept in {out}; continue with: {again}", r.output
    assert "round 1/1: performing past on 1 scene with" in r.output and "1 graded run (mean grade" in r.output
    assert re.search(r"^  performed 1/1 run \(\d+s, ETA 0s\)$", r.output, re.M), r.output
    # the copy being fine-tuned was never named bundle/, and is gone: nothing looks like a finished round
    assert seen == {"bundle": False, "part": True}
    assert not (rd / "bundle").exists() and not (rd / "bundle.part").exists() and not (rd / "metrics.json").exists()

    r = cli(*shlex.split(again)[1:])  # the hint, as given: resumes the round
    assert r.exit_code == 0, r.output
    assert "reusing 1 run performed before" in r.output and "1 graded motion (1 from the rounds" in r.output
    assert re.search(r"^  fine-tuned 1/\d+ ensemble members \(\d+s, ETA \d+s\)$", r.output, re.M), r.output
    assert (rd / "metrics.json").is_file() and (rd / "bundle" / "manifest.toml").is_file()
    assert not (rd / "bundle.part").exists()
    lines = r.output.strip().splitlines()
    assert lines[-2].startswith("round 1: success") and ", 1 grade (mean " in lines[-2], r.output
    assert lines[-1].startswith(f"next: l2p-bullet score {rd / 'bundle'} MOTION") and "train-policy past" in lines[-1]


def test_improve_refits_a_round_whose_bundle_has_no_metrics(tmp_path, monkeypatch):
    """A bundle/ without metrics.json (an older l2p-bullet stopped there) is never taken for a finished one."""
    out = tmp_path / "imp"
    rd = out / "round-1"
    calls = []

    def stopped(*_a, **_k):
        calls.append((rd / "bundle").exists())
        raise KeyboardInterrupt

    monkeypatch.setattr(train_progress_mod, "train_action", stopped)
    assert cli("improve", "past", "--rounds", "1", "--scenes", "1", "--out", str(out)).exit_code == 130
    shutil.copytree(builtin_bundle_dir("past"), rd / "bundle", ignore=shutil.ignore_patterns("__pycache__"))
    r = cli("improve", "past", "--rounds", "1", "--scenes", "1", "--out", str(out))
    assert r.exit_code == 130 and "already done" not in r.output, r.output
    assert calls == [False, False]  # fine-tuned again, the stale bundle/ removed first


@pytest.mark.parametrize("kw, expect", [
    ({}, "l2p-bullet improve past --rounds 2 --scenes 10 --out runs/improve/past"),
    ({"judge": "my reviews.sqlite", "feedback": ("original", "a.csv"), "seed": 3, "force": True},
     "l2p-bullet improve past --rounds 2 --scenes 10 --judge 'my reviews.sqlite' --feedback original "
     "--feedback a.csv --out runs/improve/past --seed 3"),  # never --force: it would start over
])
def test_improve_continue_command_repeats_the_settings(kw, expect):
    args = {"judge": "rules", "feedback": (), "seed": 0, "force": False} | kw
    assert _improve_command("past", 2, 10, out=Path("runs/improve/past"), **args) == expect


# --- review --import-original ----------------------------------------------------------------------
def test_import_original_points_to_the_report(tmp_path):
    db = tmp_path / "my reviews.sqlite"
    r = cli("review", "--import-original", "--db", str(db))
    assert r.exit_code == 0, r.output
    assert last_line(r) == f"next: l2p-bullet report --db {shlex.quote(str(db))}"
