"""``l2p-bullet replay``: execute a recorded or planned 2-D motion with the arm, and record it."""

from __future__ import annotations

import time

import click

from .common import (
    arm_option,
    file_of_run_folder,
    force_option,
    load_scene_or_default,
    mesh_dirs,
    moved_text,
    render_settings,
    scene_option,
    seed_option,
    video_options,
)


@click.command()
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
def replay(path_json, demo, scene_path, out, seed, force, arm, mover, anchor, no_render, resolution, fps, camera, renderer,
           width, height, render_fps, video, quiet):
    """Execute a 2-D motion of a block with the arm in PyBullet.

    \b
    PATH_JSON is a scoring input {"size", "mover", "anchor"} (placed relative to the scene's anchor,
    scaled to its block size), a plan.json (in the scene frame, replayed on the scene it records;
    --scene must then be that scene) or a run folder (its plan.json). --demo ACTION:INDEX replays a real human demonstration the same way.

    \b
    Examples:
      l2p-bullet replay --demo around:0
      l2p-bullet replay runs/demo/plan.json --no-render
    """
    from ..core.runfolder import run_folder
    from ..core.scene import load_scene
    from ..embodiment.replay import motion_source, replay_scene, run_replay
    from ..errors import PathError

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
    from ..embodiment import arm_plugins

    spec = arm_plugins.get(arm)  # an unknown arm fails before anything is read or written
    if path_json is not None and _replay_chain(path_json, scene_path, out, force, render, seed, spec.name, quiet):
        return
    scene = replay_scene(path_json, None if scene_path is None else load_scene(scene_path, mesh_dirs()), scene_path,
                         mesh_dirs())
    scene = arm_plugins.fit_scene(scene, spec)  # the motion is fitted into what this arm reaches
    source = motion_source(path_json, demo, scene, mover, anchor)
    t0 = time.perf_counter()

    def on_stage(message: str) -> None:  # perform's style: elapsed time, then the stage
        if not quiet:
            click.echo(f"[{time.perf_counter() - t0:5.1f}s] execute: {message}", err=True)

    inputs = tuple(p for p in (path_json, scene_path) if p)  # --force never replaces what it reads
    with run_folder(out, force=force, prefix="replay", command="replay", inputs=inputs) as folder:
        ex = run_replay(scene, source, folder, render, seed, on_stage=on_stage, arm=spec)
    click.echo(f"replayed {source.label}: {ex.duration_s:.1f} s simulated, "
               f"block within {ex.max_deviation_m * 1000:.1f} mm of its path, "
               f"{moved_text(ex.displacements_m, [source.anchor] if source.anchor else [])}")
    video = ex.files.get("video")
    click.echo(f"run folder: {folder}" + (f"\nvideo: {video}" if video else " (no video: --no-render)"))


def _replay_chain(path_json: str, scene_path: str | None, out: str | None, force: bool, render, seed: int,
                  arm: str = "panda", quiet: bool = False) -> bool:
    """Replay a chain run's plan.json (every clause, one episode; l2p_bullet/chain/replay.py) in the scene
    it was planned in (or ``--scene``); False when the file is no chain plan."""
    from ..chain.replay import is_chain_plan, replay_chain
    from ..core.contracts import read_json
    from ..core.runfolder import run_folder

    doc = read_json(path_json)
    if not is_chain_plan(doc):
        return False
    scene = load_scene_or_default(scene_path) if scene_path is not None else None
    with run_folder(out, force=force, prefix="replay", command="replay",
                    inputs=tuple(p for p in (path_json, scene_path) if p)) as folder:
        r = replay_chain(doc, folder, scene=scene, render_settings=render, seed=seed,
                         on_stage=None if quiet else lambda s: click.echo(f"  {s}...", err=True), arm=arm,
                         path=path_json)
    v = r.verdict()
    click.echo(f"replayed the chain {path_json}: {v['completed']} of {v['clauses']} clauses done ({v['reason']})")
    click.echo(f"run folder: {folder}")
    return True


COMMANDS: list[click.Command] = [replay]
