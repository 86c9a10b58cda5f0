"""``l2p-bullet arms``: list the installed arms (built-in and plugins); ``--check`` runs a reach test over the table."""

from __future__ import annotations

import json
import sys

import click

CHECK_TIMEOUT_S = 900
"""Seconds one arm's check may take in its own process (a shipped arm takes about a minute on two cores)."""


@click.command("arms")
@click.argument("names", nargs=-1)
@click.option("--json", "as_json", is_flag=True, help="Print JSON (for scripts).")
@click.option("--check", is_flag=True,
              help="Also load every arm and run a reach test over the table (its reach ring and hand profile, "
                   "measured); exit 1 if any arm is broken or reaches less than it declares.")
def arms_cmd(names: tuple[str, ...], as_json: bool, check: bool) -> None:
    """List the installed arms: name, package, joints, reach, workspace, gripper opening (NAMES: only these).

    Arms are entry points of the group "l2p_bullet.arms" (the built-in panda, xarm6 and kuka-iiwa register
    the same way); broken ones are listed with the reason. Choose one with perform/replay/evaluate --arm NAME.
    --check measures each arm in a process of its own, so an arm whose description crashes the simulator is
    reported broken and the arms after it are still checked.
    """
    from ..arms import fit_workspace
    from ..core.contracts import dumps_json
    from ..core.scene import Workspace
    from ..errors import UnknownArmError
    from ..plugins import arms as arm_plugins
    from ..plugins.finder import name_key

    infos = arm_plugins.discover()
    for n in names:
        if not any(name_key(a.name) == name_key(n) for a in infos):
            raise UnknownArmError(n, [a.name for a in infos])
    if names:
        infos = [a for a in infos if any(name_key(a.name) == name_key(n) for n in names)]
    rows = []
    for a in infos:
        row = {"name": a.name, "package": a.package, "package_version": a.package_version, "value": a.entry_point,
               "entry_point": a.entry_point, "builtin": a.builtin, "ok": a.ok, "error": a.error}
        if a.obj is not None:
            s = a.obj
            ws = fit_workspace(Workspace(), s)
            row |= {"description": s.description, "urdf": s.urdf, "arm_joints": len(s.arm_joints),
                    "finger_joints": len(s.finger_joints), "reach_m": list(s.reach), "mount": list(s.mount),
                    "workspace_radius_m": round(ws.inner_radius, 4), "workspace": ws.to_dict(),
                    "gripper_opening_m": s.gripper_opening, "wrist_limit_rad": s.wrist_limit,
                    "payload_kg": s.payload}
        if check and a.ok:
            click.echo(f"checking {a.name} ...", err=True)
            result = check_apart(a.name, a.obj)
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
            click.echo(
                f"{'':<{w}}  check: reaches {c['measured_reach_m'][0]:.2f}-{c['measured_reach_m'][1]:.2f} m "
                f"(workspace {_words(c['measured_workspace'])}), fingertips "
                f"{c['fingertip_drop_m'] * 1000:.1f} mm below the tool point: " + ("OK" if r["ok"] else r["error"])
            )
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


