"""The automatic confusion matrices and ``evaluate --report``: rows = asked, columns = recognised."""

from __future__ import annotations

import json
import math

import numpy as np
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.evaluate.confusion import confusion, touching_finding
from l2p_bullet.evaluate.report import report_text
from l2p_bullet.evaluate.results import ResultsStore


def _row(i: int, action: str, accepted: set[str], scores: dict[str, float], gap: float = 1.0, error=None) -> dict:
    acts = ("closer", "away", "next-to", "past", "around")
    return {"run_id": f"s{i}|{action}", "idx": i, "action": action, "success": int(action in accepted),
            "error": error, "final_gap_blocks": gap, "final_progress": scores.get(action),
            "judged": None if error else {a: {"success": a in accepted, "score": 0.5} for a in acts},
            "scored": None if error else {a: scores.get(a, 0.0) for a in acts}}


ROWS = [
    _row(0, "closer", {"closer", "next-to"}, {"closer": 0.9, "next-to": 0.95}, gap=0.15),
    _row(1, "closer", {"closer"}, {"closer": 0.9, "next-to": 0.5}, gap=0.8),
    _row(2, "around", {"around"}, {"around": 0.97, "past": 0.3}),
    _row(3, "around", set(), {}, error="PlanError: no room"),
]


def test_matrices_read_rows_as_asked_and_columns_as_recognised():
    c = confusion(ROWS)
    assert c.asked == ["closer", "around"] and c.recognised == ["closer", "away", "next-to", "past", "around"]
    assert c.counts.tolist() == [2, 1] and c.errors.tolist() == [0, 1]
    np.testing.assert_allclose(c.judges[0], [1.0, 0.0, 0.5, 0.0, 0.0])
    np.testing.assert_allclose(c.models[0], [0.9, 0.0, 0.725, 0.0, 0.0])
    np.testing.assert_allclose(c.argmax[0], [0.5, 0.0, 0.5, 0.0, 0.0])  # rows of the argmax matrix sum to one
    np.testing.assert_allclose(c.argmax[1], [0, 0, 0, 0, 1.0])
    f = touching_finding(ROWS, "closer", "next-to")
    assert (f["runs"], f["touching"], f["read_as_also"]) == (2, 1, 1)
    assert f["share_within"]["0.2"] == 0.5


def test_report_alone_reads_a_recorded_evaluation_and_saves_plots(tmp_path):
    with ResultsStore(tmp_path) as store:
        store.set_meta("config", {"actions": ["closer", "around"]})
        for r in ROWS:
            store.add(r)
    res = CliRunner().invoke(main, ["evaluate", "--out", str(tmp_path), "--report"])
    assert res.exit_code == 0, res.output
    assert "judge-based confusion" in res.output and "asked \\ recognised" in res.output
    assert "within 0.2 / 0.3 / 0.5 block: 50 / 50 / 50 % of 2" in res.output
    for name in ("confusion_judges.png", "confusion_models.png"):
        assert (tmp_path / name).read_bytes()[:4] == b"\x89PNG"
    data = json.loads((tmp_path / "report.json").read_text())
    assert data["confusion"]["judges"][0] == [1.0, 0.0, 0.5, 0.0, 0.0]
    s = data["success"][1]
    assert (s["action"], s["runs"], s["errors"], s["success"]) == ("around", 2, 1, 0.5)


def test_unknown_settings_are_one_line_errors(tmp_path):
    r = CliRunner().invoke(main, ["evaluate", "--planner", "gredy", "--scenes", "1", "--out", str(tmp_path / "a")])
    assert r.exit_code == 2 and 'Did you mean "greedy"' in r.output
    r = CliRunner().invoke(main, ["evaluate", "--scenes", "1", "--study", "--out", str(tmp_path / "b")])
    assert r.exit_code == 2 and "choose one scene set" in r.output
    r = CliRunner().invoke(main, ["evaluate", "--out", str(tmp_path / "c"), "--resume"])
    assert r.exit_code == 2 and "no evaluation to resume" in r.output


def test_empty_cells_are_blank_not_zero():
    rows = [{"run_id": "1", "action": "closer", "error": None, "judged": {"closer": {"success": True}}, "success": 1,
             "final_gap_blocks": 0.5,
             "scored": {"closer": 0.9}},
            {"run_id": "2", "action": "between", "error": "PlanError: no room between B and C", "judged": None},
            {"run_id": "3", "action": "between", "error": None, "success": 1, "final_gap_blocks": 1.0,
             "judged": {"closer": {"success": False}, "between": {"success": True}},
             "scored": {"closer": 0.2, "between": 0.8}}]
    c = confusion(rows)
    assert c.asked == ["closer", "between"] and c.recognised == ["closer", "between"] and c.judges[0, 0] == 1.0
    # between cannot judge nor score closer's one-anchor runs: blank, not 0 %
    assert math.isnan(c.judges[0, 1]) and math.isnan(c.models[0, 1]) and math.isnan(c.argmax[0, 1])
    assert c.judges[1].tolist() == [0.0, 1.0] and c.argmax[1].tolist() == [0.0, 1.0]
    assert c.to_dict()["judges"][0] == [1.0, None]  # null in report.json
    text = report_text(rows)
    assert "between: 1 x PlanError: no room between B and C" in text
    assert "nan" not in text
