"""Options and helpers the commands share, and the one printer of what a command did (:func:`say`)."""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import click

from ..core.contracts import MAX_SEED

seed_option = click.option(
    "--seed",
    type=click.IntRange(0, MAX_SEED),
    default=0,
    show_default=True,
    help="Random seed (runs are deterministic for a seed).",
)
arm_option = click.option(
    "--arm", default="panda", show_default=True, metavar="NAME",
    help="The arm that performs (l2p-bullet arms lists them: panda, xarm6, kuka-iiwa and installed plugins).")
force_option = click.option(
    "--force", is_flag=True,
    help="Replace the output folder if it holds a finished run of l2p-bullet (never a folder with other files).")
def _remember_mesh_dirs(ctx: click.Context, param: click.Parameter, value: tuple[str, ...]) -> tuple[str, ...]:
    ctx.meta["l2p_bullet.mesh_dirs"] = tuple(value)
    return value


def scene_option(f):
    """``--scene FILE`` and ``--mesh-dir DIR`` (repeatable: folders whose meshes a scene file may name by
    absolute path, besides its own folder; kept in the click context, so no command's signature changes)."""
    f = click.option("--mesh-dir", "mesh_dirs", multiple=True, type=click.Path(file_okay=False, exists=True),
                     expose_value=False, callback=_remember_mesh_dirs,
                     help="A folder the scene file's meshes may come from (absolute paths), besides its own.")(f)
    return click.option(
        "--scene", "scene_path", type=click.Path(dir_okay=False), default=None,
        help="Scene file (JSON, see README); default: blocks A (red) and B (green).",
    )(f)


def mesh_dirs() -> tuple[str, ...]:
    """The ``--mesh-dir`` folders of the command being run (none outside a command)."""
    ctx = click.get_current_context(silent=True)
    return () if ctx is None else tuple(ctx.meta.get("l2p_bullet.mesh_dirs", ()))


def load_scene_or_default(scene_path: str | None):
    """The scene from ``--scene`` (its meshes read from its folder or a ``--mesh-dir``), or the default
    two-block scene."""
    from ..core.scene import default_scene, load_scene

    return default_scene() if scene_path is None else load_scene(scene_path, mesh_dirs())


def greedy_options(*names: str) -> type[click.Command]:
    """A click command class whose options ``names`` take every value that follows them.

    Click options take one value each (``multiple=True`` repeats the option), but a shell glob such as
    ``--demos demos/*.npz`` expands to ``--demos a.npz b.npz``. The arguments are rewritten to
    ``--demos a.npz --demos b.npz`` before click parses them: values run until the next word that starts
    with ``-`` (or ``--``), so ``--demos a.npz --demos b.npz`` keeps working. Put positional arguments
    before such an option.
    """

    class GreedyCommand(click.Command):
        def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
            return super().parse_args(ctx, expand_greedy(args, names))

    return GreedyCommand


def expand_greedy(args: list[str], names: tuple[str, ...]) -> list[str]:
    """``[--demos, a, b, --out, x]`` -> ``[--demos, a, --demos, b, --out, x]`` (see :func:`greedy_options`)."""
    out: list[str] = []
    current: str | None = None
    expect_value = False
    for i, a in enumerate(args):
        if a == "--":
            return out + list(args[i:])
        if expect_value:  # the option's own value, whatever it looks like
            out.append(a)
            expect_value = False
        elif a in names:
            current, expect_value = a, True
            out.append(a)
        elif any(a.startswith(n + "=") for n in names):
            current = a.split("=", 1)[0]
            out.append(a)
        elif a.startswith("-"):
            current = None
            out.append(a)
        elif current is not None:
            out += [current, a]
        else:
            out.append(a)
    return out


def video_options(f):
    """--resolution, --fps, --camera and --renderer: how the run's video is filmed (perform, replay)."""
    f = click.option("--renderer", type=click.Choice(["egl", "tiny"]), default="egl", show_default=True,
                     help="egl: PyBullet's EGL plugin (Mesa's software driver without a GPU; falls back to tiny "
                          "with a note where it cannot start); tiny: TinyRenderer.")(f)
    f = click.option("--camera", default="auto", show_default=True, metavar="NAME|JSON",
                     help="auto (framed on the action from behind the robot: its left is the video's left), "
                          "viewer (fixed, behind the robot), robot (facing it), side, top, "
                          'or a JSON camera {"eye": [x, y, z], "target": [x, y, z], "fov": 45}.')(f)
    f = click.option("--fps", "fps", type=float, default=15.0, show_default=True,
                     help="Video frames per second of simulated time (1-60).")(f)
    f = click.option("--resolution", default="640x480", show_default=True, metavar="WxH",
                     help="Video frame size in pixels (width a multiple of 8).")(f)
    return f


def render_settings(resolution: str, fps: float, camera: str, renderer: str, video: str = "mp4"):
    """RenderSettings from the video options, checked (one-line errors) before anything runs."""
    from ..embodiment.sim.camera import RenderSettings, check_fps, parse_camera, parse_resolution

    width, height = parse_resolution(resolution)
    return RenderSettings(width, height, check_fps(fps), renderer, video, parse_camera(camera)).check()


def file_of_run_folder(path: str, name: str) -> str:
    """A run folder given where a file is expected stands for its ``name`` (``score`` reads trajectory.json,
    ``replay`` plan.json), as ``recognize`` takes a run folder; a folder without it is a one-line error."""
    from pathlib import Path

    from ..errors import PathError

    p = Path(path)
    if not p.is_dir():
        return path
    if not (p / name).is_file():
        raise PathError(f"{p} is a folder without {name}: give a run folder or the file itself")
    return str(p / name)


def stage_printer(quiet: bool, prefix: str = "") -> Callable[[str], None] | None:
    """The progress messages of a run on stderr (elapsed time, then the stage), or None with ``--quiet``."""
    if quiet:
        return None
    t0 = time.perf_counter()
    return lambda message: click.echo(f"[{time.perf_counter() - t0:5.1f}s] {prefix}{message}", err=True)


def say(result: Any, as_json: bool, indent: int | None = None) -> None:
    """Print what a command did, one way for every result (a run, a chain, a plan): its ``to_dict()`` as JSON
    with ``--json`` (for scripts), else its ``text()`` lines."""
    from ..core.contracts import dumps_json

    click.echo(dumps_json(result.to_dict(), indent=indent) if as_json else "\n".join(result.text()))


def error_json(sentence: str, e: Exception) -> dict:
    """What ``perform --json`` and ``plan --json`` print when they fail: the error, its type and, for a refusal,
    which check."""
    out = {"sentence": sentence, "ok": False, "error": str(e), "error_type": type(e).__name__}
    check = getattr(e, "check", None)
    if check is not None:
        out["refused"] = {"check": check, "details": getattr(e, "details", {})}
    if getattr(e, "word", ""):  # a word no object has, which a scene file's "kind" could give one
        out["unknown_word"] = e.word
    return out


@contextmanager
def reporting(sentence: str, as_json: bool) -> Iterator[None]:
    """With ``--json``, an error (L2PError) is also printed as JSON on stdout, where scripts read why; the
    one-line error still goes to stderr (exit 2)."""
    from ..errors import L2PError

    try:
        yield
    except L2PError as e:
        if as_json:
            from ..core.contracts import dumps_json

            click.echo(dumps_json(error_json(sentence, e), indent=1))
        raise
