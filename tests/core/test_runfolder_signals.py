"""A ``--force`` run stopped by SIGTERM, SIGHUP or SIGKILL never costs the run it was replacing: SIGTERM
and SIGHUP put it back as Ctrl-C does; after SIGKILL the next command into the folder puts it back before
anything else touches it (a plain run then refuses the finished run, it does not delete it)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from l2p_bullet.core.runfolder import claim_run_folder, run_folder, run_folder_state
from l2p_bullet.errors import RunFolderError

CLI = [sys.executable, "-m", "l2p_bullet.cli"]


def _finished_run(folder: Path, mark: str = "old") -> Path:
    with run_folder(folder, command="perform") as out:
        (out / "trajectory.json").write_text(json.dumps({"frames": [], "mark": mark}))
        (out / "summary.json").write_text(json.dumps({"schema": 1, "ok": True, "timings_s": {}}))
    return folder


def _killed_force_run(out: Path) -> None:
    """What a ``--force`` run killed by SIGKILL leaves: the finished run set aside, a partial folder."""
    claim = claim_run_folder(out, force=True, command="perform", keep_replaced=True)
    (claim.path / "plan.json").write_text("{}")
    claim.release()  # the kernel drops a dead process's lock; nothing restores or drops what lies aside


def _mark(out: Path) -> str:
    return json.loads((out / "trajectory.json").read_text())["mark"]


def test_a_plain_run_after_a_killed_force_run_refuses_the_earlier_run_instead_of_deleting_it(tmp_path):
    out = _finished_run(tmp_path / "keep")
    _killed_force_run(out)
    assert any(p.name.startswith(".keep.replaced-") for p in tmp_path.iterdir())
    with pytest.raises(RunFolderError) as info:
        claim_run_folder(out, command="perform")  # no --force
    assert "finished run" in str(info.value) and "is back" in str(info.value)
    assert _mark(out) == "old" and run_folder_state(out) == "finished"
    assert [p.name for p in tmp_path.iterdir()] == ["keep"]  # put back, nothing left aside


def test_a_reader_skipping_the_killed_run_says_where_the_earlier_one_is(tmp_path):
    from l2p_bullet.core.folders import unfinished

    out = _finished_run(tmp_path / "keep")
    _killed_force_run(out)
    note = unfinished(out)
    assert note is not None and ".keep.replaced-" in note and "puts it back" in note


def test_a_force_run_after_a_killed_one_sets_the_earlier_run_aside_again_and_ctrl_c_still_restores_it(tmp_path):
    out = _finished_run(tmp_path / "keep")
    _killed_force_run(out)
    with pytest.raises(KeyboardInterrupt), run_folder(out, force=True, command="perform") as folder:
        (folder / "plan.json").write_text("{}")
        raise KeyboardInterrupt
    assert _mark(out) == "old" and [p.name for p in tmp_path.iterdir()] == ["keep"]


def test_a_run_set_aside_beside_a_folder_of_someone_else_is_refused_and_nothing_is_deleted(tmp_path):
    out = _finished_run(tmp_path / "keep")
    _killed_force_run(out)
    (out / "thesis.txt").write_text("mine")  # the folder is no run folder of ours any more
    parked = [p for p in tmp_path.iterdir() if p.name.startswith(".keep.")]
    for force in (False, True):
        with pytest.raises(RunFolderError, match="set aside"):
            claim_run_folder(out, force=force, command="perform")
    assert (out / "thesis.txt").read_text() == "mine" and all(p.is_dir() for p in parked)
    assert _mark(parked[0]) == "old"


def test_a_replacement_that_finished_before_it_was_killed_stands(tmp_path):
    out = _finished_run(tmp_path / "keep")
    claim = claim_run_folder(out, force=True, command="perform", keep_replaced=True)
    (claim.path / "trajectory.json").write_text(json.dumps({"frames": [], "mark": "new"}))
    (claim.path / "summary.json").write_text(json.dumps({"schema": 1, "ok": True, "timings_s": {}}))
    claim.finish()
    claim.release()  # killed between finishing and dropping the old run
    with pytest.raises(RunFolderError, match="finished run"):
        claim_run_folder(out, command="perform")
    assert _mark(out) == "new" and [p.name for p in tmp_path.iterdir()] == ["keep"]


def _default_signals() -> None:
    for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):  # a background test run may ignore them
        signal.signal(s, signal.SIG_DFL)


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_sigterm_and_sighup_stop_a_force_run_as_ctrl_c_does(tmp_path, signum):
    out = tmp_path / "keep"
    first = subprocess.run(
        [*CLI, "perform", "move A past B", "--no-render", "--quiet", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert first.returncode == 0, first.stderr
    before = {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()}
    proc = subprocess.Popen([*CLI, "perform", "move A around B", "--quiet", "--force", "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=_default_signals)
    t0 = time.monotonic()
    while not (out / "plan.json").exists() or (out / "plan.json").read_bytes() == before.get("plan.json"):
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() - t0 < 120, "the perform run never planned"
        time.sleep(0.02)
    os.kill(proc.pid, signum)
    code = proc.wait(timeout=120)
    _, err = proc.communicate()
    assert code == 128 + signum, err
    assert "Traceback" not in err and f"interrupted ({signal.Signals(signum).name})" in err, err
    assert "holds the earlier run again" in err, err
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()} == before
    assert [p.name for p in tmp_path.iterdir()] == ["keep"]


@pytest.mark.parametrize("stop", ["ctrl-c", "sigterm"])
def test_an_interrupted_run_says_what_stopped_it(tmp_path, stop):
    from l2p_bullet.cli import Stopped

    exc = KeyboardInterrupt() if stop == "ctrl-c" else Stopped(signal.SIGTERM)
    with pytest.raises(KeyboardInterrupt), run_folder(tmp_path / "run", command="perform"):
        raise exc
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["failed_stage"] == "interrupted"
    assert summary["error"] == f"interrupted ({'Ctrl-C' if stop == 'ctrl-c' else 'SIGTERM'}) before the run finished"
