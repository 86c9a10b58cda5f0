"""Which run folders ``l2p-bullet review`` serves: never one whose run did not finish writing.

Audit (2026-11-28): a rendered perform stopped with Ctrl-C (an interrupted summary.json, no video, a
0-byte frame) was served for grading like any other run.
"""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from review_fixtures import run_folder  # noqa: F401 - fixture

from l2p_bullet.cli import main
from l2p_bullet.errors import ReviewError
from l2p_bullet.review.runs import find_runs


def _interrupt(run) -> None:
    """Make ``run`` look as a Ctrl-C during rendering leaves it."""
    (run / "summary.json").write_text(json.dumps({"schema": 1, "ok": False, "failed_stage": "interrupted",
                                                  "error": "interrupted (Ctrl-C) before the run finished"}))
    for video in run.glob("video.*"):
        video.unlink()
    (run / "frames" / f"{len(list((run / 'frames').glob('*.png'))):04d}.png").write_bytes(b"")


def test_unfinished_runs_are_skipped_with_a_note_and_a_failed_action_is_served(run_folder):  # noqa: F811
    stopped, failed, broken = run_folder / "run0", run_folder / "run1", run_folder / "run3"
    _interrupt(stopped)
    summary = json.loads((failed / "summary.json").read_text())
    (failed / "summary.json").write_text(json.dumps(summary | {"ok": True, "success": False}))
    (broken / "summary.json").write_text(json.dumps({"schema": 1, "ok": False, "failed_stage": "execute",
                                                     "error": "the hand could not reach A"}))
    notes: list[str] = []
    runs = find_runs([run_folder, stopped], note=notes.append)  # named twice: noted once
    assert sorted(r.path.name for r in runs) == ["run1", "run2"]
    assert notes == [f"skipped {stopped}: its run was interrupted; perform it again",
                     f"skipped {broken}: its run failed (stage execute); perform it again"]
    with pytest.raises(ReviewError, match="^nothing to review: none of the 1 run folders given finished"):
        find_runs([stopped], note=notes.append)


def test_the_review_command_refuses_only_unfinished_runs_in_one_line(run_folder, tmp_path):  # noqa: F811
    stopped = run_folder / "run0"
    _interrupt(stopped)
    db = tmp_path / "r.sqlite"
    r = CliRunner().invoke(main, ["review", str(stopped), "--db", str(db)])
    assert r.exit_code == 2 and r.stderr.splitlines() == [
        f"skipped {stopped}: its run was interrupted; perform it again",
        "error: nothing to review: none of the 1 run folders given finished (see the notes above)"], r.output
    assert not db.exists()  # refused before a database is made
