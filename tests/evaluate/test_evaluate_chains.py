"""``evaluate --chains K`` (evaluate/chains.py): seeded chain scenes and draws, CALVIN's numbers, and the same
rows from the local pool and from a real two-node Ray cluster."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.errors import EvaluationError
from l2p_bullet.evaluate.chains import chain_report, chain_report_text, chain_scenes, clause_rows
from l2p_bullet.evaluate.results import comparable
from l2p_bullet.evaluate.runner import EvaluationConfig, evaluate, load_rows

TWO = EvaluationConfig(chains=2, scenes=2, seed=5)  # 2 chains of 2 clauses


def test_chain_scenes_hold_3_to_5_blocks_and_are_seeded():
    a, b = chain_scenes(12, seed=40), chain_scenes(12, seed=40)
    assert [s.scene.to_dict() for s in a] == [s.scene.to_dict() for s in b]
    counts = {len(s.scene.objects) for s in a}
    assert counts <= {3, 4, 5} and len(counts) > 1
    assert [s.id for s in a[:2]] == ["chain/40", "chain/41"]


def test_bystanders_fix_every_chain_scene_at_two_more_blocks():
    """``--chains K --bystanders 3``: the same seeds, five blocks each (A and B where the seed puts them)."""
    five = EvaluationConfig(chains=5, scenes=6, seed=40, bystanders=3).scene_set()
    assert {len(s.scene.objects) for s in five} == {5}
    assert [s.id for s in five[:2]] == ["chain/40/5b", "chain/41/5b"]
    drawn = chain_scenes(6, seed=40)
    assert [s.scene.objects[:2] for s in five] == [s.scene.objects[:2] for s in drawn]
    assert five == EvaluationConfig(chains=5, scenes=6, seed=40, bystanders=3).scene_set()


def test_bad_chain_settings_are_refused_before_anything_runs(tmp_path):
    with pytest.raises(EvaluationError, match="1 to 10"):
        evaluate(EvaluationConfig(chains=11, scenes=1), tmp_path / "a", workers=0, progressbar=False)
    with pytest.raises(EvaluationError, match="draws its own scenes"):
        evaluate(EvaluationConfig(chains=2, study=True), tmp_path / "b", workers=0, progressbar=False)


def test_chain_report_is_calvins_arithmetic():
    def row(i, completed, n=3):
        clauses = [{"clause": c, "action": "closer", "success": c <= completed, "others_moved_m": 0.0002,
                    "failed_stage": None} for c in range(1, min(completed + 1, n) + 1)]
        return {"run_id": f"chain/{i}|chain3|default|chain", "scene_id": f"chain/{i}", "seed": i, "mode": "chain",
                "completed": completed, "clauses": clauses, "redraws": 1, "error": None}

    rep = chain_report([row(0, 3), row(1, 1), row(2, 0), row(3, 2)])
    assert rep["success_first"] == {"1": 0.75, "2": 0.5, "3": 0.25}
    assert rep["average_completed"] == 1.5 and rep["redraws"] == 4 and rep["chains"] == 4
    assert rep["first_clause_success"] == 0.75
    assert len(clause_rows([row(0, 3)])) == 3


@pytest.fixture(scope="module")
def pool_rows(tmp_path_factory):
    out = tmp_path_factory.mktemp("chains") / "pool"
    evaluate(TWO, out, workers=1, progressbar=False)
    return out, load_rows(out)


@pytest.mark.slow
def test_rows_per_chain_and_per_clause(pool_rows):
    _, rows = pool_rows
    assert [r["run_id"] for r in rows] == ["chain/5|chain2|default|chain", "chain/6|chain2|default|chain"]
    for r in rows:
        assert r["error"] is None, r["error"]
        assert r["mode"] == "chain" and r["sentence"].count(", then ") == 1
        cl = r["clauses"]
        assert 1 <= len(cl) <= 2 and [c["clause"] for c in cl] == list(range(1, len(cl) + 1))
        in_a_row = next((i for i, c in enumerate(cl) if not c["success"]), len(cl))
        assert r["completed"] == in_a_row and len(cl) == min(2, in_a_row + 1)  # the first failure stops it
        assert bool(r["success"]) == (r["completed"] == 2)
        assert all(c["others_moved_m"] < 0.001 or not c["success"] for c in cl)
        assert r["redraws"] >= 0


@pytest.mark.slow
def test_cli_reports_success_of_the_first_clauses(pool_rows):
    out, rows = pool_rows
    r = CliRunner().invoke(main, ["evaluate", "--out", str(out), "--report", "--json"])
    assert r.exit_code == 0, r.output
    rep = json.loads(r.stdout)["report"]["chains"]
    done = [row["completed"] for row in rows]
    assert rep["success_first"]["1"] == sum(d >= 1 for d in done) / 2
    assert rep["average_completed"] == sum(done) / 2
    per_clause = [json.loads(line) for line in (out / "clauses.jsonl").read_text().splitlines()]
    assert len(per_clause) == sum(len(row["clauses"]) for row in rows)
    assert {c["run_id"] for c in per_clause} == {row["run_id"] for row in rows}


@pytest.mark.slow
def test_a_two_node_ray_cluster_gives_the_pool_rows(pool_rows, tmp_path):
    """``ray start --head`` plus a second ``ray start --address`` node on the loopback address (not --ray
    local): one CPU per node, so the two actors run on different nodes."""
    pytest.importorskip("ray")
    from ray_cluster import two_node_cluster

    _, rows = pool_rows
    with two_node_cluster() as address:
        s = evaluate(TWO, tmp_path / "ray", workers=2, ray=address, progressbar=False)
    assert s.backend == "ray" and s.ran == 2
    got = load_rows(tmp_path / "ray")
    assert [comparable(r) for r in got] == [comparable(r) for r in rows]
    assert len({r["worker"] for r in got}) == 2  # two actors, one per node (each node has one CPU)


def test_an_evaluation_stored_before_chains_existed_resumes(tmp_path):
    from l2p_bullet.evaluate.results import ResultsStore

    config = EvaluationConfig(actions=["closer"], scenes=0)
    with ResultsStore(tmp_path) as store:  # the settings as an older l2p-bullet stored them
        store.set_meta("config", {k: v for k, v in config.to_dict().items() if k != "chains"})
    s = evaluate(config, tmp_path, workers=0, resume=True, progressbar=False)
    assert s.total == 0
    with pytest.raises(EvaluationError, match="chains"):
        evaluate(EvaluationConfig(actions=["closer"], scenes=0, chains=2), tmp_path, workers=0, resume=True,
                 progressbar=False)


@pytest.mark.slow
def test_chains_on_another_arm_are_drawn_and_performed_by_it(tmp_path):
    """``evaluate --chains K --arm xarm6``: the forecast, the world and every clause are the xArm's. One
    evaluation that keeps its run folders answers both (keep only says where a run folder is written)."""
    kept = EvaluationConfig(chains=2, scenes=2, seed=5, arm="xarm6", keep="all")
    evaluate(kept, tmp_path / "kept", workers=0, progressbar=False)
    rows = load_rows(tmp_path / "kept")
    assert len(rows) == 2 and all(r["error"] is None for r in rows)
    # the arm performed each chain's first clause (executed and judged, whatever the verdict: the chains drawn
    # depend on the planner, and since "around" from afar is performed rather than re-drawn one of them fails)
    for r in rows:
        clauses = r["clauses"] if isinstance(r["clauses"], list) else json.loads(r["clauses"])
        first = clauses[0]
        assert first["failed_stage"] is None and first["final_progress"] is not None and first["reason"], first
        assert first["frames"][1] > first["frames"][0]
    summaries = list((tmp_path / "kept" / "runs").glob("*/summary.json"))
    assert summaries and {json.loads(p.read_text())["arm"] for p in summaries} == {"xarm6"}


def test_refused_chains_count_as_none_completed_and_by_cause():
    """``--chain-draw sentence``: a refused chain is no error, completes nothing and is counted by its clause
    and check; the chain's planning is compared with its clauses planned alone."""

    def row(i, completed, error=None, timings=None):
        return {"run_id": f"chain/{i}|chain2|default|chain", "scene_id": f"chain/{i}", "seed": i, "mode": "chain",
                "completed": completed, "clauses": [], "redraws": 0, "error": error,
                "error_type": "refused" if error else None, "timings": timings}

    refusal = 'clause {} ("move C around A") cannot be planned ({}): no room'
    rows = [row(0, 2, timings={"forecast": 3.0, "forecast_alone": 2.0}),
            row(1, 1, timings={"forecast": 1.0, "forecast_alone": 1.0}),
            row(2, 0, refusal.format(2, "room-around")), row(3, 0, refusal.format(2, "room-around")),
            row(4, 0, refusal.format(1, "far-around"))]
    rep = chain_report(rows)
    assert rep["refused"] == 3 and rep["errors"] == 0 and rep["average_completed"] == 0.6
    assert rep["refused_by"] == {"clause 2: room-around": 2, "clause 1: far-around": 1}
    assert rep["forecast_ratio"] == {"chains": 2, "mean": 1.25, "of_sums": 4 / 3, "max": 1.5}
    assert "refused up front: 3 (60.0 %): clause 2: room-around 2" in chain_report_text(rep)


def test_a_sentence_is_drawn_whole_and_the_same_from_the_same_seed(tmp_path):
    from l2p_bullet.evaluate.chains import chain_rng, draw_sentence
    from l2p_bullet.plugins import registry

    plugins = registry.discover()
    scene = chain_scenes(1, seed=7)[0].scene
    a = draw_sentence(scene, 5, ["closer", "past"], chain_rng(7, 5), plugins)
    b = draw_sentence(scene, 5, ["closer", "past"], chain_rng(7, 5), plugins)
    assert [c.text for c in a] == [c.text for c in b] and [c.index for c in a] == [1, 2, 3, 4, 5]
    with pytest.raises(EvaluationError, match="chain-draw"):
        evaluate(EvaluationConfig(chains=2, scenes=1, chain_draw="whole"), tmp_path / "a", workers=0,
                 progressbar=False)
