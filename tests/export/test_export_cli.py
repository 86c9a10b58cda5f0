"""``l2p-bullet export``'s command line: unfinished runs skipped, unreadable frames, what it prints, OUT's errors.

Audit (2026-11-28): a rendered perform stopped with Ctrl-C leaves trajectory.json, an interrupted
summary.json and a 0-byte frame; ``export`` crashed on that frame with imageio's traceback.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.core.scene import default_scene
from l2p_bullet.embodiment.sim.camera import RenderSettings
from l2p_bullet.pipeline import perform


@pytest.fixture(scope="module")
def finished(tmp_path_factory) -> Path:
    """One rendered run (tiny frames), finished."""
    root = tmp_path_factory.mktemp("export-cli")
    settings = RenderSettings(64, 48, fps=5.0, renderer="tiny", workers=0)
    return perform("move A closer to B", default_scene(), out_dir=root / "run", render_settings=settings).out_dir


def interrupted_copy(run: Path, to: Path) -> Path:
    """``run`` as a Ctrl-C during rendering leaves it: an interrupted summary, no video, a 0-byte last frame."""
    shutil.copytree(run, to)
    (to / "summary.json").write_text(json.dumps({"schema": 1, "ok": False, "failed_stage": "interrupted",
                                                 "error": "interrupted (Ctrl-C) before the run finished"}))
    for video in to.glob("video.*"):
        video.unlink()
    frames = sorted((to / "frames").glob("*.png"))
    (to / "frames" / f"{len(frames):04d}.png").write_bytes(b"")
    return to


def failed_verdict_copy(run: Path, to: Path) -> Path:
    """``run`` finished, but its action judged a failure (``ok`` true, ``success`` false)."""
    shutil.copytree(run, to)
    summary = json.loads((to / "summary.json").read_text())
    (to / "summary.json").write_text(json.dumps(summary | {"ok": True, "success": False}))
    return to


def one_line_error(result) -> str:
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2 and lines[-1].startswith("error: "), result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return lines[-1]


def test_an_interrupted_run_is_skipped_with_a_note_and_a_failed_action_is_kept(finished, tmp_path):
    runs = tmp_path / "runs"
    runs.mkdir()
    stopped = interrupted_copy(finished, runs / "stopped")
    failed = failed_verdict_copy(finished, runs / "failed")
    shutil.copytree(finished, runs / "ok")
    r = CliRunner().invoke(main, ["export", str(runs), str(tmp_path / "out")])
    assert r.exit_code == 0, r.output
    assert f"skipped {stopped}: its run was interrupted; perform it again" in r.stderr.splitlines()
    eps = [json.loads(line) for line in (tmp_path / "out" / "episodes.jsonl").read_text().splitlines()]
    assert sorted(e["source"] for e in eps) == [str(failed), str(runs / "ok")]
    assert [e["extra"]["success"] for e in eps if e["source"] == str(failed)] == [False]
    # a run that broke off with an error is no episode either
    (runs / "ok" / "summary.json").write_text(json.dumps({"schema": 1, "ok": False, "failed_stage": "render",
                                                         "error": "disk full"}))
    r = CliRunner().invoke(main, ["export", str(runs), str(tmp_path / "out2")])
    assert r.exit_code == 0 and f"skipped {runs / 'ok'}: its run failed (stage render); perform it again" in r.stderr


def test_nothing_finished_to_export_is_a_one_line_error(finished, tmp_path):
    stopped = interrupted_copy(finished, tmp_path / "stopped")
    r = CliRunner().invoke(main, ["export", str(stopped), str(tmp_path / "out")])
    line = one_line_error(r)
    assert "nothing to export" in line and r.stderr.startswith(f"skipped {stopped}: its run was interrupted")
    assert not (tmp_path / "out").exists()  # refused before the output folder is claimed


def test_an_unreadable_frame_of_a_finished_run_is_a_one_line_error_naming_it(finished, tmp_path):
    run = shutil.copytree(finished, tmp_path / "run")
    bad = sorted((run / "frames").glob("*.png"))[1]
    bad.write_bytes(b"")
    r = CliRunner().invoke(main, ["export", str(run), str(tmp_path / "out")])
    line = one_line_error(r)
    assert str(bad) in line and "empty file" in line and "Traceback" not in r.output
    bad.write_bytes(b"\x89PNG")  # cut short: imageio's plugins raise struct.error
    line = one_line_error(CliRunner().invoke(main, ["export", str(run), str(tmp_path / "out"), "--force"]))
    assert line.startswith(f"error: cannot read the frame image {bad} (")


def test_a_sentence_by_default_and_the_json_behind_json(finished, tmp_path):
    r = CliRunner().invoke(main, ["export", str(finished), str(tmp_path / "a")])
    assert r.exit_code == 0, r.output
    frames = len(json.loads((finished / "trajectory.json").read_text())["frames"])
    assert r.stdout == f"wrote 1 episode ({frames} frames) to {tmp_path / 'a' / 'episodes.jsonl'}\n"
    r = CliRunner().invoke(main, ["export", str(finished), str(tmp_path / "b"), "--json"])
    assert r.exit_code == 0 and json.loads(r.stdout) == {"out": str(tmp_path / "b" / "episodes.jsonl"), "episodes": 1}


def test_an_existing_out_is_named_as_the_argument_it_is(finished, tmp_path):
    out = tmp_path / "out"
    assert CliRunner().invoke(main, ["export", str(finished), str(out)]).exit_code == 0
    line = one_line_error(CliRunner().invoke(main, ["export", str(finished), str(out)]))
    assert "already holds a finished run; choose another OUT, or pass --force" in line and "--out" not in line


def test_runs_put_aside_in_hidden_folders_are_not_exported(tmp_path):
    """A run a killed --force left aside (.NAME.replaced-*) is no episode (review finding, 2026-11-27)."""
    from l2p_bullet.export.episodes import run_folders

    (tmp_path / "runs" / "a").mkdir(parents=True)
    (tmp_path / "runs" / "a" / "trajectory.json").write_text("{}")
    (tmp_path / "runs" / ".a.replaced-1").mkdir()
    (tmp_path / "runs" / ".a.replaced-1" / "trajectory.json").write_text("{}")
    assert run_folders([tmp_path / "runs"]) == [tmp_path / "runs" / "a"]
