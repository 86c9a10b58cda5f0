"""The whole chain planned in 2-D before the arm moves: each clause from the end state the previous
clauses' plans predict, so a clause that cannot be planned is refused up front, naming it and the check.

The checks per clause, in order: the arm's and the judge's feasibility checks (``grasp``, ``boxed-in``,
``room-*``: planning.feasibility), the planner itself (``plan``: no legal move), and the execution's path
check (``path``: the planned path leaves the workspace or runs into a block). The forecast is a prediction:
at run time each clause is planned again from where the simulated world really left the blocks.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .. import planning
from ..arms import PANDA, ArmSpec
from ..core.contracts import Plan
from ..core.scene import Scene
from ..embodiment.manners import manner_planning
from ..errors import InfeasibleError, L2PError, PathError, PlanError
from ..judge import judge_context, judge_for
from ..manners import registry as manners
from ..pipeline import check_feasible
from ..plugins import registry
from .clauses import Clause, _named


@dataclass
class Step:
    """What one clause needs at run time: the clause, its loaded action, and its forecast plan."""

    clause: Clause
    bundle: Any
    model: Any
    judge: Any
    forecast: Plan

    @property
    def viewer(self):
        return getattr(self.model, "viewpoint", None)


def forecast(clauses: list[Clause], scene: Scene, plugins: list, *, planner: str, seed: int,
             budget: int | None, threshold: float | None, bundles: dict | None = None,
             arm: ArmSpec = PANDA) -> list[Step]:
    """Load each clause's action (once per action) and plan the chain from the predicted states, for ``arm``
    (its reach, hand and gripper: the same checks a one-clause run makes).

    Raises the failing check's error (InfeasibleError with ``.check`` and ``details["clause"]``, or a
    PlanError / PathError) with the clause named in its message, before anything moves or is written.
    """
    # lazy: the arm's modules load only when a chain is forecast (plan and parsing stay light)
    from ..embodiment.execute import check_for

    loaded: dict[str, tuple[Any, Any, Any]] = {}
    for c in clauses:
        name = c.command.action
        if name not in loaded:
            bundle = (bundles or {}).get(name) or registry.load(name, plugins)
            loaded[name] = (bundle, bundle.progress_model(), judge_for(bundle))
    steps: list[Step] = []
    predicted = scene
    for c in clauses:
        cmd = c.command
        bundle, model, judge = loaded[cmd.action]
        try:
            check_feasible(cmd, predicted, plugins, arm)
            plan = planning.plan(predicted, cmd.mover, list(cmd.anchors), bundle, planner=planner, seed=seed,
                                 budget=budget, threshold=threshold,
                                 target=None if c.target is None else c.target(predicted), arm=arm,
                                 **manner_planning(manners.get(cmd.manner), predicted.get(cmd.mover).size, arm))
            check_for(manners.get(cmd.manner), predicted, cmd.mover, plan.path, arm)
        except InfeasibleError as e:
            e.details["clause"] = c.index
            raise _named(e, f"{c.label()} cannot be planned ({e.check})") from None
        except PlanError as e:
            raise _named(PlanError(str(e)), f"{c.label()} cannot be planned (plan)") from None
        except PathError as e:
            raise _named(PathError(str(e)), f"{c.label()} cannot be planned (path)") from None
        except L2PError as e:
            raise _named(e, c.label()) from None
        poses = [plan.anchor_pose, *([] if plan.more_anchor_poses is None else list(plan.more_anchor_poses))]
        plan.extra["verdict"] = judge.judge(plan.path, plan.anchor_pose, plan.size,
                                            final_progress=plan.extra.get("final_progress"),
                                            **judge_context(poses, plan.viewer)).to_dict()
        plan.extra.setdefault("sentence", c.text)
        steps.append(Step(c, bundle, model, judge, plan))
        predicted = predicted.with_pose(cmd.mover, plan.path[-1])
    return steps
