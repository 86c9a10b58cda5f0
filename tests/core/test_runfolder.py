"""Run folders (issue 15, data loss): --force replaces only a run folder l2p-bullet wrote, never a folder
with someone else's files, the current folder or a link; options are checked before the disk is touched;
two runs into one --out give one run and one clear error; an interrupted run is marked and replaceable."""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from interrupt import ctrl_c_as_at_a_terminal

from l2p_bullet.cli import main
from l2p_bullet.core.contracts import dumps_json
from l2p_bullet.core.runfolder import (
    MARKER,
    claim_run_folder,
    finish_run_folder,
    prepare_run_folder,
    run_folder,
    run_folder_state,
)
from l2p_bullet.errors import RunFolderError

CLI = [sys.executable, "-m", "l2p_bullet.cli"]


def one_line_error(result) -> str:
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2 and len(lines) == 1 and lines[0].startswith("error: "), result.output
    assert "Traceback" not in result.output
    return lines[0]


def plan_args(out: Path, *extra: str) -> list[str]:
    return ["plan", "move A past B", "--out", str(out), *extra]


def test_force_never_deletes_a_folder_with_other_files(tmp_path):
    d = tmp_path / "d"
    d.mkdir()
    (d / "thesis.txt").write_text("four years of work")
    line = one_line_error(CliRunner().invoke(main, plan_args(d, "--force")))
    assert "thesis.txt" in line and "--force never deletes" in line
    assert (d / "thesis.txt").read_text() == "four years of work"
    # the same when the foreign file sits inside a real run folder
    run = tmp_path / "run"
    assert CliRunner().invoke(main, plan_args(run)).exit_code == 0
    (run / "notes.md").write_text("mine")
    one_line_error(CliRunner().invoke(main, plan_args(run, "--force")))
    assert (run / "notes.md").read_text() == "mine" and (run / "plan.json").exists()


def test_the_already_exists_error_only_offers_force_for_our_own_runs(tmp_path):
    run = tmp_path / "run"
    assert CliRunner().invoke(main, plan_args(run)).exit_code == 0
    assert run_folder_state(run) == "finished"
    line = one_line_error(CliRunner().invoke(main, plan_args(run)))
    assert "finished run" in line and "--force" in line
    before = (run / MARKER).read_text()
    r = CliRunner().invoke(main, plan_args(run, "--force"))
    assert r.exit_code == 0, r.output
    assert (run / MARKER).read_text() != before  # replaced by the new run
    assert not list(tmp_path.glob(".run.replaced-*"))  # the old one is gone, not left hidden


@pytest.mark.parametrize("where", ["cwd", "parent", "home"])
def test_force_refuses_the_current_folder_its_parents_and_home(tmp_path, monkeypatch, where):
    work = tmp_path / "a" / "b"
    work.mkdir(parents=True)
    (work / "x.txt").write_text("x")
    monkeypatch.chdir(work)
    monkeypatch.setenv("HOME", str(tmp_path / "a"))
    out = {"cwd": ".", "parent": "..", "home": str(tmp_path / "a")}[where]
    line = one_line_error(CliRunner().invoke(main, plan_args(Path(out), "--force")))
    assert "cannot be a run folder" in line
    assert (work / "x.txt").exists()


def test_a_symlinked_out_is_a_one_line_error(tmp_path):
    target = tmp_path / "target"
    target.mkdir()
    (tmp_path / "link").symlink_to(target)
    line = one_line_error(CliRunner().invoke(main, plan_args(tmp_path / "link", "--force")))
    assert "symbolic link" in line
    (tmp_path / "dangling").symlink_to(tmp_path / "nowhere")
    one_line_error(CliRunner().invoke(main, plan_args(tmp_path / "dangling")))


def test_an_option_typo_with_force_keeps_the_previous_run(tmp_path):
    run = tmp_path / "run"
    assert CliRunner().invoke(main, plan_args(run)).exit_code == 0
    files = {p.name: p.read_bytes() for p in run.iterdir()}
    for bad in (["--planner", "beamm"], ["--seed", "-1"], ["--budget", "0"], ["--threshold", "7"]):
        one_line_error(CliRunner().invoke(main, plan_args(run, "--force", *bad)))
        assert {p.name: p.read_bytes() for p in run.iterdir()} == files, bad
    one_line_error(CliRunner().invoke(main, ["perform", "move A past B", "--out", str(run), "--force",
                                             "--planner", "beamm", "--no-render"]))
    assert {p.name: p.read_bytes() for p in run.iterdir()} == files


