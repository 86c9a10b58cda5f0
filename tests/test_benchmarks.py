"""Every benchmark still runs: each ``benchmarks/bench_*.py`` at its smallest size, as a process of its own.

A benchmark is run by hand, rarely, and its tables go into the docs; an import or option that a change
broke would otherwise be found only at the next measurement. ``SMALLEST`` names, for every benchmark,
the options that make it cheapest while it still goes through all its code (one scene, one action,
one LSTM for one or two epochs, one way of a session split, a few small frames); a new benchmark must add
its own line (the first test says so), and one that has no small size yet gets an option for it. (Smallest is
in CPU, not in options: bench_prepositions trains its plugins 4 epochs on 4 generated events a session, not 1 epoch
on 16, because the planner searches 3-8 s for a path a one-epoch model scores well.) Each
runs in an empty temporary folder, so a cache or output a benchmark keeps relative to where it runs
stays out of the checkout. The numbers are not checked: only that it finishes and prints its table.

The processes are forked from one Python that imported numpy, torch, PyBullet and the package once
(tests/bench_runner.py: each was 2 CPU s of a 3-10 s run), one after another, so the module is one unit of work.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from review_fixtures import CHROMIUM, make_runs

ROOT = Path(__file__).resolve().parents[1]
BENCHMARKS = ROOT / "benchmarks"

SMALLEST: dict[str, list[str]] = {
    "bench_asked.py": ["--corpora", "heldout109.tsv", "--workers", "0"],
    "bench_arms.py": ["--arms", "xarm6", "--actions", "closer", "--scenes", "1", "--timed", "0"],
    "bench_chains.py": ["--chains", "1", "--clauses", "2"],
    "bench_clauses.py": ["--every", "38", "--kinds", "level", "--manners", "push", "--actions", "closer"],
    "bench_embodiment.py": ["--repeats", "1", "--resolution", "64x48", "--fps", "2", "--arc", "30", "--samples", "1"],
    "bench_envs.py": ["--steps", "5", "--size", "32"],
    "bench_evaluate.py": ["--runs", "1", "--actions", "closer", "--no-ray"],
    "bench_feedback.py": ["--quick", "--only", "shipped,head", "--head-seeds", "1"],
    "bench_generalise.py": ["--ensemble", "1", "--epochs", "1", "--cache", "cache", "--one-way"],
    "bench_learning.py": ["--quick", "--skip-split", "--epochs", "1", "--actions", "closer"],
    "bench_manners.py": ["--scenes", "1", "--manners", "push", "--actions", "closer"],
    "bench_objects.py": ["--scenes", "1", "--actions", "closer"],
    "bench_past.py": ["--sizes", "0.03", "--scenes", "1"],
    "bench_perform.py": ["--scenes", "1", "--render-scenes", "0", "--cold", "0", "--actions", "closer"],
    "bench_pictures.py": ["--sentences", "move A closer to B", "--renderer", "tiny", "--fps", "2",
                          "--resolution", "160x120"],
    "bench_planning.py": ["--scenes", "1", "--planners", "default", "--actions", "closer"],
    "bench_prepositions.py": ["--scenes", "1", "--ensemble", "1", "--epochs", "4", "--events", "4"],
    "bench_recognize.py": ["--quick", "--cache", "cache", "--one-way"],
    "bench_render.py": ["--only", "0"],
    "bench_review.py": ["--runs", "1", "--no-watch"],  # and --runs-dir: the review tests' runs (below)
    "bench_robustness.py": ["--scenes", "1", "--actions", "closer"],
    "bench_rows.py": ["--scenes", "1", "--sizes", "3"],
    "bench_sweep.py": ["--scenes", "1", "--arms", "xarm6"],
    "bench_thresholds.py": ["--chains", "1", "--clauses", "2", "--thresholds", "closer=0.97"],
}
"""Benchmark file -> the options of its smallest run."""


def test_every_benchmark_has_a_smallest_size():
    found = sorted(p.name for p in BENCHMARKS.glob("bench_*.py"))
    assert found == sorted(SMALLEST), "add the smallest options of a new benchmark to SMALLEST (or drop a gone one)"


def _env() -> dict[str, str]:
    """The checkout first: a benchmark imports l2p_bullet (and research/) from the tree it belongs to."""
    return {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p),
            "MPLBACKEND": "Agg"}


PLAN_ONLY = ["--plan-only", "--chains", "1", "--clauses", "2", "--seed", "9700", "--json", "plan.json"]
"""bench_chains.py's --plan-only run (test_bench_chains_plan_only_counts_...), run with the others."""


