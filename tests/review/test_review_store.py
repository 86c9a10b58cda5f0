"""The review database: migrations, answers that are never lost or overwritten, export, the original study."""

from __future__ import annotations

import json
import sqlite3

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from review_fixtures import run_folder  # noqa: F401 - fixture

from l2p_bullet.data import review_schema as schema
from l2p_bullet.data.demos import load_graded_demos
from l2p_bullet.errors import ReviewError, SchemaVersionError
from l2p_bullet.review.original import import_original
from l2p_bullet.review.report import build_report, write_grade_report
from l2p_bullet.review.runs import find_runs
from l2p_bullet.review.stats import disparity, fleiss_kappa, label_confusion
from l2p_bullet.review.store import EXPORT_FIELDS, Answer, AnswerConflict, GradeRow, Store, load_grades


def _v1_db(path):
    """A database as the first release of the review app left it, with one answer in it."""
    conn = schema.connect(path)
    schema.migrate(conn, path, target=1)
    conn.execute("INSERT INTO runs VALUES ('r1', '/x/r1', 'abc', 'past', 'move A past B', '2026-01-01T00:00:00Z')")
    conn.execute("INSERT INTO answers (run_id, trajectory_sha256, reviewer, mode, view, grade, label, comment, "
                 "created_at, updated_at) VALUES ('r1', 'abc', 'ann', 'graded', '3d', 6, NULL, 'ok', 't0', 't0')")
    conn.close()


def test_an_old_database_is_migrated_and_keeps_its_answers(tmp_path):
    db = tmp_path / "old.sqlite"
    _v1_db(db)
    store = Store(db)
    assert store.migrated_from == 1
    with store.connect() as conn:
        assert schema.version(conn) == schema.SCHEMA_VERSION
    (row,) = store.grades()
    assert (row.run_id, row.reviewer, row.grade, row.comment, row.source, row.demo_id) == (
        "r1",
        "ann",
        6,
        "ok",
        "app",
        None,
    )


def test_a_newer_database_is_refused_untouched(tmp_path):
    db = tmp_path / "new.sqlite"
    Store(db)
    conn = sqlite3.connect(db)
    conn.execute(f"PRAGMA user_version = {schema.SCHEMA_VERSION + 1}")
    conn.close()
    before = db.read_bytes()
    with pytest.raises(SchemaVersionError) as e:
        Store(db)
    assert (e.value.found, e.value.supported) == (schema.SCHEMA_VERSION + 1, schema.SCHEMA_VERSION)
    with pytest.raises(SchemaVersionError):
        load_grades(db)
    assert db.read_bytes() == before


