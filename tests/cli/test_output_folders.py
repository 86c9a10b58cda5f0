"""The commands that write bundles, scaffolds and reports never touch a person's files, and check their
options and output folder before any work (core/runfolder.py's rules): improve, train, train-policy,
new-action, new-arm, report, recognize --action. Every case is refused in one line, exit 2, before a
network trains or a round is performed, so each test takes well under a second or two."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.core.runfolder import claim_run_folder
from l2p_bullet.data.grades import GradeRow, write_grades
from l2p_bullet.errors import RunFolderError
from l2p_bullet.plugins.bundle import builtin_bundle_dir, check_bundle_target


def cli(*args: str):
    return CliRunner().invoke(main, list(args))


def one_line_error(result) -> str:
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2 and len(lines) == 1 and lines[0].startswith("error: "), result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return lines[0]


def user_folder(path: Path) -> Path:
    path.mkdir(parents=True)
    (path / "notes.txt").write_text("mine")
    (path / "important.csv").write_text("a,b\n")
    return path


@pytest.fixture
def unwritable(monkeypatch):
    """Make ``os.access`` deny writing under a folder (permission bits do not bind root, who runs CI)."""
    real = os.access

    def deny(folder: Path) -> Path:
        def access(path, mode, *a, **k):
            if mode & os.W_OK and Path(path).resolve().is_relative_to(folder.resolve()):
                return False
            return real(path, mode, *a, **k)

        monkeypatch.setattr(os, "access", access)
        return folder

    return deny


# --- improve ----------------------------------------------------------------------------------------
def test_improve_force_never_deletes_a_users_files(tmp_path):
    out = user_folder(tmp_path / "plain2")
    for extra in ((), ("--force",)):
        msg = one_line_error(cli("improve", "past", "--rounds", "1", "--scenes", "1", "--out", str(out), *extra))
        assert "did not write" in msg and "important.csv, notes.txt" in msg and "pass --force" not in msg
    assert sorted(p.name for p in out.iterdir()) == ["important.csv", "notes.txt"]


def test_improve_force_replaces_only_its_own_rounds(tmp_path):
    from l2p_bullet.learning.improve import _claim

    out = tmp_path / "imp"
    (out / "round-1" / "runs").mkdir(parents=True)
    (out / "round-1" / "metrics.json").write_text("{}")
    (out / "improve.json").write_text(json.dumps({"seed": 1}))
    with pytest.raises(RunFolderError, match="pass --force"):
        _claim(out, {"seed": 2}, force=False)
    (out / "round-1" / "mine.txt").write_text("x")
    with pytest.raises(RunFolderError, match=r"did not write \(round-1/mine.txt\)"):
        _claim(out, {"seed": 2}, force=True)
    (out / "round-1" / "mine.txt").unlink()
    _claim(out, {"seed": 2}, force=True)
    assert [p.name for p in out.iterdir()] == ["improve.json"]
    assert json.loads((out / "improve.json").read_text()) == {"seed": 2}
    (out / "round-1").mkdir()  # the same settings: resumed without --force, started over with it
    _claim(out, {"seed": 2}, force=False)
    assert (out / "round-1").is_dir()
    _claim(out, {"seed": 2}, force=True)
    assert [p.name for p in out.iterdir()] == ["improve.json"]


@pytest.mark.parametrize("option, expect", [
    (("--judge", "scenes/good.json"), "unknown feedback format"),
    (("--judge", "scenes"), "scenes is a folder"),
    (("--feedback", "nosuch.csv"), "no such feedback file"),
])
def test_improve_checks_its_options_before_writing_anything(tmp_path, monkeypatch, option, expect):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "scenes").mkdir()
    (tmp_path / "scenes" / "good.json").write_text('{"objects": []}')
    msg = one_line_error(cli("improve", "past", "--rounds", "1", "--scenes", "1", "--out", "imp", *option))
    assert expect in msg
    assert not (tmp_path / "imp").exists()


def test_improve_refuses_an_unwritable_out(tmp_path, unwritable):
    unwritable(tmp_path)
    assert "permission denied" in one_line_error(cli("improve", "past", "--rounds", "1", "--scenes", "1", "--out",
                                                     str(tmp_path / "imp")))


# --- train ------------------------------------------------------------------------------------------
def test_train_refuses_a_folder_that_is_not_a_bundle(tmp_path):
    out = user_folder(tmp_path / "user")
    proj = tmp_path / "proj"
    proj.mkdir()
    (proj / "manifest.toml").write_text('[package]\nname = "mine"\n')
    run = claim_run_folder(tmp_path / "run", command="perform")
    run.finish()
    run.release()
    for folder, extra in ((out, ()), (proj, ("--force",)), (tmp_path / "run", ("--force",))):
        msg = one_line_error(cli("train", "past", "--out", str(folder), "--ensemble", "1", "--epochs", "1", *extra))
        assert "not an action bundle's" in msg
    assert (proj / "manifest.toml").read_text() == '[package]\nname = "mine"\n'
    assert sorted(p.name for p in out.iterdir()) == ["important.csv", "notes.txt"]


def test_train_replaces_only_this_actions_bundle_and_only_with_force(tmp_path):
    bundle = tmp_path / "b"
    shutil.copytree(builtin_bundle_dir("past"), bundle)
    with pytest.raises(RunFolderError, match="pass --force"):
        check_bundle_target(bundle, "past", force=False)
    check_bundle_target(bundle, "past", force=True)
    with pytest.raises(RunFolderError, match='bundle of the action "past", not of "around"'):
        check_bundle_target(bundle, "around", force=True)
    check_bundle_target(tmp_path / "new", "past", force=False)


def test_train_refuses_an_unwritable_out_before_training(tmp_path, unwritable):
    unwritable(tmp_path)
    assert "permission denied" in one_line_error(cli("train", "past", "--out", str(tmp_path / "b")))


# --- train-policy -----------------------------------------------------------------------------------
def test_train_policy_refuses_another_actions_bundle(tmp_path):
    bundle = tmp_path / "trb"
    shutil.copytree(builtin_bundle_dir("around"), bundle)
    msg = one_line_error(cli("train-policy", "past", "--bundle", str(bundle), "--iterations", "1", "--episodes", "2"))
    assert 'bundle of the action "around", not of "past"' in msg


def test_train_policy_refuses_unwritable_folders(tmp_path, unwritable):
    bundle = tmp_path / "trb"
    shutil.copytree(builtin_bundle_dir("past"), bundle)
    unwritable(tmp_path)
    for args in (("--bundle", str(bundle)), ("--out", str(tmp_path / "copy"))):
        assert "permission denied" in one_line_error(cli("train-policy", "past", *args, "--iterations", "1"))
    assert not (tmp_path / "copy").exists()


# --- new-action, new-arm ----------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["around", "row"])
def test_new_action_refuses_an_installed_actions_name(tmp_path, name):
    out = tmp_path / "l2p"
    msg = one_line_error(cli("new-action", name, "--phrase", "zorpily near", "--out", str(out)))
    assert f'an action named "{name}" is already installed' in msg
    assert not out.exists()


def test_teach_of_a_built_in_action_suggests_a_name_new_action_takes(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # no ./l2p-around here
    msg = one_line_error(cli("teach", "around"))
    assert '"around" is a built-in action' in msg and "new-action my-around" in msg
    assert cli("new-action", "my-around", "--phrase", "zorpily near", "--out", str(tmp_path / "p")).exit_code == 0


def test_new_action_refuses_an_unwritable_out(tmp_path, unwritable):
    unwritable(tmp_path)
    msg = one_line_error(cli("new-action", "zorp", "--phrase", "zorpily near", "--out", str(tmp_path / "z")))
    assert "permission denied" in msg


@pytest.mark.parametrize("text, expect", [
    ("not xml at all", "not valid XML"),
    ('<?xml version="1.0"?><sdf/>', "root element is <sdf>"),
    ('<robot name="x"><link name="a"/><joint name="j" type="revolute"><parent link="zz"/><child link="a"/>'
     "</joint></robot>", 'names the parent link "zz", which is not a link of the file'),
])
def test_new_arm_says_what_is_wrong_with_a_urdf(tmp_path, text, expect):
    (tmp_path / "bad.urdf").write_text(text)
    r = cli("new-arm", "myarm", "--urdf", str(tmp_path / "bad.urdf"), "--out", str(tmp_path / "arm"))
    assert r.exit_code == 2 and isinstance(r.exception, SystemExit), r.output  # no traceback
    last = r.output.strip().splitlines()[-1]
    assert last.startswith("error: ") and expect in last, r.output
    assert not (tmp_path / "arm").exists()


@pytest.mark.parametrize("out, target", [(None, "./l2p-arm-myarm"), ("abs", "{tmp}/made")])
def test_new_arm_next_step_installs_with_this_pythons_pip_at_the_folder_written(tmp_path, monkeypatch, out, target):
    """The printed pip command works where the environment's bin/ has no pip (a venv layered on another, pipx: then
    this Python's ``-m pip``) and names an absolute --out as it is (``./`` before it named a folder under the
    current one)."""
    import sys

    from l2p_bullet.arms import PANDA
    from l2p_bullet.plugins import arm_scaffold

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "prefix", str(tmp_path / "env"))  # an environment whose bin/ holds no pip
    root = Path("l2p-arm-myarm") if out is None else tmp_path / "made"
    made = arm_scaffold.ArmScaffold(root, "l2p_arm_myarm", "l2p-arm-myarm", PANDA, [])
    monkeypatch.setattr(arm_scaffold, "scaffold_arm", lambda name, *a, **kw: made)
    (tmp_path / "arm.urdf").write_text('<robot name="r"><link name="base"/></robot>\n')
    r = cli("new-arm", "myarm", "--urdf", "arm.urdf", *([] if out is None else ["--out", str(root)]))
    assert r.exit_code == 0, r.output
    nxt = r.output.strip().splitlines()[-1]
    assert nxt.startswith(f"next: {sys.executable} -m pip install {target.format(tmp=tmp_path)}   then"), nxt


# --- report -----------------------------------------------------------------------------------------
@pytest.fixture
def grades(tmp_path) -> Path:
    rows = [GradeRow(run_id=f"r{i}", action="past", mode="graded", reviewer="ann", grade=g, view="2d")
            for i, g in enumerate((3, 7))]
    path = tmp_path / "g.csv"
    write_grades(rows, path)
    return path


def test_report_never_overwrites_a_persons_files(tmp_path, grades):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "report.md").write_text("my notes")
    assert "did not write" in one_line_error(cli("report", "--db", str(grades), "--out", str(mine)))
    assert (mine / "report.md").read_text() == "my notes"
    run = claim_run_folder(tmp_path / "run", command="perform")
    run.finish()
    run.release()
    msg = one_line_error(cli("report", "--db", str(grades), "--out", str(tmp_path / "run")))
    assert "l2p-bullet perform" in msg and not (tmp_path / "run" / "report.md").exists()


def test_report_replaces_a_report_from_before_the_marker_and_keeps_the_old_one_if_writing_fails(tmp_path, grades,
                                                                                                  monkeypatch):
    """Review finding (2026-11-27): every existing runs/reviews-report (no marker) was refused as someone else's,
    and an error while writing lost the earlier report."""
    from l2p_bullet.review import report as report_mod

    mine = tmp_path / "mine"  # a person's own report.md and report.json: never taken for an earlier report
    mine.mkdir()
    (mine / "report.md").write_text("my notes")
    (mine / "report.json").write_text('{"title": "my own"}')
    assert "did not write" in one_line_error(cli("report", "--db", str(grades), "--out", str(mine)))
    assert (mine / "report.md").read_text() == "my notes" and sorted(p.name for p in mine.iterdir()) == [
        "report.json", "report.md"]
    old = tmp_path / "old"  # what report wrote before the marker: its report.json has the report's keys
    old.mkdir()
    for name in ("report.md", "table1_original.csv"):
        (old / name).write_text("earlier")
    (old / "report.json").write_text(json.dumps(dict.fromkeys(
        ("source", "answers", "reviewers", "graded", "blind", "views", "problems"), None)))
    assert cli("report", "--db", str(grades), "--out", str(old)).exit_code == 0
    assert (old / "report.md").read_text() != "earlier"
    before = (old / "report.md").read_text()

    def broken(rep, folder):
        (folder / "report.md").write_text("half")
        raise report_mod.ReviewError("cannot write the report: disk full")

    monkeypatch.setattr(report_mod, "write_grade_report", broken)
    r = cli("report", "--db", str(grades), "--out", str(old))
    assert r.exit_code == 2 and "disk full" in r.output and "holds the earlier run again" in r.output
    assert (old / "report.md").read_text() == before  # the earlier report is back, nothing left aside
    assert not [p.name for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_report_regenerates_its_own_report(tmp_path, grades):
    """A report is made again after every grading session: its own earlier report is replaced, as it was
    before the marker, without --force; nothing else in the folder would be (test above)."""
    out = str(tmp_path / "rep")
    assert cli("report", "--db", str(grades), "--out", out).exit_code == 0
    (tmp_path / "rep" / "report.md").write_text("stale")
    r = cli("report", "--db", str(grades), "--out", out)
    assert r.exit_code == 0, r.output
    assert (tmp_path / "rep" / "report.md").read_text() != "stale"


@pytest.mark.parametrize("name, content, expect", [
    ("g.csv", "name,score\nbob,3\n", "not a grades export: no action, mode, grade columns"),
    ("fake.sqlite", "junk junk\n", "not a review database SQLite can open"),
    ("empty.csv", "", "holds no answers"),
    ("header.csv", "action,mode,grade\n", "holds no answers"),
    ("g.jsonl", '{"name": "bob"}\n', "not a grades export"),
])
def test_report_refuses_what_is_not_a_grades_file(tmp_path, name, content, expect):
    (tmp_path / name).write_text(content)
    assert expect in one_line_error(cli("report", "--db", str(tmp_path / name), "--out", str(tmp_path / "rep")))
    assert not (tmp_path / "rep").exists()


# --- recognize --action -----------------------------------------------------------------------------
def test_recognize_action_that_looks_like_a_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "userdir").mkdir()
    for spec, expect in (("./userdir", "not a bundle folder (no manifest.toml)"), ("userdir", "not a bundle folder"),
                         ("./nosuchdir", "no such folder")):
        msg = one_line_error(cli("recognize", "--demo", "past:3", "--action", spec))
        assert expect in msg and "unknown action" not in msg


def test_improve_force_stopped_half_way_leaves_a_folder_force_replaces_again(tmp_path):
    """Review finding: --force removed improve.json first; a kill after that left rounds without it, refused even
    with --force. It goes last now; an improve.json without the weights' digest (older) still resumes."""
    from l2p_bullet.learning.improve import _claim

    out = tmp_path / "imp"
    for k in (1, 2):
        (out / f"round-{k}" / "runs").mkdir(parents=True)
    (out / "improve.json").write_text(json.dumps({"seed": 1}))
    order = []
    real_unlink, real_rmtree = Path.unlink, shutil.rmtree

    def unlink(self, *a, **k):
        order.append(self.name)
        return real_unlink(self, *a, **k)

    def rmtree(path, *a, **k):
        order.append(Path(path).name)
        return real_rmtree(path, *a, **k)

    import unittest.mock

    with unittest.mock.patch.object(Path, "unlink", unlink), unittest.mock.patch("shutil.rmtree", rmtree):
        _claim(out, {"seed": 1}, force=True)
    assert sorted(order[:-1]) == ["round-1", "round-2"] and order[-1] == "improve.json", order
    assert [p.name for p in out.iterdir()] == ["improve.json"]
    (out / "round-1").mkdir()
    _claim(out, {"seed": 1, "started_from_sha256": "abc"}, force=False)  # the older file: resumed
    assert (out / "round-1").is_dir()