def test_a_folder_whose_run_is_going_on_is_never_taken(tmp_path):
    out = tmp_path / "busy"
    with run_folder(out, command="test"):
        assert run_folder_state(out) == "running"
        with pytest.raises(RunFolderError, match="being written by another"):
            claim_run_folder(out, force=True)
    assert run_folder_state(out) == "finished"


def test_a_killed_run_is_incomplete_and_replaced_without_force(tmp_path):
    out = tmp_path / "killed"
    claim = claim_run_folder(out, command="test")
    (out / "trajectory.json").write_text("{}")
    claim.release()  # the process died: the kernel drops its lock, nobody marked it finished
    assert run_folder_state(out) == "incomplete"
    with run_folder(out) as again:
        assert again == out and not (out / "trajectory.json").exists()


def test_an_empty_folder_is_used_and_default_names_never_collide(tmp_path):
    (tmp_path / "empty").mkdir()
    assert prepare_run_folder(tmp_path / "empty") == tmp_path / "empty"
    finish_run_folder(tmp_path / "empty")
    names = {prepare_run_folder(None, prefix="p", root=tmp_path / "runs") for _ in range(3)}
    assert len(names) == 3 and all(p.is_dir() for p in names)


def test_a_run_folder_from_before_the_marker_is_still_ours(tmp_path):
    old = tmp_path / "old"
    old.mkdir()
    (old / "summary.json").write_text(json.dumps({"schema": 1, "timings_s": {}, "ok": True}))
    (old / "trajectory.json").write_text("{}")
    assert run_folder_state(old) == "finished"
    with pytest.raises(RunFolderError, match="--force"):
        claim_run_folder(old)
    claim_run_folder(old, force=True).release()


def test_a_failed_run_records_why_and_counts_as_finished(tmp_path):
    out = tmp_path / "failed"
    with pytest.raises(ValueError), run_folder(out):
        raise ValueError("boom")
    summary = json.loads((out / "summary.json").read_text())
    assert summary["ok"] is False and summary["error"] == "boom"
    assert run_folder_state(out) == "finished"


def test_nan_never_reaches_json():
    text = dumps_json({"a": float("nan"), "b": [float("inf"), 1.5], "c": __import__("numpy").float32("nan")})
    assert json.loads(text) == {"a": None, "b": [None, 1.5], "c": None} and "NaN" not in text


def _wait_for(path: Path, proc: subprocess.Popen, timeout: float = 60.0) -> None:
    t0 = time.monotonic()
    while not path.exists():
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() - t0 < timeout, f"{path} never appeared"
        time.sleep(0.01)


@pytest.mark.slow
def test_two_performs_into_one_folder_give_one_run_and_one_clear_error(tmp_path):
    out = tmp_path / "shared"
    cmd = [*CLI, "perform", "move A past B", "--no-render", "--quiet", "--out", str(out)]
    procs = [subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(2)]
    results = [(p.wait(timeout=300), *p.communicate()) for p in procs]
    codes = sorted(r[0] for r in results)
    assert codes == [0, 2], results
    loser = next(r for r in results if r[0] == 2)
    assert len(loser[2].strip().splitlines()) == 1 and loser[2].startswith("error: "), loser
    assert "being written by another" in loser[2] or "finished run" in loser[2]
    summary = json.loads((out / "summary.json").read_text())
    assert summary["ok"] is True and run_folder_state(out) == "finished"


@pytest.mark.slow
def test_ctrl_c_marks_the_run_interrupted_and_the_next_run_replaces_it(tmp_path):
    out = tmp_path / "run"
    cmd = [*CLI, "perform", "move A around B", "--quiet", "--out", str(out)]
    # rendering: the arm executes and records frames for several seconds after plan.json appears
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=ctrl_c_as_at_a_terminal)
    _wait_for(out / "plan.json", proc)  # planned: the arm is about to execute and record
    os.kill(proc.pid, signal.SIGINT)
    code = proc.wait(timeout=120)
    _, err = proc.communicate()
    assert code == 130 and "Traceback" not in err, err
    summary = json.loads((out / "summary.json").read_text())
    assert summary["ok"] is False and summary["failed_stage"] == "interrupted"
    assert summary["interrupted_stage"] in ("plan", "execute")  # plan: between saving plan.json and executing
    assert run_folder_state(out) == "incomplete"
    r = subprocess.run([*cmd, "--no-render"], capture_output=True, text=True, timeout=300)  # no --force needed
    assert r.returncode == 0, r.stderr
    assert json.loads((out / "summary.json").read_text())["ok"] is True


