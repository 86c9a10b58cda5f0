"""``l2p-bullet export RUNS --format rerun OUT.rrd``: read back through Rerun's own dataframe API."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from l2p_bullet.cli import main
from l2p_bullet.core.scene import default_scene
from l2p_bullet.embodiment.sim.camera import RenderSettings
from l2p_bullet.pipeline import perform

rr = pytest.importorskip("rerun")


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    root = tmp_path_factory.mktemp("rerun")
    settings = RenderSettings(64, 48, fps=5.0, renderer="tiny", workers=0)
    r = perform("move A closer to B", default_scene(), out_dir=root / "run-1", render_settings=settings)
    return r.out_dir


def _column(recording, entity: str, component: str) -> tuple[np.ndarray, list]:
    """(time in seconds, values) of one component column, over the ``time`` timeline."""
    table = recording.view(index="time", contents=entity).select().read_all()
    import pyarrow as pa

    times = table.column("time").cast(pa.int64()).to_numpy() / 1e9  # nanoseconds of duration
    return times, table.column(f"{entity}:{component}").to_pylist()


@pytest.mark.slow
def test_poses_and_progress_read_back_as_trajectory_json_has_them(run, tmp_path):
    out = tmp_path / "out.rrd"
    r = CliRunner().invoke(main, ["export", str(run), "--format", "rerun", str(out), "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.output)["entities"] == ["/run-1"]
    traj = json.loads((run / "trajectory.json").read_text())
    t = np.array([f["t"] for f in traj["frames"]])
    rec = rr.dataframe.load_recording(out)
    for name in ("A", "B"):
        times, values = _column(rec, f"/run-1/world/objects/{name}", "Transform3D:translation")
        assert np.allclose(times, t, atol=1e-6)
        want = np.array([f["poses"][name][:3] for f in traj["frames"]])
        assert np.allclose(np.array([v[0] for v in values]), want, atol=1e-6)
        _, quats = _column(rec, f"/run-1/world/objects/{name}", "Transform3D:quaternion")
        yaw = np.array([2 * np.arctan2(q[0][2], q[0][3]) for q in quats])
        want_yaw = np.array([f["poses"][name][3] for f in traj["frames"]])
        assert np.allclose(np.angle(np.exp(1j * (yaw - want_yaw))), 0, atol=1e-5)
    times, values = _column(rec, "/run-1/progress", "Scalars:scalars")
    assert np.allclose(np.array([v[0] for v in values]), [f["progress"] for f in traj["frames"]], atol=1e-9)
    # the arm: every mesh posed at every frame, the hand moving, the base not
    columns = {c.name for c in rec.schema().component_columns()}
    links = sorted({c.split(":")[0] for c in columns if "/world/arm/" in c and c.endswith("Transform3D:translation")})
    assert len(links) >= 8 and any(c.endswith("mesh:Asset3D:blob") for c in columns)
    base = np.array([v[0] for v in _column(rec, links[0], "Transform3D:translation")[1]])
    hand = np.array([v[0] for v in _column(rec, links[-1], "Transform3D:translation")[1]])
    assert len(hand) == len(t) and np.ptp(base, axis=0).max() < 1e-6 and np.ptp(hand, axis=0).max() > 0.05
    assert "/run-1/world/plan:LineStrips3D:strips" in columns
    times, images = _column(rec, "/run-1/camera/image", "EncodedImage:blob")
    assert len(images) == len(list((run / "frames").glob("*.png"))) and np.allclose(np.diff(times), 0.2)
    # a chain's segments become text log entries at their first frames
    assert not any("/segments" in c for c in columns)


def test_the_rrd_file_is_never_overwritten_without_force(run, tmp_path):
    out = tmp_path / "x.rrd"
    out.write_text("keep me")
    r = CliRunner().invoke(main, ["export", str(run), "--format", "rerun", str(out)])
    assert r.exit_code == 2 and "--force" in r.output and out.read_text() == "keep me"
    r = CliRunner().invoke(main, ["export", str(run), "--format", "rerun", str(tmp_path / "x.txt")])
    assert r.exit_code == 2 and "OUT.rrd" in r.output


def test_segments_are_logged_at_their_first_frames(run, tmp_path):
    chain = tmp_path / "chain"
    chain.mkdir()
    traj = json.loads((run / "trajectory.json").read_text())
    traj["segments"] = [{"clause": 1, "text": "move A closer to B", "first_frame": 0, "last_frame": 9, "mover": "A",
                         "anchors": ["B"]},
                        {"clause": 2, "text": "move A away from B", "first_frame": 10, "last_frame": 20, "mover": "A",
                         "anchors": ["B"]}]  # checked as every exporter checks a chain's segments
    (chain / "trajectory.json").write_text(json.dumps(traj))
    out = tmp_path / "c.rrd"
    r = CliRunner().invoke(main, ["export", str(chain), "--format", "rerun", str(out)])
    assert r.exit_code == 0, r.output
    times, texts = _column(rr.dataframe.load_recording(out), "/chain/segments", "TextLog:text")
    assert [x[0] for x in texts] == ["clause 1: move A closer to B", "clause 2: move A away from B"]
    assert np.allclose(times, [traj["frames"][0]["t"], traj["frames"][10]["t"]])
