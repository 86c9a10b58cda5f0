"""An arm and a gripper given as separate URDFs (``new-arm --gripper``): composed into one URDF whose meshes all
resolve, grippers read as they are described (mimic joints, finger limits of either sign, a four-bar linkage), one
line for a gripper that cannot be composed. The UR5e with the Robotiq 2F-85 from ``airo-models``, made by one
``new-arm`` command, installed and performing, is tests/plugins/test_arm_plugin_install.py's."""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from l2p_bullet.errors import PluginError


def _data() -> Path:
    import pybullet_data

    return Path(pybullet_data.getDataPath())


def _link(name: str, mesh: str | None = None) -> str:
    shape = f'<mesh filename="{mesh}"/>' if mesh else '<box size="0.02 0.02 0.02"/>'
    geom = f"<geometry>{shape}</geometry>"
    return (f'<link name="{name}"><inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" '
            f'iyz="0" izz="1e-4"/></inertial><visual>{geom}</visual><collision>{geom}</collision></link>')


def _joint(name: str, parent: str, child: str, kind: str = "revolute", xyz: str = "0 0 0.1",
           limit: str = 'lower="-3" upper="3"', extra: str = "") -> str:
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{xyz}"/><axis xyz="0 0 1"/><limit {limit} effort="10" velocity="1"/>{extra}</joint>')


def _files(tmp_path: Path) -> tuple[Path, Path]:
    """An arm in ``tmp/ws/my_arm/urdf/`` naming its meshes by ``package://my_arm/...`` and a gripper in
    ``tmp/grip/urdf/`` naming its own by a relative path, both with a link called ``base_link``."""
    arm_dir, grip_dir = tmp_path / "ws" / "my_arm", tmp_path / "grip"
    for d in (arm_dir / "urdf", arm_dir / "meshes", grip_dir / "urdf", grip_dir / "meshes"):
        d.mkdir(parents=True)
    for d in (arm_dir / "meshes", grip_dir / "meshes"):
        shutil.copy(_data() / "cube.obj", d / "part.obj")
    arm = arm_dir / "urdf" / "arm.urdf"
    chain = "".join(_link(f"link{i}") + _joint(f"j{i}", f"link{i - 1}", f"link{i}") for i in range(2, 7))
    arm.write_text('<robot name="arm" xmlns:drake="http://drake.mit.edu">' + _link("base_link")
                   + _link("link1", "package://my_arm/meshes/part.obj") + _link("tool0")
                   + _joint("j1", "base_link", "link1").replace("<limit", '<limit drake:acceleration="2"') + chain
                   + _joint("flange", "link6", "tool0", "fixed") + "<transmission name='t'/></robot>")
    gripper = grip_dir / "urdf" / "gripper.urdf"
    gripper.write_text(
        '<robot name="g">' + _link("base_link", "../meshes/part.obj") + _link("left") + _link("right")
        + _joint("left_finger", "base_link", "left", "prismatic", "0 0.02 0.05", 'lower="0" upper="0.04"')
        + _joint("right_finger", "base_link", "right", "prismatic", "0 -0.02 0.05", 'lower="-0.04" upper="0"',
                 '<mimic joint="left_finger" multiplier="-1" offset="0"/>')
        + "<drake:collision_filter_group name='x'><drake:member link='left'/></drake:collision_filter_group></robot>"
    )
    return arm, gripper


def test_composition_resolves_every_mesh_path_and_renames_what_collides(tmp_path: Path):
    from l2p_bullet.embodiment.arm_compose import MOUNT_JOINT, compose
    from l2p_bullet.embodiment.sim.bullet import Bullet

    arm, gripper = _files(tmp_path)
    out = compose(arm, gripper, tmp_path / "pkg" / "description", "mine")
    shutil.rmtree(tmp_path / "ws")  # the composed robot needs nothing of the sources
    shutil.rmtree(tmp_path / "grip")
    root = ET.parse(out).getroot()
    meshes = [m.get("filename") for m in root.iter("mesh")]
    assert len(meshes) == 4 and all(not Path(m).is_absolute() and (out.parent / m).is_file() for m in meshes), meshes
    links = [link.get("name") for link in root.findall("link")]
    assert "gripper_base_link" in links and links.count("base_link") == 1
    mount = next(j for j in root.findall("joint") if j.get("name") == MOUNT_JOINT)
    assert (mount.find("parent").get("link"), mount.find("child").get("link")) == ("tool0", "gripper_base_link")
    assert root.find("transmission") is None and "drake" not in out.read_text()
    sim = Bullet()
    try:
        sim.load_urdf("r", str(out), (0.0, 0.0, 0.0), fixed=True)
        assert {j.name for j in sim.joints("r") if j.movable} == {f"j{i}" for i in range(1, 7)} | {"left_finger",
                                                                                                "right_finger"}
    finally:
        sim.close()


