"""``evaluate --chains K``: the chain benchmark, judged as CALVIN judges agents (how far a chain gets).

Scenes: ``chain/S`` is :func:`~l2p_bullet.core.scene.random_scene` for seed S (blocks A and B) with 1-3
more blocks (:func:`~.scenes.add_bystanders`), 3-5 blocks in all, the count drawn from S; with ``--bystanders K``
every scene has 2 + K (``chain/S/5b`` for five), so that the same seeds are measured on fuller tables. Chains: drawn in
the worker from the task's seed, clause by clause, over the installed one-anchor actions and random
mover/anchor pairs; a clause that cannot be planned from the state the previous clauses' plans predict
(the forecast's refusals: feasibility checks, no legal move, a path into a block) is drawn again, and the
re-draws are counted (``--chain-draw clause``, the default). With ``--chain-draw sentence`` the whole chain's
clauses are drawn first, as a person would say them, and the chain is planned as a whole (chain/forecast.py:
each clause's end state chosen so the later clauses stay possible); a chain that no end states make possible
is refused up front: its row has ``error_type`` "refused", ``completed`` 0 and the refusal as its ``error``
(the clause and the check). The chain is then performed as ``perform`` performs it (l2p_bullet/chain), in the
worker's reused world. A task's row depends on the task alone, so the pool and Ray give equal rows.

Rows: one per chain in the results table (``mode`` "chain", ``completed`` clauses in a row, ``redraws``,
``clauses``: a JSON list with one entry per clause performed); :func:`clause_rows` gives one row per
clause. The report: success of the first 1..K clauses and the average number completed.
"""

from __future__ import annotations

import json
import re
import shutil
import statistics
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from ..arms import PANDA, ArmSpec, fit_scene
from ..chain import perform_chain
from ..chain.clauses import Clause
from ..chain.forecast import Search, forecast
from ..core.scene import Scene, random_scene
from ..errors import EvaluationError, L2PError
from ..pipeline import resolve
from ..plugins import registry
from .scenes import SceneSpec, add_bystanders
from .tasks import Task, _safe, sentence_for

CHAIN_BLOCK = 0.05
"""Block side of the chain scenes (m): the evaluation's random two-block scenes use the same."""
MAX_DRAWS = 25
"""Draws per clause before a chain is given up as impossible to continue (an error row)."""
MAX_CHAIN = 10
DRAWS = ("clause", "sentence")
"""How a chain is drawn (``--chain-draw``): clause by clause until each plans, or the whole sentence first."""


def chain_scenes(n: int, seed: int = 0, blocks: int | None = None) -> list[SceneSpec]:
    """``n`` seeded scenes, seeds ``seed`` .. ``seed + n - 1``, of 3-5 blocks drawn from the seed, or of ``blocks``
    each."""
    if n < 0:
        raise EvaluationError(f"--scenes must be 0 or more (got {n})")
    if blocks is not None and blocks < 2:
        raise EvaluationError(f"a chain scene has at least 2 blocks (got {blocks})")
    out = []
    for s in range(seed, seed + n):
        count = int(np.random.default_rng([s, 21]).integers(3, 6)) if blocks is None else blocks
        scene = add_bystanders(random_scene(s, CHAIN_BLOCK), count - 2, s)
        out.append(SceneSpec(f"chain/{s}" if blocks is None else f"chain/{s}/{blocks}b", scene, s, source="chain"))
    return out


def make_chain_tasks(specs: list[SceneSpec], k: int, actions: list[str], *, planner: str = "default",
                     render_every: int = 0, keep: str = "none", out_dir: str | None = None,
                     plugins: list | None = None, budget: int | None = None,
                     threshold: float | None = None, arm: str = "panda", draw: str = "clause") -> list[Task]:
    """One chain of ``k`` clauses per scene, performed by ``arm``; the clauses are drawn by the worker (see the
    module docstring)."""
    if not 1 <= k <= MAX_CHAIN:
        raise EvaluationError(f"--chains must be 1 to {MAX_CHAIN} clauses (got {k})")
    plugins = registry.discover() if plugins is None else plugins
    names = [registry.find(a, plugins).name for a in actions]
    one_anchor = tuple(n for n in names if registry.anchor_counts(plugins).get(n, 1) == 1)
    if not one_anchor:
        raise EvaluationError("a chain draws one-anchor actions; none of the actions chosen has one anchor")
    tasks = []
    for i, spec in enumerate(specs):
        run_dir = None if out_dir is None else f"{out_dir}/runs/{_safe(spec.id)}--chain{k}--{planner}"
        tasks.append(Task(f"{spec.id}|chain{k}|{planner}|chain", i, spec.id, spec.source, spec.scene.to_dict(),
                          "", "", "chain", "", planner, spec.seed, "chain",
                          render_every > 0 and i % render_every == 0, keep, run_dir, budget, threshold,
                          chain_length=k, chain_actions=one_anchor, arm=arm, chain_draw=draw))
    return tasks


