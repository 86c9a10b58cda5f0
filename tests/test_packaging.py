"""The package must work from a non-editable wheel: data, URDFs and bundles travel inside it."""

from __future__ import annotations

import shutil
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


SOURCES = ("pyproject.toml", "README.md", "l2p_bullet")
"""What a wheel is built from (setuptools writes build/ and *.egg-info/ next to them, so a copy is built)."""


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    """A wheel built from a copy of the sources: building in place would leave build/ in the checkout."""
    before = sorted(p.name for p in ROOT.iterdir())
    src, out = tmp_path_factory.mktemp("src"), tmp_path_factory.mktemp("wheel")
    skip = shutil.ignore_patterns("__pycache__", "*.egg-info", "build", "runs")
    for name in SOURCES:
        copy = shutil.copytree if (ROOT / name).is_dir() else shutil.copy2
        copy(ROOT / name, src / name, **({"ignore": skip} if (ROOT / name).is_dir() else {}))
    r = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-v", "-w", str(out), str(src)],
        check=True, capture_output=True, text=True,
    )
    (out / "build.log").write_text(r.stdout + r.stderr)
    (whl,) = out.glob("l2p_bullet-*.whl")
    assert sorted(p.name for p in ROOT.iterdir()) == before, "building the wheel wrote into the checkout"
    return whl


def test_the_build_has_no_deprecation_warning_and_an_spdx_licence(wheel: Path) -> None:
    """Issue 26: ``project.license`` as a table made setuptools warn on every install."""
    log = (wheel.parent / "build.log").read_text()
    assert "project.license" not in log and "deprecated" not in log.lower(), log[-2000:]
    meta = next(n for n in zipfile.ZipFile(wheel).namelist() if n.endswith(".dist-info/METADATA"))
    assert "License-Expression: MIT" in zipfile.ZipFile(wheel).read(meta).decode()


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


def test_every_make_target_the_docs_name_exists_and_the_readme_names_it() -> None:
    """Issue 26: docs/perform.md said "README: `make install`", which the README never mentioned."""
    import re

    makefile = (ROOT / "Makefile").read_text()
    targets = set(re.findall(r"^([a-z][a-z-]*):", makefile, re.M))
    readme = (ROOT / "README.md").read_text()
    for doc in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        for target in re.findall(r"`make ([a-z-]+)`|^\s+make ([a-z-]+)", doc.read_text(), re.M):
            name = target[0] or target[1]
            assert name in targets, f"{doc.name} names `make {name}`, which the Makefile lacks"
            assert re.search(rf"make {name}\b", readme), f"{doc.name} names `make {name}`; the README does not"


def test_every_option_the_readme_command_table_names_exists() -> None:
    """The README's command table is written by hand: every ``--option`` a row names must be one of that
    command's options, and every choice it lists one the option accepts (a maintainer's onboarding read,
    2026-11-28, found the table drifting from ``--help``)."""
    import re

    import click

    from l2p_bullet.cli import main

    readme = (ROOT / "README.md").read_text()
    table = readme.split("## Commands", 1)[1].split("\n\n", 2)[1]
    checked = 0
    for row in table.splitlines()[2:]:
        code = re.match(r"\| `l2p-bullet ([a-z-]+)([^`]*)`", row)
        assert code, row
        command = main.commands[code.group(1)]
        params = {o: p for p in command.params for o in (*p.opts, *p.secondary_opts)}
        for option, choices in re.findall(r"(--[a-z][a-z-]*)(?: ([a-z:0-9]+(?:\\\|[a-z:0-9]+)+))?", code.group(2)):
            assert option in params, f"README: `{code.group(1)} {option}` is no option of {code.group(1)}"
            listed = set(choices.split("\\|")) if choices else set()
            if listed and isinstance(params[option].type, click.Choice):
                assert listed == set(params[option].type.choices), (code.group(1), option, listed)
            elif listed:  # a free-form option: its help names every value the README lists
                words = set(re.findall(r"[a-z0-9][a-z0-9:]*", params[option].help or ""))
                assert listed <= words, (code.group(1), option, listed - words, params[option].help)
            checked += 1
    assert checked > 60


def test_the_planner_option_names_every_planner() -> None:
    """``--planner``'s help is written by hand (commands import only click, so that --help starts fast): it
    must name every planner ``planning.PLANNERS`` has."""
    import re

    from l2p_bullet.cli import main
    from l2p_bullet.planning import PLANNERS

    for name in ("perform", "plan"):
        (option,) = [p for p in main.commands[name].params if "--planner" in p.opts]
        assert set(PLANNERS) <= set(re.findall(r"[a-z]+", option.help)), (name, option.help)


def test_the_readme_and_docs_give_one_worker_scaling_figure() -> None:
    """The benchmarks page and docs/evaluate.md give the same 1 -> 2 workers figure (they once disagreed: 1.98x
    against "not shown on this machine")."""
    import re

    def figure(text: str) -> str:
        return re.search(r"1 -> 2 workers[^\n]*?(\d\.\d\d)x", text).group(1)

    readme, docs = (ROOT / "docs" / "benchmarks.md").read_text(), (ROOT / "docs" / "evaluate.md").read_text()
    assert figure(readme) == figure(docs)
    assert "bench_evaluate.py --runs 40" in docs and "quiet" in docs
