"""``l2p-bullet arms``: list the installed arms (built-in and plugins); ``--check`` runs a reach test over the table."""

from __future__ import annotations

import sys

import click


@click.command("arms")
@click.option("--json", "as_json", is_flag=True, help="Print JSON (for scripts).")
@click.option("--check", is_flag=True,
              help="Also load every arm and run a reach test over the table (its reach ring and hand profile, "
                   "measured); exit 1 if any arm is broken or reaches less than it declares.")
def arms_cmd(as_json: bool, check: bool) -> None:
    """List the installed arms: name, package, joints, reach, workspace, gripper opening.

    Arms are entry points of the group "l2p_bullet.arms" (the built-in panda, xarm6 and kuka-iiwa register
    the same way); broken ones are listed with the reason. Choose one with perform/replay/evaluate --arm NAME.
    """
    from ..core.contracts import dumps_json
    from ..core.scene import Workspace
    from ..embodiment import arm_plugins

    infos = arm_plugins.discover()
    rows = []
    for a in infos:
        row = {"name": a.name, "package": a.package, "package_version": a.package_version, "value": a.value,
               "ok": a.ok, "error": a.error}
        if a.spec is not None:
            s = a.spec
            ws = arm_plugins.fit_workspace(Workspace(), s)
            row |= {"description": s.description, "urdf": s.urdf, "arm_joints": len(s.arm_joints),
                    "finger_joints": len(s.finger_joints), "reach_m": list(s.reach), "mount": list(s.mount),
                    "workspace_radius_m": round(ws.inner_radius, 4), "workspace": ws.to_dict(),
                    "gripper_opening_m": s.gripper_opening, "wrist_limit_rad": s.wrist_limit,
                    "payload_kg": s.payload}
        if check and a.ok:
            click.echo(f"checking {a.name} ...", err=True)
            result = arm_plugins.check(a.spec)
            row["check"] = result
            row["ok"], row["error"] = result["ok"], result["error"]
        rows.append(row)
    failed = check and any(not r["ok"] for r in rows)
    if as_json:
        click.echo(dumps_json({"arms": rows}, indent=1))
        sys.exit(1 if failed else 0)
    good = [r for r in rows if "arm_joints" in r]
    w = max((len(r["name"]) for r in rows), default=4)
    for r in good:
        click.echo(f'{r["name"]:<{w}}  {r["arm_joints"]} joints  reach {r["reach_m"][0]:.2f}-{r["reach_m"][1]:.2f} m  '
                   f'workspace {_words(r["workspace"])}  opens {r["gripper_opening_m"] * 100:.1f} cm  '
                   f'carries {r["payload_kg"]:g} kg  {r["package"]} {r["package_version"]}  {r["description"]}')
        c = r.get("check")
        if c is not None and "measured_reach_m" in c:
            click.echo(f'{"":<{w}}  check: reaches {c["measured_reach_m"][0]:.2f}-{c["measured_reach_m"][1]:.2f} m '
                       f'(workspace {_words(c["measured_workspace"])}), fingertips '
                       f'{c["fingertip_drop_m"] * 1000:.1f} mm below the tool point: ' + ("OK" if r["ok"] else r["error"]))
    bad = [r for r in rows if not r["ok"]]
    if bad:
        click.echo("\nbroken arms (not usable):")
        for r in bad:
            click.echo(f'  {r["name"]} (package {r["package"]} {r["package_version"]}): {r["error"]}')
    if check:
        click.echo(f"all {len(rows)} arms OK (each loaded and reach-tested)" if not failed else
                   f"{len(bad)} of {len(rows)} arms failed the check")
    if failed:
        sys.exit(1)


COMMANDS: list[click.Command] = [arms_cmd]


@click.command("new-arm")
@click.argument("name")
@click.option("--urdf", required=True, type=click.Path(dir_okay=False), help="The arm's URDF (meshes where it says).")
@click.option("--tool-link", default=None, help="An existing link to use as the tool point (default: one is added "
              "between the closed fingertips).")
@click.option("--fingers", default=None, metavar="J,J", help='The finger joints (default: joints named "finger").')
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Folder to create (default: ./l2p-arm-NAME). Never overwritten.")
def new_arm_cmd(name: str, urdf: str, tool_link: str | None, fingers: str | None, out: str | None) -> None:
    """Scaffold an installable arm plugin package for NAME from a URDF.

    It reads the joints, guesses the arm's chain, the fingers and the tool point between the fingertips,
    measures the gripper's opening, the hand profile and the reachable ring on the table, and writes the
    package. A URDF with meshes missing, without a gripper, or whose chain cannot reach the table is refused.

    \b
    Example:
      l2p-bullet new-arm my-xarm --urdf path/to/xarm6_with_gripper.urdf
      pip install ./l2p-arm-my-xarm && l2p-bullet arms --check
      l2p-bullet perform "move A around B" --arm my-xarm
    """
    from ..plugins.arm_scaffold import scaffold_arm

    click.echo(f"reading and measuring {urdf} (a minute) ...", err=True)
    names = [f.strip() for f in fingers.split(",") if f.strip()] if fingers else None
    made = scaffold_arm(name, urdf, out, tool_link=tool_link, fingers=names)
    s = made.spec
    click.echo(f'wrote {made.root}/ for the arm "{name}": {len(s.arm_joints)} arm joints, '
               f"{len(s.finger_joints)} gripper joints, opens {s.gripper_opening * 100:.1f} cm, reaches "
               f"{s.reach[0]:.2f}-{s.reach[1]:.2f} m (mounted at x={s.mount[0]:.3f} m); payload {s.payload:g} kg "
               "(a URDF does not say: set your arm's rated payload in its ArmSpec)")
    click.echo(f"next: {sys.executable.rsplit('/', 1)[0]}/pip install ./{made.root}   then   l2p-bullet arms --check")


COMMANDS.append(new_arm_cmd)


def _words(ws: dict) -> str:
    """A workspace's JSON (Workspace.to_dict) in a listing: the disk's radius, and the ring cutting it."""
    return f'r={ws["r"]:.2f} m' + (f' cut to {ws["near"]:.2f}-{ws["far"]:.2f} m from the base' if "near" in ws else "")
