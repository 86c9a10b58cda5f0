"""``l2p-bullet export``: run folders (and the shipped demonstrations) as a dataset others can load."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import click

from .common import force_option


@click.command("export")
@click.argument("runs", nargs=-1, type=click.Path(exists=True))
@click.argument("out", type=click.Path())
@click.option("--format", "fmt", type=click.Choice(["json", "lerobot", "rerun"]), default="json", show_default=True,
              help="json: OUT/episodes.jsonl; lerobot: a LeRobot v3.0 dataset (needs l2p-bullet[export]); "
                   "rerun: the file OUT.rrd, a 3-D replay for the Rerun viewer (needs l2p-bullet[rerun]).")
@click.option(
    "--demos",
    multiple=True,
    metavar="SPEC",
    help="Also the shipped human demonstrations, replayed by the arm: all, ACTION or ACTION:INDEX (repeatable).",
)
@click.option("--no-video", is_flag=True, help="Leave the camera images out (lerobot), and render no demonstration.")
@click.option("--json", "as_json", is_flag=True,
              help="Print what was written as one JSON object (for scripts; export printed it always before).")
@force_option
def export_cmd(runs: tuple[str, ...], out: str, fmt: str, demos: tuple[str, ...], no_video: bool, as_json: bool,
               force: bool) -> None:
    """Write RUNS (run folders, or folders holding them, e.g. an evaluation's) to OUT.

    \b
    Examples:
      l2p-bullet export runs/eval --format lerobot datasets/eval
      l2p-bullet export --demos around --demos closer:0 --format lerobot datasets/demos
    Every episode's task is its sentence ("move A around B"). Render the runs (perform without
    --no-render, evaluate --render-every 1) to have videos. A run that did not finish (interrupted,
    broken off) is skipped with a note on stderr; one whose action failed is exported.
    """
    from ..core.folders import unfinished
    from ..core.runfolder import run_folder, run_folder_state
    from ..errors import L2PError, PathError, RunFolderError, plural
    from ..evaluate.progressbar import ProgressBar
    from ..export.episodes import EXPORT_FILES, demo_specs, run_folders

    if not runs and not demos:
        raise PathError("nothing to export: give run folders and/or --demos")
    found = run_folders(list(runs)) if runs else []  # bad inputs fail before the output folder is claimed
    sources = []
    for r in found:
        note = unfinished(r)  # an interrupted run's folder may hold a 0-byte frame: never an episode
        if note:
            click.echo(note, err=True)
        else:
            sources.append(r)
    if found and not sources and not demos:
        raise PathError(f"nothing to export: none of the {len(found)} run folders given finished (see the notes above)")
    if fmt == "rerun":
        info = _export_rerun(sources, out, demos, force)
        click.echo(
            json.dumps(info) if as_json else f"wrote {plural(info['runs'], 'run')} to {out} (view it: rerun {out})"
        )
        return
    specs = demo_specs(list(demos)) if demos else []
    # evaluate's progress bar on stderr: a rendered demonstration takes seconds each
    bar = ProgressBar(len(sources) + len(specs), unit="episodes", label="export: reading")
    before = run_folder_state(Path(out))
    try:
        with run_folder(out, force=force, prefix="export", command="export", files=EXPORT_FILES, inputs=tuple(runs),
                        option="OUT", restore_on_error=True) as folder:  # OUT: export's argument, not --out
            _export(folder, out, fmt, sources, demos, no_video, as_json, bar)
    except L2PError as e:
        # a refused export (a crafted run, runs of different arms) leaves OUT as it was, so the retry just works:
        # gone if it was not there, empty if it was (a finished export it was to replace is back: restore_on_error)
        if before in ("missing", "empty", "incomplete") and not isinstance(e, RunFolderError):
            shutil.rmtree(out, ignore_errors=True)
            if before == "empty":
                Path(out).mkdir(exist_ok=True)
        raise


def _export(folder, out: str, fmt: str, sources: list, demos: tuple[str, ...], no_video: bool, as_json: bool,
            bar) -> None:
    """Read ``sources`` (run folders) and ``demos`` and write them into the claimed ``folder`` in ``fmt``."""
    from ..errors import plural
    from ..evaluate.progressbar import ProgressBar
    from ..export.episodes import demo_episodes, episodes_from_run, write_jsonl

    bar.advance(0)  # a first line at once (the folder is claimed): the first rendered demonstration is slow
    episodes = []
    try:
        for r in sources:
            episodes.extend(episodes_from_run(r))  # a chain run gives one episode per clause
            bar.advance()
        for ep in demo_episodes(list(demos), render=not no_video and fmt == "lerobot") if demos else []:
            episodes.append(ep)
            bar.advance()
    finally:
        bar.close()
    if fmt == "lerobot":
        from ..export.lerobot import steps, write_lerobot

        video = False if no_video else all(e.images is not None for e in episodes) or None
        bar = ProgressBar(steps(episodes, bool(video)), unit="steps", label="export: writing")
        try:
            info = write_lerobot(episodes, folder, video=video, tick=bar.advance)
        finally:
            bar.close()
        has_video = info["video_path"] is not None
        result = {"out": out, "episodes": info["total_episodes"], "frames": info["total_frames"],
                  "tasks": info["total_tasks"], "fps": info["fps"], "video": has_video}
        said = (f"wrote {plural(info['total_episodes'], 'episode')} ({info['total_frames']} frames at {info['fps']} "
                f"fps, {plural(info['total_tasks'], 'task')}, {'with' if has_video else 'without'} video) to {out}, "
                "a LeRobot v3.0 dataset")
    else:
        path = write_jsonl(episodes, folder)
        result = {"out": str(path), "episodes": len(episodes)}
        said = f"wrote {plural(len(episodes), 'episode')} ({sum(len(e.frames) for e in episodes)} frames) to {path}"
    click.echo(json.dumps(result) if as_json else said)  # the JSON as export printed it always before --json


def _export_rerun(sources: list, out: str, demos: tuple[str, ...], force: bool) -> dict:
    """``--format rerun``: one .rrd file (never a folder), replaced only with --force."""
    from pathlib import Path

    from ..errors import PathError
    from ..export.rerun import write_rerun

    path = Path(out)
    if demos:
        raise PathError("--format rerun exports run folders; replay a demonstration first (l2p-bullet replay --demo)")
    if path.suffix != ".rrd":
        raise PathError(f"--format rerun writes one file: name it OUT.rrd (got {out})")
    if path.is_symlink() or (path.exists() and not path.is_file()):
        raise PathError(f"{out} exists and is not a plain file; choose another name")
    if path.exists() and not force:
        raise PathError(f"{out} exists; add --force to replace it")
    if not path.parent.is_dir():
        raise PathError(f"no folder {path.parent} to write {path.name} into")
    return write_rerun(sources, path)


COMMANDS: list[click.Command] = [export_cmd]
