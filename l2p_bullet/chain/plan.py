"""``plan`` of a chain: the up-front forecast alone (forecast.py), written as a chain's plan.json.

Each clause is planned from the state the previous clauses' plans predict (no arm, no physics); plan.json
has the first clause's plan in the one-clause layout and every clause's ``forecast``; ``plan.png`` plots
the first clause and ``plan-K.png`` clause K, each in the scene it was planned in.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..core.contracts import dumps_json
from ..core.runfolder import run_folder
from ..core.scene import Scene
from ..pipeline import check_options, check_scene, scene_fields
from ..plugins import registry
from .clauses import resolve_clauses
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


def plan_chain(sentence: str, scene: Scene, *, out_dir: str | Path | None = None, planner: str = "default",
               seed: int = 0, budget: int | None = None, threshold: float | None = None, force: bool = False,
               plot: bool = True, plugins: list | None = None, arm: str | None = None) -> ChainPlan:
    """Resolve and forecast the chain for ``arm`` (default the Panda); write plan.json (and the plots).
    Refusals as in ``perform``."""
    from ..arms import fit_scene
    from ..plugins import arms as arm_plugins

    check_options(planner, seed, budget, threshold)
    check_scene(scene)
    spec = arm_plugins.get(arm)
    scene = fit_scene(scene, spec)
    plugins = registry.discover() if plugins is None else plugins
    steps = forecast(resolve_clauses(sentence, scene, plugins), scene, plugins, planner=planner, seed=seed,
                     budget=budget, threshold=threshold, arm=spec)
    with run_folder(out_dir, force=force, prefix="plan", command="plan", files=("plan-*.png",)) as folder:
        doc = steps[0].forecast.to_dict() | scene_fields(scene) | {  # scene, scene_sha256: as a one-clause plan.json
            "clauses": [{"clause": s.clause.index, "text": s.clause.text, "plan": None, "forecast": s.forecast.to_dict()}
                        for s in steps],
            "chain": {"sentence": sentence, "scene": scene.to_dict()}}
        (folder / "plan.json").write_text(dumps_json(doc, indent=1) + "\n")
        if plot:
            from ..planning.plot import plot_plan

            predicted = scene
            for s in steps:
                name = "plan.png" if s.clause.index == 1 else f"plan-{s.clause.index}.png"
                plot_plan(s.forecast, predicted, folder / name)
                predicted = predicted.with_pose(s.forecast.mover, s.forecast.path[-1])
    return ChainPlan(sentence, steps, folder)
