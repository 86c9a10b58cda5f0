"""``l2p-bullet export``: run folders (and the shipped demonstrations) as a dataset others can load."""

from __future__ import annotations

import json

import click

from .common import force_option


@click.command("export")
@click.argument("runs", nargs=-1, type=click.Path(exists=True))
@click.argument("out", type=click.Path(file_okay=False))
@click.option("--format", "fmt", type=click.Choice(["json", "lerobot"]), default="json", show_default=True,
              help="json: OUT/episodes.jsonl; lerobot: a LeRobot v3.0 dataset (needs l2p-bullet[export]).")
@click.option("--demos", multiple=True, metavar="SPEC",
              help="Also the shipped human demonstrations, replayed by the arm: all, ACTION or ACTION:INDEX (repeatable).")
@click.option("--no-video", is_flag=True, help="Leave the camera images out (lerobot), and render no demonstration.")
@force_option
def export_cmd(runs: tuple[str, ...], out: str, fmt: str, demos: tuple[str, ...], no_video: bool, force: bool) -> None:
    """Write RUNS (run folders, or folders holding them, e.g. an evaluation's) to OUT.

    \b
    Examples:
      l2p-bullet export runs/eval --format lerobot datasets/eval
      l2p-bullet export --demos around --demos closer:0 --format lerobot datasets/demos
    Every episode's task is its sentence ("move A around B"). Render the runs (perform without
    --no-render, evaluate --render-every 1) to have videos.
    """
    from ..core.runfolder import run_folder
    from ..errors import PathError
    from ..export.episodes import EXPORT_FILES, demo_episodes, episode_from_run, find_runs, write_jsonl

    if not runs and not demos:
        raise PathError("nothing to export: give run folders and/or --demos")
    sources = find_runs(list(runs)) if runs else []  # bad inputs fail before the output folder is claimed
    with run_folder(out, force=force, prefix="export", command="export", files=EXPORT_FILES,
                    inputs=tuple(runs)) as folder:
        episodes = [episode_from_run(r) for r in sources]
        if demos:
            episodes += list(demo_episodes(list(demos), render=not no_video and fmt == "lerobot"))
        if fmt == "lerobot":
            from ..export.lerobot import write_lerobot

            info = write_lerobot(episodes, folder, video=False if no_video else None)
            click.echo(json.dumps({"out": out, "episodes": info["total_episodes"], "frames": info["total_frames"],
                                   "tasks": info["total_tasks"], "fps": info["fps"],
                                   "video": info["video_path"] is not None}))
        else:
            path = write_jsonl(episodes, folder)
            click.echo(json.dumps({"out": str(path), "episodes": len(episodes)}))


COMMANDS: list[click.Command] = [export_cmd]
