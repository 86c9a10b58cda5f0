"""``l2p-bullet replay``: execute a recorded or planned 2-D motion with the arm, and record it."""

from __future__ import annotations

import click

from .common import (
    arm_option,
    file_of_run_folder,
    force_option,
    mesh_dirs,
    render_settings,
    say,
    scene_option,
    seed_option,
    stage_printer,
    video_options,
)


@click.command("replay")
@click.argument("path_json", required=False, type=click.Path())
@click.option("--demo", metavar="ACTION:INDEX", help="Replay a shipped human demonstration, e.g. around:0.")
@scene_option
@click.option("--out", type=click.Path(file_okay=False), default=None,
              help="Run folder (default: runs/replay-<timestamp>).")
@seed_option
@force_option
@arm_option
@click.option("--mover", default="A", show_default=True, help="Block that moves (demos and scoring inputs).")
@click.option("--anchor", default="B", show_default=True, help="Block it moves relative to.")
@click.option("--no-render", is_flag=True, help="Skip images and video (much faster).")
@video_options
@click.option("--width", type=int, default=None, hidden=True, help="Frame width (old spelling of --resolution).")
@click.option("--height", type=int, default=None, hidden=True, help="Frame height (old spelling of --resolution).")
@click.option("--render-fps", type=float, default=None, hidden=True, help="Old spelling of --fps.")
@click.option("--video", type=click.Choice(["mp4", "gif"]), default="mp4", show_default=True,
              help="Video format written next to the frames.")
@click.option("--quiet", "-q", is_flag=True, help="No progress messages on stderr (as perform's).")
def replay_cmd(
    path_json,
    demo,
    scene_path,
    out,
    seed,
    force,
    arm,
    mover,
    anchor,
    no_render,
    resolution,
    fps,
    camera,
    renderer,
    width,
    height,
    render_fps,
    video,
    quiet,
):
    """Execute a 2-D motion of a block with the arm in PyBullet.

    \b
    PATH_JSON is a scoring input {"size", "mover", "anchor"} (placed relative to the scene's anchor,
    scaled to its block size), a plan.json (in the scene frame, replayed on the scene it records;
    --scene must then be that scene) or a run folder (its plan.json). --demo ACTION:INDEX replays a real human
    demonstration the same way.

    \b
    Examples:
      l2p-bullet replay --demo around:0
      l2p-bullet replay runs/demo/plan.json --no-render
    """
    from ..chain.replay import replay
    from ..errors import PathError
    from ..options import RunOptions

    if (path_json is None) == (demo is None):
        raise PathError("give either PATH_JSON or --demo ACTION:INDEX (one of them)")
    if path_json is not None:
        path_json = file_of_run_folder(path_json, "plan.json")
    if width is not None or height is not None:  # the spelling before --resolution still works
        from ..embodiment.sim.camera import parse_resolution

        w, h = parse_resolution(resolution)
        resolution = f"{w if width is None else width}x{h if height is None else height}"
    render = None if no_render else render_settings(resolution, fps if render_fps is None else render_fps, camera,
                                                    renderer, video)
    options = RunOptions(seed=seed, arm=arm, render=render is not None, render_settings=render, out_dir=out,
                         force=force, on_stage=stage_printer(quiet, "execute: "))
    say(replay(path_json, demo, options, scene_path=scene_path, mesh_dirs=mesh_dirs(), mover=mover, anchor=anchor),
        as_json=False)


COMMANDS: list[click.Command] = [replay_cmd]
