"""``l2p-bullet perform SENTENCE``: the product's main command."""

from __future__ import annotations

import time

import click

from .common import (
    arm_option,
    force_option,
    load_scene_or_default,
    moved_text,
    render_settings,
    scene_option,
    seed_option,
    video_options,
)


@click.command("perform")
@click.argument("sentence")
@scene_option
@seed_option
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Run folder (default: runs/perform-<timestamp>).")
@click.option("--planner", default="default", show_default=True,
              help="Planner: default (the action's choice), mixed, greedy, beam, discrete or reinforce (docs/planning.md).")
@click.option("--no-render", is_flag=True, help="Skip frames and video (much faster).")
@video_options
@force_option
@arm_option
@click.option("--quiet", "-q", is_flag=True, help="No progress messages on stderr.")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON on stdout.")
def perform_cmd(sentence: str, scene_path: str | None, seed: int, out: str | None, planner: str,
                no_render: bool, resolution: str, fps: float, camera: str, renderer: str, force: bool, arm: str,
                quiet: bool, as_json: bool) -> None:
    """Make the arm perform SENTENCE, e.g. "move A around B", and record the run.

    \b
    Sentences: VERB MOVER PREPOSITION ANCHOR, e.g.
      "move A around B"   "Please slide the red block next to the green one."
    Verbs: move, slide, shift, drag, put (a slide); carry, bring, "lift / pick up A and
    put / place it ..." (a carry); push, nudge, shove (a push). Prepositions: those of the
    installed actions (l2p-bullet actions). The run folder gets trajectory.json,
    plan.json, summary.json and, unless --no-render, frames and a video.

    \b
    Chains: clauses joined by ", then", "and then", "then", "after that" or ";" run one
    after another in one episode, e.g. "move A next to B, then slide C past A".
    """
    from ..core.contracts import dumps_json
    from ..pipeline import perform

    t0 = time.perf_counter()

    def on_stage(message: str) -> None:
        if not quiet:
            click.echo(f"[{time.perf_counter() - t0:5.1f}s] {message}", err=True)

    from ..chain import is_chain
    from ..errors import L2PError

    if is_chain(sentence):
        settings = None if no_render else render_settings(resolution, fps, camera, renderer)
        return _perform_chain(sentence, scene_path, seed, out, planner, no_render, force, on_stage, as_json, arm,
                              settings)
    try:
        settings = None if no_render else render_settings(resolution, fps, camera, renderer)
        scene = load_scene_or_default(scene_path)
        r = perform(sentence, scene, out_dir=out, planner=planner, seed=seed, render=not no_render, force=force,
                    on_stage=on_stage, render_settings=settings, arm=arm)
    except L2PError as e:
        if as_json:  # scripts read why on stdout; the one-line error still goes to stderr (exit 2)
            click.echo(dumps_json(error_json(sentence, e), indent=1))
        raise
    if as_json:
        click.echo(dumps_json(r.to_dict(), indent=1))
        return
    v = r.verdict
    fp = "n/a" if r.final_progress is None else f"{r.final_progress:.2f}"
    click.echo(f'{r.command.mover} {r.command.preposition} {" and ".join(r.command.anchors)}: action "{r.command.action}", '
               f'{"success" if r.success else "FAILED"} ({v.get("reason", "")})')
    click.echo(f"final progress {fp} (planned {r.planned_progress:.2f}), "
               f"block within {r.max_deviation_m * 1000:.1f} mm of the plan, "
               f"{moved_text(r.displacements_m, r.command.anchors)}, {r.timings.get('total', 0):.1f} s")
    video = r.files.get("video")
    click.echo(f"run folder: {r.out_dir}" + (f"\nvideo: {video}" if video else " (no video: --no-render)"))


def _perform_chain(sentence: str, scene_path: str | None, seed: int, out: str | None, planner: str,
                   no_render: bool, force: bool, on_stage, as_json: bool, arm: str = "panda",
                   settings=None) -> None:
    """``perform`` of a chain (l2p_bullet/chain): one line per clause, then the chain's verdict."""
    from ..chain import perform_chain
    from ..core.contracts import dumps_json
    from ..errors import L2PError

    try:
        r = perform_chain(sentence, load_scene_or_default(scene_path), out_dir=out, planner=planner, seed=seed,
                          render=not no_render, force=force, on_stage=on_stage, arm=arm, render_settings=settings)
    except L2PError as e:
        if as_json:
            click.echo(dumps_json(error_json(sentence, e), indent=1))
        raise
    if as_json:
        click.echo(dumps_json(r.to_dict(), indent=1))
        return
    for c in r.results:
        fp = "n/a" if c.final_progress is None else f"{c.final_progress:.2f}"
        click.echo(f'{c.clause.index}. {c.clause.command.sentence}: "{c.clause.command.action}", '
                   f'{"success" if c.success else "FAILED"} ({c.verdict.get("reason", "")}), final progress {fp}')
    v = r.verdict()
    if r.row is not None:  # a composite ("make a row of ..."): the whole judged too
        click.echo(f'row: {r.row["reason"]} (largest gap {r.row["max_gap_sides"]:.2f} side, farthest from the '
                   f'line {r.row["max_offset_sides"]:.2f} side)')
    click.echo(f'chain: {"success" if r.success else "FAILED"}, {v["completed"]} of {v["clauses"]} clauses done, '
               f'{r.timings.get("total", 0):.1f} s')
    video = r.files.get("video")
    click.echo(f"run folder: {r.out_dir}" + (f"\nvideo: {video}" if video else " (no video: --no-render)"))


def error_json(sentence: str, e: Exception) -> dict:
    """What ``perform --json`` prints when it fails: the error, its type and, for a refusal, which check."""
    out = {"sentence": sentence, "ok": False, "error": str(e), "error_type": type(e).__name__}
    check = getattr(e, "check", None)
    if check is not None:
        out["refused"] = {"check": check, "details": getattr(e, "details", {})}
    return out


COMMANDS: list[click.Command] = [perform_cmd]
