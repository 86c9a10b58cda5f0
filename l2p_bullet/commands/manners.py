"""``l2p-bullet manners``: list the installed manners of motion (slide, carry, push and plugins)."""

from __future__ import annotations

import sys

import click


@click.command("manners")
@click.option("--json", "as_json", is_flag=True, help="Print JSON (for scripts).")
def manners_cmd(as_json: bool) -> None:
    """List the installed manners of motion: name, the verbs that ask for one, what the arm does.

    Manners are entry points of the group "l2p_bullet.manners" (the built-in slide, carry and push register
    the same way); broken ones are listed with the reason and exit 1. A sentence's verb picks the manner:
    "carry A past B". See docs/manners.md.
    """
    from ..core.contracts import dumps_json
    from ..manners import registry

    rows = [{"name": m.name, "verbs": list(m.verbs), "motion": m.motion, "signature": m.signature,
             "airborne": m.airborne, "default": m.default, "description": m.description,
             "loose": list(m.loose), "over": m.over, "package": registry.package(m.name)} for m in registry.discover()]
    bad = [{"name": b.name, "error": f"{b.error} (package {b.package} {b.package_version})", "package": b.package,
            "package_version": b.package_version, "entry_point": b.entry_point} for b in registry.broken()]
    if as_json:
        click.echo(dumps_json({"manners": rows, "broken": bad}, indent=1))
        sys.exit(1 if bad else 0)
    w = max((len(r["name"]) for r in rows), default=4)
    for r in rows:
        verbs = ", ".join(r["verbs"]) + (" (and any verb no manner claims)" if r["default"] else "")
        click.echo(f'{r["name"]:<{w}}  {verbs}  [{r["package"]}]')
        click.echo(f'{"":<{w}}  {r["description"]}' + (" (above the other objects)" if r["airborne"] else ""))
        if r["over"] and r["loose"]:
            click.echo(f'{"":<{w}}  where the other objects block its way: {r["over"]} over them, for '
                       f'{", ".join(r["loose"][:4])} and the other verbs that say where, not how')
    if bad:
        click.echo("\nbroken manners (not usable):")
        for b in bad:
            click.echo(f'  {b["name"]}: {b["error"]}')
        sys.exit(1)


COMMANDS: list[click.Command] = [manners_cmd]
