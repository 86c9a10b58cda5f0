"""``plan`` of any sentence: a chain's up-front forecast alone (forecast.py), written as a chain's plan.json;
a lone clause planned by the pipeline's stages, written as a one-clause plan.json.

Each clause is planned from the state the previous clauses' plans predict (no arm, no physics); plan.json
has the first clause's plan in the one-clause layout and every clause's ``forecast``; ``plan.png`` plots
the first clause and ``plan-K.png`` clause K, each in the scene it was planned in.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from ..core.contracts import dumps_json
from ..core.runfolder import run_folder
from ..core.scene import Scene
from ..options import RunOptions, admit
from ..pipeline import PlanResult, plan_prepared, prepare_command, scene_fields
from ..planning.plot import plot_plan
from ..plugins import registry
from .clauses import one_clause, resolve_clauses
from .forecast import Step, forecast


@dataclass
class ChainPlan:
    """What ``plan`` did for a chain: the steps (clause + forecast plan with its verdict) and where they went."""

    sentence: str
    steps: list[Step]
    out_dir: Path

    def to_dict(self) -> dict[str, Any]:
        """What ``l2p-bullet plan`` prints: the first clause's fields and one entry per clause."""
        clauses = []
        for s in self.steps:
            x, v = s.forecast.extra, s.forecast.extra.get("verdict", {})
            clauses.append({"clause": s.clause.index, "text": s.clause.text, "action": s.clause.command.action,
                            "planner": s.forecast.planner, "stopped": s.forecast.stopped,
                            "final_progress": x.get("final_progress"), "steps": x.get("steps"),
                            "success": v.get("success"), "reason": v.get("reason")})
        return {"out": str(self.out_dir), "chain": True, "sentence": self.sentence,
                "success": all(c["success"] for c in clauses), "clauses": clauses}

    def text(self) -> list[str]:
        """What ``plan`` prints for a chain: a line per clause in ``perform``'s style, then the chain's."""
        d = self.to_dict()
        out = []
        for c in d["clauses"]:
            fp = "n/a" if c["final_progress"] is None else f"{c['final_progress']:.2f}"
            out.append(
                f'{c["clause"]}. {c["text"]}: "{c["action"]}", {"success" if c["success"] else "FAILED"} on '
                f"the plan ({c['reason']}), final progress {fp}, {c['steps']} steps of the {c['planner']} planner"
            )
        return out + [f'chain: {"success" if d["success"] else "FAILED"} on the plan, {len(d["clauses"])} clauses',
                      f"plan folder: {d['out']}"]


def plan_chain(sentence: str, scene: Scene, options: RunOptions | None = None, *, plugins: list | None = None,
               **changes: Any) -> ChainPlan | PlanResult:
    """Plan any sentence (the front door of ``plan``) for the options' arm (default the Panda): resolve and
    forecast its clauses, write plan.json (and the plots unless ``plot`` is off). A lone clause (no composite)
    is a chain of one, planned by the pipeline's stages (:class:`~l2p_bullet.pipeline.PlanResult`, one-clause
    plan.json). ``options`` and ``changes`` by name: ``RunOptions.of``. Refusals as in ``perform``."""
    opts = RunOptions.of(options, **changes)
    scene, arm = admit(scene, opts)
    plugins = registry.discover() if plugins is None else plugins
    clauses = resolve_clauses(sentence, scene, plugins)
    if one_clause(clauses):
        return plan_prepared(prepare_command(clauses[0].command, scene, arm, plugins, opts))
    steps = forecast(clauses, scene, plugins, replace(opts, arm=arm))
    with run_folder(opts.out_dir, force=opts.force, prefix="plan", command="plan",
                    files=("plan-*.png",)) as folder:
        doc = (
            steps[0].forecast.to_dict()
            | scene_fields(scene)
            | {  # scene, scene_sha256: as a one-clause plan.json
                "clauses": [
                    {"clause": s.clause.index, "text": s.clause.text, "plan": None, "forecast": s.forecast.to_dict()}
                    for s in steps
                ],
                "chain": {"sentence": sentence, "scene": scene.to_dict()},
            }
        )
        (folder / "plan.json").write_text(dumps_json(doc, indent=1) + "\n")
        if opts.plot:
            predicted = scene
            for s in steps:
                name = "plan.png" if s.clause.index == 1 else f"plan-{s.clause.index}.png"
                plot_plan(s.forecast, predicted, folder / name)
                predicted = predicted.with_pose(s.forecast.mover, s.forecast.path[-1])
    return ChainPlan(sentence, steps, folder)
