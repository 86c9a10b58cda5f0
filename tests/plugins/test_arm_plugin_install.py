"""A new arm, end to end, the way an author adds one (issue 22): ``new-arm`` makes a plugin package from a
shipped URDF (the xArm6 with its gripper), pip installs it into a throw-away environment layered on the
project's (as tests/plugins/test_plugin_install.py does), and the installed arm performs "move A around B".
Also the URDFs ``new-arm`` must refuse, each with one line."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
from test_plugin_install import run  # the same subprocess helper (no network, the pip settings)

from l2p_bullet.errors import PluginError


def _data() -> Path:
    import pybullet_data

    return Path(pybullet_data.getDataPath())


def _layered_venv(tmp_path: Path) -> tuple[Path, list[str]]:
    """A throw-away environment layered on the project's (its packages visible through a .pth), where a plugin is
    pip-installed as a user would: its python, and the CLI run by it."""
    env = tmp_path / "env"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(env)], check=True)
    site = next((env / "lib").glob("python3*/site-packages"))
    (site / "zz_host_env.pth").write_text(f"import site; site.addsitedir({sysconfig.get_paths()['purelib']!r})\n")
    venv = env / "bin" / "python"
    return venv, [str(venv), "-m", "l2p_bullet.cli"]


@pytest.mark.slow
def test_new_arm_makes_an_installable_plugin_that_performs(tmp_path: Path):
    from l2p_bullet.arms import XARM6

    venv, cli = _layered_venv(tmp_path)
    out = run([*cli, "new-arm", "my-xarm", "--urdf", str(_data() / "xarm" / "xarm6_with_gripper.urdf")], tmp_path,
              timeout=600)
    assert "wrote l2p-arm-my-xarm/" in out.stdout and "6 arm joints" in out.stdout
    module = (tmp_path / "l2p-arm-my-xarm" / "l2p_arm_my_xarm" / "__init__.py").read_text()
    assert "URDF = 'xarm/xarm6_with_gripper.urdf'" in module  # inside pybullet_data: written portably
    assert re.search(r"gripper_opening=0\.08\d*", module), module
    run([sys.executable, "-m", "pip", "--python", str(venv), "install", "--no-deps", "--no-build-isolation",
         "--no-index", "--quiet", str(tmp_path / "l2p-arm-my-xarm")], tmp_path)
    try:
        arms = {a["name"]: a for a in json.loads(run([*cli, "arms", "--json"], tmp_path).stdout)["arms"]}
        assert arms["my-xarm"]["ok"] and arms["my-xarm"]["package"] == "l2p-arm-my-xarm", arms["my-xarm"]
        assert arms["my-xarm"]["workspace_radius_m"] >= 0.25 - 0.01  # as the built-in xarm6's
        # the ring the built-in measures (0.105-0.685 m), to a step of the measurement: not the 0.07 m the IK reaches
        # near the base with the gripper through the arm's base
        near, far = arms["my-xarm"]["reach_m"]
        assert abs(near - XARM6.reach[0]) <= 0.011 and abs(far - XARM6.reach[1]) <= 0.011, (near, far)
        r = json.loads(run([*cli, "perform", "move A around B", "--arm", "my-xarm", "--no-render", "--json", "-q",
                            "--out", str(tmp_path / "run")], tmp_path, timeout=300).stdout)
        assert r["verdict"]["success"], r
        assert r["anchor_displacement_m"] < 0.001 and r["final_error_m"] < 0.005
        summary = json.loads((tmp_path / "run" / "summary.json").read_text())
        assert summary["arm"] == "my-xarm"
        here = subprocess.run([sys.executable, "-m", "l2p_bullet.cli", "arms", "--json"], capture_output=True,
                              text=True, check=True)
        assert "my-xarm" not in {a["name"] for a in json.loads(here.stdout)["arms"]}  # the project's env is untouched
    finally:
        run([sys.executable, "-m", "pip", "--python", str(venv), "uninstall", "--yes", "--quiet", "l2p-arm-my-xarm"],
            tmp_path)
    arms = {a["name"] for a in json.loads(run([*cli, "arms", "--json"], tmp_path).stdout)["arms"]}
    assert "my-xarm" not in arms


def test_new_arm_measures_the_opening_across_the_fingers_of_a_turned_hand():
    """The Panda's hand sits turned 45 degrees on its flange, so at the URDF's zero pose its fingers open along a
    diagonal of the world: boxes aligned with the world's axes overlap there and read 3.0 cm for fingers that
    travel 2 x 4 cm, and the arm new-arm made from pybullet_data's panda.urdf could grasp no block of the default
    scene (5 cm). Measured along the hand's own axes, the boxes (Bullet's, grown by its collision margin, as for
    the xArm6's 8.3 cm) leave 7.2 cm. (What new-arm reads from the URDF, ``read_arm``: the ring, wrist and hand
    measurements that ``guess`` adds after it leave the fingers alone, and the two installs in this module run them
    whole.)"""
    from l2p_bullet.arms import PANDA
    from l2p_bullet.embodiment.arm_guess import read_arm

    spec = read_arm("my-panda", str(_data() / "franka_panda" / "panda.urdf"))
    assert 0.07 <= spec.gripper_opening <= PANDA.gripper_opening, spec.gripper_opening
    assert spec.finger_joints == PANDA.finger_joints and spec.finger_closed == PANDA.finger_closed


def test_new_arm_refuses_a_urdf_with_missing_meshes(tmp_path: Path):
    from l2p_bullet.plugins.arm_scaffold import scaffold_arm

    urdf = tmp_path / "arm.urdf"
    urdf.write_text((_data() / "xarm" / "xarm6_with_gripper.urdf").read_text())  # its meshes stay behind
    with pytest.raises(PluginError, match=r"names \d+ mesh file\(s\) that do not exist \(first: package://"):
        scaffold_arm("lost", str(urdf), tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_new_arm_refuses_an_arm_without_a_gripper_and_a_taken_name(tmp_path: Path):
    from l2p_bullet.plugins.arm_scaffold import scaffold_arm

    with pytest.raises(PluginError, match="has no gripper this toolkit can use"):
        scaffold_arm("bare", str(_data() / "xarm" / "xarm6_robot.urdf"), tmp_path / "out")
    with pytest.raises(PluginError, match='an arm named "xarm6" is already installed'):
        scaffold_arm("xarm6", str(_data() / "xarm" / "xarm6_with_gripper.urdf"), tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_new_arm_refuses_a_chain_that_cannot_reach_the_table(tmp_path: Path):
    from l2p_bullet.plugins.arm_scaffold import scaffold_arm

    folder = _data() / "xarm"
    text = (folder / "xarm6_with_gripper.urdf").read_text().replace("package://", f"{folder}/")
    text = re.sub(r'(<joint name="world_joint" type="fixed">.*?<origin[^>]*xyz=")[^"]*', r"\g<1>0 0 1.5", text,
                  count=1, flags=re.S)  # the base 1.5 m above the table
    (tmp_path / "high.urdf").write_text(text)
    with pytest.raises(PluginError, match="cannot reach the table"):
        scaffold_arm("high", str(tmp_path / "high.urdf"), tmp_path / "out")


@pytest.mark.parametrize("filename", ['x""";import os;os.system("echo owned");"""y.urdf', "back\\Nslash.urdf"])
def test_new_arm_writes_a_urdf_named_like_code_into_a_module_that_runs_none(tmp_path: Path, monkeypatch, filename):
    """The URDF's file name stands in the module's docstring: a name that closes the docstring must not
    become code the plugin runs when imported (nor a backslash a SyntaxError)."""
    import ast
    import dataclasses

    from l2p_bullet.arms import PANDA
    from l2p_bullet.embodiment import arm_guess
    from l2p_bullet.plugins.arm_scaffold import scaffold_arm

    urdf = tmp_path / filename
    urdf.write_text('<robot name="r"><link name="base"/></robot>\n')  # one link: new-arm checks that first
    monkeypatch.setattr(arm_guess, "guess", lambda name, path, **kw: dataclasses.replace(PANDA, name=name, urdf=path))
    made = scaffold_arm("named", str(urdf), tmp_path / "out")
    tree = ast.parse((made.root / made.module / "__init__.py").read_text())
    assert [type(s).__name__ for s in tree.body] == ["Expr", "ImportFrom", "Assign", "Assign"], ast.dump(tree)[:400]
    assert "made by `l2p-bullet new-arm` from " in ast.get_docstring(tree)


@pytest.mark.slow
def test_the_composed_ur5e_with_a_robotiq_is_installed_checked_and_performs_around(tmp_path: Path):
    """The named goal: the UR5e and the Robotiq 2F-85 of airo-models, one new-arm command, pip-installed into a
    throw-away environment layered on the project's (as test_arm_plugin_install.py does), ``arms --check`` OK,
    and "move A around B" succeeds with the anchor untouched."""
    airo = pytest.importorskip("airo_models.files")
    venv, cli = _layered_venv(tmp_path)
    out = run([*cli, "new-arm", "my-ur5e", "--urdf", airo.get_urdf_path("ur5e"), "--gripper",
               airo.get_urdf_path("robotiq_2f_85")], tmp_path, timeout=600)
    assert "wrote l2p-arm-my-ur5e/" in out.stdout and "6 arm joints" in out.stdout and "opens 8." in out.stdout
    run([sys.executable, "-m", "pip", "--python", str(venv), "install", "--no-deps", "--no-build-isolation",
         "--no-index", "--quiet", str(tmp_path / "l2p-arm-my-ur5e")], tmp_path)
    shutil.rmtree(tmp_path / "l2p-arm-my-ur5e")  # the installed package carries its URDF and meshes
    checked = json.loads(run([*cli, "arms", "my-ur5e", "--check", "--json"], tmp_path, timeout=900).stdout)
    assert checked["arms"][0]["ok"], checked
    r = json.loads(run([*cli, "perform", "move A around B", "--arm", "my-ur5e", "--no-render", "--json", "-q",
                        "--out", str(tmp_path / "run")], tmp_path, timeout=300).stdout)
    assert r["verdict"]["success"], r
    assert r["anchor_displacement_m"] < 0.001 and r["final_error_m"] < 0.005
