"""``l2p-bullet perform SENTENCE``: the product's main command."""

from __future__ import annotations

import click

from .asking import ask_option, scene_asked
from .common import (
    arm_option,
    force_option,
    load_scene_or_default,
    render_settings,
    reporting,
    say,
    scene_option,
    seed_option,
    stage_printer,
    video_options,
)


@click.command("perform")
@click.argument("sentence")
@scene_option
@seed_option
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Run folder (default: runs/perform-<timestamp>).")
@click.option(
    "--planner",
    default="default",
    show_default=True,
    help="Planner: default (the action's choice), mixed, greedy, beam, discrete or reinforce (docs/planning.md).",
)
@click.option("--no-render", is_flag=True, help="Skip frames and video (much faster).")
@video_options
@force_option
@arm_option
@click.option("--quiet", "-q", is_flag=True, help="No progress messages on stderr.")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON on stdout.")
@ask_option
def perform_cmd(sentence: str, scene_path: str | None, seed: int, out: str | None, planner: str,
                no_render: bool, resolution: str, fps: float, camera: str, renderer: str, force: bool, arm: str,
                quiet: bool, as_json: bool, ask: bool | None) -> None:
    """Make the arm perform SENTENCE, e.g. "move A around B", and record the run.

    \b
    Sentences: VERB MOVER PREPOSITION ANCHOR, e.g.
      "move A around B"   "Please slide the red block next to the green one."
    Verbs: move, slide, shift, drag, put, bring (a slide); carry, "lift / pick up A and
    put / place it ..." (a carry); push, nudge, shove (a push). Prepositions: those of the
    installed actions (l2p-bullet actions). The run folder gets trajectory.json,
    plan.json, summary.json and, unless --no-render, frames and a video.

    \b
    Chains: clauses joined by ", then", "and then", "then", "after that" or ";" run one
    after another in one episode, e.g. "move A next to B, then slide C past A".

    \b
    Your own words: "move the tin next to the lime" where no object is a "tin" asks
    which object it is (at a terminal, or with --ask) and offers to keep the word in
    the scene file as that object's "kind".
    """
    from ..chain import perform_chain
    from ..options import RunOptions

    with reporting(sentence, as_json):
        settings = None if no_render else render_settings(resolution, fps, camera, renderer)
        options = RunOptions(planner=planner, seed=seed, arm=arm, render=not no_render,
                             render_settings=settings, out_dir=out, force=force, on_stage=stage_printer(quiet))
        scene = scene_asked(sentence, load_scene_or_default(scene_path), scene_path, ask, as_json)
        r = perform_chain(sentence, scene, options)
    say(r, as_json, indent=1)


COMMANDS: list[click.Command] = [perform_cmd]
