"""``l2p-bullet actions`` and ``l2p-bullet new-action``: list installed action plugins, start a new one."""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

import click


def _metrics_line(metrics: dict) -> str:
    """A short 'key=value' summary of a manifest's [metrics]: numbers only (notes and the rest are in
    --json), one level of nesting as 'table.key'."""
    def number(v: object) -> bool:
        return isinstance(v, int | float) and not isinstance(v, bool)

    parts = []
    for k, v in metrics.items():
        if number(v):
            parts.append(f"{k}={_fmt(v)}")
        elif isinstance(v, dict):
            parts += [f"{k}.{k2}={_fmt(v2)}" for k2, v2 in v.items() if number(v2)]
    return " ".join(parts)


def _fmt(v: object) -> str:
    return f"{v:.3g}" if isinstance(v, float) else str(v)


@click.command("actions")
@click.option("--json", "as_json", is_flag=True, help="Print JSON (for scripts).")
@click.option("--check", is_flag=True,
              help="Also load every plugin as perform would (import, manifest, weights, judge); exit 1 if any "
                   "plugin is broken or two conflict.")
def actions_cmd(as_json: bool, check: bool) -> None:
    """List the installed action plugins: name, version, package, phrases, metrics.

    Plugins are found through the entry-point group "l2p_bullet.actions" without importing them;
    broken ones are listed with the reason. --check loads each one as perform would and exits with
    status 1 when any plugin is broken or two plugins claim the same name or phrase (0 otherwise).
    """
    from ..core.contracts import dumps_json
    from ..plugins import registry

    plugins = registry.discover()
    reasons = {(p.name, p.package): p.error for p in plugins if not p.ok}  # a built-in and a plugin may share a name
    if check:
        for p in plugins:
            if p.ok:
                reason = registry.load_problem(p.name, plugins)
                if reason:
                    reasons[p.name, p.package] = reason
    problems = registry.conflicts(plugins)
    rows = [
        {
            "name": p.name, "version": p.version, "package": p.package, "package_version": p.package_version,
            "module": p.module, "path": str(p.path) if p.path else None, "phrases": list(p.phrases),
            "description": p.description, "frame": p.frame, "anchors": p.anchors,
            "metrics": p.metrics, "ok": (p.name, p.package) not in reasons,
            "error": reasons.get((p.name, p.package)), "kind": p.kind, "entry_point": p.entry_point,
            "builtin": p.builtin,
        }
        for p in plugins
    ]
    composites = [{"name": p.name, "version": p.version, "package": p.package, "phrases": list(p.phrases),
                   "path": str(p.path) if p.path else None, "ok": p.ok, "error": p.error, "kind": p.kind,
                   "entry_point": p.entry_point, "builtin": p.builtin}
                  for p in registry.discover("composite")]
    failed = check and (bool(reasons) or bool(problems))
    if as_json:
        click.echo(dumps_json({"actions": rows, "composites": composites, "conflicts": [str(p) for p in problems]},
                              indent=1))
        if failed:
            sys.exit(1)
        return
    good = [r for r in rows if r["ok"]]
    bad = [r for r in rows if not r["ok"]]
    if not good:
        click.echo("no usable action plugins installed")
    else:
        w = max(len(r["name"]) for r in good)
        wp = max(len(f'{r["package"]} {r["package_version"]}') for r in good)
        for r in good:
            pkg = f'{r["package"]} {r["package_version"]}'
            shape = "".join([f' ({r["frame"]} frame)' if r["frame"] != "relative" else "",
                             f' ({r["anchors"]} anchors)' if r["anchors"] != 1 else ""])
            click.echo(f'{r["name"]:<{w}}  v{r["version"] or "?":<6} {pkg:<{wp}}  {", ".join(r["phrases"])}{shape}')
            line = _metrics_line(r["metrics"])
            if line:
                pad = " " * (w + 2)
                click.echo(textwrap.fill(line, width=100, initial_indent=pad, subsequent_indent=pad,
                                         break_on_hyphens=False))
    for c in composites:  # composite actions: a phrase over a list of objects (docs/perform.md)
        click.echo(f'{c["name"]}  composite  {c["package"]}  {", ".join(c["phrases"])} A, B, C ...'
                   + ("" if c["ok"] else f'  (broken: {c["error"]})'))
    if bad:
        click.echo("\nbroken plugins (not usable):")
        for r in bad:
            click.echo(f'  {r["name"]} (package {r["package"]} {r["package_version"]}): {r["error"]}')
    for msg in problems:
        click.echo(f"conflict: {msg}", err=True)
    if check:  # a check ends with its verdict, either way
        n = len(rows)
        click.echo(f"all {n} action plugins OK (each loaded as perform would)" if not failed else
                   f"{len(reasons)} of {n} action plugins broken, {len(problems)} conflicts")
    if failed:
        sys.exit(1)


