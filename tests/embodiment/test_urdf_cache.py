"""The stripped-URDF cache (issue 15): a stale, corrupt or planted file never breaks or steers a run."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import pytest

from l2p_bullet.arms import PANDA
from l2p_bullet.embodiment.sim import arms
from l2p_bullet.embodiment.sim.arms import arm_urdf


@pytest.fixture
def tmpdir_root(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    monkeypatch.setattr(arms, "_PRIVATE", [])
    return tmp_path


def _loads(path: str) -> int:
    import pybullet as p

    client = p.connect(p.DIRECT)
    try:
        return p.getNumJoints(p.loadURDF(path, physicsClientId=client), physicsClientId=client)
    finally:
        p.disconnect(client)


def test_a_corrupt_or_stale_cached_urdf_is_rewritten(tmpdir_root):
    path = Path(arm_urdf(PANDA, visuals=False, collisions=False))
    good = path.read_bytes()
    assert path.parent == tmpdir_root / f"l2p_bullet-urdf-{os.getuid()}"
    assert path.parent.stat().st_mode & 0o777 == 0o700
    for bad in (b"", good[: len(good) // 2], good.replace(b"<robot", b"<rbt")):
        path.write_bytes(bad)
        assert Path(arm_urdf(PANDA, visuals=False, collisions=False)).read_bytes() == good
    assert _loads(str(path)) > 7


def test_a_planted_link_is_not_followed(tmpdir_root):
    path = Path(arm_urdf(PANDA, visuals=False, collisions=True))
    good = path.read_bytes()
    elsewhere = tmpdir_root / "elsewhere.urdf"
    elsewhere.write_bytes(good)
    path.unlink()
    path.symlink_to(elsewhere)  # same content, but a link: replaced by a real file of ours
    assert Path(arm_urdf(PANDA, visuals=False, collisions=True)) == path and not path.is_symlink()


@pytest.mark.parametrize("how", ["symlink", "world-writable"])
def test_a_cache_folder_others_control_is_not_used(tmpdir_root, how):
    folder = tmpdir_root / f"l2p_bullet-urdf-{os.getuid()}"
    target = tmpdir_root / "theirs"
    target.mkdir()
    if how == "symlink":
        folder.symlink_to(target)
    else:
        folder.mkdir()
        folder.chmod(0o777)
    path = Path(arm_urdf(PANDA, visuals=False, collisions=False))
    assert path.parent != folder and target not in path.parents
    assert path.parent.stat().st_mode & 0o077 == 0
    assert _loads(str(path)) > 7
