"""``l2p-bullet recognize``: which installed action a motion shows (logic in :mod:`l2p_bullet.progress.recognition`)."""

from __future__ import annotations

import click


@click.command()
@click.argument("motion", required=False, type=click.Path())
@click.option("--demo", metavar="ACTION:INDEX", help="Recognise a shipped human demonstration instead, e.g. past:3.")
@click.option("--action", "actions", multiple=True, metavar="ACTION|BUNDLE",
              help="Recognise with this action (repeatable; an installed action or a bundle folder) "
                   "instead of every installed action.")
@click.option("--top", type=click.IntRange(min=1), default=10, show_default=True, help="Readings listed (text output).")
@click.option("--json", "as_json", is_flag=True, help="Print every reading as JSON on stdout.")
def recognize(motion: str | None, demo: str | None, actions: tuple[str, ...], top: int, as_json: bool) -> None:
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
    from ..progress.recognition import demo_tracks, read_tracks, recognisers
    from ..progress.recognition import recognize as run

    if (motion is None) == (demo is None):
        raise PathError("give either MOTION (a run folder or a motion file) or --demo ACTION:INDEX (one of them)")
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


COMMANDS: list[click.Command] = [recognize]