@pytest.mark.parametrize("case, match", [
    ("fixed", "cannot be composed: it has no movable joint"),
    ("two roots", "cannot be composed: it has 2 root links"),
    ("mount", 'has no link "wrist_9" to mount the gripper on'),
    ("not xml", "is not valid XML"),
    ("mesh", r"names 1 mesh file\(s\) that do not exist"),
    ("bare", 'the fingertip link "left" has no collision shape'),
])
def test_a_gripper_that_cannot_be_composed_is_one_line_and_leaves_nothing(tmp_path: Path, case: str, match: str):
    from l2p_bullet.plugins.arm_scaffold import scaffold_arm

    arm, gripper = _files(tmp_path)
    text = gripper.read_text()
    if case == "fixed":
        text = text.replace('type="prismatic"', 'type="fixed"')
    elif case == "two roots":
        text = text.replace("</robot>", _link("loose") + "</robot>")
    elif case == "not xml":
        text = text.replace("</robot>", "")
    elif case == "bare":  # a gripper described without its fingers (airo-models' Schunk EGK40 alone)
        text = text.replace(_link("left"), '<link name="left"/>').replace(_link("right"), '<link name="right"/>')
    elif case == "mesh":
        (gripper.parent.parent / "meshes" / "part.obj").unlink()
    gripper.write_text(text)
    with pytest.raises(PluginError, match=match) as e:
        scaffold_arm("mine", str(arm), tmp_path / "out", gripper=str(gripper),
                     mount="wrist_9" if case == "mount" else None)
    assert "\n" not in str(e.value)
    assert not (tmp_path / "out").exists()


def test_a_mount_option_without_a_gripper_is_one_line():
    from click.testing import CliRunner

    from l2p_bullet.cli import main

    r = CliRunner().invoke(main, ["new-arm", "mine", "--urdf", "arm.urdf", "--mount", "tool0"])
    assert r.exit_code != 0
    lines = [ln for ln in r.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and "--mount, --mount-xyz and --mount-rpy place a --gripper" in lines[0], r.output


def test_mimic_chains_follow_their_first_leader_and_opposite_limits_close_both_fingers(tmp_path: Path):
    """The gripper above: its right finger mimics the left with a multiplier of -1, their limits of opposite sign.
    Closed is the left finger at 0 and the right, following, at 0; open, 4 cm each way."""
    from l2p_bullet.embodiment import arm_guess
    from l2p_bullet.embodiment.arm_compose import compose
    from l2p_bullet.embodiment.sim.bullet import Bullet

    arm, gripper = _files(tmp_path)
    out = compose(arm, gripper, tmp_path / "d", "mine")
    sim = Bullet()
    try:
        sim.load_urdf("r", str(out), (0.0, 0.0, 0.0), fixed=True)
        joints = sim.joints("r")
        by = {j.name: j for j in joints}
        grip = [by["left_finger"].index, by["right_finger"].index]
        mimic = arm_guess._mimics(str(out), by, grip)
        assert mimic == {by["right_finger"].index: (by["left_finger"].index, -1.0, 0.0)}
        tips = [by["left_finger"].index, by["right_finger"].index]
        hand = by[next(n for n in by if n == "l2p_mount")].index
        closed, opening, _ = arm_guess._closing(sim, "r", joints, grip, tips, hand, mimic)
    finally:
        sim.close()
    assert closed == [0.0, 0.0]
    assert opening == pytest.approx(0.08 - 0.02, abs=0.003)  # 2 x 4 cm apart, less the two 2 cm boxes


def _ur_robotiq(tmp_path: Path) -> Path:
    airo = pytest.importorskip("airo_models.files")
    from l2p_bullet.embodiment.arm_compose import compose

    return compose(airo.get_urdf_path("ur5e"), airo.get_urdf_path("robotiq_2f_85"), tmp_path / "d", "ur5e-robotiq")


def _ur_spec(tmp_path: Path):
    """The composed UR5e + Robotiq as an ArmSpec written by hand (tool0 its tool link; new-arm's measuring is the
    slow test's), and the Robotiq's mimics: joint -> (leader, multiplier, offset)."""
    from l2p_bullet.arms import ArmSpec
    from l2p_bullet.embodiment import arm_guess
    from l2p_bullet.embodiment.sim.bullet import Bullet
    from l2p_bullet.embodiment.sim.robot import ARM

    urdf = _ur_robotiq(tmp_path)
    sim = Bullet()
    try:
        sim.load_urdf(ARM, str(urdf), (0.0, 0.0, 0.0), fixed=True)
        joints = sim.joints(ARM)
    finally:
        sim.close()
    by = {j.name: j for j in joints}
    arm = tuple(by[n].index for n in ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
                                      "wrist_2_joint", "wrist_3_joint"))
    grip = [j.index for j in joints if j.movable and j.index not in arm]
    mimic = arm_guess._mimics(str(urdf), by, grip)
    lead = by["finger_joint"].index
    closed = arm_guess.follow({lead: 0.8}, mimic)
    spec = ArmSpec(name="ur-test", urdf=str(urdf), arm_joints=arm, tool_link=by["flange-tool0"].index,
                   finger_joints=tuple(grip), finger_closed=tuple(closed[j] for j in grip),
                   home=(0.0, -1.76, 1.85, -1.66, -1.57, 0.0), ik_seeds=(), wrist_joint=arm[-1],
                   fingertip_links=(by["left_inner_finger_pad_joint"].index, by["right_inner_finger_pad_joint"].index),
                   wrist_limit=6.2832, mount=(-0.54, 0.0, 0.0),
                   finger_mimic=tuple((j, lead_, m, o) for j, (lead_, m, o) in sorted(mimic.items())))
    return spec, mimic, lead


