"""Every benchmark still runs: each ``benchmarks/bench_*.py`` at its smallest size, as a fresh process.

A benchmark is run by hand, rarely, and its tables go into the docs; an import or option that a change
broke would otherwise be found only at the next measurement. ``SMALLEST`` names, for every benchmark,
the options that make it cheapest while it still goes through all its code (one scene, one action,
one LSTM for one or two epochs, one way of a session split, a few small frames); a new benchmark must add
its own line (the first test says so), and one that has no small size yet gets an option for it. (Smallest is
in CPU, not in options: bench_prepositions trains its plugins 4 epochs on 4 generated events a session, not 1 epoch
on 16, because the planner searches 3-8 s for a path a one-epoch model scores well.) Each
runs in an empty temporary folder, so a cache or output a benchmark keeps relative to where it runs
stays out of the checkout. The numbers are not checked: only that it finishes and prints its table.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from review_fixtures import CHROMIUM, run_folder  # noqa: F401 - fixture

ROOT = Path(__file__).resolve().parents[1]
BENCHMARKS = ROOT / "benchmarks"

SMALLEST: dict[str, list[str]] = {
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


@pytest.mark.slow
@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.xdist_group(n)) for n in sorted(SMALLEST)])
def test_the_benchmark_runs_at_its_smallest_size(name: str, tmp_path: Path, request):
    """(Each its own unit of work under pytest-xdist: together they take minutes.) bench_review grades the
    review tests' four runs (``review_fixtures.run_folder``: performed once per test session, shared by the
    workers) instead of performing one of its own."""
    if name == "bench_review.py" and not os.path.exists(CHROMIUM):
        if os.environ.get("CI", "").lower() in ("1", "true", "yes"):
            pytest.fail(f"{CHROMIUM} is missing")
        pytest.skip(f"{CHROMIUM} is missing")
    # the checkout first: a benchmark imports l2p_bullet (and research/) from the tree it belongs to
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p),
           "MPLBACKEND": "Agg"}
    args = list(SMALLEST[name])
    if name == "bench_review.py":
        args += ["--runs-dir", str(request.getfixturevalue("run_folder"))]
    r = subprocess.run([sys.executable, str(BENCHMARKS / name), *args], cwd=tmp_path, env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, f"{name} failed ({r.returncode}):\n{r.stdout[-2000:]}\n{r.stderr[-3000:]}"
    assert r.stdout.strip(), f"{name} printed nothing:\n{r.stderr[-2000:]}"


@pytest.mark.slow
def test_bench_chains_plan_only_counts_refusals_and_the_planning_ratio_without_running(tmp_path: Path):
    import json

    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH")) if p)}
    out = tmp_path / "plan.json"
    r = subprocess.run([sys.executable, str(BENCHMARKS / "bench_chains.py"), "--plan-only", "--chains", "1",
                        "--clauses", "2", "--seed", "9700", "--json", str(out)], cwd=tmp_path, env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-3000:]
    rep = json.loads(out.read_text())
    assert rep["chains"] == 1 and rep["refused"] + len([x for x in rep["rows"] if not x["refused"]]) == 1
    (row,) = rep["rows"]
    assert row["sentence"].count(", then ") == 1 and (row["refused"] or len(row["accepted"]) == 2)
    assert "planning a chain / its clauses alone" in r.stdout or row["refused"]
    assert not (tmp_path / "eval").exists()  # nothing performed, nothing written but the numbers
