"""``l2p-bullet replay``: execute a recorded or planned 2-D motion with the arm, and record it."""

from __future__ import annotations

import click

from .common import force_option, load_scene_or_default, scene_option, seed_option


@click.command()
@click.argument("path_json", required=False, type=click.Path(dir_okay=False))
@click.option("--demo", metavar="ACTION:INDEX", help="Replay a shipped human demonstration, e.g. around:0.")
@scene_option
@click.option("--out", type=click.Path(file_okay=False), default=None,
              help="Run folder (default: runs/replay-<timestamp>).")
@seed_option
@force_option
@click.option("--mover", default="A", show_default=True, help="Block that moves (demos and scoring inputs).")
@click.option("--anchor", default="B", show_default=True, help="Block it moves relative to.")
@click.option("--no-render", is_flag=True, help="Skip images and video (much faster).")
@click.option("--renderer", type=click.Choice(["tiny", "egl"]), default="tiny", show_default=True,
              help="tiny: deterministic CPU renderer; egl: faster where the plugin loads.")
@click.option("--width", type=click.IntRange(16, 4096), default=320, show_default=True, help="Frame width in pixels.")
@click.option("--height", type=click.IntRange(16, 4096), default=240, show_default=True, help="Frame height in pixels.")
@click.option("--render-fps", type=click.FloatRange(0.1, 240.0), default=10.0, show_default=True,
              help="Rendered frames per second of simulated time.")
@click.option("--video", type=click.Choice(["mp4", "gif"]), default="mp4", show_default=True,
              help="Video format written next to the frames.")
def replay(path_json, demo, scene_path, out, seed, force, mover, anchor, no_render, renderer, width, height,
           render_fps, video):
    """Execute a 2-D motion of a block with the arm in PyBullet.

    \b
    PATH_JSON is a scoring input {"size", "mover", "anchor"} (placed relative to the scene's anchor,
    scaled to its block size) or a plan.json (in the scene frame). --demo ACTION:INDEX replays a real
    human demonstration the same way.

    \b
    Examples:
      l2p-bullet replay --demo around:0
      l2p-bullet replay runs/demo/plan.json --no-render
    """
    from ..core.runfolder import run_folder
    from ..embodiment.replay import motion_source, run_replay
    from ..embodiment.sim.camera import RenderSettings
    from ..errors import PathError

    if (path_json is None) == (demo is None):
        raise PathError("give either PATH_JSON or --demo ACTION:INDEX (one of them)")
    scene = load_scene_or_default(scene_path)
    source = motion_source(path_json, demo, scene, mover, anchor)
    render = None if no_render else RenderSettings(width, height, render_fps, renderer, video)
    inputs = tuple(p for p in (path_json, scene_path) if p)
    with run_folder(out, force=force, prefix="replay", command="replay", inputs=inputs) as folder:
        ex = run_replay(scene, source, folder, render, seed, on_stage=lambda s: click.echo(f"  {s}...", err=True))
    click.echo(f"replayed {source.label}: {ex.duration_s:.1f} s simulated, "
               f"block within {ex.max_deviation_m * 1000:.1f} mm of its path, "
               f"other blocks moved {ex.anchor_displacement_m * 1000:.1f} mm")
    click.echo(f"run folder: {folder}")


COMMANDS: list[click.Command] = [replay]
