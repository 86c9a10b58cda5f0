"""``l2p-bullet score`` and ``train`` from the command line."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.data.demos import data_dir
from l2p_bullet.plugins.bundle import builtin_bundle_dir, load_bundle, sha256_file


def _scoring_input(tmp_path: Path, mover: np.ndarray, size: float = 0.05, anchor=None) -> Path:
    p = tmp_path / "motion.json"
    anchor = [[0.0, 0.0, 0.0]] if anchor is None else anchor
    p.write_text(json.dumps({"size": size, "mover": mover.tolist(), "anchor": anchor}))
    return p


def _circle(n: int = 60, radius: float = 0.12, turns: float = 1.0) -> np.ndarray:
    a = np.linspace(0, 2 * np.pi * turns, n)
    return np.column_stack([radius * np.cos(a), radius * np.sin(a), np.zeros(n)])


def test_score_prints_per_frame_progress_and_final(tmp_path):
    f = _scoring_input(tmp_path, _circle())
    res = CliRunner().invoke(main, ["score", "around", str(f)])
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    assert out["action"] == "around" and len(out["progress"]) == 60
    assert out["final"] == out["progress"][-1]
    assert all(0.0 <= v <= 1.0 for v in out["progress"])


def test_score_accepts_a_bundle_folder_and_alias(tmp_path):
    folder = tmp_path / "my_bundle"
    shutil.copytree(builtin_bundle_dir("next-to"), folder)
    f = _scoring_input(tmp_path, np.array([[0.3, 0.0, 0.0], [0.06, 0.0, 0.0]]))
    by_path = json.loads(CliRunner().invoke(main, ["score", str(folder), str(f)]).output)
    by_alias = json.loads(CliRunner().invoke(main, ["score", "next_to", str(f)]).output)
    assert by_path == by_alias and by_path["action"] == "next-to"


def test_score_is_resampled_so_frame_rate_does_not_matter(tmp_path):
    """A square path around the anchor given by its corners only, or by 200 frames, scores the same."""
    c = 0.16  # not on a QDC bin edge (3 blocks), where rounding could flip a bin
    corners = np.array([[c, 0, 0], [c, c, 0], [-c, c, 0], [-c, -c, 0], [c, -c, 0]])
    dense = np.concatenate([np.linspace(corners[i], corners[i + 1], 50, endpoint=False) for i in range(4)]
                           + [corners[-1:]])
    a = json.loads(CliRunner().invoke(main, ["score", "around", str(_scoring_input(tmp_path, corners))]).output)
    b = json.loads(CliRunner().invoke(main, ["score", "around", str(_scoring_input(tmp_path, dense))]).output)
    assert abs(a["final"] - b["final"]) < 1e-3
    assert len(a["progress"]) == 5 and len(b["progress"]) == 201


def test_score_reads_trajectory_json(tmp_path):
    circle = _circle(40)
    frames = [{"t": i / 30, "poses": {"A": [x, y, 0.025, th], "B": [0.0, 0.0, 0.025, 0.0]}, "ee": [x, y, 0.1],
               "grasped": "A", "progress": None} for i, (x, y, th) in enumerate(circle)]
    traj = {"schema": 1, "sentence": "move A around B", "action": "around", "mover": "A", "anchor": "B",
            "fps": 30.0, "objects": {"A": {"size": 0.05}, "B": {"size": 0.05}}, "frames": frames}
    p = tmp_path / "trajectory.json"
    p.write_text(json.dumps(traj))
    res = CliRunner().invoke(main, ["score", "around", str(p)])
    assert res.exit_code == 0, res.output
    assert len(json.loads(res.output)["progress"]) == 40
    folder = CliRunner().invoke(main, ["score", "around", str(tmp_path)])  # a run folder: its trajectory.json
    assert folder.exit_code == 0 and json.loads(folder.output) == json.loads(res.output), folder.output
    empty = tmp_path / "empty"
    empty.mkdir()
    res = CliRunner().invoke(main, ["score", "around", str(empty)])
    assert res.exit_code == 2 and "is a folder without trajectory.json" in res.output


def test_score_errors_are_one_line(tmp_path):
    def one_line(res) -> str:
        lines = res.output.strip().splitlines()
        assert res.exit_code == 2 and len(lines) == 1 and lines[0].startswith("error: "), res.output
        assert res.exception is None or isinstance(res.exception, SystemExit), res.exception
        return lines[0]

    runner = CliRunner()
    line = one_line(runner.invoke(main, ["score", "arround", str(_scoring_input(tmp_path, _circle()))]))
    assert 'unknown action "arround"' in line and 'Did you mean "around"' in line
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"size": 0.05, "mover": [[0, 0, 0]], "anchor": [[0, 0, 0], [1, 1, 1]]}))
    line = one_line(runner.invoke(main, ["score", "around", str(bad)]))
    assert f'{bad}: "mover" has 1 poses but "anchor" has 2' in line


@pytest.mark.slow
def test_train_is_deterministic_and_writes_a_loadable_bundle(tmp_path):
    session = data_dir() / "captures" / "SlidePast_Session1.npz"
    args = ["train", "past", "--demos", str(session), "--ensemble", "1", "--epochs", "2", "--seed", "3"]
    runner = CliRunner()
    from l2p_bullet.learning import trainset

    # the two trainings label every sequence anew (tests/learning keeps labellings only while its modules run)
    assert trainset._labelled.__qualname__ == "_labelled"
    r1 = runner.invoke(main, [*args, "--out", str(tmp_path / "a")])
    assert r1.exit_code == 0, r1.output
    # progress with an ETA on stderr, also when it is not a terminal (issue 26: 30 s of silence)
    assert "training past: building the training set" in r1.stderr
    assert "2/2 epochs (100%)" in r1.stderr and "ETA" in r1.stderr and "ETA" not in r1.stdout
    r2 = runner.invoke(main, [*args, "--out", str(tmp_path / "b")])
    assert r2.exit_code == 0, r2.output
    assert sha256_file(tmp_path / "a" / "progress.safetensors") == sha256_file(tmp_path / "b" / "progress.safetensors")
    import os

    umask = os.umask(0o022)
    os.umask(umask)
    for name in ("progress.safetensors", "manifest.toml"):  # issue 26: weights were written 0600
        assert (tmp_path / "a" / name).stat().st_mode & 0o777 == 0o666 & ~umask, name
    b = load_bundle(tmp_path / "a")
    assert b.name == "past" and b.manifest["training"]["seed"] == 3
    assert "--demos" in b.manifest["training"]["command"]
    # refuses to overwrite without --force
    r3 = runner.invoke(main, [*args, "--out", str(tmp_path / "a")])
    assert r3.exit_code == 2 and "--force" in r3.output