def chain_rng(seed: int, k: int) -> np.random.Generator:
    """The generator a chain of ``k`` clauses of ``seed`` is drawn with (:func:`draw_chain`), here and wherever
    the same chains must be drawn again (benchmarks/bench_thresholds.py)."""
    return np.random.default_rng([seed, k, 2118])


def draw_chain(scene: Scene, k: int, actions: list[str], rng: np.random.Generator, plugins: list, *,
               planner: str, seed: int, budget: int | None, threshold: float | None,
               arm: ArmSpec = PANDA) -> tuple[list, int]:
    """``k`` forecast steps (l2p_bullet/chain/forecast.py), each clause drawn until one can be planned from
    the predicted state; returns the steps and how many draws were refused."""
    names, steps, redraws, predicted = scene.names, [], 0, scene
    for i in range(1, k + 1):
        for _ in range(MAX_DRAWS):
            action = actions[int(rng.integers(len(actions)))]
            m, a = (int(v) for v in rng.choice(len(names), 2, replace=False))
            text = sentence_for(action, names[m], names[a], plugins)
            clause = Clause(i, text, resolve(text, scene, plugins))
            try:
                step = forecast([clause], predicted, plugins, planner=planner, seed=seed, budget=budget,
                                threshold=threshold, arm=arm)[0]
            except L2PError:
                redraws += 1
                continue
            break
        else:
            raise EvaluationError(f"no clause {i} could be planned in {MAX_DRAWS} draws")
        steps.append(step)
        predicted = predicted.with_pose(clause.command.mover, step.forecast.path[-1])
    return steps, redraws


def draw_sentence(scene: Scene, k: int, actions: list[str], rng: np.random.Generator, plugins: list) -> list[Clause]:
    """``k`` clauses drawn up front, each a random action with a random mover and anchor (``--chain-draw
    sentence``): what is asked does not depend on what the planner can do."""
    names, clauses = scene.names, []
    for i in range(1, k + 1):
        action = actions[int(rng.integers(len(actions)))]
        m, a = (int(v) for v in rng.choice(len(names), 2, replace=False))
        text = sentence_for(action, names[m], names[a], plugins)
        clauses.append(Clause(i, text, resolve(text, scene, plugins)))
    return clauses


