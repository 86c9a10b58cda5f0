"""``evaluate`` on a process pool and on Ray: parallel equals serial, nothing recorded is lost, crashes are rows."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest
from interrupt import ctrl_c_as_at_a_terminal

from l2p_bullet.errors import EvaluationError
from l2p_bullet.evaluate.results import ResultsStore, comparable
from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows

TEN = EvaluationConfig(actions=["closer", "past"], scenes=5, seed=3)  # 5 scenes x 2 actions = 10 runs


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    out = tmp_path_factory.mktemp("eval") / "serial"
    evaluate(TEN, out, workers=1, progressbar=False)
    return [comparable(r) for r in load_rows(out)]


def test_rows_hold_the_run_and_every_actions_verdict(serial):
    assert len(serial) == 10
    assert [r["idx"] for r in serial] == list(range(10))
    for r in serial:
        assert r["error"] is None, r["error"]
        assert r["sentence"] in ("move A closer to B", "move A past B")
        assert set(r["judged"]) == set(r["scored"]) >= {"closer", "away", "next-to", "past", "around"}
        # the row's own verdict is its action's judge on the same trajectory
        assert bool(r["success"]) == r["judged"][r["action"]]["success"]
        assert r["scored"][r["action"]] == pytest.approx(r["final_progress"], abs=1e-5)
        assert r["max_deviation_m"] < 0.005 and r["anchor_displacement_m"] < 0.002


@pytest.mark.slow(40)  # a local Ray cluster started
def test_two_workers_and_ray_local_give_the_serial_rows(serial, tmp_path):
    evaluate(TEN, tmp_path / "pool", workers=2, progressbar=False)
    assert [comparable(r) for r in load_rows(tmp_path / "pool")] == serial
    pytest.importorskip("ray")
    s = evaluate(TEN, tmp_path / "ray", workers=2, ray="local", progressbar=False)
    assert s.backend == "ray"
    rows = load_rows(tmp_path / "ray")
    assert [comparable(r) for r in rows] == serial
    assert len({r["worker"] for r in rows}) == 2  # both actors worked


@pytest.mark.slow
def test_resume_skips_recorded_runs_and_refuses_other_settings(serial, tmp_path):
    out = tmp_path / "e"
    cfg = EvaluationConfig(actions=["closer", "past"], scenes=2, seed=3)
    evaluate(cfg, out, workers=0, progressbar=False)
    with sqlite3.connect(out / "results.sqlite") as db:  # as if the last two runs had been in flight
        db.execute("DELETE FROM runs WHERE idx >= 2")
    with pytest.raises(EvaluationError):
        evaluate(cfg, out, workers=0, progressbar=False)  # not without --resume: nothing is overwritten
    with pytest.raises(EvaluationError) as e:
        evaluate(EvaluationConfig(actions=["closer"], scenes=2, seed=3), out, resume=True, workers=0, progressbar=False)
    assert "actions" in str(e.value)
    s = evaluate(None, out, resume=True, workers=0, progressbar=False)
    assert (s.total, s.skipped, s.ran) == (4, 2, 2)
    assert [comparable(r) for r in load_rows(out)] == serial[:4]


def test_a_failing_run_is_a_row_and_the_evaluation_goes_on(tmp_path):
    f = tmp_path / "s.jsonl"
    # A and B at opposite ends of the workspace: no room to go one block farther (refused up front)
    f.write_text('{"id": "no-room", "objects": [{"name": "A", "color": "red", "size": 0.05, "xy": [0.0, -0.32]},'
                 ' {"name": "B", "color": "green", "size": 0.05, "xy": [0.0, 0.32]}]}\n'
                 '{"id": "fine", "objects": [{"name": "A", "color": "red", "size": 0.05, "xy": [0.15, 0.0]},'
                 ' {"name": "B", "color": "green", "size": 0.05, "xy": [0.0, 0.0]}]}\n')
    evaluate(EvaluationConfig(actions=["away"], scene_file=str(f), mode="plan"), tmp_path / "e", workers=0,
             progressbar=False)
    bad, good = load_rows(tmp_path / "e")
    assert bad["error_type"] == "InfeasibleError" and "no room" in bad["error"] and bad["success"] == 0
    assert good["error"] is None and good["success"] == 1 and good["mode"] == "plan"


@pytest.mark.slow
def test_a_killed_worker_costs_only_its_run(tmp_path):
    """SIGKILL a busy worker: its run is a WorkerDied row, a new worker takes over, --retry-errors redoes it."""
    import multiprocessing

    from l2p_bullet.evaluate import pool
    from l2p_bullet.evaluate.tasks import make_tasks

    cfg = EvaluationConfig(actions=["closer", "past"], scenes=3, seed=3)
    tasks = make_tasks(cfg.scene_set(), cfg.actions)
    rows: list[dict] = []
    killed: list[int] = []

    def on_row(row: dict) -> None:
        rows.append(row)
        if not killed:
            me = int(row["worker"].rsplit(":", 1)[1])
            other = [p for p in multiprocessing.active_children() if p.pid != me]
            killed.append(other[0].pid)
            os.kill(other[0].pid, signal.SIGKILL)

    pool.run_pool(tasks, 2, on_row)
    assert len(rows) == len(tasks)
    died = [r for r in rows if r["error_type"] == "WorkerDied"]
    assert len(died) == 1 and "exit code -9" in died[0]["error"]
    assert sum(r["error"] is None for r in rows) == len(tasks) - 1


@pytest.mark.slow
def test_ctrl_c_keeps_what_was_recorded_and_resume_finishes(tmp_path):
    out = tmp_path / "e"
    cmd = [sys.executable, "-m", "l2p_bullet.cli", "evaluate", "--actions", "closer", "--scenes", "8",
           "--workers", "2", "--out", str(out), "--quiet"]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         preexec_fn=ctrl_c_as_at_a_terminal)
    deadline = time.time() + 120
    while time.time() < deadline and _count(out) < 2:
        time.sleep(0.2)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    n = _count(out)
    assert 2 <= n < 8 and "--resume" in err
    r = subprocess.run([sys.executable, "-m", "l2p_bullet.cli", "evaluate", "--out", str(out), "--resume",
                        "--workers", "2", "--quiet", "--json"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert _count(out) == 8
    with ResultsStore(out) as store:
        assert len(store.recorded(with_errors=False)) == 8


def _count(out: Path) -> int:
    if not (out / "results.sqlite").exists():
        return 0
    try:
        with sqlite3.connect(out / "results.sqlite", timeout=5) as db:
            return db.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
    except sqlite3.OperationalError:
        return 0


def test_pool_workers_start_with_one_blas_thread_unless_the_user_chose(monkeypatch):
    """W workers for W cores: numpy's BLAS in each worker runs one thread (it made 2 workers only 1.44x one)."""
    import os

    from l2p_bullet.evaluate.pool import THREAD_VARIABLES, _one_thread_per_worker

    monkeypatch.delenv("OMP_NUM_THREADS", raising=False)
    monkeypatch.setenv("MKL_NUM_THREADS", "3")
    with _one_thread_per_worker():
        assert os.environ["OMP_NUM_THREADS"] == "1" and os.environ["MKL_NUM_THREADS"] == "3"
    assert "OMP_NUM_THREADS" not in os.environ and os.environ["MKL_NUM_THREADS"] == "3"
    assert "OPENBLAS_NUM_THREADS" in THREAD_VARIABLES


