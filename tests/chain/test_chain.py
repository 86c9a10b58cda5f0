"""Chains of clauses in ``perform`` (l2p_bullet/chain): parsing, up-front refusals, one continuous episode."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from l2p_bullet.chain import MAX_CLAUSES, perform_chain, resolve_clauses, split_clauses
from l2p_bullet.cli import main
from l2p_bullet.core.scene import Scene, SceneObject
from l2p_bullet.errors import InfeasibleError, LanguageError, UnknownObjectError
from l2p_bullet.plugins import registry

CHAIN = "move A next to B, then slide C past A and then move D around B"


def four_blocks(b_xy=(0.0, 0.02)) -> Scene:
    """Four 4 cm blocks spread over the workspace (the anchor B near the centre unless told)."""
    return Scene([SceneObject("A", "red", 0.04, (0.10, -0.08), 0.2), SceneObject("B", "green", 0.04, b_xy, 0.0),
                  SceneObject("C", "blue", 0.04, (-0.12, -0.06), 0.4),
                  SceneObject("D", "yellow", 0.04, (-0.06, 0.10), 0.1)]).validate()


@pytest.mark.parametrize("sentence, texts", [
    (CHAIN, ["move A next to B", "slide C past A", "move D around B"]),
    ("move A around B; move C next to D", ["move A around B", "move C next to D"]),
    ("move A around B after that move C closer to D", ["move A around B", "move C closer to D"]),
    ("Then move A around B.", ["move A around B"]),
    ("move A around B", ["move A around B"]),
])
def test_split_clauses(sentence, texts):
    assert split_clauses(sentence) == texts


def test_a_missing_verb_repeats_the_previous_one_and_its_mover():
    clauses = resolve_clauses("slide A around B, then next to C; then the blue block past D", four_blocks(),
                              registry.discover())
    got = [(c.index, c.command.verb, c.command.mover, c.command.action, c.command.anchor) for c in clauses]
    assert got == [(1, "slide", "A", "around", "B"), (2, "slide", "A", "next-to", "C"),
                   (3, "slide", "C", "past", "D")]


def test_unknown_block_in_clause_3_refused_before_anything_moves(tmp_path):
    out = tmp_path / "run"
    with pytest.raises(UnknownObjectError, match=r'^clause 3 \("push E past A"\): .*"E"'):
        perform_chain("move A next to C, then move D around B, then push E past A", four_blocks(), out_dir=out,
                      render=False)
    assert not out.exists()
    with pytest.raises(UnknownObjectError, match=r"^clause 2 .*purple"):
        resolve_clauses("move A next to C, then push the purple block past A", four_blocks(), registry.discover())


def test_too_many_clauses_refused():
    with pytest.raises(LanguageError, match=f"at most {MAX_CLAUSES}"):
        resolve_clauses("; ".join(["move A next to B"] * (MAX_CLAUSES + 1)), four_blocks(), registry.discover())


def test_impossible_clause_refused_up_front_with_its_index(tmp_path):
    out = tmp_path / "run"
    runner = CliRunner()
    r = runner.invoke(main, ["perform", "move A next to C, then move D around B", "--no-render", "--json", "-q",
                             "--out", str(out), "--scene", _save(four_blocks(b_xy=(0.0, 0.335)), tmp_path)])
    assert r.exit_code == 2, r.output
    d = json.loads(r.stdout)
    assert d["refused"]["check"] == "room-around" and d["refused"]["details"]["clause"] == 2
    assert d["error"].startswith('clause 2 ("move D around B") cannot be planned (room-around)')
    assert not out.exists()  # refused before the arm moved or anything was written
    with pytest.raises(
        InfeasibleError, match=r'^clause 1 \("move D around B"\) cannot be planned \(room-around\)'
    ) as e:
        perform_chain("move D around B; move A next to C", four_blocks(b_xy=(0.0, 0.335)), out_dir=out, render=False)
    assert e.value.check == "room-around" and e.value.details["clause"] == 1 and not out.exists()


def _save(scene: Scene, folder) -> str:
    p = folder / "scene.json"
    p.write_text(json.dumps(scene.to_dict()))
    return str(p)


@pytest.fixture(scope="module")
def chain_runs(tmp_path_factory):
    """The same 3-clause chain performed twice with one seed (each costs about 5 s unrendered)."""
    base = tmp_path_factory.mktemp("chain")
    return [perform_chain(CHAIN, four_blocks(), out_dir=base / f"run{i}", render=False, seed=7) for i in (1, 2)]


@pytest.mark.slow
def test_three_clauses_on_four_blocks(chain_runs):
    r = chain_runs[0]
    assert r.success and r.completed == 3, r.verdict()
    traj = json.loads((r.out_dir / "trajectory.json").read_text())
    segs = traj["segments"]
    assert [(s["clause"], s["action"], s["mover"], s["anchors"]) for s in segs] == [
        (1, "next-to", "A", ["B"]), (2, "past", "C", ["A"]), (3, "around", "D", ["B"])]
    assert segs[0]["first_frame"] == 0 and segs[-1]["last_frame"] == len(traj["frames"]) - 1
    for a, b in zip(segs, segs[1:], strict=False):
        assert b["first_frame"] == a["last_frame"] + 1  # one continuous episode, no gap, no overlap
    assert all(set(f["poses"]) == {"A", "B", "C", "D"} for f in traj["frames"])
    summary = json.loads((r.out_dir / "summary.json").read_text())
    assert summary["chain"]["success"] and summary["chain"]["completed"] == 3
    assert [c["success"] for c in summary["clauses"]] == [True, True, True]
    plan = json.loads((r.out_dir / "plan.json").read_text())
    assert plan["mover"] == "A" and [c["plan"]["mover"] for c in plan["clauses"]] == ["A", "C", "D"]
    assert plan["scene"] == plan["chain"]["scene"] == four_blocks().to_dict()  # the one-clause layout's scene too
    assert plan["scene_sha256"] == four_blocks().digest()
    # each clause starts where the previous one really left its mover (re-planned from the world)
    c_end = traj["frames"][segs[1]["last_frame"]]["poses"]["C"]
    assert plan["clauses"][2]["plan"]["anchor_pose"][:2] == pytest.approx(
        traj["frames"][segs[2]["first_frame"]]["poses"]["B"][:2], abs=1e-5)
    assert c_end[:2] == pytest.approx(traj["frames"][-1]["poses"]["C"][:2], abs=1e-3)


@pytest.mark.slow
def test_bystanders_stay_put(chain_runs):
    r = chain_runs[0]
    traj = json.loads((r.out_dir / "trajectory.json").read_text())
    for seg in traj["segments"]:
        frames = traj["frames"][seg["first_frame"]:seg["last_frame"] + 1]
        for name in "ABCD":
            if name != seg["mover"]:
                x0, y0 = frames[0]["poses"][name][:2]
                moved = max(((f["poses"][name][0] - x0) ** 2 + (f["poses"][name][1] - y0) ** 2) ** 0.5
                            for f in frames)
                assert moved < 0.001, (seg["clause"], name, moved)
    summary = json.loads((r.out_dir / "summary.json").read_text())
    assert set(summary["displacements_m"]) == {"B"} and summary["displacements_m"]["B"] < 0.001
    # the one-clause fields with a chain-wide meaning (a reader that knows no clauses finds them)
    moved = [v for c in summary["clauses"] for v in c["displacements_m"].values()]
    assert summary["anchor_displacement_m"] == pytest.approx(max(moved)) and summary["disturbed"] == []
    assert summary["max_deviation_m"] == pytest.approx(max(c["max_deviation_m"] for c in summary["clauses"]))
    assert (summary["action"], summary["mover"], summary["anchor"]) == ("next-to", "A", "B")


@pytest.mark.slow
def test_chain_is_deterministic_for_a_seed(chain_runs):
    a, b = ((r.out_dir / "trajectory.json").read_bytes() for r in chain_runs)
    assert a == b
    pa, pb = (json.loads((r.out_dir / "plan.json").read_text()) for r in chain_runs)
    for d in (pa, pb):
        for c in d["clauses"]:
            for p in (c["plan"], c["forecast"]):
                p.pop("seconds", None)
        d.pop("seconds", None)
    assert pa == pb


# --- the other commands read chain runs --------------------------------------------------------------


@pytest.mark.slow
def test_score_scores_each_segment_with_its_own_blocks(chain_runs):
    from l2p_bullet.commands.learn import score_file

    traj = chain_runs[0].out_dir / "trajectory.json"
    d = score_file("around", traj)
    segs = d["segments"]
    assert [(s["clause"], s["mover"], s["anchors"]) for s in segs] == [
        (1, "A", ["B"]),
        (2, "C", ["A"]),
        (3, "D", ["B"]),
    ]
    assert len(segs[2]["progress"]) == segs[2]["last_frame"] - segs[2]["first_frame"] + 1
    recorded = json.loads(traj.read_text())["frames"][-1]["progress"]  # clause 3 is "around": its own model
    assert segs[2]["final"] == pytest.approx(recorded, abs=1e-4)


@pytest.mark.slow
def test_export_writes_one_episode_per_clause(chain_runs, tmp_path):
    out = tmp_path / "export"
    r = CliRunner().invoke(main, ["export", str(chain_runs[0].out_dir), str(out)])
    assert r.exit_code == 0, r.output
    eps = [json.loads(line) for line in (out / "episodes.jsonl").read_text().splitlines()]
    assert [(e["task"], e["mover"], e["anchor"], e["extra"]["chain"]["clause"]) for e in eps] == [
        ("move A next to B", "A", "B", 1), ("slide C past A", "C", "A", 2), ("move D around B", "D", "B", 3)]
    assert all(e["extra"]["success"] is True for e in eps)
    assert sum(len(e["frames"]) for e in eps) == len(json.loads((chain_runs[0].out_dir / "trajectory.json")
                                                                 .read_text())["frames"])


@pytest.mark.slow
def test_review_follows_the_clause(chain_runs):
    from l2p_bullet.review.runs import motion_for_browser, read_run

    run = read_run(chain_runs[0].out_dir)
    seen = motion_for_browser(run, blind=False)
    assert [(s["clause"], s["mover"], s["anchor"]) for s in seen["segments"]] == [(1, "A", "B"), (2, "C", "A"),
                                                                                   (3, "D", "B")]
    blind = motion_for_browser(run, blind=True)
    assert "text" not in blind["segments"][0] and "action" not in blind["segments"][0]


@pytest.mark.slow
def test_replay_of_a_chain_plan_replays_every_clause(chain_runs, tmp_path):
    src = chain_runs[0].out_dir
    out = tmp_path / "replay"
    r = CliRunner().invoke(main, ["replay", str(src / "plan.json"), "--no-render", "--out", str(out)])
    assert r.exit_code == 0, r.output
    a, b = (json.loads((d / "trajectory.json").read_text()) for d in (src, out))
    assert [s["mover"] for s in b["segments"]] == ["A", "C", "D"]
    last_a, last_b = a["frames"][-1]["poses"], b["frames"][-1]["poses"]
    for name in "ABCD":  # the plans are stored rounded to 1e-6 m: the replay ends where the run did
        assert last_b[name][:2] == pytest.approx(last_a[name][:2], abs=2e-4)
    assert json.loads((out / "summary.json").read_text())["chain"]["completed"] == 3


def test_plan_writes_every_clause(tmp_path):
    out = tmp_path / "plan"
    r = CliRunner().invoke(main, ["plan", "move A next to B; then slide C past A", "--out", str(out), "--seed", "1",
                                  "--scene", _save(four_blocks(), tmp_path), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    assert d["chain"] and [c["action"] for c in d["clauses"]] == ["next-to", "past"]
    doc = json.loads((out / "plan.json").read_text())
    assert doc["mover"] == "A" and doc["clauses"][1]["forecast"]["mover"] == "C"
    text = CliRunner().invoke(main, ["plan", "move A next to B; then slide C past A", "--out", str(out), "--seed", "1",
                                     "--scene", _save(four_blocks(), tmp_path), "--force"])  # without --json: text
    lines = text.output.strip().splitlines()
    assert text.exit_code == 0 and lines[0].startswith('1. move A next to B: "next-to"'), text.output
    assert lines[-1] == f"plan folder: {out}"
    assert doc["clauses"][1]["forecast"]["anchor_pose"][:2] == pytest.approx(doc["path"][-1][:2], abs=1e-6)
    assert (out / "plan.png").is_file() and (out / "plan-2.png").is_file()


@pytest.mark.slow
def test_the_review_page_names_the_clause_being_performed(chain_runs, chromium, tmp_path):
    import shutil

    from review_fixtures import Live, open_page

    runs = tmp_path / "runs"
    shutil.copytree(chain_runs[0].out_dir, runs / "chain")
    s = Live(tmp_path / "reviews.sqlite", runs, view="2d")
    try:
        page, errors = open_page(chromium, s.url, 1000, 660)
        page.wait_for_selector("#name")
        page.fill("#name", "ann")
        page.press("#name", "Enter")
        page.wait_for_function(
            "() => document.querySelector('#sentence').textContent.includes('now 1/3: move A next to B')"
        )
        assert page.inner_text("#sentence").startswith(f"“{CHAIN}”")
        assert not errors, errors
    finally:
        s.stop()


@pytest.mark.slow
def test_video_captions_follow_the_clauses(chain_runs):
    from types import SimpleNamespace

    from l2p_bullet.chain.files import captions

    r = chain_runs[0]
    frames = json.loads((r.out_dir / "trajectory.json").read_text())["frames"]
    times = [i / 10 for i in range(int(frames[-1]["t"] * 10) + 1)]  # a 10 fps camera over the episode
    shown = captions(r, SimpleNamespace(frames=frames, image_times=times))
    firsts = [frames[c.first_frame]["t"] for c in r.results]
    expect = [next(f"{c.clause.index}/3: {c.clause.command.sentence}" for c, t0 in reversed(list(zip(r.results, firsts,
               strict=True))) if t + 1e-6 >= t0) for t in times]
    assert shown == expect
    assert shown[0] == "1/3: move A next to B" and shown[-1] == "3/3: move D around B"


@pytest.mark.slow
def test_the_first_clause_is_the_one_clause_run(chain_runs, tmp_path):
    """Clause 1 starts from the scene itself: its frames and verdict are exactly a one-clause perform's, so a
    chain's first-clause success is the single action's success on the same scene and seed."""
    from l2p_bullet.pipeline import perform

    single = perform("move A next to B", four_blocks(), out_dir=tmp_path / "one", render=False, seed=7)
    traj = json.loads((chain_runs[0].out_dir / "trajectory.json").read_text())
    seg = traj["segments"][0]
    alone = json.loads((tmp_path / "one" / "trajectory.json").read_text())["frames"]
    assert traj["frames"][seg["first_frame"]:seg["last_frame"] + 1] == alone
    assert chain_runs[0].results[0].verdict == single.verdict


@pytest.mark.slow
def test_eight_blocks(tmp_path):
    import math

    names, colours = "ABCDEFGH", ["red", "green", "blue", "yellow", "orange", "purple", "cyan", "pink"]
    ring = [SceneObject(names[i + 1], colours[i + 1], 0.04, (0.15 * math.cos(2 * math.pi * i / 7),
                                                            0.15 * math.sin(2 * math.pi * i / 7)), 0.1 * i)
            for i in range(7)]
    scene = Scene([SceneObject("A", "red", 0.04, (0.0, 0.0)), *ring]).validate()
    r = perform_chain("move B next to A, then move the orange block closer to A", scene, out_dir=tmp_path / "r",
                      render=False)
    assert r.success, r.verdict()
    assert max(v for c in r.results for k, v in c.displacements_m.items() if k != c.clause.command.mover) < 0.001