def check_apart(name: str, spec) -> dict:
    """``embodiment.arm_measure.check`` of the installed arm ``name`` (whose spec is ``spec``) in a fresh
    interpreter: a description that crashes the simulator ends that process only (PyBullet can segfault on
    a malformed URDF), and the arm is reported broken with how its check ended."""
    import signal
    import subprocess
    import tempfile
    from pathlib import Path


    out: dict = {"name": name, "declared_reach_m": list(spec.reach)}
    code = "import sys; from l2p_bullet.commands.arms import check_here; check_here(sys.argv[1], sys.argv[2])"
    with tempfile.TemporaryDirectory(prefix="l2p-arm-check-") as tmp:
        result = Path(tmp) / "check.json"
        try:
            p = subprocess.run([sys.executable, "-c", code, name, str(result)], stdin=subprocess.DEVNULL,
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=CHECK_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            return out | {"ok": False, "error": f"its check did not finish in {CHECK_TIMEOUT_S} s"}
        if p.returncode == 0 and result.is_file():
            return json.loads(result.read_text())
    if p.returncode < 0:
        try:
            how = f"killed by {signal.Signals(-p.returncode).name}"
        except ValueError:
            how = f"killed by signal {-p.returncode}"
        return out | {"ok": False, "error": f"loading or moving the arm crashed the simulator ({how})"}
    last = (p.stderr.decode(errors="replace").strip().splitlines() or ["no message"])[-1]
    return out | {"ok": False, "error": f"its check failed (exit {p.returncode}): {last}"[:300]}


def check_here(name: str, result: str) -> None:
    """The child's side of :func:`check_apart`: check the arm ``name`` and write the result to ``result``."""
    from pathlib import Path

    from ..core.contracts import dumps_json
    from ..embodiment.arm_measure import check
    from ..plugins import arms as arm_plugins

    Path(result).write_text(dumps_json(check(arm_plugins.get(name))))


COMMANDS: list[click.Command] = [arms_cmd]


@click.command("new-arm")
@click.argument("name")
@click.option("--urdf", required=True, type=click.Path(dir_okay=False), help="The arm's URDF (meshes where it says).")
@click.option("--tool-link", default=None, help="An existing link to use as the tool point (default: one is added "
              "between the closed fingertips).")
@click.option("--fingers", default=None, metavar="J,J", help='The finger joints (default: joints named "finger").')
@click.option("--out", "out", type=click.Path(file_okay=False), default=None,
              help="Folder to create (default: ./l2p-arm-NAME). Never overwritten.")
@click.option("--gripper", default=None, type=click.Path(dir_okay=False),
              help="The gripper's own URDF, bolted to the arm's --mount link (the arm's URDF then has no gripper); "
                   "the two are written as one URDF, with their meshes, into the package.")
@click.option("--mount", default=None, metavar="LINK", help="The arm's link the gripper is bolted to (default: tool0 "
              "if the arm has it, else its last link).")
@click.option("--mount-xyz", default="0,0,0", metavar="X,Y,Z",
              help="The gripper's offset in the mount link's frame (m).")
@click.option("--mount-rpy", default="0,0,0", metavar="R,P,Y", help="The gripper's rotation on the mount link (rad).")
def new_arm_cmd(name: str, urdf: str, tool_link: str | None, fingers: str | None, out: str | None,
                gripper: str | None, mount: str | None, mount_xyz: str, mount_rpy: str) -> None:
    """Scaffold an installable arm plugin package for NAME from a URDF (or an arm's URDF and a gripper's).

    It reads the joints, guesses the arm's chain, the fingers and the tool point between the fingertips,
    measures the gripper's opening, the hand profile and the reachable ring on the table, and writes the
    package. A URDF with meshes missing, without a gripper, or whose chain cannot reach the table is refused.

    \b
    Example:
      l2p-bullet new-arm my-xarm --urdf path/to/xarm6_with_gripper.urdf
      l2p-bullet new-arm my-ur5e --urdf ur5e.urdf --gripper robotiq_2f_85.urdf
      pip install ./l2p-arm-my-xarm && l2p-bullet arms --check
      l2p-bullet perform "move A around B" --arm my-xarm
    """
    from ..errors import PluginError
    from ..plugins.arm_scaffold import scaffold_arm

    def triple(text: str, option: str) -> tuple[float, float, float]:
        try:
            x, y, z = (float(v) for v in text.split(","))
        except ValueError:
            raise PluginError(f"{option} takes three numbers joined by commas, e.g. 0,0,0.01 (got {text!r})") from None
        return x, y, z

    xyz, rpy = triple(mount_xyz, "--mount-xyz"), triple(mount_rpy, "--mount-rpy")
    if gripper is None and (mount is not None or mount_xyz != "0,0,0" or mount_rpy != "0,0,0"):
        raise PluginError("--mount, --mount-xyz and --mount-rpy place a --gripper: give its URDF too")
    click.echo(f"reading and measuring {urdf} (a minute) ...", err=True)
    names = [f.strip() for f in fingers.split(",") if f.strip()] if fingers else None
    made = scaffold_arm(name, urdf, out, tool_link=tool_link, fingers=names, gripper=gripper, mount=mount,
                        mount_xyz=xyz, mount_rpy=rpy)
    s = made.spec
    click.echo(f'wrote {made.root}/ for the arm "{name}": {len(s.arm_joints)} arm joints, '
               f"{len(s.finger_joints)} gripper joints, opens {s.gripper_opening * 100:.1f} cm, reaches "
               f"{s.reach[0]:.2f}-{s.reach[1]:.2f} m (mounted at x={s.mount[0]:.3f} m); payload {s.payload:g} kg "
               "(a URDF does not say: set your arm's rated payload in its ArmSpec)")
    from .actions import pip_install_command  # new-action's: this environment's pip, the folder as a path

    click.echo(f"next: {pip_install_command(made.root)}   then   l2p-bullet arms --check")


COMMANDS.append(new_arm_cmd)


def _words(ws: dict) -> str:
    """A workspace's JSON (Workspace.to_dict) in a listing: the disk's radius, and the ring cutting it."""
    return f'r={ws["r"]:.2f} m' + (f' cut to {ws["near"]:.2f}-{ws["far"]:.2f} m from the base' if "near" in ws else "")