def _perform_like_run(folder: Path) -> Path:
    """A finished run folder of ``perform`` (the real claim, a minimal trajectory), fast enough for CI."""
    with run_folder(folder, command="perform") as out:
        frame = {"t": 0.0, "poses": {"A": [0, 0, 0.025, 0], "B": [0.1, 0, 0.025, 0]}, "ee": [0, 0, 0.3],
                 "grasped": None}
        (out / "trajectory.json").write_text(json.dumps({"frames": [frame], "mover": "A", "anchor": "B", "fps": 30,
                                                         "sentence": "move A past B"}))
        (out / "summary.json").write_text(json.dumps({"schema": 1, "ok": True, "timings_s": {}}))
    return folder


def test_export_force_never_replaces_another_commands_run_nor_an_input(tmp_path):
    """Issue 27.1: ``export runA runB --force`` read as "export two runs" replaced the perform run runB;
    ``export RUNS --format json RUNS/run-b --force`` deleted an input's files."""
    runs = tmp_path / "runs"
    a, b = _perform_like_run(runs / "run-a"), _perform_like_run(runs / "run-b")
    before = {p: p.read_bytes() for p in sorted(runs.rglob("*")) if p.is_file()}
    for args in ([str(a), str(b), "--force"], [str(runs), "--format", "json", str(b), "--force"],
                 [str(a), str(runs), "--force"], [str(a), str(a), "--force"]):
        line = one_line_error(CliRunner().invoke(main, ["export", *args]))
        assert "--force" in line or "input" in line, line
    assert {p: p.read_bytes() for p in sorted(runs.rglob("*")) if p.is_file()} == before
    # the same command may still replace its own previous output
    out = tmp_path / "ex"
    assert CliRunner().invoke(main, ["export", str(a), str(out)]).exit_code == 0
    assert CliRunner().invoke(main, ["export", str(a), str(b), str(out), "--force"]).exit_code == 0
    assert len((out / "episodes.jsonl").read_text().splitlines()) == 2
    # and another command's --force never takes an export folder either
    one_line_error(CliRunner().invoke(main, plan_args(out, "--force")))
    assert (out / "episodes.jsonl").exists()


def test_ctrl_c_in_a_force_run_puts_the_replaced_run_back(tmp_path):
    """Stopping a --force run half-way must not cost the finished run it was replacing (audit, 2026-11-27):
    the old folder waits aside until the new run ends, and comes back if the new one is interrupted."""
    out = _perform_like_run(tmp_path / "run")
    before = (out / "trajectory.json").read_text()
    with pytest.raises(KeyboardInterrupt) as info, run_folder(out, force=True, command="perform") as folder:
        (folder / "plan.json").write_text("{}")  # the new run got as far as its plan
        raise KeyboardInterrupt
    assert "holds the earlier run again" in " ".join(getattr(info.value, "__notes__", ()))
    assert (out / "trajectory.json").read_text() == before and not (out / "plan.json").exists()
    assert run_folder_state(out) == "finished"
    assert [p.name for p in tmp_path.iterdir()] == ["run"]  # nothing left aside


@pytest.mark.parametrize("ending", ["finished", "failed"])
def test_a_force_run_that_ends_replaces_the_old_run_and_leaves_nothing_aside(tmp_path, ending):
    out = _perform_like_run(tmp_path / "run")
    with pytest.raises(ValueError) if ending == "failed" else contextlib.nullcontext():
        with run_folder(out, force=True, command="perform") as folder:
            (folder / "summary.json").write_text(json.dumps({"schema": 1, "ok": True}))
            if ending == "failed":
                raise ValueError("the new run failed")
    assert not (out / "trajectory.json").exists()  # the new run's folder, not the old one's
    assert json.loads((out / "summary.json").read_text())["ok"] is (ending == "finished")
    assert [p.name for p in tmp_path.iterdir()] == ["run"]


