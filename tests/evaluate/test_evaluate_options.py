"""``evaluate``'s options are checked before anything is made: one-line errors, exit 2, no folder left behind;
nothing a person wrote is overwritten or written into (--parquet FILE, --out with notes.txt)."""

from __future__ import annotations

import json
import os

import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.core.runfolder import MARKER
from l2p_bullet.core.scene import default_scene
from l2p_bullet.errors import SceneError
from l2p_bullet.evaluate.results import ResultsStore
from l2p_bullet.evaluate.runner import EvaluationConfig
from l2p_bullet.evaluate.scenes import scene_file

TINY = ["evaluate", "--plan-only", "--workers", "0", "--scenes", "1", "--actions", "around", "--quiet"]


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)


def _run(*args: str):
    return CliRunner().invoke(main, list(args))


def _refused(r, *words: str) -> None:
    assert r.exit_code == 2, r.output
    assert "Traceback" not in r.output and r.output.startswith("error: "), r.output
    for w in words:
        assert w in r.output, r.output


def test_parquet_never_overwrites_a_file_and_its_folder_is_checked_before_running(tmp_path):
    (tmp_path / "scene.json").write_text("{}")
    _refused(_run(*TINY, "--out", "a", "--parquet", "scene.json"), "already exists", "another --parquet")
    assert (tmp_path / "scene.json").read_text() == "{}"
    _refused(_run(*TINY, "--out", "a", "--parquet", "nosuchdir/x.parquet"), "nosuchdir", "does not exist")
    _refused(_run(*TINY, "--out", "a", "--parquet", "scene.json/x.parquet"), "does not exist")
    assert not (tmp_path / "a").exists()  # nothing ran
    r = _run(*TINY, "--out", "a", "--parquet", "a/results.parquet")  # the evaluation's own (new) folder is fine
    assert r.exit_code == 0, r.output
    assert (tmp_path / "a" / "results.parquet").read_bytes()[:4] == b"PAR1"


@pytest.mark.parametrize("args, words", [
    (["--seed", "-1"], ["--seed", "0<=x<=4294967295"]),
    (["--seed", "99999999999"], ["--seed"]),
    (["--seed", "4294967295", "--scenes", "2"], ["last scene's seed"]),
    (["--bystanders", "-1"], ["--bystanders must be 0 to 10"]),
    (["--render-every", "-1"], ["--render-every must be 0"]),
    (["--chains", "0"], ["--chains must be 1 to 10"]),
    (["--actions", ""], ["--actions needs at least one name"]),
    (["--actions", " , "], ["--actions needs at least one name"]),
    (["--manners", ""], ["--manners needs at least one name"]),
    (["--workers", "1000"], ["--workers must be at most 256"]),
    (["--retry-errors"], ["--retry-errors needs --resume"]),
])
def test_out_of_range_options_are_refused_before_the_folder_is_made(tmp_path, args, words):
    _refused(_run(*TINY, "--out", "o", *args), *words)
    assert not (tmp_path / "o").exists()


def test_a_start_that_failed_before_storing_settings_leaves_a_reusable_folder(tmp_path):
    with ResultsStore(tmp_path / "o"):  # what a start that failed on its scenes used to leave
        pass
    _refused(_run(*TINY, "--out", "o", "--resume"), "nothing to resume in o")
    assert _run(*TINY, "--out", "o").exit_code == 0
    assert _run(*TINY, "--out", "o", "--resume").exit_code == 0


