"""Feedback from grades: reading review exports, turning grades into training targets, fine-tuning
(cross-validation over the grades: tests/research/test_agreement_cv.py)."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.learning.feedback import (
    FeedbackError,
    FeedbackItem,
    items_from_rows,
    original_items,
    read_grades,
)
from l2p_bullet.learning.feedback_targets import FeedbackConfig, feedback_sequences, target_of
from l2p_bullet.learning.trainset import DataConfig
from l2p_bullet.progress.features import QSRConfig
from l2p_bullet.review.store import EXPORT_FIELDS, GradeRow, write_grades


def _trajectory(folder: Path, end_x: float = 0.15) -> str:
    """A small valid trajectory.json (A slides past B along x); returns its sha256."""
    folder.mkdir(parents=True, exist_ok=True)
    xs = np.linspace(-0.15, end_x, 40)
    frames = [{"t": i / 30, "poses": {"A": [float(x), 0.08, 0.025, 0.0], "B": [0.0, 0.0, 0.025, 0.0]},
               "ee": [float(x), 0.08, 0.1], "grasped": "A", "progress": 0.0} for i, x in enumerate(xs)]
    data = {"schema": 1, "sentence": "move A past B", "action": "past", "mover": "A", "anchor": "B", "fps": 30.0,
            "objects": {"A": {"size": 0.05}, "B": {"size": 0.05}}, "frames": frames}
    path = folder / "trajectory.json"
    path.write_text(json.dumps(data))
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _row(**kw) -> GradeRow:
    base = {"run_id": "r1", "action": "past", "mode": "graded", "reviewer": "ann", "grade": 8.0}
    return GradeRow(**{**base, **kw})


def test_csv_and_jsonl_exports_round_trip(tmp_path):
    rows = [_row(), _row(reviewer="bob", grade=None, mode="blind", label="around"), _row(run_id="r2", grade=2.5)]
    csv_path = tmp_path / "g.csv"
    write_grades(rows, csv_path)
    assert read_grades(csv_path) == [GradeRow(**{**r.__dict__, "label": r.label}) for r in rows]
    jl = tmp_path / "g.jsonl"
    jl.write_text(
        "\n".join(json.dumps({k: getattr(r, k) for k in EXPORT_FIELDS} | {"extra": 1}) for r in rows) + "\n\n"
    )
    assert read_grades(jl) == read_grades(csv_path)


@pytest.mark.parametrize("content, line", [
    ("run_id,action,mode,grade\nr1,past,graded,11\n", 2),
    ("run_id,action,mode,grade\nr1,past,graded,8\nr2,past,graded,high\n", 3),
    ("run_id,action,mode,grade\nr1,past,sideways,8\n", 2),
    ("run_id,action,mode,grade\n,past,graded,8\n", 2),
])
def test_bad_rows_name_the_line(tmp_path, content, line):
    p = tmp_path / "bad.csv"
    p.write_text(content)
    with pytest.raises(FeedbackError) as e:
        read_grades(p)
    assert e.value.line == line and e.value.path == str(p)


def test_unknown_or_missing_files_are_clear_errors(tmp_path):
    (tmp_path / "g.txt").write_text("x")
    with pytest.raises(FeedbackError, match=r'unknown feedback format "\.txt" \(expected \.csv, \.jsonl') as e:
        read_grades(tmp_path / "g.txt")  # not read as some other format (a CSV without a header, say)
    assert e.value.path == str(tmp_path / "g.txt") and e.value.line is None and "\n" not in str(e.value)
    with pytest.raises(FeedbackError, match="no such feedback file") as e:
        read_grades(tmp_path / "missing.csv")
    assert e.value.path == str(tmp_path / "missing.csv") and not (tmp_path / "missing.csv").exists()


def test_a_review_database_is_read_through_the_review_store(tmp_path):
    """The review app's own database (here with the original study's grades imported) reads as its export."""
    from l2p_bullet.review.original import import_original
    from l2p_bullet.review.store import Store, load_grades

    db = tmp_path / "reviews.sqlite"
    import_original(Store(db))
    rows = read_grades(db)
    def key(r):
        return (r.run_id, r.demo_id, r.reviewer, r.grade, r.mode, r.action, r.source)

    assert [key(r) for r in rows] == [key(r) for r in load_grades(db)] and len(rows) == 180  # 90 demos x 2 graders
    assert {r.source for r in rows} == {"original"} and all(r.demo_id and 0 <= r.grade <= 10 for r in rows)
    broken = db.parent / "broken.sqlite"
    broken.write_bytes(b"SQLite format 3\x00" + b"\x00" * 100)
    with pytest.raises(FeedbackError, match="cannot read review database .*: file is not a database") as e:
        read_grades(broken)
    assert e.value.path == str(broken) and broken.read_bytes() == b"SQLite format 3\x00" + b"\x00" * 100  # untouched


def test_runs_are_grouped_averaged_and_changed_runs_reported(tmp_path):
    sha = _trajectory(tmp_path / "runs" / "a")
    _trajectory(tmp_path / "runs" / "b")
    rows = [_row(run_id="a", run_path="runs/a", trajectory_sha256=sha, grade=8.0),
            _row(run_id="a", run_path="runs/a", trajectory_sha256=sha, reviewer="bob", grade=6.0),
            _row(run_id="a", run_path="runs/a", mode="blind", grade=None, label="Around"),
            _row(run_id="b", run_path="runs/b", trajectory_sha256="0" * 64, grade=9.0),
            _row(run_id="c", run_path="runs/c", grade=9.0)]
    items, skipped = items_from_rows(rows, tmp_path)
    (it,) = items
    assert it.id == "a" and it.action == "past" and it.grade == 7.0 and it.labels == ["around"]
    assert it.size == 0.05 and it.mover.shape[1] == 3
    assert {s.id: ("changed" in s.reason) for s in skipped} == {"b": True, "c": False}


def test_study_rows_use_the_graded_demonstrations():
    rows = [GradeRow(demo_id="SlidePast/3", source="original", action="past", grade=1.0, reviewer="x"),
            GradeRow(demo_id="SlidePast/3", source="original", action="past", grade=2.0, reviewer="y"),
            GradeRow(demo_id="SlidePast/99", source="original", action="past", grade=2.0)]
    items, skipped = items_from_rows(rows)
    assert [it.id for it in items] == ["SlidePast/3"] and items[0].grade == 1.5 and items[0].folder == "SlidePast"
    assert [s.id for s in skipped] == ["SlidePast/99"]


def test_original_items_are_the_90_graded_demos():
    items = original_items()
    assert len(items) == 90 and len({it.folder for it in items}) == 6
    assert all(len(it.grades) == 2 and 0 <= it.grade <= 10 for it in items)


def _item(grade, action="past", labels=(), idx="m"):
    mover = np.column_stack([np.linspace(-3, 3, 25), np.full(25, 2.0), np.zeros(25)]) * 0.15
    return FeedbackItem(idx, action, mover, np.zeros((25, 3)), 0.15, [grade] if grade is not None else [], list(labels))


def test_targets_follow_the_mean_grade_or_the_originals_clear_cases():
    cfg, clear = FeedbackConfig(), FeedbackConfig(target="clear")
    assert target_of(_item(7.5), cfg) == 0.75 and target_of(_item(None), cfg) is None
    assert [target_of(_item(g), clear) for g in (3.5, 5, 7)] == [0.0, None, 1.0]
    assert target_of(_item(4.5, "away"), clear) == 0.0  # away's lower threshold is 4.5 in the original's code
    assert target_of(_item(5.5, "around"), clear) == 1.0 and target_of(_item(1.6, "around"), clear) is None


def test_graded_motions_end_at_their_grade_and_blind_mislabels_are_negatives():
    q, d, cfg = QSRConfig(), DataConfig(), FeedbackConfig()
    seqs = feedback_sequences("past", [_item(6.0), _item(8.0, action="away")], q, d, cfg)
    assert len(seqs) == 2 * (1 + cfg.copies)  # the past item, its mirror image, their copies; away is not past's
    for s in seqs:
        assert s.y[s.end] == pytest.approx(0.6, abs=1e-6) and s.y[0] == 0 and np.all(np.diff(s.y) >= -1e-6)
    assert not np.allclose(seqs[0].x[-1], seqs[1].x[-1])  # a perturbed copy is another motion
    again = feedback_sequences("past", [_item(6.0)], q, d, cfg)
    assert all(np.array_equal(a.x, b.x) for a, b in zip(seqs, again, strict=True))  # and the same every time
    neg = feedback_sequences("past", [_item(None, labels=["around", "none", "past"])], q, d, cfg)
    assert len(neg) == 2 and all(np.all(s.y == 0) and s.frame_w is not None for s in neg)
    assert feedback_sequences("past", [_item(None, labels=["past", "around"])], q, d, cfg) == []


def test_fine_tuning_is_deterministic_and_learns_the_grades():
    import torch

    from l2p_bullet.learning.progress_net import ProgressNet
    from l2p_bullet.learning.train_progress import ProgressTrainConfig, fine_tune

    q, d = QSRConfig(), DataConfig()
    items = [_item(g, idx=str(g)) for g in (1.0, 9.0)]
    items[1].mover = items[1].mover * np.array([1.0, 0.5, 1.0])  # a nearer pass, graded high
    seqs = feedback_sequences("past", items, q, d, FeedbackConfig(copies=0))
    torch.manual_seed(0)
    base = [ProgressNet(q.n_features, 8)]
    cfg, fcfg = ProgressTrainConfig(hidden=8, ensemble=1), FeedbackConfig(epochs=40, lr=0.02, demo_fraction=0.0)
    a = fine_tune(base, [], seqs, fcfg, cfg, seed=1)
    b = fine_tune(base, [], seqs, fcfg, cfg, seed=1)
    assert all(torch.equal(x, y) for x, y in zip(a[0].state_dict().values(), b[0].state_dict().values(), strict=True))
    with torch.no_grad():
        ends = [float(a[0](torch.from_numpy(s.x[None]))[0, s.end]) for s in seqs]
    assert ends[0] < 0.3 and ends[2] > 0.7  # seqs: item 1.0, its mirror, item 9.0, its mirror
    assert not torch.equal(base[0].head.weight, a[0].head.weight)  # the base is left untouched, a copy learned


def test_train_cli_rejects_a_bad_feedback_file_in_one_line(tmp_path):
    bad = tmp_path / "g.csv"
    bad.write_text("run_id,action,mode,grade\nr1,past,graded,12\n")
    r = CliRunner().invoke(main, ["train", "past", "--feedback", str(bad), "--out", str(tmp_path / "b")])
    assert r.exit_code == 2 and "line 2" in r.output and "Traceback" not in r.output
    assert not (tmp_path / "b").exists()


@pytest.mark.slow
def test_train_with_feedback_records_it_in_the_manifest(tmp_path):
    from l2p_bullet.plugins.bundle import load_bundle

    r = CliRunner().invoke(main, ["train", "past", "--ensemble", "1", "--epochs", "1", "--feedback", "original",
                                  "--out", str(tmp_path / "b")])
    assert r.exit_code == 0, r.output
    m = load_bundle(tmp_path / "b").manifest["training"]
    assert m["feedback"]["sources"] == ["original"] and m["feedback"]["n_items"] == 15
    assert (
        m["feedback"]["n_sequences"] == 15 * 2 * (1 + FeedbackConfig().copies) and "--feedback original" in m["command"]
    )


@pytest.mark.slow
def test_improve_waits_for_people_then_resumes_and_never_overwrites(tmp_path):
    from l2p_bullet.errors import DataError, RunFolderError
    from l2p_bullet.learning.improve import improve

    export = tmp_path / "reviews.csv"
    write_grades([GradeRow(run_id="other", action="past", grade=5.0)], export)
    out = tmp_path / "imp"
    fcfg = FeedbackConfig(epochs=1)
    with pytest.raises(DataError):  # the runs are performed, but nobody has graded them yet
        improve("past", 1, out, scenes=1, judge=str(export), feedback_cfg=fcfg)
    traj = out / "round-1" / "runs" / "seed-1000" / "trajectory.json"
    assert traj.is_file() and not (out / "round-1" / "bundle").exists()
    sha = hashlib.sha256(traj.read_bytes()).hexdigest()
    write_grades([GradeRow(run_id="seed-1000", run_path=str(traj.parent), trajectory_sha256=sha, action="past",
                           reviewer="ann", grade=3.0)], export, force=True)  # the reviewer's new export
    (res,) = improve("past", 1, out, scenes=1, judge=str(export), feedback_cfg=fcfg)
    assert res.n_grades == 1 and res.mean_grade == 3.0 and res.seeds == [1000]
    assert hashlib.sha256(traj.read_bytes()).hexdigest() == sha  # the graded run was reused, not performed again
    man = (out / "round-1" / "bundle" / "manifest.toml").read_text()
    assert "[policy]" in man and "[judge]" in man and "round = 1" in man
    assert json.loads((out / "round-1" / "metrics.json").read_text())["round"] == 1
    with pytest.raises(RunFolderError):  # other settings into the same folder
        improve("past", 1, out, scenes=2, judge="rules", feedback_cfg=fcfg)
    (again,) = improve("past", 1, out, scenes=1, judge=str(export), feedback_cfg=fcfg)  # finished: kept as is
    assert again.to_dict() == res.to_dict()


@pytest.mark.slow
def test_train_with_the_rule_judge_grades_the_models_own_plans(tmp_path):
    from l2p_bullet.data.demos import session_files
    from l2p_bullet.plugins.bundle import load_bundle

    # one of closer's three sessions: the feedback and the determinism do not depend on how many (~2 s a train)
    session = session_files("closer")[0]
    args = ["train", "closer", "--demos", str(session), "--ensemble", "1", "--epochs", "1", "--feedback-judge", "rules",
            "--judge-scenes", "1"]
    r = CliRunner().invoke(main, [*args, "--out", str(tmp_path / "a")])
    assert r.exit_code == 0, r.output
    fb = load_bundle(tmp_path / "a").manifest["training"]["feedback"]
    assert fb["judge"] == "rules" and fb["n_items"] == 3 and fb["judge_scenes"] == 1  # 3 plans of one scene
    r = CliRunner().invoke(main, [*args, "--out", str(tmp_path / "b")])
    assert (tmp_path / "a" / "progress.safetensors").read_bytes() == (
        tmp_path / "b" / "progress.safetensors"
    ).read_bytes()