def run_chain(worker: Any, task: Task, row: dict) -> None:
    """Draw and perform ``task``'s chain in ``worker``'s world; fill ``row`` (the chain's row)."""
    import time

    from ..plugins import arms as arm_plugins

    arm = arm_plugins.get(task.arm)
    scene = fit_scene(Scene.from_dict(task.scene, source=task.scene_id).validate(), arm)
    rng = chain_rng(task.seed, task.chain_length)
    if task.chain_draw == "sentence":
        clauses = draw_sentence(scene, task.chain_length, list(task.chain_actions), rng, worker.plugins)
        sentence = ", then ".join(c.text for c in clauses)
        row.update(sentence=sentence, redraws=0)
        search, t0 = Search(), time.perf_counter()
        try:
            steps = forecast(clauses, scene, worker.plugins, planner=task.planner, seed=task.seed,
                             budget=task.budget, threshold=task.threshold, arm=arm, search=search)
        except L2PError as e:
            row.update(success=0, completed=0, error=str(e), error_type="refused", reason=f"refused: {e}",
                       timings={"forecast": round(time.perf_counter() - t0, 5), "forecast_plans": search.plans})
            return
        forecast_timings = {"forecast": round(time.perf_counter() - t0, 5),
                            "forecast_alone": round(search.kept_seconds, 5), "forecast_plans": search.plans,
                            "ends_changed": len(search.changed)}
    else:
        steps, redraws = draw_chain(scene, task.chain_length, list(task.chain_actions), rng, worker.plugins,
                                    planner=task.planner, seed=task.seed, budget=task.budget,
                                    threshold=task.threshold, arm=arm)
        sentence = ", then ".join(s.clause.text for s in steps)
        row.update(sentence=sentence, redraws=redraws)
        forecast_timings = {}
    keep_always = task.render or task.keep == "all"
    out = Path(task.run_dir) if (task.run_dir and (keep_always or task.keep == "failed")) else worker.scratch() / "run"
    world = worker.world(scene, visuals=task.render, arm=task.arm)
    try:
        r = perform_chain(sentence, scene, replace(task.options(out), arm=arm), plugins=worker.plugins,
                          world=world, steps=steps)
    except BaseException:
        worker.drop_world(task.render, task.arm)
        if out.exists() and not (keep_always or task.keep == "failed"):
            shutil.rmtree(out, ignore_errors=True)
        raise
    clauses = [clause_entry(c) for c in r.results]
    others = [v for c in r.results for k, v in c.displacements_m.items() if k != c.clause.command.mover]
    v = r.verdict()
    row.update(success=int(r.success), completed=r.completed, clauses=clauses, reason=v["reason"],
               planner_used=r.results[0].plan.planner if r.results and r.results[0].plan else None,
               final_progress=r.results[-1].final_progress if r.results else None,
               max_deviation_m=max((c.max_deviation_m for c in r.results), default=None),
               anchor_displacement_m=max(others, default=None), total_s=r.timings.get("total"),
               timings={k: round(t, 5) for k, t in r.timings.items()} | forecast_timings)
    kept = keep_always or (task.keep == "failed" and not r.success)
    if kept:
        row["run_dir"] = str(out)
    else:
        shutil.rmtree(out, ignore_errors=True)


def clause_entry(c: Any) -> dict:
    """One clause of a chain's row: what was asked and how it went (no timings: rows compare across backends)."""
    cmd = c.clause.command
    others = {k: v for k, v in c.displacements_m.items() if k != cmd.mover}
    return {"clause": c.clause.index, "sentence": cmd.sentence, "action": cmd.action, "mover": cmd.mover,
            "anchor": cmd.anchor, "success": bool(c.success), "reason": c.verdict.get("reason"),
            "score": c.verdict.get("score"), "final_progress": _r(c.final_progress),
            "planned_progress": _r(float(c.plan.progress[-1])) if c.plan is not None and len(c.plan.progress) else None,
            "max_deviation_m": _r(c.max_deviation_m), "others_moved_m": _r(max(others.values(), default=0.0)),
            "failed_stage": c.failed_stage, "frames": [c.first_frame, c.last_frame]}


def _r(v: float | None) -> float | None:
    return None if v is None else round(float(v), 6)


def clause_rows(rows: list[dict]) -> list[dict]:
    """One row per clause performed: the chain's id, seed and the clause's fields."""
    out = []
    for r in rows:
        for c in r.get("clauses") or []:
            out.append({"run_id": r["run_id"], "scene_id": r["scene_id"], "seed": r["seed"], **c})
    return out


def chain_report(rows: list[dict]) -> dict:
    """CALVIN's numbers: success of the first 1..K clauses over all chains, the average completed, and per
    clause: success per action, failures by stage, the largest move of a block that was not the mover."""
    rows = [r for r in rows if r.get("mode") == "chain"]
    refused = [r for r in rows if r.get("error_type") == "refused"]
    k = max((int(str(r["run_id"]).split("|")[1][len("chain"):]) for r in rows), default=0)  # "chain/S|chainK|..."
    done = [int(r.get("completed") or 0) for r in rows]
    clauses = clause_rows(rows)
    per_action = {}
    for a in sorted({c["action"] for c in clauses}):
        cs = [c for c in clauses if c["action"] == a]
        per_action[a] = {"clauses": len(cs), "success": sum(c["success"] for c in cs) / len(cs)}
    first = [c for c in clauses if c["clause"] == 1]
    return {
        "chains": len(rows), "clauses_per_chain": k,
        "errors": sum(r.get("error") is not None for r in rows) - len(refused),
        "refused": len(refused), "refused_by": refusal_causes(refused),
        "forecast_ratio": forecast_ratio(rows),
        "success_first": {str(i): (sum(d >= i for d in done) / len(rows) if rows else None) for i in range(1, k + 1)},
        "average_completed": statistics.fmean(done) if done else None,
        "redraws": sum(int(r.get("redraws") or 0) for r in rows),
        "clauses_performed": len(clauses),
        "first_clause_success": sum(c["success"] for c in first) / len(first) if first else None,
        "per_action": per_action,
        "failed_stage": {s: sum(c.get("failed_stage") == s for c in clauses)
                         for s in ("plan", "path", "reach", "execute")},
        "max_others_moved_mm": 1000 * max((c["others_moved_m"] or 0.0 for c in clauses), default=0.0),
    }


