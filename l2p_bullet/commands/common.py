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
