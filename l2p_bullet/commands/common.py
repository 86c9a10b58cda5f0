"""Options and helpers the commands share."""

from __future__ import annotations

import click

MAX_SEED = 2**32 - 1
"""Seeds are what numpy's and torch's generators accept alike: 0 to 2**32 - 1."""

seed_option = click.option("--seed", type=click.IntRange(0, MAX_SEED), default=0, show_default=True, help="Random seed (runs are deterministic for a seed).")
force_option = click.option(
    "--force", is_flag=True,
    help="Replace the output folder if it holds a finished run of l2p-bullet (never a folder with other files).")
scene_option = click.option(
    "--scene", "scene_path", type=click.Path(dir_okay=False), default=None,
    help="Scene file (JSON, see README); default: blocks A (red) and B (green).",
)


def load_scene_or_default(scene_path: str | None):
    """The scene from ``--scene``, or the default two-block scene."""
    from ..core.scene import default_scene, load_scene

    return default_scene() if scene_path is None else load_scene(scene_path)