_REFUSAL = re.compile(r'clause (\d+) \(".*?"\) cannot be planned \(([\w-]+)\)')


def refusal_causes(refused: list[dict]) -> dict[str, int]:
    """Refused chains by cause: "clause N: check" ("clause 1" is the clause from the scene as drawn: no
    earlier clause's end state could have helped), most frequent first."""
    causes: dict[str, int] = {}
    for r in refused:
        m = _REFUSAL.search(str(r.get("error")))
        key = f"clause {m.group(1)}: {m.group(2)}" if m else "other"
        causes[key] = causes.get(key, 0) + 1
    return dict(sorted(causes.items(), key=lambda kv: (-kv[1], kv[0])))


def forecast_ratio(rows: list[dict]) -> dict | None:
    """The chain's up-front planning against its clauses planned alone (``--chain-draw sentence``): the mean
    of each planned chain's seconds over its kept plans' seconds, the same of the sums, and the worst."""
    pairs = [(r["timings"]["forecast"], r["timings"]["forecast_alone"]) for r in rows
             if isinstance(r.get("timings"), dict) and r["timings"].get("forecast_alone")]
    if not pairs:
        return None
    ratios = [a / b for a, b in pairs]
    return {"chains": len(pairs), "mean": statistics.fmean(ratios), "of_sums": sum(a for a, _ in pairs)
            / sum(b for _, b in pairs), "max": max(ratios)}


def chain_report_text(rep: dict) -> str:
    k = rep["clauses_per_chain"]
    lines = [f"chains of {k}: {rep['chains']} chains, {rep['errors']} errors, {rep['redraws']} clauses re-drawn "
             "(impossible from the predicted state)",
             f"refused up front: {rep.get('refused', 0)} ({100 * rep.get('refused', 0) / max(rep['chains'], 1):.1f} %)"
             + (": " + ", ".join(f"{c} {n}" for c, n in rep["refused_by"].items()) if rep.get("refused_by") else ""),
             "success of the first i clauses: " + "  ".join(f"{i}: {100 * v:.1f}%" for i, v in
                                                           rep["success_first"].items() if v is not None),
             f"average completed: {rep['average_completed'] or 0:.2f} of {k}",
             f"first clause success: {100 * (rep['first_clause_success'] or 0):.1f}%; per action: "
             + ", ".join(f"{a} {100 * s['success']:.0f}% of {s['clauses']}" for a, s in rep["per_action"].items()),
             f"failures by stage: {rep['failed_stage']}; largest move of a block not moved by its clause: "
             f"{rep['max_others_moved_mm']:.2f} mm"]
    ratio = rep.get("forecast_ratio")
    if ratio:
        lines.append(f"planning a chain / planning its clauses alone: {ratio['mean']:.2f} mean, "
                     f"{ratio['of_sums']:.2f} of the sums, {ratio['max']:.1f} at most ({ratio['chains']} chains)")
    return "\n".join(lines)


def write_chain_report(rows: list[dict], out_dir: str | Path) -> tuple[str, dict[str, Path]]:
    """The text, ``report.json`` (the numbers) and ``clauses.jsonl`` (one row per clause) of a chain evaluation."""
    rep = chain_report(rows)
    path = Path(out_dir) / "report.json"
    path.write_text(json.dumps({"chains": rep}, indent=1, default=float) + "\n")
    per_clause = Path(out_dir) / "clauses.jsonl"
    per_clause.write_text("".join(json.dumps(r, sort_keys=True) + "\n" for r in clause_rows(rows)))
    return chain_report_text(rep), {"json": path, "clauses": per_clause}