@pytest.mark.slow
def test_a_second_resume_of_a_folder_being_written_is_refused(tmp_path):
    """Issue 27.7: two concurrent ``evaluate --out X --resume`` both ran every remaining task."""
    out = tmp_path / "e"
    # a fresh evaluation stopped after its first row, then resumed twice at once (400 tasks: the first resume
    # must still be running when the second starts, also on a quiet machine where a plan takes ~50 ms)
    cmd = [sys.executable, "-m", "l2p_bullet.cli", "evaluate", "--actions", "closer,past", "--scenes", "200",
           "--plan-only", "--workers", "0", "--out", str(out), "--quiet"]
    first = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             preexec_fn=ctrl_c_as_at_a_terminal)
    deadline = time.time() + 120
    while time.time() < deadline and _count(out) < 1:
        time.sleep(0.05)
    first.send_signal(signal.SIGINT)
    first.communicate(timeout=60)
    resume = [sys.executable, "-m", "l2p_bullet.cli", "evaluate", "--out", str(out), "--resume", "--workers", "0",
              "--quiet"]
    stopped_at = _count(out)  # the first run may have recorded more than one row before it stopped
    # Ctrl-C as at a terminal: with the SIGINT a background test run hands down, the first resume ignored the
    # interrupt in `finally` and ran all ~400 tasks to their end (~40 s of the suite)
    a = subprocess.Popen(resume, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         preexec_fn=ctrl_c_as_at_a_terminal)
    try:  # a new row: the first resume holds the folder's lock (rows are written only under it)
        while time.time() < deadline and _count(out) <= stopped_at and a.poll() is None:
            time.sleep(0.05)
        assert a.poll() is None, "the first resume ended before the second started"
        b = subprocess.run(resume, capture_output=True, text=True, timeout=120)
        assert b.returncode == 2 and "another l2p-bullet evaluate" in b.stderr, (b.stdout, b.stderr)
        assert "Traceback" not in b.stderr
    finally:
        a.send_signal(signal.SIGINT)
        _, err = a.communicate(timeout=60)
    assert a.returncode == 130 and "--resume" in err, err  # stopped by the Ctrl-C, not run to its end
    with pytest.raises(EvaluationError, match="already holds"):  # and a fresh start still is refused
        evaluate(EvaluationConfig(actions=["closer"], scenes=1), out, workers=0, progressbar=False)
