"""``l2p-bullet recognize``: which installed action a motion shows (logic in :mod:`l2p_bullet.recognition`)."""

from __future__ import annotations

import click


@click.command("recognize")
@click.argument("motion", required=False, type=click.Path())
@click.option("--demo", metavar="ACTION:INDEX", help="Recognise a shipped human demonstration instead, e.g. past:3.")
@click.option("--action", "actions", multiple=True, metavar="ACTION|BUNDLE",
              help="Recognise with this action (repeatable; an installed action or a bundle folder) "
                   "instead of every installed action.")
@click.option("--top", type=click.IntRange(min=1), default=10, show_default=True, help="Readings listed (text output).")
@click.option("--json", "as_json", is_flag=True, help="Print every reading as JSON on stdout.")
def recognize_cmd(motion: str | None, demo: str | None, actions: tuple[str, ...], top: int, as_json: bool) -> None:
    """Say which action MOTION shows: every installed action's final progress, ranked.

    \b
    MOTION is a run folder, a trajectory.json, a plan.json or a scoring
    input {"size", "mover", "anchor"}. Each block that moved is read
    against each other block (a two-anchor action such as "between"
    against each pair of other blocks); the best reading comes first,
    as a sentence.

    \b
    Examples:
      l2p-bullet recognize runs/demo
      l2p-bullet recognize --demo past:3 --json
    """
    from ..core.contracts import dumps_json
    from ..errors import PathError
    from ..recognition import demo_tracks, read_tracks, recognisers
    from ..recognition import recognize as run

    if (motion is None) == (demo is None):
        raise PathError("give either MOTION (a run folder or a motion file) or --demo ACTION:INDEX (one of them)")
    for spec in actions:
        check_bundle_path(spec)
    tracks = demo_tracks(demo) if demo is not None else read_tracks(motion)
    models, skipped = recognisers(actions)
    result = run(tracks, models)
    result.skipped = skipped
    if as_json:
        click.echo(dumps_json(result.to_dict(), indent=1))
        return
    click.echo(result.best.sentence)
    width = max(len(r.claim) for r in result.readings[:top])
    for i, r in enumerate(result.readings[:top], 1):
        click.echo(f"  {i:2d}. {r.claim:<{width}}  {r.final:.2f}  ({r.action})")
    if len(result.readings) > top:
        click.echo(f"  ... {len(result.readings) - top} more (--top N, --json)")
    for s in skipped:
        click.echo(f'warning: action "{s["action"]}" left out: {s["reason"]}', err=True)


def check_bundle_path(spec: str) -> None:
    """An ``--action`` value that looks like a path (it holds a path separator, or names something that
    exists) must be a bundle folder: say so, rather than "unknown action" (no installed action is ``./x``)."""
    import os
    from pathlib import Path

    from ..core.contracts import MANIFEST
    from ..errors import BundleError

    p = Path(spec)
    seps = {os.sep} | ({os.altsep} if os.altsep else set())
    if not any(c in spec for c in seps):
        if not (p.exists() or p.is_symlink()):
            return  # an action's name: the registry says whether it is installed
        from ..core.vocabulary import ACTIONS, normalize_name
        from ..plugins import registry

        if normalize_name(spec) in {normalize_name(n) for n in [*ACTIONS, *(i.name for i in registry.discover())]}:
            return  # "around" names the action, even where a folder around/ lies in the current one
    if not p.exists():
        raise BundleError(f"--action {spec}: no such folder (give an installed action's name or a bundle folder)")
    if not p.is_dir():
        raise BundleError(f"--action {spec}: not a folder (a bundle is a folder with {MANIFEST})")
    if not (p / MANIFEST).is_file():
        raise BundleError(f"--action {spec}: not a bundle folder (no {MANIFEST})")


COMMANDS: list[click.Command] = [recognize_cmd]