def test_a_foreign_sqlite_file_or_a_folder_is_refused(tmp_path):
    other = tmp_path / "other.sqlite"
    conn = sqlite3.connect(other)
    conn.execute("CREATE TABLE photos (id INTEGER)")
    conn.close()
    with pytest.raises(ReviewError, match=r"is an SQLite file of something else .*; give another --db"):
        Store(other)
    with sqlite3.connect(f"{other.as_uri()}?mode=ro", uri=True) as conn:  # someone else's database: not migrated
        tables = [r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")]
        assert tables == ["photos"] and conn.execute("PRAGMA user_version").fetchone()[0] == 0
    conn.close()
    with pytest.raises(ReviewError, match=r"^--db .* is a folder; give a file name"):
        Store(tmp_path)
    with pytest.raises(ReviewError, match=r"folder .*missing-folder does not exist"):
        Store(tmp_path / "missing-folder" / "r.sqlite")
    assert not (tmp_path / "missing-folder").exists()  # refused, not made
    with pytest.raises(ReviewError, match="is a file, not a run folder"):  # review SCENE.json by mistake
        find_runs([other])


def test_a_refused_foreign_sqlite_file_is_left_byte_for_byte(tmp_path):
    """Refused before anything is written: opening it used to switch it to WAL (its header changed, -wal and
    -shm files appeared beside it) before the check said it was not ours."""
    other = tmp_path / "photos.sqlite"
    with sqlite3.connect(other) as conn:
        conn.execute("CREATE TABLE photos (id INTEGER)")
    conn.close()
    before = other.read_bytes()
    with pytest.raises(ReviewError, match="is an SQLite file of something else"):
        Store(other)
    assert other.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["photos.sqlite"]


@pytest.mark.parametrize("user_version", [1, schema.SCHEMA_VERSION + 5])
def test_a_foreign_sqlite_file_with_its_own_user_version_is_refused_untouched(tmp_path, user_version):
    """Many programs set ``PRAGMA user_version`` themselves: at 1 the file was taken for a review database
    and migrated, above the schema refused as a newer l2p-bullet's, and switched to WAL before either."""
    other = tmp_path / "photos.sqlite"
    with sqlite3.connect(other) as conn:
        conn.execute("CREATE TABLE photos (id INTEGER)")
        conn.execute(f"PRAGMA user_version = {user_version}")
    conn.close()
    before = other.read_bytes()
    with pytest.raises(ReviewError, match="is an SQLite file of something else"):
        Store(other)
    with pytest.raises(ReviewError, match="is an SQLite file of something else"):
        load_grades(other)
    assert other.read_bytes() == before and sorted(p.name for p in tmp_path.iterdir()) == ["photos.sqlite"]


def test_answers_are_never_overwritten_silently(tmp_path, run_folder):  # noqa: F811
    store = Store(tmp_path / "r.sqlite")
    run = find_runs([run_folder])[0]
    store.register_runs([run])
    a = Answer(run.run_id, "ann", "graded", "3d", 7, None, "fine")
    first = store.save_answer(a, run.trajectory_sha256)
    with pytest.raises(AnswerConflict) as e:  # a second window submitting a "first" answer
        store.save_answer(Answer(run.run_id, "ann", "graded", "3d", 2), run.trajectory_sha256)
    assert e.value.reason == "answered"
    with pytest.raises(AnswerConflict):  # wrong trajectory version
        store.save_answer(a, "0" * 64)
    changed = store.save_answer(Answer(run.run_id, "ann", "graded", "3d", 9), run.trajectory_sha256,
                                replaces=first.updated_at)
    with pytest.raises(AnswerConflict) as e:  # changing from a stale copy
        store.save_answer(
            Answer(run.run_id, "ann", "graded", "3d", 1), run.trajectory_sha256, replaces=first.updated_at
        )
    assert e.value.reason == "stale-edit"
    store.save_answer(Answer(run.run_id, "bob", "graded", "3d", 3), run.trajectory_sha256)
    grades = {g.reviewer: g.grade for g in store.grades()}
    assert grades == {"ann": 9, "bob": 3}
    assert changed.created_at == first.created_at and changed.updated_at >= first.updated_at
    assert [(e["event"], e["grade"]) for e in store.log()] == [("answer", 7), ("change", 9), ("answer", 3)]


def test_a_changed_run_keeps_its_grades_and_is_reported(tmp_path, run_folder):  # noqa: F811
    store = Store(tmp_path / "r.sqlite")
    run = find_runs([run_folder])[0]
    store.register_runs([run])
    store.save_answer(Answer(run.run_id, "ann", "graded", "3d", 8), run.trajectory_sha256)
    traj = run.path / "trajectory.json"
    doc = json.loads(traj.read_text())
    doc["frames"] = doc["frames"][: len(doc["frames"]) // 2]
    traj.write_text(json.dumps(doc))
    reg = store.register_runs(find_runs([run_folder]))
    assert [(r.run_id, old, n) for r, old, n in reg.changed] == [(run.run_id, run.trajectory_sha256, 1)]
    assert store.registered_sha(run.run_id) == run.trajectory_sha256  # not re-registered without asking
    rep = build_report(store.grades())
    assert not rep["graded"]["app"]
    assert rep["problems"] == [{"run_id": run.run_id, "run_path": str(run.path), "problem": "changed since graded",
                                "answers": 1}]


def test_export_and_load_grades_round_trip(tmp_path, run_folder):  # noqa: F811
    store = Store(tmp_path / "r.sqlite")
    runs = find_runs([run_folder])
    store.register_runs(runs)
    store.save_answer(Answer(runs[0].run_id, "ann", "graded", "3d", 10, None, 'comma, "quote"\nnew line'),
                      runs[0].trajectory_sha256)
    store.save_answer(Answer(runs[1].run_id, "bob", "blind", "2d", 0, "none"), runs[1].trajectory_sha256)
    import_original(store)
    rows = store.grades()
    for name in ("g.csv", "g.jsonl"):
        assert store.export(tmp_path / name) == len(rows) == 182
        assert load_grades(tmp_path / name) == rows
        exported = (tmp_path / name).read_bytes()
        with pytest.raises(ReviewError, match="already exists; pass --force"):
            store.export(tmp_path / name)  # never overwritten without --force
        assert (tmp_path / name).read_bytes() == exported
    assert load_grades(store.path) == rows
    header = (tmp_path / "g.csv").read_text().splitlines()[0].split(",")
    assert tuple(header) == EXPORT_FIELDS
    for f in ("run_id", "run_path", "trajectory_sha256", "action", "sentence", "mode", "reviewer", "grade", "label",
              "comment", "view", "created_at", "updated_at", "source", "demo_id", "folder"):
        assert f in EXPORT_FIELDS
    with pytest.raises(ReviewError, match=r"must end in \.csv or \.jsonl"):
        store.export(tmp_path / "g.xlsx")
    assert not (tmp_path / "g.xlsx").exists()


def test_load_grades_never_writes_to_a_database(tmp_path):
    db = tmp_path / "old.sqlite"
    _v1_db(db)
    before = db.read_bytes()
    (row,) = load_grades(db)
    assert isinstance(row, GradeRow) and row.grade == 6
    assert db.read_bytes() == before


def test_importing_the_original_study_is_idempotent_and_gives_its_table_1(tmp_path):
    store = Store(tmp_path / "r.sqlite")
    first, again = import_original(store), import_original(store)
    assert (first.demos, first.grades, first.added) == (90, 180, 180)
    assert again.added == 0 and len(store.grades()) == 180
    demos = load_graded_demos()
    rep = build_report(store.grades())
    table = {r["group"].split("(")[1].rstrip(")"): r for r in rep["graded"]["original"]}
    assert set(table) == {"SlideToward", "SlideAway", "SlideNext", "SlidePast", "SlideAround", "SlideAroundDiscrete"}
    for folder, row in table.items():
        grades = [list(d["scores_txt"].values()) for d in demos if d["folder"] == folder]
        assert row["runs"] == 15 and row["grades"] == 30
        assert row["mean_grade"] == pytest.approx(np.mean(grades), abs=1e-4)
        assert row["disparity"] == pytest.approx(np.mean([abs(a - b) for a, b in grades]), abs=1e-4)
        assert -1 <= row["spearman_final_progress"] <= 1 and -1 <= row["spearman_judge"] <= 1
    assert table["SlideToward"]["mean_grade"] == pytest.approx(5.2333, abs=1e-4)  # 15 of the paper's 30 demos
    files = write_grade_report(rep, tmp_path / "report")
    assert {f.name for f in files} >= {"report.md", "report.json", "table1_original.csv", "table1.png", "agreement.png"}
    assert all(f.stat().st_size > 0 for f in files)


def test_fleiss_kappa_of_the_textbook_example():
    """Fleiss (1971) as in Wikipedia's worked example: 10 items, 14 raters, 5 categories, kappa 0.210."""
    counts = [[0, 0, 0, 0, 14], [0, 2, 6, 4, 2], [0, 0, 3, 5, 6], [0, 3, 9, 2, 0], [2, 2, 8, 1, 1],
              [7, 7, 0, 0, 0], [3, 2, 6, 3, 0], [2, 5, 3, 2, 2], [6, 5, 2, 1, 0], [0, 2, 2, 3, 7]]
    k = fleiss_kappa(np.array(counts))
    assert k["kappa"] == pytest.approx(0.210, abs=5e-4)
    assert k["p_bar"] == pytest.approx(0.378, abs=5e-4) and k["p_e"] == pytest.approx(0.213, abs=5e-4)
    assert np.isnan(fleiss_kappa(np.array([[2, 0], [0, 1]]))["kappa"])  # one item with two raters: no kappa


def test_disparity_and_confusion():
    assert disparity([[9, 8], [8, 5], [4]]) == pytest.approx(2.0)  # a single grade carries no disparity
    assert disparity([[1, 4, 7]]) == pytest.approx(4.0)  # pairs 3, 6, 3
    c = label_confusion([("a", "a"), ("a", "b"), ("b", "b"), ("x", "a")], ["a", "b"], ["a", "b", "none"])
    assert c["counts"] == [[1, 1, 0], [0, 1, 0]]
    assert c["shares"] == [[0.5, 0.5, 0.0], [0.0, 1.0, 0.0]]


def test_report_of_blind_labels_and_of_both_views(tmp_path, run_folder):  # noqa: F811
    """Question 2 and 3 from answers stored the way the app stores them, on real runs."""
    store = Store(tmp_path / "r.sqlite")
    runs = [r for r in find_runs([run_folder]) if r.video is not None]  # closer, next-to, past
    store.register_runs(runs)
    by_action = {r.action: r for r in runs}
    labels = {"ann": {"closer": "closer", "next-to": "closer", "past": "past"},
              "bob": {"closer": "closer", "next-to": "next-to", "past": "none"},
              "cy": {"closer": "next-to", "next-to": "closer", "past": "past"}}
    for who, picks in labels.items():
        for action, label in picks.items():
            store.save_answer(Answer(by_action[action].run_id, who, "blind", "3d", 5, label),
                              by_action[action].trajectory_sha256)
    for view, grades in (
        ("2d", {"closer": 4, "next-to": 6, "past": 8}),
        ("3d", {"closer": 5, "next-to": 9, "past": 9}),
    ):
        for action, g in grades.items():
            store.save_answer(
                Answer(by_action[action].run_id, "ann", "graded", view, g), by_action[action].trajectory_sha256
            )
    rep = build_report(store.grades())
    b = rep["blind"]
    assert b["confusion"]["rows"] == ["closer", "next-to", "past"]
    assert b["confusion"]["cols"] == ["closer", "next-to", "past", "none"]
    assert b["confusion"]["counts"] == [[2, 1, 0, 0], [2, 1, 0, 0], [0, 0, 2, 1]]
    expected = fleiss_kappa(np.array([[2, 1, 0, 0], [2, 1, 0, 0], [0, 0, 2, 1]]))["kappa"]
    assert b["fleiss"]["kappa"] == pytest.approx(expected, abs=1e-4) and b["fleiss"]["items"] == 3
    assert b["accuracy"] == pytest.approx(5 / 9, abs=1e-4)
    views = {v["action"]: v for v in rep["views"]}
    assert views["past"]["mean_2d"] == 8 and views["past"]["mean_3d"] == 9 and views["next-to"]["mean_3d_minus_2d"] == 3
    (row,) = [r for r in rep["graded"]["app"] if r["action"] == "past"]
    assert row["views"] == "3d+2d" and row["mean_grade"] == 8.5 and row["disparity"] is None  # one grader
    files = write_grade_report(rep, tmp_path / "rep")
    assert {"confusion.png", "views.png", "confusion.csv", "table1_app.csv"} <= {f.name for f in files}


_cell = st.text(alphabet=st.sampled_from(list("=+-@'\t\r\n\",; ab1(")), max_size=12)


@settings(max_examples=60, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(reviewer=_cell, comment=_cell, label=st.none() | _cell)
def test_a_csv_export_never_holds_a_formula_and_reads_back_exactly(tmp_path, reviewer, comment, label):
    """Issue 27.7: a reviewer named ``=HYPERLINK(...)`` was exported as a live formula."""
    import csv

    from l2p_bullet.data.grades import write_grades

    rows = [GradeRow(run_id="r1", reviewer=reviewer, comment=comment, label=label, grade=3,
                     sentence="=HYPERLINK(\"http://evil.example\",\"x\")"),
            GradeRow(run_id="r2", reviewer="@SUM(1+1)", comment="-2+3", grade=None)]
    out = tmp_path / "g.csv"
    write_grades(rows, out, force=True)
    with open(out, newline="", encoding="utf-8") as f:
        for record in csv.DictReader(f):
            for v in record.values():
                assert not v.startswith(("=", "+", "-", "@", "\t", "\r")), record
    assert load_grades(out) == [GradeRow(**{**r.__dict__, "label": r.label or None}) for r in rows]