@click.command("new-action")
@click.argument("name")
@click.option("--phrase", "phrases", multiple=True, required=True,
              help='A preposition this action answers to, e.g. "to the left of" (repeat for synonyms).')
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Folder to create (default: ./l2p-NAME). Never overwritten.")
@click.option("--description", default="", help="One line for the manifest.")
@click.option("--frame", default="relative", show_default=True,
              help='Where the relation is seen from: relative, viewer (the robot\'s base) or viewer:camera.')
@click.option("--anchors", type=click.IntRange(1, 2), default=1, show_default=True,
              help='Reference objects in a sentence: 1 ("next to B") or 2 ("between B and C").')
@click.option("--judge", "judge", default=None,
              help="A rule judge of l2p_bullet/judge/rules.py (e.g. between, left-of); default: the model's own.")
@click.option("--composite", is_flag=True,
              help='A composite action over a list of objects ("make a row of A, B and C"), taught with teach.')
def new_action_cmd(name: str, phrases: tuple[str, ...], out: str | None, description: str, frame: str,
                   anchors: int, judge: str | None, composite: bool) -> None:
    """Scaffold an installable action plugin package for NAME (e.g. left-of).

    \b
    Examples:
      l2p-bullet new-action left-of --phrase "to the left of" --frame viewer --judge left-of
      l2p-bullet new-action between --phrase between --anchors 2 --judge between
      l2p-bullet new-action row --composite --phrase "make a row of" --phrase "line up"
    \b
    Then: write demonstrations into DIR/demos (see DIR/README.md, or use l2p-bullet teach NAME),
          l2p-bullet train NAME --demos DIR/demos/*.npz --out DIR/<module>
          <this environment>/bin/pip install ./DIR   (a path: never the bare name, which
                                                      would fetch a stranger's package)
          l2p-bullet perform "move A <phrase> B"
    """
    from ..core.vocabulary import ACTIONS
    from ..plugins import registry
    from ..plugins.scaffold import scaffold

    plugins = registry.discover() + registry.discover("composite")
    installed = {ph: p.name for p in plugins if p.ok for ph in p.phrases}
    names = {p.name for p in plugins} | set(ACTIONS)  # broken plugins too: the name would still clash
    s = scaffold(name, list(phrases), out, installed=installed, description=description, frame=frame,
                 anchors=anchors, judge=judge, kind="composite" if composite else "action", installed_names=names)
    if composite:
        click.echo(f"created {s.root}/ (package {s.dist_name}, module {s.module}); next steps:")
        click.echo(f"  1. l2p-bullet teach {name} --plugin {s.root}   (record rows of 2 and 3 blocks, then train)")
        click.echo(f"  2. {pip_install_command(s.root)}")
        click.echo(f'  3. l2p-bullet perform "{registry.normalize_phrase(phrases[0])} A, B, C and D" --scene ...')
        return
    click.echo(f"created {s.root}/ (package {s.dist_name}, module {s.module}); next steps:")
    click.echo(f"  1. put demonstrations in {s.root}/demos/ (format: {s.root}/README.md)")
    click.echo(f"  2. l2p-bullet train {name} --demos {s.root}/demos/*.npz --out {s.package_dir}")
    click.echo(f"  3. {pip_install_command(s.root)}")
    click.echo(f'  4. l2p-bullet perform "move A {registry.normalize_phrase(phrases[0])} B'
               + (' and C"' if anchors == 2 else '"'))


def pip_install_command(folder: Path) -> str:
    """The command that installs the scaffolded plugin into the environment running l2p-bullet.

    Always a path (``./l2p-left-of``), never a bare name: ``pip install l2p-left-of`` would look the
    name up on the package index and install whatever a stranger published under it.
    """
    import shlex
    import sys

    pip = Path(sys.prefix) / "bin" / "pip"
    cmd = shlex.quote(str(pip)) if pip.is_file() else f"{shlex.quote(sys.executable)} -m pip"
    target = str(folder)
    if not (folder.is_absolute() or target.startswith(("./", "../"))):
        target = "./" + target
    return f"{cmd} install {shlex.quote(target)}"


COMMANDS: list[click.Command] = [actions_cmd, new_action_cmd]
