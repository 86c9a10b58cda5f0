"""benchmarks/collect_meshes.py: the everyday meshes of bench_objects' ``--meshes``, copied out of the model
packages' wheels into a tuned and four held-out folders with each one's scale, turn and source."""

from __future__ import annotations

import importlib.util
import json
import struct
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

TETRA_V = [0.0, 0.0, 0.0, 0.03, 0.0, 0.0, 0.0, 0.03, 0.0, 0.0, 0.0, 0.03]
TETRA_F = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]


def _module():
    spec = importlib.util.spec_from_file_location("collect_meshes", ROOT / "benchmarks" / "collect_meshes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _msh(normals: int = 4, texcoords: int = 4) -> bytes:
    """MuJoCo's binary mesh of a 3 cm tetrahedron, with normals and texture coordinates as MyoSuite's has."""
    return (struct.pack("<4i", 4, normals, texcoords, 4) + struct.pack("<12f", *TETRA_V)
            + struct.pack(f"<{3 * normals}f", *([0.0, 0.0, 1.0] * normals))
            + struct.pack(f"<{2 * texcoords}f", *([0.5] * 2 * texcoords)) + struct.pack("<12i", *TETRA_F))


def test_the_meshes_are_copied_into_tuned_and_held_out_with_their_sources(tmp_path):
    cm = _module()
    wheels = tmp_path / "wheels"
    wheels.mkdir()
    for package, version in cm.PACKAGES.items():  # stand-in wheels holding every listed path
        with zipfile.ZipFile(wheels / f"{package.replace('-', '_')}-{version}-py3-none-any.whl", "w") as z:
            for name, (_, pkg, inner, _) in cm.MESHES.items():
                if pkg == package:
                    z.writestr(inner, _msh() if inner.endswith(".msh") else f"mesh {name}")
    tables = cm.collect(tmp_path / "out", wheels)
    assert set(tables) == {"tuned", "held-out", "held-out-2", "held-out-3", "held-out-4"}
    assert len(tables["held-out"]) * 3 >= len(tables["tuned"]) + len(tables["held-out"]) - 1
    assert len(tables["held-out-2"]) >= 6
    names = [set(t) for t in tables.values()]
    assert sum(map(len, names)) == len(set().union(*names))  # no mesh in two sets
    # the new held-out set comes from packages the other two never used
    used = {e["source"].split()[0] for g in ("tuned", "held-out") for e in tables[g].values()}
    assert not used & {e["source"].split()[0] for e in tables["held-out-2"].values()}
    # and the newest from a package none of the others used
    used |= {e["source"].split()[0] for e in tables["held-out-2"].values()}
    assert len(tables["held-out-3"]) == 6
    assert not used & {e["source"].split()[0] for e in tables["held-out-3"].values()}
    used |= {e["source"].split()[0] for e in tables["held-out-3"].values()}
    assert len(tables["held-out-4"]) == 6
    assert not used & {e["source"].split()[0] for e in tables["held-out-4"].values()}
    for group, table in tables.items():
        assert json.loads((tmp_path / "out" / group / "meshes.json").read_text()) == table
        for name, entry in table.items():
            if not entry["source"].endswith(".msh"):
                assert (tmp_path / "out" / group / name).read_text() == f"mesh {name}"
            assert entry["scale"] > 0 and entry["source"].split(":")[0].split()[0] in cm.PACKAGES
    assert tables["held-out"]["apple.glb"]["rpy"][0] > 1.5  # a Y-up GLB stood upright
    box = (tmp_path / "out" / "held-out-2" / "gelatin_box.obj").read_text().splitlines()
    assert box[1] == "v 0.03 0 0" and box[-1] == "f 2 3 4"  # the .msh written as an OBJ, faces from 1


def test_only_the_sets_asked_for_are_collected(tmp_path):
    cm = _module()
    wheels = tmp_path / "wheels"
    wheels.mkdir()
    with zipfile.ZipFile(wheels / f"genesis_world-{cm.PACKAGES['genesis-world']}-py3-none-any.whl", "w") as z:
        for name, (_, pkg, inner, _) in cm.MESHES.items():
            if pkg == "genesis-world":
                z.writestr(inner, f"mesh {name}")
    with zipfile.ZipFile(wheels / f"myosuite-{cm.PACKAGES['myosuite']}-py3-none-any.whl", "w") as z:
        for name, (_, pkg, inner, _) in cm.MESHES.items():
            if pkg == "myosuite":
                z.writestr(inner, _msh(0, 0) if inner.endswith(".msh") else f"mesh {name}")
    tables = cm.collect(tmp_path / "out", wheels, ["held-out-2"])  # no other package's wheel is needed
    assert set(tables) == {"held-out-2"} and not (tmp_path / "out" / "tuned").exists()


def test_a_file_that_is_no_msh_is_refused_in_one_line():
    cm = _module()
    with pytest.raises(SystemExit, match="not a MuJoCo .msh"):
        cm.msh_to_obj(_msh()[:-4])
    obj = cm.msh_to_obj(_msh()).decode().splitlines()
    assert len(obj) == 8 and obj[0] == "v 0 0 0" and obj[4] == "f 1 3 2"


def test_a_package_with_only_a_foreign_wheel_is_downloaded_with_its_pip_arguments(tmp_path, monkeypatch):
    """Roboschool publishes only a CPython 3.6 wheel: pip is told that platform, or it finds nothing to fetch."""
    cm = _module()
    calls = []

    def run(cmd, check):
        calls.append(cmd)
        (tmp_path / "roboschool-1.0.49-cp36-cp36m-manylinux1_x86_64.whl").write_bytes(b"")

    monkeypatch.setattr(cm.subprocess, "run", run)
    assert cm.wheel("roboschool", tmp_path).name.startswith("roboschool-1.0.49-")
    assert calls and all(a in calls[0] for a in cm.PIP_ARGS["roboschool"]) and calls[0][-1] == "roboschool==1.0.49"
