"""The package must work from a non-editable wheel: data, URDFs and bundles travel inside it."""

from __future__ import annotations

import subprocess
import sys
import time
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", str(out), str(ROOT)],
        check=True,
    )
    (whl,) = out.glob("l2p_bullet-*.whl")
    return whl


def test_wheel_ships_data_urdf_and_bundles_under_the_package(wheel: Path) -> None:
    names = zipfile.ZipFile(wheel).namelist()
    assert not any(n.startswith("actions/") for n in names), "no top-level 'actions' package"
    for action in ("closer", "away", "next_to", "past", "around"):
        assert f"l2p_bullet/actions/{action}/manifest.toml" in names
        assert f"l2p_bullet/actions/{action}/progress.safetensors" in names
    assert any(n.startswith("l2p_bullet/urdf/") and n.endswith(".urdf") for n in names)
    assert "l2p_bullet/data/LICENSE" in names
    for page in ("index.html", "app.js", "style.css"):  # the review app's page
        assert f"l2p_bullet/review/static/{page}" in names
    assert sum(n.startswith("l2p_bullet/data/captures/") and n.endswith(".npz") for n in names) == 11
    for f in ("index.html", "teach.js", "style.css"):  # the teach page
        assert f"l2p_bullet/teach/static/{f}" in names
    entry_points = next(n for n in names if n.endswith("entry_points.txt"))
    text = zipfile.ZipFile(wheel).read(entry_points).decode()
    assert "[l2p_bullet.actions]" in text and "around = l2p_bullet.actions.around" in text
    for f in ("manifest.toml", "recipe.json", "demos.json"):  # the composite "row" (kind = "composite")
        assert f"l2p_bullet/actions/row/{f}" in names
    assert "row = l2p_bullet.actions.row" in text


def test_help_is_fast_and_imports_neither_torch_nor_pybullet() -> None:
    code = (
        "import sys, time; t=time.perf_counter();"
        "from click.testing import CliRunner; from l2p_bullet.cli import main;"
        "r=CliRunner().invoke(main, ['--help']); assert r.exit_code == 0, r.output;"
        "bad=[m for m in ('torch','pybullet','trimesh','ruckig') if m in sys.modules]; assert not bad, bad"
    )
    t = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], check=True)
    assert time.perf_counter() - t < 5.0  # generous: the real target (0.3 s) is measured in benchmarks/
