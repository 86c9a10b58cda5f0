"""``l2p-bullet plan SENTENCE``: plan the mover's 2-D path without the arm; writes plan.json and plan.png."""

from __future__ import annotations

import click

from .common import force_option, load_scene_or_default, scene_option, seed_option


@click.command("plan")
@click.argument("sentence")
@scene_option
@click.option("--planner", default="default", show_default=True,
              help="greedy, beam, discrete, reinforce or default (the action's preferred one).")
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Output folder (default: runs/plan-<time>).")
@click.option("--budget", type=click.IntRange(min=1), default=None,
              help="Search steps at most (default: the planner's).")
@click.option("--threshold", type=click.FloatRange(0.0, 1.0), default=None,
              help="Stop when the learned progress reaches this (default: 0.9 or the bundle's).")
@seed_option
@force_option
def plan_command(sentence: str, scene_path: str | None, planner: str, out: str | None, budget: int | None,
                 threshold: float | None, seed: int, force: bool) -> None:
    """Plan SENTENCE (e.g. "move A around B") in 2-D and write plan.json and a plot.

    \b
    The plan maximises the action's learned progress model; the rule-based evaluator's verdict is
    printed alongside (it judges the path, the planner never sees it).
    """
    import json

    from .. import language
    from ..core.runfolder import prepare_run_folder
    from ..judge.rules import evaluate
    from ..planning import plan, resolve_planner
    from ..planning.plot import plot_plan
    from ..plugins import registry

    resolve_planner(planner, {})  # a bad name fails before anything is loaded
    scene = load_scene_or_default(scene_path)
    cmd = language.parse(sentence, scene, registry.phrase_table())
    bundle = registry.load(cmd.action)
    result = plan(scene, cmd.mover, cmd.anchor, bundle, planner=planner, seed=seed, budget=budget,
                  threshold=threshold)
    result.extra.setdefault("sentence", sentence)
    verdict = evaluate(cmd.action, result.path, result.anchor_pose, result.size)
    result.extra["verdict"] = {"success": verdict.success, "score": round(verdict.score, 4), "reason": verdict.reason}
    folder = prepare_run_folder(out, force=force, prefix="plan")
    result.save(folder / "plan.json")
    plot_plan(result, scene, folder / "plan.png")
    click.echo(json.dumps({
        "out": str(folder), "action": cmd.action, "planner": result.planner, "stopped": result.stopped,
        "final_progress": result.extra["final_progress"], "steps": result.extra["steps"],
        "seconds": result.extra["seconds"], "success": verdict.success, "reason": verdict.reason,
    }))


COMMANDS: list[click.Command] = [plan_command]
