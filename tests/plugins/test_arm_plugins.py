"""Arm plugins through the one plugin finder: the rule for names (a plugin cannot take a built-in's name),
and ``arms --check`` measuring each arm in a process of its own."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from l2p_bullet.arms import PANDA
from l2p_bullet.cli import main
from l2p_bullet.plugins import arms as arm_plugins
from l2p_bullet.plugins.finder import Plugin, settle


def _arm_package(site: Path, dist: str, module: str, source: str, entry_points: dict[str, str]) -> Path:
    """An installed-looking arm plugin in ``site``: ``module`` holding ``source``, and the distribution
    ``dist`` declaring ``entry_points`` in the group "l2p_bullet.arms"."""
    (site / module).mkdir(parents=True)
    (site / module / "__init__.py").write_text(source)
    info = site / f"{dist.replace('-', '_')}-0.3.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 0.3\n")
    lines = "".join(f"{k} = {v}\n" for k, v in entry_points.items())
    (info / "entry_points.txt").write_text(f"[l2p_bullet.arms]\n{lines}")
    return site


def test_one_rule_for_names_of_every_kind():
    """A plugin with a built-in's name is broken and the built-in kept; two usable plugins of one name are
    both broken; a broken plugin blocks no usable one of its name."""
    found = [Plugin("arm", "panda", "l2p-bullet", "0.1.0", "l2p_bullet.arms.builtin:PANDA"),
             Plugin("arm", "Panda", "l2p-impostor", "1.0", "imp:ARM"),
             Plugin("manner", "roll", "l2p-a", "1.0", "a"), Plugin("manner", "roll", "l2p-b", "2.0", "b"),
             Plugin("action", "left-of", "l2p-old", "0.1", "old", error="no trained weights"),
             Plugin("action", "left_of", "l2p-new", "0.2", "new")]
    got = {(p.name, p.package): p.error for p in settle(found)}
    assert got["panda", "l2p-bullet"] is None
    impostor = got["Panda", "l2p-impostor"]
    assert impostor.startswith('the name "Panda" is the built-in arm\'s (package l2p-bullet)')
    assert "uninstall l2p-impostor" in got["Panda", "l2p-impostor"]
    assert got["roll", "l2p-a"] == got["roll", "l2p-b"] == (
        'two manner plugins are both named "roll" (packages l2p-a 1.0 and l2p-b 2.0); uninstall one of them')
    assert got["left_of", "l2p-new"] is None and got["left-of", "l2p-old"] == "no trained weights"


def test_an_arm_plugin_named_panda_is_broken_and_the_builtin_panda_kept(tmp_path, monkeypatch):
    """An arm plugin named "panda" made every plain perform, plan and replay exit 2 ("two arm plugins are both
    named"): the built-in is kept, the plugin listed as broken naming its package."""
    site = _arm_package(tmp_path / "site", "l2p-impostor", "l2p_impostor",
                        "from dataclasses import replace\nfrom l2p_bullet.arms import PANDA\n"
                        "ARM = replace(PANDA, description='an impostor')\n", {"panda": "l2p_impostor:ARM"})
    monkeypatch.syspath_prepend(str(site))
    assert arm_plugins.get(None) is PANDA and arm_plugins.get("panda") is PANDA
    r = CliRunner().invoke(main, ["arms", "--json"])
    assert r.exit_code == 0, r.output
    rows = [a for a in json.loads(r.output)["arms"] if a["name"] == "panda"]
    assert [(a["package"], a["ok"], a["builtin"]) for a in rows] == [("l2p-bullet", True, True),
                                                                     ("l2p-impostor", False, False)], rows
    why = rows[1]["error"]
    assert 'the name "panda" is the built-in arm\'s' in why and "uninstall l2p-impostor" in why
    text = CliRunner().invoke(main, ["arms"]).output
    assert "panda (package l2p-impostor 0.3): the name" in text
    r = CliRunner().invoke(main, ["plan", "move A next to B", "--out", str(tmp_path / "plan")])
    assert r.exit_code == 0, r.output


CRASHING = '''
import os
import signal
from dataclasses import dataclass, fields, replace

from l2p_bullet.arms import PANDA, ArmSpec


@dataclass(frozen=True)
class CrashingArm(ArmSpec):
    """Ends the process that loads it, as a URDF that crashes PyBullet does (a segfault)."""

    def __getattribute__(self, name):
        if name == "collision_free_links":  # read when the description is loaded, never when it is listed
            os.kill(os.getpid(), signal.SIGSEGV)
        return super().__getattribute__(name)


CRASH = CrashingArm(**{f.name: getattr(PANDA, f.name) for f in fields(PANDA)} | {"name": "aaa-crash"})
MISSING = replace(PANDA, name="aab-missing", urdf="/nonexistent/l2p/arm.urdf")
'''


@pytest.mark.slow  # two fresh interpreters load the simulator
def test_arms_check_survives_an_arm_that_crashes_the_simulator(tmp_path):
    """A description that segfaulted PyBullet ended ``arms --check`` (exit 139), and the arms after it were
    never checked: each arm is checked in a process of its own and a crash is that arm's failure."""
    site = _arm_package(tmp_path / "site", "l2p-crashy", "l2p_crashy", CRASHING,
                        {"aaa-crash": "l2p_crashy:CRASH", "aab-missing": "l2p_crashy:MISSING"})
    path = os.pathsep.join(p for p in (str(site), os.environ.get("PYTHONPATH")) if p)
    cmd = [sys.executable, "-m", "l2p_bullet.cli", "arms", "--check", "--json", "aaa-crash", "aab-missing"]
    env = dict(os.environ, PYTHONPATH=path)
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600, cwd=tmp_path)
    assert p.returncode == 1, p.stdout + p.stderr
    rows = {a["name"]: a for a in json.loads(p.stdout)["arms"]}
    assert set(rows) == {"aaa-crash", "aab-missing"}
    assert not rows["aaa-crash"]["ok"]
    assert "crashed the simulator (killed by SIGSEGV)" in rows["aaa-crash"]["error"]
    assert not rows["aab-missing"]["ok"] and "cannot load or move the arm" in rows["aab-missing"]["error"]
    assert "checking aaa-crash ...\nchecking aab-missing ..." in p.stderr


def test_arms_names_an_unknown_arm_in_one_line():
    r = CliRunner().invoke(main, ["arms", "--check", "xarm"])
    assert r.exit_code == 2 and 'unknown arm "xarm"' in r.output and 'Did you mean "xarm6"?' in r.output