def test_the_robotiq_mimic_joints_move_together(tmp_path: Path):
    """PyBullet ignores <mimic>: driven by its one leading joint, the Robotiq's five mimic joints follow it (its
    four-bar linkage stays closed), and its pads open 8 cm apart."""
    from l2p_bullet.core.scene import Scene
    from l2p_bullet.embodiment.sim.robot import ARM
    from l2p_bullet.embodiment.sim.world import World

    spec, mimic, lead = _ur_spec(tmp_path)
    assert len(mimic) == 5 and {m[0] for m in mimic.values()} == {lead}
    grip = list(spec.finger_joints)
    with World(Scene([]), arm=spec, visuals=False) as world:
        robot = world.robot
        assert robot.finger_opening() == 0.0
        robot.drive_fingers({lead: 0.0})
        for _ in range(400):
            world.step()
        q = dict(zip(grip, world.sim.joint_positions(ARM, grip), strict=True))
        assert abs(q[lead]) < 0.02, q
        for j, (lead_, mult, off) in mimic.items():
            assert q[j] == pytest.approx(mult * q[lead_] + off, abs=0.02), (j, q)
        assert robot.finger_opening() > 0.05


def test_ik_restarts_reach_what_a_far_seed_misses(tmp_path: Path):
    """From joints drawn anywhere, PyBullet's IK alone misses some poses pointing down in the UR5e's workspace (a
    joint limit, or a residual); with the restarts ``new-arm`` writes (``ik_restarts``) it reaches all."""
    import dataclasses
    import math

    import numpy as np

    from l2p_bullet.embodiment.sim.robot import Kinematics
    from l2p_bullet.errors import ReachError

    spec, _, _ = _ur_spec(tmp_path)
    reached = {}
    for n in (0, 12):
        kin = Kinematics(dataclasses.replace(spec, ik_restarts=n), spec.mount)
        rng = np.random.default_rng(5)
        reached[n] = 0
        try:
            for _ in range(30):
                seed = rng.uniform(-math.pi, math.pi, 6)
                pose = (-0.1 + rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), 0.25)
                try:
                    q = kin.solve(pose, rng.uniform(-3.0, 3.0), seed)
                except ReachError as e:
                    assert "cannot reach (" in str(e) and "pointing down with yaw" in str(e)
                    continue
                reached[n] += 1
                assert np.all(q >= kin.arm_lower - 1e-6) and np.all(q <= kin.arm_upper + 1e-6)
        finally:
            kin.close()
    assert reached[0] < 30 and reached[12] == 30, reached
