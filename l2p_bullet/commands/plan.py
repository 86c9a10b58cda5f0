"""``l2p-bullet plan SENTENCE``: plan the mover's 2-D path without the arm; writes plan.json and plan.png
(unless ``--no-plot``)."""

from __future__ import annotations

import click

from .common import arm_option, force_option, load_scene_or_default, scene_option, seed_option


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
def plan_command(sentence: str, scene_path: str | None, planner: str, out: str | None, budget: int | None,
                 threshold: float | None, no_plot: bool, as_json: bool, seed: int, force: bool, arm: str) -> None:
    """Plan SENTENCE (e.g. "move A around B") in 2-D and write plan.json and a plot.

    \b
    The plan maximises the action's learned progress model; the action's judge (rules for the built-in
    actions) gives its verdict alongside (it judges the path, the planner never sees it).
    """
    from ..chain import is_chain
    from ..core.contracts import dumps_json
    from ..errors import L2PError
    from ..pipeline import plan_sentence
    from .perform import error_json

    try:
        if is_chain(sentence):  # "move A next to B, then ...": every clause planned from the predicted state
            from ..chain.plan import plan_chain

            chained = plan_chain(sentence, load_scene_or_default(scene_path), out_dir=out, planner=planner,
                                 seed=seed, budget=budget, threshold=threshold, force=force, plot=not no_plot, arm=arm)
            return _say_chain(chained, as_json)
        result = plan_sentence(sentence, load_scene_or_default(scene_path), out_dir=out, planner=planner, seed=seed,
                               budget=budget, threshold=threshold, force=force, plot=not no_plot, arm=arm)
    except L2PError as e:
        if as_json:  # as perform --json: scripts read why on stdout; the one-line error still goes to stderr
            click.echo(dumps_json(error_json(sentence, e), indent=1))
        raise
    if as_json:
        click.echo(dumps_json(result.to_dict()))
        return
    # the same text style as perform; JSON only when asked for
    d, cmd = result.to_dict(), result.command
    click.echo(f'{cmd.mover} {cmd.preposition} {" and ".join(cmd.anchors)}: action "{cmd.action}", '
               f'{"success" if d["success"] else "FAILED"} on the plan ({d["reason"]})')
    click.echo(f"final progress {d['final_progress']:.2f}, {d['steps']} steps of the {d['planner']} planner "
               f"(stopped: {d['stopped']}), {d['seconds']:.2f} s")
    plot = result.out_dir / "plan.png"
    click.echo(f"plan folder: {result.out_dir}" + (f"\nplot: {plot}" if plot.exists() else " (no plot: --no-plot)"))


def _say_chain(chained, as_json: bool) -> None:
    """A chain's plan: JSON with ``--json``, else a line per clause in perform's style (it printed JSON always)."""
    from ..core.contracts import dumps_json

    d = chained.to_dict()
    if as_json:
        click.echo(dumps_json(d))
        return
    for c in d["clauses"]:
        fp = "n/a" if c["final_progress"] is None else f"{c['final_progress']:.2f}"
        click.echo(f'{c["clause"]}. {c["text"]}: "{c["action"]}", {"success" if c["success"] else "FAILED"} on the '
                   f'plan ({c["reason"]}), final progress {fp}, {c["steps"]} steps of the {c["planner"]} planner')
    click.echo(f'chain: {"success" if d["success"] else "FAILED"} on the plan, {len(d["clauses"])} clauses')
    click.echo(f"plan folder: {d['out']}")


COMMANDS: list[click.Command] = [plan_command]
