"""One front door: every sentence goes through ``chain.perform_chain`` / ``chain.plan.plan_chain`` with one
checked ``RunOptions``; a lone clause is a chain of one, written in the one-clause layout, byte for byte as
``pipeline.perform`` / ``pipeline.plan_sentence`` write it."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

import l2p_bullet
from l2p_bullet import pipeline
from l2p_bullet.chain import perform_chain
from l2p_bullet.chain.plan import plan_chain
from l2p_bullet.core.scene import default_scene
from l2p_bullet.embodiment.sim.camera import RenderSettings
from l2p_bullet.errors import ExecutionError, PlanError
from l2p_bullet.options import RunOptions

TIMING = {"timings_s", "timings", "seconds", "created", "finished_at", "started_at", "versions"}


def _strip(x):
    if isinstance(x, dict):
        return {k: _strip(v) for k, v in x.items() if k not in TIMING}
    if isinstance(x, list):
        return [_strip(v) for v in x]
    return x


def _read(folder: Path, name: str) -> dict:
    text = (folder / name).read_text().replace(str(folder), "<out>")
    return _strip(json.loads(text))


@pytest.mark.slow
def test_a_lone_clause_through_the_door_is_the_one_clause_run(tmp_path):
    options = RunOptions(seed=3, render=False)
    door = perform_chain("carry A past B", default_scene(), options, out_dir=tmp_path / "door")
    one = pipeline.perform("carry A past B", default_scene(), options, out_dir=tmp_path / "one")
    assert isinstance(door, pipeline.PerformResult)
    assert "segments" not in json.loads((tmp_path / "door" / "trajectory.json").read_text())
    for name in ("trajectory.json", "plan.json", "summary.json"):
        assert _read(tmp_path / "door", name) == _read(tmp_path / "one", name), name
    assert door.text()[0] == one.text()[0]


@pytest.mark.slow
def test_a_lone_clause_is_planned_as_one_clause(tmp_path):
    door = plan_chain("move A next to B", default_scene(), seed=3, plot=False, out_dir=tmp_path / "door")
    one = pipeline.plan_sentence("move A next to B", default_scene(), seed=3, plot=False, out_dir=tmp_path / "one")
    assert isinstance(door, pipeline.PlanResult)
    assert _read(tmp_path / "door", "plan.json") == _read(tmp_path / "one", "plan.json")
    assert not (tmp_path / "door" / "plan.png").exists()
    assert door.text()[0] == one.text()[0] and door.text()[-1].endswith("(no plot: --no-plot)")


@pytest.mark.parametrize(
    "changes, error, match",
    [
        ({"seed": -1}, PlanError, "seed"),
        ({"budget": 0}, PlanError, "budget"),
        ({"threshold": 2.0}, PlanError, "threshold"),
        ({"planner": "nope"}, PlanError, "nope"),
        ({"render_settings": RenderSettings(fps=0.0)}, ExecutionError, "fps|frames per second"),
    ],
)
def test_the_options_are_checked_once_before_anything_is_written(tmp_path, changes, error, match):
    with pytest.raises(error, match=match):
        RunOptions.of(**changes).check()
    for door in (perform_chain, plan_chain):
        with pytest.raises(error, match=match):
            door("move A next to B, then move B around A", default_scene(), out_dir=tmp_path / "x", **changes)
    assert not (tmp_path / "x").exists()


def test_an_unknown_option_name_is_refused_like_an_unknown_keyword():
    with pytest.raises(TypeError, match="rendr"):
        RunOptions.of(rendr=False)
    assert RunOptions.of(RunOptions(seed=4), render=False) == RunOptions(seed=4, render=False)


def _chain_imports() -> dict[str, set[str]]:
    """Every module of l2p_bullet/chain -> the modules of chain/ it imports (function-level imports too)."""
    root = Path(l2p_bullet.__file__).parent / "chain"
    out = {}
    for f in root.glob("*.py"):
        found = set()
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                found.add(node.module or "__init__")
        out[f.stem] = found & {g.stem for g in root.glob("*.py")}
    return out


def test_no_import_circle_inside_chain():
    graph = _chain_imports()
    assert "clauses" not in graph["composite"], "composite.py imports clauses.py, which asks composite.py first"

    def reach(start: str) -> set[str]:
        seen, todo = set(), [start]
        while todo:
            for m in graph.get(todo.pop(), ()):
                if m not in seen and m != "__init__":
                    seen.add(m)
                    todo.append(m)
        return seen

    circles = sorted(m for m in graph if m != "__init__" and m in reach(m))
    assert not circles, f"modules of chain/ that import themselves through others: {circles}"
