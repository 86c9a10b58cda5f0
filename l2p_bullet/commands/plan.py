"""``l2p-bullet plan SENTENCE``: plan the mover's 2-D path without the arm; writes plan.json and plan.png
(unless ``--no-plot``)."""

from __future__ import annotations

import click

from .asking import ask_option, scene_asked
from .common import arm_option, force_option, load_scene_or_default, reporting, say, scene_option, seed_option


@click.command("plan")
@click.argument("sentence")
@scene_option
@click.option("--planner", default="default", show_default=True,
              help="mixed, greedy, beam, discrete, reinforce or default (the action's preferred one).")
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Output folder (default: runs/plan-<time>).")
@click.option("--budget", type=click.IntRange(min=1), default=None,
              help="Search steps at most (default: the planner's).")
@click.option("--threshold", type=click.FloatRange(0.0, 1.0), default=None,
              help="Stop when the learned progress reaches this (default: 0.9 or the bundle's).")
@click.option("--no-plot", is_flag=True, help="Write plan.json only, no plan.png.")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON (for scripts).")
@seed_option
@force_option
@arm_option
@ask_option
def plan_cmd(sentence: str, scene_path: str | None, planner: str, out: str | None, budget: int | None,
                 threshold: float | None, no_plot: bool, as_json: bool, seed: int, force: bool, arm: str,
                 ask: bool | None) -> None:
    """Plan SENTENCE (e.g. "move A around B") in 2-D and write plan.json and a plot.

    \b
    The plan maximises the action's learned progress model; the action's judge (rules for the built-in
    actions) gives its verdict alongside (it judges the path, the planner never sees it).
    """
    from ..chain.plan import plan_chain
    from ..options import RunOptions

    with reporting(sentence, as_json):
        options = RunOptions(planner=planner, seed=seed, budget=budget, threshold=threshold, arm=arm,
                             out_dir=out, force=force, plot=not no_plot)
        scene = scene_asked(sentence, load_scene_or_default(scene_path), scene_path, ask, as_json)
        result = plan_chain(sentence, scene, options)
    say(result, as_json)


COMMANDS: list[click.Command] = [plan_cmd]