@pytest.fixture(scope="module")
def smallest_runs(tmp_path_factory, request) -> dict[str, tuple[int, str, str, Path]]:
    """Every benchmark's smallest run (and bench_chains' plan-only one, as "plan-only"): name -> (exit code, stdout,
    stderr, its working folder). bench_review grades the review tests' four runs (``review_fixtures.make_runs``:
    performed once per test session, shared by the workers) instead of performing one of its own; without Chromium
    it is left out (its test says why)."""
    root = tmp_path_factory.mktemp("bench")
    jobs, names = [], {}
    for name, args in [*SMALLEST.items(), ("plan-only", PLAN_ONLY)]:
        script = BENCHMARKS / ("bench_chains.py" if name == "plan-only" else name)
        args = list(args)
        if name == "bench_review.py":
            if not os.path.exists(CHROMIUM):
                continue
            base = tmp_path_factory.getbasetemp()
            shared = base.parent if hasattr(request.config, "workerinput") else base
            args += ["--runs-dir", str(make_runs(tmp_path_factory.mktemp("runs") / "runs", shared))]
        cwd = root / name.removesuffix(".py")
        cwd.mkdir()
        jobs.append({"script": str(script), "args": args, "cwd": str(cwd), "out": str(cwd / "_out")})
        names[str(cwd / "_out")] = (name, cwd)
    (root / "jobs.json").write_text(json.dumps(jobs))
    r = subprocess.run([sys.executable, str(ROOT / "tests" / "bench_runner.py"), str(root / "jobs.json")], cwd=root,
                       env=_env(), capture_output=True, text=True, timeout=300 * len(jobs))
    assert r.returncode == 0, f"the benchmark runner failed ({r.returncode}):\n{r.stdout[-2000:]}\n{r.stderr[-3000:]}"
    out = {}
    for line in r.stdout.splitlines():
        row = json.loads(line)
        name, cwd = names[row["out"]]
        stdout, stderr = (Path(f"{row['out']}.{kind}").read_text() for kind in ("stdout", "stderr"))
        out[name] = (row["returncode"], stdout, stderr, cwd)
    return out


@pytest.mark.slow(3)  # its share of the module fixture's runs, every benchmark one after another
@pytest.mark.parametrize("name", sorted(SMALLEST))
def test_the_benchmark_runs_at_its_smallest_size(name: str, smallest_runs):
    if name == "bench_review.py" and not os.path.exists(CHROMIUM):
        if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
            pytest.fail(f"{CHROMIUM} is missing")
        pytest.skip(f"{CHROMIUM} is missing")
    code, stdout, stderr, _ = smallest_runs[name]
    assert code == 0, f"{name} failed ({code}):\n{stdout[-2000:]}\n{stderr[-3000:]}"
    assert stdout.strip(), f"{name} printed nothing:\n{stderr[-2000:]}"


@pytest.mark.slow
def test_bench_chains_plan_only_counts_refusals_and_the_planning_ratio_without_running(smallest_runs):
    code, stdout, stderr, cwd = smallest_runs["plan-only"]
    assert code == 0, stderr[-3000:]
    rep = json.loads((cwd / "plan.json").read_text())
    assert rep["chains"] == 1 and rep["refused"] + len([x for x in rep["rows"] if not x["refused"]]) == 1
    (row,) = rep["rows"]
    assert row["sentence"].count(", then ") == 1 and (row["refused"] or len(row["accepted"]) == 2)
    assert "planning a chain / its clauses alone" in stdout or row["refused"]
    assert not (cwd / "eval").exists()  # nothing performed, nothing written but the numbers