@pytest.mark.slow
def test_ctrl_c_during_perform_force_keeps_the_earlier_run(tmp_path):
    out = tmp_path / "run"
    first = subprocess.run([*CLI, "perform", "move A past B", "--quiet", "--no-render", "--out", str(out)],
                           capture_output=True, text=True, timeout=300)
    assert first.returncode == 0, first.stderr
    before = (out / "trajectory.json").read_text()
    cmd = [*CLI, "perform", "move A around B", "--quiet", "--force", "--out", str(out)]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=ctrl_c_as_at_a_terminal)
    _wait_for_new_plan(out, proc)
    os.kill(proc.pid, signal.SIGINT)
    code = proc.wait(timeout=120)
    _, err = proc.communicate()
    assert code == 130 and "Traceback" not in err and "holds the earlier run again" in err, err
    assert (out / "trajectory.json").read_text() == before and run_folder_state(out) == "finished"
    assert [p.name for p in tmp_path.iterdir()] == ["run"]


def _wait_for_new_plan(out: Path, proc: subprocess.Popen, timeout: float = 120.0) -> None:
    """Wait until the new run's folder holds its plan.json (the old run's folder has a trajectory.json)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if (out / "plan.json").exists() and not (out / "trajectory.json").exists():
            return
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.05)
    raise AssertionError("the new run never planned")


def test_no_other_run_can_take_the_folder_while_an_interrupted_one_puts_the_old_run_back(tmp_path, monkeypatch):
    """Review finding (2026-11-27): the restore ran after the new run's lock was released, so a second run could
    claim the folder in between and have it deleted under it. The lock is held until the old run is back."""
    from l2p_bullet.core import runfolder

    out = _perform_like_run(tmp_path / "run")
    taken = []
    restore = runfolder._Claim.restore_replaced

    def meanwhile(self):
        with pytest.raises(RunFolderError, match="being written by another"):
            claim_run_folder(out, command="perform")  # a second run started in that moment
        taken.append(True)
        return restore(self)

    monkeypatch.setattr(runfolder._Claim, "restore_replaced", meanwhile)
    with pytest.raises(KeyboardInterrupt), run_folder(out, force=True, command="perform"):
        raise KeyboardInterrupt
    assert taken and run_folder_state(out) == "finished" and (out / "trajectory.json").exists()


def test_a_run_put_aside_by_a_killed_force_run_is_dropped_by_the_next_claim(tmp_path):
    """A run ended by SIGTERM/SIGKILL never drops what it put aside; the next run into the folder does."""
    out = _perform_like_run(tmp_path / "run")
    aside = tmp_path / ".run.replaced-0badc0de"
    aside.mkdir()
    (aside / "trajectory.json").write_text("{}")
    (tmp_path / ".other.replaced-1").mkdir()  # another folder's: left alone
    with run_folder(out, force=True, command="perform") as folder:
        (folder / "summary.json").write_text(json.dumps({"schema": 1, "ok": True}))
    assert sorted(p.name for p in tmp_path.iterdir()) == [".other.replaced-1", "run"]


def test_an_earlier_run_that_could_not_be_put_back_is_never_dropped_later(tmp_path, monkeypatch):
    """Review finding: the note said 'kept in .run.replaced-...', and the next claim dropped it as stale. It is
    renamed .run.kept-... (no claim drops that), and the note names it."""
    out = _perform_like_run(tmp_path / "run")
    real_rename = Path.rename

    def failing(self, target):
        if ".replaced-" in self.name and Path(target).name == "run":
            raise OSError("simulated")
        return real_rename(self, target)

    monkeypatch.setattr(Path, "rename", failing)
    with pytest.raises(KeyboardInterrupt) as info, run_folder(out, force=True, command="perform"):
        raise KeyboardInterrupt
    monkeypatch.setattr(Path, "rename", real_rename)
    kept = [p for p in tmp_path.iterdir() if ".kept-" in p.name]
    assert len(kept) == 1 and str(kept[0]) in " ".join(info.value.__notes__)
    with run_folder(out, force=True, command="perform") as folder:
        (folder / "summary.json").write_text(json.dumps({"schema": 1, "ok": True}))
    assert kept[0].is_dir() and (kept[0] / "trajectory.json").exists()


def test_the_stale_runs_dropped_are_exactly_this_folders(tmp_path):
    """'.a.replaced-x.replaced-<hex>' belongs to a folder named 'a.replaced-x', not to 'a' (review finding)."""
    out = _perform_like_run(tmp_path / "a")
    other = tmp_path / ".a.replaced-x.replaced-0123abcd"
    other.mkdir()
    with run_folder(out, force=True, command="perform") as folder:
        (folder / "summary.json").write_text(json.dumps({"schema": 1, "ok": True}))
    assert other.is_dir()