def test_scene_file_seeds_and_ids_are_checked_per_line(tmp_path):
    f = tmp_path / "s.jsonl"
    for bad, words in ((dict(seed=-3), ["line 1", '"seed"', "-3"]), (dict(id=""), ["line 1", '"id"', "non-empty"]),
                       (dict(seed=2**32), ["line 1", '"seed"'])):
        f.write_text(json.dumps(default_scene().to_dict() | bad) + "\n")
        with pytest.raises(SceneError) as e:
            scene_file(f)
        assert all(w in str(e.value) for w in words), e.value
    f.write_text(json.dumps(default_scene().to_dict()) + "\n" + json.dumps(default_scene().to_dict()) + "\n")
    _refused(_run("evaluate", "--plan-only", "--actions", "around", "--scene-file", str(f), "--seed", "4294967295",
                  "--out", "o2"), "s.jsonl/1 would plan with seed 4294967296", "seeds are 0 to")
    assert not (tmp_path / "o2").exists()


def test_out_holding_files_evaluate_did_not_write_is_refused(tmp_path):
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "notes.txt").write_text("mine")
    _refused(_run(*TINY, "--out", "notes"), "holds files l2p-bullet did not write (notes.txt)", "another --out")
    assert sorted(os.listdir(tmp_path / "notes")) == ["notes.txt"]
    (tmp_path / "perform").mkdir()
    (tmp_path / "perform" / MARKER).write_text('{"tool": "l2p-bullet"}')
    _refused(_run(*TINY, "--out", "perform"), MARKER)
    (tmp_path / "empty").mkdir()
    assert _run(*TINY, "--out", "empty", "--report").exit_code == 0  # an empty folder is fine ...
    (tmp_path / "empty" / "notes.txt").write_text("mine")  # ... and notes added to an evaluation do not stop it
    assert _run(*TINY, "--out", "empty", "--resume").exit_code == 0
    assert _run("evaluate", "--out", "empty", "--report").exit_code == 0


def test_resume_needs_an_existing_evaluation_in_out(tmp_path):
    _refused(_run(*TINY, "--resume"), "--resume needs --out")
    _refused(_run(*TINY, "--resume", "--out", "nonexistent"), "nothing to resume in nonexistent")
    assert os.listdir(tmp_path) == []


def test_resume_refuses_another_mode(tmp_path):
    with ResultsStore(tmp_path / "perf") as store:  # a stored perform evaluation: --plan-only is another one
        store.set_meta("config", EvaluationConfig(actions=["around"], scenes=1).to_dict())
    _refused(_run(*TINY, "--out", "perf", "--resume"), "settings differ: mode")


def test_report_alone_on_a_missing_folder_runs_nothing(tmp_path):
    _refused(_run("evaluate", "--out", "o/typo", "--report"), "nothing to report in o/typo")
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("setting, message", [
    ({"budget": 0}, "budget must be a positive"), ({"threshold": 5}, "threshold must be a progress"),
    ({"scenes": "2"}, "whole number"), ({"bystanders": 1.5}, "whole number"), ({"planner": "astar"}, "astar"),
])
def test_the_python_config_is_checked_before_the_folder_exists(tmp_path, setting, message):
    """As perform checks them: an error row per task before (API audit, 2026-11-27)."""
    from l2p_bullet.errors import L2PError
    from l2p_bullet.evaluate.runner import evaluate

    config = EvaluationConfig(**({"actions": ["around"], "scenes": 1, "mode": "plan"} | setting))
    with pytest.raises(L2PError, match=message):
        evaluate(config, tmp_path / "e", workers=0, progressbar=False)
    with pytest.raises(L2PError, match="EvaluationConfig"):
        evaluate({"actions": ["around"]}, tmp_path / "e", workers=0, progressbar=False)
    assert not (tmp_path / "e").exists()


def test_the_progress_bar_starts_before_the_first_run_ends(tmp_path):
    """A '0/N runs' line at once: the first run (workers starting, a render) takes seconds (audit, 2026-11-27)."""
    r = CliRunner().invoke(main, [*[a for a in TINY if a != "--quiet"], "--out", str(tmp_path / "e")])
    assert r.exit_code == 0, r.output
    lines = [ln for ln in r.stderr.splitlines() if "runs (" in ln]
    assert lines and "] 0/1 runs" in lines[0] and "] 1/1 runs" in lines[-1], r.stderr
